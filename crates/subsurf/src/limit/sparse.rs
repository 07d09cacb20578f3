//! Sparse feature-adaptive refinement: the levels a patch table is built from, each refined
//! only around the faces that still need isolating (Nießner, Loop, Meyer & DeRose 2012;
//! OpenSubdiv's `Far::TopologyRefiner::RefineAdaptive`).
//!
//! # Levels
//!
//! Level 0 is the base mesh. Level `d + 1` is one uniform refinement step
//! ([`refine_topology`], [`level_stencils_real`]) of a *sub-mesh* `M_d` of level `d`: the faces
//! `F_d` selected for isolation at level `d` ([`face_has_features`], evaluated on the faces
//! the quadtree walk visits) and one ring of faces around them,
//!
//! ```text
//! M_d = ring(F_d) = every face sharing a vertex with a face of F_d
//! ```
//!
//! — the neighbourhood OpenSubdiv's sparse refinement keeps (`Vtr::SparseSelector`, whose
//! "incomplete" faces are our ring). Each level is a real [`Topology`], so the feature rules,
//! the regular-patch gather and the end caps read it as they read a uniformly refined level.
//! The cost of a level is that of its sub-mesh: around an isolated extraordinary vertex it
//! stays constant from level to level, where uniform refinement multiplies it by four.
//!
//! # Why one ring suffices, and how exactness is checked
//!
//! Let every vertex of `F_d` have its whole ring in level `d`, and every face of
//! `ring(F_d)` exact vertices. Refining `M_d` then gives exactly:
//!
//! - the child of a vertex `v` of `F_d` (it reads `v`'s ring: all in `M_d`, so its valence,
//!   rule and Chaikin crease decay are the true ones);
//! - the edge point of every edge at such a vertex (its faces are around the vertex);
//! - the face point of every face of `M_d`.
//!
//! These are the vertices of the children of `ring(F_d)` at the corners that are vertices of
//! `F_d`, and those children are, for any child `c` of `F_d`, all the faces around `c`'s
//! corners (child of a vertex: the children of its faces at it; edge point: the children of
//! the edge's faces at its ends; face point: its face's children). So the faces the walk
//! visits at level `d + 1` (children of `F_d`) have complete corners and exact one-rings,
//! which is what a patch reads, and the next selection `F_{d+1}` satisfies the hypothesis:
//! by induction from the base, every emitted patch is the one uniform refinement gives.
//!
//! The sub-mesh's own border is wrong on purpose: its edges are made infinitely sharp
//! boundaries and its border vertices infinitely sharp non-manifold corners. Nothing
//! computed from them is used, and this is *checked*, not assumed: every vertex carries two
//! flags, propagated through each step from the rules' inputs —
//!
//! - `exact`: its value (its stencil) is the one uniform refinement gives;
//! - `sound`: its ring is complete and its sharpness, rule, tags and incident edges'
//!   sharpness are the true ones (what [`super::features`], [`super::gather`] and
//!   [`super::endcap`] read);
//!
//! and every edge `edge_ok` (complete, sharpness and tags true). The walk refuses (an internal
//! error) to decide a face whose corners are not sound or to emit a patch that reads a point
//! that is not exact. The sub-mesh keeps the level's relations restricted to its faces (not
//! rebuilt from face lists), so the rings of complete vertices are the level's own, ordering
//! and non-manifold edge instances included.

use super::features::{face_has_features, level_tags, FeatureMask, VTag};
use super::loop_patches::tri_face_has_features;
use crate::error::{Error, MeshError, Result};
use crate::options::{CreaseMethod, Scheme};
use crate::real::Real;
use crate::refine::{
    level_stencils_real, loop_level_stencils_real, refine_topology, refine_tri_topology,
    LevelStencils,
};
use crate::topology::tags::{self, rule};
use crate::topology::Topology;
use crate::util::budget::Budget;
use crate::SHARPNESS_INFINITE;

/// No child / not in the sub-mesh.
pub const NONE: u32 = u32::MAX;

/// How much of each level is refined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    /// The faces being isolated and one ring of faces around them (the default).
    Sparse,
    /// The faces being isolated and `n` rings around them (`n = 0` loses exactness, which
    /// the construction detects).
    #[cfg(test)]
    Rings(usize),
    /// Every face: uniform refinement to the isolation level (the reference the sparse
    /// construction is tested against).
    #[cfg(test)]
    Uniform,
}

