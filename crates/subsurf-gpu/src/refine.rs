//! Uniform refinement on the GPU: the per-level stencils of a [`Refiner`] uploaded once,
//! applied level after level with the data staying on the GPU.
//!
//! Each level is three dispatches of `refine_level` (face, vertex, edge table; see
//! [`crate::cpu::refine_level`] for the layout). Every table is split into chunks of rows
//! ([`plan_chunks`]) so that no binding exceeds `max_storage_buffer_binding_size` and no
//! dispatch exceeds `max_compute_workgroups_per_dimension`; a chunk's first child row is a
//! field of its uniform, so chunks need no aligned binding offsets. The vertex buffers of a
//! level are bound whole when they fit one binding; a level whose parent or child buffer
//! does not is refined chunk by chunk from its inputs gathered through windows of the level
//! buffers ([`crate::gather`]), with the same bits.
//!
//! Bind groups and uniforms are built once in [`GpuRefiner::new`]; [`GpuRefiner::update`]
//! writes new base positions and records the dispatches, nothing else.

use crate::buffers::{storage_buffer_init, VertexBuffer};
use crate::context::GpuContext;
use crate::cpu::refine_level::{level_dispatches, WORKGROUP_SIZE};
use crate::error::{GpuError, Result};
use crate::gather::plan_gather;
use crate::kernels::stencil::{plan_chunks, ChunkLimits};
use crate::kernels::{grid_2d, part, whole};
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
    /// Gathered inputs of the chunks of levels too large for one binding.
    _scratch: VertexBuffer,
}

/// Where a dispatch reads its inputs: a level buffer (whole, or the window from a vertex),
/// or the scratch buffer.
#[derive(Debug, Clone, Copy)]
enum Source {
    Level(usize, Option<usize>),
    Scratch,
}

/// Where a dispatch writes: a level buffer (whole, or the window from a vertex), or the
/// scratch buffer of the given rows.
#[derive(Debug, Clone, Copy)]
enum Target {
    Level(usize, Option<usize>),
    Scratch(usize),
}

