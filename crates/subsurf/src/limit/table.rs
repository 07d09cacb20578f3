//! The patch table: every non-hole ptex face of the base mesh tiled by bicubic B-spline,
//! single-crease and Gregory end-cap patches, as flat arrays ready for upload.
//!
//! # Construction
//!
//! Feature-adaptive refinement (Nießner, Loop, Meyer & DeRose 2012) refines only faces with
//! irregular features, level by level up to the isolation level `L`, and emits every other
//! face as a patch at the coarsest level where it is no longer refined. [`super::sparse`]
//! builds those levels sparsely, as OpenSubdiv's `RefineAdaptive` does: level `d + 1` refines
//! only the faces selected at level `d` ([`super::features::face_has_features`]) and one ring
//! of faces around them, so the cost grows linearly with `L` around each feature (not as
//! `4^L`). The patches of each level's leaf faces are made while the next level is refined
//! ([`super::leaves`]); the walk then descends each base face's quadtree through the selected
//! faces and places them in quadtree order. A construction whose levels would not fit in
//! memory is refused up front, level by level ([`super::budget`]). The patches, their levels and parameters are those of OpenSubdiv's feature-adaptive
//! `Far::PatchTable`; every control point is checked to be the one uniform refinement gives.
//!
//! Leaf faces become:
//! - a regular bicubic B-spline patch (16 points, boundary mask for boundary/corner patches)
//!   when no corner is extraordinary or non-manifold ([`super::features::is_patch_regular`]);
//! - a single-crease patch when, in addition, the face is interior and has one regular
//!   semi-sharp (or infinitely sharp) crease edge (Nießner, Loop & Greiner 2012). The stored
//!   sharpness is the level's own, evaluated exactly; with
//!   [`PatchOptions::cap_crease_sharpness`] it is OpenSubdiv's `min(s, L − level)` and crease
//!   faces at level `L` stay plain B-spline patches;
//! - a Gregory-basis end cap otherwise ([`super::endcap`]), whose 20 points are extra *local
//!   points* given as stencils over the refined vertices.
//!
//! # Differences from OpenSubdiv 3.5
//!
//! - Options: `useInfSharpPatch = false` (infinitely sharp interior features are isolated
//!   and approximated as smooth in end caps), `generateLegacySharpCornerPatches = true`
//!   (smooth one-face corners are sharp), Gregory-basis end caps only.
//! - Local points are not shared between adjacent end caps (OpenSubdiv shares their corner
//!   and edge points), so there are 20 per end cap.
//! - Transition masks (edges shared with a deeper patch) are left 0; evaluation does not
//!   need them.
//! - Single-crease sharpness is exact unless [`PatchOptions::cap_crease_sharpness`] is set.
//!   OpenSubdiv's own CPU `PatchTable::EvaluateBasis` ignores that sharpness and evaluates
//!   the crease edge as a boundary; [`super::eval`] evaluates the crease.
//!
//! # Layout
//!
//! Control point indices refer to one flat point array: the vertices of level 0, then of each
//! sparse level 1, 2, … (`level_offsets`; fewer than `L` levels where nothing is left to
//! isolate), then the local points (rows of `local_points`, whose inputs are the level
//! vertices). Level `d + 1` is `level_stencils[d]` applied to the level-`d` vertices listed in
//! `level_inputs[d]` (its sub-mesh); vertices on a sub-mesh's border are computed but never
//! referenced by a patch. Per patch: `kinds` ([`PatchType`] as `u8`), `cv_offsets`
//! (`P + 1` offsets into `cvs`: 16 or 20 `u32` indices), `params` (packed
//! [`PatchParam`], 2 × `u32`), `sharpness` (`f32`, 0 unless single-crease).

use super::features::FeatureMask;
use super::leaves::{level_patches, LeafOptions, LevelPatches, UNWALKED};
use super::patch_map::{PatchMap, EMPTY, LEAF, QUADRANT};
use super::sparse::{self, Selection};
use crate::error::{Error, Result};
use crate::options::Scheme;
use crate::patch::{GregoryDerivatives, PatchKind, PatchParam, PatchParamFields};
use crate::real::{Real, VertexData};
use crate::refine::{LevelStencils, StencilTable};
use crate::topology::Topology;
use crate::util::budget::Budget;
use rayon::prelude::*;

/// Largest isolation level accepted ([`PatchParam`]'s depth field holds 15, OpenSubdiv
/// allows 10).
pub const MAX_ISOLATION_LEVEL: u32 = 10;

