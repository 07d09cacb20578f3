//! The arithmetic of the subdivision scheme: sharpness decay, crease rules and the weights
//! ("masks") of new points. Nothing here knows about topology: each function is given the
//! sharpness values and counts of one neighbourhood.

pub(crate) mod catmark;
pub(crate) mod crease;
pub(crate) mod r#loop;

/// The crease rule of a vertex (Hoppe et al. 1994; DeRose et al. 1998), as bit masks so that
/// a transition between two rules can be stored as their union.
pub mod rule {
    /// Smooth vertex: no sharp edges.
    pub const SMOOTH: u8 = 1;
    /// Dart: exactly one sharp edge.
    pub const DART: u8 = 2;
    /// Crease: exactly two sharp edges.
    pub const CREASE: u8 = 4;
    /// Corner: a sharp vertex or three and more sharp edges.
    pub const CORNER: u8 = 8;

    /// The rule for a vertex of the given sharpness with `sharp_edges` incident sharp edges
    /// (OpenSubdiv `Sdc::Crease::DetermineVertexVertexRule`).
    pub fn determine(vertex_sharpness: f32, sharp_edges: usize) -> u8 {
        if vertex_sharpness > 0.0 {
            return CORNER;
        }
        match sharp_edges {
            0 => SMOOTH,
            1 => DART,
            2 => CREASE,
            _ => CORNER,
        }
    }
}
