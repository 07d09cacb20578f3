//! The last level of a refinement without its relations (OpenSubdiv's
//! `UniformOptions::fullTopologyInLastLevel = false`, its default).
//!
//! Output needs only the last level's face lists, its hole flags and its vertex count; the
//! stencils of the last step need only the sharpness and rules of the children of the parent's
//! vertices and edges ([`ChildSharpness`]). Both are derived here straight from the parent, so
//! the child's edges, rings, tags and offsets into them are never built — about six sevenths
//! of the bytes of a full level. Under the uniform crease method the child sharpness is not
//! even stored: each value is the parent's, decremented, when a stencil row asks for it
//! (Chaikin's rule averages over neighbours, so it is computed once and stored).

use super::alloc::put;
use super::level::{
    child_edge_sharpness, child_end_at_vertex, edge_point_tags, iota, sharp_tag, vertex_child_tags,
};
use crate::options::{CreaseMethod, Scheme};
use crate::rules::crease;
use crate::topology::tags::{self, rule};
use crate::topology::Topology;
use crate::util::par;
use rayon::prelude::*;

/// Number of face points a step from `p` creates: one per face, none under Loop (whose child
/// numbering is vertex children, then edge points).
#[inline]
pub(crate) fn face_points(p: &Topology) -> usize {
    if p.options.scheme == Scheme::Loop {
        0
    } else {
        p.num_faces()
    }
}

/// What the stencils of one step read about the child level: the sharpness of the children
/// of the parent's vertices and edges, and the rule of every child vertex.
#[derive(Debug, Clone, Copy)]
pub(crate) enum ChildSharpness<'a> {
    /// Stored values.
    Stored {
        /// Two per parent edge: child edge `2e + end` of parent edge `e` touches its end `end`.
        edge: &'a [f32],
        /// One per parent vertex: the sharpness of its child.
        vertex: &'a [f32],
        /// One per child vertex, child numbering.
        rule: &'a [u8],
    },
    /// Derived from the parent on demand, where sharpness decays uniformly (the uniform crease
    /// method, or nothing semi-sharp): both children of an edge of sharpness `s` have
    /// `decrement(s)`, a child vertex `decrement` of its parent's, and rules follow by counting
    /// as [`super::refine_topology`] counts.
    Derived(&'a Topology),
}

impl<'a> ChildSharpness<'a> {
    /// The sharpness held by a full child level `c` of `p` (its child edges `nc + 2e + end`).
    pub(crate) fn of_child(p: &Topology, c: &'a Topology) -> Self {
        ChildSharpness::Stored {
            edge: &c.edge_sharpness[p.num_corners()..],
            vertex: &c.vert_sharpness[..p.num_vertices()],
            rule: &c.vert_rule,
        }
    }

    /// Sharpness of child edge `2e + end` of parent edge `e`.
    #[inline]
    pub(crate) fn edge(&self, i: usize) -> f32 {
        match self {
            ChildSharpness::Stored { edge, .. } => edge[i],
            ChildSharpness::Derived(p) => child_of_edge(p.edge_sharpness[i / 2]),
        }
    }

    /// Sharpness of the child of parent vertex `v`.
    #[inline]
    pub(crate) fn vertex(&self, v: usize) -> f32 {
        match self {
            ChildSharpness::Stored { vertex, .. } => vertex[v],
            ChildSharpness::Derived(p) => crease::decrement(p.vert_sharpness[v]),
        }
    }

    /// Rule of child vertex `i` (child numbering; face points are smooth).
    #[inline]
    pub(crate) fn rule(&self, i: usize) -> u8 {
        match self {
            ChildSharpness::Stored { rule, .. } => rule[i],
            ChildSharpness::Derived(p) => {
                let (nv, nf) = (p.num_vertices(), face_points(p));
                if i < nv {
                    let s = crease::decrement(p.vert_sharpness[i]);
                    let pt = p.vert_tags[i];
                    if pt & (tags::V_SEMI_SHARP | tags::V_SEMI_SHARP_EDGES) != 0 && s <= 0.0 {
                        let (mut inf, mut semi) = (0, 0);
                        for &e in p.vertex_edges(i) {
                            let t = sharp_tag(child_of_edge(p.edge_sharpness[e as usize]));
                            inf += (t & tags::E_INF_SHARP != 0) as usize;
                            semi += (t & tags::E_SEMI_SHARP != 0) as usize;
                        }
                        vertex_child_tags(p, i, s, inf, semi).1
                    } else {
                        p.vert_rule[i]
                    }
                } else if i < nv + nf {
                    rule::SMOOTH
                } else {
                    let e = i - nv - nf;
                    let t = sharp_tag(child_of_edge(p.edge_sharpness[e]));
                    edge_point_tags(p.edge_tags[e], t, t).1
                }
            }
        }
    }
}

/// Sharpness of either child of an edge of sharpness `s` under uniform decay (as
/// [`super::refine_topology`] sets it).
#[inline]
fn child_of_edge(s: f32) -> f32 {
    if crease::is_infinite(s) {
        crate::SHARPNESS_INFINITE
    } else if crease::is_semi_sharp(s) {
        crease::decrement(s)
    } else {
        0.0
    }
}

