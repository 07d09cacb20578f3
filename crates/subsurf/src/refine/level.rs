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
use super::alloc::{self, put, unwritten, written, Slot};
use crate::options::CreaseMethod;
use crate::rules::crease;
use crate::util::par;
use crate::SHARPNESS_INFINITE;
use rayon::prelude::*;
use std::mem::MaybeUninit;

/// How a child level's tables are held: [`Unwritten`] while a step's passes fill them,
/// [`Written`] once every value is.
pub(super) trait Form {
    type Of<T>;
}

/// Tables allocated unwritten ([`alloc::unwritten`]).
pub(super) struct Unwritten;

/// Tables whose every value is written.
pub(super) struct Written;

impl Form for Unwritten {
    type Of<T> = Box<[MaybeUninit<T>]>;
}

impl Form for Written {
    type Of<T> = Vec<T>;
}

/// The face and edge tables of a child level, laid out alike by the quad and the triangle
/// (Loop) split: the child edges of faces first (`interior` of them, smooth: their sharpness
/// and tags are filled by [`ChildEdges::new`]), then two children per parent edge.
pub(super) struct ChildEdges<F: Form = Unwritten> {
    pub(super) face_verts: F::Of<u32>,
    pub(super) face_edges: F::Of<u32>,
    pub(super) edge_verts: F::Of<[u32; 2]>,
    pub(super) edge_face_offsets: F::Of<u32>,
    pub(super) edge_faces: F::Of<u32>,
    pub(super) edge_face_local: F::Of<u16>,
    pub(super) edge_sharpness: F::Of<f32>,
    pub(super) edge_tags: F::Of<u8>,
}

impl ChildEdges {
    /// Tables of `face_values` face vertices (and as many face edges), `edges` child edges of
    /// which the first `interior` are children of faces, and `edge_faces` edge-face incidences,
    /// for a step's face and edge passes to fill.
    pub(super) fn new(
        face_values: usize,
        interior: usize,
        edges: usize,
        edge_faces: usize,
    ) -> Self {
        let mut t: Self = ChildEdges {
            face_verts: unwritten(face_values, u32::MAX),
            face_edges: unwritten(face_values, u32::MAX),
            edge_verts: unwritten(edges, [u32::MAX; 2]),
            edge_face_offsets: unwritten(edges + 1, u32::MAX),
            edge_faces: unwritten(edge_faces, u32::MAX),
            edge_face_local: unwritten(edge_faces, u16::MAX),
            edge_sharpness: unwritten(edges, f32::NAN),
            edge_tags: unwritten(edges, u8::MAX),
        };
        alloc::fill(&mut t.edge_sharpness[..interior], 0.0);
        alloc::fill(&mut t.edge_tags[..interior], 0);
        t
    }

    /// The tables as `Vec`s.
    ///
    /// # Safety
    /// Every value of every table has been written.
    #[allow(unsafe_code)]
    pub(super) unsafe fn written(self) -> ChildEdges<Written> {
        // SAFETY: every value written (the caller's promise).
        unsafe {
            ChildEdges {
                face_verts: written(self.face_verts),
                face_edges: written(self.face_edges),
                edge_verts: written(self.edge_verts),
                edge_face_offsets: written(self.edge_face_offsets),
                edge_faces: written(self.edge_faces),
                edge_face_local: written(self.edge_face_local),
                edge_sharpness: written(self.edge_sharpness),
                edge_tags: written(self.edge_tags),
            }
        }
    }
}

/// The vertex tables of a child level (rings, tags, rules).
pub(super) struct ChildRings<F: Form = Unwritten> {
    pub(super) vert_faces: F::Of<u32>,
    pub(super) vert_face_local: F::Of<u16>,
    pub(super) vert_edges: F::Of<u32>,
    pub(super) vert_tags: F::Of<u16>,
    pub(super) vert_rule: F::Of<u8>,
}

impl ChildRings {
    /// Tables of `faces` vertex-face and `edges` vertex-edge incidences of `vertices` vertices,
    /// for a step's vertex passes to fill.
    pub(super) fn new(faces: usize, edges: usize, vertices: usize) -> Self {
        ChildRings {
            vert_faces: unwritten(faces, u32::MAX),
            vert_face_local: unwritten(faces, u16::MAX),
            vert_edges: unwritten(edges, u32::MAX),
            vert_tags: unwritten(vertices, u16::MAX),
            vert_rule: unwritten(vertices, u8::MAX),
        }
    }

