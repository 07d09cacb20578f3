//! Conversions from subsurf's own mesh model.

use std::borrow::Cow;

use subsurf::{BoundaryInterpolation, CreaseMethod, FVarLinearInterpolation, Scheme};

use crate::mesh::{OsdBoundary, OsdCreaseMethod, OsdMesh, OsdOptions, OsdScheme};

impl From<&subsurf::Options> for OsdOptions {
    /// Maps every option one to one. `fvar_propagate_corners` has no counterpart in
    /// OpenSubdiv 3's `Sdc::Options` (it is folded into `FVAR_LINEAR_CORNERS_PLUS2`) and is
    /// ignored.
    fn from(o: &subsurf::Options) -> Self {
        OsdOptions {
            scheme: match o.scheme {
                Scheme::Catmark => OsdScheme::Catmark,
                Scheme::Bilinear => OsdScheme::Bilinear,
                Scheme::Loop => OsdScheme::Loop,
            },
            boundary: match o.boundary {
                BoundaryInterpolation::None => OsdBoundary::None,
                BoundaryInterpolation::EdgeOnly => OsdBoundary::EdgeOnly,
                BoundaryInterpolation::EdgeAndCorner => OsdBoundary::EdgeAndCorner,
            },
            crease_method: match o.crease_method {
                CreaseMethod::Uniform => OsdCreaseMethod::Uniform,
                CreaseMethod::Chaikin => OsdCreaseMethod::Chaikin,
            },
            triangle_smooth: o.triangle_subdivision == subsurf::TriangleSubdivision::Smooth,
            fvar_interp: match o.uv_interpolation {
                FVarLinearInterpolation::None => 0,
                FVarLinearInterpolation::CornersOnly => 1,
                FVarLinearInterpolation::CornersPlus1 => 2,
                FVarLinearInterpolation::CornersPlus2 => 3,
                FVarLinearInterpolation::Boundaries => 4,
                FVarLinearInterpolation::All => 5,
            },
        }
    }
}

impl<'a> From<&'a subsurf::Mesh> for OsdMesh<'a> {
    /// Borrows the arrays; only the crease and corner tags are copied into tuples.
    fn from(m: &'a subsurf::Mesh) -> Self {
        OsdMesh {
            positions: &m.positions,
            positions_f64: m.positions.as_f64(),
            face_counts: &m.face_counts,
            face_indices: &m.face_indices,
            creases: Cow::Owned(
                m.creases
                    .iter()
                    .map(|c| (c.v0, c.v1, c.sharpness))
                    .collect(),
            ),
            corners: Cow::Owned(m.corners.iter().map(|c| (c.vertex, c.sharpness)).collect()),
            holes: &m.holes,
            uvs: m.uvs.as_ref().map(|fv| (&fv.values[..], &fv.indices[..])),
            options: OsdOptions::from(&m.options),
        }
    }
}

/// `mesh` as a Loop mesh: every face fanned into triangles from its first corner, the
/// triangles of a hole holes, creases (edges kept by the fans) and corners kept, UVs dropped —
/// the Loop shapes made from Catmull-Clark ones in the tests and the memory comparison.
pub fn fan_triangulated_loop(mesh: &subsurf::Mesh) -> subsurf::Mesh {
    let mut hole = vec![false; mesh.face_counts.len()];
    for &h in &mesh.holes {
        if let Some(x) = hole.get_mut(h as usize) {
            *x = true;
        }
    }
    let (mut faces, mut holes) = (Vec::new(), Vec::new());
    let mut at = 0usize;
    for (f, &n) in mesh.face_counts.iter().enumerate() {
        let poly = &mesh.face_indices[at..at + n as usize];
        at += n as usize;
        for k in 1..poly.len().saturating_sub(1) {
            if hole[f] {
                holes.push(faces.len() as u32);
            }
            faces.push([poly[0], poly[k], poly[k + 1]]);
        }
    }
    let mut out = subsurf::Mesh::from_faces(mesh.positions.clone(), &faces);
    out.creases = mesh.creases.clone();
    out.corners = mesh.corners.clone();
    out.holes = holes;
    out.options = mesh.options;
    out.options.scheme = Scheme::Loop;
    out
}
