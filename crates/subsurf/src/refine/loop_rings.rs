//! One Loop refinement step of a manifold all-triangle level, every child table derived
//! directly from the parent's (no search, no sorting) and filled in place: each table is
//! allocated once at its exact size, its row starts following from the parent's offsets, and
//! filled in parallel chunks over parent faces, edges and vertices. Numbering as
//! [`super::loop_level`] documents it (OpenSubdiv's `Vtr::TriRefinement`); rings in the order
//! [`Topology`] documents: faces counter-clockwise, `vertex_edges(v)[i]` leaving `v` along
//! face `i`, a boundary ring starting and ending with its boundary edges.
//!
//! In a parent triangle `f` whose edge `k` runs from corner `k` to corner `k + 1`, the child of
//! edge `k` at corner `k` lies in corner child `k`, the child at corner `k + 1` in corner child
//! `k + 1`, both as that child's edge `k`. The edge point of edge `k` lies in three child faces,
//! counter-clockwise from the side of corner `k + 1`: the corner child `k + 1` (the edge point
//! at its corner `k`), the centre child 3 (corner `k + 2`) and the corner child `k` (corner
//! `k + 1`); the edges leaving it along those faces are the child of edge `k` at corner `k + 1`,
//! then the interior edges `3f + k + 1` and `3f + k`, and the last face's other edge is the
//! child of edge `k` at corner `k`.
//!
//! Sizes: a child of a vertex keeps its parent's ring sizes; the edge point of an edge of `k`
//! faces (1 or 2 on a manifold level) has `3k` faces and `2 + 2k` edges; an interior child edge
//! has two faces, a child of an edge as many as that edge.

use super::alloc::{fill, put, unwritten, written, Slot};
use super::level::{
    assemble, child_halves, edge_point_tags, iota, vertex_child_tags, ChildEdges, ChildRings,
};
use super::loop_level::child_triangles;
use crate::rules::crease;
use crate::topology::tags;
use crate::topology::Topology;
use crate::util::par;
use rayon::prelude::*;

/// Whether the all-triangle level `p` refines by [`refine_manifold`]: no non-manifold vertex
/// or edge, every edge with one or two faces.
pub(super) fn is_manifold(p: &Topology) -> bool {
    p.vert_tags.iter().all(|&t| t & tags::V_NON_MANIFOLD == 0)
        && p.edge_tags.iter().all(|&t| t & tags::E_NON_MANIFOLD == 0)
        && p.edge_face_offsets
            .windows(2)
            .all(|w| matches!(w[1] - w[0], 1 | 2))
}