    /// The tables as `Vec`s.
    ///
    /// # Safety
    /// Every value of every table has been written.
    #[allow(unsafe_code)]
    pub(super) unsafe fn written(self) -> ChildRings<Written> {
        // SAFETY: every value written (the caller's promise).
        unsafe {
            ChildRings {
                vert_faces: written(self.vert_faces),
                vert_face_local: written(self.vert_face_local),
                vert_edges: written(self.vert_edges),
                vert_tags: written(self.vert_tags),
                vert_rule: written(self.vert_rule),
            }
        }
    }
}

/// A child level of `p` from its parts: its face and edge tables, its vertex rings, tags and
/// rules, and the rest.
#[allow(clippy::too_many_arguments)]
pub(super) fn assemble(
    p: &Topology,
    num_vertices: usize,
    face_offsets: Vec<u32>,
    edges: ChildEdges<Written>,
    vert_face_offsets: Vec<u32>,
    vert_edge_offsets: Vec<u32>,
    rings: ChildRings<Written>,
    vert_sharpness: Vec<f32>,
    face_is_hole: Vec<bool>,
) -> Topology {
    Topology {
        options: p.options,
        num_vertices,
        face_offsets,
        face_verts: edges.face_verts,
        face_edges: edges.face_edges,
        edge_verts: edges.edge_verts,
        edge_face_offsets: edges.edge_face_offsets,
        edge_faces: edges.edge_faces,
        edge_face_local: edges.edge_face_local,
        vert_face_offsets,
        vert_faces: rings.vert_faces,
        vert_face_local: rings.vert_face_local,
        vert_edge_offsets,
        vert_edges: rings.vert_edges,
        edge_sharpness: edges.edge_sharpness,
        vert_sharpness,
        face_is_hole,
        edge_tags: edges.edge_tags,
        vert_tags: rings.vert_tags,
        vert_rule: rings.vert_rule,
    }
}

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
///
/// Every child table is filled in place: its row starts follow from the parent's offsets
/// (a child of a vertex has the parent vertex's ring sizes, a face point as many faces and
/// edges as its face has corners, an edge point `2k` faces and `2 + k` edges for `k` incident
/// faces), so each table is allocated once at its exact size, unwritten (no zero pass), and
/// filled in parallel chunks that cover it whole, each row writing every value of its own.
#[allow(unsafe_code)]
pub fn refine_topology(p: &Topology) -> Topology {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let echild = |e: usize| (nv + nf + e) as u32;
    let cv = nv + nf + ne;
    let (cf, ce) = (nc, nc + 2 * ne);
    let fo = |f: usize| p.face_offsets[f] as usize;
    let efo = |e: usize| p.edge_face_offsets[e] as usize;
    let (fb, eb, vb) = (par::bounds(nf), par::bounds(ne), par::bounds(nv));
    let (fr, er, vr) = (par::ranges(&fb), par::ranges(&eb), par::ranges(&vb));

    // Faces: vertices and edges.
    let face_offsets = iota(cf + 1, |i| 4 * i as u32);
    let total_ef = 2 * nc + 2 * efo(ne);
    let mut tables = ChildEdges::new(4 * cf, nc, ce, total_ef);
    fr.clone()
        .into_par_iter()
        .zip(par::split_exact(&mut tables.face_verts, &fb, |f| 4 * fo(f)))
        .zip(par::split_exact(&mut tables.face_edges, &fb, |f| 4 * fo(f)))
        .zip(par::split_exact(&mut tables.edge_verts[..nc], &fb, fo))
        .for_each(|(((r, cfv), cfe), cev)| {
            let base = fo(r.start);
            for f in r {
                let (s, n) = (fo(f), fo(f + 1) - fo(f));
                // The same code with n = 4 known (quads, nearly every face after one step)
                // unrolls and folds the corner positions.
                let out = (&mut *cfv, &mut *cfe, &mut *cev);
                if n == 4 {
                    face_children(p, f, s, 4, base, out);
                } else {
                    face_children(p, f, s, n, base, out);
                }
            }
        });

    // Vertices: offsets. Children of vertices keep the parent's ring sizes.
    let (vf0, ve0) = (
        p.vert_face_offsets[nv] as usize,
        p.vert_edge_offsets[nv] as usize,
    );
    let vert_face_offsets =
        child_vertex_offsets(p, &p.vert_face_offsets, vf0 + nc, |e| vf0 + nc + 2 * efo(e));
    let vert_edge_offsets = child_vertex_offsets(p, &p.vert_edge_offsets, ve0 + nc, |e| {
        ve0 + nc + 2 * e + efo(e)
    });
    let total_vf = vf0 + nc + 2 * efo(ne);
    let total_ve = ve0 + nc + 2 * ne + efo(ne);
    let mut rings = ChildRings::new(total_vf, total_ve, cv);
    let (vf_v, vf_rest) = rings.vert_faces.split_at_mut(vf0);
    let (vf_f, vf_e) = vf_rest.split_at_mut(nc);
    let (vl_v, vl_rest) = rings.vert_face_local.split_at_mut(vf0);
    let (vl_f, vl_e) = vl_rest.split_at_mut(nc);
    let (ve_v, ve_rest) = rings.vert_edges.split_at_mut(ve0);
    let (ve_f, ve_e) = ve_rest.split_at_mut(nc);
    let (vt_v, vt_rest) = rings.vert_tags.split_at_mut(nv);
    let (vt_f, vt_e) = vt_rest.split_at_mut(nf);
    let (vr_v, vr_rest) = rings.vert_rule.split_at_mut(nv);
    let (vr_f, vr_e) = vr_rest.split_at_mut(nf);

    // Edges: vertices and incident faces. Child edges of faces have two faces each; the two
    // children of parent edge e have as many as e.
    {
        let (efo_f, efo_e) = tables.edge_face_offsets.split_at_mut(nc + 1);
        efo_f
            .par_chunks_mut(1 << 14)
            .enumerate()
            .for_each(|(c, o)| {
                for (i, x) in o.iter_mut().enumerate() {
                    x.set(2 * ((c << 14) + i) as u32);
                }
            });
        let (ef_f, ef_e) = tables.edge_faces.split_at_mut(2 * nc);
        let (el_f, el_e) = tables.edge_face_local.split_at_mut(2 * nc);
        fr.clone()
            .into_par_iter()
            .zip(par::split_exact(ef_f, &fb, |f| 2 * fo(f)))
            .zip(par::split_exact(el_f, &fb, |f| 2 * fo(f)))
            .for_each(|((r, ef), el)| {
                let base = 2 * fo(r.start);
                for f in r {
                    let (s, n) = (fo(f), fo(f + 1) - fo(f));
                    let o = 2 * s - base;
                    let out = (&mut ef[o..o + 2 * n], &mut el[o..o + 2 * n]);
                    if n == 4 {
                        face_child_edge_faces(s, 4, out);
                    } else {
                        face_child_edge_faces(s, n, out);
                    }
                }
            });
        let (_, ev_e) = tables.edge_verts.split_at_mut(nc);
        let (es_e, et_e) = (
            &mut tables.edge_sharpness[nc..],
            &mut tables.edge_tags[nc..],
        );
        // One pass per parent edge: its two children (ends, offsets, faces, sharpness and
        // tags, decayed by the crease method) and its edge point (rings, tags, rule; only its
        // two child edges can be sharp).
        er.clone()
            .into_par_iter()
            .zip(par::split_exact(ev_e, &eb, |e| 2 * e))
            .zip(par::split_exact(efo_e, &eb, |e| 2 * e))
            .zip(par::split_exact(ef_e, &eb, |e| 2 * efo(e)))
            .zip(par::split_exact(el_e, &eb, |e| 2 * efo(e)))
            .zip(par::split_exact(es_e, &eb, |e| 2 * e))
            .zip(par::split_exact(et_e, &eb, |e| 2 * e))
            .zip(par::split_exact(vf_e, &eb, |e| 2 * efo(e)))
            .zip(par::split_exact(vl_e, &eb, |e| 2 * efo(e)))
            .zip(par::split_exact(ve_e, &eb, |e| 2 * e + efo(e)))
            .zip(par::split_exact(vt_e, &eb, |e| e))
            .zip(par::split_exact(vr_e, &eb, |e| e))
            .for_each(
                |(((((((((((r, cev), co), ef), el), ces), cet), vf), vl), ve), vt), vru)| {
                    let (ebase, fbase) = (2 * r.start, 2 * efo(r.start));
                    let (vebase, base) = (2 * r.start + efo(r.start), r.start);
                    let mut around: Vec<f32> = Vec::new();
                    for e in r {
                        let ev = p.edge_verts[e];
                        let i = 2 * e - ebase;
                        let [(s0, t0), (s1, t1)] = child_halves(p, e, &mut around);
                        put(&mut ces[i..], &[s0, s1]);
                        put(&mut cet[i..], &[t0, t1]);
                        cev[i].set([echild(e), ev[0]]);
                        cev[i + 1].set([echild(e), ev[1]]);
                        let k = efo(e + 1) - efo(e);
                        co[i].set((2 * nc + 2 * efo(e) + k) as u32);
                        co[i + 1].set((2 * nc + 2 * efo(e + 1)) as u32);
                        let mut fill = [2 * efo(e) - fbase, 2 * efo(e) + k - fbase];
                        let faces = p.edge_faces(e).iter().zip(p.edge_faces_local(e));
                        for (slot, (&f, &k)) in faces.enumerate() {
                            let (s, n) = (fo(f as usize), p.face_size(f as usize));
                            let k = k as usize;
                            let kn = if k + 1 == n { 0 } else { k + 1 };
                            let end = child_end(ev, p.face_verts[s + k], true) as usize;
                            let at = ((s + k) as u32, pos(n, k, 0));
                            // Corner `kn` is the edge's other end (`child_end` of it, unread).
                            let next = ((s + kn) as u32, pos(n, kn, 3));
                            if ev[0] != ev[1] {
                                // Each face meets both ends once: child `c` takes the face's
                                // entry at slot `slot` of its list, whichever corner it is (no
                                // store address waits on the orientation read).
                                let [c0, c1] = if end == 0 { [at, next] } else { [next, at] };
                                for (c, (x, l)) in [c0, c1].into_iter().enumerate() {
                                    ef[fill[c] + slot].set(x);
                                    el[fill[c] + slot].set(l);
                                }
                            } else {
                                for ((x, l), end) in [(at, end), (next, 1)] {
                                    ef[fill[end]].set(x);
                                    el[fill[end]].set(l);
                                    fill[end] += 1;
                                }
                            }
                        }
                        let of = 2 * efo(e) - fbase;
                        let oe = 2 * e + efo(e) - vebase;
                        let (t, rl) = edge_point_ring(
                            p,
                            e,
                            &mut vf[of..],
                            &mut vl[of..],
                            &mut ve[oe..],
                            (t0, t1),
                        );
                        vt[e - base].set(t);
                        vru[e - base].set(rl);
                    }
                },
            );
    }
    // SAFETY: the face and edge passes above cover these tables whole (`split_exact`), each
    // parent face writing its corners' four child face vertices and edges (every slot of a
    // quad's rotation), its child edges' ends and two faces, and each parent edge its two
    // children's ends, offsets, `k` faces, sharpness and tags each.
    let edges = unsafe { tables.written() };

    // Sharpness: children of vertices decayed in the vertex pass, face and edge points smooth.
    let mut vert_sharpness = unwritten(cv, f32::NAN);
    alloc::fill(&mut vert_sharpness[nv..], 0.0);

    // Children of vertices: rings mapped to the children of the ring's faces and edges; tags
    // and rules inherited, recounted where semi-sharp features decayed.
    let pvfo = |v: usize| p.vert_face_offsets[v] as usize;
    let pveo = |v: usize| p.vert_edge_offsets[v] as usize;
    vr.clone()
        .into_par_iter()
        .zip(par::split_exact(vf_v, &vb, pvfo))
        .zip(par::split_exact(vl_v, &vb, pvfo))
        .zip(par::split_exact(ve_v, &vb, pveo))
        .zip(par::split_exact(&mut vert_sharpness[..nv], &vb, |v| v))
        .zip(par::split_exact(vt_v, &vb, |v| v))
        .zip(par::split_exact(vr_v, &vb, |v| v))
        .for_each(|((((((r, vf), vl), ve), vs), vt), vru)| {
            let (fbase, ebase, vbase) = (pvfo(r.start), pveo(r.start), r.start);
            for v in r {
                let (a, b) = (pvfo(v), pvfo(v + 1));
                let ring = vf[a - fbase..b - fbase]
                    .iter_mut()
                    .zip(&mut vl[a - fbase..b - fbase])
                    .zip(&p.vert_faces[a..b])
                    .zip(&p.vert_face_local[a..b]);
                for (((cf, cl), &f), &k) in ring {
                    let (f, k) = (f as usize, k as usize);
                    let s = fo(f);
                    cf.set((s + k) as u32);
                    cl.set(pos(fo(f + 1) - s, k, 0));
                }
                let pe = p.vertex_edges(v);
                let (mut inf, mut semi) = (0usize, 0usize);
                let out = &mut ve[pveo(v) - ebase..pveo(v + 1) - ebase];
                for (i, (&e, o)) in pe.iter().zip(out).enumerate() {
                    let ce = (nc + 2 * e as usize) as u32 + child_end_at_vertex(p, pe, i, v);
                    o.set(ce);
                    let et = edges.edge_tags[ce as usize];
                    inf += (et & tags::E_INF_SHARP != 0) as usize;
                    semi += (et & tags::E_SEMI_SHARP != 0) as usize;
                }
                let s = crease::decrement(p.vert_sharpness[v]);
                let (t, rl) = vertex_child_tags(p, v, s, inf, semi);
                vs[v - vbase].set(s);
                vt[v - vbase].set(t);
                vru[v - vbase].set(rl);
            }
        });

    // Face points: smooth, no sharp edges.
    fr.clone()
        .into_par_iter()
        .zip(par::split_exact(vf_f, &fb, fo))
        .zip(par::split_exact(vl_f, &fb, fo))
        .zip(par::split_exact(ve_f, &fb, fo))
        .zip(par::split_exact(vt_f, &fb, |f| f))
        .zip(par::split_exact(vr_f, &fb, |f| f))
        .for_each(|(((((r, vf), vl), ve), vt), vru)| {
            let (base, fbase) = (fo(r.start), r.start);
            for f in r {
                let (s, n) = (fo(f), fo(f + 1) - fo(f));
                let o = s - base..s + n - base;
                let out = (&mut vf[o.clone()], &mut vl[o.clone()], &mut ve[o]);
                if n == 4 {
                    face_point_ring(s, 4, out);
                } else {
                    face_point_ring(s, n, out);
                }
                vt[f - fbase].set(if n != 4 { tags::V_XORDINARY } else { 0 });
                vru[f - fbase].set(rule::SMOOTH);
            }
        });

    // SAFETY: the vertex and face-point passes above and the edge pass cover these tables
    // whole (`split_exact`), each child vertex writing its whole ring (a vertex's parent ring
    // sizes, a face point's `n`, an edge point's `2k` faces and `2 + k` edges), its tags and
    // its rule; each child of a vertex its sharpness (the face and edge points' filled above).
    let (mut rings, vert_sharpness) = unsafe { (rings.written(), written(vert_sharpness)) };

    let mut face_is_hole = super::alloc::zeroed(nc, false);
    if p.face_is_hole.iter().any(|&h| h) {
        for f in 0..nf {
            if p.face_is_hole[f] {
                face_is_hole[fo(f)..fo(f + 1)].fill(true);
                for i in fo(f)..fo(f + 1) {
                    for &v in &edges.face_verts[4 * i..4 * i + 4] {
                        rings.vert_tags[v as usize] |= tags::V_INCIDENT_HOLE;
                    }
                }
            }
        }
    }

    assemble(
        p,
        cv,
        face_offsets,
        edges,
        vert_face_offsets,
        vert_edge_offsets,
        rings,
        vert_sharpness,
        face_is_hole,
    )
}

