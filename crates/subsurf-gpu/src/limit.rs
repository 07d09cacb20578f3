//! The limit surface of a [`PatchTable`] on the GPU: refinement, end-cap points and patch
//! evaluation with the data resident between passes (OpenSubdiv's `Osd` evaluators over a
//! `Far::PatchTable`).
//!
//! [`GpuLimit::new`] uploads the table once: per sparse level `d`, the gather of the level-`d`
//! vertices of its refined sub-mesh (`level_inputs[d]`, a stencil table of unit weights run
//! by [`StencilKernel`]) and its refinement stencils (run by a one-level [`GpuRefiner`]); the
//! end-cap local-point stencils ([`StencilKernel`]); and the patch map, per-patch data and
//! control indices read by `limit_eval` ([`crate::cpu::limit_eval`]). Per frame,
//! [`GpuLimit::update`] writes the base positions and rebuilds the flat point array
//! `[level 0 | level 1 | … | level L | local points]` on the GPU
//! ([`PatchTable::points`]): each level is gathered from the flat array, refined and copied
//! into place, then the local points are computed from the levels. [`GpuLimit::eval`] then evaluates a
//! sample set allocated once:
//!
//! - [`GpuLimit::tessellation`]: the samples of [`PatchTable::tessellation_plan`], with an
//!   index buffer of the plan's triangles; every seam sample is one vertex shared by index,
//!   so the mesh is watertight and its indices are those of
//!   [`subsurf::limit::LimitSurface::tessellate`];
//! - [`GpuLimit::samples`]: any `(ptex face, u, v)` list, with or without derivatives.
//!
//! Samples are dispatched in chunks whose query and output bindings start at aligned offsets,
//! so no binding exceeds `max_storage_buffer_binding_size` and no dispatch exceeds
//! `max_compute_workgroups_per_dimension`. When the patch tables and the point array each
//! fit one binding they are bound whole; otherwise every chunk of samples reads compacted
//! copies holding only what it samples (its ptex faces' patch sub-trees, their control
//! indices renumbered and, if the point array exceeds a binding too, its points gathered each
//! frame into a scratch buffer by a unit-weight [`StencilKernel`]; see
//! [`crate::limit_chunks`]), with results bit for bit those of the
//! whole tables. A flat point array over one binding is read by `update` the same way: the
//! level gathers and end-cap stencils gather their sources window by window
//! ([`StencilKernel`]), and sparse levels over one binding are refined from gathered inputs
//! ([`GpuRefiner`]); only the adapter's `max_buffer_size` bounds the point array.
//!
//! # Figures
//!
//! `cargo run --release -p subsurf-gpu --example gpu_pipeline` (`GPU_PIPELINE_ONLY=limit`):
//! `catmark_car` at isolation level 3 (11,499 patches: 8,943 regular, 1,316 single-crease,
//! 1,240 Gregory; 67,444 points on sparse levels), watertight `N × N` tessellation, medians,
//! on Mesa lavapipe (`llvmpipe (LLVM 15.0.6, 256 bits)`, Vulkan) on a shared 2-core machine
//! (quietest of several runs; others were up to 2× slower on both sides). M/s = million
//! samples per second.
//!
//! | N | samples | CPU, 2 threads: points + `eval_batch` | + `tessellate` | lavapipe: `update` + `eval` | + read-back | `eval` only |
//! |---|---|---|---|---|---|---|
//! | 5 | 25,357 | 1.50 ms (16.9 M/s) | 1.83 ms (13.8 M/s) | 5.71 ms (4.4 M/s) | 10.1 ms | 3.06 ms (8.3 M/s) |
//! | 9 | 101,077 | 4.59 ms (22.0 M/s) | 6.15 ms (16.5 M/s) | 10.6 ms (9.5 M/s) | 11.3 ms | 6.20 ms (16.3 M/s) |
//! | 17 | 403,717 | 16.9 ms (23.9 M/s) | 38.5 ms (10.5 M/s) | 28.5 ms (14.2 M/s) | 31.0 ms | 22.7 ms (17.8 M/s) |
//! | 33 | 1,613,797 | 91.7 ms (17.6 M/s) | 152 ms (10.6 M/s) | 98.2 ms (16.4 M/s) | 152 ms | 93.7 ms (17.2 M/s) |
//!
//! Compacted inputs (the same example with `with_limits` bindings of 256 KiB, so the car's
//! tables split into 8 chunks at N = 5 and 12 at N = 9; two runs): `eval` 15–20 ms against
//! 2.2 ms whole at N = 5 and 21 ms against 8.5 ms at N = 9, `update` + `eval` 22 ms against
//! 7.3 ms and 28–35 ms against 13.7 ms. At these forced limits the 800 KB point array itself
//! exceeds a binding, so the chunks' per-frame point gathers, the level gathers and the
//! end-cap stencils first gather their sources window by window ([`crate::gather`]); at the
//! real 128 MiB that happens only past about 11 million points. (Before sources were split,
//! the same forced run bound the point array whole: `eval` 5.6 ms at N = 5.)
//!
//! The software rasterizer runs the kernel as 8-wide SIMD lanes on the same two cores, so
//! evaluation alone is about as fast as the rayon CPU path; `update` (gathers and refinement
//! of the sparse levels, end-cap stencils, copies) adds 3–5 ms. One gather loop serves every
//! patch kind (the curves are chosen per kind, the Gregory face points scaled by their
//! rational weights): a first kernel with one gather per kind, whose divergent lanes ran
//! every branch, evaluated 0.5–1 M samples/s on lavapipe.

