//! `stencil_apply` on the GPU: applies a [`StencilTable`] to a [`VertexBuffer`].
//!
//! The table is uploaded once and split into chunks of rows so that no binding exceeds
//! `max_storage_buffer_binding_size` and no dispatch exceeds
//! `max_compute_workgroups_per_dimension` (a 2D grid is used when one dimension is not
//! enough). Each chunk holds its own `offsets` (rebased to start at 0), `indices` and
//! `weights`; the destination is bound at the chunk's first row, which is a multiple of
//! `min_storage_buffer_offset_alignment / 4` rows so the binding offset is aligned for any
//! stride. The source is bound from vertex 0 to the last vertex the table reads. When that
//! exceeds one binding (sized for `max_stride`), each chunk first gathers the source
//! vertices it reads into a scratch buffer, window by aligned window of the source, with
//! unit-weight dispatches of the same kernel ([`crate::gather`]), and its rows read the
//! scratch: the same bits as one binding of the whole source.
//!
//! Per frame a caller re-uploads only the source ([`VertexBuffer::write`]) and calls
//! [`StencilKernel::apply`]; the results stay on the GPU until downloaded.

use crate::buffers::{storage_buffer_init, VertexBuffer, STORAGE_USAGE};
use crate::context::GpuContext;
use crate::cpu::stencil_apply::WORKGROUP_SIZE;
use crate::error::{GpuError, Result};
use crate::gather::plan_gather;
use crate::kernels::{grid_2d, part, whole};
use crate::shaders;
use crate::shared::StencilConfig;
use crate::table::StencilTable;

const WORD: u64 = 4;

/// Limits the table is chunked against. [`ChunkLimits::from_context`] gives the adapter's;
/// lower values (never higher: they are clamped to the adapter's) force more chunks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkLimits {
    /// Largest storage binding, in bytes.
    pub max_binding_bytes: u64,
    /// Largest workgroup count along one dispatch dimension.
    pub max_workgroups_per_dimension: u32,
    /// Largest stride the destination binding of a chunk is sized for. Applying with a
    /// larger stride still works when each chunk's destination fits the binding limit.
    pub max_stride: usize,
}

impl ChunkLimits {
    /// The adapter's limits, sized for strides up to 4 floats.
    pub fn from_context(ctx: &GpuContext) -> Self {
        let l = ctx.limits();
        Self {
            max_binding_bytes: l.max_storage_buffer_binding_size.min(l.max_buffer_size),
            max_workgroups_per_dimension: l.max_compute_workgroups_per_dimension,
            max_stride: 4,
        }
    }

    pub(crate) fn clamped_to(self, adapter: ChunkLimits) -> Self {
        Self {
            max_binding_bytes: self.max_binding_bytes.min(adapter.max_binding_bytes),
            max_workgroups_per_dimension: self
                .max_workgroups_per_dimension
                .min(adapter.max_workgroups_per_dimension)
                .max(1),
            max_stride: self.max_stride.max(1),
        }
    }
}

/// A contiguous range of table rows uploaded together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkRange {
    /// First row.
    pub row_start: usize,
    /// One past the last row.
    pub row_end: usize,
}

/// Splits `table` into chunks: greedy over groups of `row_align` rows, each chunk as large
/// as the limits allow. Chunk starts are multiples of `row_align`.
pub fn plan_chunks(
    table: &StencilTable<'_>,
    limits: &ChunkLimits,
    row_align: usize,
) -> Result<Vec<ChunkRange>> {
    let offsets = table.offsets();
    let rows = table.rows();
    let row_align = row_align.max(1);
    let max_words = (limits.max_binding_bytes / WORD) as usize;
    let max_dispatch_rows =
        u64::from(limits.max_workgroups_per_dimension).pow(2) * u64::from(WORKGROUP_SIZE);
    let fits = |start: usize, end: usize| {
        let n = end - start;
        let entries = (offsets[end] - offsets[start]) as usize;
        n < max_words
            && n.saturating_mul(limits.max_stride) <= max_words
            && entries <= max_words
            && (n as u64) <= max_dispatch_rows
            && n <= u32::MAX as usize
    };
    let mut chunks = Vec::new();
    let mut start = 0;
    while start < rows {
        let mut end = start;
        loop {
            let next = (end + row_align).min(rows);
            if next == end || !fits(start, next) {
                break;
            }
            end = next;
        }
        if end == start {
            let next = (start + row_align).min(rows);
            return Err(GpuError::TooLarge {
                what: "stencil rows of one aligned chunk",
                needed: (offsets[next] - offsets[start]) as u64 * WORD,
                limit: limits.max_binding_bytes,
            });
        }
        chunks.push(ChunkRange {
            row_start: start,
            row_end: end,
        });
        start = end;
    }
    Ok(chunks)
}

