//! Catmull-Clark masks (Catmull & Clark 1978) with the semi-sharp crease rules of DeRose,
//! Kass & Truong (1998), matching OpenSubdiv's `Sdc::Scheme<SCHEME_CATMARK>`.
//!
//! Face weights of edge and vertex masks apply to the *face points* of the same level (the
//! child vertices of the incident faces); edge weights apply to the vertex at the other end
//! of each incident edge.

use super::crease::{fractional_weight_at_vertex, sharp_edge_pair};
use super::rule;
use crate::options::{CreaseMethod, TriangleSubdivision};
use crate::real::Real;

/// Weight given to a triangle's face point by the `Smooth` triangle rule (OpenSubdiv, after Hbr).
pub const SMOOTH_TRI_EDGE_WEIGHT: f32 = 0.470;

/// An edge-point mask: the same weight for both end vertices and for every incident face point.
/// Weights are `W` (`f32` for the tables, `f64` for double-precision ones); sharpness values
/// stay `f32`, as in OpenSubdiv, whose masks are templated on the weight type only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeMask<W = f32> {
    /// Weight of each end vertex.
    pub vertex: W,
    /// Weight of each incident face point (0 for a crease).
    pub face: W,
}

/// The edge-point mask of an edge of sharpness `sharpness` with `face_count` faces, given the
/// rule of its child vertex. `tri` says which of the (two) faces are triangles, for the
/// `Smooth` triangle rule.
pub fn edge_mask<W: Real>(
    sharpness: f32,
    child_rule: u8,
    face_count: usize,
    tri: [bool; 2],
    tri_rule: TriangleSubdivision,
) -> EdgeMask<W> {
    let c = W::from_f64;
    let smooth = || -> EdgeMask<W> {
        let use_tri =
            tri_rule == TriangleSubdivision::Smooth && face_count == 2 && (tri[0] || tri[1]);
        if !use_tri {
            let face = if face_count == 2 {
                c(0.25)
            } else {
                c(0.5) / c(face_count as f64)
            };
            EdgeMask {
                vertex: c(0.25),
                face,
            }
        } else {
            let tri_w = W::from_f32(SMOOTH_TRI_EDGE_WEIGHT);
            let f0 = if tri[0] { tri_w } else { c(0.25) };
            let f1 = if tri[1] { tri_w } else { c(0.25) };
            let face = c(0.5) * (f0 + f1);
            EdgeMask {
                vertex: c(0.5) * (W::ONE - c(2.0) * face),
                face,
            }
        }
    };
    if sharpness <= 0.0 {
        return smooth();
    }
    if child_rule == rule::CREASE {
        return EdgeMask {
            vertex: c(0.5),
            face: W::ZERO,
        };
    }
    // Crease in the parent, smooth (or dart) in the child: blend by the parent sharpness.
    let m = smooth();
    let p = W::from_f32(sharpness);
    let q = W::ONE - p;
    EdgeMask {
        vertex: p * c(0.5) + q * m.vertex,
        face: m.face * q,
    }
}

/// A vertex-point mask over a vertex with `n` incident edges and faces (ring order).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VertexMask<W = f32> {
    /// Weight of the vertex itself.
    pub vertex: W,
    /// One weight per incident edge (its other end); empty means all zero.
    pub edges: Vec<W>,
    /// One weight per incident face point; empty means all zero.
    pub faces: Vec<W>,
}

impl<W: Real> VertexMask<W> {
    fn set(&mut self, r: u8, edge_sharpness: &[f32], num_faces: usize) {
        let c = W::from_f64;
        let n = edge_sharpness.len();
        self.edges.clear();
        self.faces.clear();
        if r == rule::SMOOTH || r == rule::DART {
            let valence = num_faces;
            self.vertex = (c(valence as f64) - c(2.0)) / c(valence as f64);
            let w = W::ONE / c((valence * valence) as f64);
            self.edges.resize(n, w);
            self.faces.resize(num_faces, w);
        } else if r == rule::CREASE {
            let ends = sharp_edge_pair(edge_sharpness);
            self.vertex = c(0.75);
            self.edges.resize(n, W::ZERO);
            self.edges[ends[0]] = c(0.125);
            self.edges[ends[1]] = c(0.125);
        } else {
            self.vertex = W::ONE;
        }
    }
}

/// Inputs of a vertex-point mask: the rules and sharpness of the vertex and its edges in the
/// parent and child levels (edges in ring order).
#[derive(Debug, Clone, Copy)]
pub struct VertexNeighbourhood<'a> {
    /// Number of incident faces.
    pub num_faces: usize,
    /// Parent vertex sharpness.
    pub parent_sharpness: f32,
    /// Child vertex sharpness.
    pub child_sharpness: f32,
    /// Parent edge sharpness, one per incident edge.
    pub parent_edges: &'a [f32],
    /// Child edge sharpness, one per incident edge (same order).
    pub child_edges: &'a [f32],
    /// Rule of the parent vertex.
    pub parent_rule: u8,
    /// Rule of the child vertex.
    pub child_rule: u8,
}