/// Options of [`PatchTable::build`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PatchOptions {
    /// Isolation level of irregular features, `0..=10` (default 4). Meshes with non-quad faces
    /// use at least 1.
    pub isolation_level: u32,
    /// Evaluate regular faces with one semi-sharp crease directly (default `true`).
    pub single_crease: bool,
    /// Store `min(s, L − level)` as a single-crease patch's sharpness and make crease faces
    /// at the isolation level plain B-spline patches, as OpenSubdiv 3.5 does (default
    /// `false`: the level's own sharpness is stored, which `crate::patch::single_crease`
    /// evaluates exactly for any value).
    pub cap_crease_sharpness: bool,
}

impl PatchOptions {
    /// The isolation level the table of `base` is built to: `isolation_level`, at least 1 on
    /// a mesh with non-quad faces (whose sub-faces are level-1 faces).
    pub fn level_for(&self, base: &Topology) -> u32 {
        if base.is_all_quads() {
            self.isolation_level
        } else {
            self.isolation_level.max(1)
        }
    }
}

impl Default for PatchOptions {
    fn default() -> Self {
        PatchOptions {
            isolation_level: 4,
            single_crease: true,
            cap_crease_sharpness: false,
        }
    }
}

/// The basis of a patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PatchType {
    /// Bicubic B-spline, 16 points.
    Regular = 0,
    /// Bicubic B-spline with one semi-sharp crease, 16 points.
    SingleCrease = 1,
    /// Gregory-basis end cap, 20 points.
    Gregory = 2,
}

impl PatchType {
    /// The patch kind evaluated by [`crate::patch::patch_weights`]. Gregory derivatives are
    /// OpenSubdiv's default approximation.
    pub fn kind(self) -> PatchKind {
        match self {
            PatchType::Regular => PatchKind::Regular,
            PatchType::SingleCrease => PatchKind::SingleCrease,
            PatchType::Gregory => PatchKind::GregoryBasis(GregoryDerivatives::BezierApproximation),
        }
    }

    pub(crate) fn from_u8(x: u8) -> PatchType {
        match x {
            0 => PatchType::Regular,
            1 => PatchType::SingleCrease,
            _ => PatchType::Gregory,
        }
    }
}

/// Patches of a mesh (see the module documentation for the layout).
///
/// The stencil weights, and so the points and the evaluation, are `R`: `f32` (the default,
/// [`PatchTable::build`]: what the GPU reads) or `f64` ([`PatchTable::build_real`]: masks,
/// end-cap weights, points and basis in double precision, as OpenSubdiv's tables templated
/// on `double`). The patches, their types, parameters and sharpness are the same for both.
#[derive(Debug, Clone)]
pub struct PatchTable<R = f32> {
    /// The options used.
    pub(crate) options: PatchOptions,
    /// The base topology.
    pub(crate) base: Topology,
    /// `level_stencils[d]`: the vertices of level `d + 1` from those of the sub-mesh of level
    /// `d` that was refined ([`super::sparse`]).
    pub(crate) level_stencils: Vec<LevelStencils<R>>,
    /// `level_inputs[d][i]`: the level-`d` vertex that is vertex `i` of that sub-mesh (the
    /// input of `level_stencils[d]`).
    pub(crate) level_inputs: Vec<Vec<u32>>,
    /// Offsets of each level's vertices in the flat point array (one more than the number of
    /// levels, which stops early where nothing is left to isolate).
    pub(crate) level_offsets: Vec<u32>,
    /// End-cap points as stencils over the level vertices (flat indices); after a local
    /// crease edit ([`super::edit_local`]) also the refined points of the regions it rebuilt,
    /// whose rows read earlier local points: `local_segments` orders them.
    pub(crate) local_points: StencilTable<R>,
    /// Row offsets of the local points' segments: the rows of a segment read the level
    /// vertices and the local points of the segments before it only (`[0, rows]` after a
    /// build).
    pub(crate) local_segments: Vec<u32>,
    /// What local crease edits left in the table ([`super::edit_local`]); `None` after a
    /// build.
    pub(crate) spliced: Option<Box<super::edit_local::Spliced>>,
    /// The largest share of the base faces a local crease edit's sub-mesh may hold
    /// ([`super::edit_local`]; default one half).
    pub(crate) local_share: f32,
    /// [`PatchType`] per patch.
    pub(crate) kinds: Vec<u8>,
    /// `P + 1` offsets into `cvs`.
    pub(crate) cv_offsets: Vec<u32>,
    /// Control point indices into the flat point array.
    pub(crate) cvs: Vec<u32>,
    /// Packed parameter per patch.
    pub(crate) params: Vec<PatchParam>,
    /// Crease sharpness per patch (0 unless single-crease).
    pub(crate) sharpness: Vec<f32>,
    /// `F + 1` offsets: base face `f` has ptex faces `ptex_offsets[f]..ptex_offsets[f + 1]`.
    pub(crate) ptex_offsets: Vec<u32>,
    /// Patch lookup per ptex face.
    pub(crate) patch_map: PatchMap,
    /// The levels kept for incremental crease edits ([`super::edit_region`]), made by the
    /// first [`PatchTable::set_sharpness`]; `None` after a plain build.
    pub(crate) edit_state: Option<std::sync::Arc<super::edit_region::EditState>>,
    /// Per base face, the isolation level of its region when the levels were chosen per
    /// region ([`PatchTable::build_face_levels`], [`super::tolerance`]); `None` when
    /// `options.isolation_level` applies everywhere.
    pub(crate) face_levels: Option<Vec<u8>>,
    /// The rate curves' layout, formed on first use ([`PatchTable::rate_curves`]) and kept
    /// (shared by clones): it reads only the base topology, the ptex faces and which of them
    /// have patches, which a crease edit keeps (an edit that rebuilds makes a new table).
    pub(crate) rate_curves: std::sync::OnceLock<std::sync::Arc<super::rate_curves::RateCurves>>,
}

