//! [`GpuRates`]: per-edge tessellation rates measured on the GPU, so that a renderer can choose
//! its rates again every frame (a moving camera under a screen-space policy, animated
//! positions under a tolerance) without evaluating the surface on the CPU.
//!
//! The rate curves of [`subsurf::tess::RateCurves`] (every base edge's limit curve and every ptex
//! face's isolines, [`CURVE_POINTS`] samples each) are uploaded once as limit samples of a
//! [`GpuLimit`]. Per call, `limit_eval` evaluates them from the limit's current points, the
//! `rate_measure` kernel reduces each curve to its measure (one `f32` per curve: the car's
//! 12,650 curves read back as 51 KB instead of 215,050 samples), and the CPU turns the measures
//! into rates with [`RatePolicy::rates_from_measures`], the same last step as
//! [`RatePolicy::rates`] on the CPU.
//!
//! The GPU's measures are `f32` (the CPU's are `f64` from the same `f32` positions), and its
//! positions agree with the CPU's to rounding, so a rate can differ by one where a need falls
//! within rounding of an integer; `tests/rates_gpu_vs_cpu.rs` measures how often.

use crate::buffers::{read_back, storage_buffer_init};
use crate::context::GpuContext;
use crate::error::Result;
use crate::kernels::stencil::ChunkLimits;
use crate::kernels::{aligned_chunks, encode_pass, grid_2d, part, whole};
use crate::limit::{GpuLimit, GpuSamples};
use crate::refine::{auto_pipeline, uniform_init};
use crate::shaders;
use crate::shared::RateConfig;
use std::sync::Arc;
use subsurf::limit::PatchTable;
use subsurf::tess::{CurveMeasure, RateCurves, CURVE_POINTS};
use subsurf::tess::{EdgeRates, RatePolicy};

use crate::cpu::rate_measure::WORKGROUP_SIZE;

const WORD: u64 = 4;

/// The rate curves of a patch table resident on the GPU as limit samples, with the
/// dispatches that measure them (module documentation).
#[derive(Debug)]
pub struct GpuRates {
    /// The table's own layout ([`PatchTable::rate_curves`], shared).
    curves: Arc<RateCurves>,
    samples: GpuSamples,
    measures: wgpu::Buffer,
    pipeline: wgpu::ComputePipeline,
    /// Per chunk of curves: its uniform, bind group, workgroup grid and configuration.
    chunks: Vec<(wgpu::Buffer, wgpu::BindGroup, (u32, u32), RateConfig)>,
}

/// The `rate_measure` configuration of `curve_count` curves under `m` (grid width left 0).
pub fn rate_config(curve_count: usize, sample_stride: usize, m: &CurveMeasure) -> RateConfig {
    let (kind, width, height, view_proj) = match m {
        CurveMeasure::SecondDerivative => (0, 0.0, 0.0, [[0.0; 4]; 4]),
        CurveMeasure::Speed => (1, 0.0, 0.0, [[0.0; 4]; 4]),
        CurveMeasure::ScreenSpeed(c) => (2, c.width as f32, c.height as f32, c.view_proj),
    };
    RateConfig {
        curve_count: curve_count as u32,
        points_per_curve: CURVE_POINTS as u32,
        sample_stride: sample_stride as u32,
        kind,
        grid_width: 0,
        width,
        height,
        _pad: 0,
        view_proj,
    }
}

impl GpuRates {
    /// Uploads the rate curves of `table` (the table `limit` was made from) as samples of
    /// `limit`.
    pub fn new(ctx: &GpuContext, limit: &GpuLimit, table: &PatchTable) -> Result<Self> {
        Self::with_limits(ctx, limit, table, ChunkLimits::from_context(ctx))
    }

