//! Uniform refinement on the GPU: the per-level stencils of a [`Refiner`] uploaded once,
//! applied level after level with the data staying on the GPU.
//!
//! Each level is three dispatches of `refine_level` (face, vertex, edge table; see
//! [`crate::cpu::refine_level`] for the layout). Every table is split into chunks of rows
//! ([`plan_chunks`]) so that no binding exceeds `max_storage_buffer_binding_size` and no
//! dispatch exceeds `max_compute_workgroups_per_dimension`; a chunk's first child row is a
//! field of its uniform, so chunks need no aligned binding offsets. The vertex buffers of the
//! levels are bound whole and must each fit one binding.
//!
//! Bind groups and uniforms are built once in [`GpuRefiner::new`]; [`GpuRefiner::update`]
//! writes new base positions and records the dispatches, nothing else.

use crate::buffers::{storage_buffer_init, VertexBuffer};
use crate::context::GpuContext;
use crate::cpu::refine_level::{level_dispatches, WORKGROUP_SIZE};
use crate::error::{GpuError, Result};
use crate::kernels::grid_2d;
use crate::kernels::stencil::{plan_chunks, ChunkLimits};
use crate::shaders;
use crate::shared::RefineConfig;
use crate::table::StencilTable;
use subsurf::refine::LevelStencils;
use subsurf::Refiner;

const WORD: u64 = 4;
/// Floats per vertex of the refined data (positions).
const STRIDE: usize = 3;

#[derive(Debug)]
struct Dispatch {
    bind_group: wgpu::BindGroup,
    groups: (u32, u32),
    // Kept alive for the bind group.
    _buffers: [wgpu::Buffer; 4],
}

/// A [`Refiner`]'s per-level stencils resident on the GPU, with one vertex buffer per level.
#[derive(Debug)]
pub struct GpuRefiner {
    /// `levels[0]` holds the base positions, `levels[k]` level `k`.
    levels: Vec<VertexBuffer>,
    dispatches: Vec<Dispatch>,
    pipeline: wgpu::ComputePipeline,
    bytes: u64,
}

impl GpuRefiner {
    /// Uploads every level's tables, chunked against the adapter's limits.
    pub fn new(ctx: &GpuContext, refiner: &Refiner) -> Result<Self> {
        Self::with_limits(ctx, refiner, ChunkLimits::from_context(ctx))
    }

    /// Uploads with the given chunk limits (clamped to the adapter's; lower values force more
    /// chunks, which tests use to exercise chunking).
    pub fn with_limits(ctx: &GpuContext, refiner: &Refiner, limits: ChunkLimits) -> Result<Self> {
        let counts: Vec<usize> = refiner.levels.iter().map(|t| t.num_vertices()).collect();
        Self::from_stencils(ctx, &counts, &refiner.stencils, limits)
    }