impl<R> PatchTable<R> {
    /// The options used.
    pub fn options(&self) -> &PatchOptions {
        &self.options
    }

    /// The base topology.
    pub fn base(&self) -> &Topology {
        &self.base
    }

    /// `level_stencils[d]`: the vertices of level `d + 1` from those of the sub-mesh of level
    /// `d` that was refined (`super::sparse`).
    pub fn level_stencils(&self) -> &[LevelStencils<R>] {
        &self.level_stencils
    }

    /// `level_inputs[d][i]`: the level-`d` vertex that is vertex `i` of that sub-mesh (the
    /// input of `level_stencils[d]`).
    pub fn level_inputs(&self) -> &[Vec<u32>] {
        &self.level_inputs
    }

    /// Offsets of each level's vertices in the flat point array (one more than the number of
    /// levels, which stops early where nothing is left to isolate).
    pub fn level_offsets(&self) -> &[u32] {
        &self.level_offsets
    }

    /// End-cap points as stencils over the level vertices (flat indices); after a local
    /// crease edit, also the refined points of the regions it rebuilt, which read earlier
    /// local points ([`PatchTable::local_segments`]).
    pub fn local_points(&self) -> &StencilTable<R> {
        &self.local_points
    }

    /// Row offsets of the segments of [`PatchTable::local_points`]: the rows of a segment
    /// read the level vertices and the local points of the segments before it only, so a
    /// segment is applied once the ones before it are (one segment after a build; a local
    /// crease edit appends a few, [`PatchTable::apply_sharpness`]).
    pub fn local_segments(&self) -> &[u32] {
        &self.local_segments
    }

    /// [`PatchType`] per patch.
    pub fn kinds(&self) -> &[u8] {
        &self.kinds
    }

    /// `P + 1` offsets into `cvs`.
    pub fn cv_offsets(&self) -> &[u32] {
        &self.cv_offsets
    }

    /// Control point indices into the flat point array.
    pub fn cvs(&self) -> &[u32] {
        &self.cvs
    }

    /// Packed parameter per patch.
    pub fn params(&self) -> &[PatchParam] {
        &self.params
    }

    /// Crease sharpness per patch (0 unless single-crease).
    pub fn sharpness(&self) -> &[f32] {
        &self.sharpness
    }

    /// `F + 1` offsets: base face `f` has ptex faces `ptex_offsets[f]..ptex_offsets[f + 1]`.
    pub fn ptex_offsets(&self) -> &[u32] {
        &self.ptex_offsets
    }

    /// Patch lookup per ptex face.
    pub fn patch_map(&self) -> &PatchMap {
        &self.patch_map
    }

    /// Per base face, the isolation level of its region when the levels were chosen per
    /// region ([`PatchTable::build_face_levels`], `super::tolerance`); `None` when
    /// `options.isolation_level` applies everywhere.
    pub fn face_levels(&self) -> Option<&[u8]> {
        self.face_levels.as_deref()
    }
}

/// Patch counts by type.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PatchCounts {
    /// Regular B-spline patches.
    pub regular: usize,
    /// Single-crease patches.
    pub single_crease: usize,
    /// Gregory end caps.
    pub gregory: usize,
}

