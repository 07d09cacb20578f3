//! Manifold *spans* around non-manifold vertices (OpenSubdiv `Vtr::Level::VSpan`): the fan
//! of faces around corner `k` of face `f` reachable by crossing manifold interior edges.
//! Patch regularity and patch points at a non-manifold corner are those of its span, which
//! looks like the ring of an ordinary boundary (or interior) vertex.
//!
//! Walking "forward" crosses a face's edge arriving at the vertex (its `b` edge, from the
//! previous corner), which is the counter-clockwise order of [`crate::topology`]'s rings.

use crate::topology::tags;
use crate::topology::Topology;

/// A span: its faces in counter-clockwise order with the vertex's corner in each, and
/// whether it closes on itself (an interior fan).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Span {
    /// `(face, corner)` pairs, counter-clockwise.
    pub faces: Vec<(u32, u16)>,
    /// The fan closes (no singular edge bounds it).
    pub cyclic: bool,
}

fn singular(t: &Topology, e: u32) -> bool {
    let e = e as usize;
    t.edge_tags[e] & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD) != 0
        || t.edge_faces(e).len() != 2
        || t.edge_verts[e][0] == t.edge_verts[e][1]
}

/// The face across manifold edge `k` of face `f` and that edge's index in it.
fn across(t: &Topology, f: usize, k: usize) -> Option<(usize, usize)> {
    let e = t.face_edges(f)[k];
    if singular(t, e) {
        return None;
    }
    let (faces, locals) = (t.edge_faces(e as usize), t.edge_faces_local(e as usize));
    (0..2)
        .find(|&i| !(faces[i] as usize == f && locals[i] as usize == k))
        .map(|i| (faces[i] as usize, locals[i] as usize))
}

/// One step forward (across the edge arriving at corner `k`): the next face and the
/// vertex's corner in it.
fn forward(t: &Topology, f: usize, k: usize) -> Option<(usize, usize)> {
    let n = t.face_size(f);
    let (g, j) = across(t, f, (k + n - 1) % n)?;
    // In g the shared edge leaves the vertex: it is g's edge starting at its corner j.
    Some((g, j))
}

/// One step backward (across the edge leaving corner `k`).
fn backward(t: &Topology, f: usize, k: usize) -> Option<(usize, usize)> {
    let (g, j) = across(t, f, k)?;
    // In g the shared edge arrives at the vertex: the vertex is g's corner j + 1.
    Some((g, (j + 1) % t.face_size(g)))
}

/// The span of corner `k` of face `f`.
pub fn span(t: &Topology, f: usize, k: usize) -> Span {
    let limit = t.vertex_faces(t.face_vertices(f)[k] as usize).len() + 1;
    let (mut sf, mut sk) = (f, k);
    let mut cyclic = false;
    for _ in 0..limit {
        match backward(t, sf, sk) {
            Some((g, j)) if (g, j) == (f, k) => {
                cyclic = true;
                break;
            }
            Some((g, j)) => (sf, sk) = (g, j),
            None => break,
        }
    }
    if cyclic {
        (sf, sk) = (f, k);
    }
    let mut faces = vec![(sf as u32, sk as u16)];
    for _ in 0..limit {
        let (cf, ck) = faces[faces.len() - 1];
        match forward(t, cf as usize, ck as usize) {
            Some((g, j)) if (g as u32, j as u16) == faces[0] => break,
            Some((g, j)) => faces.push((g as u32, j as u16)),
            None => break,
        }
    }
    Span { faces, cyclic }
}

/// The vertex after and before corner `k` in face `f`, and the one opposite (quads).
pub fn neighbours(t: &Topology, f: usize, k: usize) -> (u32, u32, u32) {
    let fv = t.face_vertices(f);
    let n = fv.len();
    (fv[(k + 1) % n], fv[(k + n - 1) % n], fv[(k + 2) % n])
}
