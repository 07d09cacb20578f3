//! Incremental crease edits: a table updated in place where new sharpness keeps its isolation
//! structure, with the result a fresh [`PatchTable::build`] gives, bit for bit.
//!
//! The first edit of a table rebuilds it keeping its sparse levels ([`EditState`]: the
//! topology of every level and of every refined sub-mesh, which faces were refined and which
//! were leaves). A later edit then walks the levels from the base down:
//!
//! 1. the edited base; at each level the elements whose sharpness, tags or rule changed, and
//!    the vertices they touch (an edge marks both ends);
//! 2. the decisions of the faces around them are made again with the level's feature rules
//!    ([`super::features`]): a face refined that should not be, a leaf that should be refined
//!    or whose patch changes between B-spline and end cap, or an end cap whose points change,
//!    is a change of structure, and the table is rebuilt (with its levels kept);
//! 3. otherwise the leaves around them take their new type, boundary mask and crease
//!    sharpness ([`super::leaves::leaf_kind`]: single-crease ↔ regular, the patch parameter's
//!    boundary bits);
//! 4. the level's sub-mesh takes the new values of its elements (its border stays sharp),
//!    the child level's sharpness, tags and rules are derived from it as refinement derives
//!    them, and the stencil rows of the step whose inputs changed (parent or child sharpness
//!    or rule of the vertex, its edges and their children; of the edge and its edge point)
//!    are formed again, the others copied;
//! 5. a level where nothing changed ends the walk: every deeper level is unchanged.
//!
//! The work is that of the changed rows and leaves plus a linear pass over each level's
//! sharpness arrays down to the depth where the edit decays, instead of refining every
//! level's topology, stencils and end caps again. A structural change costs a full build.

use super::endcap::gregory_points;
use super::features::{face_has_features, FeatureMask, VTag};
use super::leaves::{leaf_kind, LeafOptions};
use super::sparse::{border_vertex, Trace};
use super::table::{PatchTable, PatchType};
use crate::error::{Error, Result};
use crate::patch::{PatchParam, PatchParamFields};
use crate::real::Real;
use crate::refine::{resharpen_at, restencil, unique, Bits, Rewritten};
use crate::topology::Topology;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;

/// Not visited by the walk.
const NONE: u32 = u32::MAX;
/// Refined further.
const CHOSEN: u32 = u32::MAX - 1;

/// The levels of a table kept for incremental edits.
#[derive(Debug, Clone)]
pub struct EditState {
    trace: Trace,
    /// `visit[d][f]`: [`CHOSEN`], the leaf index of face `f` of level `d`, or [`NONE`].
    visit: Vec<Vec<u32>>,
    /// `leaf_patch[d][i]`: the patch of leaf `i` of level `d`.
    leaf_patch: Vec<Vec<u32>>,
}

impl EditState {
    /// The state of a construction: its `trace` and the `(level, leaf)` of each patch.
    pub(crate) fn new(trace: Trace, patch_leaves: &[(u32, u32)]) -> EditState {
        let visit = (0..trace.levels.len())
            .map(|d| {
                let mut v = vec![NONE; trace.levels[d].num_faces()];
                for &f in &trace.chosen[d] {
                    v[f as usize] = CHOSEN;
                }
                for (i, &f) in trace.leaves[d].iter().enumerate() {
                    v[f as usize] = i as u32;
                }
                v
            })
            .collect();
        let mut leaf_patch: Vec<Vec<u32>> =
            trace.leaves.iter().map(|l| vec![NONE; l.len()]).collect();
        for (p, &(d, i)) in patch_leaves.iter().enumerate() {
            leaf_patch[d as usize][i as usize] = p as u32;
        }
        EditState {
            trace,
            visit,
            leaf_patch,
        }
    }
}

/// The sharpness arrays of a topology, to tell what an update changed.
struct Values {
    edge_sharpness: Vec<f32>,
    edge_tags: Vec<u8>,
    vert_sharpness: Vec<f32>,
    vert_tags: Vec<u16>,
    vert_rule: Vec<u8>,
}

impl Values {
    fn of(t: &Topology) -> Values {
        Values {
            edge_sharpness: t.edge_sharpness.clone(),
            edge_tags: t.edge_tags.clone(),
            vert_sharpness: t.vert_sharpness.clone(),
            vert_tags: t.vert_tags.clone(),
            vert_rule: t.vert_rule.clone(),
        }
    }

