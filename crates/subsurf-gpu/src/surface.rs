//! [`GpuBackend`]: the GPU behind `subsurf::surface::build`. The library defines the
//! [`Backend`] trait with CPU bodies and knows no GPU; this crate overrides each step with its
//! wgpu kernels (refinement stencils and the limit step, limit-surface patch evaluation on
//! Catmull-Clark and Loop meshes, adaptive tessellation rates, the p-rep passes and grid).

use crate::{
    GpuContext, GpuError, GpuLimit, GpuLoopLimit, GpuPrep, GpuRates, GpuRefiner, GpuUvRefiner,
    StencilKernel,
};
use subsurf::limit::LoopLimit;
use subsurf::limit::TriTessellation;
use subsurf::limit::{LimitSurface, PatchTable, Tessellation};
use subsurf::prep::PrepTopology;
use subsurf::refine::FVarRefinement;
use subsurf::surface::{Backend, PrepOutput, SurfaceError};
use subsurf::tess::{EdgeRates, RatePolicy};
use subsurf::{FaceVarying, Mesh, Refiner, Topology};

/// The GPU as a surface backend (one device, opened once).
#[derive(Debug)]
pub struct GpuBackend {
    /// The device the kernels run on.
    pub ctx: GpuContext,
}

impl GpuBackend {
    /// Opens the default adapter.
    pub fn new() -> Result<Self, GpuError> {
        Ok(GpuBackend {
            ctx: GpuContext::new()?,
        })
    }
}

fn gpu_err(what: &str) -> impl FnOnce(GpuError) -> SurfaceError + '_ {
    move |e| SurfaceError::Backend {
        backend: "gpu",
        message: format!("{what}: {e}"),
        source: Some(Box::new(e)),
    }
}

fn triples(flat: &[f32]) -> Vec<[f32; 3]> {
    flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

impl Backend for GpuBackend {
    fn name(&self) -> &'static str {
        "gpu"
    }

    fn refine(
        &self,
        refiner: &Refiner,
        base: &[[f32; 3]],
        limit: bool,
    ) -> Result<Vec<[f32; 3]>, SurfaceError> {
        let ctx = &self.ctx;
        let gpu = GpuRefiner::new(ctx, refiner).map_err(gpu_err("uploading the refiner"))?;
        gpu.update(ctx, base).map_err(gpu_err("refining"))?;
        if limit {
            let flat = StencilKernel::apply_once(ctx, refiner.limit_table(), gpu.output())
                .map_err(gpu_err("limit step"))?;
            return Ok(triples(&flat));
        }
        gpu.download(ctx).map_err(gpu_err("reading positions back"))
    }

    fn one_pass(&self) -> bool {
        false
    }

    fn refine_uvs(
        &self,
        refiner: &Refiner,
        fvar: &FVarRefinement,
        base: &[[f32; 2]],
        limit: bool,
    ) -> Result<FaceVarying, SurfaceError> {
        let ctx = &self.ctx;
        let mut gpu = GpuUvRefiner::new(ctx, fvar).map_err(gpu_err("uploading the UV refiner"))?;
        gpu.update(ctx, base).map_err(gpu_err("refining UVs"))?;
        let flat = if limit {
            StencilKernel::apply_once(ctx, &refiner.fvar_limit_table(fvar)?, gpu.output())
                .map_err(gpu_err("UV limit step"))?
        } else {
            gpu.output()
                .download(ctx)
                .map_err(gpu_err("reading UVs back"))?
        };
        let last = fvar.levels.last().ok_or_else(|| {
            subsurf::Error::Internal("face-varying refinement without levels".into())
        })?;
        Ok(FaceVarying {
            values: flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
            indices: last.corner_values.clone(),
        })
    }

    fn limit(
        &self,
        table: &PatchTable,
        base: &[[f32; 3]],
        samples: usize,
    ) -> Result<Tessellation, SurfaceError> {
        let ctx = &self.ctx;
        let mut gpu = GpuLimit::new(ctx, table).map_err(gpu_err("uploading the patch table"))?;
        gpu.update(ctx, base)
            .map_err(gpu_err("refining and computing end-cap points"))?;
        let t = gpu
            .tessellation(ctx, table, samples)
            .map_err(gpu_err("planning the tessellation"))?;
        gpu.eval(ctx, &t.samples)
            .map_err(gpu_err("evaluating the samples"))?;
        t.download(ctx)
            .map_err(gpu_err("reading the tessellation back"))
    }

    /// The patch table and the surface's points uploaded, the rate curves evaluated by
    /// `limit_eval` and measured by `rate_measure` ([`GpuRates`]);
    /// the rates formed on the CPU from one measure per curve. Bad policy values and
    /// oversize tessellations are refused with the library's errors, as on the CPU.
    fn adaptive_rates(
        &self,
        surface: &LimitSurface,
        policy: &RatePolicy,
        origin: &str,
    ) -> Result<EdgeRates, SurfaceError> {
        if policy.measure().is_none() {
            return Ok(policy.rates(surface, origin)?);
        }
        let table = &surface.table();
        policy.validate(table.base(), origin)?;
        let ctx = &self.ctx;
        let gpu = GpuLimit::new(ctx, table).map_err(gpu_err("uploading the patch table"))?;
        // The surface's points are already refined: uploaded, not refined again.
        gpu.set_points(ctx, surface.points())
            .map_err(gpu_err("uploading the points"))?;
        let rates =
            GpuRates::new(ctx, &gpu, table).map_err(gpu_err("uploading the rate curves"))?;
        let diagonal = subsurf::mesh::bbox_diagonal(surface.points());
        match rates.rates(ctx, &gpu, table, policy, diagonal, origin) {
            Ok(r) => Ok(r),
            Err(GpuError::Library(e)) => Err(e.into()),
            Err(e) => Err(gpu_err("measuring the rate curves")(e)),
        }
    }

    /// The patches (and their points, gathered by the library) uploaded, every sample of
    /// the library's tessellation plan evaluated by `loop_eval`.
    fn loop_limit(
        &self,
        limit: &LoopLimit,
        base: &Topology,
        segments: usize,
    ) -> Result<TriTessellation, SurfaceError> {
        let ctx = &self.ctx;
        let gpu = GpuLoopLimit::new(ctx, limit).map_err(gpu_err("uploading the Loop patches"))?;
        gpu.tessellate(ctx, limit, base, segments)
            .map_err(gpu_err("evaluating the Loop limit surface"))
    }

    fn prep(
        &self,
        quads: &Mesh,
        samples: usize,
        perturbed: bool,
    ) -> Result<PrepOutput, SurfaceError> {
        if !perturbed {
            return Err(SurfaceError::Unsupported(
                "the GPU p-rep always includes the bi-5 perturbations; use the CPU backend".into(),
            ));
        }
        let ctx = &self.ctx;
        let topo = PrepTopology::new(&Topology::new(quads)?)?;
        let mut gpu = GpuPrep::new(ctx, &topo).map_err(gpu_err("uploading the p-rep"))?;
        gpu.update(ctx, &quads.positions)
            .map_err(gpu_err("vertex and patch pass"))?;
        let grid = gpu
            .grid(ctx, samples.max(2))
            .and_then(|g| gpu.eval_grid(ctx, &g).and_then(|_| g.download(ctx)))
            .map_err(gpu_err("tessellating"))?;
        let mut flags = vec![false; topo.num_faces()];
        for &f in topo.perturbed_faces() {
            flags[f as usize] = true;
        }
        Ok(PrepOutput {
            tessellation: grid,
            perturbed: flags,
        })
    }
}
