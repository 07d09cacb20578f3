//! Uniform Catmull-Clark (and bilinear) refinement, matching OpenSubdiv's `Far::TopologyRefiner`
//! + `Far::PrimvarRefiner` vertex for vertex.
//!
//! Refinement is split like OpenSubdiv's: [`Refiner::new`] refines the topology once and builds
//! one [`StencilTable`] per level; [`Refiner::refine_positions`] then only applies those tables,
//! so an animated mesh re-evaluates each frame without rebuilding anything. The tables (and
//! the composed base-to-last-level table of [`Refiner::stencil_table`]) are what a GPU backend
//! uploads.
//!
//! Two ways to store fewer bytes, which is much of a refinement's time (the kernel
//! zero-fills every fresh page): [`RefineOptions::lean`] leaves the last level with its face
//! lists only (OpenSubdiv's `fullTopologyInLastLevel = false`), and [`refine_once`] refines
//! vertex data once without keeping any stencil table, evaluating each row as it is formed.
//!
//! Vertex order at each level (OpenSubdiv's): children of the parent vertices first (same
//! indices), then one face point per parent face, then one edge point per parent edge.
//!
//! Face-varying data (UVs) refines on the same levels with its own value topology and
//! stencils, in any of OpenSubdiv's `FVarLinearInterpolation` modes:
//! [`Refiner::refine_uvs`], or [`Refiner::fvar_refinement`] to keep the tables.

mod alloc;
mod frame_plan;
mod fvar_limit;
mod fvar_propagate;
mod fvar_stencils;
mod fvar_topology;
mod interpolate;
mod into;
#[cfg(target_arch = "x86_64")]
mod lanes;
mod last_level;
mod level;
mod level_tags;
mod loop_frame;
mod loop_level;
mod loop_masks;
mod loop_nonmanifold;
mod loop_rings;
mod masks;
mod moved;
mod resharpen;
mod smooth_frame;
mod stencil;
mod uv;

pub(crate) use fvar_limit::fvar_limit_stencils;
pub use fvar_stencils::FVarRefinement;
pub use interpolate::{refine_once, refine_once_mesh};
use last_level::{refine_face_lists, ChildSharpness, ChildSharpnessBuf};
pub use level::refine_topology;
pub use level_tags::{level_tags, tagged_level_mesh, LevelTags};
pub(crate) use loop_level::{check_triangles, refine_tri_topology};
pub(crate) use loop_masks::{loop_level_stencils, loop_level_stencils_real, loop_limit_stencils};
pub use masks::{level_stencils, LevelStencils};
pub(crate) use masks::{level_stencils_real, limit_stencils};
use masks::{level_stencils_with, LevelRows};
pub(crate) use moved::{edge_values, vertex_values, Moved};
pub(crate) use resharpen::{form_rows, resharpen_at, unique, Bits, Restenciled};
use smooth_frame::StepPlan;
pub use stencil::StencilTable;
pub use uv::refine_uvs_linear;

use crate::error::{Error, MeshError, Result};
use crate::mesh::{Mesh, Positions};
use crate::options::Scheme;
use crate::topology::Topology;
use crate::util::budget::{check, human, saturate};

/// Options of [`Refiner::with_options`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RefineOptions {
    /// Build the last level's full topology: edges, rings, sharpness, tags (the default, and
    /// what [`Refiner::new`] does). With `false` the last level holds only its face lists, hole
    /// flags and vertex count — all that positions and output meshes need — as OpenSubdiv's
    /// `UniformOptions::fullTopologyInLastLevel = false` (OpenSubdiv's default) leaves it.
    /// [`Refiner::limit`] and the face-varying methods then rebuild that level in full when
    /// they are called.
    pub full_topology_in_last_level: bool,
}

impl Default for RefineOptions {
    fn default() -> Self {
        RefineOptions {
            full_topology_in_last_level: true,
        }
    }
}

