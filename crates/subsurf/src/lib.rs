//! # subsurf
//!
//! Subdivision surfaces in pure Rust: Catmull-Clark, Loop and bilinear refinement that
//! matches OpenSubdiv, limit-surface evaluation and tessellation, and the p-rep G1 conversion
//! of quad meshes (Myles, Yeo & Peters 2008).
//!
//! The data flows one way (the layers are described in `docs/architecture.md` of the
//! repository):
//!
//! ```text
//! file ──io──▶ Mesh ──Topology::new──▶ Topology ──refine──▶ refined levels + stencils
//!                                         ├──patches──▶ PatchTable ──eval──▶ points
//!                                         └──prep─────▶ PrepPatches ──eval──▶ points
//! ```
//!
//! Every table is a flat array (`u32` indices, counts + offsets, one value per element) so
//! that a GPU backend can upload the very same vectors.
//!
//! # Example
//!
//! Refine a cube twice, check the first level against the Catmull-Clark vertex rule, move
//! the last level to the limit surface and write it as OBJ text:
//!
//! ```
//! use subsurf::{io, shapes, Refiner, Topology};
//!
//! let cube = shapes::cube(); // [-1, 1]^3, 8 vertices, 6 quads
//! let topology = Topology::new(&cube)?;
//! let refiner = Refiner::new(topology, 2)?;
//! // Every quad splits into four: 24 faces at level 1, 96 at level 2.
//! assert_eq!(refiner.levels[1].num_faces(), 24);
//! assert_eq!(refiner.last().num_faces(), 96);
//!
//! let levels = refiner.refine_all(&cube.positions);
//! // Vertex 0 keeps its index. Its valence-3 rule (Q + 2R) / 3, with Q the mean of the face
//! // centres and R the mean of the edge midpoints, moves (-1, -1, 1) to (-5/9, -5/9, 5/9).
//! let p = levels[1][0];
//! for (got, want) in p.iter().zip([-5.0f32 / 9.0, -5.0 / 9.0, 5.0 / 9.0]) {
//!     assert!((got - want).abs() < 1e-6);
//! }
//!
//! // Limit positions: at a smooth vertex of valence n the limit mask is
//! // (n² p + 4 Σ edge neighbours + Σ face-diagonal neighbours) / (n (n + 5)).
//! let (t, last) = (refiner.last(), &levels[2]);
//! let limit = refiner.limit(last);
//! let n = t.valence(0) as f32; // 3: still the cube's corner
//! let mut want = last[0].map(|x| n * n * x);
//! for &e in t.vertex_edges(0) {
//!     let q = last[t.other_vertex(e as usize, 0) as usize];
//!     (0..3).for_each(|c| want[c] += 4.0 * q[c]);
//! }
//! for (&f, &k) in t.vertex_faces(0).iter().zip(t.vertex_faces_local(0)) {
//!     let q = last[t.face_vertices(f as usize)[(k as usize + 2) % 4] as usize];
//!     (0..3).for_each(|c| want[c] += q[c]);
//! }
//! for c in 0..3 {
//!     assert!((limit[0][c] - want[c] / (n * (n + 5.0))).abs() < 1e-6);
//! }
//!
//! // Output: a mesh of the last level, written and read back.
//! let mesh = refiner.to_mesh(2, limit);
//! let mut obj = Vec::new();
//! io::obj::write(&mesh, &mut obj)?;
//! let back = io::obj::read(std::str::from_utf8(&obj).expect("OBJ is text"))?;
//! assert_eq!((back.num_vertices(), back.num_faces()), (98, 96));
//! # Ok::<(), subsurf::Error>(())
//! ```
//!
//! # Where to start
//!
//! | to … | use |
//! |---|---|
//! | read and write meshes (OBJ, PLY, glTF, USD) | [`io::read_path`], [`io::write_path`], [`Mesh`] |
//! | validate a mesh and walk its connectivity | [`Topology`] |
//! | refine uniformly, animate with stencils | [`Refiner`], [`StencilTable`], [`refine`] |
//! | evaluate the limit surface anywhere | [`limit::PatchTable`], [`limit::LimitSurface`] |
//! | tessellate adaptively (tolerance, edge length, pixels) | [`tess`] |
//! | edit creases of a built surface | [`limit::SharpnessEdit`], [`limit::PatchTable::set_sharpness`] |
//! | convert to G1 patches and export Bezier | [`prep::PrepPatches`] |
//! | one call from a mesh to a drawable surface, CPU or GPU | [`surface`] |
//! | patch basis functions (B-spline, Gregory, box-spline) | [`patch`] |
//! | refuse requests that would not fit in memory | [`budget`] |
//!
//! Tutorials, one small program each, are the crate's examples (`docs/tutorials.md`).

#![warn(missing_docs)]
pub(crate) mod error;
pub mod io;
pub mod limit;
pub mod mesh;
pub(crate) mod options;
pub mod patch;
pub mod prep;
pub(crate) mod real;
pub mod refine;
pub(crate) mod rules;
pub mod shapes;
pub mod surface;
pub mod tess;
pub(crate) mod topology;
pub(crate) mod util;

/// Up-front memory refusals: a request is estimated before anything is allocated, and one
/// that would not fit in 80% of the available memory is refused with its true size
/// ([`MeshError::TooLarge`]).
pub mod budget {
    #[doc(inline)]
    pub use crate::util::budget::{check, count, human, Budget};
}

#[doc(inline)]
pub use error::{Error, MeshError, QueryError, Result, TessError};
#[doc(inline)]
pub use mesh::{Corner, Crease, FaceVarying, Mesh, Positions};
#[doc(inline)]
pub use options::{
    BoundaryInterpolation, CreaseMethod, FVarLinearInterpolation, OptionValue, Options,
    ParseOptionError, Scheme, TriangleSubdivision,
};
#[doc(inline)]
pub use real::{Real, VertexData};
#[doc(inline)]
pub use refine::{RefineOptions, Refiner, StencilTable};
#[doc(inline)]
pub use topology::{Topology, TopologyArrays};

/// Sharpness at or above which an edge or vertex is infinitely sharp (RenderMan rule).
pub const SHARPNESS_INFINITE: f32 = 10.0;
