//! The Loop limit surface on the GPU: the patches of a [`LoopLimit`] (quartic box splines
//! with their boundary and corner variants, Gregory-triangle end caps) evaluated by
//! `loop_eval` ([`crate::cpu::loop_eval`]) at `(patch, u, v)` samples.
//!
//! [`GpuLoopLimit::new`] uploads the flat tables once ([`LoopTables`]: kind, first point and
//! [`PatchParam`](subsurf::patch::PatchParam) per patch, and the 12 or 18 points of every
//! patch as the library gathered them, rounded to f32). [`GpuLoopLimit::samples`] uploads a
//! sample set, [`GpuLoopLimit::eval`] evaluates it; [`GpuLoopLimit::tessellate`] evaluates
//! the samples of the library's watertight tessellation
//! ([`subsurf::limit::tri_tessellation_plan`]), so its triangles are those of
//! [`LoopLimit::tessellate`] and only positions and normals come from the GPU. The patch of
//! each sample is found on the host with the triangle patch map.
//!
//! Samples are dispatched in chunks whose query and output bindings start at aligned
//! offsets, within `max_storage_buffer_binding_size` and
//! `max_compute_workgroups_per_dimension`; the patch tables are bound whole, so a surface
//! whose points exceed one binding (about 620,000 end caps at 128 MiB) is refused with
//! [`GpuError::TooLarge`].

use crate::buffers::storage_buffer_init;
use crate::context::GpuContext;
use crate::cpu::loop_eval::{pack_queries, LoopTables, QUERY_WORDS, WORKGROUP_SIZE};
use crate::error::{GpuError, Result};
use crate::kernels::stencil::ChunkLimits;
use crate::kernels::{aligned_chunks, encode_pass, grid_2d, part, whole};
use crate::limit::GpuSamples;
pub use crate::loop_twin::{assemble, loop_eval_cpu, loop_tessellate_cpu, plan_queries};
use crate::refine::{auto_pipeline, uniform_init};
use crate::shaders;
use crate::shared::LoopConfig;
use subsurf::limit::LoopLimit;
use subsurf::limit::{tri_tessellation_plan, TriTessellation};
use subsurf::Topology;

const WORD: u64 = 4;

/// The patches of a Loop limit surface resident on the GPU.
#[derive(Debug)]
pub struct GpuLoopLimit {
    patch_info: wgpu::Buffer,
    points: wgpu::Buffer,
    num_patches: u32,
    limits: ChunkLimits,
    row_align: usize,
    pipeline: wgpu::ComputePipeline,
}

impl GpuLoopLimit {
    /// Uploads `limit`'s patch tables against the adapter's limits.
    pub fn new(ctx: &GpuContext, limit: &LoopLimit) -> Result<Self> {
        Self::with_limits(ctx, limit, ChunkLimits::from_context(ctx))
    }

    /// Uploads `limit`'s patch tables; sample sets are chunked against `limits` (clamped to
    /// the adapter's; lower values force more chunks).
    pub fn with_limits(ctx: &GpuContext, limit: &LoopLimit, limits: ChunkLimits) -> Result<Self> {
        let adapter = ChunkLimits::from_context(ctx);
        let limits = ChunkLimits {
            max_binding_bytes: limits.max_binding_bytes.min(adapter.max_binding_bytes),
            max_workgroups_per_dimension: limits
                .max_workgroups_per_dimension
                .clamp(1, adapter.max_workgroups_per_dimension),
            max_stride: 12,
        };
        let t = LoopTables::new(limit);
        for (what, words) in [
            ("Loop patch data", t.patch_info.len()),
            ("Loop patch points", t.points.len()),
        ] {
            let needed = words as u64 * WORD;
            if needed > limits.max_binding_bytes {
                return Err(GpuError::TooLarge {
                    what,
                    needed,
                    limit: limits.max_binding_bytes,
                });
            }
        }
        let patch_info =
            storage_buffer_init(ctx, "Loop patch data", bytemuck::cast_slice(&t.patch_info))?;
        let points =
            storage_buffer_init(ctx, "Loop patch points", bytemuck::cast_slice(&t.points))?;
        let pipeline = auto_pipeline(ctx, "loop_eval", shaders::LOOP_EVAL, "main")?;
        let row_align =
            (ctx.limits().min_storage_buffer_offset_alignment as usize / WORD as usize).max(1);
        Ok(Self {
            patch_info,
            points,
            num_patches: t.num_patches,
            limits,
            row_align,
            pipeline,
        })
    }

