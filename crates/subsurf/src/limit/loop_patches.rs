//! Feature-adaptive isolation for the Loop scheme: which triangles are refined, which leaf
//! triangles are regular quartic box-spline patches and which are irregular (end caps) —
//! OpenSubdiv 3.5's rules for triangles (`Far::TopologyRefiner` feature selection,
//! `Far::PatchBuilder::IsPatchRegular`), with its default options for Loop:
//! `useInfSharpPatch = false`, no single-crease patches (they are quad patches),
//! `generateLegacySharpCornerPatches = true`.
//!
//! The rules are those of [`super::features`] read with Loop's regular valences (6 faces
//! inside, 3 on a boundary, recorded by the topology's extraordinary tag) and three corners
//! per face:
//!
//! - a face is refined when a corner is non-manifold, or extraordinary and smooth (at levels
//!   0 and 1: any extraordinary smooth corner), or has semi-sharp features, or infinitely
//!   sharp features that are not regular (a sharp corner, a crease or dart not continued
//!   regularly); where some corner is smooth and none is on the boundary, the face's
//!   combined tag decides, otherwise each non-smooth corner does;
//! - a leaf face is regular when no corner is extraordinary or non-manifold, except smooth
//!   boundary corners of one face (both face edges at the corner on the boundary), which are
//!   treated as sharp corners, and non-manifold corners whose manifold span is regular.
//!
//! The levels are those of the sparse construction ([`super::sparse`]), built with the
//! triangle split ([`crate::refine::refine_tri_topology`]): level `d + 1` refines only the
//! faces chosen at level `d` and the ring of faces sharing a vertex with them, a sub-mesh
//! whose border is made infinitely sharp. One ring is what the Loop rules need: a patch of
//! a child `c` of a chosen face `f` reads the one-ring of `c`'s corners (the 12 box-spline
//! points, or the Gregory triangle's corner rings), which are children of `f`'s vertices
//! and edge points of the edges at `f`'s vertices; the child of a vertex reads the vertex's
//! neighbours, an edge point its ends and the two vertices opposite it, all vertices of
//! faces around a vertex of `f`, hence in the ring. The exactness flags of
//! [`super::sparse`] check this on every patch: a patch reading a point that is not the
//! uniform refinement's is refused as an internal error. The walk then follows each base
//! triangle's tree of children (the four children of a refined face are consecutive,
//! child 3 the middle one) through the refined faces.

use super::features::{
    inf_sharp_vtag_has_features, FeatureMask, VTag, T_BOUNDARY, T_INF_SHARP, T_INF_SHARP_EDGES,
    T_NON_MANIFOLD, T_SEMI_SHARP, T_SEMI_SHARP_EDGES, T_XORDINARY,
};
use super::leaves::UNWALKED;
use super::loop_endcap::{gregory_tri_points, Row};
use super::loop_eval::{gather_box_spline_points, tri_boundary_mask};
use super::patch_map::{PatchMap, EMPTY, LEAF};
use super::sparse::{self, Hierarchy, Level, Selection};
use super::table::MAX_ISOLATION_LEVEL;
use crate::error::{Error, Result};
use crate::options::Scheme;
use crate::real::Real;
use crate::topology::tags::{self, rule};
use crate::topology::Topology;
use crate::util::budget::Budget;

/// Patch counts of a Loop patch table.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LoopPatchCounts {
    /// Regular quartic box-spline patches (boundary and corner variants included).
    pub regular: usize,
    /// Irregular leaf triangles: Gregory-triangle end caps.
    pub irregular: usize,
    /// Leaf patches per depth (`by_depth[d]` for depth `d`).
    pub by_depth: Vec<usize>,
}

impl LoopPatchCounts {
    /// Total number of patches.
    pub fn total(&self) -> usize {
        self.regular + self.irregular
    }
}

/// Corner tags of triangle `f` (Loop levels are never "base" in the sense of
/// [`VTag::of`]: their faces are all triangles, none is an irregular face).
fn tri_tags(t: &Topology, tags: &[VTag], f: usize) -> [VTag; 3] {
    let fv = t.face_vertices(f);
    [0, 1, 2].map(|k| tags[fv[k] as usize])
}

fn inf_sharp_tri_has_features(c: VTag, v: &[VTag; 3], m: &FeatureMask) -> bool {
    if c.rule & rule::SMOOTH != 0 && !c.has(T_BOUNDARY) {
        return inf_sharp_vtag_has_features(c, m);
    }
    v.iter()
        .any(|t| t.rule & rule::SMOOTH == 0 && inf_sharp_vtag_has_features(*t, m))
}

/// Whether adaptive refinement refines triangle `f` of level `depth`.
pub fn tri_face_has_features(t: &Topology, tags: &[VTag], f: usize, depth: usize) -> bool {
    let v = tri_tags(t, tags, f);
    let c = VTag::or(&v);
    if c.has(T_NON_MANIFOLD) {
        return true;
    }
    if c.has(T_XORDINARY) {
        if c.rule == rule::SMOOTH {
            return true;
        }
        if depth < 2
            && v.iter()
                .any(|t| t.has(T_XORDINARY) && t.rule == rule::SMOOTH)
        {
            return true;
        }
    }
    if c.rule == rule::SMOOTH {
        return false;
    }
    if c.has(T_SEMI_SHARP) || c.has(T_SEMI_SHARP_EDGES) {
        return true;
    }
    if c.has(T_INF_SHARP) || c.has(T_INF_SHARP_EDGES) {
        return inf_sharp_tri_has_features(c, &v, &FeatureMask::new(false));
    }
    false
}