use crate::buffers::{read_back, storage_buffer_init, VertexBuffer, STORAGE_USAGE};
use crate::context::GpuContext;
use crate::cpu::limit_eval::{pack_queries, LimitTables, QUERY_WORDS, WORKGROUP_SIZE};
use crate::error::{GpuError, Result};
use crate::kernels::stencil::{ChunkLimits, StencilKernel};
use crate::kernels::{aligned_chunks, encode_pass, grid_2d};
use crate::limit_chunks;
pub use crate::limit_twin::{eval_cpu, tessellate_cpu, unpack_points};
use crate::refine::{auto_pipeline, uniform_init, GpuRefiner};
use crate::shaders;
use crate::shared::LimitConfig;
use crate::table::StencilTable;
use subsurf::limit::{LimitPoint, PatchTable, Tessellation};

mod edit;
pub use edit::EditUpload;

const WORD: u64 = 4;

/// A patch table resident on the GPU with its point array.
#[derive(Debug)]
pub struct GpuLimit {
    /// Per sparse level: the gather of its sub-mesh from the flat array, and its refinement.
    levels: Vec<(StencilKernel, GpuRefiner)>,
    level_offsets: Vec<u32>,
    num_base: usize,
    points: VertexBuffer,
    local: Option<(StencilKernel, VertexBuffer)>,
    tables: Tables,
    num_roots: u32,
    limits: ChunkLimits,
    row_align: usize,
    pipeline: wgpu::ComputePipeline,
    /// What crease edits compare against ([`GpuLimit::apply_edit`]).
    uploaded: edit::Uploaded,
}

/// The patch tables of `limit_eval`: bound whole when they and the point array fit one
/// binding, else kept on the host and compacted per chunk of samples ([`limit_chunks`]).
#[derive(Debug)]
enum Tables {
    Whole {
        patch_map: wgpu::Buffer,
        patch_info: wgpu::Buffer,
        cvs: wgpu::Buffer,
    },
    Chunked {
        tables: LimitTables,
        cv_offsets: Vec<u32>,
    },
}

