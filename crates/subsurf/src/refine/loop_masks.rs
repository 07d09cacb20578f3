//! Stencils of one Loop refinement step and of the Loop limit, from the masks of
//! [`crate::rules::r#loop`], as OpenSubdiv's `Far::PrimvarRefiner` applies them.
//!
//! A Loop step has no face points, so its [`LevelStencils`] has an empty face table and its
//! vertex and edge rows refer to parent vertices only.

use super::alloc::{init, unwritten, written};
use super::last_level::ChildSharpness;
use super::level::child_end_at_vertex;
use super::masks::{build_rows, LevelStencils, Scratch};
use super::stencil::StencilTable;
use crate::real::Real;
use crate::rules::r#loop::{edge_mask, limit_mask, smooth_weights, vertex_mask};
use crate::topology::tags::rule;
use crate::topology::Topology;
use crate::util::par;
use rayon::prelude::*;

/// The stencils mapping vertex data of the triangle level `p` to its Loop child `c` (as
/// [`super::loop_level::refine_tri_topology`] builds it): children of vertices, then edge
/// points.
pub fn loop_level_stencils(p: &Topology, c: &Topology) -> LevelStencils {
    loop_level_stencils_with(p, ChildSharpness::of_child(p, c))
}

/// [`loop_level_stencils`] from what the rows read of the child: its sharpness and rules
/// (stored in a full child, or derived from `p` for a lean last level).
pub(crate) fn loop_level_stencils_with(p: &Topology, c: ChildSharpness<'_>) -> LevelStencils {
    let (vertex, edge) = if super::loop_rings::is_manifold(p) {
        manifold_tables(p, c, None)
    } else {
        merged_tables(p, c)
    };
    loop_level(p, vertex, edge)
}

/// [`loop_level_stencils`] with weights in `W` (OpenSubdiv's `PrimvarRefinerReal<W>`): the
/// masks evaluated in `W`, repeated inputs of a row merged ([`merged_tables`]); for `f32`,
/// the same rows as [`loop_level_stencils`].
pub fn loop_level_stencils_real<W: Real>(p: &Topology, c: &Topology) -> LevelStencils<W> {
    let (vertex, edge) = merged_tables(p, ChildSharpness::of_child(p, c));
    loop_level(p, vertex, edge)
}

