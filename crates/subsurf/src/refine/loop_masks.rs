//! Stencils of one Loop refinement step and of the Loop limit, from the masks of
//! [`crate::rules::r#loop`], as OpenSubdiv's `Far::PrimvarRefiner` applies them.
//!
//! A Loop step has no face points, so its [`LevelStencils`] has an empty face table and its
//! vertex and edge rows refer to parent vertices only.

use super::level::child_end_at_vertex;
use super::masks::{build_rows, LevelStencils, Scratch};
use super::stencil::StencilTable;
use crate::rules::r#loop::{edge_mask, limit_mask, smooth_weights, vertex_mask};
use crate::topology::tags::rule;
use crate::topology::Topology;

/// The stencils mapping vertex data of the triangle level `p` to its Loop child `c` (as
/// [`super::loop_level::refine_tri_topology`] builds it): children of vertices, then edge
/// points.
pub fn loop_level_stencils(p: &Topology, c: &Topology) -> LevelStencils {
    let (nv, ne) = (p.num_vertices(), p.num_edges());
    let vertex = build_rows(nv, nv, |v, b, s: &mut Scratch| {
        if p.vertex_edges(v).is_empty() {
            b.add(v as u32, 1.0);
            return;
        }
        let mask = loop_vertex_mask(p, c, v, s);
        for (&e, &w) in p.vertex_edges(v).iter().zip(&mask.edges) {
            if w != 0.0 {
                b.add(p.other_vertex(e as usize, v as u32), w);
            }
        }
        b.add(v as u32, mask.vertex);
    });
    let edge = build_rows(ne, nv, |e, b, _| {
        let ev = p.edge_verts[e];
        let faces = p.edge_faces(e);
        let m = edge_mask(p.edge_sharpness[e], c.vert_rule[nv + e], faces.len());
        b.add(ev[0], m.vertex);
        b.add(ev[1], m.vertex);
        if m.opposite != 0.0 {
            for (&f, &k) in faces.iter().zip(p.edge_faces_local(e)) {
                let fv = p.face_vertices(f as usize);
                b.add(fv[(k as usize + 2) % fv.len()], m.opposite);
            }
        }
    });
    LevelStencils {
        num_parent_vertices: nv,
        face: StencilTable {
            offsets: vec![0],
            indices: Vec::new(),
            weights: Vec::new(),
            num_inputs: nv,
        },
        vertex,
        edge,
    }
}

/// The Loop vertex-point mask of parent vertex `v` of the triangle level `p` (edge weights in
/// ring order, applying to the far end of each edge; no face weights), from the sharpness and
/// rules of `p` and its child `c`. `v` must have edges.
pub(super) fn loop_vertex_mask<'s>(
    p: &Topology,
    c: &Topology,
    v: usize,
    s: &'s mut Scratch,
) -> &'s crate::rules::catmark::VertexMask {
    let nc = p.num_corners();
    let pe = p.vertex_edges(v);
    let nfaces = p.vertex_faces(v).len();
    let pr = p.vert_rule[v];
    if (pr == rule::SMOOTH || pr == rule::DART) && nfaces == pe.len() {
        let (vw, ew) = smooth_weights(nfaces);
        s.mask.vertex = vw;
        s.mask.edges.clear();
        s.mask.edges.resize(pe.len(), ew);
        s.mask.faces.clear();
        return &s.mask;
    }
    s.pe.clear();
    s.pe.extend(pe.iter().map(|&e| p.edge_sharpness[e as usize]));
    // The per-thread scratch, not fresh vectors: this runs once per vertex of every level.
    s.ce.clear();
    s.ce.extend((0..pe.len()).map(|i| {
        c.edge_sharpness[nc + 2 * pe[i] as usize + child_end_at_vertex(p, pe, i, v) as usize]
    }));
    vertex_mask(
        nfaces,
        [pr, c.vert_rule[v]],
        [p.vert_sharpness[v], c.vert_sharpness[v]],
        &s.pe,
        &s.ce,
        p.options.crease_method,
        &mut s.mask,
        &mut s.child_mask,
    );
    &s.mask
}

/// Stencils moving each vertex of the Loop level `t` to its limit position (OpenSubdiv
/// `PrimvarRefiner::Limit`): the smooth, crease or corner limit mask of its rule.
pub fn loop_limit_stencils(t: &Topology) -> StencilTable {
    build_rows(t.num_vertices(), t.num_vertices(), |v, b, s| {
        let edges = t.vertex_edges(v);
        if edges.is_empty() {
            b.add(v as u32, 1.0);
            return;
        }
        s.pe.clear();
        s.pe.extend(edges.iter().map(|&e| t.edge_sharpness[e as usize]));
        limit_mask(t.vert_rule[v], &s.pe, t.vertex_faces(v).len(), &mut s.mask);
        for (&e, &w) in edges.iter().zip(&s.mask.edges) {
            if w != 0.0 {
                b.add(t.other_vertex(e as usize, v as u32), w);
            }
        }
        b.add(v as u32, s.mask.vertex);
    })
}

impl super::Refiner {
    /// The Loop refinement of `base` (all triangles, checked by the caller), every level with
    /// its full topology.
    pub(super) fn new_loop(base: Topology, level: usize) -> crate::error::Result<super::Refiner> {
        let mut levels = vec![base];
        let mut stencils = Vec::with_capacity(level);
        for _ in 0..level {
            let parent = &levels[levels.len() - 1];
            let child = super::loop_level::refine_tri_topology(parent)?;
            stencils.push(loop_level_stencils(parent, &child));
            levels.push(child);
        }
        Ok(super::Refiner {
            levels,
            stencils,
            limit_table: std::sync::OnceLock::new(),
            frame_plans: std::sync::OnceLock::new(),
            options: super::RefineOptions::default(),
        })
    }
}