/// Whether the leaf triangle `f` is a regular box-spline patch (see the module
/// documentation).
pub fn is_tri_patch_regular(t: &Topology, tags: &[VTag], f: usize) -> bool {
    let v = tri_tags(t, tags, f);
    let c = VTag::or(&v);
    if c.bits & (T_NON_MANIFOLD | T_XORDINARY) == 0 {
        return true;
    }
    let fe = t.face_edges(f);
    let boundary = |k: usize| t.edge_tags[fe[k] as usize] & tags::E_BOUNDARY != 0;
    (0..3).all(|k| {
        if v[k].has(T_NON_MANIFOLD) {
            let sp = super::span::span(t, f, k);
            let want = if v[k].has(T_INF_SHARP) { 1 } else { 3 };
            return !sp.cyclic && sp.faces.len() == want;
        }
        !v[k].has(T_XORDINARY)
            || (v[k].has(T_INF_SHARP_EDGES)
                && v[k].has(T_BOUNDARY)
                && !v[k].has(T_INF_SHARP)
                && boundary(k)
                && boundary((k + 2) % 3))
    })
}

/// A leaf triangle of the isolation: a patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LoopLeaf {
    /// Refinement level of the patch.
    pub depth: usize,
    /// Its index among the leaves of its level ([`LoopLevel::leaves`]).
    pub index: u32,
    /// Sub-triangle origin in the base face at `depth` (see
    /// [`crate::patch::tri_basis`]): children 0, 1, 2 of `(U, V)` are `(2U, 2V)`,
    /// `(2U + 1, 2V)`, `(2U, 2V + 1)`; the middle child 3 is `(2^(d+1) − 2U − 1, 2^(d+1) − 2V − 1)`,
    /// turned relative to its parent.
    pub uv: (u16, u16),
    /// Base face.
    pub base_face: u32,
    /// A regular box-spline patch (otherwise an end cap).
    pub regular: bool,
}

/// What a leaf face of a level becomes, computed while the level is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LevelLeaf {
    /// A regular box-spline patch (otherwise an end cap).
    pub regular: bool,
    /// Its boundary mask ([`super::loop_eval::tri_boundary_mask`]; 0 for an end cap).
    pub boundary: u8,
    /// Its first point: in [`LoopLevel::cvs`] (12 per regular leaf) or
    /// [`LoopLevel::rows`] (18 per end cap).
    pub first: u32,
}

/// The leaves of one level of the isolation.
#[derive(Debug, Clone, Default)]
pub struct LoopLevel {
    /// Per face of the level: `LEAF | leaf`, its first child face (refined), or
    /// [`UNWALKED`] (not reached by the walk, or a hole).
    pub slot: Vec<u32>,
    /// The leaves, in the order the level's walk decided them.
    pub leaves: Vec<LevelLeaf>,
    /// The 12 box-spline points of every regular leaf (vertices of the level).
    pub cvs: Vec<u32>,
    /// The 18 Gregory-triangle points of every end cap, as stencils over the level's
    /// vertices.
    pub rows: Vec<Row>,
}

/// The levels of the sparse isolation ([`super::sparse`]): their sizes and the stencils
/// between them, and every level's leaves.
#[derive(Debug, Clone)]
pub struct LoopIsolation<W> {
    /// Sizes, stencils and sub-mesh inputs of the levels.
    pub hierarchy: Hierarchy<W>,
    /// The leaves of each level.
    pub levels: Vec<LoopLevel>,
    /// The bytes the levels were estimated at and counted against the memory limit
    /// ([`super::budget::child_level_bytes`]; kept for the tests of the estimate).
    #[cfg(test)]
    pub estimated_bytes: u64,
}

/// The leaves of the faces `faces` of `lv` (level `d`), and with `gather` their points,
/// each checked to be exact.
fn level_leaves(lv: &Level, d: usize, faces: &[u32], gather: bool) -> Result<LoopLevel> {
    let t = &lv.topo;
    let mut out = LoopLevel {
        slot: vec![UNWALKED; t.num_faces()],
        ..Default::default()
    };
    for f in (0..t.num_faces()).filter(|&f| lv.refine[f]) {
        out.slot[f] = lv.child[f];
    }
    let inexact = |f: u32, i: u32| {
        Error::Internal(format!(
            "sparse Loop isolation: patch of face {f} at level {d} reads vertex {i}, \
             which is not exact"
        ))
    };
    for &f in faces {
        let fi = f as usize;
        let regular = is_tri_patch_regular(t, &lv.tags, fi);
        out.slot[fi] = LEAF | out.leaves.len() as u32;
        let (boundary, first) = match regular {
            true => (tri_boundary_mask(t, fi), out.cvs.len() as u32 / 12),
            false => (0, out.rows.len() as u32 / 18),
        };
        out.leaves.push(LevelLeaf {
            regular,
            boundary,
            first,
        });
        if !gather {
            continue;
        }
        if regular {
            let cvs = gather_box_spline_points(t, fi);
            if let Some(&i) = cvs.iter().find(|&&i| !lv.exact[i as usize]) {
                return Err(inexact(f, i));
            }
            out.cvs.extend_from_slice(&cvs);
        } else {
            let rows = gregory_tri_points(t, fi);
            let mut read = rows.iter().flatten().map(|&(i, _)| i);
            if let Some(i) = read.find(|&i| !lv.exact[i as usize]) {
                return Err(inexact(f, i));
            }
            out.rows.extend(rows);
        }
    }
    Ok(out)
}

