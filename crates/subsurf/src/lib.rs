//! # subsurf
//!
//! Catmull-Clark subdivision surfaces in pure Rust: uniform refinement that matches
//! OpenSubdiv, limit-surface evaluation, and the p-rep C1 conversion of quad meshes.
//!
//! The data flows one way (see `design.md` in the repository):
//!
//! ```text
//! file ──io──▶ Mesh ──Topology::new──▶ Topology ──refine──▶ refined levels + stencils
//!                                         ├──patches──▶ PatchTable ──eval──▶ points
//!                                         └──prep─────▶ PrepPatches ──eval──▶ points
//! ```
//!
//! Every table is a flat array (`u32` indices, counts + offsets, one value per element) so
//! that a GPU backend can upload the very same vectors.

pub mod error;
pub mod io;
pub mod limit;
pub mod mesh;
pub mod options;
pub mod patch;
pub mod prep;
pub mod real;
pub mod refine;
pub mod rules;
pub mod shapes;
pub mod topology;

pub use error::{Error, MeshError, Result};
pub use mesh::{Corner, Crease, FaceVarying, Mesh};
pub use options::{
    BoundaryInterpolation, CreaseMethod, FVarLinearInterpolation, Options, Scheme,
    TriangleSubdivision,
};
pub use real::Real;
pub use refine::{RefineOptions, Refiner, StencilTable};
pub use topology::Topology;

/// Sharpness at or above which an edge or vertex is infinitely sharp (RenderMan rule).
pub const SHARPNESS_INFINITE: f32 = 10.0;
