//! Which faces feature-adaptive refinement isolates, which leaf faces are regular patches, and
//! which are single-crease patches — OpenSubdiv 3.5's rules (`Far::TopologyRefiner`
//! feature selection, `Far::PatchBuilder::IsPatchRegular`, `Vtr::Level::isSingleCreasePatch`;
//! Nießner, Loop, Meyer & DeRose 2012, "Feature-adaptive GPU rendering of Catmull-Clark
//! subdivision surfaces").
//!
//! Every decision is made from per-vertex tags that are combined by bitwise OR over a face's
//! corners. The tags are recomputed from each level's [`Topology`] ([`VTag::of`]); they equal
//! OpenSubdiv's, which propagates them from parent to child.
//!
//! Supported option set: `useInfSharpPatch = false` (infinitely sharp interior features are
//! isolated, and approximated as smooth in the end caps), with or without single-crease
//! patches.

use crate::topology::tags::{self, rule};
use crate::topology::Topology;
use crate::SHARPNESS_INFINITE;

/// OpenSubdiv-style vertex tag bits (`Vtr::internal::Level::VTag`), plus the crease rule in
/// [`VTag::rule`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct VTag {
    /// Bit set of the `T_*` constants.
    pub bits: u16,
    /// Crease rule bits ([`rule`]).
    pub rule: u8,
}

/// On a boundary edge.
pub const T_BOUNDARY: u16 = 1;
/// Non-manifold.
pub const T_NON_MANIFOLD: u16 = 1 << 1;
/// Extraordinary (never set for corners and non-manifold vertices).
pub const T_XORDINARY: u16 = 1 << 2;
/// Sharpened topological corner.
pub const T_CORNER: u16 = 1 << 3;
/// Infinitely sharp vertex.
pub const T_INF_SHARP: u16 = 1 << 4;
/// Semi-sharp vertex.
pub const T_SEMI_SHARP: u16 = 1 << 5;
/// Has semi-sharp edges.
pub const T_SEMI_SHARP_EDGES: u16 = 1 << 6;
/// Has infinitely sharp edges.
pub const T_INF_SHARP_EDGES: u16 = 1 << 7;
/// Its infinitely sharp edges make a crease.
pub const T_INF_SHARP_CREASE: u16 = 1 << 8;
/// Its infinitely sharp features are irregular.
pub const T_INF_IRREGULAR: u16 = 1 << 9;
/// Incident to a non-quad face (base level only).
pub const T_INCID_IRREG_FACE: u16 = 1 << 10;

impl VTag {
    /// The tag of vertex `v` of `t`; `base` says whether `t` is the base level (only there
    /// is incidence to a non-quad face recorded).
    pub fn of(t: &Topology, v: usize, base: bool) -> VTag {
        let vt = t.vert_tags[v];
        let mut bits = 0u16;
        let nonman = vt & tags::V_NON_MANIFOLD != 0;
        let set = |b: &mut u16, on: bool, bit: u16| {
            if on {
                *b |= bit
            }
        };
        set(&mut bits, vt & tags::V_BOUNDARY != 0, T_BOUNDARY);
        set(&mut bits, nonman, T_NON_MANIFOLD);
        set(&mut bits, vt & tags::V_CORNER != 0, T_CORNER);
        set(
            &mut bits,
            vt & tags::V_XORDINARY != 0 && !nonman && vt & tags::V_CORNER == 0,
            T_XORDINARY,
        );
        let s = t.vert_sharpness[v];
        let inf = s >= SHARPNESS_INFINITE;
        set(&mut bits, inf, T_INF_SHARP);
        set(&mut bits, s > 0.0 && !inf, T_SEMI_SHARP);
        let edges = t.vertex_edges(v);
        let mut n_inf = 0usize;
        let mut n_semi = 0usize;
        for &e in edges {
            let es = t.edge_sharpness[e as usize];
            if es >= SHARPNESS_INFINITE {
                n_inf += 1;
            } else if es > 0.0 {
                n_semi += 1;
            }
        }
        set(&mut bits, n_semi > 0, T_SEMI_SHARP_EDGES);
        set(&mut bits, n_inf > 0, T_INF_SHARP_EDGES);
        let mut inf_irregular = inf || n_inf > 0;
        if n_inf > 0 {
            let inf_rule = rule::determine(if inf { s } else { 0.0 }, n_inf);
            if inf_rule == rule::CREASE {
                bits |= T_INF_SHARP_CREASE;
                if bits & (T_XORDINARY | T_NON_MANIFOLD) == 0 {
                    if bits & T_BOUNDARY != 0 {
                        inf_irregular = false;
                    } else if edges.len() == 4 {
                        let sharp =
                            |i: usize| t.edge_sharpness[edges[i] as usize] >= SHARPNESS_INFINITE;
                        inf_irregular = sharp(0) != sharp(2);
                    }
                }
            } else if inf_rule == rule::CORNER && n_inf == edges.len() && (edges.len() > 2 || inf) {
                inf_irregular = false;
            }
        }
        set(&mut bits, inf_irregular, T_INF_IRREGULAR);
        if base {
            let irregular = t
                .vertex_faces(v)
                .iter()
                .any(|&f| t.face_size(f as usize) != 4);
            set(&mut bits, irregular, T_INCID_IRREG_FACE);
        }
        VTag {
            bits,
            rule: t.vert_rule[v],
        }
    }

