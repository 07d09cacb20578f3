//! Loop masks (Loop 1987) with the semi-sharp crease rules of DeRose, Kass & Truong (1998),
//! matching OpenSubdiv's `Sdc::Scheme<SCHEME_LOOP>`.
//!
//! Loop refinement creates no face points: the "face" weights of an edge mask apply to the
//! vertex opposite the edge in each incident triangle, and a vertex mask has edge weights only
//! (each applying to the vertex at the other end of an incident edge).

use super::catmark::VertexMask;
use super::crease::{fractional_weight_at_vertex, sharp_edge_pair};
use super::rule;
use crate::options::CreaseMethod;
use crate::real::Real;

/// An edge-point mask: the same weight for both end vertices and for the opposite vertex of
/// every incident triangle. Weights are `W` (`f32` for the tables, `f64` for double-precision
/// ones); sharpness values stay `f32`, as in OpenSubdiv, whose masks are templated on the
/// weight type only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeMask<W = f32> {
    /// Weight of each end vertex.
    pub vertex: W,
    /// Weight of the opposite vertex of each incident face (0 for a crease).
    pub opposite: W,
}

/// The smooth edge mask: 3/8 per end, 1/8 per opposite vertex; with other than two faces the
/// opposite weights are scaled by `2 / face_count`, keeping their ratio to the ends.
fn smooth_edge<W: Real>(face_count: usize) -> EdgeMask<W> {
    let c = W::from_f64;
    let opposite = if face_count == 2 {
        c(0.125)
    } else {
        c(0.125) * (c(2.0) / c(face_count as f64))
    };
    EdgeMask {
        vertex: c(0.375),
        opposite,
    }
}

/// The edge-point mask of an edge of sharpness `sharpness` with `face_count` faces, given the
/// rule of its child vertex: smooth, crease (the midpoint) or, for a crease that decays to
/// smooth, the two blended by the parent sharpness.
pub fn edge_mask<W: Real>(sharpness: f32, child_rule: u8, face_count: usize) -> EdgeMask<W> {
    if sharpness <= 0.0 {
        return smooth_edge(face_count);
    }
    if child_rule == rule::CREASE {
        return EdgeMask {
            vertex: W::from_f64(0.5),
            opposite: W::ZERO,
        };
    }
    let m = smooth_edge::<W>(face_count);
    let p = W::from_f32(sharpness);
    let c = W::ONE - p;
    EdgeMask {
        vertex: p * W::from_f64(0.5) + c * m.vertex,
        opposite: c * m.opposite,
    }
}

/// Vertex and edge weights of the smooth vertex mask of valence `n` (Loop 1987):
/// `beta = 3/8 + cos(2 pi / n) / 4`, edge weight `(5/8 - beta^2) / n`; 1/16 and 5/8 at
/// valence 6.
pub fn smooth_weights<W: Real>(n: usize) -> (W, W) {
    if n == 6 {
        return (W::from_f64(0.625), W::from_f64(0.0625));
    }
    let dn = n as f64;
    let inv = 1.0 / dn;
    let beta = 0.25 * (std::f64::consts::PI * 2.0 * inv).cos() + 0.375;
    let ew = W::from_f64((0.625 - beta * beta) * inv);
    (W::ONE - ew * W::from_f64(dn), ew)
}

/// Sets `out` to the mask of rule `r` over `edge_sharpness.len()` edges of a vertex with
/// `num_faces` faces.
fn set<W: Real>(out: &mut VertexMask<W>, r: u8, edge_sharpness: &[f32], num_faces: usize) {
    let n = edge_sharpness.len();
    out.edges.clear();
    out.faces.clear();
    if r == rule::SMOOTH || r == rule::DART {
        let (vw, ew) = smooth_weights(num_faces);
        out.vertex = vw;
        out.edges.resize(n, ew);
    } else if r == rule::CREASE {
        let ends = sharp_edge_pair(edge_sharpness);
        out.vertex = W::from_f64(0.75);
        out.edges.resize(n, W::ZERO);
        out.edges[ends[0]] = W::from_f64(0.125);
        out.edges[ends[1]] = W::from_f64(0.125);
    } else {
        out.vertex = W::ONE;
    }
}