/// One dispatch's table on the GPU (`offsets` rebased to 0) and its uniform.
#[derive(Debug)]
struct Rows {
    rows: u32,
    offsets: wgpu::Buffer,
    indices: wgpu::Buffer,
    weights: wgpu::Buffer,
    config: wgpu::Buffer,
}

impl Rows {
    fn upload(ctx: &GpuContext, offsets: &[u32], indices: &[u32], weights: &[f32]) -> Result<Self> {
        Ok(Rows {
            rows: (offsets.len() - 1) as u32,
            offsets: storage_buffer_init(ctx, "stencil offsets", bytemuck::cast_slice(offsets))?,
            indices: storage_buffer_init(ctx, "stencil indices", bytemuck::cast_slice(indices))?,
            weights: storage_buffer_init(ctx, "stencil weights", bytemuck::cast_slice(weights))?,
            config: ctx.scoped(|| {
                Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("stencil config"),
                    size: std::mem::size_of::<StencilConfig>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }))
            })?,
        })
    }

    /// Unit-weight rows copying source vertex `rel[i]` to row `i` (a gather, exact).
    fn gather(ctx: &GpuContext, rel: &[u32]) -> Result<Self> {
        let offsets: Vec<u32> = (0..=rel.len() as u32).collect();
        Self::upload(ctx, &offsets, rel, &vec![1.0; rel.len()])
    }
}

#[derive(Debug)]
struct Chunk {
    range: ChunkRange,
    table: Rows,
    /// Gathered source: the chunk's scratch rows and its gathers.
    gathered: Option<(usize, Vec<SourceGather>)>,
}

/// Rows copying source vertices of window `window` to scratch rows `first..`.
#[derive(Debug)]
struct SourceGather {
    window: usize,
    first: usize,
    rows: Rows,
}

/// A stencil table uploaded to the GPU with the `stencil_apply` pipeline.
#[derive(Debug)]
pub struct StencilKernel {
    rows: usize,
    min_source_vertices: usize,
    limits: ChunkLimits,
    /// The adapter's binding limit, which bounds the (unchunked) source binding.
    source_binding_limit: u64,
    /// Vertices per source window when the source is gathered.
    source_window: Option<usize>,
    /// Scratch of the gathered source (`max_stride` floats per row).
    scratch: Option<wgpu::Buffer>,
    chunks: Vec<Chunk>,
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    /// Rows applied relative to their first input ([`StencilKernel::relative`]).
    relative: bool,
}

impl StencilKernel {
    /// Validates and uploads the table (`offsets`: rows + 1, `indices` and `weights`: one
    /// per entry), chunked against the adapter's limits.
    pub fn new(
        ctx: &GpuContext,
        offsets: &[u32],
        indices: &[u32],
        weights: &[f32],
    ) -> Result<Self> {
        let table = StencilTable::new(offsets, indices, weights)?;
        Self::with_limits(ctx, &table, ChunkLimits::from_context(ctx))
    }

    /// Applies a library stencil table once to `src` and reads the result back (`rows ×
    /// stride` floats): for a step run once, such as the limit step after refinement.
    pub fn apply_once(
        ctx: &GpuContext,
        table: &subsurf::StencilTable,
        src: &VertexBuffer,
    ) -> Result<Vec<f32>> {
        let kernel = Self::new(ctx, table.offsets(), table.indices(), table.weights())?;
        let mut dst = VertexBuffer::zeroed(ctx, table.num_rows(), src.stride())?;
        kernel.apply(ctx, src, &mut dst)?;
        dst.download(ctx)
    }

