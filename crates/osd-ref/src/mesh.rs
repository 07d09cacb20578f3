//! The input handed to OpenSubdiv: a borrowed mesh with tags and `Sdc::Options`.

use std::borrow::Cow;
use std::os::raw::c_int;

use crate::ffi::MeshDesc;
use crate::{Error, Result};

/// Subdivision scheme (`Sdc::SchemeType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum OsdScheme {
    /// `SCHEME_CATMARK`.
    #[default]
    Catmark,
    /// `SCHEME_BILINEAR`.
    Bilinear,
    /// `SCHEME_LOOP` (triangles only).
    Loop,
}

/// Boundary interpolation (`Sdc::Options::VtxBoundaryInterpolation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum OsdBoundary {
    /// `VTX_BOUNDARY_NONE`.
    None,
    /// `VTX_BOUNDARY_EDGE_ONLY`.
    #[default]
    EdgeOnly,
    /// `VTX_BOUNDARY_EDGE_AND_CORNER`.
    EdgeAndCorner,
}

/// Crease decay (`Sdc::Options::CreasingMethod`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum OsdCreaseMethod {
    /// `CREASE_UNIFORM`.
    #[default]
    Uniform,
    /// `CREASE_CHAIKIN`.
    Chaikin,
}

/// The `Sdc::Options` (and scheme) OpenSubdiv refines with.
///
/// The default is Catmull-Clark, edge-only boundaries, uniform creases, plain triangle
/// weights and linear face-varying interpolation everywhere (`FVAR_LINEAR_ALL`), the
/// same as `subsurf::Options::default()`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct OsdOptions {
    /// Subdivision scheme.
    pub scheme: OsdScheme,
    /// Boundary interpolation.
    pub boundary: OsdBoundary,
    /// Crease method.
    pub crease_method: OsdCreaseMethod,
    /// `TRI_SUB_SMOOTH` when true, `TRI_SUB_CATMARK` otherwise.
    pub triangle_smooth: bool,
    /// `Sdc::Options::FVarLinearInterpolation` as its integer value, in OpenSubdiv's order:
    /// 0 NONE, 1 CORNERS_ONLY, 2 CORNERS_PLUS1, 3 CORNERS_PLUS2, 4 BOUNDARIES, 5 ALL.
    pub fvar_interp: u8,
}

impl Default for OsdOptions {
    fn default() -> Self {
        OsdOptions {
            scheme: OsdScheme::Catmark,
            boundary: OsdBoundary::EdgeOnly,
            crease_method: OsdCreaseMethod::Uniform,
            triangle_smooth: false,
            fvar_interp: 5,
        }
    }
}

/// A polygon mesh as OpenSubdiv's `Far::TopologyDescriptor` sees it. Indices are 0-based.
///
/// Creases and corners are [`Cow`]s so that [`OsdMesh::from`] a `subsurf::Mesh` can
/// convert its tag structs while everything else stays borrowed.
#[derive(Debug, Clone)]
pub struct OsdMesh<'a> {
    /// Vertex positions.
    pub positions: &'a [[f32; 3]],
    /// The positions as given, when they were given in `f64`: what the double-precision
    /// paths ([`crate::eval_limit_grid_f64`], [`crate::OsdRefiner::interpolate_f64`]) read
    /// instead of `positions`.
    pub positions_f64: Option<&'a [[f64; 3]]>,
    /// Number of vertices of each face.
    pub face_counts: &'a [u32],
    /// Vertex indices of all faces, concatenated.
    pub face_indices: &'a [u32],
    /// Sharp edges `(v0, v1, sharpness)`.
    pub creases: Cow<'a, [(u32, u32, f32)]>,
    /// Sharp vertices `(vertex, sharpness)`.
    pub corners: Cow<'a, [(u32, f32)]>,
    /// Faces tagged as holes.
    pub holes: &'a [u32],
    /// Face-varying channel 0: `(values, indices parallel to face_indices)`.
    pub uvs: Option<(&'a [[f32; 2]], &'a [u32])>,
    /// Scheme and options.
    pub options: OsdOptions,
}

impl<'a> OsdMesh<'a> {
    /// A mesh without tags or UVs, with default options.
    pub fn new(positions: &'a [[f32; 3]], face_counts: &'a [u32], face_indices: &'a [u32]) -> Self {
        OsdMesh {
            positions,
            positions_f64: None,
            face_counts,
            face_indices,
            creases: Cow::Borrowed(&[]),
            corners: Cow::Borrowed(&[]),
            holes: &[],
            uvs: None,
            options: OsdOptions::default(),
        }
    }