impl RefineOptions {
    /// Options for output only: the last level keeps face lists, holes and vertex count.
    pub fn lean() -> Self {
        RefineOptions {
            full_topology_in_last_level: false,
        }
    }
}

/// Refined topology of every level, the per-frame plans between consecutive levels, and
/// the stencils between them ([`Refiner::stencils`], on first use for Catmull-Clark).
///
/// # Example
///
/// Positions and UVs of a unit square refined once; the UVs linearly (OpenSubdiv's default
/// face-varying mode), so the level-1 values are the 3×3 lattice of corners, edge midpoints
/// and centre, and their limit is themselves:
///
/// ```
/// use subsurf::{shapes, FVarLinearInterpolation, FaceVarying, Refiner, Topology};
///
/// let mut square = shapes::grid(1, 1);
/// let uvs = FaceVarying {
///     values: square.positions.iter().map(|p| [p[0], p[1]]).collect(),
///     indices: square.face_indices.clone(),
/// };
/// square.uvs = Some(uvs.clone());
/// let refiner = Refiner::new(Topology::new(&square)?, 1)?;
///
/// // Positions: children of the 4 vertices, then the face point, then 4 edge points.
/// let positions = refiner.refine_positions(&square.positions);
/// assert_eq!(positions.len(), 9);
/// assert_eq!(positions[4], [0.5, 0.5, 0.0]);
///
/// // UVs: one value per distinct (vertex, UV) pair, one index per face corner.
/// let fvar = refiner.fvar_refinement(&uvs.indices, uvs.values.len(), FVarLinearInterpolation::All)?;
/// let last = fvar.refine(&uvs.values)?.pop().expect("levels 0 and 1");
/// assert_eq!(last.indices.len(), 16); // 4 quads
/// let mut lattice: Vec<[f32; 2]> = last.values.clone();
/// lattice.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
/// let want: Vec<[f32; 2]> = (0..9).map(|k| [(k / 3) as f32 / 2.0, (k % 3) as f32 / 2.0]).collect();
/// assert_eq!(lattice, want);
/// // The corner at the face point has the centre UV in every child face.
/// let t = refiner.last();
/// for (corner, &v) in t.arrays().face_verts.iter().enumerate() {
///     if v == 4 {
///         assert_eq!(last.values[last.indices[corner] as usize], [0.5, 0.5]);
///     }
/// }
/// // Linear UVs are their own limit.
/// assert_eq!(refiner.limit_face_varying(&fvar, &last.values)?, last.values);
/// # Ok::<(), subsurf::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Refiner {
    /// `levels[0]` is the base; `levels[k]` the result of `k` refinement steps. Under
    /// [`RefineOptions::lean`] the last level (if refined at all) has only `face_offsets`,
    /// `face_verts`, `face_is_hole` and `num_vertices`; its other tables are empty, so its
    /// relation accessors (`vertex_faces`, `edge_faces`, ...) must not be called — check
    /// [`Refiner::is_full`] first.
    pub levels: Vec<Topology>,
    /// `stencils[k]` maps vertex data of level `k` to level `k + 1` ([`Refiner::stencils`]):
    /// built on first use where the per-frame plans were made from the topology.
    stencils: std::sync::OnceLock<Vec<LevelStencils>>,
    /// Limit stencils of the last level, built on first use of [`Refiner::limit`].
    limit_table: std::sync::OnceLock<StencilTable>,
    /// Smooth rows and exceptions of each step: made from the topology as a Catmull-Clark
    /// refiner refines, else found from the stencils on first use of
    /// [`Refiner::refine_positions_into`].
    frame_plans: std::sync::OnceLock<Vec<smooth_frame::StepPlan>>,
    options: RefineOptions,
}

