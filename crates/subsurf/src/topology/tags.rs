//! Per-element tag bits and the vertex rule, as OpenSubdiv's `Vtr::Level::VTag`/`ETag`.

/// Edge tag: the edge has a single incident face.
pub const E_BOUNDARY: u8 = 1 << 0;
/// Edge tag: more than two faces, two faces wound the same way, a degenerate (v, v) edge, or an
/// edge that occurs twice in one face. Such edges are infinitely sharp.
pub const E_NON_MANIFOLD: u8 = 1 << 1;
/// Edge tag: sharpness is infinite (>= 10).
pub const E_INF_SHARP: u8 = 1 << 2;
/// Edge tag: sharpness is in (0, 10).
pub const E_SEMI_SHARP: u8 = 1 << 3;

/// Vertex tag: on a boundary edge.
pub const V_BOUNDARY: u16 = 1 << 0;
/// Vertex tag: its faces do not form one ordered fan (also set for vertices with no faces).
pub const V_NON_MANIFOLD: u16 = 1 << 1;
/// Vertex tag: a topological corner (one face, two edges) made infinitely sharp.
pub const V_CORNER: u16 = 1 << 2;
/// Vertex tag: valence differs from the regular one (4 inside, 2 faces on a boundary).
pub const V_XORDINARY: u16 = 1 << 3;
/// Vertex tag: infinitely sharp vertex.
pub const V_INF_SHARP: u16 = 1 << 4;
/// Vertex tag: semi-sharp vertex.
pub const V_SEMI_SHARP: u16 = 1 << 5;
/// Vertex tag: at least one incident semi-sharp edge.
pub const V_SEMI_SHARP_EDGES: u16 = 1 << 6;
/// Vertex tag: at least one incident infinitely sharp edge.
pub const V_INF_SHARP_EDGES: u16 = 1 << 7;
/// Vertex tag: at least one incident face is a hole.
pub const V_INCIDENT_HOLE: u16 = 1 << 8;
pub use crate::rules::rule;