/// Child face vertices and edges of parent face `f` (corners `s..s + n`), and the child
/// edges from its face point, into chunk slices starting at corner `base`.
#[inline(always)]
fn face_children(
    p: &Topology,
    f: usize,
    s: usize,
    n: usize,
    base: usize,
    (cfv, cfe, cev): (
        &mut [impl Slot<u32>],
        &mut [impl Slot<u32>],
        &mut [impl Slot<[u32; 2]>],
    ),
) {
    let (nv, nf, nc) = (p.num_vertices(), p.num_faces(), p.num_corners());
    let fchild = (nv + f) as u32;
    let echild = |e: u32| (nv + nf) as u32 + e;
    let fv = &p.face_verts[s..s + n];
    let fe = &p.face_edges[s..s + n];
    // Which child of face edge j touches corner j (the other touches corner j+1).
    let end_at = |j: usize| child_end(p.edge_verts[fe[j] as usize], fv[j], true);
    let last = end_at(n - 1);
    let mut prev = last;
    for j in 0..n {
        let jp = if j == 0 { n - 1 } else { j - 1 };
        let a = if j + 1 == n { last } else { end_at(j) };
        let c = 4 * (s + j - base);
        let q = |slot| c + pos(n, j, slot) as usize;
        cfv[q(0)].set(fv[j]);
        cfv[q(1)].set(echild(fe[j]));
        cfv[q(2)].set(fchild);
        cfv[q(3)].set(echild(fe[jp]));
        cfe[q(0)].set((nc + 2 * fe[j] as usize) as u32 + a);
        cfe[q(1)].set((s + j) as u32);
        cfe[q(2)].set((s + jp) as u32);
        cfe[q(3)].set((nc + 2 * fe[jp] as usize) as u32 + (1 - prev));
        cev[s + j - base].set([fchild, echild(fe[j])]);
        prev = a;
    }
}