/// A set of samples on the GPU: queries uploaded once, an output buffer of `stride` floats
/// per sample (position, unit normal, then `∂P/∂u`, `∂P/∂v` when `stride` is 12), and the
/// dispatches that fill it ([`GpuLimit::eval`]).
#[derive(Debug)]
pub struct GpuSamples {
    /// Number of samples.
    pub count: usize,
    /// Floats per sample (6 or 12).
    pub stride: usize,
    /// The output buffer (also usable as a vertex buffer).
    pub output: wgpu::Buffer,
    chunks: Vec<(wgpu::BindGroup, (u32, u32))>,
    /// With compacted inputs: the gather of every chunk's points into a scratch buffer.
    gather: Option<(StencilKernel, VertexBuffer)>,
    compacted: bool,
    _buffers: Vec<wgpu::Buffer>,
}

/// A watertight tessellation on the GPU: the samples of a [`TessellationPlan`] (6 floats per
/// vertex: position, unit normal) and an index buffer of its triangles.
///
/// [`TessellationPlan`]: subsurf::limit::TessellationPlan
#[derive(Debug)]
pub struct GpuTessellation {
    /// Samples per side actually used.
    pub samples_per_side: usize,
    /// The vertices.
    pub samples: GpuSamples,
    /// Index buffer, 3 `u32` per ccw triangle.
    pub indices: wgpu::Buffer,
    /// Number of indices.
    pub num_indices: usize,
    quads: Vec<[u32; 4]>,
}

impl GpuSamples {
    /// A set evaluated by `chunks` (bind group, workgroup grid) reading whole tables;
    /// `buffers` are kept alive with it.
    pub(crate) fn from_chunks(
        count: usize,
        stride: usize,
        output: wgpu::Buffer,
        chunks: Vec<(wgpu::BindGroup, (u32, u32))>,
        buffers: Vec<wgpu::Buffer>,
    ) -> Self {
        Self {
            count,
            stride,
            output,
            chunks,
            gather: None,
            compacted: false,
            _buffers: buffers,
        }
    }

    /// The dispatches: bind group and workgroup grid of each chunk.
    pub(crate) fn chunks(&self) -> &[(wgpu::BindGroup, (u32, u32))] {
        &self.chunks
    }

    /// Number of dispatches evaluating the set (more than one when chunked).
    pub fn num_dispatches(&self) -> usize {
        self.chunks.len()
    }

    /// Whether the chunks read compacted copies of the patch tables and points (tables or
    /// point array larger than one binding) rather than the whole tables.
    pub fn inputs_compacted(&self) -> bool {
        self.compacted
    }

    /// Reads the output back (`stride` floats per sample; waits for the submitted work).
    pub fn download(&self, ctx: &GpuContext) -> Result<Vec<f32>> {
        read_back(ctx, &self.output, (self.count * self.stride) as u64 * WORD)
    }

    /// Reads the output back as limit points (derivatives zero when `stride` is 6).
    pub fn download_points(&self, ctx: &GpuContext) -> Result<Vec<LimitPoint>> {
        Ok(unpack_points(&self.download(ctx)?, self.stride))
    }
}

impl GpuTessellation {
    /// Reads the tessellation back: positions, normals and the plan's quads.
    pub fn download(&self, ctx: &GpuContext) -> Result<Tessellation> {
        let out = self.samples.download(ctx)?;
        Ok(Tessellation {
            samples_per_side: self.samples_per_side,
            positions: out.chunks_exact(6).map(|v| [v[0], v[1], v[2]]).collect(),
            normals: out.chunks_exact(6).map(|v| [v[3], v[4], v[5]]).collect(),
            quads: self.quads.clone(),
        })
    }
}

fn upload_words(ctx: &GpuContext, what: &'static str, words: &[u32]) -> Result<wgpu::Buffer> {
    let zero = [0u32];
    let words = if words.is_empty() { &zero[..] } else { words };
    storage_buffer_init(ctx, what, bytemuck::cast_slice(words))
}

impl GpuLimit {
    /// Uploads `table`, chunked against the adapter's limits. Positions are zero until
    /// [`Self::update`].
    pub fn new(ctx: &GpuContext, table: &PatchTable) -> Result<Self> {
        Self::with_limits(ctx, table, ChunkLimits::from_context(ctx))
    }