/// Rough number of bytes the refiner needs for `level` steps of `base` (topology of all levels,
/// stencils and one set of positions). A float: at high levels the estimate passes `u64::MAX`,
/// and the refusal says how far.
pub fn estimate_bytes(base: &Topology, level: usize) -> f64 {
    let mut faces = base.num_corners() as f64; // quads after the first step
    let mut total = 0f64;
    for _ in 0..level {
        // ~ per child quad: face verts/edges 32 B, ~2 edges x 30 B, ~1 vertex x (rings 40 B,
        // stencil row 60 B, tags, positions 12 B).
        total += faces * 200.0;
        faces *= 4.0;
    }
    total
}

/// Refuses a Loop mesh with a face other than a triangle, and up front, with the estimated
/// size, a level whose tables would not fit in memory ([`check`]) or overflow 32-bit
/// indices.
fn check_size(base: &Topology, level: usize) -> Result<()> {
    if base.options.scheme == Scheme::Loop {
        check_triangles(base)?;
    }
    let estimate = estimate_bytes(base, level);
    let what = || format!("refining {} faces to level {level}", base.num_faces());
    let corners = (base.num_corners() as u128) << (2 * level.max(1) as u32).min(120);
    if corners > (u32::MAX as u128) / 2 {
        return Err(MeshError::TooLarge {
            what: what(),
            bytes: saturate(estimate),
            human: human(estimate),
            limit_human: "2^31 face corners (32-bit indices)".into(),
        }
        .into());
    }
    check(estimate, what)?;
    Ok(())
}

impl Refiner {
    /// Refines `base` uniformly `level` times, every level with its full topology. Refuses up
    /// front, with the estimated size, a level whose tables would not fit in memory or
    /// overflow 32-bit indices.
    pub fn new(base: Topology, level: usize) -> Result<Refiner> {
        Self::with_options(base, level, RefineOptions::default())
    }

    /// As [`Refiner::new`], under `options`.
    pub fn with_options(base: Topology, level: usize, options: RefineOptions) -> Result<Refiner> {
        check_size(&base, level)?;
        if base.options.scheme == Scheme::Loop {
            return Ok(Self::new_loop(base, level, options));
        }
        let full = |k: usize| k + 1 < level || options.full_topology_in_last_level;
        let mut levels = vec![base];
        // Per step, the per-frame plan made from the topology (`None` for a bilinear step or
        // one whose rows are mostly exceptions: the refiner then keeps its stencil tables).
        let mut plans = Vec::with_capacity(level);
        // The full child of the last level, built ahead while the previous step's plan was:
        // both read only that level, so they run side by side (`rayon::join`; one after the
        // other on one thread, with the same results).
        let mut ahead: Option<Topology> = None;
        for k in 0..level {
            let parent = levels
                .last()
                .ok_or_else(|| Error::Internal("no base level".into()))?;
            if !full(k) {
                let (plan, child) = rayon::join(
                    || {
                        let sharpness = ChildSharpnessBuf::new(parent);
                        let rows = LevelRows::new(parent, sharpness.view(parent));
                        StepPlan::from_topology(parent, rows)
                    },
                    || refine_face_lists(parent),
                );
                plans.push(plan);
                levels.push(child);
            } else {
                let child = ahead.take().unwrap_or_else(|| refine_topology(parent));
                let (plan, next) = rayon::join(
                    || {
                        let rows = LevelRows::new(parent, ChildSharpness::of_child(parent, &child));
                        StepPlan::from_topology(parent, rows)
                    },
                    || (k + 1 < level && full(k + 1)).then(|| refine_topology(&child)),
                );
                ahead = next;
                plans.push(plan);
                levels.push(child);
            }
        }
        let mut r = Refiner {
            levels,
            stencils: std::sync::OnceLock::new(),
            limit_table: std::sync::OnceLock::new(),
            frame_plans: std::sync::OnceLock::new(),
            options,
        };
        match plans.into_iter().collect::<Option<Vec<StepPlan>>>() {
            Some(plans) => r.frame_plans = std::sync::OnceLock::from(plans),
            None => r.stencils = std::sync::OnceLock::from(r.build_stencils()),
        }
        Ok(r)
    }