/// The two faces of each child edge from the face point of a parent face (corners `s..s + n`):
/// child faces `j` and `j + 1`, into `ef`/`el` (two entries per corner).
#[inline(always)]
fn face_child_edge_faces(
    s: usize,
    n: usize,
    (ef, el): (&mut [impl Slot<u32>], &mut [impl Slot<u16>]),
) {
    for (j, (ef, el)) in ef
        .chunks_exact_mut(2)
        .zip(el.chunks_exact_mut(2))
        .enumerate()
        .take(n)
    {
        let jn = if j + 1 == n { 0 } else { j + 1 };
        ef[0].set((s + j) as u32);
        el[0].set(pos(n, j, 1));
        ef[1].set((s + jn) as u32);
        el[1].set(pos(n, jn, 2));
    }
}

/// The ring of the face point of a parent face (corners `s..s + n`): its child faces, its
/// corner in each, and its child edges (one per corner, shifted by one).
#[inline(always)]
fn face_point_ring(
    s: usize,
    n: usize,
    (vf, vl, ve): (
        &mut [impl Slot<u32>],
        &mut [impl Slot<u16>],
        &mut [impl Slot<u32>],
    ),
) {
    for (j, ((vf, vl), ve)) in vf
        .iter_mut()
        .zip(vl.iter_mut())
        .zip(ve.iter_mut())
        .enumerate()
        .take(n)
    {
        vf.set((s + j) as u32);
        vl.set(pos(n, j, 2));
        ve.set((s + if j == 0 { n - 1 } else { j - 1 }) as u32);
    }
}

