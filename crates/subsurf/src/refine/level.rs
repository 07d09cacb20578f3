//! One level of uniform quad-split refinement of the topology, derived directly from the
//! parent's tables (no search, no hashing), numbered exactly as OpenSubdiv's
//! `Vtr::QuadRefinement` numbers it.
//!
//! Child vertices: the children of the parent vertices (same index), then one per parent face
//! (face points), then one per parent edge (edge points). Child faces: one per parent face
//! corner, in corner order. Child edges: one per parent face corner (from the face point to the
//! edge point of edge `j`), then two per parent edge (from its edge point to the child of end
//! 0, then of end 1).
//!
//! A child face of a quad keeps the parent's orientation: child `j` has the child of corner
//! `j` at its own corner `j`. A child face of any other polygon starts at that corner:
//!
//! ```text
//!   slot 0: child of vertex j        slot 1: edge point of edge j (j → j+1)
//!   slot 2: face point               slot 3: edge point of edge j−1
//! ```

use super::super::topology::tags::{self, rule};
use super::super::topology::Topology;
use crate::options::CreaseMethod;
use crate::rules::crease;
use crate::SHARPNESS_INFINITE;

/// Position in child face `j` of a parent face of size `n` of the given slot (0..4).
#[inline]
fn pos(n: usize, j: usize, slot: usize) -> u16 {
    if n == 4 {
        ((j + slot) & 3) as u16
    } else {
        slot as u16
    }
}

/// Which child edge (0 or 1) of edge `ev` touches corner vertex `v`, as seen from the face
/// where the edge follows the corner (`next`) or precedes it (`!next`).
#[inline]
fn child_end(ev: [u32; 2], v: u32, next: bool) -> u32 {
    if ev[0] != ev[1] {
        (ev[0] != v) as u32
    } else if next {
        0
    } else {
        1
    }
}