/// A Loop step's stencils: no face points.
fn loop_level<W: Real>(
    p: &Topology,
    vertex: StencilTable<W>,
    edge: StencilTable<W>,
) -> LevelStencils<W> {
    let nv = p.num_vertices();
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

/// The vertex and edge tables of a step from a manifold level ([`super::loop_rings::
/// is_manifold`]), written directly: there a vertex's neighbours are distinct and differ from
/// it, an edge's ends differ from each other and from its opposite vertices, and only the two
/// opposite vertices of an edge can coincide (two triangles on the same three vertices), so
/// every row's length is known before it is formed and only that pair is merged (in `f64`, as
/// [`merged_tables`] merges it). Same entries, order and weights as [`merged_tables`].
///
/// With `only = Some((vertices, edges))` the tables hold those rows alone, in that order (the
/// exceptions of a per-frame plan, [`super::loop_frame::LoopPlan`]).
pub(super) fn manifold_tables(
    p: &Topology,
    c: ChildSharpness<'_>,
    only: Option<(&[u32], &[u32])>,
) -> (StencilTable, StencilTable) {
    let (nv, ne) = (p.num_vertices(), p.num_edges());
    let vrow = |i: usize| only.map_or(i, |o| o.0[i] as usize);
    let erow = |i: usize| only.map_or(i, |o| o.1[i] as usize);
    let vertex = write_rows(
        only.map_or(nv, |o| o.0.len()),
        nv,
        |_| Scratch::default(),
        |v, s| {
            let v = vrow(v);
            let n = p.valence(v);
            if n == 0 {
                1
            } else if smooth_vertex(p, v) {
                n + 1
            } else {
                let mask = loop_vertex_mask(p, c, v, s);
                mask.edges.iter().filter(|&&w| w != 0.0).count() + 1
            }
        },
        |v, s, idx, wts| {
            let v = vrow(v);
            let pe = p.vertex_edges(v);
            if pe.is_empty() {
                (idx[0], wts[0]) = (v as u32, 1.0);
                return;
            }
            let n = pe.len();
            if smooth_vertex(p, v) {
                let (vw, ew) = smooth_weights::<f32>(n);
                for ((&e, i), w) in pe.iter().zip(&mut idx[..n]).zip(&mut wts[..n]) {
                    (*i, *w) = (p.other_vertex(e as usize, v as u32), ew);
                }
                (idx[n], wts[n]) = (v as u32, vw);
                return;
            }
            let mask = loop_vertex_mask(p, c, v, s);
            let mut k = 0;
            for (&e, &w) in pe.iter().zip(&mask.edges) {
                if w != 0.0 {
                    (idx[k], wts[k]) = (p.other_vertex(e as usize, v as u32), w);
                    k += 1;
                }
            }
            (idx[k], wts[k]) = (v as u32, mask.vertex);
        },
    );
    // The edge mask and the opposite vertices of edge `e` (the second `u32::MAX` where the
    // edge has one face or both opposite vertices are one). A smooth edge's mask needs no
    // child rule (`edge_mask` reads it only for a sharp edge), so none is looked up there.
    let edge_row = |e: usize| {
        let nfaces = (p.edge_face_offsets[e + 1] - p.edge_face_offsets[e]) as usize;
        let s = p.edge_sharpness[e];
        let child_rule = if s > 0.0 {
            c.rule(nv + e)
        } else {
            rule::SMOOTH
        };
        let m = edge_mask::<f32>(s, child_rule, nfaces);
        let o0 = opposite(p, e, 0);
        let o1 = if nfaces == 2 { opposite(p, e, 1) } else { o0 };
        let o1 = if o1 != o0 { o1 } else { u32::MAX };
        (m, [o0, o1], nfaces == 2 && o1 == u32::MAX)
    };
    let smooth2 = edge_mask::<f32>(0.0, rule::SMOOTH, 2);
    let edge = write_rows(
        only.map_or(ne, |o| o.1.len()),
        nv,
        |_| (),
        |e, _| {
            let e = erow(e);
            if smooth_edge(p, e) {
                // Smooth: both opposite vertices, merged where they are one.
                3 + (opposite(p, e, 0) != opposite(p, e, 1)) as usize
            } else {
                let (m, o, _) = edge_row(e);
                if m.opposite == 0.0 {
                    2
                } else {
                    3 + (o[1] != u32::MAX) as usize
                }
            }
        },
        |e, _, idx, wts| {
            let e = erow(e);
            let ev = p.edge_verts[e];
            if smooth_edge(p, e) {
                // Smooth, two faces (what `edge_row` gives there, without the general mask).
                let (o0, o1) = (opposite(p, e, 0), opposite(p, e, 1));
                (idx[0], wts[0]) = (ev[0], smooth2.vertex);
                (idx[1], wts[1]) = (ev[1], smooth2.vertex);
                if o0 != o1 {
                    (idx[2], wts[2]) = (o0, smooth2.opposite);
                    (idx[3], wts[3]) = (o1, smooth2.opposite);
                } else {
                    let w = (smooth2.opposite as f64 + smooth2.opposite as f64) as f32;
                    (idx[2], wts[2]) = (o0, w);
                }
                return;
            }
            let (m, o, merged) = edge_row(e);
            (idx[0], wts[0]) = (ev[0], m.vertex);
            (idx[1], wts[1]) = (ev[1], m.vertex);
            if m.opposite != 0.0 {
                let w = if merged {
                    (m.opposite as f64 + m.opposite as f64) as f32
                } else {
                    m.opposite
                };
                (idx[2], wts[2]) = (o[0], w);
                if o[1] != u32::MAX {
                    (idx[3], wts[3]) = (o[1], w);
                }
            }
        },
    );
    (vertex, edge)
}

/// Whether vertex `v` of a manifold triangle level follows the smooth rule (smooth or dart,
/// as many faces as edges): its row is then its `n` neighbours, `(5/8 - beta^2) / n` each
/// (positive, as beta <= 5/8, so no entry is dropped), and itself.
#[inline]
pub(super) fn smooth_vertex(p: &Topology, v: usize) -> bool {
    let pr = p.vert_rule[v];
    (pr == rule::SMOOTH || pr == rule::DART) && p.vertex_faces(v).len() == p.valence(v)
}

/// Whether edge `e` is a smooth edge of two faces: its row is its two ends and the two
/// opposite vertices (one, merged, where they coincide).
#[inline]
pub(super) fn smooth_edge(p: &Topology, e: usize) -> bool {
    p.edge_sharpness[e] <= 0.0 && p.edge_faces(e).len() == 2
}

/// The vertex opposite edge `e` in its `i`-th face (a triangle).
#[inline]
pub(super) fn opposite(p: &Topology, e: usize, i: usize) -> u32 {
    let o = p.edge_face_offsets[e] as usize + i;
    let (f, k) = (p.edge_faces[o] as usize, p.edge_face_local[o] as usize);
    p.face_verts[3 * f + if k == 0 { 2 } else { k - 1 }]
}

/// Builds a table of `rows` rows over `num_inputs` inputs whose lengths `len(r)` are known
/// before the rows are formed: sized in one parallel pass, then each row written by `row(r,
/// indices, weights)` into its own slices of tables allocated once at their exact size. Each
/// pass over a chunk of rows starts with a state `state(first row)` (scratch buffers, a
/// cursor) handed to `len` and `row` with each row, in order. The tables are allocated
/// unwritten ([`super::alloc::unwritten`]); each row's slices are zeroed just before `row`
/// fills them.
#[allow(unsafe_code)]
pub(super) fn write_rows<S, L, R>(
    rows: usize,
    num_inputs: usize,
    state: impl Fn(usize) -> S + Sync,
    len: L,
    row: R,
) -> StencilTable
where
    L: Fn(usize, &mut S) -> usize + Sync,
    R: Fn(usize, &mut S, &mut [u32], &mut [f32]) + Sync,
{
    let b = par::bounds(rows);
    let mut offsets = unwritten(rows + 1, u32::MAX);
    offsets[0].write(0);
    par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut offsets[1..], &b, |r| r))
        .for_each(|(r, out)| {
            let mut s = state(r.start);
            let base = r.start;
            for i in r {
                out[i - base].write(len(i, &mut s) as u32);
            }
        });
    // SAFETY: the first value above, the rest by the chunks, which cover them.
    let mut offsets = unsafe { written(offsets) };
    let mut acc = 0u32;
    for o in &mut offsets[1..] {
        acc += *o;
        *o = acc;
    }
    let mut indices = unwritten(acc as usize, u32::MAX);
    let mut weights = unwritten(acc as usize, f32::NAN);
    let start = |r: usize| offsets[r] as usize;
    par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut indices, &b, start))
        .zip(par::split_exact(&mut weights, &b, start))
        .for_each(|((r, io), wo)| {
            let mut s = state(r.start);
            let base = start(r.start);
            for i in r {
                let (a, b) = (start(i) - base, start(i + 1) - base);
                row(i, &mut s, init(&mut io[a..b], 0), init(&mut wo[a..b], 0.0));
            }
        });
    // SAFETY: the chunks cover both tables and every row's values are written (`init`).
    let (indices, weights) = unsafe { (written(indices), written(weights)) };
    StencilTable {
        offsets,
        indices,
        weights,
        num_inputs,
    }
}