/// `(0..len).map(f)`, filled in parallel.
#[allow(unsafe_code)]
pub(super) fn iota(len: usize, f: impl Fn(usize) -> u32 + Sync) -> Vec<u32> {
    let mut out = unwritten(len, u32::MAX);
    out.par_chunks_mut(1 << 14).enumerate().for_each(|(c, o)| {
        for (i, x) in o.iter_mut().enumerate() {
            x.write(f((c << 14) + i));
        }
    });
    // SAFETY: the chunks cover `out`, every value of each written.
    unsafe { written(out) }
}

/// Offsets of a child vertex table: the parent's for children of vertices, then `face_start +
/// face_offsets[f]` for face points, then `edge_start(e)` for edge points (`e` in `0..=E`).
#[allow(unsafe_code)]
fn child_vertex_offsets(
    p: &Topology,
    parent: &[u32],
    face_start: usize,
    edge_start: impl Fn(usize) -> usize + Sync,
) -> Vec<u32> {
    let (nv, nf, ne) = (p.num_vertices(), p.num_faces(), p.num_edges());
    let mut out = unwritten(nv + nf + ne + 1, u32::MAX);
    let (a, rest) = out.split_at_mut(nv);
    let (b, c) = rest.split_at_mut(nf);
    put(a, &parent[..nv]);
    let f0 = face_start - p.num_corners();
    b.par_iter_mut()
        .zip(&p.face_offsets[..nf])
        .with_min_len(4096)
        .for_each(|(x, &o)| x.set((f0 + o as usize) as u32));
    c.par_iter_mut()
        .enumerate()
        .with_min_len(4096)
        .for_each(|(e, x)| x.set(edge_start(e) as u32));
    // SAFETY: the three parts written whole above (`c` holds `ne + 1` values).
    unsafe { written(out) }
}