/// The walk of a chunk of base faces: its patches' types, parameters and quadtree, and
/// which leaf each patch is (its points are copied once, when the chunks are joined).
struct Builder<'a, R> {
    patches: &'a [LevelPatches<R>],
    kinds: Vec<u8>,
    params: Vec<PatchParam>,
    sharpness: Vec<f32>,
    /// `(level, leaf)` of each patch.
    leaves: Vec<(u32, u32)>,
    nodes: Vec<[u32; 4]>,
    roots: Vec<u32>,
}

/// The arrays of all walked base faces, joined in base face order.
#[derive(Default)]
struct Joined<R> {
    kinds: Vec<u8>,
    cv_offsets: Vec<u32>,
    cvs: Vec<u32>,
    params: Vec<PatchParam>,
    sharpness: Vec<f32>,
    local: StencilTable<R>,
    nodes: Vec<[u32; 4]>,
    roots: Vec<u32>,
    /// `(level, leaf)` of each patch.
    leaves: Vec<(u32, u32)>,
}

impl<R: Real> Joined<R> {
    /// Reserves room for every chunk (`rows`, `entries`: end-cap rows and their entries).
    fn reserve(&mut self, parts: &[Builder<R>], rows: usize, entries: usize) {
        let sum = |f: &dyn Fn(&Builder<R>) -> usize| parts.iter().map(f).sum::<usize>();
        let patches = sum(&|b| b.kinds.len());
        self.kinds.reserve(patches);
        self.cv_offsets.reserve(patches);
        self.params.reserve(patches);
        self.sharpness.reserve(patches);
        self.cvs.reserve(16 * patches + rows / 5);
        self.nodes.reserve(sum(&|b| b.nodes.len()));
        self.roots.reserve(sum(&|b| b.roots.len()));
        self.local.offsets.reserve(rows);
        self.local.indices.reserve(entries);
        self.local.weights.reserve(entries);
    }

    /// Appends one chunk's arrays, renumbering its patches and nodes, and copies its
    /// patches' points, placing local points after the `num_level_points` level vertices.
    fn append(&mut self, b: Builder<R>, num_level_points: u32) {
        let (p0, n0) = (self.kinds.len() as u32, self.nodes.len() as u32);
        let handle = |h: u32| match h {
            EMPTY => EMPTY,
            h if h & LEAF != 0 => LEAF | ((h & !LEAF) + p0),
            h => h + n0,
        };
        self.roots.extend(b.roots.iter().map(|&h| handle(h)));
        self.nodes
            .extend(b.nodes.iter().map(|n| [0, 1, 2, 3].map(|q| handle(n[q]))));
        self.kinds.extend_from_slice(&b.kinds);
        self.params.extend_from_slice(&b.params);
        self.sharpness.extend_from_slice(&b.sharpness);
        self.leaves.extend_from_slice(&b.leaves);
        for &(d, i) in &b.leaves {
            let (part, leaf) = b.patches[d as usize].leaf(i);
            let first = leaf.first as usize;
            if leaf.kind == PatchType::Gregory {
                let l0 = num_level_points + self.local.num_rows() as u32;
                let rows = &part.local_offsets[first..first + 21];
                let (a, z) = (rows[0] as usize, rows[20] as usize);
                let (from, to) = (rows[0], self.local.indices.len() as u32);
                self.local
                    .indices
                    .extend_from_slice(&part.local_indices[a..z]);
                self.local
                    .weights
                    .extend_from_slice(&part.local_weights[a..z]);
                self.local
                    .offsets
                    .extend(rows[1..].iter().map(|&o| o - from + to));
                self.cvs.extend(l0..l0 + 20);
            } else {
                self.cvs.extend_from_slice(&part.cvs[first..first + 16]);
            }
            self.cv_offsets.push(self.cvs.len() as u32);
        }
    }
}

