//! The Catmull-Clark limit surface as a table of patches, evaluated anywhere.
//!
//! ```text
//! Topology ──PatchTable::build──▶ PatchTable ──points(positions)──▶ LimitSurface
//!                                                   ├── eval(ptex, u, v) / eval_batch
//!                                                   └── tessellate(N)
//! ```
//!
//! How it is built: the faces next to features (extraordinary vertices, creases, corners,
//! boundaries) are isolated by sparse refinement to the isolation level, within a memory
//! budget that refuses a table which would not fit before it is allocated; every leaf face
//! becomes a regular B-spline, single-crease or Gregory end-cap patch (box-spline and
//! Gregory-triangle patches for Loop), whose points are stencil rows relative to their first
//! input ([`PatchTable::points`]). A [`PatchMap`] finds the patch of a `(ptex, u, v)`; a
//! [`LimitSurface`] evaluates positions and derivatives and tessellates watertight
//! ([`LimitSurface::tessellate`], per-edge rates through `crate::tess`);
//! [`build_for_tolerance`] chooses the isolation per region; [`PatchTable::set_sharpness`]
//! edits creases of a built table ([`SharpnessEdit`]). The Loop limit is [`LoopLimit`].
//!
//! # Ptex faces
//!
//! A quad is one ptex face; a face with `n ≠ 4` corners is `n` ptex faces, its level-1
//! sub-faces in corner order. Sub-face `k` has `(0,0)` at corner `k`, `(1,0)` at the midpoint
//! of edge `k → k+1`, `(1,1)` at the face centre and `(0,1)` at the midpoint of edge
//! `k−1 → k` — the vertex order of the child faces made by [`crate::refine`]. Ptex faces are
//! numbered in base face order (OpenSubdiv `Far::PtexIndices`), holes included.
//!
//! # Example
//!
//! On a regular part of a mesh the limit surface is the uniform bicubic B-spline of the
//! 4×4 control points around a face; here the middle face of a bumpy 5×5 grid, compared
//! with the tensor-product basis `(1−t)³/6, (3t³−6t²+4)/6, (−3t³+3t²+3t+1)/6, t³/6`:
//!
//! ```
//! use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, PatchType};
//! use subsurf::{shapes, Topology};
//!
//! let mut grid = shapes::grid(5, 5); // vertex (x, y) is 6 y + x, face (i, j) is 5 j + i
//! for p in grid.positions.as_f32_mut() {
//!     p[2] = ((7 * p[0] as usize + 3 * p[1] as usize) % 5) as f32 * 0.1;
//! }
//! let table = PatchTable::build(&Topology::new(&grid)?, &PatchOptions::default())?;
//! let surface = LimitSurface::new(table, &grid.positions);
//!
//! let middle = 5 * 2 + 2; // face (2, 2): a quad is one ptex face
//! let patch = surface.table().patch_map().find(middle, 0.5, 0.5).expect("not a hole") as usize;
//! assert_eq!(surface.table().patch_type(patch), PatchType::Regular);
//!
//! let basis = |t: f32| {
//!     let s = 1.0 - t;
//!     [s * s * s, 3.0 * t * t * t - 6.0 * t * t + 4.0, -3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0, t * t * t]
//!         .map(|w| w / 6.0)
//! };
//! for (u, v) in [(0.0, 0.0), (0.25, 0.5), (0.9, 0.1), (1.0, 1.0)] {
//!     let (bu, bv) = (basis(u), basis(v));
//!     let mut want = [0.0f32; 3];
//!     for a in 0..4 {
//!         for b in 0..4 {
//!             let q = grid.positions[6 * (1 + b) + (1 + a)]; // x = 1 + a, y = 1 + b
//!             (0..3).for_each(|c| want[c] += bu[a] * bv[b] * q[c]);
//!         }
//!     }
//!     let got = surface.eval(middle, u, v).expect("inside the face");
//!     assert!((0..3).all(|c| (got.p[c] - want[c]).abs() < 1e-5), "{got:?} vs {want:?}");
//!     assert!(got.n[2] > 0.0); // faces are counter-clockwise seen from +z
//! }
//!
//! // Watertight tessellation: neighbouring faces share their seam samples.
//! let mesh = surface.tessellate(4)?;
//! assert_eq!(mesh.positions.len(), (5 * 3 + 1) * (5 * 3 + 1));
//! assert_eq!(mesh.quads.len(), 25 * 9);
//! # Ok::<(), subsurf::Error>(())
//! ```

pub(crate) mod budget;
pub(crate) mod curve_eval;
pub(crate) mod edit;
pub(crate) mod edit_local;
pub(crate) mod edit_rebuild;
pub(crate) mod edit_region;
pub(crate) mod endcap;
pub(crate) mod eval;
pub(crate) mod features;
pub(crate) mod gather;
pub(crate) mod leaves;
pub(crate) mod loop_endcap;
pub(crate) mod loop_eval;
pub(crate) mod loop_patches;
pub(crate) mod loop_tessellate;
pub(crate) mod patch_map;
pub(crate) mod points;
pub(crate) mod query;
pub(crate) mod rate_curves;
pub(crate) mod span;
pub(crate) mod sparse;
pub(crate) mod table;
pub(crate) mod tessellate;
pub(crate) mod tolerance;
pub(crate) mod tri_patch_map;

pub use edit::{EditOutcome, SharpnessEdit};
pub use eval::{LimitPoint, LimitSurface};
pub use loop_eval::LoopLimit;
pub use loop_patches::{loop_patch_counts, LoopPatchCounts};
pub use loop_tessellate::{tri_tessellation_plan, TriTessellation, TriTessellationPlan};
pub use patch_map::PatchMap;
pub use query::{check_square, check_triangle};
pub use table::{PatchCounts, PatchOptions, PatchTable, PatchType, MAX_ISOLATION_LEVEL};
pub use tessellate::{Tessellation, TessellationPlan};
pub use tolerance::{build_for_tolerance, choose_isolation, split_tolerance, IsolationChoice};
#[cfg(test)]
mod sparse_tests;