    /// Number of patches.
    pub fn num_patches(&self) -> usize {
        self.num_patches as usize
    }

    /// Uploads a sample set of `(patch, u, v)` queries, `(u, v)` on the patch's base face;
    /// `derivatives` selects 12 floats per sample (with `∂P/∂u`, `∂P/∂v`) instead of 6. A
    /// sample of a patch out of range evaluates to zeros; parameters must be finite.
    pub fn samples(
        &self,
        ctx: &GpuContext,
        queries: &[(u32, f32, f32)],
        derivatives: bool,
    ) -> Result<GpuSamples> {
        let (count, stride) = crate::limit::check_samples(queries, derivatives)?;
        let output = crate::limit::sample_output(ctx, "Loop limit samples", count, stride)?;
        let words = pack_queries(queries);
        let queries_buf =
            storage_buffer_init(ctx, "Loop limit queries", bytemuck::cast_slice(&words))?;
        let layout = self.pipeline.get_bind_group_layout(0);
        let mut chunks = Vec::new();
        let mut buffers = Vec::new();
        for (start, end) in self.sample_chunks(count, stride)? {
            let n = (end - start) as u32;
            let (gx, gy) = grid_2d(n, WORKGROUP_SIZE, self.limits.max_workgroups_per_dimension);
            let config = LoopConfig {
                item_count: n,
                grid_width: gx * WORKGROUP_SIZE,
                out_stride: stride as u32,
                num_patches: self.num_patches,
            };
            let config_buf = uniform_init(ctx, bytemuck::bytes_of(&config))?;
            let at = |words_per: usize| (start * words_per) as u64 * WORD;
            let size = |words_per: usize| u64::from(n) * words_per as u64 * WORD;
            let bind_group = ctx.scoped(|| {
                Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("loop_eval"),
                    layout: &layout,
                    entries: &[
                        whole(0, &config_buf),
                        part(1, &queries_buf, at(QUERY_WORDS), size(QUERY_WORDS)),
                        whole(2, &self.patch_info),
                        whole(3, &self.points),
                        part(4, &output, at(stride), size(stride)),
                    ],
                }))
            })?;
            chunks.push((bind_group, (gx, gy)));
            buffers.push(config_buf);
        }
        buffers.push(queries_buf);
        Ok(GpuSamples::from_chunks(
            count, stride, output, chunks, buffers,
        ))
    }

    /// Sample ranges `[start, end)` of the dispatches: starts are multiples of the binding
    /// offset alignment (in words, so aligned for any stride), bindings and grids within the
    /// limits.
    fn sample_chunks(&self, count: usize, stride: usize) -> Result<Vec<(usize, usize)>> {
        aligned_chunks(
            count,
            stride.max(QUERY_WORDS),
            &self.limits,
            WORKGROUP_SIZE,
            self.row_align,
            "one aligned chunk of Loop limit samples",
        )
    }

    /// Submits the evaluation of `samples` (the result stays on the GPU until downloaded).
    pub fn eval(&self, ctx: &GpuContext, samples: &GpuSamples) -> Result<()> {
        ctx.scoped(|| {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("loop_eval"),
                });
            let chunks = samples.chunks().iter().map(|(g, grid)| (g, *grid));
            encode_pass(&mut encoder, "loop_eval", &self.pipeline, chunks);
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })
    }

    /// The watertight tessellation of `limit` (the surface uploaded, built on `base`) with
    /// `segments` per base edge: the triangles of [`LoopLimit::tessellate`], positions and
    /// normals evaluated on the GPU (f32, widened).
    pub fn tessellate(
        &self,
        ctx: &GpuContext,
        limit: &LoopLimit,
        base: &Topology,
        segments: usize,
    ) -> Result<TriTessellation> {
        if limit.patches.len() != self.num_patches() {
            return Err(GpuError::BufferMismatch(format!(
                "a Loop surface of {} patches for tables of {}",
                limit.patches.len(),
                self.num_patches
            )));
        }
        let plan = tri_tessellation_plan(base, segments)?;
        let queries = plan_queries(limit, &plan)?;
        let samples = self.samples(ctx, &queries, false)?;
        self.eval(ctx, &samples)?;
        Ok(assemble(&plan, &samples.download(ctx)?))
    }
}