impl<R> Builder<'_, R> {
    fn visit(
        &mut self,
        d: usize,
        f: usize,
        ptex: u32,
        u: u32,
        v: u32,
        nonquad: bool,
    ) -> Result<u32> {
        let slot = self.patches[d].slot[f];
        if slot == EMPTY {
            return Ok(EMPTY);
        }
        if slot == UNWALKED {
            return Err(Error::Internal(format!(
                "face {f} at level {d} is walked but was not selected"
            )));
        }
        if slot & LEAF == 0 {
            let first = slot as usize;
            let node = self.nodes.len();
            self.nodes.push([EMPTY; 4]);
            for (j, &(du, dv)) in QUADRANT.iter().enumerate() {
                let h = self.visit(d + 1, first + j, ptex, 2 * u + du, 2 * v + dv, nonquad)?;
                self.nodes[node][j] = h;
            }
            return Ok(node as u32);
        }
        self.emit(d, (slot & !LEAF) as usize, ptex, u, v, nonquad)
    }

    /// Places the patch of leaf `i` of level `d` ([`super::leaves`]).
    fn emit(
        &mut self,
        d: usize,
        i: usize,
        ptex: u32,
        u: u32,
        v: u32,
        nonquad: bool,
    ) -> Result<u32> {
        let (_, leaf) = self.patches[d].leaf(i as u32);
        let patch = self.kinds.len() as u32;
        self.kinds.push(leaf.kind as u8);
        self.sharpness.push(leaf.sharpness);
        self.params.push(PatchParam::new(PatchParamFields {
            face_id: ptex,
            u: u as u16,
            v: v as u16,
            depth: d as u8,
            non_quad_root: nonquad,
            boundary: leaf.boundary,
            transition: 0,
            regular: leaf.regular,
        })?);
        self.leaves.push((d as u32, i as u32));
        Ok(LEAF | patch)
    }
}

impl PatchTable {
    /// Builds the patch table of `base` (Catmull-Clark only) by sparse feature-adaptive
    /// refinement (`super::sparse`). Refuses with [`crate::error::MeshError::TooLarge`],
    /// giving the estimate, a construction whose levels would not fit in 80% of the
    /// available memory (`super::budget`).
    pub fn build(base: &Topology, options: &PatchOptions) -> Result<PatchTable> {
        Self::build_with(base, options, Selection::Sparse)
    }

    /// Builds the patch table refining every face of every level: the same patches, at the
    /// cost of uniform refinement (the reference of the sparse construction's tests).
    pub(crate) fn build_with(
        base: &Topology,
        options: &PatchOptions,
        selection: Selection,
    ) -> Result<PatchTable> {
        Self::build_within(base, options, selection, Budget::of_available_memory())
    }

    /// [`PatchTable::build_with`] within a memory `budget`.
    pub(crate) fn build_within(
        base: &Topology,
        options: &PatchOptions,
        selection: Selection,
        budget: Budget,
    ) -> Result<PatchTable> {
        PatchTable::build_within_real(base, options, selection, budget, false, None)
    }
}

impl<R: Real> PatchTable<R> {
    /// [`PatchTable::build`] with stencil weights of type `R`: `PatchTable::<f64>::build_real`
    /// builds the double-precision table (the same patches; `f32` gives the same bits as
    /// [`PatchTable::build`]).
    pub fn build_real(base: &Topology, options: &PatchOptions) -> Result<PatchTable<R>> {
        Self::build_sparse(base, options, None)
    }

    /// The sparse construction within the available memory, untraced.
    fn build_sparse(
        base: &Topology,
        options: &PatchOptions,
        face_levels: Option<&[u8]>,
    ) -> Result<PatchTable<R>> {
        Self::build_within_real(
            base,
            options,
            Selection::Sparse,
            Budget::of_available_memory(),
            false,
            face_levels,
        )
    }

    /// [`PatchTable::build_real`] with the isolation level chosen per region: the faces
    /// descending from base face `f` are isolated to level `face_levels[f]` (each raised to
    /// `options.isolation_level` and, on a mesh with non-quad faces, to 1), up to
    /// [`MAX_ISOLATION_LEVEL`]. Where every level is `options.isolation_level`, the table is
    /// [`PatchTable::build_real`]'s, bit for bit. A level list of the wrong length or a level
    /// past the maximum is refused with [`Error::Unsupported`].
    pub fn build_face_levels(
        base: &Topology,
        options: &PatchOptions,
        face_levels: &[u8],
    ) -> Result<PatchTable<R>> {
        if face_levels.len() != base.num_faces() {
            return Err(Error::Unsupported(format!(
                "{} isolation levels given for {} base faces",
                face_levels.len(),
                base.num_faces()
            )));
        }
        if let Some((f, &l)) = face_levels
            .iter()
            .enumerate()
            .find(|(_, &l)| u32::from(l) > MAX_ISOLATION_LEVEL)
        {
            return Err(Error::Unsupported(format!(
                "isolation level {l} of base face {f} exceeds the maximum {MAX_ISOLATION_LEVEL}"
            )));
        }
        Self::build_sparse(base, options, Some(face_levels))
    }