/// Writes the ring of the edge point of parent edge `e` (faces, their local corners, edges)
/// and returns its tags and rule.
fn edge_point_ring(
    p: &Topology,
    e: usize,
    vf: &mut [impl Slot<u32>],
    vl: &mut [impl Slot<u16>],
    ve: &mut [impl Slot<u32>],
    (t0, t1): (u8, u8),
) -> (u16, u8) {
    let nc = p.num_corners();
    let ev = p.edge_verts[e];
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
        // Both corners read before the orientation picks their order (no load address waits
        // on the orientation read).
        let (first, second) = (corner(0), corner(1));
        let ((sa, na, ka, kan), (sb, nb, kb, kbn)) = if forward(0) {
            (first, second)
        } else {
            (second, first)
        };
        put(
            vf,
            &[
                (sa + kan) as u32,
                (sa + ka) as u32,
                (sb + kbn) as u32,
                (sb + kb) as u32,
            ],
        );
        put(
            vl,
            &[
                pos(na, kan, 3),
                pos(na, ka, 1),
                pos(nb, kbn, 3),
                pos(nb, kb, 1),
            ],
        );
        put(ve, &[c1, (sa + ka) as u32, c0, (sb + kb) as u32]);
    } else if manifold && faces.len() == 1 {
        let (s, n, k, kn) = corner(0);
        put(vf, &[(s + kn) as u32, (s + k) as u32]);
        put(vl, &[pos(n, kn, 3), pos(n, k, 1)]);
        let (first, last) = if forward(0) { (c1, c0) } else { (c0, c1) };
        put(ve, &[first, (s + k) as u32, last]);
    } else {
        vt |= tags::V_NON_MANIFOLD;
        ve[0].set(c0);
        ve[1].set(c1);
        for i in 0..faces.len() {
            let (s, n, k, kn) = corner(i);
            vf[2 * i].set((s + k) as u32);
            vl[2 * i].set(pos(n, k, 1));
            vf[2 * i + 1].set((s + kn) as u32);
            vl[2 * i + 1].set(pos(n, kn, 3));
            ve[2 + i].set((s + k) as u32);
        }
    }
    if et & tags::E_NON_MANIFOLD != 0 {
        vt |= tags::V_NON_MANIFOLD;
    }
    let (t, rl) = edge_point_tags(et, t0, t1);
    (vt | t, rl)
}

