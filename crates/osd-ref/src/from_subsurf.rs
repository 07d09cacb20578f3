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