    /// Checks every index, so that OpenSubdiv (which trusts its input) never reads out of
    /// bounds.
    pub fn validate(&self) -> Result<()> {
        let invalid = |s: String| Err(Error::Invalid(s));
        let nv = self.positions.len();
        let nf = self.face_counts.len();
        let fits = |n: usize| n < i32::MAX as usize;
        if !fits(nv) || !fits(nf) || !fits(self.face_indices.len()) {
            return invalid("mesh too large for OpenSubdiv's 32-bit indices".into());
        }
        let mut total = 0usize;
        for (f, &c) in self.face_counts.iter().enumerate() {
            if c < 3 {
                return invalid(format!("face {f} has {c} vertices (need at least 3)"));
            }
            total += c as usize;
        }
        if total != self.face_indices.len() {
            return invalid(format!(
                "face counts sum to {total} but there are {} face indices",
                self.face_indices.len()
            ));
        }
        if let Some(i) = self.face_indices.iter().position(|&v| v as usize >= nv) {
            return invalid(format!(
                "face index {i} refers to missing vertex {}",
                self.face_indices[i]
            ));
        }
        for (k, &(a, b, s)) in self.creases.iter().enumerate() {
            if a as usize >= nv || b as usize >= nv || !s.is_finite() {
                return invalid(format!("crease {k} ({a}, {b}, {s}) is out of range"));
            }
        }
        for (k, &(v, s)) in self.corners.iter().enumerate() {
            if v as usize >= nv || !s.is_finite() {
                return invalid(format!("corner {k} ({v}, {s}) is out of range"));
            }
        }
        if let Some(&h) = self.holes.iter().find(|&&h| h as usize >= nf) {
            return invalid(format!("hole refers to missing face {h}"));
        }
        if let Some((values, indices)) = self.uvs {
            if indices.len() != self.face_indices.len() {
                return invalid(format!(
                    "{} uv indices for {} face corners",
                    indices.len(),
                    self.face_indices.len()
                ));
            }
            if !fits(values.len()) {
                return invalid("too many uv values".into());
            }
            if let Some(&i) = indices.iter().find(|&&i| i as usize >= values.len()) {
                return invalid(format!(
                    "uv index {i} out of range ({} values)",
                    values.len()
                ));
            }
        }
        if self.options.fvar_interp > 5 {
            return invalid(format!(
                "fvar_interp {} not in 0..=5",
                self.options.fvar_interp
            ));
        }
        Ok(())
    }
}

/// A validated mesh in the shim's layout; the tag arrays it owns live as long as it does.
pub(crate) struct Desc<'a> {
    mesh: &'a OsdMesh<'a>,
    crease_pairs: Vec<i32>,
    crease_weights: Vec<f32>,
    corner_vertices: Vec<i32>,
    corner_weights: Vec<f32>,
}

impl<'a> Desc<'a> {
    pub(crate) fn new(mesh: &'a OsdMesh<'a>) -> Result<Self> {
        mesh.validate()?;
        Ok(Desc {
            mesh,
            crease_pairs: mesh
                .creases
                .iter()
                .flat_map(|c| [c.0 as i32, c.1 as i32])
                .collect(),
            crease_weights: mesh.creases.iter().map(|c| c.2).collect(),
            corner_vertices: mesh.corners.iter().map(|c| c.0 as i32).collect(),
            corner_weights: mesh.corners.iter().map(|c| c.1).collect(),
        })
    }

    /// The C view; pointers are valid while `self` is borrowed.
    pub(crate) fn raw(&self) -> MeshDesc {
        let m = self.mesh;
        let o = m.options;
        let ints = |s: &[u32]| bytemuck::cast_slice::<u32, i32>(s).as_ptr();
        let (num_uvs, uvs, uv_indices) = match m.uvs {
            Some((values, indices)) => (
                values.len() as c_int,
                values.as_ptr().cast::<f32>(),
                ints(indices),
            ),
            None => (0, std::ptr::null(), std::ptr::null()),
        };
        MeshDesc {
            num_vertices: m.positions.len() as c_int,
            positions: m.positions.as_ptr().cast::<f32>(),
            positions_f64: m
                .positions_f64
                .filter(|p| p.len() == m.positions.len())
                .map_or(std::ptr::null(), |p| p.as_ptr().cast::<f64>()),
            num_faces: m.face_counts.len() as c_int,
            face_counts: ints(m.face_counts),
            face_indices: ints(m.face_indices),
            num_creases: self.crease_weights.len() as c_int,
            crease_pairs: self.crease_pairs.as_ptr(),
            crease_weights: self.crease_weights.as_ptr(),
            num_corners: self.corner_weights.len() as c_int,
            corner_vertices: self.corner_vertices.as_ptr(),
            corner_weights: self.corner_weights.as_ptr(),
            num_holes: m.holes.len() as c_int,
            holes: ints(m.holes),
            num_uvs,
            uvs,
            uv_indices,
            scheme: match o.scheme {
                OsdScheme::Bilinear => 0,
                OsdScheme::Catmark => 1,
                OsdScheme::Loop => 2,
            },
            boundary: match o.boundary {
                OsdBoundary::None => 0,
                OsdBoundary::EdgeOnly => 1,
                OsdBoundary::EdgeAndCorner => 2,
            },
            crease_method: match o.crease_method {
                OsdCreaseMethod::Uniform => 0,
                OsdCreaseMethod::Chaikin => 1,
            },
            triangle_smooth: o.triangle_smooth as c_int,
            fvar_interp: o.fvar_interp as c_int,
        }
    }
}