    /// Uploads `stencils[k]` (level `k` to `k + 1`) for levels of `vertex_counts[k]` vertices
    /// (`stencils.len() + 1` counts), chunked against `limits` (clamped to the adapter's):
    /// the tables of a [`Refiner`] or of a patch table's `level_stencils`.
    pub fn from_stencils(
        ctx: &GpuContext,
        vertex_counts: &[usize],
        stencils: &[LevelStencils],
        limits: ChunkLimits,
    ) -> Result<Self> {
        if vertex_counts.len() != stencils.len() + 1 {
            return Err(GpuError::InvalidStencil(format!(
                "{} level vertex counts for {} stencil levels",
                vertex_counts.len(),
                stencils.len()
            )));
        }
        let adapter = ChunkLimits::from_context(ctx);
        let limits = ChunkLimits {
            max_binding_bytes: limits.max_binding_bytes.min(adapter.max_binding_bytes),
            max_workgroups_per_dimension: limits
                .max_workgroups_per_dimension
                .clamp(1, adapter.max_workgroups_per_dimension),
            max_stride: 1,
        };
        let pipeline = ctx.scoped(|| Ok(create_pipeline(ctx)))?;
        let layout = pipeline.get_bind_group_layout(0);
        let mut levels = Vec::with_capacity(vertex_counts.len());
        for &count in vertex_counts {
            let bytes = (count * STRIDE) as u64 * WORD;
            if bytes > adapter.max_binding_bytes {
                return Err(GpuError::TooLarge {
                    what: "refined level vertex buffer (bound whole)",
                    needed: bytes,
                    limit: adapter.max_binding_bytes,
                });
            }
            levels.push(VertexBuffer::zeroed(ctx, count, STRIDE)?);
        }
        let mut dispatches = Vec::new();
        let mut bytes = 0u64;
        for (level, s) in stencils.iter().enumerate() {
            if levels[level + 1].vertex_count() != s.num_rows() {
                return Err(GpuError::InvalidStencil(format!(
                    "level {} has {} vertices but its stencils {} rows",
                    level + 1,
                    levels[level + 1].vertex_count(),
                    s.num_rows()
                )));
            }
            for (table, first_row) in level_dispatches(s) {
                bytes += table.size_bytes() as u64;
                let t = StencilTable::new(&table.offsets, &table.indices, &table.weights)?;
                if t.min_source_vertices() > s.num_rows() {
                    return Err(GpuError::InvalidStencil(format!(
                        "level {} table references input {} beyond the child vertices",
                        level + 1,
                        t.min_source_vertices() - 1
                    )));
                }
                for range in plan_chunks(&t, &limits, 1)? {
                    let (r0, r1) = (range.row_start, range.row_end);
                    let (e0, e1) = (table.offsets[r0] as usize, table.offsets[r1] as usize);
                    let local: Vec<u32> = table.offsets[r0..=r1]
                        .iter()
                        .map(|&o| o - table.offsets[r0])
                        .collect();
                    let rows = (r1 - r0) as u32;
                    let (gx, gy) =
                        grid_2d(rows, WORKGROUP_SIZE, limits.max_workgroups_per_dimension);
                    let config = RefineConfig {
                        row_count: rows,
                        stride: STRIDE as u32,
                        grid_width: gx * WORKGROUP_SIZE,
                        first_row: (first_row + r0) as u32,
                        num_parent: s.num_parent_vertices as u32,
                        _pad: [0; 3],
                    };
                    let buffers = [
                        uniform_init(ctx, bytemuck::bytes_of(&config))?,
                        storage_buffer_init(ctx, "refine offsets", bytemuck::cast_slice(&local))?,
                        storage_buffer_init(
                            ctx,
                            "refine indices",
                            bytemuck::cast_slice(&table.indices[e0..e1]),
                        )?,
                        storage_buffer_init(
                            ctx,
                            "refine weights",
                            bytemuck::cast_slice(&table.weights[e0..e1]),
                        )?,
                    ];
                    let bind_group = ctx.scoped(|| {
                        Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                            label: Some("refine_level"),
                            layout: &layout,
                            entries: &[
                                whole(0, &buffers[0]),
                                whole(1, &buffers[1]),
                                whole(2, &buffers[2]),
                                whole(3, &buffers[3]),
                                whole(4, levels[level].raw()),
                                whole(5, levels[level + 1].raw()),
                            ],
                        }))
                    })?;
                    dispatches.push(Dispatch {
                        bind_group,
                        groups: (gx, gy),
                        _buffers: buffers,
                    });
                }
            }
        }
        Ok(Self {
            levels,
            dispatches,
            pipeline,
            bytes,
        })
    }

    /// Number of refinement steps.
    pub fn max_level(&self) -> usize {
        self.levels.len() - 1
    }

    /// Number of dispatches per update (three per level, more when tables are chunked).
    pub fn num_dispatches(&self) -> usize {
        self.dispatches.len()
    }

    /// Bytes of stencil tables uploaded.
    pub fn table_bytes(&self) -> u64 {
        self.bytes
    }

    /// Vertices of the last level.
    pub fn num_output_vertices(&self) -> usize {
        self.levels[self.levels.len() - 1].vertex_count()
    }

    /// Writes new base positions and submits every level's dispatches (nothing is rebuilt).
    /// The result stays on the GPU: see [`Self::output`], [`Self::download`].
    pub fn update(&self, ctx: &GpuContext, base: &[[f32; 3]]) -> Result<()> {
        if base.len() != self.levels[0].vertex_count() {
            return Err(GpuError::BufferMismatch(format!(
                "{} base positions for a refiner of {} base vertices",
                base.len(),
                self.levels[0].vertex_count()
            )));
        }
        self.levels[0].write(ctx, base.as_flattened())?;
        self.dispatch(ctx)
    }

    /// Submits every level's dispatches from the current contents of the base buffer
    /// ([`Self::input_mut`]), which a caller may have filled on the GPU.
    pub fn dispatch(&self, ctx: &GpuContext) -> Result<()> {
        ctx.scoped(|| {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("refine_level"),
                });
            self.encode(&mut encoder);
            ctx.queue.submit([encoder.finish()]);
            Ok(())
        })
    }

    /// Records [`Self::dispatch`]'s passes into `encoder` (submitted by the caller).
    pub(crate) fn encode(&self, encoder: &mut wgpu::CommandEncoder) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("refine_level"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        for d in &self.dispatches {
            pass.set_bind_group(0, &d.bind_group, &[]);
            pass.dispatch_workgroups(d.groups.0, d.groups.1, 1);
        }
    }

    /// [`Self::update`] then [`Self::download`].
    pub fn refine(&self, ctx: &GpuContext, base: &[[f32; 3]]) -> Result<Vec<[f32; 3]>> {
        self.update(ctx, base)?;
        self.download(ctx)
    }

    /// The last level's positions, on the GPU (3 floats per vertex).
    pub fn output(&self) -> &VertexBuffer {
        &self.levels[self.levels.len() - 1]
    }

    /// Reads the last level back (waits for the submitted work).
    pub fn download(&self, ctx: &GpuContext) -> Result<Vec<[f32; 3]>> {
        self.download_level(ctx, self.max_level())
    }

    /// The base buffer, to be filled on the GPU (for example by a [`crate::StencilKernel`])
    /// before [`Self::dispatch`].
    pub fn input_mut(&mut self) -> &mut VertexBuffer {
        &mut self.levels[0]
    }

    /// Level `level`'s vertex buffer (0 = base), on the GPU.
    pub fn level(&self, level: usize) -> Option<&VertexBuffer> {
        self.levels.get(level)
    }

    /// Reads level `level` back (0 = base).
    pub fn download_level(&self, ctx: &GpuContext, level: usize) -> Result<Vec<[f32; 3]>> {
        let buf = self.levels.get(level).ok_or_else(|| {
            GpuError::BufferMismatch(format!(
                "level {level} requested of a refiner with {} levels",
                self.max_level()
            ))
        })?;
        let flat = buf.download(ctx)?;
        Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }
}

fn whole(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// A uniform buffer holding `bytes`.
pub(crate) fn uniform_init(ctx: &GpuContext, bytes: &[u8]) -> Result<wgpu::Buffer> {
    use wgpu::util::DeviceExt;
    ctx.scoped(|| {
        Ok(ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("subsurf config"),
                contents: bytes,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            }))
    })
}

/// A compute pipeline with the layout derived from the shader (entry point `entry`).
pub(crate) fn auto_pipeline(
    ctx: &GpuContext,
    label: &'static str,
    source: &'static str,
    entry: &'static str,
) -> wgpu::ComputePipeline {
    let module = ctx
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    ctx.device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: None,
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        })
}

fn create_pipeline(ctx: &GpuContext) -> wgpu::ComputePipeline {
    auto_pipeline(ctx, "refine_level", shaders::REFINE_LEVEL, "main")
}