    /// The construction; `traced` keeps its levels for incremental crease edits.
    pub(crate) fn build_within_real(
        base: &Topology,
        options: &PatchOptions,
        selection: Selection,
        mut budget: Budget,
        traced: bool,
        face_levels: Option<&[u8]>,
    ) -> Result<PatchTable<R>> {
        if base.options.scheme != Scheme::Catmark {
            return Err(Error::Unsupported(
                "limit patches are implemented for the Catmull-Clark scheme only".into(),
            ));
        }
        if options.isolation_level > MAX_ISOLATION_LEVEL {
            return Err(Error::Unsupported(format!(
                "isolation level {} exceeds the maximum {MAX_ISOLATION_LEVEL}",
                options.isolation_level
            )));
        }
        let mut level = options.level_for(base) as usize;
        // Per-region levels, each at least the table's; the same table as without them where
        // none is higher.
        let face_levels: Option<Vec<u8>> = face_levels
            .map(|l| l.iter().map(|&x| x.max(level as u8)).collect::<Vec<u8>>())
            .filter(|l| l.iter().any(|&x| x as usize > level));
        if let Some(l) = &face_levels {
            level = l.iter().copied().max().unwrap_or(0) as usize;
            // A traced table (crease edits) keeps one level everywhere.
            if traced {
                return Err(Error::Internal(
                    "per-region isolation levels cannot be traced for edits".into(),
                ));
            }
        }
        let leaf_options = LeafOptions::new(options, level);
        let mut trace = traced.then(sparse::Trace::default);
        let (h, patches) = sparse::build_traced(
            base,
            level,
            face_levels.as_deref(),
            &FeatureMask::new(options.single_crease),
            selection,
            &mut budget,
            &|lv, d, off, faces| level_patches(lv, d, off, faces, &leaf_options),
            trace.as_mut(),
        )?;
        Self::assemble(base, options, h, patches, trace, face_levels)
    }

    /// The patches of the base faces `only` (increasing) of `base`, the other faces' ptex
    /// faces left empty (a local crease edit's sub-mesh, [`super::edit_local`]): the faces
    /// of `only` have the patches a build gives them. `options.isolation_level` applies.
    pub(crate) fn build_only(
        base: &Topology,
        options: &PatchOptions,
        only: &[u32],
    ) -> Result<PatchTable<R>> {
        let level = options.isolation_level as usize;
        let leaf_options = LeafOptions::new(options, level);
        let (h, patches) = sparse::build_only(
            base,
            level,
            None,
            &FeatureMask::new(options.single_crease),
            Selection::Sparse,
            &mut Budget::of_available_memory(),
            &|lv, d, off, faces| level_patches(lv, d, off, faces, &leaf_options),
            None,
            Some(only),
        )?;
        let mut walked = vec![false; base.num_faces()];
        for &f in only {
            walked[f as usize] = true;
        }
        Self::assemble_only(base, options, h, patches, None, None, Some(&walked))
    }

    /// The table of `base` from its levels `h` and their leaves' patches: the walk of every
    /// base face's quadtree, its patches placed in quadtree order; `trace` kept for edits.
    pub(crate) fn assemble(
        base: &Topology,
        options: &PatchOptions,
        h: sparse::Hierarchy<R>,
        patches: Vec<LevelPatches<R>>,
        trace: Option<sparse::Trace>,
        face_levels: Option<Vec<u8>>,
    ) -> Result<PatchTable<R>> {
        Self::assemble_only(base, options, h, patches, trace, face_levels, None)
    }

