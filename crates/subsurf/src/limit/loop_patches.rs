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
//! The levels are uniform refinements ([`crate::refine::refine_tri_topology`]): the isolation walks
//! each base triangle's tree of children (child `k` of face `f` is face `4 f + k`, child 3
//! the middle one) through the refined faces.

use super::budget::tri_child_level_bytes;
use super::features::{
    inf_sharp_vtag_has_features, FeatureMask, VTag, T_BOUNDARY, T_INF_SHARP, T_INF_SHARP_EDGES,
    T_NON_MANIFOLD, T_SEMI_SHARP, T_SEMI_SHARP_EDGES, T_XORDINARY,
};
use super::table::MAX_ISOLATION_LEVEL;
use crate::error::{Error, Result};
use crate::options::Scheme;
use crate::refine::refine_tri_topology;
use crate::topology::tags::{self, rule};
use crate::topology::Topology;
use crate::util::budget::check;

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
    /// Refinement level of the patch (the index into [`LoopLeaves::levels`]).
    pub depth: usize,
    /// The face of that level.
    pub face: u32,
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

/// The levels refined for isolation and the leaves, base face by base face (each base
/// face's leaves in depth-first order of its tree).
#[derive(Debug, Clone)]
pub struct LoopLeaves {
    /// Level 0 (the base) and every uniformly refined level the walk reached.
    pub levels: Vec<Topology>,
    /// Every leaf.
    pub leaves: Vec<LoopLeaf>,
}

/// The leaves of the feature-adaptive isolation of `base` at `isolation_level`.
pub fn loop_leaves(base: &Topology, isolation_level: u32) -> Result<LoopLeaves> {
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
    let level = isolation_level as usize;
    let mut levels = vec![base.clone()];
    let mut decided = Vec::new();
    // `front`: (face, U, V, base face) of the faces of the current level the walk reaches.
    let mut front: Vec<(u32, u16, u16, u32)> = (0..base.num_faces() as u32)
        .filter(|&f| !base.face_is_hole[f as usize])
        .map(|f| (f, 0, 0, f))
        .collect();
    for d in 0..=level {
        let topo = &levels[d];
        let tags: Vec<VTag> = (0..topo.num_vertices())
            .map(|v| VTag::of(topo, v, false))
            .collect();
        let mut next = Vec::new();
        for &(f, u, v, b) in &front {
            let fi = f as usize;
            if d < level && tri_face_has_features(topo, &tags, fi, d) {
                let side = 2u16 << d;
                next.extend([
                    (4 * f, 2 * u, 2 * v, b),
                    (4 * f + 1, 2 * u + 1, 2 * v, b),
                    (4 * f + 2, 2 * u, 2 * v + 1, b),
                    (4 * f + 3, side - 2 * u - 1, side - 2 * v - 1, b),
                ]);
                decided.push((d, f, u, v, b, None));
            } else {
                let regular = is_tri_patch_regular(topo, &tags, fi);
                decided.push((d, f, u, v, b, Some(regular)));
            }
        }
        if next.is_empty() {
            break;
        }
        // Refused up front, with the estimate, before any level is allocated: the isolation
        // refines every level whole (each four times the last), and a feature found at the
        // base (an extraordinary vertex, a boundary, a crease) is met again at every level
        // down to `level`, so all of them are counted at once.
        if d == 0 {
            let faces = base.num_faces() as u64;
            let total = (1..=level as u32).fold(0u64, |sum, k| {
                sum.saturating_add(tri_child_level_bytes(faces << (2 * (k - 1))))
            });
            check(total as f64, || {
                format!(
                    "isolating the Loop features of {faces} triangles to level {isolation_level} \
                     ({} triangles at the last level)",
                    faces << (2 * level)
                )
            })?;
        }
        let child = refine_tri_topology(topo)?;
        levels.push(child);
        front = next;
    }
    // Depth-first order per base face: sort the leaves by base face, then by their path.
    let mut leaves: Vec<LoopLeaf> = decided
        .into_iter()
        .filter_map(|(depth, face, u, v, base_face, regular)| {
            regular.map(|regular| LoopLeaf {
                depth,
                face,
                uv: (u, v),
                base_face,
                regular,
            })
        })
        .collect();
    leaves.sort_by_key(|l| (l.base_face, path_key(l)));
    Ok(LoopLeaves { levels, leaves })
}

/// A key ordering leaves depth-first: the child index at each depth, from the face index
/// (child `k` of face `f` is `4 f + k`), padded to the maximum depth.
fn path_key(l: &LoopLeaf) -> u64 {
    let mut key = 0u64;
    let mut f = l.face as u64;
    for _ in 0..l.depth {
        key = (key >> 2) | ((f & 3) << 62);
        f >>= 2;
    }
    key
}

/// Counts the patches of the feature-adaptive Loop patch table of `base` at
/// `isolation_level` (`0..=10`).
pub fn loop_patch_counts(base: &Topology, isolation_level: u32) -> Result<LoopPatchCounts> {
    let l = loop_leaves(base, isolation_level)?;
    let mut counts = LoopPatchCounts {
        by_depth: vec![0; isolation_level as usize + 1],
        ..Default::default()
    };
    for leaf in &l.leaves {
        if leaf.regular {
            counts.regular += 1;
        } else {
            counts.irregular += 1;
        }
        counts.by_depth[leaf.depth] += 1;
    }
    Ok(counts)
}
