//! Face-varying value topology of one level (OpenSubdiv `Vtr::FVarLevel` semantics): which
//! distinct values ("siblings") each vertex carries, which edges are seams, and how each
//! value is to be refined.
//!
//! At the base level the topology is derived from the per-corner value indices: around a
//! vertex, corners that share an index share a value, and an edge is a *seam* (discontinuous)
//! where its two faces disagree on the value at either end. A seam acts as an infinitely sharp
//! crease for the face-varying data only. Each value of a vertex touching a seam (or a
//! boundary, depending on the mode) is classified from the *span* of faces that carry it:
//!
//! - a **corner** (interpolated by copying the parent value): spans that are disjoint (the
//!   value is interrupted by a seam or an infinitely sharp edge), single-face spans when the
//!   mode sharpens corners, and every value of infinitely sharp or non-manifold vertices;
//!   with linear boundaries (`Boundaries`, `All`) every value on a seam or boundary;
//! - a **crease** (the crease rule `3/4 v + 1/8 (a + b)` over the values `a`, `b` across the
//!   two seam edges bounding the span): other spans;
//! - a **semi-sharp** value: a span containing semi-sharp edges (or a semi-sharp vertex),
//!   kept as a corner until the sharpness decays, then blended into a crease by the
//!   fractional weight (DeRose, Kass & Truong 1998);
//! - with `CornersPlus1` / `CornersPlus2`, a vertex with more than two values is a corner
//!   for all of them, and of two values a semi-sharp one makes the other *dependent*
//!   semi-sharp; `CornersPlus2` also sharpens both when one is a single-face corner and
//!   sharpens darts.
//!
//! Values of vertices with no seam or boundary treatment keep the vertex's own rule of the
//! scheme (Catmull-Clark or Loop). Child levels are not re-analysed: the classification is
//! propagated through the child numbering of [`super::refine_topology`] or
//! [`super::refine_tri_topology`] (vertex children keep their parent's values, each child
//! face the sibling of the parent corner it comes from; an edge point on a seam gets one
//! value per incident face; face points get one value).

use crate::error::{MeshError, Result};
use crate::options::FVarLinearInterpolation as Mode;
use crate::topology::tags;
use crate::topology::Topology;

/// Value tag bit: the value's topology differs from the vertex's (seam, boundary treatment).
pub const V_MISMATCH: u8 = 1;
/// Value tag bit: the value is a smooth crease along the seam (else a corner).
pub const V_CREASE: u8 = 2;
/// Value tag bit: a corner until the semi-sharp features of its span decay.
pub const V_SEMI_SHARP: u8 = 4;
/// Value tag bit: semi-sharp because the vertex's other value is.
pub const V_DEP_SHARP: u8 = 8;

/// Edge tag bit: a seam (the faces disagree on a value at one end at least).
pub const E_MISMATCH: u8 = 1;
/// Edge tag bit: the edge's point is interpolated linearly (seams and boundaries with
/// linear boundaries).
pub const E_LINEAR: u8 = 2;

/// Face-varying topology of one level.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FVarTopology {
    /// The interpolation mode.
    pub mode: Mode,
    /// Number of values this level's data has (the inputs of the next level's stencils).
    pub num_values: usize,
    /// One value index per face corner.
    pub corner_values: Vec<u32>,
    /// `V + 1` offsets into the per-sibling arrays below.
    pub vert_value_offsets: Vec<u32>,
    /// Value index of each sibling (identity after the base level).
    pub vert_values: Vec<u32>,
    /// Sibling of each vertex-face incidence, parallel to [`Topology::vert_faces`].
    pub vert_face_siblings: Vec<u16>,
    /// Tags of each sibling (`V_*`).
    pub value_tags: Vec<u8>,
    /// Ring positions of the first and last face of each crease value's span.
    pub crease_ends: Vec<[u16; 2]>,
    /// Tags of each edge (`E_*`).
    pub edge_tags: Vec<u8>,
}