/// One level of the hierarchy.
#[derive(Debug, Clone)]
pub struct Level {
    /// Its topology.
    pub topo: Topology,
    /// Feature tags of its vertices: every vertex of the base, the corners of the faces the
    /// walk reaches in a refined level (the only ones read), default elsewhere.
    pub tags: Vec<VTag>,
    /// Per vertex: its value is exact.
    pub exact: Vec<bool>,
    /// Per vertex: ring, sharpness, rule and tags are exact.
    pub sound: Vec<bool>,
    /// Per edge: complete, sharpness and tags exact.
    pub edge_ok: Vec<bool>,
    /// Per face: refined further by the walk.
    pub refine: Vec<bool>,
    /// Per face: its first child face in the next level, or [`NONE`].
    pub child: Vec<u32>,
    /// Per face the walk reaches: the isolation level of its base face (a child inherits its
    /// parent's), when the levels are chosen per base face ([`build_traced`]'s
    /// `face_levels`); empty otherwise.
    pub levels: Vec<u8>,
}

impl Level {
    /// The isolation level that applies to walked face `f` (`default` unless chosen per base
    /// face).
    pub fn level_of(&self, f: usize, default: usize) -> usize {
        self.levels.get(f).map_or(default, |&l| l as usize)
    }
}

/// The sizes of the levels, and the stencils from each to the next (a level itself is
/// released once its leaves and the stencils that make it are computed, so that the next
/// levels reuse its memory).
#[derive(Debug, Clone)]
pub struct Hierarchy<W = f32> {
    /// Number of vertices of each level; `num_vertices[0]` is the base's.
    pub num_vertices: Vec<usize>,
    /// `stencils[d]`: level `d + 1` from the vertices of the sub-mesh of level `d`.
    pub stencils: Vec<LevelStencils<W>>,
    /// `inputs[d][i]`: the level-`d` vertex that is vertex `i` of its sub-mesh.
    pub inputs: Vec<Vec<u32>>,
}

impl Level {
    /// A level of a construction resumed below the levels kept by an edit: its topology
    /// and exactness flags as kept, tags default (the walk tags the corners it reaches).
    pub fn resumed(topo: Topology, flags: Flags) -> Level {
        let (nv, nf) = (topo.num_vertices(), topo.num_faces());
        Level {
            tags: vec![VTag::default(); nv],
            exact: flags.exact,
            sound: flags.sound,
            edge_ok: flags.edge_ok,
            refine: vec![false; nf],
            child: vec![NONE; nf],
            levels: Vec::new(),
            topo,
        }
    }

    fn new(topo: Topology, base: bool) -> Level {
        let (nv, ne, nf) = (topo.num_vertices(), topo.num_edges(), topo.num_faces());
        Level {
            tags: if base {
                // Loop levels have no irregular faces to record.
                level_tags(&topo, !is_loop(&topo))
            } else {
                vec![VTag::default(); nv]
            },
            exact: vec![true; nv],
            sound: vec![true; nv],
            edge_ok: vec![true; ne],
            refine: vec![false; nf],
            child: vec![NONE; nf],
            levels: Vec::new(),
            topo,
        }
    }
}

/// The levels of a construction, kept for crease edits ([`super::edit_region`]): what
/// [`build`] otherwise releases level by level.
#[derive(Debug, Clone, Default)]
pub struct Trace {
    /// The topology of every level (`levels[0]` is the base).
    pub levels: Vec<Topology>,
    /// `subs[d]`: the sub-mesh of level `d` that was refined (its border made sharp).
    pub subs: Vec<Topology>,
    /// `in_sub[d]`: the vertex and the edge of `subs[d]` that each vertex and edge of level
    /// `d` is, or [`NONE`].
    pub in_sub: Vec<(Vec<u32>, Vec<u32>)>,
    /// `chosen[d]`: the faces of level `d` selected for refinement.
    pub chosen: Vec<Vec<u32>>,
    /// `leaves[d]`: the leaf faces of level `d`, in leaf order.
    pub leaves: Vec<Vec<u32>>,
    /// `tags[d]`: the feature tags of level `d` ([`Level::tags`]: every corner of a face the
    /// walk reached).
    pub tags: Vec<Vec<VTag>>,
    /// `child[d]`: the first child face of each face of level `d` ([`Level::child`]).
    pub child: Vec<Vec<u32>>,
    /// `flags[d]`: the exactness flags of level `d`, which only its structure decides.
    pub flags: Vec<Flags>,
}