/// Refines `p` once; returns the child topology with its sharpness, tags and rules.
pub fn refine_topology(p: &Topology) -> Topology {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let fchild = |f: usize| (nv + f) as u32;
    let echild = |e: usize| (nv + nf + e) as u32;
    let cv = nv + nf + ne;
    let (cf, ce) = (nc, nc + 2 * ne);

    // Faces: vertices and edges.
    let face_offsets: Vec<u32> = (0..=cf as u32).map(|i| 4 * i).collect();
    let mut face_verts = vec![0u32; 4 * cf];
    let mut face_edges = vec![0u32; 4 * cf];
    for f in 0..nf {
        let (s, n) = (p.face_offsets[f] as usize, p.face_size(f));
        let fv = &p.face_verts[s..s + n];
        let fe = &p.face_edges[s..s + n];
        for j in 0..n {
            let jp = if j == 0 { n - 1 } else { j - 1 };
            let c = 4 * (s + j);
            face_verts[c + pos(n, j, 0) as usize] = fv[j];
            face_verts[c + pos(n, j, 1) as usize] = echild(fe[j] as usize);
            face_verts[c + pos(n, j, 2) as usize] = fchild(f);
            face_verts[c + pos(n, j, 3) as usize] = echild(fe[jp] as usize);
            let en = fe[j] as usize;
            let ep = fe[jp] as usize;
            face_edges[c + pos(n, j, 0) as usize] =
                (nc + 2 * en) as u32 + child_end(p.edge_verts[en], fv[j], true);
            face_edges[c + pos(n, j, 1) as usize] = (s + j) as u32;
            face_edges[c + pos(n, j, 2) as usize] = (s + jp) as u32;
            face_edges[c + pos(n, j, 3) as usize] =
                (nc + 2 * ep) as u32 + child_end(p.edge_verts[ep], fv[j], false);
        }
    }

    // Edges: vertices, faces, sharpness, tags.
    let mut edge_verts = vec![[0u32; 2]; ce];
    let mut edge_face_counts = vec![0u32; ce];
    for f in 0..nf {
        let (s, n) = (p.face_offsets[f] as usize, p.face_size(f));
        for j in 0..n {
            edge_verts[s + j] = [fchild(f), echild(p.face_edges[s + j] as usize)];
            edge_face_counts[s + j] = 2;
        }
    }
    for e in 0..ne {
        let ev = p.edge_verts[e];
        edge_verts[nc + 2 * e] = [echild(e), ev[0]];
        edge_verts[nc + 2 * e + 1] = [echild(e), ev[1]];
        let k = p.edge_faces(e).len() as u32;
        edge_face_counts[nc + 2 * e] = k;
        edge_face_counts[nc + 2 * e + 1] = k;
    }
    let edge_face_offsets = crate::topology::offsets_from_counts(&edge_face_counts);
    let total_ef = edge_face_offsets[ce] as usize;
    let mut edge_faces = vec![0u32; total_ef];
    let mut edge_face_local = vec![0u16; total_ef];
    for f in 0..nf {
        let (s, n) = (p.face_offsets[f] as usize, p.face_size(f));
        for j in 0..n {
            let jn = if j + 1 == n { 0 } else { j + 1 };
            let o = edge_face_offsets[s + j] as usize;
            edge_faces[o] = (s + j) as u32;
            edge_face_local[o] = pos(n, j, 1);
            edge_faces[o + 1] = (s + jn) as u32;
            edge_face_local[o + 1] = pos(n, jn, 2);
        }
    }
    for e in 0..ne {
        let ev = p.edge_verts[e];
        let mut fill = [
            edge_face_offsets[nc + 2 * e] as usize,
            edge_face_offsets[nc + 2 * e + 1] as usize,
        ];
        for (&f, &k) in p.edge_faces(e).iter().zip(p.edge_faces_local(e)) {
            let (s, n) = (p.face_offsets[f as usize] as usize, p.face_size(f as usize));
            let k = k as usize;
            let kn = if k + 1 == n { 0 } else { k + 1 };
            let end = child_end(ev, p.face_verts[s + k], true) as usize;
            edge_faces[fill[end]] = (s + k) as u32;
            edge_face_local[fill[end]] = pos(n, k, 0);
            fill[end] += 1;
            let end = child_end(ev, p.face_verts[s + kn], false) as usize;
            edge_faces[fill[end]] = (s + kn) as u32;
            edge_face_local[fill[end]] = pos(n, kn, 3);
            fill[end] += 1;
        }
    }

    // Vertices: faces and edges in ring order.
    let mut vf_counts = vec![0u32; cv];
    let mut ve_counts = vec![0u32; cv];
    for v in 0..nv {
        vf_counts[v] = p.vertex_faces(v).len() as u32;
        ve_counts[v] = p.valence(v) as u32;
    }
    for f in 0..nf {
        let n = p.face_size(f) as u32;
        vf_counts[nv + f] = n;
        ve_counts[nv + f] = n;
    }
    for e in 0..ne {
        let k = p.edge_faces(e).len() as u32;
        vf_counts[nv + nf + e] = 2 * k;
        ve_counts[nv + nf + e] = 2 + k;
    }
    let vert_face_offsets = crate::topology::offsets_from_counts(&vf_counts);
    let vert_edge_offsets = crate::topology::offsets_from_counts(&ve_counts);
    let mut vert_faces = vec![0u32; vert_face_offsets[cv] as usize];
    let mut vert_face_local = vec![0u16; vert_faces.len()];
    let mut vert_edges = vec![0u32; vert_edge_offsets[cv] as usize];
    let mut vert_tags = vec![0u16; cv];
    for v in 0..nv {
        let o = vert_face_offsets[v] as usize;
        for (i, (&f, &k)) in p
            .vertex_faces(v)
            .iter()
            .zip(p.vertex_faces_local(v))
            .enumerate()
        {
            let (s, n) = (p.face_offsets[f as usize] as usize, p.face_size(f as usize));
            vert_faces[o + i] = (s + k as usize) as u32;
            vert_face_local[o + i] = pos(n, k as usize, 0);
        }
        let o = vert_edge_offsets[v] as usize;
        let pe = p.vertex_edges(v);
        for (i, &e) in pe.iter().enumerate() {
            let ev = p.edge_verts[e as usize];
            let end = if ev[0] != ev[1] {
                (ev[0] != v as u32) as u32
            } else {
                (i > 0 && pe[i - 1] == e) as u32
            };
            vert_edges[o + i] = (nc + 2 * e as usize) as u32 + end;
        }
        vert_tags[v] = p.vert_tags[v]
            & !(tags::V_SEMI_SHARP
                | tags::V_INF_SHARP
                | tags::V_SEMI_SHARP_EDGES
                | tags::V_INF_SHARP_EDGES);
    }
    for f in 0..nf {
        let (s, n) = (p.face_offsets[f] as usize, p.face_size(f));
        let (of, oe) = (
            vert_face_offsets[nv + f] as usize,
            vert_edge_offsets[nv + f] as usize,
        );
        for j in 0..n {
            vert_faces[of + j] = (s + j) as u32;
            vert_face_local[of + j] = pos(n, j, 2);
            vert_edges[oe + j] = (s + if j == 0 { n - 1 } else { j - 1 }) as u32;
        }
        if n != 4 {
            vert_tags[nv + f] |= tags::V_XORDINARY;
        }
    }
    for e in 0..ne {
        let ev = p.edge_verts[e];
        let cvx = nv + nf + e;
        let (of, oe) = (
            vert_face_offsets[cvx] as usize,
            vert_edge_offsets[cvx] as usize,
        );
        let (c0, c1) = ((nc + 2 * e) as u32, (nc + 2 * e + 1) as u32);
        let faces = p.edge_faces(e);
        let locals = p.edge_faces_local(e);
        let et = p.edge_tags[e];
        let mut vt = 0u16;
        if et & tags::E_BOUNDARY != 0 {
            vt |= tags::V_BOUNDARY;
        }
        let corner = |i: usize| -> (usize, usize, usize, usize) {
            let f = faces[i] as usize;
            let (s, n) = (p.face_offsets[f] as usize, p.face_size(f));
            let k = locals[i] as usize;
            (s, n, k, if k + 1 == n { 0 } else { k + 1 })
        };
        let forward = |i: usize| -> bool {
            let (s, _, k, _) = corner(i);
            p.face_verts[s + k] == ev[0]
        };
        let manifold = et & tags::E_NON_MANIFOLD == 0 && ev[0] != ev[1];
        if manifold && faces.len() == 2 {
            let (ia, ib) = if forward(0) { (0, 1) } else { (1, 0) };
            let (sa, na, ka, kan) = corner(ia);
            let (sb, nb, kb, kbn) = corner(ib);
            vert_faces[of..of + 4].copy_from_slice(&[
                (sa + kan) as u32,
                (sa + ka) as u32,
                (sb + kbn) as u32,
                (sb + kb) as u32,
            ]);
            vert_face_local[of..of + 4].copy_from_slice(&[
                pos(na, kan, 3),
                pos(na, ka, 1),
                pos(nb, kbn, 3),
                pos(nb, kb, 1),
            ]);
            vert_edges[oe..oe + 4].copy_from_slice(&[c1, (sa + ka) as u32, c0, (sb + kb) as u32]);
        } else if manifold && faces.len() == 1 {
            let (s, n, k, kn) = corner(0);
            vert_faces[of..of + 2].copy_from_slice(&[(s + kn) as u32, (s + k) as u32]);
            vert_face_local[of..of + 2].copy_from_slice(&[pos(n, kn, 3), pos(n, k, 1)]);
            let (first, last) = if forward(0) { (c1, c0) } else { (c0, c1) };
            vert_edges[oe..oe + 3].copy_from_slice(&[first, (s + k) as u32, last]);
        } else {
            vt |= tags::V_NON_MANIFOLD;
            vert_edges[oe] = c0;
            vert_edges[oe + 1] = c1;
            for i in 0..faces.len() {
                let (s, n, k, kn) = corner(i);
                vert_faces[of + 2 * i] = (s + k) as u32;
                vert_face_local[of + 2 * i] = pos(n, k, 1);
                vert_faces[of + 2 * i + 1] = (s + kn) as u32;
                vert_face_local[of + 2 * i + 1] = pos(n, kn, 3);
                vert_edges[oe + 2 + i] = (s + k) as u32;
            }
        }
        if et & tags::E_NON_MANIFOLD != 0 {
            vt |= tags::V_NON_MANIFOLD;
        }
        vert_tags[cvx] = vt;
    }

    // Sharpness.
    let method = p.options.crease_method;
    let mut edge_sharpness = vec![0.0f32; ce];
    let mut edge_tags = vec![0u8; ce];
    let mut around: Vec<f32> = Vec::new();
    for e in 0..ne {
        let s = p.edge_sharpness[e];
        let et = p.edge_tags[e] & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD);
        for end in 0..2 {
            let c = nc + 2 * e + end;
            let cs = if crease::is_infinite(s) {
                SHARPNESS_INFINITE
            } else if crease::is_semi_sharp(s) {
                if method == CreaseMethod::Uniform {
                    crease::decrement(s)
                } else {
                    let v = p.edge_verts[e][end] as usize;
                    around.clear();
                    around.extend(
                        p.vertex_edges(v)
                            .iter()
                            .map(|&x| p.edge_sharpness[x as usize]),
                    );
                    crease::subdivide_edge_sharpness_at_vertex(method, s, &around)
                }
            } else {
                0.0
            };
            edge_sharpness[c] = cs;
            edge_tags[c] = et | sharp_tag(cs);
        }
    }
    let mut vert_sharpness = vec![0.0f32; cv];
    for v in 0..nv {
        vert_sharpness[v] = crease::decrement(p.vert_sharpness[v]);
    }

    let mut face_is_hole = vec![false; nc];
    for f in 0..nf {
        if p.face_is_hole[f] {
            let (s, e) = (p.face_offsets[f] as usize, p.face_offsets[f + 1] as usize);
            face_is_hole[s..e].fill(true);
        }
    }

    let mut child = Topology {
        options: p.options,
        num_vertices: cv,
        face_offsets,
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
        edge_sharpness,
        vert_sharpness,
        face_is_hole,
        edge_tags,
        vert_tags,
        vert_rule: vec![rule::SMOOTH; cv],
    };
    assign_child_rules(p, &mut child);
    child
}