/// The vertex-point mask, blending the parent and child rules by the fractional weight when
/// they differ (OpenSubdiv `Scheme::ComputeVertexVertexMask`). `scratch` is reused.
pub fn vertex_mask<W: Real>(
    h: &VertexNeighbourhood<'_>,
    method: CreaseMethod,
    out: &mut VertexMask<W>,
    scratch: &mut VertexMask<W>,
) {
    let (p_rule, c_rule) = (h.parent_rule, h.child_rule);
    if p_rule == rule::SMOOTH || p_rule == rule::DART {
        out.set(rule::SMOOTH, h.parent_edges, h.num_faces);
        return;
    }
    out.set(p_rule, h.parent_edges, h.num_faces);
    if c_rule == p_rule {
        return;
    }
    scratch.set(c_rule, h.child_edges, h.num_faces);
    let pw = W::from_f32(fractional_weight_at_vertex(
        method,
        h.parent_sharpness,
        h.child_sharpness,
        h.parent_edges,
        h.child_edges,
    ));
    let cw = W::ONE - pw;
    out.vertex = pw * out.vertex + cw * scratch.vertex;
    combine(&mut out.edges, &scratch.edges, pw, cw);
    combine(&mut out.faces, &scratch.faces, pw, cw);
}

fn combine<W: Real>(dst: &mut Vec<W>, src: &[W], pw: W, cw: W) {
    if src.is_empty() {
        return;
    }
    if dst.is_empty() {
        dst.extend(src.iter().map(|&s| cw * s));
    } else {
        for (d, &s) in dst.iter_mut().zip(src) {
            *d = pw * *d + cw * s;
        }
    }
}

/// Limit-position mask of a vertex (OpenSubdiv `ComputeVertexLimitMask`). For the smooth rule
/// the face weights apply to the vertex opposite in each (quad) face.
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
    if (r == rule::SMOOTH || r == rule::DART) && num_faces != 2 {
        let valence = num_faces;
        let (fw, ew, vw) = if valence == 4 {
            (c(1.0) / c(36.0), c(1.0) / c(9.0), c(4.0) / c(9.0))
        } else {
            let k = c(valence as f64);
            let fw = W::ONE / (k * (k + c(5.0)));
            let ew = c(4.0) * fw;
            (fw, ew, W::ONE - k * (ew + fw))
        };
        out.vertex = vw;
        out.edges.resize(n, ew);
        out.faces.resize(num_faces, fw);
    } else if r == rule::CREASE {
        let ends = sharp_edge_pair(edge_sharpness);
        out.vertex = c(2.0) / c(3.0);
        out.edges.resize(n, W::ZERO);
        out.edges[ends[0]] = c(1.0) / c(6.0);
        out.edges[ends[1]] = c(1.0) / c(6.0);
    } else {
        out.vertex = W::ONE;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_masks_sum_to_one() {
        for n in 3..10usize {
            let e = vec![0.0; n];
            let h = VertexNeighbourhood {
                num_faces: n,
                parent_sharpness: 0.0,
                child_sharpness: 0.0,
                parent_edges: &e,
                child_edges: &e,
                parent_rule: rule::SMOOTH,
                child_rule: rule::SMOOTH,
            };
            let (mut m, mut s) = (VertexMask::default(), VertexMask::default());
            vertex_mask(&h, CreaseMethod::Uniform, &mut m, &mut s);
            let sum: f32 = m.vertex + m.edges.iter().sum::<f32>() + m.faces.iter().sum::<f32>();
            assert!((sum - 1.0).abs() < 1e-6);
            limit_mask(rule::SMOOTH, &e, n, &mut m);
            let sum: f32 = m.vertex + m.edges.iter().sum::<f32>() + m.faces.iter().sum::<f32>();
            assert!((sum - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn fractional_crease_blends_halfway() {
        // A crease of sharpness 0.5 decays to smooth: half crease, half smooth.
        let pe = [0.5, 0.0, 0.5, 0.0];
        let ce = [0.0; 4];
        let h = VertexNeighbourhood {
            num_faces: 4,
            parent_sharpness: 0.0,
            child_sharpness: 0.0,
            parent_edges: &pe,
            child_edges: &ce,
            parent_rule: rule::CREASE,
            child_rule: rule::SMOOTH,
        };
        let (mut m, mut s) = (VertexMask::<f32>::default(), VertexMask::default());
        vertex_mask(&h, CreaseMethod::Uniform, &mut m, &mut s);
        assert!((m.vertex - (0.5 * 0.75 + 0.5 * 0.5)).abs() < 1e-7);
        assert!((m.edges[0] - (0.5 * 0.125 + 0.5 / 16.0)).abs() < 1e-7);
        assert!((m.edges[1] - 0.5 / 16.0).abs() < 1e-7);
        let em = edge_mask(
            0.5,
            rule::SMOOTH,
            2,
            [false; 2],
            TriangleSubdivision::Catmark,
        );
        assert_eq!(
            em,
            EdgeMask {
                vertex: 0.375,
                face: 0.125
            }
        );
    }
}