impl Trace {
    /// Keeps `level` (its topology, tags, children and flags, taken), the faces it refined
    /// and its leaves; its sub-mesh and maps are kept apart.
    fn push_level(&mut self, level: &mut Level, chosen: Vec<u32>, leaves: Vec<u32>) {
        use std::mem::take;
        self.levels.push(take(&mut level.topo));
        self.tags.push(take(&mut level.tags));
        self.child.push(take(&mut level.child));
        self.flags.push(Flags {
            exact: take(&mut level.exact),
            sound: take(&mut level.sound),
            edge_ok: take(&mut level.edge_ok),
        });
        self.chosen.push(chosen);
        self.leaves.push(leaves);
    }

    /// The levels above level `d` only (and the sub-meshes and maps of their steps).
    pub(crate) fn truncate(&mut self, d: usize) {
        self.levels.truncate(d);
        self.subs.truncate(d);
        self.in_sub.truncate(d);
        self.chosen.truncate(d);
        self.leaves.truncate(d);
        self.tags.truncate(d);
        self.child.truncate(d);
        self.flags.truncate(d);
    }
}

/// The exactness flags of a level ([`Level::exact`], [`Level::sound`], [`Level::edge_ok`]).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Flags {
    /// Per vertex: its value is exact.
    pub exact: Vec<bool>,
    /// Per vertex: ring, sharpness, rule and tags are exact.
    pub sound: Vec<bool>,
    /// Per edge: complete, sharpness and tags exact.
    pub edge_ok: Vec<bool>,
}

/// What is made of a level's leaf faces: `(level, d, offset, faces)`, see [`build`].
pub type LeafFn<'a, T> = dyn Fn(&Level, usize, u32, &[u32]) -> Result<T> + Sync + 'a;

/// Builds the levels of `base` up to `max_level`, refining the faces the walk of
/// [`super::table`] descends into (at level 0: every base face), within `budget`.
///
/// `leaves(level, d, offset, faces)` is given each level's leaf faces (walked, not holes, not
/// refined further) and the offset of its vertices in the flat point array; its results are
/// returned per level. It runs while the next level is refined (in parallel where rayon has
/// threads), on the level whose tables were just read by the selection.
#[cfg(test)]
pub fn build<W: Real, T: Send>(
    base: &Topology,
    max_level: usize,
    mask: &FeatureMask,
    selection: Selection,
    budget: &mut Budget,
    leaves: &LeafFn<'_, T>,
) -> Result<(Hierarchy<W>, Vec<T>)> {
    build_traced(base, max_level, None, mask, selection, budget, leaves, None)
}

/// [`build`], keeping the levels in `trace` when one is given. With `face_levels` (one per
/// base face, each at most `max_level`), the faces descending from base face `f` are refined
/// to level `face_levels[f]` at most instead of `max_level`: the isolation is chosen per
/// region. Faces of different regions may then meet at leaves two or more levels apart; each
/// patch is still exact (its points are checked, as everywhere), and the surface is as
/// continuous as the end caps make it.
#[allow(clippy::too_many_arguments)]
pub fn build_traced<W: Real, T: Send>(
    base: &Topology,
    max_level: usize,
    face_levels: Option<&[u8]>,
    mask: &FeatureMask,
    selection: Selection,
    budget: &mut Budget,
    leaves: &LeafFn<'_, T>,
    trace: Option<&mut Trace>,
) -> Result<(Hierarchy<W>, Vec<T>)> {
    build_only(
        base,
        max_level,
        face_levels,
        mask,
        selection,
        budget,
        leaves,
        trace,
        None,
    )
}

/// [`build_traced`] walking only the base faces `only` (increasing) where given: the other
/// faces are neither decided nor refined but as the ring of those refined.
#[allow(clippy::too_many_arguments)]
pub fn build_only<W: Real, T: Send>(
    base: &Topology,
    max_level: usize,
    face_levels: Option<&[u8]>,
    mask: &FeatureMask,
    selection: Selection,
    budget: &mut Budget,
    leaves: &LeafFn<'_, T>,
    trace: Option<&mut Trace>,
    only: Option<&[u32]>,
) -> Result<(Hierarchy<W>, Vec<T>)> {
    if let Some(l) = face_levels {
        if l.len() != base.num_faces() || l.iter().any(|&x| x as usize > max_level) {
            return Err(Error::Internal(format!(
                "{} isolation levels for {} base faces, levels up to {max_level}",
                l.len(),
                base.num_faces()
            )));
        }
    }
    let mut level = Level::new(base.clone(), true);
    if let Some(l) = face_levels {
        level.levels = l.to_vec();
    }
    let start = Start {
        d: 0,
        level,
        visited: only
            .map(<[u32]>::to_vec)
            .unwrap_or_else(|| (0..base.num_faces() as u32).collect()),
        h: Hierarchy {
            num_vertices: vec![base.num_vertices()],
            stencils: Vec::new(),
            inputs: Vec::new(),
        },
        out: Vec::new(),
    };
    resume(start, max_level, mask, selection, budget, leaves, trace)
}