/// What a mode implies (OpenSubdiv `FVarLevel::completeTopologyFromFaceValues`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ModeRules {
    pub linear_boundaries: bool,
    pub dependent: bool,
    pub corners_sharp: bool,
    pub make_smooth_corners_sharp: bool,
    pub sharpen_both_if_one_corner: bool,
    pub sharpen_darts: bool,
}

impl ModeRules {
    pub(crate) fn new(mode: Mode, t: &Topology) -> ModeRules {
        let linear_boundaries = matches!(mode, Mode::All | Mode::Boundaries);
        let both = mode == Mode::CornersPlus2;
        let geom_corners_smooth =
            t.options.boundary != crate::options::BoundaryInterpolation::EdgeAndCorner;
        ModeRules {
            linear_boundaries,
            dependent: matches!(mode, Mode::CornersPlus1 | Mode::CornersPlus2),
            corners_sharp: mode != Mode::None,
            make_smooth_corners_sharp: geom_corners_smooth && mode != Mode::None,
            sharpen_both_if_one_corner: both,
            sharpen_darts: both || linear_boundaries,
        }
    }
}

/// Span of faces carrying one value around a vertex.
#[derive(Debug, Clone, Copy, Default)]
struct Span {
    size: u16,
    start: u16,
    /// Seams inside the span, plus one per time the value's faces resume after another
    /// value (a disjoint, "bowtie" value).
    discts: u16,
    semi_sharp: u16,
    inf_sharp: u16,
}