/// Sharpness and tags of the two children of every parent edge (`es`, `et`: two entries per
/// parent edge, child `2e + end` touching end `end`), decayed by the crease method.
pub(super) fn child_edge_sharpness(
    p: &Topology,
    es: &mut [impl Slot<f32>],
    et: &mut [impl Slot<u8>],
) {
    let eb = par::bounds(p.num_edges());
    par::ranges(&eb)
        .into_par_iter()
        .zip(par::split_exact(es, &eb, |e| 2 * e))
        .zip(par::split_exact(et, &eb, |e| 2 * e))
        .for_each(|((r, es), et_out)| {
            let base = 2 * r.start;
            let mut around: Vec<f32> = Vec::new();
            for e in r {
                let o = 2 * e - base;
                let [(s0, t0), (s1, t1)] = child_halves(p, e, &mut around);
                put(&mut es[o..], &[s0, s1]);
                put(&mut et_out[o..], &[t0, t1]);
            }
        });
}

/// Sharpness and tag of both children of parent edge `e` (`around`: scratch): a smooth edge's
/// (most edges) inline, without [`child_half`]'s call.
#[inline(always)]
pub(super) fn child_halves(p: &Topology, e: usize, around: &mut Vec<f32>) -> [(f32, u8); 2] {
    let s = p.edge_sharpness[e];
    if s <= 0.0 || s.is_nan() {
        let t = p.edge_tags[e] & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD);
        return [(0.0, t); 2];
    }
    let first = child_half(p, e, 0, around);
    [first, child_half(p, e, 1, around)]
}