    /// The stencil tables of every step: from the per-frame plans where they were made from
    /// the topology, else from the levels.
    fn build_stencils(&self) -> Vec<LevelStencils> {
        let plans = self.frame_plans.get();
        (0..self.max_level())
            .map(|k| {
                let parent = &self.levels[k];
                if let Some(s) = plans.and_then(|p| p[k].stencils(parent)) {
                    s
                } else if parent.options.scheme == Scheme::Loop {
                    if self.is_full(k + 1) {
                        loop_level_stencils(parent, &self.levels[k + 1])
                    } else {
                        let sharpness = ChildSharpnessBuf::new(parent);
                        loop_masks::loop_level_stencils_with(parent, sharpness.view(parent))
                    }
                } else if self.is_full(k + 1) {
                    level_stencils(parent, &self.levels[k + 1])
                } else {
                    let sharpness = ChildSharpnessBuf::new(parent);
                    level_stencils_with(parent, sharpness.view(parent))
                }
            })
            .collect()
    }

    /// `stencils()[k]` maps vertex data of level `k` to level `k + 1`: one sparse table per
    /// step, what the GPU backend uploads. A Catmull-Clark refiner, and a Loop refiner whose
    /// levels are manifold, builds them on first use (its per-frame path,
    /// [`Refiner::refine_positions_into`], reads plans made from the topology instead), and
    /// keeps them; other refiners build them during setup.
    pub fn stencils(&self) -> &[LevelStencils] {
        self.stencils.get_or_init(|| self.build_stencils())
    }

    /// The options the refiner was built with.
    pub fn options(&self) -> RefineOptions {
        self.options
    }

    /// Whether level `k` carries its full topology (every level does but a lean last one).
    pub fn is_full(&self, k: usize) -> bool {
        k == 0 || k < self.max_level() || self.options.full_topology_in_last_level
    }