    /// [`PatchTable::assemble`] of the base faces `walked` only, where given.
    fn assemble_only(
        base: &Topology,
        options: &PatchOptions,
        h: sparse::Hierarchy<R>,
        patches: Vec<LevelPatches<R>>,
        trace: Option<sparse::Trace>,
        face_levels: Option<Vec<u8>>,
        walked: Option<&[bool]>,
    ) -> Result<PatchTable<R>> {
        let mut level_offsets = vec![0u32];
        for &nv in &h.num_vertices {
            let last = *level_offsets.last().unwrap_or(&0);
            let n = u32::try_from(nv)
                .ok()
                .and_then(|n| last.checked_add(n))
                .ok_or_else(|| Error::Internal("more than 2^32 refined vertices".into()))?;
            level_offsets.push(n);
        }
        let mut ptex_offsets = vec![0u32];
        for f in 0..base.num_faces() {
            let n = base.face_size(f) as u32;
            let last = *ptex_offsets.last().unwrap_or(&0);
            ptex_offsets.push(last + if n == 4 { 1 } else { n });
        }
        // Base faces are walked in parallel chunks, each into its own arrays, then joined.
        let num_level_points = *level_offsets.last().unwrap_or(&0);
        let nf = base.num_faces();
        let chunk = nf.div_ceil(8 * rayon::current_num_threads().max(1)).max(16);
        let parts = (0..nf.div_ceil(chunk))
            .into_par_iter()
            .map(|c| {
                let mut b = Builder {
                    patches: &patches,
                    kinds: Vec::new(),
                    params: Vec::new(),
                    sharpness: Vec::new(),
                    leaves: Vec::new(),
                    nodes: Vec::new(),
                    roots: Vec::new(),
                };
                for f in c * chunk..((c + 1) * chunk).min(nf) {
                    let (n, ptex) = (base.face_size(f), ptex_offsets[f]);
                    if walked.is_some_and(|w| !w[f]) {
                        b.roots
                            .extend(std::iter::repeat_n(EMPTY, if n == 4 { 1 } else { n }));
                    } else if n == 4 {
                        let r = b.visit(0, f, ptex, 0, 0, false)?;
                        b.roots.push(r);
                    } else if base.face_is_hole[f] {
                        b.roots.extend(std::iter::repeat_n(EMPTY, n));
                    } else {
                        // A non-quad face is refined: its slot is its first child.
                        let first = patches[0].slot[f] as usize;
                        for j in 0..n {
                            let r = b.visit(1, first + j, ptex + j as u32, 0, 0, true)?;
                            b.roots.push(r);
                        }
                    }
                }
                Ok(b)
            })
            .collect::<Result<Vec<Builder<R>>>>()?;
        let mut all = Joined {
            local: StencilTable {
                offsets: vec![0],
                num_inputs: num_level_points as usize,
                ..Default::default()
            },
            cv_offsets: vec![0],
            ..Default::default()
        };
        let (rows, entries) = patches
            .iter()
            .flat_map(|p| &p.parts)
            .fold((0, 0), |(r, e), p| {
                (r + p.local_offsets.len() - 1, e + p.local_indices.len())
            });
        all.reserve(&parts, rows, entries);
        for b in parts {
            all.append(b, num_level_points);
        }
        let Joined {
            kinds,
            cv_offsets,
            cvs,
            params,
            sharpness,
            local: local_points,
            nodes,
            roots,
            leaves,
        } = all;
        let edit_state = trace
            .map(|t| super::edit_region::EditState::new(t, base.num_faces(), &leaves))
            .map(std::sync::Arc::new);
        let local_segments = vec![0, local_points.num_rows() as u32];
        Ok(PatchTable::<R> {
            options: *options,
            base: base.clone(),
            level_stencils: h.stencils,
            level_inputs: h.inputs,
            level_offsets,
            local_points,
            local_segments,
            spliced: None,
            local_share: super::edit_local::LOCAL_SHARE,
            kinds,
            cv_offsets,
            cvs,
            params,
            sharpness,
            ptex_offsets,
            patch_map: PatchMap { roots, nodes },
            edit_state,
            face_levels,
            rate_curves: std::sync::OnceLock::new(),
        })
    }
}

impl<R: Real> PatchTable<R> {
    /// The layout of the rate curves of this table's surface ([`super::rate_curves::RateCurves::new`]),
    /// formed by the first call and kept with the table: a renderer that chooses its rates
    /// every frame ([`crate::tess::RatePolicy::rates`]) lays the curves out once; shared, so
    /// that a holder of it (the GPU rates) keeps it without a copy.
    pub fn rate_curves(&self) -> &std::sync::Arc<super::rate_curves::RateCurves> {
        self.rate_curves
            .get_or_init(|| std::sync::Arc::new(super::rate_curves::RateCurves::new(self)))
    }

    /// Number of patches (the per-patch arrays' length; after local crease edits, the
    /// patches of the regions they replaced are still there, unreached by the patch map:
    /// [`PatchTable::num_live_patches`]).
    pub fn num_patches(&self) -> usize {
        self.kinds.len()
    }

    /// Number of patches the patch map reaches (those of a fresh build of the base):
    /// [`PatchTable::num_patches`] less the patches local crease edits replaced.
    pub fn num_live_patches(&self) -> usize {
        self.kinds.len() - self.spliced.as_ref().map_or(0, |s| s.dead_patches)
    }

    /// Whether patch `p` is reached by the patch map (every patch but those local crease
    /// edits replaced).
    pub fn is_live(&self, p: usize) -> bool {
        self.spliced.as_ref().is_none_or(|s| !s.is_dead(p))
    }