/// Whether child sharpness can be derived edge by edge: the uniform crease method, or no
/// semi-sharp edge at all (Chaikin's rule then has nothing to average).
fn derivable(p: &Topology) -> bool {
    p.options.crease_method == CreaseMethod::Uniform
        || p.edge_sharpness
            .par_iter()
            .all(|&s| !crease::is_semi_sharp(s))
}

/// [`ChildSharpness`] derived from the parent alone: nothing stored where nothing decays.
#[derive(Debug, Clone, Default)]
pub(crate) struct ChildSharpnessBuf {
    stored: Option<(Vec<f32>, Vec<f32>, Vec<u8>)>,
}

impl ChildSharpnessBuf {
    /// The sharpness and rules of the children of `p`, the same values as
    /// [`super::refine_topology`] stores in the child level.
    pub(crate) fn new(p: &Topology) -> Self {
        if derivable(p) {
            return ChildSharpnessBuf { stored: None };
        }
        let (nv, nf, ne) = (p.num_vertices(), face_points(p), p.num_edges());
        let mut edge = vec![0.0f32; 2 * ne];
        let mut edge_tags = vec![0u8; 2 * ne];
        child_edge_sharpness(p, &mut edge, &mut edge_tags);
        let vertex: Vec<f32> = p.vert_sharpness[..nv]
            .par_iter()
            .with_min_len(4096)
            .map(|&s| crease::decrement(s))
            .collect();
        let mut rules = vec![rule::SMOOTH; nv + nf + ne];
        let (rv, rest) = rules.split_at_mut(nv);
        let re = &mut rest[nf..];
        rv.par_iter_mut()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(v, out)| {
                let pe = p.vertex_edges(v);
                let (mut inf, mut semi) = (0usize, 0usize);
                for (i, &e) in pe.iter().enumerate() {
                    let t = edge_tags[2 * e as usize + child_end_at_vertex(p, pe, i, v) as usize];
                    inf += (t & tags::E_INF_SHARP != 0) as usize;
                    semi += (t & tags::E_SEMI_SHARP != 0) as usize;
                }
                *out = vertex_child_tags(p, v, vertex[v], inf, semi).1;
            });
        re.par_iter_mut()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(e, out)| {
                *out = edge_point_tags(p.edge_tags[e], edge_tags[2 * e], edge_tags[2 * e + 1]).1;
            });
        ChildSharpnessBuf {
            stored: Some((edge, vertex, rules)),
        }
    }

    /// Borrowed view; `p` is the parent the buffer was built from.
    pub(crate) fn view<'a>(&'a self, p: &'a Topology) -> ChildSharpness<'a> {
        match &self.stored {
            Some((edge, vertex, rule)) => ChildSharpness::Stored { edge, vertex, rule },
            None => ChildSharpness::Derived(p),
        }
    }
}

/// Refines `p` once keeping only the child's face lists, hole flags and vertex count: the
/// face vertices are those of [`super::refine_topology`]; every other table is left empty.
#[allow(unsafe_code)]
pub(crate) fn refine_face_lists(p: &Topology) -> Topology {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let fo = |f: usize| p.face_offsets[f] as usize;
    let fb = par::bounds(nf);
    let mut face_verts = super::alloc::unwritten(4 * nc, u32::MAX);
    par::ranges(&fb)
        .into_par_iter()
        .zip(par::split_exact(&mut face_verts, &fb, |f| 4 * fo(f)))
        .for_each(|(r, cfv)| {
            let base = 4 * fo(r.start);
            for f in r {
                let (s, n) = (fo(f), fo(f + 1) - fo(f));
                let fv = &p.face_verts[s..s + n];
                let fe = &p.face_edges[s..s + n];
                let fp = (nv + f) as u32;
                let ep = |j: usize| (nv + nf + fe[j] as usize) as u32;
                if n == 4 {
                    // Child j keeps the parent's orientation: the child of corner j at corner j.
                    let e = [ep(0), ep(1), ep(2), ep(3)];
                    let c = &mut cfv[4 * s - base..4 * s - base + 16];
                    put(
                        c,
                        &[
                            fv[0], e[0], fp, e[3], // child 0
                            e[0], fv[1], e[1], fp, // child 1
                            fp, e[1], fv[2], e[2], // child 2
                            e[3], fp, e[2], fv[3], // child 3
                        ],
                    );
                } else {
                    for j in 0..n {
                        let jp = if j == 0 { n - 1 } else { j - 1 };
                        let c = 4 * (s + j) - base;
                        put(&mut cfv[c..c + 4], &[fv[j], ep(j), fp, ep(jp)]);
                    }
                }
            }
        });
    // SAFETY: the chunks cover the table, each parent face writing its `4n` values.
    let face_verts = unsafe { super::alloc::written(face_verts) };
    let mut face_is_hole = vec![false; nc];
    for f in 0..nf {
        if p.face_is_hole[f] {
            face_is_hole[fo(f)..fo(f + 1)].fill(true);
        }
    }
    Topology {
        options: p.options,
        num_vertices: nv + nf + ne,
        face_offsets: iota(nc + 1, |i| 4 * i as u32),
        face_verts,
        face_is_hole,
        ..Default::default()
    }
}