/// Where a construction starts: level `d`, whose faces `visited` are still to be decided,
/// and what the levels above it made.
#[derive(Debug)]
pub struct Start<W, T> {
    /// The level.
    pub d: usize,
    /// Its topology, exactness flags and (with per-region isolation) face levels.
    pub level: Level,
    /// Its faces the walk reaches: every base face, or the children of the faces refined
    /// at level `d - 1`.
    pub visited: Vec<u32>,
    /// The levels above: `num_vertices` up to level `d` included, the `d` steps' stencils
    /// and inputs.
    pub h: Hierarchy<W>,
    /// The leaves' results of the levels above.
    pub out: Vec<T>,
}

/// [`build_traced`] from `start` (a crease edit that keeps the levels above `start.d`,
/// [`super::edit_rebuild`]): the levels `start.d..` are built, and traced where `trace`
/// holds the levels above. Where the start level carries per-face isolation levels
/// ([`Level::levels`]), children inherit them.
pub fn resume<W: Real, T: Send>(
    start: Start<W, T>,
    max_level: usize,
    mask: &FeatureMask,
    selection: Selection,
    budget: &mut Budget,
    leaves: &LeafFn<'_, T>,
    mut trace: Option<&mut Trace>,
) -> Result<(Hierarchy<W>, Vec<T>)> {
    let Start {
        d: first,
        mut level,
        mut visited,
        mut h,
        mut out,
    } = start;
    if h.num_vertices.len() != first + 1
        || h.num_vertices[first] != level.topo.num_vertices()
        || h.stencils.len() != first
        || h.inputs.len() != first
        || out.len() != first
    {
        return Err(Error::Internal(format!(
            "sparse refinement started at level {first} with {} levels above",
            out.len()
        )));
    }
    let face_levels = !level.levels.is_empty();
    let tri = is_loop(&level.topo);
    let mut total_vertices: u64 = h.num_vertices.iter().map(|&n| n as u64).sum();
    let mut offset = (total_vertices - level.topo.num_vertices() as u64) as u32;
    let mut prev_sub: Option<Topology> = None;
    for d in first..=max_level {
        let cur = &mut level;
        if d > 0 {
            tag_corners(cur, &visited);
        }
        let (mut chosen, mut leaf_faces) = (Vec::new(), Vec::with_capacity(visited.len()));
        for &f in &visited {
            let f = f as usize;
            if cur.topo.face_is_hole[f] {
                continue;
            }
            let t = &cur.topo;
            if let Some(&v) = t.face_vertices(f).iter().find(|&&v| !cur.sound[v as usize]) {
                return Err(Error::Internal(format!(
                    "sparse refinement: corner {v} of face {f} at level {d} is not exact"
                )));
            }
            let features = match tri {
                true => tri_face_has_features(t, &cur.tags, f, d),
                false => face_has_features(t, &cur.tags, f, d, mask),
            };
            if d < cur.level_of(f, max_level) && features {
                cur.refine[f] = true;
                chosen.push(f as u32);
            } else {
                leaf_faces.push(f as u32);
            }
        }
        if chosen.is_empty() {
            let cur: &Level = cur;
            let (patches, stencils) = rayon::join(
                || leaves(cur, d, offset, &leaf_faces),
                || prev_sub.as_ref().map(|p| step_stencils(p, &cur.topo)),
            );
            out.push(patches?);
            h.stencils.extend(stencils);
            if let Some(tr) = trace.as_deref_mut() {
                tr.subs.extend(prev_sub.take());
                tr.push_level(&mut level, chosen, leaf_faces);
            }
            break;
        }
        let keep = match selection {
            #[cfg(test)]
            Selection::Uniform => vec![true; cur.topo.num_faces()],
            Selection::Sparse => rings(&cur.topo, &chosen, 1),
            #[cfg(test)]
            Selection::Rings(n) => rings(&cur.topo, &chosen, n),
        };
        let step = Step::new(cur, &keep);
        // Child corners and vertices are indexed with `u32`, and so is the flat point array.
        let corners = 4 * step.sub.num_corners() as u64;
        if corners + total_vertices > (u32::MAX / 2) as u64 {
            return Err(MeshError::TooLarge {
                what: format!(
                    "isolating features of level {d} ({} faces)",
                    step.faces.len()
                ),
                bytes: corners * 50,
                human: crate::util::budget::human((corners * 50) as f64),
                limit_human: "2^31 refined face corners and vertices (32-bit indices)".into(),
            }
            .into());
        }
        budget.add(super::budget::child_level_bytes(&step.sub), || {
            format!(
                "isolating features to level {max_level} (level {} from {} faces)",
                d + 1,
                step.faces.len()
            )
        })?;
        for (m, &f) in step.faces.iter().enumerate() {
            cur.child[f as usize] = match tri {
                true => 4 * m as u32,
                false => step.sub.face_offsets[m],
            };
        }
        let cur: &Level = cur;
        // The stencils of the step that made this level are computed with its leaves, while
        // the next level's topology is refined.
        let ((patches, stencils), next) = rayon::join(
            || {
                rayon::join(
                    || leaves(cur, d, offset, &leaf_faces),
                    || prev_sub.as_ref().map(|p| step_stencils(p, &cur.topo)),
                )
            },
            || -> Result<Level> {
                let child = match tri {
                    true => refine_tri_topology(&step.sub)?,
                    false => refine_topology(&step.sub),
                };
                let mut next = Level::new(child, false);
                step.propagate(&mut next);
                if face_levels {
                    // A child takes its parent's level (the level of their base face).
                    next.levels = vec![0; next.topo.num_faces()];
                    for &f in &chosen {
                        let first = cur.child[f as usize] as usize;
                        let n = num_children(&cur.topo, f as usize) as usize;
                        next.levels[first..first + n].fill(cur.levels[f as usize]);
                    }
                }
                Ok(next)
            },
        );
        let next = next?;
        out.push(patches?);
        h.stencils.extend(stencils);
        offset += cur.topo.num_vertices() as u32;
        total_vertices += next.topo.num_vertices() as u64;
        visited = chosen
            .iter()
            .flat_map(|&f| {
                let first = cur.child[f as usize];
                first..first + num_children(&cur.topo, f as usize)
            })
            .collect();
        h.inputs.push(step.verts);
        h.num_vertices.push(next.topo.num_vertices());
        let done_sub = prev_sub.replace(step.sub);
        let mut done = std::mem::replace(&mut level, next);
        if let Some(tr) = trace.as_deref_mut() {
            tr.subs.extend(done_sub);
            tr.in_sub.push(step.in_sub);
            tr.push_level(&mut done, chosen, leaf_faces);
        }
    }
    Ok((h, out))
}