    pub(crate) fn has(&self, bit: u16) -> bool {
        self.bits & bit != 0
    }

    pub(crate) fn or(tags: &[VTag]) -> VTag {
        tags.iter().fold(VTag::default(), |a, b| VTag {
            bits: a.bits | b.bits,
            rule: a.rule | b.rule,
        })
    }
}

/// Tags of every vertex of one level.
pub fn level_tags(t: &Topology, base: bool) -> Vec<VTag> {
    (0..t.num_vertices())
        .map(|v| VTag::of(t, v, base))
        .collect()
}

/// The feature mask of OpenSubdiv's adaptive refinement for the supported options.
#[derive(Debug, Clone, Copy)]
pub struct FeatureMask {
    semi_sharp_single: bool,
    inf_sharp_regular_crease: bool,
    unisolated_interior_edge: bool,
}

impl FeatureMask {
    /// The mask for `use_single_crease` (and `useInfSharpPatch = false`).
    pub fn new(use_single_crease: bool) -> Self {
        FeatureMask {
            semi_sharp_single: !use_single_crease,
            inf_sharp_regular_crease: !use_single_crease,
            unisolated_interior_edge: use_single_crease,
        }
    }
}

pub(crate) fn inf_sharp_vtag_has_features(c: VTag, m: &FeatureMask) -> bool {
    if c.has(T_INF_IRREGULAR) {
        // Irregular corner, crease (boundary or interior) and dart are all selected.
        c.rule & (rule::CORNER | rule::CREASE | rule::DART) != 0
    } else if c.has(T_BOUNDARY) {
        c.rule & rule::CORNER != 0 && !c.has(T_CORNER)
    } else if c.rule & rule::CORNER != 0 {
        true
    } else {
        m.inf_sharp_regular_crease
    }
}

fn inf_sharp_face_has_features(c: VTag, v: &[VTag; 4], m: &FeatureMask) -> bool {
    if c.rule & rule::SMOOTH != 0 {
        return inf_sharp_vtag_has_features(c, m);
    }
    if m.unisolated_interior_edge
        && v.iter()
            .any(|t| t.has(T_INF_SHARP_EDGES) && !t.has(T_BOUNDARY))
    {
        return true;
    }
    v.iter()
        .any(|t| t.rule & rule::SMOOTH == 0 && inf_sharp_vtag_has_features(*t, m))
}

/// Corner tags of face `f`.
pub fn face_tags(t: &Topology, tags: &[VTag], f: usize) -> [VTag; 4] {
    let mut out = [VTag::default(); 4];
    for (o, &v) in out.iter_mut().zip(t.face_vertices(f)) {
        *o = tags[v as usize];
    }
    out
}

/// Whether adaptive refinement refines face `f` of level `depth`
/// (`doesFaceHaveFeatures`). Holes are never refined (the caller skips them).
pub fn face_has_features(
    t: &Topology,
    tags: &[VTag],
    f: usize,
    depth: usize,
    m: &FeatureMask,
) -> bool {
    if t.face_size(f) != 4 {
        return true;
    }
    let v = face_tags(t, tags, f);
    let c = VTag::or(&v);
    if c.has(T_INCID_IRREG_FACE) {
        return true;
    }
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
        return if single_crease(t, tags, f).is_some() {
            m.semi_sharp_single
        } else {
            true
        };
    }
    if c.has(T_INF_SHARP) || c.has(T_INF_SHARP_EDGES) {
        return inf_sharp_face_has_features(c, &v, m);
    }
    false
}