fn sharp_vertex_tags(s: f32, inf: usize, semi: usize) -> u16 {
    let mut vt = 0;
    if crease::is_infinite(s) {
        vt |= tags::V_INF_SHARP;
    } else if s > 0.0 {
        vt |= tags::V_SEMI_SHARP;
    }
    if inf > 0 {
        vt |= tags::V_INF_SHARP_EDGES;
    }
    if semi > 0 {
        vt |= tags::V_SEMI_SHARP_EDGES;
    }
    vt
}

fn sharp_tag(s: f32) -> u8 {
    if crease::is_infinite(s) {
        tags::E_INF_SHARP
    } else if s > 0.0 {
        tags::E_SEMI_SHARP
    } else {
        0
    }
}

/// Vertex sharpness tags and rules of the child level (OpenSubdiv `Refinement::
/// reclassifySemisharpVertices` and the tag propagation before it).
fn assign_child_rules(p: &Topology, c: &mut Topology) {
    let (nv, nf, ne) = (p.num_vertices(), p.num_faces(), p.num_edges());
    let count_sharp = |c: &Topology, edges: &[u32]| -> (usize, usize) {
        let (mut inf, mut semi) = (0usize, 0usize);
        for &e in edges {
            let et = c.edge_tags[e as usize];
            inf += (et & tags::E_INF_SHARP != 0) as usize;
            semi += (et & tags::E_SEMI_SHARP != 0) as usize;
        }
        (inf, semi)
    };
    // Children of vertices: inherit, and recount where semi-sharp features decayed.
    for v in 0..nv {
        let (inf, semi) = count_sharp(c, c.vertex_edges(v));
        let s = c.vert_sharpness[v];
        c.vert_tags[v] |= sharp_vertex_tags(s, inf, semi);
        let pt = p.vert_tags[v];
        c.vert_rule[v] = if pt & (tags::V_SEMI_SHARP | tags::V_SEMI_SHARP_EDGES) != 0 && s <= 0.0 {
            rule::determine(0.0, inf + semi)
        } else {
            p.vert_rule[v]
        };
    }
    // Face points are smooth and have no sharp edges (already so initialised).
    // Edge points: only their two child edges can be sharp.
    let nc = p.num_corners();
    for e in 0..ne {
        let v = nv + nf + e;
        let (inf, semi) = count_sharp(c, &[(nc + 2 * e) as u32, (nc + 2 * e + 1) as u32]);
        c.vert_tags[v] |= sharp_vertex_tags(0.0, inf, semi);
        let et = p.edge_tags[e];
        c.vert_rule[v] = if et & tags::E_SEMI_SHARP != 0 {
            rule::determine(0.0, semi)
        } else if et & tags::E_INF_SHARP != 0 {
            rule::CREASE
        } else {
            rule::SMOOTH
        };
    }
    debug_assert_eq!(c.num_vertices, nv + nf + ne);
    for f in 0..c.num_faces() {
        if c.face_is_hole[f] {
            let (s, e) = (c.face_offsets[f] as usize, c.face_offsets[f + 1] as usize);
            for i in s..e {
                let v = c.face_verts[i] as usize;
                c.vert_tags[v] |= tags::V_INCIDENT_HOLE;
            }
        }
    }
}