/// Whether `t` is refined by the Loop scheme (triangle split, no face points).
fn is_loop(t: &Topology) -> bool {
    t.options.scheme == Scheme::Loop
}

/// The number of child faces of face `f` of `t`: one per corner (quad split), four
/// (triangle split).
fn num_children(t: &Topology, f: usize) -> u32 {
    match is_loop(t) {
        true => 4,
        false => t.face_size(f) as u32,
    }
}

/// The stencils of one step from the sub-mesh `p` to its child `c`, by `p`'s scheme.
fn step_stencils<W: Real>(p: &Topology, c: &Topology) -> LevelStencils<W> {
    match is_loop(p) {
        true => loop_level_stencils_real(p, c),
        false => level_stencils_real(p, c),
    }
}

/// Tags the corners of the faces `faces` of a refined level.
fn tag_corners(lv: &mut Level, faces: &[u32]) {
    let t = &lv.topo;
    let mut done = vec![false; t.num_vertices()];
    for &f in faces {
        for &v in t.face_vertices(f as usize) {
            if !done[v as usize] {
                done[v as usize] = true;
                lv.tags[v as usize] = VTag::of(t, v as usize, false);
            }
        }
    }
}

/// The faces within `n` rings of `faces`.
fn rings(t: &Topology, faces: &[u32], n: usize) -> Vec<bool> {
    let mut m = vec![false; t.num_faces()];
    for &f in faces {
        m[f as usize] = true;
    }
    if n == 0 {
        return m;
    }
    // The first ring from the faces themselves, further rings from the whole selection.
    let mut vmark = vec![false; t.num_vertices()];
    for &f in faces {
        for &v in t.face_vertices(f as usize) {
            if !vmark[v as usize] {
                vmark[v as usize] = true;
                for &g in t.vertex_faces(v as usize) {
                    m[g as usize] = true;
                }
            }
        }
    }
    (1..n).fold(m, |m, _| ring(t, &m))
}