/// Whether the leaf face `f` is a regular B-spline patch (`IsPatchRegular` with infinitely
/// sharp features approximated as smooth and OpenSubdiv's default
/// `generateLegacySharpCornerPatches`): a quad whose non-manifold corners have regular spans
/// ([`super::span`]) and whose
/// extraordinary corners, if any, are smooth corners — boundary vertices with one face, both
/// of whose face edges are boundary edges — which are treated as sharp corners.
pub fn is_patch_regular(t: &Topology, tags: &[VTag], f: usize) -> bool {
    if t.face_size(f) != 4 {
        return false;
    }
    let v = face_tags(t, tags, f);
    let c = VTag::or(&v);
    if c.has(T_NON_MANIFOLD) {
        // A non-manifold corner is regular when its manifold span is a regular boundary
        // (two faces) or, at an infinitely sharp vertex, a regular corner (one face).
        for k in 0..4 {
            if v[k].has(T_NON_MANIFOLD) {
                let sp = super::span::span(t, f, k);
                let want = if v[k].has(T_INF_SHARP) { 1 } else { 2 };
                if sp.cyclic || sp.faces.len() != want {
                    return false;
                }
            }
        }
    }
    if !c.has(T_XORDINARY) {
        return true;
    }
    let fe = t.face_edges(f);
    let boundary = |k: usize| t.edge_tags[fe[k] as usize] & tags::E_BOUNDARY != 0;
    (0..4).all(|k| {
        !v[k].has(T_XORDINARY)
            || (v[k].has(T_BOUNDARY)
                && !v[k].has(T_INF_SHARP)
                && boundary(k)
                && boundary((k + 3) % 4))
    })
}

/// Whether vertex `v` is a smooth corner that OpenSubdiv's legacy option treats as sharp: a
/// boundary vertex with one face, not itself infinitely sharp.
pub fn is_smooth_corner(t: &Topology, v: usize) -> bool {
    let vt = t.vert_tags[v];
    vt & tags::V_BOUNDARY != 0
        && vt & tags::V_NON_MANIFOLD == 0
        && t.vert_sharpness[v] < SHARPNESS_INFINITE
        && t.vertex_faces(v).len() == 1
}

/// Boundary mask of a regular patch: bit `k` for each boundary or non-manifold edge `k`.
pub fn boundary_mask(t: &Topology, f: usize) -> u8 {
    let mut mask = 0u8;
    for (k, &e) in t.face_edges(f).iter().enumerate() {
        if t.edge_tags[e as usize] & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD) != 0 {
            mask |= 1 << k;
        }
    }
    mask
}

/// `Some((edge in face, sharpness))` when `f` is a regular interior quad whose only sharp
/// feature is one regular crease along edge `k` (`Vtr::Level::isSingleCreasePatch`): two
/// adjacent Crease corners, the other two Smooth, and at each crease corner the opposite
/// edges equally sharp.
pub fn single_crease(t: &Topology, tags: &[VTag], f: usize) -> Option<(usize, f32)> {
    if t.face_size(f) != 4 {
        return None;
    }
    let v = face_tags(t, tags, f);
    let c = VTag::or(&v);
    if c.rule & rule::CREASE == 0
        || c.rule & (rule::CORNER | rule::DART) != 0
        || c.has(T_BOUNDARY)
        || c.has(T_XORDINARY)
        || c.has(T_NON_MANIFOLD)
    {
        return None;
    }
    let mask = (0..4).fold(0usize, |m, i| {
        m | ((v[i].rule == rule::CREASE) as usize) << i
    });
    const EDGE: [i8; 16] = [-1, -1, -1, 0, -1, -1, 1, -1, -1, 3, -1, -1, 2, -1, -1, -1];
    let k = EDGE[mask];
    if k < 0 {
        return None;
    }
    let k = k as usize;
    let fv = t.face_vertices(f);
    for vert in [fv[k], fv[(k + 1) % 4]] {
        let es = t.vertex_edges(vert as usize);
        if es.len() != 4 {
            return None;
        }
        let s = |i: usize| t.edge_sharpness[es[i] as usize];
        if s(0) != s(2) || s(1) != s(3) {
            return None;
        }
    }
    Some((k, t.edge_sharpness[t.face_edges(f)[k] as usize]))
}