    /// Number of ptex faces.
    pub fn num_ptex_faces(&self) -> usize {
        self.patch_map.roots.len()
    }

    /// Type of patch `p`.
    pub fn patch_type(&self, p: usize) -> PatchType {
        PatchType::from_u8(self.kinds[p])
    }

    /// Control point indices of patch `p`.
    pub fn patch_cvs(&self, p: usize) -> &[u32] {
        &self.cvs[self.cv_offsets[p] as usize..self.cv_offsets[p + 1] as usize]
    }

    /// Per ptex face, the base face it belongs to.
    pub fn ptex_base_faces(&self) -> Vec<u32> {
        let mut out = vec![0u32; self.num_ptex_faces()];
        for f in 0..self.base.num_faces() {
            let r = self.ptex_offsets[f] as usize..self.ptex_offsets[f + 1] as usize;
            out[r].fill(f as u32);
        }
        out
    }

    /// Patch counts by type (of the patches the patch map reaches).
    pub fn counts(&self) -> PatchCounts {
        let mut c = PatchCounts::default();
        for &k in &self.kinds {
            match PatchType::from_u8(k) {
                PatchType::Regular => c.regular += 1,
                PatchType::SingleCrease => c.single_crease += 1,
                PatchType::Gregory => c.gregory += 1,
            }
        }
        if let Some(s) = &self.spliced {
            c.regular -= s.dead.regular;
            c.single_crease -= s.dead.single_crease;
            c.gregory -= s.dead.gregory;
        }
        c
    }

    /// Bytes of the per-patch tables: control indices, parameters, types, offsets and
    /// sharpness (the local-point stencils and level stencils are counted apart, in
    /// [`PatchTable::stencil_bytes`]).
    pub fn size_bytes(&self) -> usize {
        4 * self.cvs.len()
            + 8 * self.params.len()
            + self.kinds.len()
            + 4 * self.cv_offsets.len()
            + 4 * self.sharpness.len()
            + self.patch_map.size_bytes()
    }

    /// Bytes of the control indices and parameters only (OpenSubdiv's count).
    pub fn index_and_param_bytes(&self) -> usize {
        4 * self.cvs.len() + 8 * self.params.len()
    }

    /// Bytes of the refinement and local-point stencils.
    pub fn stencil_bytes(&self) -> usize {
        self.level_stencils
            .iter()
            .map(|s| s.size_bytes())
            .sum::<usize>()
            + 4 * self.level_inputs.iter().map(Vec::len).sum::<usize>()
            + self.local_points.size_bytes()
    }

    /// Number of points the control indices refer to: all level vertices then local points.
    pub fn num_points(&self) -> usize {
        *self.level_offsets.last().unwrap_or(&0) as usize + self.local_points.num_rows()
    }

    /// The flat point array for base vertex data `base` (`N` components): every level's
    /// vertices, then the local points; every stencil row is applied relative to its first
    /// input (`super::points`), so the rounding is relative to the patch, not the origin.
    ///
    /// `base` may hold `f32` or `f64` values ([`VertexData`]; a mesh's
    /// [`crate::mesh::Positions`] give the values as read): each is rounded to `R` once.
    pub fn points<const N: usize>(&self, base: &(impl VertexData<N> + ?Sized)) -> Vec<[R; N]> {
        let mut all = Vec::with_capacity(self.num_points());
        all.extend((0..base.num_vertices()).map(|i| base.vertex::<R>(i)));
        for (d, (s, inputs)) in self
            .level_stencils
            .iter()
            .zip(&self.level_inputs)
            .enumerate()
        {
            let start = self.level_offsets[d] as usize;
            let src: Vec<[R; N]> = inputs.iter().map(|&i| all[start + i as usize]).collect();
            let mut dst = vec![[R::ZERO; N]; s.num_rows()];
            super::points::level_apply_relative(s, &src, &mut dst);
            all.extend_from_slice(&dst);
        }
        // Segment by segment: a segment's rows may read the local points before it.
        let nl = all.len();
        all.resize(nl + self.local_points.num_rows(), [R::ZERO; N]);
        for w in self.local_segments.windows(2) {
            let (a, b) = (w[0] as usize, w[1] as usize);
            let (done, rest) = all.split_at_mut(nl + a);
            let done: &[[R; N]] = done;
            super::points::apply_relative_from(&self.local_points, a, &mut rest[..b - a], |k| {
                &done[k]
            });
        }
        all
    }
}