/// The sparse feature-adaptive isolation of `base` at `isolation_level`: each level refines
/// the faces chosen at the level above and the ring of faces around them
/// ([`super::sparse`]); with `gather`, the points of every leaf.
pub fn loop_isolation<W: Real>(
    base: &Topology,
    isolation_level: u32,
    selection: Selection,
    gather: bool,
) -> Result<LoopIsolation<W>> {
    if base.options.scheme != Scheme::Loop {
        return Err(Error::Unsupported(
            "Loop patches need a mesh with the Loop scheme".into(),
        ));
    }
    if isolation_level > MAX_ISOLATION_LEVEL {
        return Err(Error::Unsupported(format!(
            "isolation level {isolation_level} exceeds the maximum {MAX_ISOLATION_LEVEL}"
        )));
    }
    let mut budget = Budget::of_available_memory();
    let (hierarchy, levels) = sparse::build_traced(
        base,
        isolation_level as usize,
        None,
        &FeatureMask::new(false),
        selection,
        &mut budget,
        &|lv, d, _, faces| level_leaves(lv, d, faces, gather),
        None,
    )?;
    Ok(LoopIsolation {
        hierarchy,
        levels,
        #[cfg(test)]
        estimated_bytes: budget.used(),
    })
}

impl<W> LoopIsolation<W> {
    /// Walks every base face's tree of children depth first (children 0, 1, 2, 3), giving
    /// each leaf to `emit` in that order (the patch order), and returns the patch map.
    pub fn walk(
        &self,
        base: &Topology,
        mut emit: impl FnMut(&LoopLeaf) -> Result<()>,
    ) -> Result<PatchMap> {
        let mut map = PatchMap {
            roots: Vec::with_capacity(base.num_faces()),
            nodes: Vec::new(),
        };
        let mut patches = 0u32;
        for f in 0..base.num_faces() {
            let root = match base.face_is_hole[f] {
                true => EMPTY,
                false => self.visit(&mut map, &mut patches, &mut emit, 0, f, (0, 0), f as u32)?,
            };
            map.roots.push(root);
        }
        Ok(map)
    }

    #[allow(clippy::too_many_arguments)]
    fn visit(
        &self,
        map: &mut PatchMap,
        patches: &mut u32,
        emit: &mut impl FnMut(&LoopLeaf) -> Result<()>,
        d: usize,
        f: usize,
        (u, v): (u16, u16),
        base_face: u32,
    ) -> Result<u32> {
        let slot = self.levels.get(d).map_or(UNWALKED, |l| l.slot[f]);
        if slot == UNWALKED {
            return Err(Error::Internal(format!(
                "face {f} at level {d} is walked but was not decided"
            )));
        }
        if slot & LEAF != 0 {
            let index = slot & !LEAF;
            emit(&LoopLeaf {
                depth: d,
                index,
                uv: (u, v),
                base_face,
                regular: self.levels[d].leaves[index as usize].regular,
            })?;
            *patches += 1;
            return Ok(LEAF | (*patches - 1));
        }
        let node = map.nodes.len();
        map.nodes.push([EMPTY; 4]);
        let side = 2u16 << d;
        let child_uv = [
            (2 * u, 2 * v),
            (2 * u + 1, 2 * v),
            (2 * u, 2 * v + 1),
            (side - 2 * u - 1, side - 2 * v - 1),
        ];
        for (k, &uv) in child_uv.iter().enumerate() {
            let h = self.visit(map, patches, emit, d + 1, slot as usize + k, uv, base_face)?;
            map.nodes[node][k] = h;
        }
        Ok(node as u32)
    }
}

/// Counts the patches of the feature-adaptive Loop patch table of `base` at
/// `isolation_level` (`0..=10`).
pub fn loop_patch_counts(base: &Topology, isolation_level: u32) -> Result<LoopPatchCounts> {
    let l = loop_isolation::<f32>(base, isolation_level, Selection::Sparse, false)?;
    let mut counts = LoopPatchCounts {
        by_depth: vec![0; isolation_level as usize + 1],
        ..Default::default()
    };
    l.walk(base, |leaf| {
        if leaf.regular {
            counts.regular += 1;
        } else {
            counts.irregular += 1;
        }
        counts.by_depth[leaf.depth] += 1;
        Ok(())
    })?;
    Ok(counts)
}