/// A dispatch planned on the host: its chunk of table rows and its bindings.
struct Spec {
    first_row: u32,
    num_parent: u32,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f32>,
    parent: Source,
    child: Target,
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
        Self::from_stencils(ctx, &counts, refiner.stencils(), limits)
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
        let pipeline = create_pipeline(ctx)?;
        let layout = pipeline.get_bind_group_layout(0);
        let b = limits.max_binding_bytes;
        let mut levels = Vec::with_capacity(vertex_counts.len());
        for &count in vertex_counts {
            levels.push(VertexBuffer::zeroed(ctx, count, STRIDE)?);
        }
        // Levels whose parent or child buffer exceeds one binding read their inputs through
        // a scratch buffer (crate::gather). Their tables are planned at a quarter of the limit:
        // a chunk's inputs (at most one per entry) then fill at most 3/4 of the scratch
        // binding, and its rows 3/4 of the child window, whose lead-in (up to 63 vertices,
        // 756 bytes) fits the rest for limits of 3 KiB and more. Source windows are whole
        // aligned groups of 64 vertices.
        let gather_limits = ChunkLimits {
            max_binding_bytes: b / 4,
            ..limits
        };
        let window = (b / (STRIDE as u64 * WORD) / 64 * 64) as usize;
        let mut specs = Vec::new();
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
            let too_big = |n: usize| (n * STRIDE) as u64 * WORD > b;
            let gathered = too_big(s.num_parent_vertices()) || too_big(s.num_rows());
            if gathered && b < 3072 {
                return Err(GpuError::TooLarge {
                    what: "the windows of a refined level larger than one binding",
                    needed: 3072,
                    limit: b,
                });
            }
            for (table, first_row) in level_dispatches(s) {
                bytes += table.size_bytes() as u64;
                let t = StencilTable::new(table.offsets(), table.indices(), table.weights())?;
                if t.min_source_vertices() > s.num_rows() {
                    return Err(GpuError::InvalidStencil(format!(
                        "level {} table references input {} beyond the child vertices",
                        level + 1,
                        t.min_source_vertices() - 1
                    )));
                }
                let plan_limits = if gathered { &gather_limits } else { &limits };
                for range in plan_chunks(&t, plan_limits, 1)? {
                    let (r0, r1) = (range.row_start, range.row_end);
                    let (e0, e1) = (table.offsets()[r0] as usize, table.offsets()[r1] as usize);
                    let offsets: Vec<u32> = table.offsets()[r0..=r1]
                        .iter()
                        .map(|&o| o - table.offsets()[r0])
                        .collect();
                    let indices = &table.indices()[e0..e1];
                    let weights = table.weights()[e0..e1].to_vec();
                    let first = first_row + r0;
                    if !gathered {
                        specs.push(Spec {
                            first_row: first as u32,
                            num_parent: s.num_parent_vertices() as u32,
                            offsets,
                            indices: indices.to_vec(),
                            weights,
                            parent: Source::Level(level, None),
                            child: Target::Level(level + 1, None),
                        });
                        continue;
                    }
                    let plan = plan_gather(indices, s.num_parent_vertices(), window, 1);
                    for g in plan.gathers {
                        let n = g.rel.len();
                        let lvl = level + usize::from(g.child);
                        specs.push(Spec {
                            first_row: g.first,
                            num_parent: u32::MAX,
                            offsets: (0..=n as u32).collect(),
                            indices: g.rel,
                            weights: vec![1.0; n],
                            parent: Source::Level(lvl, Some(g.window * window)),
                            child: Target::Scratch(plan.inputs),
                        });
                    }
                    let start = first / 64 * 64;
                    specs.push(Spec {
                        first_row: (first - start) as u32,
                        num_parent: u32::MAX,
                        offsets,
                        indices: plan.local,
                        weights,
                        parent: Source::Scratch,
                        child: Target::Level(level + 1, Some(start)),
                    });
                }
            }
        }
        let scratch_rows = specs
            .iter()
            .map(|d| match d.child {
                Target::Scratch(n) => n,
                Target::Level(..) => 0,
            })
            .max()
            .unwrap_or(0);
        let scratch = VertexBuffer::zeroed(ctx, scratch_rows, STRIDE)?;
        let mut dispatches = Vec::with_capacity(specs.len());
        for d in specs {
            let rows = (d.offsets.len() - 1) as u32;
            let (gx, gy) = grid_2d(rows, WORKGROUP_SIZE, limits.max_workgroups_per_dimension);
            let config = RefineConfig {
                row_count: rows,
                stride: STRIDE as u32,
                grid_width: gx * WORKGROUP_SIZE,
                first_row: d.first_row,
                num_parent: d.num_parent,
                _pad: [0; 3],
            };
            let buffers = [
                uniform_init(ctx, bytemuck::bytes_of(&config))?,
                storage_buffer_init(ctx, "refine offsets", bytemuck::cast_slice(&d.offsets))?,
                storage_buffer_init(ctx, "refine indices", bytemuck::cast_slice(&d.indices))?,
                storage_buffer_init(ctx, "refine weights", bytemuck::cast_slice(&d.weights))?,
            ];
            let vertex_bytes = |n: usize| (n * STRIDE) as u64 * WORD;
            let parent = match d.parent {
                Source::Scratch => whole(4, scratch.raw()),
                Source::Level(l, None) => whole(4, levels[l].raw()),
                Source::Level(l, Some(first)) => {
                    let n = window.min(levels[l].vertex_count() - first);
                    part(4, levels[l].raw(), vertex_bytes(first), vertex_bytes(n))
                }
            };
            let child = match d.child {
                Target::Scratch(_) => whole(5, scratch.raw()),
                Target::Level(l, None) => whole(5, levels[l].raw()),
                Target::Level(l, Some(start)) => {
                    let end = start + (d.first_row + rows) as usize;
                    part(
                        5,
                        levels[l].raw(),
                        vertex_bytes(start),
                        vertex_bytes(end - start),
                    )
                }
            };
            let bind_group = ctx.scoped(|| {
                Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("refine_level"),
                    layout: &layout,
                    entries: &[
                        whole(0, &buffers[0]),
                        whole(1, &buffers[1]),
                        whole(2, &buffers[2]),
                        whole(3, &buffers[3]),
                        parent,
                        child,
                    ],
                }))
            })?;
            dispatches.push(Dispatch {
                bind_group,
                groups: (gx, gy),
                _buffers: buffers,
            });
        }
        Ok(Self {
            levels,
            dispatches,
            pipeline,
            bytes,
            _scratch: scratch,
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
        buf.download_triples(ctx)
    }

    /// Reads the last level back into `out` (one position per last-level vertex), allocating
    /// nothing once the context's staging buffer is large enough: the read-back of a frame
    /// loop.
    pub fn download_into(&self, ctx: &GpuContext, out: &mut [[f32; 3]]) -> Result<()> {
        self.output().download_into(ctx, out.as_flattened_mut())
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

/// A compute pipeline with the layout derived from the shader (entry point `entry`), compiled
/// once per device ([`GpuContext::kernel`]).
pub(crate) fn auto_pipeline(
    ctx: &GpuContext,
    label: &'static str,
    source: &'static str,
    entry: &'static str,
) -> Result<wgpu::ComputePipeline> {
    ctx.kernel(source, entry, || {
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
    })
}

fn create_pipeline(ctx: &GpuContext) -> Result<wgpu::ComputePipeline> {
    auto_pipeline(ctx, "refine_level", shaders::REFINE_LEVEL, "main")
}