/// The faces sharing a vertex with a face of `sel`.
fn ring(t: &Topology, sel: &[bool]) -> Vec<bool> {
    let mut vmark = vec![false; t.num_vertices()];
    for f in (0..t.num_faces()).filter(|&f| sel[f]) {
        for &v in t.face_vertices(f) {
            vmark[v as usize] = true;
        }
    }
    let mut out = sel.to_vec();
    for v in (0..t.num_vertices()).filter(|&v| vmark[v]) {
        for &g in t.vertex_faces(v) {
            out[g as usize] = true;
        }
    }
    out
}

/// A sub-mesh of a level and its exactness flags.
struct Step {
    sub: Topology,
    /// Sub-mesh face → level face.
    faces: Vec<u32>,
    /// Sub-mesh vertex → level vertex.
    verts: Vec<u32>,
    /// Per sub-mesh vertex: sound in the level and all its faces kept.
    sound: Vec<bool>,
    /// Per sub-mesh edge: ok in the level and all its faces kept.
    edge_ok: Vec<bool>,
    /// Per sub-mesh vertex: exact in the level.
    exact: Vec<bool>,
    /// Level vertex → sub-mesh vertex and level edge → sub-mesh edge, [`NONE`] outside.
    in_sub: (Vec<u32>, Vec<u32>),
}

impl Step {
    /// The sub-mesh of the faces `keep` of `lv`, with the level's sharpness, tags, rules and
    /// holes on every element whose faces are all kept, and the border treated as a sharp
    /// boundary.
    fn new(lv: &Level, keep: &[bool]) -> Step {
        let s = &lv.topo;
        if keep.iter().all(|&k| k) {
            return Step {
                sub: s.clone(),
                faces: (0..s.num_faces() as u32).collect(),
                verts: (0..s.num_vertices() as u32).collect(),
                sound: lv.sound.clone(),
                edge_ok: lv.edge_ok.clone(),
                exact: lv.exact.clone(),
                in_sub: (
                    (0..s.num_vertices() as u32).collect(),
                    (0..s.num_edges() as u32).collect(),
                ),
            };
        }
        let r = restrict(s, keep);
        let t = &r.sub;
        let mut edge_ok = vec![false; r.edges.len()];
        for (e, &se) in r.edges.iter().enumerate() {
            if t.edge_faces(e).len() == s.edge_faces(se as usize).len() {
                edge_ok[e] = lv.edge_ok[se as usize];
            }
        }
        let mut sound = vec![false; r.verts.len()];
        let mut exact = vec![false; r.verts.len()];
        for (v, &sv) in r.verts.iter().enumerate() {
            let sv = sv as usize;
            exact[v] = lv.exact[sv];
            if t.vertex_faces(v).len() == s.vertex_faces(sv).len() {
                sound[v] = lv.sound[sv];
            }
        }
        let Restricted {
            sub: t,
            faces,
            verts,
            in_sub,
            ..
        } = r;
        Step {
            sub: t,
            faces,
            verts,
            sound,
            edge_ok,
            exact,
            in_sub,
        }
    }

    /// Exactness flags of the child level `c` (one refinement step of the sub-mesh).
    fn propagate(&self, c: &mut Level) {
        let p = &self.sub;
        let (nv, nf, ne, nc) = (
            p.num_vertices(),
            p.num_faces(),
            p.num_edges(),
            p.num_corners(),
        );
        let chaikin = p.options.crease_method == CreaseMethod::Chaikin;
        let face_exact = |f: usize| p.face_vertices(f).iter().all(|&v| self.exact[v as usize]);
        let fexact: Vec<bool> = (0..nf).map(face_exact).collect();
        for v in 0..nv {
            c.sound[v] = self.sound[v];
            c.exact[v] = self.sound[v]
                && self.exact[v]
                && p.vertex_faces(v).iter().all(|&f| fexact[f as usize]);
        }
        // Face points (quad split only), then edge points.
        let face_points = match is_loop(p) {
            true => 0,
            false => nf,
        };
        for f in 0..face_points {
            c.sound[nv + f] = true;
            c.exact[nv + f] = fexact[f];
        }
        let ev = nv + face_points;
        for e in 0..ne {
            let [a, b] = p.edge_verts[e];
            let half_ok = |x: u32| self.edge_ok[e] && (!chaikin || self.sound[x as usize]);
            let (ha, hb) = (half_ok(a), half_ok(b));
            c.edge_ok[nc + 2 * e] = ha;
            c.edge_ok[nc + 2 * e + 1] = hb;
            c.sound[ev + e] = self.edge_ok[e] && ha && hb;
            c.exact[ev + e] =
                self.edge_ok[e] && p.edge_faces(e).iter().all(|&f| fexact[f as usize]);
        }
    }
}

