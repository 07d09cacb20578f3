//! One level of uniform triangle-split (Loop) refinement of the topology, numbered exactly as
//! OpenSubdiv's `Vtr::TriRefinement` numbers it.
//!
//! Child vertices: the children of the parent vertices (same index), then one edge point per
//! parent edge (`V + e`); Loop creates no face points. Child faces: four per parent triangle
//! `(v0, v1, v2)` with edge points `e0, e1, e2` (edge `k` joining corners `k` and `k + 1`):
//!
//! ```text
//!   0: (v0, e0, e2)    1: (e0, v1, e1)    2: (e2, e1, v2)    3: (e1, e2, e0)
//! ```
//!
//! Child edges: three per parent face, `(e0, e2)`, `(e1, e0)`, `(e2, e1)`, then two per parent
//! edge, from its edge point to the child of end 0, then of end 1 — the same layout as the
//! quad split (face-interior edges first, `C + 2e + end` after), so the crease machinery of
//! [`super::level`] serves both schemes.
//!
//! A manifold level refines by [`super::loop_rings`], every child table derived directly from
//! the parent's. Otherwise the child's rings are built from its face lists
//! ([`Topology::from_face_lists`]) and its edges then renumbered and oriented as OpenSubdiv's.

use super::level::{child_edge_sharpness, edge_point_tags, vertex_child_tags};
use crate::error::{Error, MeshError, Result};
use crate::rules::crease;
use crate::topology::tags;
use crate::topology::Topology;

/// The first face of `t` that is not a triangle, as the error Loop subdivision gives it
/// (OpenSubdiv's factory refuses such a mesh for the Loop scheme).
pub fn check_triangles(t: &Topology) -> Result<()> {
    match (0..t.num_faces()).find(|&f| t.face_size(f) != 3) {
        None => Ok(()),
        Some(f) => Err(MeshError::NotTriangle {
            face: f,
            corners: t.face_size(f),
        }
        .into()),
    }
}

