//! The relations of a Loop child level derived directly from a manifold parent's rings (no
//! search, no sorting), in the ring order [`Topology`] documents: faces counter-clockwise,
//! `vertex_edges(v)[i]` leaving `v` along face `i`, a boundary ring starting and ending with
//! its boundary edges.
//!
//! In a parent triangle `f` whose edge `k` runs from corner `k` to corner `k + 1`, the edge
//! point of edge `k` lies in three child faces, counter-clockwise from the side of corner
//! `k + 1`: the corner child `k + 1` (the edge point at its corner `k`), the centre child 3
//! (corner `k + 2`) and the corner child `k` (corner `k + 1`); the edges leaving it along those
//! faces are the child of edge `k` at corner `k + 1`, then the interior edges `3f + k + 1` and
//! `3f + k`, and the last face's other edge is the child of edge `k` at corner `k`.

use crate::topology::tags::rule;
use crate::topology::Topology;

/// Edge faces in face order (and the local index of the edge in each) of the child faces'
/// edges `face_edges`, over `ce` edges.
pub(super) fn edge_faces_of(face_edges: &[u32], ce: usize) -> (Vec<u32>, Vec<u32>, Vec<u16>) {
    let mut offsets = vec![0u32; ce + 1];
    for &e in face_edges {
        offsets[e as usize + 1] += 1;
    }
    for i in 0..ce {
        offsets[i + 1] += offsets[i];
    }
    let mut fill: Vec<u32> = offsets[..ce].to_vec();
    let mut ef = vec![0u32; face_edges.len()];
    let mut el = vec![0u16; face_edges.len()];
    for (i, &e) in face_edges.iter().enumerate() {
        let slot = &mut fill[e as usize];
        ef[*slot as usize] = (i / 3) as u32;
        el[*slot as usize] = (i % 3) as u16;
        *slot += 1;
    }
    (offsets, ef, el)
}

/// The child of the manifold all-triangle level `p` with its relations (sharpness, tags and
/// rules still zero), from the child lists of [`super::loop_level`].
pub(super) fn direct_relations(
    p: &Topology,
    face_verts: Vec<u32>,
    face_edges: Vec<u32>,
    edge_verts: Vec<[u32; 2]>,
) -> Topology {
    let (nv, ne, nc) = (p.num_vertices(), p.num_edges(), p.num_corners());
    let (cv, ce, cf) = (nv + ne, edge_verts.len(), face_verts.len() / 3);
    let (edge_face_offsets, edge_faces, edge_face_local) = edge_faces_of(&face_edges, ce);

    let pvf = p.vert_face_offsets[nv] as usize;
    let pve = p.vert_edge_offsets[nv] as usize;
    let mut vfo = Vec::with_capacity(cv + 1);
    let mut veo = Vec::with_capacity(cv + 1);
    vfo.extend_from_slice(&p.vert_face_offsets);
    veo.extend_from_slice(&p.vert_edge_offsets);
    let (mut nvf, mut nve) = (pvf, pve);
    for e in 0..ne {
        let k = p.edge_faces(e).len();
        nvf += 3 * k;
        nve += if k == 2 { 6 } else { 4 };
        vfo.push(nvf as u32);
        veo.push(nve as u32);
    }
    let mut vf = Vec::with_capacity(nvf);
    let mut vl = Vec::with_capacity(nvf);
    let mut ve = Vec::with_capacity(nve);

    // Children of vertices: the parent's rings, face by face and edge by edge.
    for v in 0..nv {
        for (&f, &k) in p.vertex_faces(v).iter().zip(p.vertex_faces_local(v)) {
            vf.push(4 * f + k as u32);
            vl.push(k);
        }
        for &e in p.vertex_edges(v) {
            let end = (p.edge_verts[e as usize][0] != v as u32) as u32;
            ve.push((nc + 2 * e as usize) as u32 + end);
        }
    }
    // Edge points: three faces per incident face, the forward face (edge in its direction)
    // first, so an interior ring starts with the child at end 1.
    for e in 0..ne {
        let faces = p.edge_faces(e);
        let locals = p.edge_faces_local(e);
        let forward = |i: usize| {
            let f = faces[i] as usize;
            p.face_verts[3 * f + locals[i] as usize] == p.edge_verts[e][0]
        };
        let order: [usize; 2] = if faces.len() == 2 && !forward(0) {
            [1, 0]
        } else {
            [0, 1]
        };
        let c0 = (nc + 2 * e) as u32;
        for &i in order.iter().take(faces.len()) {
            let f = faces[i];
            let k = locals[i] as u32;
            let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
            vf.extend_from_slice(&[4 * f + k1, 4 * f + 3, 4 * f + k]);
            vl.extend_from_slice(&[k as u16, k2 as u16, k1 as u16]);
            // The child at corner k + 1 of this face: end 1 where the face runs forward.
            let far = if forward(i) { c0 + 1 } else { c0 };
            let near = if forward(i) { c0 } else { c0 + 1 };
            ve.extend_from_slice(&[far, 3 * f + k1, 3 * f + k]);
            if faces.len() == 1 {
                ve.push(near);
            }
        }
    }

    Topology {
        options: p.options,
        num_vertices: cv,
        face_offsets: (0..=cf as u32).map(|f| 3 * f).collect(),
        face_verts,
        face_edges,
        edge_verts,
        edge_face_offsets,
        edge_faces,
        edge_face_local,
        vert_face_offsets: vfo,
        vert_faces: vf,
        vert_face_local: vl,
        vert_edge_offsets: veo,
        vert_edges: ve,
        edge_sharpness: vec![0.0; ce],
        vert_sharpness: vec![0.0; cv],
        face_is_hole: vec![false; cf],
        edge_tags: vec![0; ce],
        vert_tags: vec![0; cv],
        vert_rule: vec![rule::SMOOTH; cv],
    }
}