    /// Uploads `table` chunked against `limits` (clamped to the adapter's; lower values force
    /// more chunks, which tests use to exercise chunking).
    pub fn with_limits(ctx: &GpuContext, table: &PatchTable, limits: ChunkLimits) -> Result<Self> {
        let adapter = ChunkLimits::from_context(ctx);
        let limits = ChunkLimits {
            max_binding_bytes: limits.max_binding_bytes.min(adapter.max_binding_bytes),
            max_workgroups_per_dimension: limits
                .max_workgroups_per_dimension
                .clamp(1, adapter.max_workgroups_per_dimension),
            max_stride: 12,
        };
        if table.level_inputs().len() != table.level_stencils().len()
            || table.level_offsets().len() != table.level_stencils().len() + 2
        {
            return Err(GpuError::InvalidStencil(format!(
                "{} level stencils, {} level inputs, {} level offsets",
                table.level_stencils().len(),
                table.level_inputs().len(),
                table.level_offsets().len()
            )));
        }
        let gather_limits = ChunkLimits {
            max_stride: 3,
            ..limits
        };
        let mut levels = Vec::with_capacity(table.level_stencils().len());
        for (d, (s, inputs)) in table
            .level_stencils()
            .iter()
            .zip(table.level_inputs())
            .enumerate()
        {
            // Row i of the gather copies flat point level_offsets[d] + inputs[i] (weight 1:
            // exact).
            let first = table.level_offsets()[d];
            let offsets: Vec<u32> = (0..=inputs.len() as u32).collect();
            let indices: Vec<u32> = inputs.iter().map(|&i| first + i).collect();
            let weights = vec![1.0f32; inputs.len()];
            let gather = StencilKernel::with_limits(
                ctx,
                &StencilTable::new(&offsets, &indices, &weights)?,
                gather_limits,
            )?;
            let child = (table.level_offsets()[d + 2] - table.level_offsets()[d + 1]) as usize;
            let refiner = GpuRefiner::from_stencils(
                ctx,
                &[inputs.len(), child],
                std::slice::from_ref(s),
                limits,
            )?;
            levels.push((gather, refiner));
        }
        let num_points = table.num_points();
        let points = VertexBuffer::zeroed(ctx, num_points, 3)?;
        let lp = &table.local_points();
        if table.local_segments().iter().filter(|&&r| r > 0).count() > 1 {
            // Rows that read local points of earlier segments (a table edited locally).
            return Err(GpuError::BufferMismatch(
                "the table was edited locally (local points in segments, \
                 PatchTable::local_segments): upload a fresh build of the edited mesh"
                    .into(),
            ));
        }
        let local = if lp.num_rows() > 0 {
            let t = StencilTable::new(lp.offsets(), lp.indices(), lp.weights())?;
            // Relative rows, as `PatchTable::points` (long rows at high-valence vertices).
            let kernel = StencilKernel::with_limits(
                ctx,
                &t,
                ChunkLimits {
                    max_stride: 3,
                    ..limits
                },
            )?
            .relative(true);
            Some((kernel, VertexBuffer::zeroed(ctx, lp.num_rows(), 3)?))
        } else {
            None
        };
        let t = LimitTables::new(table);
        let uploaded = edit::Uploaded::new(table, &t);
        let num_roots = t.num_roots;
        let fits = |words: usize| words as u64 * WORD <= limits.max_binding_bytes;
        let tables = if [
            t.patch_map.len(),
            t.patch_info.len(),
            t.cvs.len(),
            3 * num_points,
        ]
        .into_iter()
        .all(fits)
        {
            Tables::Whole {
                patch_map: upload_words(ctx, "limit patch map", &t.patch_map)?,
                patch_info: upload_words(ctx, "limit patch data", &t.patch_info)?,
                cvs: upload_words(ctx, "limit control indices", &t.cvs)?,
            }
        } else {
            Tables::Chunked {
                tables: t,
                cv_offsets: table.cv_offsets().to_vec(),
            }
        };
        let pipeline = auto_pipeline(ctx, "limit_eval", shaders::LIMIT_EVAL, "main")?;
        let row_align =
            (ctx.limits().min_storage_buffer_offset_alignment as usize / WORD as usize).max(1);
        Ok(Self {
            levels,
            level_offsets: table.level_offsets().to_vec(),
            num_base: table.level_offsets()[1] as usize,
            points,
            local,
            tables,
            num_roots,
            limits,
            row_align,
            pipeline,
            uploaded,
        })
    }