    /// Per vertex: changed itself or by one of its edges. `None` when nothing changed.
    /// With `at`, only the elements written there can have changed (the rest are not
    /// compared); without, every one is.
    fn changes(&self, t: &Topology, at: Option<&Rewritten>) -> Option<Vec<bool>> {
        let mut verts = vec![false; t.num_vertices()];
        let mut any = false;
        let edge = |e: usize| {
            self.edge_sharpness[e].to_bits() != t.edge_sharpness[e].to_bits()
                || self.edge_tags[e] != t.edge_tags[e]
        };
        let vertex = |v: usize| {
            self.vert_sharpness[v].to_bits() != t.vert_sharpness[v].to_bits()
                || self.vert_tags[v] != t.vert_tags[v]
                || self.vert_rule[v] != t.vert_rule[v]
        };
        let mut mark = |e_changed: bool, ends: [u32; 2]| {
            if e_changed {
                any = true;
                for v in ends {
                    verts[v as usize] = true;
                }
            }
        };
        match at {
            Some(w) => (w.child_edges.iter()).for_each(|&e| mark(edge(e), t.edge_verts[e])),
            None => (0..t.num_edges()).for_each(|e| mark(edge(e), t.edge_verts[e])),
        }
        let mut mark = |v: usize| {
            if vertex(v) {
                verts[v] = true;
                any = true;
            }
        };
        match at {
            Some(w) => w.child_vertices.iter().for_each(|&v| mark(v)),
            None => (0..t.num_vertices()).for_each(mark),
        }
        any.then_some(verts)
    }
}

/// The rows of one step formed again: vertex rows, edge rows (increasing).
type Dirty = (Vec<u32>, Vec<u32>);

/// A level written by the walk, handed to the decisions: `(level, topology, its values
/// before the edit, per vertex whether it changed)`.
type Ready<'a> = (usize, &'a Topology, Values, Vec<bool>);

impl<R: Real> PatchTable<R> {
    /// Applies the edited base topology `base` incrementally (module documentation); returns
    /// `false`, the table unchanged but for its kept levels, where the structure changes.
    ///
    /// The walk down the levels (new values of the sub-mesh and the child level, the rows
    /// to form again) and the decisions of each level's faces run side by side: a level is
    /// handed to the decisions as soon as the walk has written it, and is not written again.
    pub(crate) fn set_sharpness_incremental(&mut self, base: Topology) -> Result<bool> {
        let Some(state) = self.edit_state.take() else {
            return Ok(false);
        };
        let mut st = std::sync::Arc::try_unwrap(state).unwrap_or_else(|a| (*a).clone());
        let max_level = self.options.level_for(&base) as usize;
        let leaf_options = LeafOptions {
            single_crease: self.options.single_crease,
            cap: self.options.cap_crease_sharpness,
            max_level,
        };
        let mask = FeatureMask::new(self.options.single_crease);
        let num_level_points = *self.level_offsets.last().unwrap_or(&0);

        let old = Values::of(&st.trace.levels[0]);
        st.trace.levels[0] = base;
        let EditState {
            trace,
            visit,
            leaf_patch,
        } = &mut st;
        let stop = AtomicBool::new(false);
        let (ready, levels) = mpsc::channel::<Ready<'_>>();
        let this = &*self;
        let (rows, patches) = rayon::join(
            || this.walk(trace, old, ready, &stop),
            || {
                let mut patches = Vec::new();
                for (d, t, old, changed) in levels {
                    let o = this.redecide(
                        t,
                        (&visit[d], &leaf_patch[d]),
                        d,
                        &old,
                        &changed,
                        (&mask, &leaf_options),
                        num_level_points,
                        &mut patches,
                    );
                    if !matches!(o, Ok(true)) {
                        stop.store(true, Ordering::Relaxed);
                        return o.map(|_| None);
                    }
                }
                Ok(Some(patches))
            },
        );
        let (Some(rows), Some(patches)) = (rows, patches?) else {
            return Ok(false);
        };
        // Every check passed: the table is changed from here on.
        for (d, (vertex, edge)) in rows {
            let (sub, child) = (&st.trace.subs[d], &st.trace.levels[d + 1]);
            restencil(sub, child, &mut self.level_stencils[d], &vertex, &edge);
        }
        for (p, kind, boundary, sharpness) in patches {
            let p = p as usize;
            self.kinds[p] = kind as u8;
            self.sharpness[p] = sharpness;
            self.params[p] = PatchParam::new(PatchParamFields {
                boundary,
                ..self.params[p].fields()
            })
            .map_err(|e| Error::Internal(format!("crease edit of patch {p}: {e}")))?;
        }
        self.base = st.trace.levels[0].clone();
        self.edit_state = Some(std::sync::Arc::new(st));
        Ok(true)
    }

