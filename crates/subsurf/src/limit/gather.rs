//! The 16 control points of a regular patch, gathered from the one-ring of the face's four
//! corners (OpenSubdiv `Far::PatchBuilder::GetRegularPatchPoints`).
//!
//! The patch face's corner `k` sits at grid position `P_k` of the 4×4 grid (index `4 j + i`,
//! see [`crate::patch`]); `a_k` points from corner `k` to corner `k + 1`, `b_k` from corner
//! `k` to corner `k − 1`:
//!
//! ```text
//!   corner   P_k      a_k      b_k
//!     0     (1,1)   (+1, 0)  ( 0,+1)
//!     1     (2,1)   ( 0,+1)  (−1, 0)
//!     2     (2,2)   (−1, 0)  ( 0,−1)
//!     3     (1,2)   ( 0,−1)  (+1, 0)
//! ```
//!
//! Around a valence-4 vertex `v` with the patch face at ring position `r`, ring edge `r`
//! runs along `a`, edge `r + 1` along `b`, edge `r + 2` along `−a` and edge `r + 3` along
//! `−b`; face `r + 2` holds the diagonal point `P − a − b`. At a boundary vertex the ring is
//! not cyclic: positions past its end are missing, and so are the points beyond the boundary,
//! whose weights the boundary mask makes zero. Missing points are filled with the corner
//! vertex itself so every index stays valid.

use super::span::span;
use crate::topology::tags;
use crate::topology::Topology;

const P: [(i32, i32); 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];
const A: [(i32, i32); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];
const B: [(i32, i32); 4] = [(0, 1), (-1, 0), (0, -1), (1, 0)];

fn at(p: (i32, i32)) -> usize {
    (4 * p.1 + p.0) as usize
}

/// Position of face `f` (as corner `k`) in the face ring of `v`.
pub fn ring_position(t: &Topology, v: usize, f: usize, k: usize) -> Option<usize> {
    t.vertex_faces(v)
        .iter()
        .zip(t.vertex_faces_local(v))
        .position(|(&g, &l)| g as usize == f && l as usize == k)
}

/// The vertex of face `g` opposite to its corner `local` (quads only).
fn opposite(t: &Topology, g: usize, local: usize) -> u32 {
    let fv = t.face_vertices(g);
    fv[(local + 2) % fv.len()]
}

/// The 16 control points (level-local vertex indices) of the regular quad `f`.
pub fn regular_points(t: &Topology, f: usize) -> [u32; 16] {
    let fv = t.face_vertices(f);
    let mut pts = [fv[0]; 16];
    for k in 0..4 {
        let v = fv[k] as usize;
        let (p, a, b) = (P[k], A[k], B[k]);
        pts[at(p)] = fv[k];
        if t.vert_tags[v] & tags::V_NON_MANIFOLD != 0 {
            span_points(t, f, k, &mut pts);
            continue;
        }
        let Some(r) = ring_position(t, v, f, k) else {
            continue;
        };
        let edges = t.vertex_edges(v);
        let faces = t.vertex_faces(v);
        let interior = edges.len() == faces.len();
        let idx = |i: usize, n: usize| -> Option<usize> {
            if interior {
                // `i < r + 4 ≤ n + 3`: a subtraction or two instead of a division.
                let mut i = i;
                while i >= n {
                    i -= n;
                }
                Some(i)
            } else if i < n {
                Some(i)
            } else if i >= 4 && i - 4 < n {
                Some(i - 4)
            } else {
                None
            }
        };
        if let Some(e) = idx(r + 2, edges.len()) {
            pts[at((p.0 - a.0, p.1 - a.1))] = t.other_vertex(edges[e] as usize, v as u32);
        }
        if let Some(e) = idx(r + 3, edges.len()) {
            pts[at((p.0 - b.0, p.1 - b.1))] = t.other_vertex(edges[e] as usize, v as u32);
        }
        if let Some(i) = idx(r + 2, faces.len()) {
            let g = faces[i] as usize;
            let local = t.vertex_faces_local(v)[i] as usize;
            pts[at((p.0 - a.0 - b.0, p.1 - a.1 - b.1))] = opposite(t, g, local);
        }
    }
    pts
}

/// The points of corner `k`'s quadrant gathered from the manifold span of a non-manifold
/// corner: `−a` from the next face of the span, `−b` from the previous one, the diagonal
/// from the face after next.
fn span_points(t: &Topology, f: usize, k: usize, pts: &mut [u32; 16]) {
    let (p, a, b) = (P[k], A[k], B[k]);
    let sp = span(t, f, k);
    let n = sp.faces.len();
    let Some(r) = sp
        .faces
        .iter()
        .position(|&(g, c)| g as usize == f && c as usize == k)
    else {
        return;
    };
    let get = |i: isize| -> Option<(usize, usize)> {
        let i = if sp.cyclic {
            i.rem_euclid(n as isize)
        } else {
            i
        };
        (0..n as isize).contains(&i).then(|| {
            (
                sp.faces[i as usize].0 as usize,
                sp.faces[i as usize].1 as usize,
            )
        })
    };
    let corner = |g: usize, c: usize, d: usize| {
        let gv = t.face_vertices(g);
        gv[(c + d) % gv.len()]
    };
    let r = r as isize;
    if let Some((g, c)) = get(r + 1) {
        pts[at((p.0 - a.0, p.1 - a.1))] = corner(g, c, 3);
    }
    if let Some((g, c)) = get(r - 1) {
        pts[at((p.0 - b.0, p.1 - b.1))] = corner(g, c, 1);
    }
    if let Some((g, c)) = get(r + 2) {
        if n >= 4 || !sp.cyclic {
            pts[at((p.0 - a.0 - b.0, p.1 - a.1 - b.1))] = corner(g, c, 2);
        }
    }
}
