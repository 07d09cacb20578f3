//! The child relations of one Loop refinement step of any all-triangle level, manifold or
//! not, each derived directly from the parent's relations as OpenSubdiv's
//! `Vtr::TriRefinement` derives them (no search over the child's face lists), so that the
//! rings and edge-face lists around non-manifold features come out in OpenSubdiv's order.
//! Numbering as [`super::loop_level`] documents it.
//!
//! Derived relations, for a parent triangle `f` with corners `v_k`, edges `E_k` (joining
//! corners `k` and `k + 1`), corner children `4f + k`, middle child `4f + 3` and interior
//! child edges `3f + k` (the one of corner child `k`):
//!
//! - the child of vertex `v`: the corner child of each parent face of `v` at `v`, in the
//!   parent's order, with the same corner; the child of each parent edge of `v` that touches
//!   `v`, in the parent's order;
//! - the edge point of edge `e`, for each parent face `f` of `e` in the parent's order (a
//!   manifold interior edge: the face running along the edge's direction first; `e`
//!   being its edge `k`): the corner child `k + 1` (at its corner `k`), the middle child
//!   (corner `k + 2`) and the corner child `k` (corner `k + 1`); its edges are the interior
//!   edges `3f + k + 1` and `3f + k` of each face, those of the first face bracketed by the
//!   children of `e`: first the child at corner `k + 1` of the first face, last the other;
//! - an interior child edge `3f + k`: corner child `k` and the middle child, both at their
//!   edge `k + 1`;
//! - the child of edge `e` at its end `j`: the corner child of each face of `e` (in the
//!   parent's order) at that end, as that child's edge `k`.
//!
//! A degenerate parent edge `(v, v)` keeps two distinct children, and so do two parent
//! faces sharing all three vertices: the child relations never merge what the parent keeps
//! apart. The ring order at a manifold vertex is the one [`Topology`] documents.

use super::level::child_end_at_vertex;
use crate::topology::tags::{self, rule};
use crate::topology::Topology;

/// Face vertices, face edges and edge vertices of the child of the all-triangle level `p`.
fn child_faces_and_edges(p: &Topology) -> (Vec<u32>, Vec<u32>, Vec<[u32; 2]>) {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let ep = |e: u32| nv as u32 + e;
    let mut fv_out = Vec::with_capacity(12 * nf);
    let mut fe_out = Vec::with_capacity(12 * nf);
    let mut ev_out = Vec::with_capacity(nc + 2 * ne);
    for f in 0..nf {
        let fv = p.face_vertices(f);
        let fe = p.face_edges(f);
        let e = [ep(fe[0]), ep(fe[1]), ep(fe[2])];
        fv_out.extend_from_slice(&[fv[0], e[0], e[2]]);
        fv_out.extend_from_slice(&[e[0], fv[1], e[1]]);
        fv_out.extend_from_slice(&[e[2], e[1], fv[2]]);
        fv_out.extend_from_slice(&[e[1], e[2], e[0]]);
        // pe[i] = [child of edge i at corner i, child at corner i + 1].
        let pe: [[u32; 2]; 3] = std::array::from_fn(|i| {
            let ev = p.edge_verts[fe[i] as usize];
            let reversed = (ev[0] != ev[1] && fv[i] != ev[0]) as u32;
            let c = (nc + 2 * fe[i] as usize) as u32;
            [c + reversed, c + 1 - reversed]
        });
        let fc = (3 * f) as u32;
        fe_out.extend_from_slice(&[pe[0][0], fc, pe[2][1]]);
        fe_out.extend_from_slice(&[pe[0][1], pe[1][0], fc + 1]);
        fe_out.extend_from_slice(&[fc + 2, pe[1][1], pe[2][0]]);
        fe_out.extend_from_slice(&[fc + 2, fc, fc + 1]);
        ev_out.extend_from_slice(&[[e[0], e[2]], [e[1], e[0]], [e[2], e[1]]]);
    }
    for e in 0..ne {
        let ev = p.edge_verts[e];
        ev_out.push([ep(e as u32), ev[0]]);
        ev_out.push([ep(e as u32), ev[1]]);
    }
    (fv_out, fe_out, ev_out)
}