    /// Number of points (level vertices and local points) refreshed by [`Self::update`].
    pub fn num_points(&self) -> usize {
        self.points.vertex_count()
    }

    /// The flat point array on the GPU (3 floats per point).
    pub fn points(&self) -> &VertexBuffer {
        &self.points
    }

    /// Reads the point array back (waits for the submitted work).
    pub fn download_points(&self, ctx: &GpuContext) -> Result<Vec<[f32; 3]>> {
        self.points.download_triples(ctx)
    }

    /// Writes the whole point array computed elsewhere ([`subsurf::limit::LimitSurface`]'s
    /// `points`, [`PatchTable::points`]) instead of refining it on the GPU: for a caller that
    /// already holds it. Sample sets keep their bindings; call [`Self::eval`] to re-evaluate
    /// them.
    pub fn set_points(&self, ctx: &GpuContext, points: &[[f32; 3]]) -> Result<()> {
        if points.len() != self.num_points() {
            return Err(GpuError::BufferMismatch(format!(
                "{} points for a point array of {}",
                points.len(),
                self.num_points()
            )));
        }
        self.points.write(ctx, points.as_flattened())
    }

    /// Writes new base positions and rebuilds the point array on the GPU: refinement, copies
    /// of each level into place, end-cap local points, all recorded into one submission.
    /// Sample sets keep their bindings; call [`Self::eval`] to re-evaluate them.
    pub fn update(&mut self, ctx: &GpuContext, positions: &[[f32; 3]]) -> Result<()> {
        if positions.len() != self.num_base {
            return Err(GpuError::BufferMismatch(format!(
                "{} base positions for a patch table of {} base vertices",
                positions.len(),
                self.num_base
            )));
        }
        if !positions.is_empty() {
            ctx.queue
                .write_buffer(self.points.raw(), 0, bytemuck::cast_slice(positions));
        }
        self.rebuild(ctx, None)
    }

    /// [`Self::update`] from base positions already on the GPU (3 floats per base vertex;
    /// for example deformed by a compute pass of the caller's): copied into the point array
    /// in the same submission, nothing goes through the host.
    pub fn update_from(&mut self, ctx: &GpuContext, positions: &VertexBuffer) -> Result<()> {
        if positions.vertex_count() != self.num_base || positions.stride() != 3 {
            return Err(GpuError::BufferMismatch(format!(
                "{} vertices of stride {} for a patch table of {} base vertices of stride 3",
                positions.vertex_count(),
                positions.stride(),
                self.num_base
            )));
        }
        self.rebuild(ctx, Some(positions))
    }