/// The vertex and edge tables of a step, repeated inputs of a row merged in `f64`: what a
/// non-manifold level needs, where a row can meet one vertex twice.
fn merged_tables<W: Real>(
    p: &Topology,
    c: ChildSharpness<'_>,
) -> (StencilTable<W>, StencilTable<W>) {
    let (nv, ne) = (p.num_vertices(), p.num_edges());
    let vertex = build_rows(nv, nv, |v, b, s: &mut Scratch<W>| {
        if p.vertex_edges(v).is_empty() {
            b.add(v as u32, W::ONE);
            return;
        }
        let mask = loop_vertex_mask(p, c, v, s);
        for (&e, &w) in p.vertex_edges(v).iter().zip(&mask.edges) {
            if w != W::ZERO {
                b.add(p.other_vertex(e as usize, v as u32), w);
            }
        }
        b.add(v as u32, mask.vertex);
    });
    let edge = build_rows(ne, nv, |e, b, _: &mut Scratch<W>| {
        let ev = p.edge_verts[e];
        let faces = p.edge_faces(e);
        let m = edge_mask::<W>(p.edge_sharpness[e], c.rule(nv + e), faces.len());
        b.add(ev[0], m.vertex);
        b.add(ev[1], m.vertex);
        if m.opposite != W::ZERO {
            for (&f, &k) in faces.iter().zip(p.edge_faces_local(e)) {
                let fv = p.face_vertices(f as usize);
                b.add(fv[(k as usize + 2) % fv.len()], m.opposite);
            }
        }
    });
    (vertex, edge)
}

/// The Loop vertex-point mask of parent vertex `v` of the triangle level `p` (edge weights in
/// ring order, applying to the far end of each edge; no face weights), from the sharpness and
/// rules of `p` and its child `c`. `v` must have edges.
pub(super) fn loop_vertex_mask<'s, W: Real>(
    p: &Topology,
    c: ChildSharpness<'_>,
    v: usize,
    s: &'s mut Scratch<W>,
) -> &'s crate::rules::catmark::VertexMask<W> {
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
    s.ce.extend(
        (0..pe.len())
            .map(|i| c.edge(2 * pe[i] as usize + child_end_at_vertex(p, pe, i, v) as usize)),
    );
    vertex_mask(
        nfaces,
        [pr, c.rule(v)],
        [p.vert_sharpness[v], c.vertex(v)],
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
    loop_limit_stencils_real(t)
}