/// Face vertices, face edges and edge vertices of the child of the all-triangle level `p`,
/// in OpenSubdiv's numbering.
fn child_lists(p: &Topology) -> (Vec<u32>, Vec<u32>, Vec<[u32; 2]>) {
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

/// Refines the all-triangle level `p` once (check with [`check_triangles`] first); returns the
/// child topology with its sharpness, tags and rules.
pub fn refine_tri_topology(p: &Topology) -> Result<Topology> {
    if super::loop_rings::is_manifold(p) {
        return Ok(super::loop_rings::refine_manifold(p));
    }
    let (nv, ne, nc) = (p.num_vertices(), p.num_edges(), p.num_corners());
    let (face_verts, face_edges, edge_verts) = child_lists(p);
    let ce = edge_verts.len();
    let (mut c, mut etags) = relations_from_faces(p, face_verts, face_edges, edge_verts)?;

    // Sharpness: interior edges smooth, children of edges decayed by the crease method.
    let mut es = vec![0.0f32; ce];
    child_edge_sharpness(p, &mut es[nc..], &mut etags[nc..]);
    for e in 0..nc {
        if c.edge_faces(e).len() != 2 {
            etags[e] |= tags::E_BOUNDARY;
        }
    }
    c.edge_sharpness = es;
    c.edge_tags = etags;
    for v in 0..nv {
        c.vert_sharpness[v] = crease::decrement(p.vert_sharpness[v]);
    }

    // Tags and rules: children of vertices inherit, recounted where features decayed.
    for v in 0..nv {
        let (mut inf, mut semi) = (0usize, 0usize);
        for &e in c.vertex_edges(v) {
            let et = c.edge_tags[e as usize];
            inf += (et & tags::E_INF_SHARP != 0) as usize;
            semi += (et & tags::E_SEMI_SHARP != 0) as usize;
        }
        let (t, r) = vertex_child_tags(p, v, c.vert_sharpness[v], inf, semi);
        c.vert_tags[v] = t & !tags::V_INCIDENT_HOLE;
        c.vert_rule[v] = r;
    }
    for e in 0..ne {
        let et = p.edge_tags[e];
        let (t0, t1) = (c.edge_tags[nc + 2 * e], c.edge_tags[nc + 2 * e + 1]);
        let (mut t, r) = edge_point_tags(et, t0, t1);
        if et & tags::E_BOUNDARY != 0 {
            t |= tags::V_BOUNDARY;
        }
        let ev = p.edge_verts[e];
        if et & tags::E_NON_MANIFOLD != 0 || ev[0] == ev[1] || p.edge_faces(e).len() > 2 {
            t |= tags::V_NON_MANIFOLD;
        }
        c.vert_tags[nv + e] = t;
        c.vert_rule[nv + e] = r;
    }

    // Holes: the four children of a hole.
    for f in 0..p.num_faces() {
        if p.face_is_hole[f] {
            for k in 4 * f..4 * f + 4 {
                c.face_is_hole[k] = true;
                for i in 3 * k..3 * k + 3 {
                    let v = c.face_verts[i] as usize;
                    c.vert_tags[v] |= tags::V_INCIDENT_HOLE;
                }
            }
        }
    }
    Ok(c)
}

/// The child's relations from its face lists, for a non-manifold parent: the rings as
/// [`Topology::from_face_lists`] orders them, the edges renumbered as OpenSubdiv's. Returns the
/// child and its edges' non-manifold tags.
fn relations_from_faces(
    p: &Topology,
    face_verts: Vec<u32>,
    face_edges: Vec<u32>,
    edge_verts: Vec<[u32; 2]>,
) -> Result<(Topology, Vec<u8>)> {
    let cv = p.num_vertices() + p.num_edges();
    let ce = edge_verts.len();
    let nf = face_verts.len() / 3;
    let face_offsets: Vec<u32> = (0..=nf as u32).map(|f| 3 * f).collect();
    let mut c = Topology::from_face_lists(cv, face_offsets, face_verts, p.options);

    // Renumber the edges found from the face lists as OpenSubdiv numbers them. The face
    // lists can join what OpenSubdiv keeps apart: the two children of a degenerate edge
    // `(v, v)` join the same two vertices and look like one edge.
    const SPLIT: u32 = u32::MAX - 1;
    let mut map = vec![u32::MAX; c.num_edges()];
    for (&found, &want) in c.face_edges.iter().zip(&face_edges) {
        let m = &mut map[found as usize];
        *m = if *m == u32::MAX || *m == want {
            want
        } else {
            SPLIT
        };
    }
    let mut etags = vec![0u8; ce];
    for (found, &want) in map.iter().enumerate() {
        if want == SPLIT {
            continue;
        }
        if want as usize >= ce {
            return Err(Error::Internal(
                "Loop refinement: an unused child edge".into(),
            ));
        }
        etags[want as usize] = c.edge_tags[found] & tags::E_NON_MANIFOLD;
    }
    // Edge faces, in face order, from the child's face edges.
    let mut counts = vec![0u32; ce];
    for &e in &face_edges {
        counts[e as usize] += 1;
    }
    let efo = crate::topology::offsets_from_counts(&counts);
    let mut fill: Vec<u32> = efo[..ce].to_vec();
    let mut ef = vec![0u32; face_edges.len()];
    let mut el = vec![0u16; face_edges.len()];
    for (i, &e) in face_edges.iter().enumerate() {
        let slot = &mut fill[e as usize];
        ef[*slot as usize] = (i / 3) as u32;
        el[*slot as usize] = (i % 3) as u16;
        *slot += 1;
    }
    if counts.contains(&0) {
        return Err(Error::Internal(
            "Loop refinement: a child edge without faces".into(),
        ));
    }
    // Vertex edges: renumbered, or, around a split edge, gathered again from the ring's faces
    // (the edge leaving the vertex in each face, then the one arriving).
    let mut veo = Vec::with_capacity(cv + 1);
    let mut ve = Vec::with_capacity(c.vert_edges.len());
    veo.push(0u32);
    for v in 0..cv {
        let ring = c.vertex_edges(v);
        if ring.iter().all(|&e| map[e as usize] != SPLIT) {
            ve.extend(ring.iter().map(|&e| map[e as usize]));
        } else {
            let start = ve.len();
            for (&f, &k) in c.vertex_faces(v).iter().zip(c.vertex_faces_local(v)) {
                let (f, k) = (f as usize, k as usize);
                for e in [face_edges[3 * f + k], face_edges[3 * f + (k + 2) % 3]] {
                    if !ve[start..].contains(&e) {
                        ve.push(e);
                    }
                }
            }
            for &e in &ve[start..] {
                etags[e as usize] |= tags::E_NON_MANIFOLD;
            }
            c.vert_tags[v] |= tags::V_NON_MANIFOLD;
        }
        veo.push(ve.len() as u32);
    }
    c.vert_edge_offsets = veo;
    c.vert_edges = ve;
    c.face_edges = face_edges;
    c.edge_verts = edge_verts;
    c.edge_face_offsets = efo;
    c.edge_faces = ef;
    c.edge_face_local = el;
    Ok((c, etags))
}