/// Refines the manifold all-triangle level `p` ([`is_manifold`]) once; returns the child
/// topology with its sharpness, tags and rules. Every table is allocated unwritten
/// ([`super::alloc::unwritten`]) and filled whole by chunks that cover it
/// ([`par::split_exact`]), each row writing every value of its own.
#[allow(unsafe_code)]
pub(super) fn refine_manifold(p: &Topology) -> Topology {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let (cv, cf, ce) = (nv + ne, 4 * nf, nc + 2 * ne);
    let efo = |e: usize| p.edge_face_offsets[e] as usize;
    let ep = |e: u32| nv as u32 + e;
    let (fb, eb, vb) = (par::bounds(nf), par::bounds(ne), par::bounds(nv));
    let (fr, er, vr) = (par::ranges(&fb), par::ranges(&eb), par::ranges(&vb));

    // Vertices: children of vertices keep the parent's ring sizes, edge points follow.
    let (pvf, pve) = (
        p.vert_face_offsets[nv] as usize,
        p.vert_edge_offsets[nv] as usize,
    );
    let mut vert_face_offsets = super::alloc::empty(cv + 1);
    vert_face_offsets.extend_from_slice(&p.vert_face_offsets[..=nv]);
    vert_face_offsets.extend(
        p.edge_face_offsets[1..=ne]
            .iter()
            .map(|&o| pvf as u32 + 3 * o),
    );
    let mut vert_edge_offsets = super::alloc::empty(cv + 1);
    vert_edge_offsets.extend_from_slice(&p.vert_edge_offsets[..=nv]);
    vert_edge_offsets.extend(
        p.edge_face_offsets[1..=ne]
            .iter()
            .zip(1..=ne as u32)
            .map(|(&o, e)| pve as u32 + 2 * e + 2 * o),
    );
    let (total_vf, total_ve) = (pvf + 3 * efo(ne), pve + 2 * ne + 2 * efo(ne));
    let mut rings = ChildRings::new(total_vf, total_ve, cv);
    let mut vert_sharpness = unwritten(cv, f32::NAN);
    fill(&mut vert_sharpness[nv..], 0.0);
    let (vf_v, vf_e) = rings.vert_faces.split_at_mut(pvf);
    let (vl_v, vl_e) = rings.vert_face_local.split_at_mut(pvf);
    let (ve_v, ve_e) = rings.vert_edges.split_at_mut(pve);
    let (vt_v, vt_e) = rings.vert_tags.split_at_mut(nv);
    let (vr_v, vr_e) = rings.vert_rule.split_at_mut(nv);

    // Faces and edges: four child faces and three interior edges per parent face, two child
    // edges per parent edge. Sharpness: interior edges smooth (`ChildEdges` fills them),
    // children of edges decayed by the crease method (in the edge pass,
    // `level::child_halves`).
    let total_ef = 2 * nc + 2 * efo(ne);
    let mut tables = ChildEdges::new(4 * nc, nc, ce, total_ef);
    {
        let (ev_f, ev_e) = tables.edge_verts.split_at_mut(nc);
        let (eo_f, eo_e) = tables.edge_face_offsets.split_at_mut(nc);
        let (ef_f, ef_e) = tables.edge_faces.split_at_mut(2 * nc);
        let (el_f, el_e) = tables.edge_face_local.split_at_mut(2 * nc);
        fr.clone()
            .into_par_iter()
            .zip(par::split_exact(&mut tables.face_verts, &fb, |f| 12 * f))
            .zip(par::split_exact(&mut tables.face_edges, &fb, |f| 12 * f))
            .zip(par::split_exact(ev_f, &fb, |f| 3 * f))
            .zip(par::split_exact(eo_f, &fb, |f| 3 * f))
            .zip(par::split_exact(ef_f, &fb, |f| 6 * f))
            .zip(par::split_exact(el_f, &fb, |f| 6 * f))
            .for_each(|((((((r, cfv), cfe), cev), ceo), cef), cel)| {
                let base = r.start;
                for f in r {
                    let i = f - base;
                    let fv = &p.face_verts[3 * f..3 * f + 3];
                    let fe = &p.face_edges[3 * f..3 * f + 3];
                    let e = [ep(fe[0]), ep(fe[1]), ep(fe[2])];
                    put(&mut cfv[12 * i..12 * i + 12], &child_triangles(fv, e));
                    // pe[k] = [child of edge k at corner k, child at corner k + 1].
                    let pe: [[u32; 2]; 3] = std::array::from_fn(|k| {
                        let ev = p.edge_verts[fe[k] as usize];
                        let reversed = (fv[k] != ev[0]) as u32;
                        let c = (nc + 2 * fe[k] as usize) as u32;
                        [c + reversed, c + 1 - reversed]
                    });
                    let fc = (3 * f) as u32;
                    put(
                        &mut cfe[12 * i..12 * i + 12],
                        &[
                            pe[0][0],
                            fc,
                            pe[2][1],
                            pe[0][1],
                            pe[1][0],
                            fc + 1,
                            fc + 2,
                            pe[1][1],
                            pe[2][0],
                            fc + 2,
                            fc,
                            fc + 1,
                        ],
                    );
                    put(
                        &mut cev[3 * i..3 * i + 3],
                        &[[e[0], e[2]], [e[1], e[0]], [e[2], e[1]]],
                    );
                    let (o, c) = ((6 * f) as u32, (4 * f) as u32);
                    put(&mut ceo[3 * i..3 * i + 3], &[o, o + 2, o + 4]);
                    put(
                        &mut cef[6 * i..6 * i + 6],
                        &[c, c + 3, c + 1, c + 3, c + 2, c + 3],
                    );
                    put(&mut cel[6 * i..6 * i + 6], &[1, 1, 2, 2, 0, 0]);
                }
            });
        eo_e[2 * ne].set(total_ef as u32);
        // One pass per parent edge: its two child edges and its edge point (three faces per
        // incident face, the forward face (edge in its direction) first, so an interior ring
        // starts with the child at end 1).
        er.clone()
            .into_par_iter()
            .zip(par::split_exact(ev_e, &eb, |e| 2 * e))
            .zip(par::split_exact(&mut eo_e[..2 * ne], &eb, |e| 2 * e))
            .zip(par::split_exact(ef_e, &eb, |e| 2 * efo(e)))
            .zip(par::split_exact(el_e, &eb, |e| 2 * efo(e)))
            .zip(par::split_exact(
                &mut tables.edge_sharpness[nc..],
                &eb,
                |e| 2 * e,
            ))
            .zip(par::split_exact(&mut tables.edge_tags[nc..], &eb, |e| {
                2 * e
            }))
            .zip(par::split_exact(vf_e, &eb, |e| 3 * efo(e)))
            .zip(par::split_exact(vl_e, &eb, |e| 3 * efo(e)))
            .zip(par::split_exact(ve_e, &eb, |e| 2 * e + 2 * efo(e)))
            .zip(par::split_exact(vt_e, &eb, |e| e))
            .zip(par::split_exact(vr_e, &eb, |e| e))
            .for_each(
                |(((((((((((r, cev), ceo), cef), cel), ces), cet), cvf), cvl), cve), cvt), cvr)| {
                    let (base, fbase) = (2 * r.start, 2 * efo(r.start));
                    let (vfbase, vebase) = (3 * efo(r.start), 2 * r.start + 2 * efo(r.start));
                    let mut around: Vec<f32> = Vec::new();
                    for e in r.clone() {
                        let ev = p.edge_verts[e];
                        let i = 2 * e - base;
                        let et = p.edge_tags[e];
                        let [(s0, t0), (s1, t1)] = child_halves(p, e, &mut around);
                        put(&mut ces[i..], &[s0, s1]);
                        put(&mut cet[i..], &[t0, t1]);
                        cev[i].set([ep(e as u32), ev[0]]);
                        cev[i + 1].set([ep(e as u32), ev[1]]);
                        let (faces, locals) = (p.edge_faces(e), p.edge_faces_local(e));
                        let k = faces.len();
                        // Whether each face runs along the edge's direction.
                        let forward: [bool; 2] = std::array::from_fn(|j| {
                            j < k && {
                                let (f, kl) = (faces[j] as usize, locals[j] as usize);
                                p.face_verts[3 * f + kl] == ev[0]
                            }
                        });
                        let s = 2 * efo(e);
                        ceo[i].set((2 * nc + s) as u32);
                        ceo[i + 1].set((2 * nc + s + k) as u32);
                        let o = s - fbase;
                        // The child edges' faces in increasing face order.
                        let order = if k == 2 && faces[1] < faces[0] {
                            [1, 0]
                        } else {
                            [0, 1]
                        };
                        // Per slot, the child at the face's first corner along the edge
                        // takes corner child `kl`, the other corner child `kl + 1`; both see
                        // the edge as the face's edge `kl`. Formed in registers and written in
                        // order (no store address waits on the orientation read).
                        let (mut child, mut local) = ([[0u32; 2]; 2], [0u16; 2]);
                        for (slot, &j) in order[..k].iter().enumerate() {
                            let (f, kl) = (faces[j], locals[j]);
                            let (x, y) = (4 * f + kl as u32, 4 * f + (kl as u32 + 1) % 3);
                            let (c0, c1) = if forward[j] { (x, y) } else { (y, x) };
                            (child[0][slot], child[1][slot], local[slot]) = (c0, c1, kl);
                        }
                        // Written with their length known (one face or two), so no copy
                        // of a variable length (a `memcpy` call each) is made.
                        if k == 2 {
                            put(
                                &mut cef[o..],
                                &[child[0][0], child[0][1], child[1][0], child[1][1]],
                            );
                            put(&mut cel[o..], &[local[0], local[1], local[0], local[1]]);
                        } else {
                            put(&mut cef[o..], &[child[0][0], child[1][0]]);
                            put(&mut cel[o..], &[local[0], local[0]]);
                        }
                        // The edge point's rings, the forward face first.
                        let ring = if k == 2 && !forward[0] {
                            [1, 0]
                        } else {
                            [0, 1]
                        };
                        let c0 = (nc + 2 * e) as u32;
                        let (mut of, mut oe) = (3 * efo(e) - vfbase, 2 * e + 2 * efo(e) - vebase);
                        for &j in &ring[..k] {
                            let f = faces[j];
                            let kl = locals[j] as u32;
                            let (k1, k2) = ((kl + 1) % 3, (kl + 2) % 3);
                            put(&mut cvf[of..of + 3], &[4 * f + k1, 4 * f + 3, 4 * f + kl]);
                            put(&mut cvl[of..of + 3], &[kl as u16, k2 as u16, k1 as u16]);
                            of += 3;
                            // The child at corner kl + 1 of this face: end 1 where the face
                            // runs forward.
                            let (far, near) = if forward[j] {
                                (c0 + 1, c0)
                            } else {
                                (c0, c0 + 1)
                            };
                            put(&mut cve[oe..oe + 3], &[far, 3 * f + k1, 3 * f + kl]);
                            oe += 3;
                            if k == 1 {
                                cve[oe].set(near);
                                oe += 1;
                            }
                        }
                        let (mut t, rl) = edge_point_tags(et, t0, t1);
                        if et & tags::E_BOUNDARY != 0 {
                            t |= tags::V_BOUNDARY;
                        }
                        cvt[e - r.start].set(t);
                        cvr[e - r.start].set(rl);
                    }
                },
            );
    }
    // SAFETY: the face and edge passes cover these tables whole (`split_exact`; the interior
    // edges' sharpness and tags filled by `ChildEdges::new`, the offsets' last value above):
    // each parent face writes its 12 child face vertices and edges, its three interior edges'
    // ends, offsets and two faces each; each parent edge its two children's ends, offsets,
    // sharpness, tags and `k` faces each.
    let edges = unsafe { tables.written() };

    // Children of vertices: the parent's rings, face by face and edge by edge; tags and rules
    // inherited, recounted where semi-sharp features decayed.
    let pvfo = |v: usize| p.vert_face_offsets[v] as usize;
    let pveo = |v: usize| p.vert_edge_offsets[v] as usize;
    let etags = &edges.edge_tags;
    vr.into_par_iter()
        .zip(par::split_exact(vf_v, &vb, pvfo))
        .zip(par::split_exact(vl_v, &vb, pvfo))
        .zip(par::split_exact(ve_v, &vb, pveo))
        .zip(par::split_exact(&mut vert_sharpness[..nv], &vb, |v| v))
        .zip(par::split_exact(vt_v, &vb, |v| v))
        .zip(par::split_exact(vr_v, &vb, |v| v))
        .for_each(|((((((r, cvf), cvl), cve), cvs), cvt), cvr)| {
            let (fbase, ebase, base) = (pvfo(r.start), pveo(r.start), r.start);
            for v in r {
                let (a, b) = (pvfo(v), pvfo(v + 1));
                let ring = cvf[a - fbase..b - fbase]
                    .iter_mut()
                    .zip(&mut cvl[a - fbase..b - fbase])
                    .zip(&p.vert_faces[a..b])
                    .zip(&p.vert_face_local[a..b]);
                for (((cf, cl), &f), &k) in ring {
                    cf.set(4 * f + k as u32);
                    cl.set(k);
                }
                let (mut inf, mut semi) = (0usize, 0usize);
                let out = &mut cve[pveo(v) - ebase..pveo(v + 1) - ebase];
                for (&e, o) in p.vertex_edges(v).iter().zip(out) {
                    let end = (p.edge_verts[e as usize][0] != v as u32) as u32;
                    let c = (nc + 2 * e as usize) as u32 + end;
                    o.set(c);
                    let et = etags[c as usize];
                    inf += (et & tags::E_INF_SHARP != 0) as usize;
                    semi += (et & tags::E_SEMI_SHARP != 0) as usize;
                }
                let s = crease::decrement(p.vert_sharpness[v]);
                let (t, rl) = vertex_child_tags(p, v, s, inf, semi);
                cvs[v - base].set(s);
                cvt[v - base].set(t & !tags::V_INCIDENT_HOLE);
                cvr[v - base].set(rl);
            }
        });

    // SAFETY: the edge pass and the vertex pass cover these tables whole (`split_exact`; the
    // edge points' sharpness filled before): each child of a vertex writes its parent's rings,
    // sharpness, tags and rule, each edge point its `3k` faces, `2 + 2k` edges, tags and rule.
    let (mut rings, vert_sharpness) = unsafe { (rings.written(), written(vert_sharpness)) };
    let face_is_hole = super::loop_level::child_holes(
        &p.face_is_hole,
        &edges.face_verts,
        Some(&mut rings.vert_tags),
    );

    assemble(
        p,
        cv,
        iota(cf + 1, |f| 3 * f as u32),
        edges,
        vert_face_offsets,
        vert_edge_offsets,
        rings,
        vert_sharpness,
        face_is_hole,
    )
}