    /// Level `k` with its full topology: borrowed, or rebuilt from level `k - 1` where the
    /// refiner keeps it lean.
    pub(crate) fn full_level(&self, k: usize) -> std::borrow::Cow<'_, Topology> {
        if self.is_full(k) {
            std::borrow::Cow::Borrowed(&self.levels[k])
        } else if self.levels[0].options.scheme == Scheme::Loop {
            std::borrow::Cow::Owned(loop_level::refine_tri(&self.levels[k - 1]))
        } else {
            std::borrow::Cow::Owned(refine_topology(&self.levels[k - 1]))
        }
    }

    /// Number of refinement steps.
    pub fn max_level(&self) -> usize {
        self.levels.len() - 1
    }

    /// The last level's topology. Built with [`RefineOptions::lean`], it holds only face lists,
    /// hole flags and the vertex count (its edge, ring and tag tables are empty).
    pub fn last(&self) -> &Topology {
        &self.levels[self.levels.len() - 1]
    }

    /// Vertex data of every level, starting with `base` (`N` components per vertex).
    pub fn refine_all<const N: usize>(&self, base: &[[f32; N]]) -> Vec<Vec<[f32; N]>> {
        let mut out = vec![base.to_vec()];
        for s in self.stencils() {
            let src = &out[out.len() - 1];
            let mut dst = vec![[0.0; N]; s.num_rows()];
            s.apply(src, &mut dst);
            out.push(dst);
        }
        out
    }

    /// Vertex data of the last level only: [`Refiner::refine_positions_into`] into a new
    /// buffer, bit-identical to applying the per-level tables ([`Refiner::stencils`]) in turn
    /// (which is what this does, panicking, when `base` does not hold one value per base
    /// vertex).
    pub fn refine_positions<const N: usize>(&self, base: &[[f32; N]]) -> Vec<[f32; N]> {
        let mut out = alloc::zeroed(self.last().num_vertices(), [0.0f32; N]);
        if self
            .refine_positions_into(base, &mut out, &mut Vec::new())
            .is_ok()
        {
            return out;
        }
        let mut cur = base.to_vec();
        for s in self.stencils() {
            let mut dst = alloc::zeroed(s.num_rows(), [0.0f32; N]);
            s.apply(&cur, &mut dst);
            cur = dst;
        }
        cur
    }

    /// Vertex data of the last level in `f64`: every step's masks evaluated in double
    /// precision (OpenSubdiv's `PrimvarRefinerReal<double>`) and applied to `base` as it is
    /// held (a mesh's [`crate::mesh::Positions`] give the values as read, without rounding).
    /// Builds the double-precision tables of every step on each call (the per-frame `f32`
    /// path, [`Refiner::refine_positions`], keeps its tables); refuses data with the wrong
    /// number of values.
    pub fn refine_f64<const N: usize>(
        &self,
        base: &(impl crate::real::VertexData<N> + ?Sized),
    ) -> Result<Vec<[f64; N]>> {
        let n = self.levels[0].num_vertices();
        if base.num_vertices() != n {
            return Err(Error::Internal(format!(
                "{} values given for {n} base vertices",
                base.num_vertices()
            )));
        }
        let mut cur: Vec<[f64; N]> = (0..n).map(|i| base.vertex_f64(i)).collect();
        for k in 0..self.max_level() {
            let (parent, child) = (self.full_level(k), self.full_level(k + 1));
            let s = if self.levels[0].options.scheme == Scheme::Loop {
                loop_masks::loop_level_stencils_real::<f64>(&parent, &child)
            } else {
                level_stencils_real::<f64>(&parent, &child)
            };
            cur = s.apply_real(&cur);
        }
        Ok(cur)
    }

    /// Moves last-level vertex data to the limit surface in `f64` (the limit masks in double
    /// precision; the tables are built on each call).
    pub fn limit_f64<const N: usize>(&self, last: &[[f64; N]]) -> Result<Vec<[f64; N]>> {
        let top = self.full_level(self.max_level());
        let t = if self.levels[0].options.scheme == Scheme::Loop {
            loop_masks::loop_limit_stencils_real::<f64>(&top)
        } else {
            masks::limit_stencils_real::<f64>(&top)
        };
        if last.len() != t.num_rows() {
            return Err(Error::Internal(format!(
                "{} values given for {} last-level vertices",
                last.len(),
                t.num_rows()
            )));
        }
        Ok(masks::rows(&t, |k| last[k]))
    }

    /// The per-level tables composed into one table from base vertices to the last level.
    pub fn stencil_table(&self) -> StencilTable {
        let n = self.levels[0].num_vertices();
        let mut acc = StencilTable {
            offsets: (0..=n as u32).collect(),
            indices: (0..n as u32).collect(),
            weights: vec![1.0; n],
            num_inputs: n,
        };
        for s in self.stencils() {
            acc = acc.then(&s.to_table());
        }
        acc
    }

    /// The stencils moving the last level's vertices to the limit surface (`limit_stencils`),
    /// built on first use and kept: an animated mesh applies them every frame, on the CPU
    /// ([`Self::limit`]) or uploaded to a GPU.
    pub fn limit_table(&self) -> &StencilTable {
        self.limit_table.get_or_init(|| {
            let last = self.full_level(self.max_level());
            if last.options.scheme == Scheme::Loop {
                loop_limit_stencils(&last)
            } else {
                limit_stencils(&last)
            }
        })
    }

    /// Moves last-level vertex data to the limit surface.
    pub fn limit<const N: usize>(&self, last: &[[f32; N]]) -> Vec<[f32; N]> {
        let t = self.limit_table();
        let mut out = vec![[0.0; N]; t.num_rows()];
        t.apply(last, &mut out);
        out
    }

    /// The stencils moving the last level's face-varying values of `fvar` (a refinement of
    /// this refiner's levels) to the limit surface (`fvar_limit_stencils`).
    pub fn fvar_limit_table(&self, fvar: &FVarRefinement) -> Result<StencilTable> {
        if fvar.levels.len() != self.levels.len() {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "a face-varying refinement of {} levels for a refiner of {}",
                    fvar.levels.len(),
                    self.levels.len()
                ),
            }
            .into());
        }
        Ok(fvar_limit_stencils(
            &self.full_level(self.max_level()),
            &fvar.levels[fvar.levels.len() - 1],
        ))
    }

    /// Moves the last level's face-varying values (`last`, one per value of
    /// `fvar.levels[max_level]`, as [`FVarRefinement::refine`] gives them) to the limit
    /// surface, as OpenSubdiv's `PrimvarRefiner::LimitFaceVarying` (`fvar_limit_stencils`;
    /// tested against it at levels 1–2 on every regression shape with UVs in all six modes).
    /// On the unrefined level the two differ where value numbers are not vertex sibling slots:
    /// OpenSubdiv 3.5 looks a value's tags up by its value index in the per-slot tag array
    /// (`FVarLevel::getValueTag`), which is the value's own slot only after refinement; and a
    /// value shared by several vertices (as OBJ files often share texture coordinates) can
    /// hold only one of their limits. Refine at least once for a well-defined limit.
    pub fn limit_face_varying<const N: usize>(
        &self,
        fvar: &FVarRefinement,
        last: &[[f32; N]],
    ) -> Result<Vec<[f32; N]>> {
        let t = self.fvar_limit_table(fvar)?;
        if last.len() != t.num_rows() {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "{} values for a last level of {} face-varying values",
                    last.len(),
                    t.num_rows()
                ),
            }
            .into());
        }
        let mut out = vec![[0.0; N]; t.num_rows()];
        t.apply(last, &mut out);
        Ok(out)
    }

    /// The faces of `level` that are not holes, as a [`Mesh`] with the given positions.
    pub fn to_mesh(&self, level: usize, positions: impl Into<Positions>) -> Mesh {
        level_mesh(&self.levels[level], positions)
    }

    /// All faces of `level`, holes included and tagged, with the sharpness that remains there
    /// and the options, as a [`Mesh`] that refines again as the level itself would
    /// ([`tagged_level_mesh`]): what a refined file is written from. A lean last level's
    /// sharpness is derived from its parent.
    pub fn to_tagged_mesh(&self, level: usize, positions: impl Into<Positions>) -> Result<Mesh> {
        let positions = positions.into();
        let t = self.levels.get(level).ok_or_else(|| {
            Error::Unsupported(format!(
                "level {level} of a refiner of {} levels",
                self.max_level()
            ))
        })?;
        if positions.len() != t.num_vertices() {
            return Err(MeshError::Unsupported {
                construction: "a refined level as a mesh",
                requirement: "one position per vertex of the level",
                details: format!(
                    "{} positions for {} vertices",
                    positions.len(),
                    t.num_vertices()
                ),
            }
            .into());
        }
        let tags = if self.is_full(level) {
            level_tags(t)?
        } else {
            let p = &self.levels[level - 1];
            let sharpness = ChildSharpnessBuf::new(p);
            level_tags::child_level_tags(p, sharpness.view(p), t)
        };
        Ok(tagged_level_mesh(t, positions, tags))
    }
}

/// The faces of a refined level (full or lean) that are not holes, as a [`Mesh`] with the given
/// positions: what [`refine_once`] returns, ready to write.
pub fn level_mesh(t: &Topology, positions: impl Into<Positions>) -> Mesh {
    let mut m = Mesh {
        positions: positions.into(),
        options: t.options,
        ..Default::default()
    };
    for f in 0..t.num_faces() {
        if !t.face_is_hole[f] {
            let fv = t.face_vertices(f);
            m.face_counts.push(fv.len() as u32);
            m.face_indices.extend_from_slice(fv);
        }
    }
    m
}

#[cfg(test)]
mod tests;