/// The faces `keep` of `s` as a mesh of their own ([`restrict`]).
pub(crate) struct Restricted {
    /// The sub-mesh: the level's relations restricted to the kept faces (the rings of
    /// complete elements in the level's order), its border an infinitely sharp boundary.
    pub sub: Topology,
    /// Sub-mesh face → level face.
    pub faces: Vec<u32>,
    /// Sub-mesh vertex → level vertex.
    pub verts: Vec<u32>,
    /// Sub-mesh edge → level edge.
    pub edges: Vec<u32>,
    /// Level vertex → sub-mesh vertex and level edge → sub-mesh edge, [`NONE`] outside.
    pub in_sub: (Vec<u32>, Vec<u32>),
}

/// The sub-mesh of the faces `keep` of `s`, with the level's sharpness, tags, rules and
/// holes on every element whose faces are all kept, and the border made an infinitely sharp
/// boundary (its edges) of infinitely sharp non-manifold corners (its vertices,
/// [`border_vertex`]).
pub(crate) fn restrict(s: &Topology, keep: &[bool]) -> Restricted {
    let faces: Vec<u32> = (0..s.num_faces() as u32)
        .filter(|&f| keep[f as usize])
        .collect();
    let mut fmap = vec![NONE; s.num_faces()];
    for (m, &f) in faces.iter().enumerate() {
        fmap[f as usize] = m as u32;
    }
    let (mut vmap, mut emap) = (vec![NONE; s.num_vertices()], vec![NONE; s.num_edges()]);
    // Capacities: about one vertex and two edges per quad, each edge in two faces.
    let nc: usize = faces.iter().map(|&f| s.face_size(f as usize)).sum();
    let (mut verts, mut edges) = (Vec::with_capacity(nc / 2), Vec::with_capacity(nc));
    let mut face_offsets = Vec::with_capacity(faces.len() + 1);
    let (mut face_verts, mut face_edges) = (Vec::with_capacity(nc), Vec::with_capacity(nc));
    face_offsets.push(0u32);
    let take = |map: &mut [u32], list: &mut Vec<u32>, x: u32| -> u32 {
        if map[x as usize] == NONE {
            map[x as usize] = list.len() as u32;
            list.push(x);
        }
        map[x as usize]
    };
    for &f in &faces {
        let r = s.face_offsets[f as usize] as usize..s.face_offsets[f as usize + 1] as usize;
        for c in r {
            face_verts.push(take(&mut vmap, &mut verts, s.face_verts[c]));
            face_edges.push(take(&mut emap, &mut edges, s.face_edges[c]));
        }
        face_offsets.push(face_verts.len() as u32);
    }
    // Every relation is the level's, restricted to the kept faces: elements whose faces
    // are all kept keep their exact rings (order included).
    let mut edge_face_offsets = Vec::with_capacity(edges.len() + 1);
    edge_face_offsets.push(0u32);
    let (mut edge_faces, mut edge_face_local) =
        (Vec::with_capacity(nc + 8), Vec::with_capacity(nc + 8));
    for &e in &edges {
        for (&f, &l) in s
            .edge_faces(e as usize)
            .iter()
            .zip(s.edge_faces_local(e as usize))
        {
            if fmap[f as usize] != NONE {
                edge_faces.push(fmap[f as usize]);
                edge_face_local.push(l);
            }
        }
        edge_face_offsets.push(edge_faces.len() as u32);
    }
    let mut vert_face_offsets = Vec::with_capacity(verts.len() + 1);
    vert_face_offsets.push(0u32);
    let (mut vert_faces, mut vert_face_local) =
        (Vec::with_capacity(nc + 8), Vec::with_capacity(nc + 8));
    let mut vert_edge_offsets = Vec::with_capacity(verts.len() + 1);
    vert_edge_offsets.push(0u32);
    let mut vert_edges = Vec::with_capacity(2 * edges.len() + 8);
    for &v in &verts {
        let v = v as usize;
        for (&f, &l) in s.vertex_faces(v).iter().zip(s.vertex_faces_local(v)) {
            if fmap[f as usize] != NONE {
                vert_faces.push(fmap[f as usize]);
                vert_face_local.push(l);
            }
        }
        vert_face_offsets.push(vert_faces.len() as u32);
        vert_edges.extend(
            s.vertex_edges(v)
                .iter()
                .filter(|&&e| emap[e as usize] != NONE)
                .map(|&e| emap[e as usize]),
        );
        vert_edge_offsets.push(vert_edges.len() as u32);
    }
    let mut t = Topology {
        options: s.options,
        num_vertices: verts.len(),
        face_offsets,
        face_verts,
        face_edges,
        edge_verts: edges
            .iter()
            .map(|&e| s.edge_verts[e as usize].map(|v| vmap[v as usize]))
            .collect(),
        edge_face_offsets,
        edge_faces,
        edge_face_local,
        vert_face_offsets,
        vert_faces,
        vert_face_local,
        vert_edge_offsets,
        vert_edges,
        edge_sharpness: edges
            .iter()
            .map(|&e| s.edge_sharpness[e as usize])
            .collect(),
        vert_sharpness: verts
            .iter()
            .map(|&v| s.vert_sharpness[v as usize])
            .collect(),
        face_is_hole: faces.iter().map(|&f| s.face_is_hole[f as usize]).collect(),
        edge_tags: edges.iter().map(|&e| s.edge_tags[e as usize]).collect(),
        vert_tags: verts.iter().map(|&v| s.vert_tags[v as usize]).collect(),
        vert_rule: verts.iter().map(|&v| s.vert_rule[v as usize]).collect(),
    };
    for (e, &se) in edges.iter().enumerate() {
        let se = se as usize;
        if t.edge_faces(e).len() != s.edge_faces(se).len() {
            let mut tag = (t.edge_tags[e] & tags::E_NON_MANIFOLD) | tags::E_INF_SHARP;
            if t.edge_faces(e).len() < 2 {
                tag |= tags::E_BOUNDARY;
            }
            t.edge_tags[e] = tag;
            t.edge_sharpness[e] = SHARPNESS_INFINITE;
        }
    }
    for (v, &sv) in verts.iter().enumerate() {
        if t.vertex_faces(v).len() != s.vertex_faces(sv as usize).len() {
            border_vertex(&mut t, v);
        }
    }
    Restricted {
        sub: t,
        faces,
        verts,
        edges,
        in_sub: (vmap, emap),
    }
}