impl FVarTopology {
    /// Analyses the base level from one value index per face corner (`indices`, into
    /// `num_values` values).
    pub fn new(t: &Topology, indices: &[u32], num_values: usize, mode: Mode) -> Result<Self> {
        if indices.len() != t.num_corners() {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "{} indices for {} face corners",
                    indices.len(),
                    t.num_corners()
                ),
            }
            .into());
        }
        if let Some((c, &i)) = indices
            .iter()
            .enumerate()
            .find(|(_, &i)| i as usize >= num_values)
        {
            return Err(MeshError::FaceVarying {
                reason: format!("index {i} of corner {c} is out of range ({num_values} values)"),
            }
            .into());
        }
        let r = ModeRules::new(mode, t);
        let nv = t.num_vertices();
        let mut mismatch = vec![false; nv];
        let mut edge_tags = vec![0u8; t.num_edges()];
        let mut vert_face_siblings = vec![0u16; t.vert_faces.len()];
        let mut offsets = Vec::with_capacity(nv + 1);
        offsets.push(0u32);
        let mut vals: Vec<u32> = Vec::new();
        let mut unique: Vec<u32> = Vec::new();
        let corner = |f: u32, k: u16| indices[t.face_offsets[f as usize] as usize + k as usize];

        // Pass 1: seams, mismatched vertices, siblings.
        for v in 0..nv {
            let faces = t.vertex_faces(v);
            let local = t.vertex_faces_local(v);
            let edges = t.vertex_edges(v);
            vals.clear();
            vals.extend(faces.iter().zip(local).map(|(&f, &k)| corner(f, k)));
            let vt = t.vert_tags[v];
            let boundary = vt & tags::V_BOUNDARY != 0;
            let mark = |e: u32, edge_tags: &mut [u8], mismatch: &mut [bool]| {
                let ev = t.edge_verts[e as usize];
                mismatch[ev[0] as usize] = true;
                mismatch[ev[1] as usize] = true;
                edge_tags[e as usize] = E_MISMATCH | if r.linear_boundaries { E_LINEAR } else { 0 };
            };
            if vt & tags::V_NON_MANIFOLD == 0 {
                for i in boundary as usize..faces.len() {
                    let prev = if i == 0 { faces.len() - 1 } else { i - 1 };
                    if vals[i] != vals[prev] {
                        mark(edges[i], &mut edge_tags, &mut mismatch);
                    }
                }
            } else if !faces.is_empty() {
                for &e in edges {
                    let ef = t.edge_faces(e as usize);
                    if ef.len() < 2 {
                        continue;
                    }
                    let el = t.edge_faces_local(e as usize);
                    let value_in = |j: usize| {
                        let f = ef[j] as usize;
                        let (s, n) = (t.face_offsets[f] as usize, t.face_size(f));
                        let k = el[j] as usize;
                        let k = if t.face_verts[s + k] == v as u32 {
                            k
                        } else {
                            (k + 1) % n
                        };
                        indices[s + k]
                    };
                    let v0 = value_in(0);
                    if (1..ef.len()).any(|j| value_in(j) != v0) {
                        mark(e, &mut edge_tags, &mut mismatch);
                    }
                }
            }
            if boundary && !mismatch[v] {
                if r.linear_boundaries && !faces.is_empty() {
                    mismatch[v] = true;
                    if vt & tags::V_NON_MANIFOLD == 0 {
                        edge_tags[edges[0] as usize] |= E_LINEAR;
                        edge_tags[edges[edges.len() - 1] as usize] |= E_LINEAR;
                    } else {
                        for &e in edges {
                            if t.edge_tags[e as usize] & tags::E_BOUNDARY != 0 {
                                edge_tags[e as usize] |= E_LINEAR;
                            }
                        }
                    }
                } else if faces.len() == 1 && r.make_smooth_corners_sharp {
                    mismatch[v] = true;
                }
            }
            // Siblings, numbered in ring order. As OpenSubdiv does, a value that differs from
            // its predecessor while two values are known is compared with the first only, so
            // a value recurring after a third one gets an extra sibling of its own.
            unique.clear();
            let sib = &mut vert_face_siblings[t.vert_face_offsets[v] as usize..];
            for (i, &x) in vals.iter().enumerate() {
                sib[i] = if i == 0 {
                    unique.push(x);
                    0
                } else if x == vals[i - 1] {
                    sib[i - 1]
                } else if unique.len() == 1 || (unique.len() == 2 && unique[0] != x) {
                    unique.push(x);
                    (unique.len() - 1) as u16
                } else if let Some(k) = unique.iter().position(|&u| u == x) {
                    k as u16
                } else {
                    unique.push(x);
                    (unique.len() - 1) as u16
                };
            }
            // Several values meeting at a non-manifold vertex without a seam between them.
            if vt & tags::V_NON_MANIFOLD != 0 && unique.len() > 1 {
                mismatch[v] = true;
            }
            let count = unique.len().max(1) as u32;
            offsets.push(offsets[v] + count);
        }

        let total = offsets[nv] as usize;
        let mut f = FVarTopology {
            mode,
            num_values,
            corner_values: indices.to_vec(),
            vert_value_offsets: offsets,
            vert_values: vec![0; total],
            vert_face_siblings,
            value_tags: vec![0; total],
            crease_ends: vec![[0, 0]; total],
            edge_tags,
        };

        // Pass 2: values of each vertex and their classification.
        let mut spans: Vec<Span> = Vec::new();
        for v in 0..nv {
            let faces = t.vertex_faces(v);
            let local = t.vertex_faces_local(v);
            let o = f.vert_value_offsets[v] as usize;
            let count = f.vert_value_offsets[v + 1] as usize - o;
            if let (Some(&f0), Some(&k0)) = (faces.first(), local.first()) {
                f.vert_values[o] = corner(f0, k0);
            }
            if !mismatch[v] {
                continue;
            }
            let sib = &f.vert_face_siblings[t.vert_face_offsets[v] as usize..];
            let mut next = 1usize;
            for i in 1..faces.len() {
                if sib[i] as usize == next {
                    f.vert_values[o + next] = corner(faces[i], local[i]);
                    next += 1;
                }
            }
            let vt = t.vert_tags[v];
            let boundary = vt & tags::V_BOUNDARY != 0;
            let mut all_corners = r.linear_boundaries
                || vt & (tags::V_INF_SHARP | tags::V_NON_MANIFOLD) != 0
                || (r.dependent && count > 2)
                || (r.sharpen_darts && count == 1 && !boundary);
            spans.clear();
            spans.resize(count, Span::default());
            f.gather_spans(t, v, &mut spans);
            let mut dependent = false;
            if !all_corners && r.dependent && count == 2 {
                all_corners = spans.iter().any(|s| s.inf_sharp > 0 || s.discts > 0);
                if r.sharpen_both_if_one_corner {
                    all_corners |= spans[0].size == 1 || spans[1].size == 1;
                }
                dependent = (spans[0].semi_sharp > 0) != (spans[1].semi_sharp > 0);
            }
            let nf = faces.len() as u16;
            for (i, s) in spans.iter().enumerate() {
                f.value_tags[o + i] = V_MISMATCH;
                let corner = all_corners
                    || s.discts > 0
                    || s.inf_sharp > 0
                    || (s.size == 1 && r.corners_sharp);
                if corner {
                    continue;
                }
                f.value_tags[o + i] = if s.semi_sharp > 0 || vt & tags::V_SEMI_SHARP != 0 {
                    V_MISMATCH | V_SEMI_SHARP
                } else if dependent {
                    V_MISMATCH | V_SEMI_SHARP | V_DEP_SHARP
                } else {
                    V_MISMATCH | V_CREASE
                };
                let last = s.start.wrapping_add(s.size).wrapping_sub(1);
                let end = if i == 0 && s.start != 0 {
                    last.wrapping_sub(nf)
                } else {
                    last
                };
                f.crease_ends[o + i] = [s.start, end];
            }
        }
        Ok(f)
    }

    /// Size, start and interruptions of the span of faces of each value of `v`
    /// (OpenSubdiv `FVarLevel::gatherValueSpans`).
    fn gather_spans(&self, t: &Topology, v: usize, spans: &mut [Span]) {
        let edges = t.vertex_edges(v);
        let faces = t.vertex_faces(v);
        let sib = &self.vert_face_siblings[t.vert_face_offsets[v] as usize..][..faces.len()];
        let boundary = edges.len() > faces.len();
        let seam = |e: u32| self.edge_tags[e as usize] & E_MISMATCH != 0;
        // Counts a seam, infinitely sharp or semi-sharp edge inside a span.
        let count = |s: &mut Span, e: u32| {
            let et = t.edge_tags[e as usize];
            if seam(e) {
                s.discts = s.discts.wrapping_add(1);
            } else if et & tags::E_INF_SHARP != 0 {
                s.inf_sharp += 1;
            } else if et & tags::E_SEMI_SHARP != 0 {
                s.semi_sharp += 1;
            }
        };
        if t.vert_tags[v] & tags::V_NON_MANIFOLD != 0 {
            for s in spans.iter_mut() {
                s.discts = 1;
            }
            return;
        }
        let n = faces.len();
        if spans.len() == 1 && !boundary {
            // A dart in the data: one seam edge starts the span; a second one splits it.
            let s = &mut spans[0];
            let mut started = false;
            for (i, &e) in edges.iter().enumerate() {
                if seam(e) {
                    if started {
                        s.discts = 1;
                        break;
                    }
                    started = true;
                    s.start = i as u16;
                } else {
                    count(s, e);
                }
            }
            s.size = n as u16;
            return;
        }
        if n == 0 {
            return;
        }
        spans[0].size = 1;
        let wraps = !boundary && sib[n - 1] == 0;
        if wraps {
            count(&mut spans[0], edges[0]);
        }
        for i in 1..n {
            let s = &mut spans[sib[i] as usize];
            if sib[i] == sib[i - 1] {
                count(s, edges[i]);
            } else {
                if s.size > 0 {
                    s.discts = s.discts.wrapping_add(1);
                }
                s.start = i as u16;
            }
            s.size += 1;
        }
        if wraps {
            spans[0].discts = spans[0].discts.wrapping_sub(1);
        }
    }

    /// The value indices of `v`'s siblings.
    pub fn vertex_values(&self, v: usize) -> &[u32] {
        &self.vert_values
            [self.vert_value_offsets[v] as usize..self.vert_value_offsets[v + 1] as usize]
    }

    /// The tags of `v`'s siblings.
    pub fn vertex_value_tags(&self, v: usize) -> &[u8] {
        &self.value_tags
            [self.vert_value_offsets[v] as usize..self.vert_value_offsets[v + 1] as usize]
    }

    /// Number of values of `v`.
    pub fn num_vertex_values(&self, v: usize) -> usize {
        (self.vert_value_offsets[v + 1] - self.vert_value_offsets[v]) as usize
    }

    /// The values at the two ends of edge `e` as seen from its `i`-th face.
    pub fn edge_face_values(&self, t: &Topology, e: usize, i: usize) -> [u32; 2] {
        let f = t.edge_faces(e)[i] as usize;
        let k = t.edge_faces_local(e)[i] as usize;
        let (s, n) = (t.face_offsets[f] as usize, t.face_size(f));
        [
            self.corner_values[s + k],
            self.corner_values[s + if k + 1 == n { 0 } else { k + 1 }],
        ]
    }

    /// The value at the far end of each edge of `v` (continuous across the edge), in
    /// [`Topology::vertex_edges`] order.
    pub fn vertex_edge_values(&self, t: &Topology, v: usize, out: &mut Vec<u32>) {
        out.clear();
        let edges = t.vertex_edges(v);
        let faces = t.vertex_faces(v);
        let local = t.vertex_faces_local(v);
        let manifold = t.vert_tags[v] & tags::V_NON_MANIFOLD == 0;
        let boundary = t.vert_tags[v] & tags::V_BOUNDARY != 0;
        for (i, &e) in edges.iter().enumerate() {
            let w = t.other_vertex(e as usize, v as u32) as usize;
            if self.num_vertex_values(w) == 1 {
                out.push(self.vertex_values(w)[0]);
            } else if manifold {
                let (f, k, next) = if boundary && i + 1 == edges.len() {
                    (faces[i - 1] as usize, local[i - 1] as usize, false)
                } else {
                    (faces[i] as usize, local[i] as usize, true)
                };
                let (s, n) = (t.face_offsets[f] as usize, t.face_size(f));
                let c = if next { (k + 1) % n } else { (k + n - 1) % n };
                out.push(self.corner_values[s + c]);
            } else {
                let f = t.edge_faces(e as usize)[0] as usize;
                let k = t.edge_faces_local(e as usize)[0] as usize;
                let (s, n) = (t.face_offsets[f] as usize, t.face_size(f));
                let c = if t.face_verts[s + k] as usize == w {
                    k
                } else {
                    (k + 1) % n
                };
                out.push(self.corner_values[s + c]);
            }
        }
    }

    /// The values across the two seam edges bounding the span of sibling `sib` of `v`.
    pub fn crease_end_values(&self, t: &Topology, v: usize, sib: usize) -> [u32; 2] {
        let [a, b] = self.crease_ends[self.vert_value_offsets[v] as usize + sib];
        let faces = t.vertex_faces(v);
        let local = t.vertex_faces_local(v);
        if faces.is_empty() {
            return [self.vertex_values(v)[sib]; 2];
        }
        let at = |p: u16, next: bool| {
            let p = (p as usize).min(faces.len() - 1);
            let f = faces[p] as usize;
            let (s, n) = (t.face_offsets[f] as usize, t.face_size(f));
            let k = local[p] as usize;
            self.corner_values[s + if next { (k + 1) % n } else { (k + n - 1) % n }]
        };
        [at(a, true), at(b, false)]
    }
}
