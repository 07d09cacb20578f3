//! Incremental crease edits: a table updated in place where new sharpness keeps its isolation
//! structure, with the result a fresh [`PatchTable::build`] gives, bit for bit.
//!
//! A table keeps its sparse levels ([`EditState`]: the topology of every level and of every
//! refined sub-mesh, which faces were refined and which were leaves, the vertex tags the
//! build computed) when built by [`PatchTable::build_editable`], or from its first edit,
//! which rebuilds it. An edit then walks the levels from the base down:
//!
//! 1. the edited base; at each level the elements whose sharpness, tags or rule changed, and
//!    the vertices they touch (an edge marks both ends);
//! 2. the decisions of the faces around them are made again with the level's feature rules
//!    ([`super::features`]): a face refined that should not be, a leaf that should be refined
//!    or whose patch changes between B-spline and end cap, or an end cap whose points change,
//!    is a change of structure at that level: the table is rebuilt from it down, the levels
//!    above kept ([`super::edit_rebuild`]; in full, with its levels kept, at the base);
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
//! The walk runs on the calling thread; steps 2–3 of a level run in a task of their own,
//! spawned as soon as the walk has derived the level (a level is not written again once
//! derived), while the walk goes on with steps 4 and 1. The stencil rows are formed during
//! the walk, and nothing is written into the table until every decision has kept the
//! structure. What changed is
//! noted where it is written (`refine/moved.rs`), so the work is that of the changed
//! elements, rows and leaves down to the depth where the edit decays, instead of refining
//! every level's topology, stencils and end caps again. A structural change costs the
//! construction of the levels from the change down.

use super::endcap::gregory_points;
use super::features::{face_has_features, FeatureMask, VTag};
use super::leaves::{leaf_kind, LeafOptions};
use super::sparse::{border_vertex, Trace};
use super::table::{PatchTable, PatchType};
use crate::error::{Error, Result};
use crate::patch::{PatchParam, PatchParamFields};
use crate::real::Real;
use crate::refine::{
    edge_values, form_rows, resharpen_at, unique, vertex_values, Bits, Moved, Restenciled,
};
use crate::topology::Topology;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// Not visited by the walk.
pub(super) const NONE: u32 = u32::MAX;
/// Refined further.
pub(super) const CHOSEN: u32 = u32::MAX - 1;

/// The levels of a table kept for incremental edits.
#[derive(Debug, Clone)]
pub struct EditState {
    /// The levels, but for level 0 (left empty): the table's base.
    pub(super) trace: Trace,
    /// `visit[d][f]`: [`CHOSEN`], the leaf index of face `f` of level `d`, or [`NONE`].
    pub(super) visit: Vec<Vec<u32>>,
    /// `leaf_patch[d][i]`: the patch of leaf `i` of level `d`.
    pub(super) leaf_patch: Vec<Vec<u32>>,
}

impl EditState {
    /// The kept levels.
    pub(crate) fn trace(&self) -> &Trace {
        &self.trace
    }

