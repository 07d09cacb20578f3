//! The Catmull-Clark limit surface as a table of patches, evaluated anywhere.
//!
//! ```text
//! Topology ──PatchTable::build──▶ PatchTable ──points(positions)──▶ LimitSurface
//!                                                   ├── eval(ptex, u, v) / eval_batch
//!                                                   └── tessellate(N)
//! ```
//!
//! - [`table`]: which faces become regular B-spline, single-crease or Gregory end-cap
//!   patches, and the flat arrays that hold them;
//! - [`sparse`]: the sparsely refined levels the patches are taken from, within the memory
//!   [`budget`];
//! - [`leaves`]: the patch of each leaf face of a level;
//! - [`features`]: OpenSubdiv's rules for adaptive isolation and patch regularity;
//! - [`gather`]: the 16 points of a regular patch;
//! - [`endcap`]: the 20 points of a Gregory end cap;
//! - [`span`]: manifold fans around non-manifold vertices;
//! - [`patch_map`]: the quadtree per ptex face;
//! - [`eval`]: evaluation; [`tessellate`]: watertight sampling.
//!
//! # Ptex faces
//!
//! A quad is one ptex face; a face with `n ≠ 4` corners is `n` ptex faces, its level-1
//! sub-faces in corner order. Sub-face `k` has `(0,0)` at corner `k`, `(1,0)` at the midpoint
//! of edge `k → k+1`, `(1,1)` at the face centre and `(0,1)` at the midpoint of edge
//! `k−1 → k` — the vertex order of the child faces made by [`crate::refine`]. Ptex faces are
//! numbered in base face order (OpenSubdiv `Far::PtexIndices`), holes included.

pub mod budget;
pub mod endcap;
pub mod eval;
pub mod features;
pub mod gather;
pub mod leaves;
pub mod patch_map;
pub mod span;
pub mod sparse;
pub mod table;
pub mod tessellate;

pub use eval::{LimitPoint, LimitSurface};
pub use patch_map::PatchMap;
pub use table::{PatchCounts, PatchOptions, PatchTable, PatchType, MAX_ISOLATION_LEVEL};
pub use tessellate::{Tessellation, TessellationPlan};
#[cfg(test)]
mod sparse_tests;
