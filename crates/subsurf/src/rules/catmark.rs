//! Catmull-Clark masks (Catmull & Clark 1978) with the semi-sharp crease rules of DeRose,
//! Kass & Truong (1998), matching OpenSubdiv's `Sdc::Scheme<SCHEME_CATMARK>`.
//!
//! Face weights of edge and vertex masks apply to the *face points* of the same level (the
//! child vertices of the incident faces); edge weights apply to the vertex at the other end
//! of each incident edge.

use super::crease::{fractional_weight_at_vertex, sharp_edge_pair};
use crate::options::{CreaseMethod, TriangleSubdivision};
use crate::topology::tags::rule;

/// Weight given to a triangle's face point by the `Smooth` triangle rule (OpenSubdiv, after Hbr).
pub const SMOOTH_TRI_EDGE_WEIGHT: f32 = 0.470;

/// An edge-point mask: the same weight for both end vertices and for every incident face point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeMask {
    /// Weight of each end vertex.
    pub vertex: f32,
    /// Weight of each incident face point (0 for a crease).
    pub face: f32,
}

/// The edge-point mask of an edge of sharpness `sharpness` with `face_count` faces, given the
/// rule of its child vertex. `tri` says which of the (two) faces are triangles, for the
/// `Smooth` triangle rule.
pub fn edge_mask(
    sharpness: f32,
    child_rule: u8,
    face_count: usize,
    tri: [bool; 2],
    tri_rule: TriangleSubdivision,
) -> EdgeMask {
    let smooth = || -> EdgeMask {
        let use_tri =
            tri_rule == TriangleSubdivision::Smooth && face_count == 2 && (tri[0] || tri[1]);
        if !use_tri {
            let face = if face_count == 2 {
                0.25
            } else {
                0.5 / face_count as f32
            };
            EdgeMask { vertex: 0.25, face }
        } else {
            let f0 = if tri[0] { SMOOTH_TRI_EDGE_WEIGHT } else { 0.25 };
            let f1 = if tri[1] { SMOOTH_TRI_EDGE_WEIGHT } else { 0.25 };
            let face = 0.5 * (f0 + f1);
            EdgeMask {
                vertex: 0.5 * (1.0 - 2.0 * face),
                face,
            }
        }
    };
    if sharpness <= 0.0 {
        return smooth();
    }
    if child_rule == rule::CREASE {
        return EdgeMask {
            vertex: 0.5,
            face: 0.0,
        };
    }
    // Crease in the parent, smooth (or dart) in the child: blend by the parent sharpness.
    let m = smooth();
    let p = sharpness;
    let c = 1.0 - p;
    EdgeMask {
        vertex: p * 0.5 + c * m.vertex,
        face: m.face * c,
    }
}

/// A vertex-point mask over a vertex with `n` incident edges and faces (ring order).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VertexMask {
    /// Weight of the vertex itself.
    pub vertex: f32,
    /// One weight per incident edge (its other end); empty means all zero.
    pub edges: Vec<f32>,
    /// One weight per incident face point; empty means all zero.
    pub faces: Vec<f32>,
}

impl VertexMask {
    fn set(&mut self, r: u8, edge_sharpness: &[f32], num_faces: usize) {
        let n = edge_sharpness.len();
        self.edges.clear();
        self.faces.clear();
        if r == rule::SMOOTH || r == rule::DART {
            let valence = num_faces;
            self.vertex = (valence as f32 - 2.0) / valence as f32;
            let w = 1.0 / (valence * valence) as f32;
            self.edges.resize(n, w);
            self.faces.resize(num_faces, w);
        } else if r == rule::CREASE {
            let ends = sharp_edge_pair(edge_sharpness);
            self.vertex = 0.75;
            self.edges.resize(n, 0.0);
            self.edges[ends[0]] = 0.125;
            self.edges[ends[1]] = 0.125;
        } else {
            self.vertex = 1.0;
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
pub fn vertex_mask(
    h: &VertexNeighbourhood<'_>,
    method: CreaseMethod,
    out: &mut VertexMask,
    scratch: &mut VertexMask,
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
    let pw = fractional_weight_at_vertex(
        method,
        h.parent_sharpness,
        h.child_sharpness,
        h.parent_edges,
        h.child_edges,
    );
    let cw = 1.0 - pw;
    out.vertex = pw * out.vertex + cw * scratch.vertex;
    combine(&mut out.edges, &scratch.edges, pw, cw);
    combine(&mut out.faces, &scratch.faces, pw, cw);
}

fn combine(dst: &mut Vec<f32>, src: &[f32], pw: f32, cw: f32) {
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
pub fn limit_mask(r: u8, edge_sharpness: &[f32], num_faces: usize, out: &mut VertexMask) {
    out.edges.clear();
    out.faces.clear();
    let n = edge_sharpness.len();
    if (r == rule::SMOOTH || r == rule::DART) && num_faces != 2 {
        let valence = num_faces;
        let (fw, ew, vw) = if valence == 4 {
            (1.0 / 36.0, 1.0 / 9.0, 4.0 / 9.0)
        } else {
            let fw = 1.0 / (valence as f32 * (valence as f32 + 5.0));
            let ew = 4.0 * fw;
            (fw, ew, 1.0 - valence as f32 * (ew + fw))
        };
        out.vertex = vw;
        out.edges.resize(n, ew);
        out.faces.resize(num_faces, fw);
    } else if r == rule::CREASE {
        let ends = sharp_edge_pair(edge_sharpness);
        out.vertex = 2.0 / 3.0;
        out.edges.resize(n, 0.0);
        out.edges[ends[0]] = 1.0 / 6.0;
        out.edges[ends[1]] = 1.0 / 6.0;
    } else {
        out.vertex = 1.0;
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
        let (mut m, mut s) = (VertexMask::default(), VertexMask::default());
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