    /// The state of a construction: its `trace` (level 0 the base, of `base_faces` faces,
    /// left empty in the trace or not) and the `(level, leaf)` of each patch.
    pub(crate) fn new(
        mut trace: Trace,
        base_faces: usize,
        patch_leaves: &[(u32, u32)],
    ) -> EditState {
        let visit = (0..trace.levels.len())
            .map(|d| {
                let faces = if d == 0 {
                    base_faces
                } else {
                    trace.levels[d].num_faces()
                };
                let mut v = vec![NONE; faces];
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
        // Level 0 is the table's base.
        trace.levels[0] = Topology::default();
        EditState {
            trace,
            visit,
            leaf_patch,
        }
    }
}

/// How [`PatchTable::set_sharpness_incremental`] applied an edit.
pub(crate) enum Incremental {
    /// In place: the structure is kept.
    Updated,
    /// Rebuilt from the first level whose structure changed.
    Rebuilt(u32),
    /// To be rebuilt in full from this base (the table is unchanged).
    Rebuild(Box<Topology>),
    /// The structure changed: to be made locally over the region ([`super::edit_local`]; the
    /// table is unchanged but for its kept levels, dropped).
    Local(Box<Topology>, super::edit_local::Region),
}

/// The rows of one step formed again: vertex rows, edge rows (increasing).
type Dirty = (Vec<u32>, Vec<u32>);

/// The new type, sharpness and parameter of patches: `(patch, type, sharpness, parameter)`.
pub(super) type NewParams = Vec<(usize, u8, f32, PatchParam)>;

/// Writes the new `params` of patches into their types, sharpness and parameters.
pub(super) fn write_params(
    params: NewParams,
    (kinds, sharpness, pp): (&mut [u8], &mut [f32], &mut [PatchParam]),
) {
    for (p, kind, s, param) in params {
        kinds[p] = kind;
        sharpness[p] = s;
        pp[p] = param;
    }
}

/// What the decisions of one level found: the new type, sharpness and parameter of its
/// leaves' patches, or `None` where the structure changes.
type Decided = Result<Option<NewParams>>;

/// What the walk writes of the kept levels: the levels ([`Trace::levels`], level 0 unused),
/// the sub-meshes, and the level-to-sub-mesh maps it reads.
type Kept<'a, 'b> = (
    &'a mut [Topology],
    &'b mut [Topology],
    &'b [(Vec<u32>, Vec<u32>)],
);

impl<R: Real> PatchTable<R> {
    /// Applies the edited base topology `base` incrementally (module documentation): in
    /// place where the structure is kept, from the first level whose structure changes
    /// otherwise ([`super::edit_rebuild`]). Returns `base` back, the table unchanged but for
    /// its kept levels, where it must be rebuilt in full (no levels kept, or the change is
    /// at the base).
    ///
    /// The walk down the levels (new values of the sub-mesh and the child level, the rows
    /// formed again) and the decisions of each level's faces run side by side: a level is
    /// handed to its decisions as soon as the walk has derived it, and is not written again.
    pub(crate) fn set_sharpness_incremental(&mut self, base: Topology) -> Result<Incremental> {
        let Some(state) = self.edit_state.take() else {
            return Ok(Incremental::Rebuild(Box::new(base)));
        };
        let mut st = Arc::try_unwrap(state).unwrap_or_else(|a| (*a).clone());
        let max_level = self.options.level_for(&base) as usize;
        let leaf_options = LeafOptions::new(&self.options, max_level);
        let mask = FeatureMask::new(self.options.single_crease);
        let num_level_points = *self.level_offsets.last().unwrap_or(&0);

        // The base is level 0 of the walk.
        let old_base = std::mem::replace(&mut self.base, base);
        // The walk writes the levels and sub-meshes; the decisions read the levels it has
        // left and write only their own tags.
        let EditState {
            trace,
            visit,
            leaf_patch,
        } = &mut st;
        let Trace {
            levels: kept,
            subs,
            in_sub,
            tags,
            ..
        } = trace;
        let stop = &AtomicBool::new(false);
        let this = &*self;
        // The walk runs on this thread; each level it has written is decided in a task of its
        // own (spawned, so that the walk starts at once and the decisions of the last levels
        // share the threads once the walk is done). A level is not written again once the
        // walk has left it, and each task writes only its own level's tags and outcome.
        let mut decided: Vec<Option<Decided>> = (0..visit.len()).map(|_| None).collect();
        let rows = rayon::in_place_scope(|scope| {
            // Each level's part of the state, taken by its task.
            let mut slots: Vec<_> = (visit.iter().zip(leaf_patch.iter()))
                .zip(tags.iter_mut().zip(decided.iter_mut()))
                .map(Some)
                .collect();
            let (mask, leaf_options) = (&mask, &leaf_options);
            let mut decide = |d: usize, t, changed: Arc<Moved>| {
                let Some(((visit, leaf_patch), (tags, out))) = slots[d].take() else {
                    return;
                };
                scope.spawn(move |_| {
                    let mut patches = Vec::new();
                    let o = this.redecide(
                        t,
                        (visit, leaf_patch, tags),
                        d,
                        &changed,
                        (mask, leaf_options),
                        num_level_points,
                        &mut patches,
                    );
                    if !matches!(o, Ok(true)) {
                        stop.store(true, Ordering::Relaxed);
                    }
                    *out = Some(match o {
                        Ok(true) => this.new_params(patches).map(Some),
                        o => o.map(|_| None),
                    });
                });
            };
            this.walk(
                (&old_base, &this.base),
                (kept, subs, in_sub),
                &mut decide,
                stop,
            )
        });
        // The first level (from the base down) whose decisions did not keep the structure
        // decides, as if the levels had been decided in order: a change of structure at
        // that level or an error; else the patches of every level.
        let mut params = Vec::new();
        let mut changed_at = None;
        for (d, o) in decided.into_iter().enumerate() {
            match o {
                None => {}
                Some(Ok(Some(p))) => params.extend(p),
                Some(Ok(None)) => {
                    changed_at = Some(d);
                    break;
                }
                Some(Err(e)) => {
                    self.base = old_base;
                    return Err(e);
                }
            }
        }
        let Some(rows) = rows else {
            return Ok(Incremental::Rebuild(Box::new(std::mem::replace(
                &mut self.base,
                old_base,
            ))));
        };
        match changed_at {
            // Every check passed: the table is changed from here on.
            None => {
                for (d, rows) in rows {
                    rows.apply(&mut self.level_stencils[d]);
                }
                write_params(
                    params,
                    (&mut self.kinds, &mut self.sharpness, &mut self.params),
                );
                self.edit_state = Some(Arc::new(st));
                Ok(Incremental::Updated)
            }
            // The levels above the change are kept ([`super::edit_rebuild`]); an error
            // leaves the table as it was (its levels dropped), as one of the decisions does.
            // A change of structure is made locally where its region is bounded.
            Some(_) if self.local_region_from(&old_base, &self.base).is_some() => {
                let region = self.local_region_from(&old_base, &self.base);
                let t = std::mem::replace(&mut self.base, old_base);
                Ok(Incremental::Local(Box::new(t), region.expect("bounded")))
            }
            Some(d) if d > 0 => {
                let rules = (&mask, &leaf_options);
                match self.rebuilt_from(d, st, rows, params, rules) {
                    Ok(table) => {
                        let share = self.local_share;
                        *self = table;
                        self.local_share = share;
                        Ok(Incremental::Rebuilt(d as u32))
                    }
                    Err(e) => {
                        self.base = old_base;
                        Err(e)
                    }
                }
            }
            Some(_) => Ok(Incremental::Rebuild(Box::new(std::mem::replace(
                &mut self.base,
                old_base,
            )))),
        }
    }

    /// The new type, sharpness and parameter of each patch in `patches` (`(patch, type,
    /// boundary mask, sharpness)`), checked before anything is written.
    fn new_params(&self, patches: Vec<(u32, PatchType, u8, f32)>) -> Result<NewParams> {
        (patches.into_iter())
            .map(|(p, kind, boundary, sharpness)| {
                let p = p as usize;
                PatchParam::new(PatchParamFields {
                    boundary,
                    ..self.params[p].fields()
                })
                .map(|param| (p, kind as u8, sharpness, param))
                .map_err(|e| Error::Internal(format!("crease edit of patch {p}: {e}")))
            })
            .collect()
    }

    /// The walk down the kept levels from the base (`(old, new)`: before and after
    /// the edit): each level's changes, its sub-mesh's new values, the child level's sharpness,
    /// tags and rules, the step's rows to form again. Every level with changes is handed to
    /// `decide` (`(level, topology, what changed)`) as soon as its values are final (a child
    /// level once derived, before the step's rows are found), in increasing order. `None`
    /// where the stored stencils do not have a step's rows; when `stop` is set (a decision
    /// found a change of structure), the rows of the steps walked so far (every step above
    /// the level that changed: its decisions were spawned before its step's rows were
    /// formed).
    fn walk<'a>(
        &self,
        (old, base): (&Topology, &'a Topology),
        (levels, subs, in_sub): Kept<'a, '_>,
        decide: &mut dyn FnMut(usize, &'a Topology, Arc<Moved>),
        stop: &AtomicBool,
    ) -> Option<Vec<(usize, Restenciled<R>)>> {
        let mut levels = levels.iter_mut().skip(1);
        let mut level = base;
        let mut moved = Moved::between(old, level).map(Arc::new);
        if let Some(m) = &moved {
            decide(0, level, m.clone());
        }
        let mut rows = Vec::new();
        for (d, sub) in subs.iter_mut().enumerate() {
            // Nothing changed here: every deeper level is unchanged.
            let Some(changed) = moved else {
                return Some(rows);
            };
            let child = levels.next()?;
            let (sub_changed, sub_moved) = refresh_sub(level, sub, &in_sub[d], &changed);
            let mut child_moved = Moved::new(child);
            let visited = resharpen_at(sub, child, &sub_changed, &mut child_moved);
            // The child level is final: its faces are decided while the walk goes on.
            let child: &'a Topology = child;
            let child_moved = Arc::new(child_moved);
            let child_changed = !child_moved.list.is_empty();
            if child_changed {
                decide(d + 1, child, child_moved.clone());
            }
            let (vertex, edge) =
                self.step_rows(sub, &sub_moved, &child_moved, d, &sub_changed, &visited)?;
            // The rows are formed here, before the decisions are known, and written into
            // the table only if they keep the structure.
            rows.push((d, form_rows(sub, child, vertex, edge)));
            moved = child_changed.then_some(child_moved);
            level = child;
            if stop.load(Ordering::Relaxed) {
                // The rows of the steps above a change of structure are kept.
                return Some(rows);
            }
        }
        Some(rows)
    }

    /// Makes the decisions of the visited faces of level `d` (topology `t`, its faces'
    /// visits, leaves' patches and vertex tags `(visit, leaf_patch, tags)`, the tags brought
    /// up to date here) around the `changed` vertices again: `false` where one differs (or
    /// an end cap's points change); the new types of the leaves are pushed to `out`.
    #[allow(clippy::too_many_arguments)]
    fn redecide(
        &self,
        t: &Topology,
        (visit, leaf_patch, tags): (&[u32], &[u32], &mut [VTag]),
        d: usize,
        changed: &Moved,
        (mask, o): (&FeatureMask, &LeafOptions),
        num_level_points: u32,
        out: &mut Vec<(u32, PatchType, u8, f32)>,
    ) -> Result<bool> {
        let faces = unique(
            (changed.list.iter())
                .flat_map(|&v| t.vertex_faces(v as usize).iter().copied())
                .filter(|&f| visit[f as usize] != NONE),
            t.num_faces(),
        );
        // A tag reads the vertex's own values and its edges' sharpness: only the changed
        // vertices' tags can differ from the kept ones. A refined level keeps the tags of the
        // corners of its walked faces (never holes: they are children of refined faces) and
        // defaults elsewhere, as the build tags them.
        for &v in &changed.list {
            let v = v as usize;
            if d == 0 || t.vertex_faces(v).iter().any(|&f| visit[f as usize] != NONE) {
                tags[v] = VTag::of(t, v, d == 0);
            }
        }
        for &f in &faces {
            let f = f as usize;
            let refine = d < o.max_level && face_has_features(t, tags, f, d, mask);
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
            let (kind, boundary, _, sharpness) = leaf_kind(t, tags, f, d, o);
            let was = self.patch_type(p as usize);
            if (kind == PatchType::Gregory) != (was == PatchType::Gregory) {
                return Ok(false);
            }
            // An end cap reads of its corners' sharpness only whether they are infinitely
            // sharp (the rest is topology, [`super::endcap`]).
            let corner_moved = t.face_vertices(f).iter().any(|&v| changed.inf.get(v));
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

    /// The rows of step `d` (from `sub`) whose inputs changed (parent or child sharpness or
    /// rule of the vertex, of its edges and their children; of the edge and its edge point),
    /// given what changed in the sub-mesh and in the child level; `None` where the stored
    /// stencils do not have the step's rows. Only the edges at `changed` (the vertices of
    /// `sub` whose values [`refresh_sub`] changed), which [`resharpen_at`] rewrote
    /// (`visited`), and their ends can differ: they alone are tested.
    fn step_rows(
        &self,
        sub: &Topology,
        sub_moved: &Moved,
        child_moved: &Moved,
        d: usize,
        changed: &[u32],
        visited: &[u32],
    ) -> Option<Dirty> {
        let (nv, nf, nc) = (sub.num_vertices(), sub.num_faces(), sub.num_corners());
        let ne = sub.num_edges();
        let old = &self.level_stencils[d];
        if old.vertex.num_rows() != nv || old.edge.num_rows() != ne {
            return None;
        }
        let ce = |i: usize| child_moved.edge_sharp.get(i as u32);
        // Increasing, as the rows are listed.
        let near_edges = Bits::of(visited.iter().copied(), ne);
        let mut edge_input = Bits::new(ne);
        let mut near_verts = Bits::of(changed.iter().copied(), nv);
        let mut edges = Vec::new();
        for e in near_edges.iter() {
            let own = sub_moved.edge_sharp.get(e as u32);
            if own || ce(nc + 2 * e) || ce(nc + 2 * e + 1) {
                edge_input.set(e as u32);
            }
            if own || child_moved.rule.get((nv + nf + e) as u32) {
                edges.push(e as u32);
            }
            for v in sub.edge_verts[e] {
                near_verts.set(v);
            }
        }
        let vertices = near_verts
            .iter()
            .filter(|&v| {
                sub_moved.sharp_or_rule.get(v as u32)
                    || child_moved.sharp_or_rule.get(v as u32)
                    || sub.vertex_edges(v).iter().any(|&e| edge_input.get(e))
            })
            .map(|v| v as u32)
            .collect();
        Some((vertices, edges))
    }
}

/// The sub-mesh `sub` of `level` given the level's current values, as [`super::sparse`]
/// makes it: elements whose faces are all kept take the level's values, the border stays an
/// infinitely sharp boundary. `in_sub` numbers the level's vertices and edges in `sub`. Only
/// the elements at the `changed` level vertices are visited (a changed edge marks both
/// ends; a border vertex's tags change only with a changed edge of its own). Returns those
/// vertices, numbered in `sub`, and what changed in `sub`.
fn refresh_sub(
    level: &Topology,
    sub: &mut Topology,
    (sub_vertex, sub_edge): &(Vec<u32>, Vec<u32>),
    changed: &Moved,
) -> (Vec<u32>, Moved) {
    let mut moved = Moved::new(sub);
    for &a in &changed.list {
        for &le in level.vertex_edges(a as usize) {
            let (le, e) = (le as usize, sub_edge[le as usize]);
            let [x, y] = level.edge_verts[le];
            // An edge whose ends both changed, visited from its first end.
            if e == NONE || x != a || !changed.vertices.get(y) {
                continue;
            }
            let e = e as usize;
            if sub.edge_faces(e).len() == level.edge_faces(le).len() {
                let old = edge_values(sub, e);
                sub.edge_sharpness[e] = level.edge_sharpness[le];
                sub.edge_tags[e] = level.edge_tags[le];
                moved.edge(sub, e, old);
            }
        }
    }
    let mut sub_changed = Vec::with_capacity(changed.list.len());
    for &lv in &changed.list {
        let (lv, v) = (lv as usize, sub_vertex[lv as usize]);
        if v == NONE {
            continue;
        }
        sub_changed.push(v);
        let v = v as usize;
        let old = vertex_values(sub, v);
        if sub.vertex_faces(v).len() == level.vertex_faces(lv).len() {
            sub.vert_sharpness[v] = level.vert_sharpness[lv];
            sub.vert_tags[v] = level.vert_tags[lv];
            sub.vert_rule[v] = level.vert_rule[lv];
        } else {
            border_vertex(sub, v);
        }
        moved.vertex(sub, v, old);
    }
    (sub_changed, moved)
}
