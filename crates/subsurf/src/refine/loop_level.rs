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
//! A manifold level refines by [`super::loop_rings`], any other by
//! [`super::loop_nonmanifold`]; both derive every child table directly from the parent's.
//! The child's tags follow OpenSubdiv's: a child of a vertex inherits its parent's, an edge
//! point is boundary or non-manifold where its parent edge is, the children of an edge inherit
//! its tags and the interior child edges have none.

use super::level::{child_edge_sharpness, edge_point_tags, vertex_child_tags};
use crate::error::{MeshError, Result};
use crate::rules::crease;
use crate::topology::tags;
use crate::topology::Topology;
use rayon::prelude::*;

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

/// The four child triangles of a parent triangle with corners `fv` and edge points `e` (edge
/// point `k` on the edge from corner `k` to corner `k + 1`), in the order above.
#[inline]
pub(super) fn child_triangles(fv: &[u32], e: [u32; 3]) -> [u32; 12] {
    [
        fv[0], e[0], e[2], e[0], fv[1], e[1], e[2], e[1], fv[2], e[1], e[2], e[0],
    ]
}

/// The hole flags of a child level of triangles: the four children of parent face `f`
/// (`4f..4f + 4`, in `child_face_verts`, three per face) are holes where `f` is one. With
/// `vert_tags`, every vertex of those children is also tagged [`tags::V_INCIDENT_HOLE`].
/// Shared by every Loop child-topology builder (full, manifold in place, lean face lists).
pub(crate) fn child_holes(
    parent_holes: &[bool],
    child_face_verts: &[u32],
    mut vert_tags: Option<&mut [u16]>,
) -> Vec<bool> {
    let mut holes = super::alloc::zeroed(4 * parent_holes.len(), false);
    if !parent_holes.iter().any(|&h| h) {
        return holes;
    }
    for (f, _) in parent_holes.iter().enumerate().filter(|(_, &h)| h) {
        holes[4 * f..4 * f + 4].fill(true);
        if let Some(t) = vert_tags.as_deref_mut() {
            for &v in &child_face_verts[12 * f..12 * f + 12] {
                t[v as usize] |= tags::V_INCIDENT_HOLE;
            }
        }
    }
    holes
}

/// Refines the all-triangle level `p` once keeping only the child's face lists, hole flags
/// and vertex count (a lean last level, [`super::RefineOptions::lean`]): the face vertices are
/// those of [`refine_tri_topology`]; every other table is left empty.
pub(crate) fn refine_tri_face_lists(p: &Topology) -> Topology {
    let (nv, nf) = (p.num_vertices(), p.num_faces());
    let fb = crate::util::par::bounds(nf);
    let mut face_verts = super::alloc::zeroed(12 * nf, 0u32);
    crate::util::par::ranges(&fb)
        .into_par_iter()
        .zip(crate::util::par::split(&mut face_verts, &fb, |f| 12 * f))
        .for_each(|(r, cfv)| {
            let base = r.start;
            for f in r {
                let fe = &p.face_edges[3 * f..3 * f + 3];
                let e = [0, 1, 2].map(|k| (nv + fe[k] as usize) as u32);
                let i = 12 * (f - base);
                cfv[i..i + 12].copy_from_slice(&child_triangles(&p.face_verts[3 * f..], e));
            }
        });
    let face_is_hole = child_holes(&p.face_is_hole, &face_verts, None);
    Topology {
        options: p.options,
        num_vertices: nv + p.num_edges(),
        face_offsets: super::level::iota(4 * nf + 1, |f| 3 * f as u32),
        face_verts,
        face_is_hole,
        ..Default::default()
    }
}

/// Refines the all-triangle level `p` once (check with [`check_triangles`] first); returns the
/// child topology with its sharpness, tags and rules.
pub fn refine_tri_topology(p: &Topology) -> Result<Topology> {
    Ok(refine_tri(p))
}

/// [`refine_tri_topology`], which cannot fail once the level is all triangles.
pub(super) fn refine_tri(p: &Topology) -> Topology {
    if super::loop_rings::is_manifold(p) {
        return super::loop_rings::refine_manifold(p);
    }
    let (nv, ne, nc) = (p.num_vertices(), p.num_edges(), p.num_corners());
    let mut c = super::loop_nonmanifold::child_relations(p);

    // Sharpness and edge tags: interior edges smooth and manifold, children of edges
    // inheriting their parent's boundary and non-manifold tags, decayed by the crease method.
    let (mut es, mut etags) = (vec![0.0f32; c.num_edges()], vec![0u8; c.num_edges()]);
    child_edge_sharpness(p, &mut es[nc..], &mut etags[nc..]);
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

    c.face_is_hole = child_holes(&p.face_is_hole, &c.face_verts, Some(&mut c.vert_tags));
    c
}