/// The vertex-point mask of a vertex with `num_faces` faces, blending the parent and child
/// rules by the fractional weight when they differ (OpenSubdiv
/// `Scheme::ComputeVertexVertexMask`). Edge sharpness is given per incident edge, in ring
/// order, in the parent and child levels. `scratch` is reused.
#[allow(clippy::too_many_arguments)]
pub fn vertex_mask<W: Real>(
    num_faces: usize,
    rules: [u8; 2],
    vertex_sharpness: [f32; 2],
    parent_edges: &[f32],
    child_edges: &[f32],
    method: CreaseMethod,
    out: &mut VertexMask<W>,
    scratch: &mut VertexMask<W>,
) {
    let [p_rule, c_rule] = rules;
    if p_rule == rule::SMOOTH || p_rule == rule::DART {
        set(out, rule::SMOOTH, parent_edges, num_faces);
        return;
    }
    set(out, p_rule, parent_edges, num_faces);
    if c_rule == p_rule {
        return;
    }
    set(scratch, c_rule, child_edges, num_faces);
    let pw = W::from_f32(fractional_weight_at_vertex(
        method,
        vertex_sharpness[0],
        vertex_sharpness[1],
        parent_edges,
        child_edges,
    ));
    let cw = W::ONE - pw;
    out.vertex = pw * out.vertex + cw * scratch.vertex;
    if out.edges.is_empty() {
        out.edges.extend(scratch.edges.iter().map(|&s| cw * s));
    } else if !scratch.edges.is_empty() {
        for (d, &s) in out.edges.iter_mut().zip(&scratch.edges) {
            *d = pw * *d + cw * s;
        }
    }
}

/// Limit-position mask of a vertex (OpenSubdiv `Scheme::ComputeVertexLimitMask`): smooth
/// `1 / (n + 3 / (8 gamma))` per edge with `gamma` the smooth edge weight (1/12 and 1/2 at
/// valence 6), the cubic B-spline limit (1/6, 2/3, 1/6) along a crease, the vertex itself at a
/// corner.
pub fn limit_mask<W: Real>(
    r: u8,
    edge_sharpness: &[f32],
    num_faces: usize,
    out: &mut VertexMask<W>,
) {
    let c = W::from_f64;
    out.edges.clear();
    out.faces.clear();
    let n = edge_sharpness.len();
    if r == rule::SMOOTH || r == rule::DART {
        let (vw, ew) = if num_faces == 6 {
            (c(0.5), c(1.0 / 12.0))
        } else {
            let dn = num_faces as f64;
            let inv = 1.0 / dn;
            let beta = 0.25 * (std::f64::consts::PI * 2.0 * inv).cos() + 0.375;
            let gamma = (0.625 - beta * beta) * inv;
            let ew = c(1.0 / (dn + 3.0 / (8.0 * gamma)));
            (W::ONE - ew * c(dn), ew)
        };
        out.vertex = vw;
        out.edges.resize(n, ew);
    } else if r == rule::CREASE {
        let ends = sharp_edge_pair(edge_sharpness);
        out.vertex = c(4.0 / 6.0);
        out.edges.resize(n, W::ZERO);
        out.edges[ends[0]] = c(1.0 / 6.0);
        out.edges[ends[1]] = c(1.0 / 6.0);
    } else {
        out.vertex = W::ONE;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masks_sum_to_one_and_regular_weights_are_loops() {
        assert_eq!(smooth_weights::<f32>(6), (0.625, 0.0625));
        // The general formula gives the same regular weights.
        let beta = 0.25 * (std::f64::consts::PI / 3.0).cos() + 0.375;
        assert!(((0.625 - beta * beta) / 6.0 - 0.0625).abs() < 1e-12);
        let mut m = VertexMask::default();
        for n in 3..12usize {
            let (vw, ew) = smooth_weights::<f32>(n);
            assert!((vw + n as f32 * ew - 1.0).abs() < 1e-6, "valence {n}");
            limit_mask::<f32>(rule::SMOOTH, &vec![0.0; n], n, &mut m);
            let sum = m.vertex + m.edges.iter().sum::<f32>();
            assert!((sum - 1.0).abs() < 1e-6, "limit valence {n}");
        }
        // Valence 3: beta = 3/8 - 1/8 = 1/4, edge weight (5/8 - 1/16) / 3 = 3/16 (Warren).
        assert!((smooth_weights::<f32>(3).1 - 3.0 / 16.0).abs() < 1e-7);
    }

    #[test]
    fn fractional_crease_edge_blends() {
        let m = edge_mask::<f32>(0.25, rule::SMOOTH, 2);
        assert!((m.vertex - (0.25 * 0.5 + 0.75 * 0.375)).abs() < 1e-7);
        assert!((m.opposite - 0.75 * 0.125).abs() < 1e-7);
        let c = edge_mask::<f32>(3.0, rule::CREASE, 2);
        assert_eq!((c.vertex, c.opposite), (0.5, 0.0));
    }
}