    /// The walk down the levels of `trace`, whose base was `old` before the edit: each
    /// level's changes, its sub-mesh's new values, the child level's sharpness, tags and
    /// rules, the step's rows to form again. Every level with changes is sent to `ready`
    /// once written. `None` where the stored stencils do not have a step's rows, or when
    /// `stop` is set (a decision found a change of structure).
    fn walk<'a>(
        &self,
        trace: &'a mut Trace,
        mut old: Values,
        ready: mpsc::Sender<Ready<'a>>,
        stop: &AtomicBool,
    ) -> Option<Vec<(usize, Dirty)>> {
        let Trace {
            levels,
            subs,
            sub_edges,
            ..
        } = trace;
        let mut levels = levels.iter_mut();
        let mut level: &'a Topology = levels.next()?;
        let mut rows = Vec::new();
        // What of a level can differ from `old`: anything on the base; below, what
        // `resharpen_at` wrote.
        let mut written = None;
        for (d, sub) in subs.iter_mut().enumerate() {
            let Some(changed) = old.changes(level, written.as_ref()) else {
                // Nothing changed here: every deeper level is unchanged.
                return Some(rows);
            };
            let child = levels.next()?;
            let sub_old = Values::of(sub);
            let sub_changed =
                refresh_sub(level, sub, &self.level_inputs[d], &sub_edges[d], &changed);
            // The level is final: its faces are decided while the walk goes on.
            ready.send((d, level, old, changed)).ok()?;
            old = Values::of(child);
            let w = resharpen_at(sub, child, &sub_changed);
            rows.push((
                d,
                self.step_rows(sub, &sub_old, child, &old, d, &sub_changed, &w)?,
            ));
            written = Some(w);
            level = child;
            if stop.load(Ordering::Relaxed) {
                return None;
            }
        }
        // The last level: decided, never refined.
        if let Some(changed) = old.changes(level, written.as_ref()) {
            let d = rows.len();
            ready.send((d, level, old, changed)).ok()?;
        }
        Some(rows)
    }

    /// Makes the decisions of the visited faces of level `d` (topology `t`, its faces'
    /// visits and leaves' patches `(visit, leaf_patch)`) around the `changed` vertices
    /// again: `false` where one differs (or an end cap's points change); the new types of
    /// the leaves are pushed to `out`.
    #[allow(clippy::too_many_arguments)]
    fn redecide(
        &self,
        t: &Topology,
        (visit, leaf_patch): (&[u32], &[u32]),
        d: usize,
        old: &Values,
        changed: &[bool],
        (mask, o): (&FeatureMask, &LeafOptions),
        num_level_points: u32,
        out: &mut Vec<(u32, PatchType, u8, f32)>,
    ) -> Result<bool> {
        let faces = unique(
            (0..t.num_vertices())
                .filter(|&v| changed[v])
                .flat_map(|v| t.vertex_faces(v).iter().copied())
                .filter(|&f| visit[f as usize] != NONE),
            t.num_faces(),
        );
        let mut tags = vec![VTag::default(); t.num_vertices()];
        let mut tagged = vec![false; t.num_vertices()];
        for &f in &faces {
            for &v in t.face_vertices(f as usize) {
                if !tagged[v as usize] {
                    tagged[v as usize] = true;
                    tags[v as usize] = VTag::of(t, v as usize, d == 0);
                }
            }
        }
        for &f in &faces {
            let f = f as usize;
            let refine = d < o.max_level && face_has_features(t, &tags, f, d, mask);
            if refine != (visit[f] == CHOSEN) {
                return Ok(false);
            }
            if refine {
                continue;
            }
            let p = leaf_patch[visit[f] as usize];
            if p == NONE {
                return Err(Error::Internal(format!(
                    "leaf {f} of level {d} has no patch"
                )));
            }
            let (kind, boundary, _, sharpness) = leaf_kind(t, &tags, f, d, o);
            let was = self.patch_type(p as usize);
            if (kind == PatchType::Gregory) != (was == PatchType::Gregory) {
                return Ok(false);
            }
            // An end cap reads of its corners' sharpness only whether they are infinitely
            // sharp (the rest is topology, [`super::endcap`]).
            let inf = |s: f32| s >= crate::SHARPNESS_INFINITE;
            let corner_moved = t.face_vertices(f).iter().any(|&v| {
                let v = v as usize;
                inf(old.vert_sharpness[v]) != inf(t.vert_sharpness[v])
            });
            if kind == PatchType::Gregory && corner_moved {
                let off = self.level_offsets[d];
                let first = self.patch_cvs(p as usize)[0] - num_level_points;
                let same = gregory_points(t, f).iter().enumerate().all(|(k, row)| {
                    let r = first as usize + k;
                    let lp = &self.local_points;
                    let (a, b) = (lp.offsets[r] as usize, lp.offsets[r + 1] as usize);
                    b - a == row.len()
                        && row.iter().zip(a..b).all(|(&(x, w), j)| {
                            lp.indices[j] == x + off
                                && lp.weights[j].to_f64().to_bits()
                                    == R::from_f64(w).to_f64().to_bits()
                        })
                });
                if !same {
                    return Ok(false);
                }
            } else if kind != PatchType::Gregory {
                out.push((p, kind, boundary, sharpness));
            }
        }
        Ok(true)
    }

    /// The rows of step `d` whose inputs changed (parent or child sharpness or rule of the
    /// vertex, of its edges and their children; of the edge and its edge point); `None`
    /// where the stored stencils do not have the step's rows. Only the edges at `changed`
    /// (the vertices of `sub` whose values [`refresh_sub`] changed), which [`resharpen_at`]
    /// rewrote (`w`), and their ends can differ: they alone are tested.
    #[allow(clippy::too_many_arguments)]
    fn step_rows(
        &self,
        sub: &Topology,
        sub_old: &Values,
        child: &Topology,
        child_old: &Values,
        d: usize,
        changed: &[u32],
        w: &Rewritten,
    ) -> Option<Dirty> {
        let (nv, nf, nc) = (sub.num_vertices(), sub.num_faces(), sub.num_corners());
        let ne = sub.num_edges();
        let old = &self.level_stencils[d];
        if old.vertex.num_rows() != nv || old.edge.num_rows() != ne {
            return None;
        }
        let bits = |a: f32, b: f32| a.to_bits() != b.to_bits();
        let ce = |i: usize| bits(child_old.edge_sharpness[i], child.edge_sharpness[i]);
        // Increasing, as the rows are listed.
        let near_edges = Bits::of(w.edges.iter().copied(), ne);
        let mut edge_input = Bits::new(ne);
        let mut near_verts = Bits::of(changed.iter().copied(), nv);
        let mut edges = Vec::new();
        for e in near_edges.iter() {
            let own = bits(sub_old.edge_sharpness[e], sub.edge_sharpness[e]);
            if own || ce(nc + 2 * e) || ce(nc + 2 * e + 1) {
                edge_input.set(e as u32);
            }
            if own || child_old.vert_rule[nv + nf + e] != child.vert_rule[nv + nf + e] {
                edges.push(e as u32);
            }
            for v in sub.edge_verts[e] {
                near_verts.set(v);
            }
        }
        let vertices = near_verts
            .iter()
            .filter(|&v| {
                bits(sub_old.vert_sharpness[v], sub.vert_sharpness[v])
                    || sub_old.vert_rule[v] != sub.vert_rule[v]
                    || bits(child_old.vert_sharpness[v], child.vert_sharpness[v])
                    || child_old.vert_rule[v] != child.vert_rule[v]
                    || sub.vertex_edges(v).iter().any(|&e| edge_input.get(e))
            })
            .map(|v| v as u32)
            .collect();
        Some((vertices, edges))
    }
}