    /// Uploads `table` chunked against `limits` (clamped to the adapter's limits).
    pub fn with_limits(
        ctx: &GpuContext,
        table: &StencilTable<'_>,
        limits: ChunkLimits,
    ) -> Result<Self> {
        let adapter_limits = ChunkLimits::from_context(ctx);
        let limits = limits.clamped_to(adapter_limits);
        let row_align =
            (ctx.limits().min_storage_buffer_offset_alignment as usize / WORD as usize).max(1);
        let b = limits.max_binding_bytes;
        let max_stride = limits.max_stride as u64;
        // Gather the source when the vertices the table reads exceed one binding. Windows are
        // as large as a binding allows; chunks are then planned so that their inputs (at most
        // one per entry) plus the alignment padding of one gather per window fill at most the
        // scratch binding.
        let gathered = table.min_source_vertices() as u64 * max_stride * WORD > b;
        let window = (b / (max_stride * WORD)) as usize / row_align * row_align;
        if gathered && window == 0 {
            return Err(GpuError::TooLarge {
                what: "one aligned window of the stencil source",
                needed: row_align as u64 * max_stride * WORD,
                limit: b,
            });
        }
        let plan_limits = if gathered {
            let windows = table.min_source_vertices().div_ceil(window) as u64;
            let padding = windows * row_align as u64 * max_stride * WORD;
            ChunkLimits {
                max_binding_bytes: b.saturating_sub(padding) / max_stride,
                ..limits
            }
        } else {
            limits
        };
        let ranges = plan_chunks(table, &plan_limits, row_align)?;
        let offsets = table.offsets();
        let mut chunks = Vec::with_capacity(ranges.len());
        let mut scratch_rows = 0usize;
        for range in ranges {
            let (e0, e1) = (
                offsets[range.row_start] as usize,
                offsets[range.row_end] as usize,
            );
            let local: Vec<u32> = offsets[range.row_start..=range.row_end]
                .iter()
                .map(|&o| o - offsets[range.row_start])
                .collect();
            let mut indices = table.indices()[e0..e1].to_vec();
            let gathered = if gathered {
                let plan = plan_gather(&indices, usize::MAX, window, row_align);
                if plan.inputs as u64 * max_stride * WORD > b {
                    return Err(GpuError::TooLarge {
                        what: "gathered stencil source of one chunk",
                        needed: plan.inputs as u64 * max_stride * WORD,
                        limit: b,
                    });
                }
                scratch_rows = scratch_rows.max(plan.inputs);
                indices = plan.local;
                let gathers = plan
                    .gathers
                    .iter()
                    .map(|g| {
                        Ok(SourceGather {
                            window: g.window,
                            first: g.first as usize,
                            rows: Rows::gather(ctx, &g.rel)?,
                        })
                    })
                    .collect::<Result<Vec<_>>>()?;
                Some((plan.inputs, gathers))
            } else {
                None
            };
            chunks.push(Chunk {
                range,
                table: Rows::upload(ctx, &local, &indices, &table.weights()[e0..e1])?,
                gathered,
            });
        }
        let scratch = if gathered {
            let size = (scratch_rows as u64 * max_stride * WORD).max(WORD);
            Some(ctx.scoped(|| {
                Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("stencil gathered source"),
                    size,
                    usage: STORAGE_USAGE,
                    mapped_at_creation: false,
                }))
            })?)
        } else {
            None
        };
        let (layout, pipeline) = create_pipeline(ctx)?;
        Ok(Self {
            rows: table.rows(),
            min_source_vertices: table.min_source_vertices(),
            limits,
            source_binding_limit: adapter_limits.max_binding_bytes,
            source_window: gathered.then_some(window),
            scratch,
            chunks,
            layout,
            pipeline,
            relative: false,
        })
    }

    /// Applies every row relative to its first input, `x_0 + Σ w (x − x_0)`: for tables
    /// whose rows sum to 1 (patch points, end caps), the rounding is then that of the row's
    /// neighbourhood, not of its distance from the origin (as
    /// `subsurf::limit::apply_relative`).
    pub fn relative(mut self, on: bool) -> Self {
        self.relative = on;
        self
    }

    /// Number of rows (destination vertices).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Whether each chunk gathers its source vertices (the vertices the table reads exceed
    /// one binding at `max_stride`).
    pub fn gathers_source(&self) -> bool {
        self.source_window.is_some()
    }

    /// Number of chunks the table was split into.
    pub fn num_chunks(&self) -> usize {
        self.chunks.len()
    }

    /// The row ranges of the chunks.
    pub fn chunk_ranges(&self) -> Vec<ChunkRange> {
        self.chunks.iter().map(|c| c.range).collect()
    }

    /// Computes `dst = table · src` on the GPU and submits the work; `dst` stays on the GPU
    /// (download it with [`VertexBuffer::download`], which waits for completion).
    pub fn apply(
        &self,
        ctx: &GpuContext,
        src: &VertexBuffer,
        dst: &mut VertexBuffer,
    ) -> Result<()> {
        ctx.scoped(|| {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("stencil_apply"),
                });
            self.encode(ctx, &mut encoder, src, dst)?;
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })
    }

    /// Records [`Self::apply`] into `encoder` (submitted by the caller). The chunks'
    /// uniforms are written through the queue, so one encoder may hold one application of
    /// a given kernel per stride.
    pub(crate) fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        src: &VertexBuffer,
        dst: &mut VertexBuffer,
    ) -> Result<()> {
        let stride = src.stride();
        if dst.stride() != stride {
            return Err(GpuError::BufferMismatch(format!(
                "source stride {stride} but destination stride {}",
                dst.stride()
            )));
        }
        if dst.vertex_count() != self.rows {
            return Err(GpuError::BufferMismatch(format!(
                "destination holds {} vertices but the table has {} rows",
                dst.vertex_count(),
                self.rows
            )));
        }
        if src.vertex_count() < self.min_source_vertices {
            return Err(GpuError::BufferMismatch(format!(
                "table references {} source vertices but the source holds {}",
                self.min_source_vertices,
                src.vertex_count()
            )));
        }
        let stride_u32 = u32::try_from(stride)
            .map_err(|_| GpuError::BufferMismatch(format!("stride {stride} is too large")))?;
        let vertex_bytes = |n: usize| n as u64 * u64::from(stride_u32) * WORD;
        // The source binding(s): up to the last vertex read, or windows for the gathers.
        let src_bytes = vertex_bytes(self.min_source_vertices);
        match self.source_window {
            None if src_bytes > self.source_binding_limit => {
                return Err(GpuError::TooLarge {
                    what: "stencil source binding",
                    needed: src_bytes,
                    limit: self.source_binding_limit,
                });
            }
            Some(_) if stride > self.limits.max_stride => {
                return Err(GpuError::TooLarge {
                    what: "gathered stencil source of a stride above the planned max_stride",
                    needed: vertex_bytes(1),
                    limit: self.limits.max_stride as u64 * WORD,
                });
            }
            _ => {}
        }
        let source = part(4, src.raw(), 0, src_bytes);
        let mut dispatches = Vec::new();
        for chunk in &self.chunks {
            let chunk_source = match (&chunk.gathered, self.source_window, &self.scratch) {
                (Some((inputs, gathers)), Some(window), Some(scratch)) => {
                    for SourceGather {
                        window: w,
                        first,
                        rows,
                    } in gathers
                    {
                        let from = w * window;
                        let n = window.min(src.vertex_count() - from);
                        dispatches.push(self.bind_group(
                            ctx,
                            rows,
                            part(4, src.raw(), vertex_bytes(from), vertex_bytes(n)),
                            part(
                                5,
                                scratch,
                                vertex_bytes(*first),
                                vertex_bytes(rows.rows as usize),
                            ),
                            stride_u32,
                        ));
                    }
                    part(4, scratch, 0, vertex_bytes(*inputs))
                }
                _ => source.clone(),
            };
            dispatches.push(self.bind_group(
                ctx,
                &chunk.table,
                chunk_source,
                self.destination(dst, chunk, stride_u32)?,
                stride_u32,
            ));
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("stencil_apply"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        for (bind_group, gx, gy) in &dispatches {
            pass.set_bind_group(0, bind_group, &[]);
            pass.dispatch_workgroups(*gx, *gy, 1);
        }
        Ok(())
    }

    /// The destination binding of `chunk`: its rows of `dst`.
    fn destination<'a>(
        &self,
        dst: &'a VertexBuffer,
        chunk: &Chunk,
        stride: u32,
    ) -> Result<wgpu::BindGroupEntry<'a>> {
        let rows = (chunk.range.row_end - chunk.range.row_start) as u64;
        let dst_bytes = rows * u64::from(stride) * WORD;
        if dst_bytes > self.limits.max_binding_bytes {
            return Err(GpuError::TooLarge {
                what: "stencil destination chunk binding",
                needed: dst_bytes,
                limit: self.limits.max_binding_bytes,
            });
        }
        let offset = chunk.range.row_start as u64 * u64::from(stride) * WORD;
        Ok(part(5, dst.raw(), offset, dst_bytes))
    }

    /// Writes the uniform of a dispatch of `rows` and returns its bind group and grid.
    fn bind_group(
        &self,
        ctx: &GpuContext,
        rows: &Rows,
        source: wgpu::BindGroupEntry<'_>,
        destination: wgpu::BindGroupEntry<'_>,
        stride: u32,
    ) -> (wgpu::BindGroup, u32, u32) {
        let (gx, gy) = grid_2d(
            rows.rows,
            WORKGROUP_SIZE,
            self.limits.max_workgroups_per_dimension,
        );
        let c = StencilConfig {
            row_count: rows.rows,
            stride,
            grid_width: gx * WORKGROUP_SIZE,
            relative: u32::from(self.relative),
        };
        ctx.queue
            .write_buffer(&rows.config, 0, bytemuck::bytes_of(&c));
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("stencil_apply"),
            layout: &self.layout,
            entries: &[
                whole(0, &rows.config),
                whole(1, &rows.offsets),
                whole(2, &rows.indices),
                whole(3, &rows.weights),
                source,
                destination,
            ],
        });
        (bind_group, gx, gy)
    }
}

fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Bind group layout (bindings 0..=5 of `shaders/stencil_apply.wgsl`) and pipeline, compiled
/// once per device ([`GpuContext::kernel`]; the layout is the pipeline's own, which bind
/// groups made from it share).
fn create_pipeline(ctx: &GpuContext) -> Result<(wgpu::BindGroupLayout, wgpu::ComputePipeline)> {
    let pipeline = ctx.kernel(shaders::STENCIL_APPLY, "main", || make_pipeline(ctx))?;
    Ok((pipeline.get_bind_group_layout(0), pipeline))
}

fn make_pipeline(ctx: &GpuContext) -> wgpu::ComputePipeline {
    let device = &ctx.device;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("stencil_apply"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: wgpu::BufferSize::new(
                        std::mem::size_of::<StencilConfig>() as u64
                    ),
                },
                count: None,
            },
            storage_entry(1, true),
            storage_entry(2, true),
            storage_entry(3, true),
            storage_entry(4, true),
            storage_entry(5, false),
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("stencil_apply"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("stencil_apply"),
        source: wgpu::ShaderSource::Wgsl(shaders::STENCIL_APPLY.into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("stencil_apply"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(bytes: u64, wg: u32) -> ChunkLimits {
        ChunkLimits {
            max_binding_bytes: bytes,
            max_workgroups_per_dimension: wg,
            max_stride: 3,
        }
    }

    #[test]
    fn chunks_partition_rows_and_respect_limits() {
        // 1000 rows of 1..=7 entries.
        let mut offsets = vec![0u32];
        for r in 0..1000u32 {
            offsets.push(offsets.last().unwrap() + 1 + r % 7);
        }
        let n = *offsets.last().unwrap() as usize;
        let indices = vec![0u32; n];
        let weights = vec![1.0f32; n];
        let table = StencilTable::new(&offsets, &indices, &weights).unwrap();
        let lim = limits(2048, 2);
        let chunks = plan_chunks(&table, &lim, 16).unwrap();
        assert!(chunks.len() > 1);
        assert_eq!(chunks[0].row_start, 0);
        assert_eq!(chunks.last().unwrap().row_end, 1000);
        for w in chunks.windows(2) {
            assert_eq!(w[0].row_end, w[1].row_start);
        }
        for c in &chunks {
            assert_eq!(c.row_start % 16, 0);
            let rows = (c.row_end - c.row_start) as u64;
            let entries = u64::from(offsets[c.row_end] - offsets[c.row_start]);
            assert!(entries * 4 <= 2048 && (rows + 1) * 4 <= 2048 && rows * 3 * 4 <= 2048);
            assert!(rows <= 2 * 2 * u64::from(WORKGROUP_SIZE));
        }
    }

    #[test]
    fn oversized_rows_are_reported() {
        let offsets = [0u32, 600];
        let indices = vec![0u32; 600];
        let weights = vec![1.0f32; 600];
        let table = StencilTable::new(&offsets, &indices, &weights).unwrap();
        assert!(matches!(
            plan_chunks(&table, &limits(2048, 8), 1),
            Err(GpuError::TooLarge { .. })
        ));
    }
}