    /// [`Self::new`] with the curves measured in chunks within `limits` (clamped to the
    /// adapter's: lower values force more dispatches, which tests use).
    pub fn with_limits(
        ctx: &GpuContext,
        limit: &GpuLimit,
        table: &PatchTable,
        limits: ChunkLimits,
    ) -> Result<Self> {
        // The table's own layout (formed once per table, shared with the CPU path).
        let curves = Arc::clone(table.rate_curves());
        let samples = limit.samples(ctx, curves.queries(), false)?;
        let n = curves.num_curves();
        let measures = storage_buffer_init(ctx, "rate measures", &vec![0u8; 4 * n.max(1)])?;
        let pipeline = auto_pipeline(ctx, "rate_measure", shaders::RATE_MEASURE, "main")?;
        let layout = pipeline.get_bind_group_layout(0);
        let limits = limits.clamped_to(ChunkLimits::from_context(ctx));
        let align =
            (ctx.limits().min_storage_buffer_offset_alignment as usize / WORD as usize).max(1);
        let stride = samples.stride;
        // The samples of a chunk of curves fit one binding; starts aligned.
        let words_per_curve = CURVE_POINTS * stride;
        let mut chunks = Vec::new();
        for (start, end) in aligned_chunks(
            n,
            words_per_curve,
            &limits,
            WORKGROUP_SIZE,
            align,
            "one aligned chunk of rate curves",
        )? {
            let count = end - start;
            let (gx, gy) = grid_2d(
                count as u32,
                WORKGROUP_SIZE,
                limits.max_workgroups_per_dimension,
            );
            let mut cfg = rate_config(count, stride, &CurveMeasure::Speed);
            cfg.grid_width = gx * WORKGROUP_SIZE;
            let uniform = uniform_init(ctx, bytemuck::bytes_of(&cfg))?;
            let bytes = |words: usize| words as u64 * WORD;
            let group = ctx.scoped(|| {
                Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("rate_measure"),
                    layout: &layout,
                    entries: &[
                        whole(0, &uniform),
                        part(
                            1,
                            &samples.output,
                            bytes(start * words_per_curve),
                            bytes(count * words_per_curve),
                        ),
                        part(2, &measures, bytes(start), bytes(count)),
                    ],
                }))
            })?;
            chunks.push((uniform, group, (gx, gy), cfg));
        }
        Ok(Self {
            curves,
            samples,
            measures,
            pipeline,
            chunks,
        })
    }

    /// The rate curves (their sample layout).
    pub fn curves(&self) -> &RateCurves {
        &self.curves
    }

    /// The curves' samples (positions and normals, 6 floats each), as last evaluated.
    pub fn samples(&self) -> &GpuSamples {
        &self.samples
    }

    /// Number of `rate_measure` dispatches (more than one past one binding of samples).
    pub fn num_dispatches(&self) -> usize {
        self.chunks.len()
    }

    /// Evaluates the curves from `limit`'s current points and measures them under `m`; returns
    /// one measure per curve (dead curves measure zero).
    pub fn measure(
        &self,
        ctx: &GpuContext,
        limit: &GpuLimit,
        m: &CurveMeasure,
    ) -> Result<Vec<f32>> {
        limit.eval(ctx, &self.samples)?;
        ctx.scoped(|| {
            for (uniform, _, _, cfg) in &self.chunks {
                let cfg = RateConfig {
                    grid_width: cfg.grid_width,
                    ..rate_config(cfg.curve_count as usize, cfg.sample_stride as usize, m)
                };
                ctx.queue.write_buffer(uniform, 0, bytemuck::bytes_of(&cfg));
            }
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("rate_measure"),
                });
            let chunks = self.chunks.iter().map(|(_, g, grid, _)| (g, *grid));
            encode_pass(&mut encoder, "rate_measure", &self.pipeline, chunks);
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })?;
        let n = self.curves.num_curves();
        if n == 0 {
            return Ok(Vec::new());
        }
        read_back(ctx, &self.measures, n as u64 * WORD)
    }

    /// The rates of `limit`'s surface under `policy` ([`RatePolicy::rates_from_measures`]
    /// from the GPU's measures; uniform and explicit rates are returned without GPU work).
    /// `table` is the table `limit` and these curves were made from; `diagonal` the
    /// bounding-box diagonal of its points (of the base positions: refined points lie inside
    /// their box), which a tolerance is relative to; `origin` names the policy in errors.
    pub fn rates(
        &self,
        ctx: &GpuContext,
        limit: &GpuLimit,
        table: &PatchTable,
        policy: &RatePolicy,
        diagonal: f32,
        origin: &str,
    ) -> Result<EdgeRates> {
        policy.validate(table.base(), origin)?;
        let measures: Vec<f64> = match policy.measure() {
            Some(m) => self
                .measure(ctx, limit, &m)?
                .into_iter()
                .map(f64::from)
                .collect(),
            None => Vec::new(),
        };
        Ok(policy.rates_from_measures(table, diagonal, &self.curves, &measures, origin)?)
    }
}