/// The sub-mesh `sub` of `level` (its vertices `verts`, edges `edges` in the level) given
/// the level's current values, as [`super::sparse`] makes it: elements whose faces are all
/// kept take the level's values, the border stays an infinitely sharp boundary. Only the
/// elements at `changed` level vertices are visited (a changed edge marks both ends; a
/// border vertex's tags change only with a changed edge of its own). Returns those
/// vertices, numbered in `sub`.
fn refresh_sub(
    level: &Topology,
    sub: &mut Topology,
    verts: &[u32],
    edges: &[u32],
    changed: &[bool],
) -> Vec<u32> {
    for (e, &le) in edges.iter().enumerate() {
        let le = le as usize;
        let [a, b] = level.edge_verts[le];
        if !(changed[a as usize] && changed[b as usize]) {
            continue;
        }
        if sub.edge_faces(e).len() == level.edge_faces(le).len() {
            sub.edge_sharpness[e] = level.edge_sharpness[le];
            sub.edge_tags[e] = level.edge_tags[le];
        }
    }
    let mut sub_changed = Vec::new();
    for (v, &lv) in verts.iter().enumerate() {
        let lv = lv as usize;
        if !changed[lv] {
            continue;
        }
        sub_changed.push(v as u32);
        if sub.vertex_faces(v).len() == level.vertex_faces(lv).len() {
            sub.vert_sharpness[v] = level.vert_sharpness[lv];
            sub.vert_tags[v] = level.vert_tags[lv];
            sub.vert_rule[v] = level.vert_rule[lv];
        } else {
            border_vertex(sub, v);
        }
    }
    sub_changed
}