    /// Records the refinement, copies and end-cap points (after copying `base` into the
    /// point array, if given) and submits them.
    fn rebuild(&mut self, ctx: &GpuContext, base: Option<&VertexBuffer>) -> Result<()> {
        let points = &self.points;
        let level_offsets = &self.level_offsets;
        let levels = &mut self.levels;
        let local = &mut self.local;
        ctx.scoped(|| {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("limit update"),
                });
            if let Some(base) = base.filter(|b| b.len_floats() > 0) {
                let bytes = base.len_floats() as u64 * WORD;
                encoder.copy_buffer_to_buffer(base.raw(), 0, points.raw(), 0, bytes);
            }
            for (d, (gather, refiner)) in levels.iter_mut().enumerate() {
                gather.encode(ctx, &mut encoder, points, refiner.input_mut())?;
                refiner.encode(&mut encoder);
                let out = refiner.output();
                let bytes = out.len_floats() as u64 * WORD;
                if bytes > 0 {
                    let at = u64::from(level_offsets[d + 1]) * 3 * WORD;
                    encoder.copy_buffer_to_buffer(out.raw(), 0, points.raw(), at, bytes);
                }
            }
            if let Some((kernel, local)) = local {
                kernel.encode(ctx, &mut encoder, points, local)?;
                let first = u64::from(*level_offsets.last().unwrap_or(&0)) * 3 * WORD;
                let bytes = local.len_floats() as u64 * WORD;
                encoder.copy_buffer_to_buffer(local.raw(), 0, points.raw(), first, bytes);
            }
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })
    }

    /// Uploads a sample set of `(ptex face, u, v)` queries; `derivatives` selects 12 floats per
    /// sample (with `∂P/∂u`, `∂P/∂v`) instead of 6. A sample in a hole, or of a ptex face out
    /// of range, evaluates to zeros (as [`subsurf::limit::LimitSurface::tessellate`] writes
    /// it); parameters are clamped to `[0, 1]` and must be finite.
    pub fn samples(
        &self,
        ctx: &GpuContext,
        queries: &[(u32, f32, f32)],
        derivatives: bool,
    ) -> Result<GpuSamples> {
        let (count, stride) = check_samples(queries, derivatives)?;
        let words = pack_queries(queries);
        let output = sample_output(ctx, "limit samples", count, stride)?;
        let layout = self.pipeline.get_bind_group_layout(0);
        let (patch_map, patch_info, cvs) = match &self.tables {
            Tables::Whole {
                patch_map,
                patch_info,
                cvs,
            } => (patch_map, patch_info, cvs),
            Tables::Chunked { tables, cv_offsets } => {
                let max_dispatch = u64::from(self.limits.max_workgroups_per_dimension).pow(2)
                    * u64::from(WORKGROUP_SIZE);
                // Points compacted (and gathered per frame) only when the flat array exceeds
                // one binding.
                let compact_points =
                    (3 * self.num_points()) as u64 * WORD > self.limits.max_binding_bytes;
                let plan = limit_chunks::plan(
                    tables,
                    cv_offsets,
                    self.num_points(),
                    &words,
                    stride,
                    limit_chunks::PlanLimits {
                        max_words: (self.limits.max_binding_bytes / WORD) as usize,
                        max_samples: max_dispatch.min(u64::from(u32::MAX)) as usize,
                        align: self.row_align,
                        compact_points,
                    },
                )?;
                let set = limit_chunks::upload(
                    ctx,
                    &layout,
                    self.limits,
                    &plan,
                    stride,
                    self.row_align,
                    &output,
                    (!compact_points).then_some(self.points.raw()),
                )?;
                return Ok(GpuSamples {
                    count,
                    stride,
                    output,
                    chunks: set.dispatches,
                    gather: set.gather,
                    compacted: true,
                    _buffers: set.buffers,
                });
            }
        };
        let queries_buf = storage_buffer_init(ctx, "limit queries", bytemuck::cast_slice(&words))?;
        let mut chunks = Vec::new();
        let mut configs = Vec::new();
        for (start, end) in self.sample_chunks(count, stride)? {
            let n = (end - start) as u32;
            let (gx, gy) = grid_2d(n, WORKGROUP_SIZE, self.limits.max_workgroups_per_dimension);
            let config = LimitConfig {
                item_count: n,
                grid_width: gx * WORKGROUP_SIZE,
                out_stride: stride as u32,
                num_roots: self.num_roots,
            };
            let config_buf = uniform_init(ctx, bytemuck::bytes_of(&config))?;
            let bind_group = ctx.scoped(|| {
                Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("limit_eval"),
                    layout: &layout,
                    entries: &[
                        entry(0, config_buf.as_entire_binding()),
                        entry(1, part(&queries_buf, start, n, QUERY_WORDS)),
                        entry(2, patch_map.as_entire_binding()),
                        entry(3, patch_info.as_entire_binding()),
                        entry(4, cvs.as_entire_binding()),
                        entry(5, self.points.raw().as_entire_binding()),
                        entry(6, part(&output, start, n, stride)),
                    ],
                }))
            })?;
            chunks.push((bind_group, (gx, gy)));
            configs.push(config_buf);
        }
        configs.push(queries_buf);
        Ok(GpuSamples {
            count,
            stride,
            output,
            chunks,
            gather: None,
            compacted: false,
            _buffers: configs,
        })
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
            "one aligned chunk of limit samples",
        )
    }

    /// The samples of the `N × N` watertight tessellation ([`PatchTable::tessellation_plan`])
    /// with its index buffer.
    pub fn tessellation(
        &self,
        ctx: &GpuContext,
        table: &PatchTable,
        samples_per_side: usize,
    ) -> Result<GpuTessellation> {
        let plan = table.tessellation_plan(samples_per_side)?;
        let samples = self.samples(ctx, &plan.queries, false)?;
        let tris = plan.triangles();
        let index_words: &[u32] = tris.as_flattened();
        let indices = ctx.scoped(|| {
            use wgpu::util::DeviceExt;
            let zero = [0u32];
            let words = if index_words.is_empty() {
                &zero[..]
            } else {
                index_words
            };
            Ok(ctx
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("limit indices"),
                    contents: bytemuck::cast_slice(words),
                    usage: wgpu::BufferUsages::INDEX
                        | wgpu::BufferUsages::STORAGE
                        | wgpu::BufferUsages::COPY_SRC,
                }))
        })?;
        Ok(GpuTessellation {
            samples_per_side: plan.samples_per_side,
            samples,
            indices,
            num_indices: index_words.len(),
            quads: plan.quads,
        })
    }

    /// Submits the evaluation of `samples` from the current point array (the result stays on
    /// the GPU until downloaded).
    pub fn eval(&self, ctx: &GpuContext, samples: &GpuSamples) -> Result<()> {
        ctx.scoped(|| {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("limit_eval"),
                });
            if let Some((gather, scratch)) = &samples.gather {
                gather.encode(ctx, &mut encoder, &self.points, &mut scratch.alias())?;
            }
            let chunks = samples.chunks.iter().map(|(g, grid)| (g, *grid));
            encode_pass(&mut encoder, "limit_eval", &self.pipeline, chunks);
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })
    }
}