/// Sharpness and tag of child `end` of parent edge `e` (`around`: scratch).
#[inline]
pub(super) fn child_half(p: &Topology, e: usize, end: usize, around: &mut Vec<f32>) -> (f32, u8) {
    let s = p.edge_sharpness[e];
    let et = p.edge_tags[e] & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD);
    if s <= 0.0 || s.is_nan() {
        // Smooth: both children smooth (what the rules below give).
        return (0.0, et);
    }
    let method = p.options.crease_method;
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
            crease::subdivide_edge_sharpness_at_vertex(method, s, around)
        }
    } else {
        0.0
    };
    (cs, et | sharp_tag(cs))
}

/// Which child (0 or 1) of `pe[i]`, the `i`-th edge of parent vertex `v`, touches the child
/// of `v` (a degenerate edge (v, v) is met twice in a row: first by its end 0, then end 1).
#[inline]
pub(super) fn child_end_at_vertex(p: &Topology, pe: &[u32], i: usize, v: usize) -> u32 {
    let e = pe[i];
    let ev = p.edge_verts[e as usize];
    if ev[0] != ev[1] {
        (ev[0] != v as u32) as u32
    } else {
        (i > 0 && pe[i - 1] == e) as u32
    }
}

/// Tags and rule of the child of parent vertex `v`, of sharpness `s`, with `inf` infinitely
/// sharp and `semi` semi-sharp child edges: inherited, recounted where semi-sharp features
/// decayed.
pub(super) fn vertex_child_tags(
    p: &Topology,
    v: usize,
    s: f32,
    inf: usize,
    semi: usize,
) -> (u16, u8) {
    let pt = p.vert_tags[v];
    let t = (pt
        & !(tags::V_SEMI_SHARP
            | tags::V_INF_SHARP
            | tags::V_SEMI_SHARP_EDGES
            | tags::V_INF_SHARP_EDGES))
        | sharp_vertex_tags(s, inf, semi);
    let rl = if pt & (tags::V_SEMI_SHARP | tags::V_SEMI_SHARP_EDGES) != 0 && s <= 0.0 {
        rule::determine(0.0, inf + semi)
    } else {
        p.vert_rule[v]
    };
    (t, rl)
}

/// Sharpness tags and rule of the edge point of a parent edge with tags `et`, whose two child
/// edges have tags `t0` and `t1`.
pub(super) fn edge_point_tags(et: u8, t0: u8, t1: u8) -> (u16, u8) {
    let inf = (t0 & tags::E_INF_SHARP != 0) as usize + (t1 & tags::E_INF_SHARP != 0) as usize;
    let semi = (t0 & tags::E_SEMI_SHARP != 0) as usize + (t1 & tags::E_SEMI_SHARP != 0) as usize;
    let rl = if et & tags::E_SEMI_SHARP != 0 {
        rule::determine(0.0, semi)
    } else if et & tags::E_INF_SHARP != 0 {
        rule::CREASE
    } else {
        rule::SMOOTH
    };
    (sharp_vertex_tags(0.0, inf, semi), rl)
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

pub(super) fn sharp_tag(s: f32) -> u8 {
    if crease::is_infinite(s) {
        tags::E_INF_SHARP
    } else if s > 0.0 {
        tags::E_SEMI_SHARP
    } else {
        0
    }
}