/// [`loop_limit_stencils`] with weights in `W`.
pub(crate) fn loop_limit_stencils_real<W: Real>(t: &Topology) -> StencilTable<W> {
    build_rows(
        t.num_vertices(),
        t.num_vertices(),
        |v, b, s: &mut Scratch<W>| {
            let edges = t.vertex_edges(v);
            if edges.is_empty() {
                b.add(v as u32, W::ONE);
                return;
            }
            s.pe.clear();
            s.pe.extend(edges.iter().map(|&e| t.edge_sharpness[e as usize]));
            limit_mask(t.vert_rule[v], &s.pe, t.vertex_faces(v).len(), &mut s.mask);
            for (&e, &w) in edges.iter().zip(&s.mask.edges) {
                if w != W::ZERO {
                    b.add(t.other_vertex(e as usize, v as u32), w);
                }
            }
            b.add(v as u32, s.mask.vertex);
        },
    )
}

impl super::Refiner {
    /// The Loop refinement of `base` (all triangles, checked by the caller), every level with
    /// its full topology but a lean last one where `options` say
    /// ([`super::RefineOptions::lean`]: its face lists only, its rows reading the child's
    /// sharpness and rules derived from the parent). Each step keeps its per-frame plan made
    /// from the topology ([`super::loop_frame::LoopPlan`]; the stencil tables are then built on
    /// first use), or, where a level is not manifold, every step keeps its stencil tables. The
    /// next level's topology is built while the plan of the step to the current one is: both
    /// read only that level, so they run side by side (`rayon::join`; one after the other on
    /// one thread, with the same results).
    pub(super) fn new_loop(
        base: Topology,
        level: usize,
        options: super::RefineOptions,
    ) -> super::Refiner {
        Self::new_loop_keeping_sharpness(base, level, options).0
    }

    /// [`Self::new_loop`], also returning the child sharpness that a lean last level's
    /// stencils read (derived from the parent; `None` where the last level is full), for
    /// callers that tag that level too (`refine_once` with tags) and so need not derive it again.
    pub(super) fn new_loop_keeping_sharpness(
        base: Topology,
        level: usize,
        options: super::RefineOptions,
    ) -> (super::Refiner, Option<super::last_level::ChildSharpnessBuf>) {
        use super::last_level::ChildSharpnessBuf;
        use super::loop_frame::LoopPlan;
        use super::loop_level::{refine_tri, refine_tri_face_lists};
        let full = |k: usize| k + 1 < level || options.full_topology_in_last_level;
        let mut levels = vec![base];
        let mut plans = Vec::with_capacity(level);
        let mut ahead = None;
        let mut lean_sharpness = None;
        for k in 0..level {
            let parent = &levels[k];
            if !full(k) {
                let ((plan, sharpness), child) = rayon::join(
                    || {
                        let sharpness = ChildSharpnessBuf::new(parent);
                        let plan = LoopPlan::from_topology(parent, sharpness.view(parent));
                        (plan, sharpness)
                    },
                    || refine_tri_face_lists(parent),
                );
                plans.push(plan);
                levels.push(child);
                lean_sharpness = Some(sharpness);
                continue;
            }
            let child = ahead.take().unwrap_or_else(|| refine_tri(parent));
            let (plan, next) = rayon::join(
                || LoopPlan::from_topology(parent, ChildSharpness::of_child(parent, &child)),
                || (k + 1 < level && full(k + 1)).then(|| refine_tri(&child)),
            );
            ahead = next;
            plans.push(plan);
            levels.push(child);
        }
        let mut refiner = super::Refiner {
            levels,
            stencils: std::sync::OnceLock::new(),
            limit_table: std::sync::OnceLock::new(),
            frame_plans: std::sync::OnceLock::new(),
            options,
        };
        match plans.into_iter().collect::<Option<Vec<LoopPlan>>>() {
            Some(plans) => {
                let plans: Vec<_> = plans
                    .into_iter()
                    .map(|lp| super::smooth_frame::StepPlan {
                        loop_plan: Some(lp),
                        ..Default::default()
                    })
                    .collect();
                refiner.frame_plans = std::sync::OnceLock::from(plans);
            }
            None => refiner.stencils = std::sync::OnceLock::from(refiner.build_stencils()),
        }
        (refiner, lean_sharpness)
    }
}