/// Samples `start .. start + n` of a buffer of `words_per` words per sample.
fn part(
    buffer: &wgpu::Buffer,
    start: usize,
    n: u32,
    words_per: usize,
) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: (start * words_per) as u64 * WORD,
        size: wgpu::BufferSize::new(u64::from(n) * words_per as u64 * WORD),
    })
}

fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

/// Checks a sample set for evaluation (finite parameters, 32-bit indexing of the output);
/// returns the number of samples and the output words per sample (12 with derivatives, else
/// 6).
pub(crate) fn check_samples(
    queries: &[(u32, f32, f32)],
    derivatives: bool,
) -> Result<(usize, usize)> {
    if let Some(i) = queries
        .iter()
        .position(|q| !(q.1.is_finite() && q.2.is_finite()))
    {
        return Err(GpuError::BufferMismatch(format!(
            "sample {i} has a non-finite parameter {:?}",
            queries[i]
        )));
    }
    let stride = if derivatives { 12 } else { 6 };
    let count = queries.len();
    if count >= u32::MAX as usize / stride {
        return Err(GpuError::BufferMismatch(format!(
            "{count} samples exceed 32-bit indexing"
        )));
    }
    Ok((count, stride))
}

/// The output buffer of `count` evaluated samples of `stride` words (storage, and a vertex
/// buffer for drawing).
pub(crate) fn sample_output(
    ctx: &GpuContext,
    label: &str,
    count: usize,
    stride: usize,
) -> Result<wgpu::Buffer> {
    ctx.scoped(|| {
        Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: ((count * stride) as u64 * WORD).max(WORD),
            usage: STORAGE_USAGE | wgpu::BufferUsages::VERTEX,
            mapped_at_creation: false,
        }))
    })
}
