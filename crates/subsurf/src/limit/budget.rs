//! The memory budget of a sparse construction: each level is estimated from the sub-mesh it
//! refines, before it is allocated, and a construction whose levels would not fit is refused
//! with [`crate::MeshError::TooLarge`] instead of failing an allocation.
//!
//! One refinement step of a sub-mesh with `V` vertices, `E` edges, `F` faces and `C` face
//! corners makes `F' = C` quads, `E' = 2 E + C` edges and `V' = V + E + F` vertices (a Loop
//! step of triangles: `F' = 4 F` triangles, `E' = 2 E + C` edges, `V' = V + E` vertices).
//! Their bytes are counted from the arrays that hold them:
//!
//! ```text
//! topology   61 F' + 37 E' + 14 V'   face/edge/vertex relations, sharpness, tags, rules
//! stencils   60 V'                   about 7 (index, weight) entries per row, offsets
//! flags       5 F' +  1 E' +  6 V'   feature tags, exactness, refinement marks, child links
//! patches    90 F'                   at most one patch per face: 16 indices, parameters
//! ```
//!
//! The levels are counted against a `crate::util::budget::Budget` (80% of the available memory by default).

use crate::options::Scheme;
use crate::topology::Topology;

/// Estimated bytes of the level one refinement step of `sub` makes (module documentation).
pub(crate) fn child_level_bytes(sub: &Topology) -> u64 {
    let c = sub.num_corners() as u64;
    let (v, e, f) = (
        sub.num_vertices() as u64,
        sub.num_edges() as u64,
        sub.num_faces() as u64,
    );
    let (f1, e1, v1) = match sub.options.scheme {
        Scheme::Loop => (4 * f, 2 * e + c, v + e),
        _ => (c, 2 * e + c, v + e + f),
    };
    (61 + 5 + 90) * f1 + (37 + 1) * e1 + (14 + 60 + 6) * v1
}