/// Tags of a vertex on the sub-mesh's border: made an infinitely sharp non-manifold corner
/// (its value is never used; its child is the identity of it whatever its ring), tagged from
/// its sub-mesh ring as OpenSubdiv tags a base vertex.
pub(super) fn border_vertex(t: &mut Topology, v: usize) {
    let (mut boundary, mut inf, mut semi) = (0usize, 0usize, 0usize);
    for &e in t.vertex_edges(v) {
        let et = t.edge_tags[e as usize];
        boundary += (et & tags::E_BOUNDARY != 0) as usize;
        inf += (et & tags::E_INF_SHARP != 0) as usize;
        semi += (et & tags::E_SEMI_SHARP != 0) as usize;
    }
    let (nfaces, nedges) = (t.vertex_faces(v).len(), t.vertex_edges(v).len());
    // Its ring is a fragment, not an ordered fan.
    let mut vt = tags::V_NON_MANIFOLD | tags::V_INF_SHARP;
    if semi > 0 {
        vt |= tags::V_SEMI_SHARP_EDGES;
    }
    if inf > 0 {
        vt |= tags::V_INF_SHARP_EDGES;
    }
    if boundary > 0 {
        vt |= tags::V_BOUNDARY;
    }
    if nfaces == 1 && nedges == 2 {
        vt |= tags::V_CORNER;
    } else if (boundary > 0 && nfaces != 2) || (boundary == 0 && nfaces != 4) {
        vt |= tags::V_XORDINARY;
    }
    if t.vertex_faces(v)
        .iter()
        .any(|&f| t.face_is_hole[f as usize])
    {
        vt |= tags::V_INCIDENT_HOLE;
    }
    t.vert_tags[v] = vt;
    t.vert_sharpness[v] = SHARPNESS_INFINITE;
    t.vert_rule[v] = rule::CORNER;
}
