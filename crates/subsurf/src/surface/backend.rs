//! Where the surface's heavy steps run. The library knows no GPU: [`Backend`] names the
//! steps (apply refinement stencils to positions and UVs, tessellate the Catmull-Clark or the
//! Loop limit surface, choose adaptive tessellation rates, tessellate the p-rep) with
//! the CPU as their default bodies; `subsurf-gpu` implements the trait with wgpu kernels, so
//! a front end passes either [`Cpu`] or `subsurf_gpu::GpuBackend` to the same call.

use super::SurfaceError;
use crate::limit::loop_eval::LoopLimit;
use crate::limit::loop_tessellate::TriTessellation;
use crate::limit::{LimitSurface, PatchTable, Tessellation};
use crate::prep::{PrepPatches, Tessellation as PrepTessellation};
use crate::refine::FVarRefinement;
use crate::tess::{EdgeRates, RatePolicy};
use crate::{Error, FaceVarying, Mesh, Refiner, Topology};

/// The p-rep tessellation and which patches carry the bi-5 perturbation.
#[derive(Debug, Clone)]
pub struct PrepOutput {
    /// Positions, unit normals and triangles, patch after patch
    /// (`2 (n - 1)^2` triangles each).
    pub tessellation: PrepTessellation<f32>,
    /// For each patch (quad of the input), whether it is perturbed.
    pub perturbed: Vec<bool>,
}

/// A place to run the surface steps. Every method has the CPU implementation as default.
pub trait Backend: std::fmt::Debug + Send + Sync {
    /// A short name for messages (`cpu`, `gpu`).
    fn name(&self) -> &'static str {
        "cpu"
    }

    /// The last level's positions of `refiner` from `base`, moved to the limit when `limit`.
    fn refine(
        &self,
        refiner: &Refiner,
        base: &[[f32; 3]],
        limit: bool,
    ) -> Result<Vec<[f32; 3]>, SurfaceError> {
        let p = refiner.refine_positions(base);
        Ok(if limit { refiner.limit(&p) } else { p })
    }

    /// Whether [`super::refine_mesh`] may refine positions in one pass without keeping
    /// stencil tables (true on the CPU; a GPU needs the tables to upload).
    fn one_pass(&self) -> bool {
        true
    }

    /// The last level's UVs (values and one index per face corner) of `fvar`, a face-varying
    /// refinement on `refiner`'s levels, from the base values `base`; moved to the limit when
    /// `limit`.
    fn refine_uvs(
        &self,
        refiner: &Refiner,
        fvar: &FVarRefinement,
        base: &[[f32; 2]],
        limit: bool,
    ) -> Result<FaceVarying, SurfaceError> {
        let mut last = fvar
            .refine(base)?
            .pop()
            .ok_or_else(|| Error::Internal("face-varying refinement without levels".into()))?;
        if limit {
            last.values = refiner.limit_face_varying(fvar, &last.values)?;
        }
        Ok(last)
    }

    /// The watertight tessellation of the limit surface of `table` with control points
    /// `base`, `samples` per ptex-face side.
    fn limit(
        &self,
        table: &PatchTable,
        base: &[[f32; 3]],
        samples: usize,
    ) -> Result<Tessellation, SurfaceError> {
        Ok(LimitSurface::new(table.clone(), base).tessellate(samples)?)
    }

    /// The per-edge rates of `policy` on `surface` ([`RatePolicy::rates`]: its rate curves
    /// measured on the CPU); a GPU backend measures them with its kernels and forms the rates
    /// with the same last step ([`RatePolicy::rates_from_measures`]).
    fn adaptive_rates(
        &self,
        surface: &LimitSurface,
        policy: &RatePolicy,
        origin: &str,
    ) -> Result<EdgeRates, SurfaceError> {
        Ok(policy.rates(surface, origin)?)
    }

    /// The watertight tessellation of the Loop limit surface `limit` (built on `base`),
    /// `segments` per base edge ([`LoopLimit::tessellate`]: positions, normals and triangles
    /// in its sample order). A backend without Loop kernels refuses with
    /// [`SurfaceError::Unsupported`] rather than running this CPU body.
    fn loop_limit(
        &self,
        limit: &LoopLimit,
        base: &Topology,
        segments: usize,
    ) -> Result<TriTessellation, SurfaceError> {
        Ok(limit.tessellate(base, segments)?)
    }

    /// The p-rep (Myles, Yeo and Peters 2008) of the quad mesh `quads`, tessellated with
    /// `samples` per patch side; `perturbed = false` drops the bi-5 perturbations.
    fn prep(
        &self,
        quads: &Mesh,
        samples: usize,
        perturbed: bool,
    ) -> Result<PrepOutput, SurfaceError> {
        let mut p = PrepPatches::<f32>::build(quads)?;
        let flags = p.h_index.iter().map(|&h| h != u32::MAX).collect();
        if !perturbed {
            p.h_index = vec![u32::MAX; p.num_faces()];
        }
        Ok(PrepOutput {
            tessellation: p.tessellate(samples.max(2)),
            perturbed: flags,
        })
    }
}

/// The CPU backend (rayon-parallel where the library is).
#[derive(Debug, Clone, Copy, Default)]
pub struct Cpu;

impl Backend for Cpu {}