/// The child of the all-triangle level `p` with every relation derived from `p`'s (see the
/// module documentation). Vertex sharpness is zero, vertex tags are empty and rules smooth;
/// the edge sharpness, edge tags and hole flags are left empty (`refine_tri` forms them
/// whole): the caller assigns them.
pub(super) fn child_relations(p: &Topology) -> Topology {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let (cv, cf, ce) = (nv + ne, 4 * nf, nc + 2 * ne);
    let (face_verts, face_edges, edge_verts) = child_faces_and_edges(p);
    let corner = |f: u32, k: usize| p.face_verts[3 * f as usize + k];

    // Edges: two faces per interior child edge, then the children of the parent edges.
    let mut edge_face_offsets = Vec::with_capacity(ce + 1);
    let mut edge_faces = Vec::with_capacity(2 * nc + 2 * p.edge_faces.len());
    let mut edge_face_local = Vec::with_capacity(edge_faces.capacity());
    edge_face_offsets.push(0u32);
    for f in 0..nf as u32 {
        for k in 0..3u32 {
            edge_faces.extend_from_slice(&[4 * f + k, 4 * f + 3]);
            let local = ((k + 1) % 3) as u16;
            edge_face_local.extend_from_slice(&[local, local]);
            edge_face_offsets.push(edge_faces.len() as u32);
        }
    }
    for e in 0..ne {
        let ev = p.edge_verts[e];
        let (faces, locals) = (p.edge_faces(e), p.edge_faces_local(e));
        for j in 0..2 {
            for (&f, &k) in faces.iter().zip(locals) {
                let at_next = if ev[0] == ev[1] {
                    j
                } else {
                    (corner(f, k as usize) != ev[j]) as usize
                };
                edge_faces.push(4 * f + ((k as usize + at_next) % 3) as u32);
                edge_face_local.push(k);
            }
            edge_face_offsets.push(edge_faces.len() as u32);
        }
    }

    // Vertices: the children of the parent vertices, then the edge points.
    let mut vert_face_offsets = Vec::with_capacity(cv + 1);
    let mut vert_faces = Vec::with_capacity(p.vert_faces.len() + 3 * p.edge_faces.len());
    let mut vert_face_local = Vec::with_capacity(vert_faces.capacity());
    let mut vert_edge_offsets = Vec::with_capacity(cv + 1);
    let mut vert_edges = Vec::with_capacity(p.vert_edges.len() + 2 * (ne + p.edge_faces.len()));
    vert_face_offsets.push(0u32);
    vert_edge_offsets.push(0u32);
    for v in 0..nv {
        for (&f, &k) in p.vertex_faces(v).iter().zip(p.vertex_faces_local(v)) {
            vert_faces.push(4 * f + k as u32);
            vert_face_local.push(k);
        }
        let pe = p.vertex_edges(v);
        for (i, &e) in pe.iter().enumerate() {
            vert_edges.push((nc + 2 * e as usize) as u32 + child_end_at_vertex(p, pe, i, v));
        }
        vert_face_offsets.push(vert_faces.len() as u32);
        vert_edge_offsets.push(vert_edges.len() as u32);
    }
    for e in 0..ne {
        let ev = p.edge_verts[e];
        let c0 = (nc + 2 * e) as u32;
        let (faces, locals) = (p.edge_faces(e), p.edge_faces_local(e));
        // A manifold interior edge's point starts its ring at the face running along the
        // edge's direction, as the manifold refinement does, so that the rings of a level do
        // not depend on which relations it was refined with (the sparse isolation refines
        // sub-meshes whose borders are non-manifold).
        let forward = |j: usize| corner(faces[j], locals[j] as usize) == ev[0];
        let turned = faces.len() == 2
            && ev[0] != ev[1]
            && p.edge_tags[e] & tags::E_NON_MANIFOLD == 0
            && !forward(0)
            && forward(1);
        let ring = match turned {
            true => [1usize, 0],
            false => [0, 1],
        };
        let ring = ring
            .into_iter()
            .chain(2..faces.len())
            .take(faces.len())
            .map(|j| (faces[j], locals[j]));
        for (i, (f, k)) in ring.enumerate() {
            let k = k as u32;
            let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
            vert_faces.extend_from_slice(&[4 * f + k1, 4 * f + 3, 4 * f + k]);
            vert_face_local.extend_from_slice(&[k as u16, k2 as u16, k1 as u16]);
            let interior = [3 * f + k1, 3 * f + k];
            if i == 0 {
                // The child at corner k + 1 of the first face leads, the other trails.
                let reversed = (ev[0] != ev[1] && corner(f, k as usize) != ev[0]) as u32;
                vert_edges.push(c0 + 1 - reversed);
                vert_edges.extend_from_slice(&interior);
                vert_edges.push(c0 + reversed);
            } else {
                vert_edges.extend_from_slice(&interior);
            }
        }
        vert_face_offsets.push(vert_faces.len() as u32);
        vert_edge_offsets.push(vert_edges.len() as u32);
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
        vert_face_offsets,
        vert_faces,
        vert_face_local,
        vert_edge_offsets,
        vert_edges,
        edge_sharpness: Vec::new(),
        vert_sharpness: vec![0.0; cv],
        face_is_hole: Vec::new(),
        edge_tags: Vec::new(),
        vert_tags: vec![0; cv],
        vert_rule: vec![rule::SMOOTH; cv],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::options::Scheme;

    fn loop_topology(num_vertices: usize, faces: &[[u32; 3]]) -> Topology {
        let positions: Vec<[f32; 3]> = (0..num_vertices)
            .map(|i| [i as f32, (i * i % 7) as f32, (i % 3) as f32])
            .collect();
        let mut mesh = Mesh::from_faces(positions, faces);
        mesh.options.scheme = Scheme::Loop;
        Topology::new(&mesh).unwrap()
    }

    /// The ring of `v` as (face, corner, leading edge) triples, rotated to start at its
    /// smallest face, so that rings equal up to rotation compare equal.
    fn ring(t: &Topology, v: usize) -> Vec<(u32, u16, u32)> {
        let mut r: Vec<_> = t
            .vertex_faces(v)
            .iter()
            .zip(t.vertex_faces_local(v))
            .zip(t.vertex_edges(v))
            .map(|((&f, &k), &e)| (f, k, e))
            .collect();
        let start = (0..r.len()).min_by_key(|&i| r[i].0).unwrap_or(0);
        r.rotate_left(start);
        r
    }

    #[test]
    fn agrees_with_the_manifold_refinement() {
        // An octahedron with one face removed: interior and boundary vertices and edges.
        let faces = [
            [0, 1, 2],
            [0, 2, 3],
            [0, 3, 4],
            [0, 4, 1],
            [5, 2, 1],
            [5, 3, 2],
            [5, 4, 3],
        ];
        let mut p = loop_topology(6, &faces);
        for level in 0..3 {
            let a = super::super::loop_rings::refine_manifold(&p);
            let b = child_relations(&p);
            assert_eq!(a.face_verts, b.face_verts, "level {level}");
            assert_eq!(a.face_edges, b.face_edges, "level {level}");
            assert_eq!(a.edge_verts, b.edge_verts, "level {level}");
            assert_eq!(a.edge_face_offsets, b.edge_face_offsets, "level {level}");
            assert_eq!(a.edge_faces, b.edge_faces, "level {level}");
            assert_eq!(a.edge_face_local, b.edge_face_local, "level {level}");
            for v in 0..a.num_vertices() {
                assert_eq!(ring(&a, v), ring(&b, v), "level {level} vertex {v}");
                assert_eq!(a.vertex_faces(v), b.vertex_faces(v), "level {level} {v}");
                assert_eq!(a.vertex_edges(v), b.vertex_edges(v), "level {level} {v}");
            }
            p = a;
        }
    }

    #[test]
    fn faces_sharing_all_vertices_keep_their_child_edges_apart() {
        // Two triangles on the same three vertices (a closed "pillow"), next to a triangle
        // fin on one edge (three faces there) and a second fan on vertex 0.
        let faces = [[0, 1, 2], [1, 0, 2], [0, 1, 3], [0, 4, 5]];
        let p = loop_topology(6, &faces);
        assert!(!p.is_manifold());
        let c = refine_tri_topology_checked(&p);
        let (nc, ne) = (p.num_corners(), p.num_edges());
        assert_eq!(c.num_edges(), nc + 2 * ne);
        for e in 0..nc {
            assert_eq!(c.edge_faces(e).len(), 2, "interior child edge {e}");
        }
        for e in 0..ne {
            let n = p.edge_faces(e).len();
            assert_eq!(c.edge_faces(nc + 2 * e).len(), n);
            assert_eq!(c.edge_faces(nc + 2 * e + 1).len(), n);
            let point = p.num_vertices() + e;
            assert_eq!(c.vertex_faces(point).len(), 3 * n);
            assert_eq!(c.vertex_edges(point).len(), 2 + 2 * n);
        }
        // The middle children of the two pillow faces join the same three edge points, yet
        // through six distinct interior edges.
        let mut interior: Vec<[u32; 2]> = (0..6).map(|e| c.edge_verts[e]).collect();
        for ev in &mut interior {
            ev.sort();
        }
        interior.sort();
        assert_eq!(interior.windows(2).filter(|w| w[0] == w[1]).count(), 3);
    }

    /// The child with its tags, checked for consistency (local indices everywhere, ring
    /// order at manifold vertices).
    fn refine_tri_topology_checked(p: &Topology) -> Topology {
        let c = super::super::refine_tri_topology(p).unwrap();
        c.check_consistency().unwrap();
        c
    }
}
