//! The last level of a refinement without its relations (OpenSubdiv's
//! `UniformOptions::fullTopologyInLastLevel = false`, its default).
//!
//! Output needs only the last level's face lists, its hole flags and its vertex count; the
//! stencils of the last step need only the sharpness and rules of the children of the parent's
//! vertices and edges ([`ChildSharpness`]). Both are derived here straight from the parent, so
//! the child's edges, rings, tags and offsets into them are never built — about six sevenths
//! of the bytes of a full level.

use super::level::{
    child_edge_sharpness, child_end_at_vertex, edge_point_tags, iota, vertex_child_tags,
};
use super::par;
use crate::rules::crease;
use crate::topology::tags::rule;
use crate::topology::Topology;
use rayon::prelude::*;

/// What the stencils of one step read about the child level: the sharpness of the children
/// of the parent's vertices and edges, and the rule of every child vertex.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChildSharpness<'a> {
    /// Two per parent edge: child edge `2e + end` of parent edge `e` touches its end `end`.
    pub edge: &'a [f32],
    /// One per parent vertex: the sharpness of its child.
    pub vertex: &'a [f32],
    /// One per child vertex, child numbering.
    pub rule: &'a [u8],
}

impl<'a> ChildSharpness<'a> {
    /// The sharpness held by a full child level `c` of `p` (its child edges `nc + 2e + end`).
    pub(crate) fn of_child(p: &Topology, c: &'a Topology) -> Self {
        ChildSharpness {
            edge: &c.edge_sharpness[p.num_corners()..],
            vertex: &c.vert_sharpness[..p.num_vertices()],
            rule: &c.vert_rule,
        }
    }
}

/// Owned [`ChildSharpness`], derived from the parent alone.
#[derive(Debug, Clone, Default)]
pub(crate) struct ChildSharpnessBuf {
    edge: Vec<f32>,
    vertex: Vec<f32>,
    rule: Vec<u8>,
}

impl ChildSharpnessBuf {
    /// The sharpness and rules of the children of `p`, the same values as
    /// [`super::refine_topology`] stores in the child level.
    pub(crate) fn new(p: &Topology) -> Self {
        let (nv, nf, ne) = (p.num_vertices(), p.num_faces(), p.num_edges());
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
                    inf += (t & crate::topology::tags::E_INF_SHARP != 0) as usize;
                    semi += (t & crate::topology::tags::E_SEMI_SHARP != 0) as usize;
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
            edge,
            vertex,
            rule: rules,
        }
    }

    /// Borrowed view.
    pub(crate) fn view(&self) -> ChildSharpness<'_> {
        ChildSharpness {
            edge: &self.edge,
            vertex: &self.vertex,
            rule: &self.rule,
        }
    }
}

/// Refines `p` once keeping only the child's face lists, hole flags and vertex count: the
/// face vertices are those of [`super::refine_topology`]; every other table is left empty.
pub(crate) fn refine_face_lists(p: &Topology) -> Topology {
    let (nv, nf, ne, nc) = (
        p.num_vertices(),
        p.num_faces(),
        p.num_edges(),
        p.num_corners(),
    );
    let fo = |f: usize| p.face_offsets[f] as usize;
    let fb = par::bounds(nf);
    let mut face_verts = vec![0u32; 4 * nc];
    par::ranges(&fb)
        .into_par_iter()
        .zip(par::split(&mut face_verts, &fb, |f| 4 * fo(f)))
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
                    c.copy_from_slice(&[
                        fv[0], e[0], fp, e[3], // child 0
                        e[0], fv[1], e[1], fp, // child 1
                        fp, e[1], fv[2], e[2], // child 2
                        e[3], fp, e[2], fv[3], // child 3
                    ]);
                } else {
                    for j in 0..n {
                        let jp = if j == 0 { n - 1 } else { j - 1 };
                        let c = 4 * (s + j) - base;
                        cfv[c..c + 4].copy_from_slice(&[fv[j], ep(j), fp, ep(jp)]);
                    }
                }
            }
        });
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
