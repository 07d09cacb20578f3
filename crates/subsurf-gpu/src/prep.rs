//! The p-rep (Myles, Yeo & Peters 2008) on the GPU: vertex pass, patch pass and watertight
//! `n×n` evaluation as three kernels over the flat ring tables of
//! [`subsurf::prep::PrepTopology`], each with its CPU twin in [`crate::cpu`].
//!
//! [`GpuPrep::new`] uploads the connectivity once; per frame [`GpuPrep::update`] writes the
//! positions (or [`GpuPrep::update_from`] takes them from a GPU buffer; a split mesh gathers
//! each sub-problem's vertices from them on the GPU) and runs both passes,
//! and [`GpuPrep::eval_grid`] fills a [`GpuGrid`] (vertex buffer of position + normal, index
//! buffer of triangles) allocated once per `n`. All data stays on the GPU until read back.
//!
//! Nothing is bound past the adapter's `max_storage_buffer_binding_size`. The mesh is split
//! into sub-problems ([`crate::prep_chunks`]: ranges of faces with their corners' rings,
//! renumbered locally) whose tables each fit one binding; a mesh that fits is one
//! sub-problem, numbered as the mesh. Each sub-problem's passes are further split into
//! dispatches of at most `max_compute_workgroups_per_dimension`² invocations (a chunk's first
//! item is the `first_item` field of its uniform), and the tessellation's vertex and index
//! buffers, the largest by far, are bound per dispatch from the aligned offset at or before
//! its first item. Only the adapter's `max_buffer_size` bounds those two buffers.

use crate::buffers::{read_back, storage_buffer_init, VertexBuffer};
use crate::context::GpuContext;
use crate::cpu::prep_eval_grid::{
    grid_params, prep_eval_grid_invocation, prep_grid_indices_invocation, EvalInputs,
};
use crate::cpu::prep_patch_pass::{prep_patch_pass, PatchInputs};
use crate::cpu::prep_vertex_pass::prep_vertex_pass;
use crate::error::{GpuError, Result};
use crate::kernels::chunked_pass::{
    empty_storage, encode_passes, pass, submit, upload_u32, Bind, Pass, PassLimits,
};
use crate::kernels::stencil::{ChunkLimits, StencilKernel};
use crate::prep_chunks::PrepChunks;
use crate::shaders;
use crate::shared::PrepConfig;
use crate::table::StencilTable;
use std::sync::Arc;
use subsurf::prep::{PrepTopology, Tessellation};

const WORD: u64 = 4;

/// The flat tables the p-rep kernels read for one sub-problem ([`crate::prep_chunks`]): the
/// whole mesh, numbered as the [`PrepTopology`], when it fits one binding.
#[derive(Debug, Clone)]
pub struct PrepTables {
    /// Counts of the sub-problem (`item_count`, `grid_width`, `samples` left 0).
    pub config: PrepConfig,
    /// Ring offsets of the core vertices (core + 1).
    pub ring_offsets: Vec<u32>,
    /// Rings of the core vertices in local numbering (2 S).
    pub ring_indices: Vec<u32>,
    /// Flat per-valence constants.
    pub valence_consts: Vec<f32>,
    /// Local vertex of each face corner (4 F).
    pub face_verts: Vec<u32>,
    /// Sector of each face corner (4 F).
    pub corner_sector: Vec<u32>,
    /// Local face corner running along each owned edge in its canonical direction (E).
    pub edge_corner: Vec<u32>,
    /// Local h block of each face (F), `u32::MAX` for a B-quad.
    pub h_index: Vec<u32>,
    /// Number of perturbed faces `P`.
    pub num_perturbed: usize,
    /// Global vertex of each local vertex: owned core, other core, then halo vertices.
    pub vertex_ids: Vec<u32>,
    /// Global edge of each owned edge (ascending).
    pub edge_ids: Vec<u32>,
    /// Global index of the first face.
    pub first_face: u32,
    /// Global h block of the first perturbed face.
    pub first_h: u32,
}

impl PrepTables {
    /// The whole of `t` as one sub-problem, checking that every count fits the kernels'
    /// 32-bit indexing.
    pub fn new(t: &PrepTopology) -> Result<Self> {
        Ok(PrepChunks::new(t, u64::MAX)?.chunks.swap_remove(0))
    }

    /// Floats of the vertex pass output.
    pub fn vertex_data_len(&self) -> usize {
        let c = &self.config;
        3 * (3 * c.num_vertices as usize + 2 * c.num_sectors as usize)
    }

    /// Floats of the patch pass output.
    pub fn patch_data_len(&self) -> usize {
        3 * 16 * (self.config.num_faces as usize + self.num_perturbed)
    }

    fn config_for(&self, items: usize, samples: usize) -> PrepConfig {
        PrepConfig {
            item_count: items as u32,
            grid_width: items as u32,
            samples: samples as u32,
            ..self.config
        }
    }

    /// CPU twin of the sub-problem's share of [`GpuPrep::update`]: `(vertex_data,
    /// patch_data)` for the positions of its local vertices.
    pub fn run_passes_cpu(&self, positions: &[[f32; 3]]) -> (Vec<f32>, Vec<f32>) {
        let mut vd = vec![0.0; self.vertex_data_len()];
        let nv = self.config.num_vertices as usize;
        prep_vertex_pass(
            &self.config_for(nv, 0),
            positions.as_flattened(),
            &self.ring_offsets,
            &self.ring_indices,
            &self.valence_consts,
            &mut vd,
        );
        let mut pd = vec![0.0; self.patch_data_len()];
        let inp = PatchInputs {
            face_verts: &self.face_verts,
            corner_sector: &self.corner_sector,
            ring_offsets: &self.ring_offsets,
            h_index: &self.h_index,
            valence_consts: &self.valence_consts,
            vertex_data: &vd,
        };
        prep_patch_pass(
            &self.config_for(self.config.num_faces as usize, 0),
            &inp,
            &mut pd,
        );
        (vd, pd)
    }

    /// CPU twin of the sub-problem's entry `main` of `prep_eval_grid`: its region of the
    /// `n×n` vertex buffer (6 floats per vertex) from its pass outputs.
    pub fn eval_region_cpu(
        &self,
        n: usize,
        vertex_data: &[f32],
        patch_data: &[f32],
        out: &mut [f32],
    ) {
        let params = grid_params(n);
        let inp = EvalInputs {
            params: &params,
            edge_corner: &self.edge_corner,
            h_index: &self.h_index,
            vertex_data,
            patch_data,
        };
        let items = out.len() / 6;
        let cfg = self.config_for(items, n);
        for item in 0..items as u32 {
            prep_eval_grid_invocation(item, &cfg, &inp, out);
        }
    }

    /// CPU twin of the sub-problem's entry `indices`: 6 indices per grid cell of its faces,
    /// given its `corner_slots` and the slot of its first face-interior sample.
    pub fn indices_cpu(&self, n: usize, corner_slots: &[u32], face_slot_base: u32) -> Vec<u32> {
        let cells = self.config.num_faces as usize * (n - 1) * (n - 1);
        let cfg = PrepConfig {
            face_slot_base,
            ..self.config_for(cells, n)
        };
        let mut idx = vec![0u32; 6 * cells];
        for item in 0..cells as u32 {
            prep_grid_indices_invocation(item, &cfg, corner_slots, &mut idx);
        }
        idx
    }
}

pub(crate) fn unpack(vertices: &[f32], indices: &[u32]) -> Tessellation<f32> {
    Tessellation {
        positions: vertices
            .chunks_exact(6)
            .map(|v| [v[0], v[1], v[2]])
            .collect(),
        normals: vertices
            .chunks_exact(6)
            .map(|v| [v[3], v[4], v[5]])
            .collect(),
        triangles: indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
    }
}

/// Fills every sub-problem's positions from `positions` (all vertices: copied for one
/// sub-problem, gathered for several) and runs `passes`, in one submission.
fn record_update(
    ctx: &GpuContext,
    buffers: &mut [ChunkBuffers],
    passes: &[Pass],
    positions: &VertexBuffer,
) -> Result<()> {
    ctx.scoped(|| {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("prep passes"),
            });
        for b in buffers {
            match &b.gather {
                Some(gather) => gather.encode(ctx, &mut encoder, positions, &mut b.positions)?,
                None if positions.len_floats() > 0 => encoder.copy_buffer_to_buffer(
                    positions.raw(),
                    0,
                    b.positions.raw(),
                    0,
                    positions.len_floats() as u64 * WORD,
                ),
                None => {}
            }
        }
        encode_passes(&mut encoder, "prep passes", passes);
        ctx.queue.submit([encoder.finish()]);
        Ok(())
    })
}

/// One sub-problem's resident buffers.
#[derive(Debug)]
struct ChunkBuffers {
    positions: VertexBuffer,
    /// Gathers the local positions from the positions of every vertex on the GPU (unit
    /// weights; only when there is more than one sub-problem).
    gather: Option<StencilKernel>,
    vertex_data: wgpu::Buffer,
    patch_data: wgpu::Buffer,
    edge_corner: wgpu::Buffer,
    h_index: wgpu::Buffer,
}

/// A p-rep resident on the GPU: connectivity tables, positions and both passes' outputs, per
/// sub-problem.
///
/// # Example
///
/// The p-rep of a cube, deformed and re-evaluated on the GPU, against the CPU's watertight
/// tessellation (same triangles, positions within f32 rounding); without an adapter only the
/// CPU surface is built:
///
/// ```
/// use subsurf::prep::PrepPatches;
/// use subsurf::shapes;
/// use subsurf_gpu::{GpuContext, GpuError, GpuPrep};
///
/// let mut cube = shapes::cube();
/// let mut cpu = PrepPatches::<f32>::build(&cube)?;
/// let ctx = match GpuContext::new() {
///     Ok(ctx) => ctx,
///     Err(GpuError::NoAdapter { .. }) => return Ok(()), // CPU only: `cpu.tessellate(n)`
///     Err(e) => return Err(e.into()),
/// };
/// let mut gpu = GpuPrep::new(&ctx, cpu.topology())?;
/// let grid = gpu.grid(&ctx, 5)?; // 5 samples per patch side, shared along edges
/// for frame in 0..2 {
///     cube.positions.as_f32_mut()[0][2] += 0.25 * frame as f32; // animate one vertex
///     cpu.update(&cube.positions)?;
///     gpu.update(&ctx, &cube.positions)?;
///     gpu.eval_grid(&ctx, &grid)?;
///     let (got, want) = (grid.download(&ctx)?, cpu.tessellate(5));
///     assert_eq!(got.triangles, want.triangles);
///     for (a, b) in got.positions.iter().zip(&want.positions) {
///         assert!((0..3).all(|c| (a[c] - b[c]).abs() < 1e-5));
///     }
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct GpuPrep {
    plan: Arc<PrepChunks>,
    /// The positions of every vertex, written by [`Self::update`] when there is more than
    /// one sub-problem (each sub-problem gathers its local vertices from it on the GPU).
    input: Option<VertexBuffer>,
    buffers: Vec<ChunkBuffers>,
    /// Vertex then patch pass of every sub-problem.
    passes: Vec<Pass>,
    lim: PassLimits,
    _consts: wgpu::Buffer,
}

/// An `n×n` watertight tessellation on the GPU: `vertices` (6 floats: position, unit normal)
/// and `indices` (3 per ccw triangle), filled by [`GpuPrep::eval_grid`].
///
/// The vertex buffer holds each sub-problem's region in turn ([`crate::prep_chunks`]); with
/// one sub-problem (any mesh whose tables fit one binding) that is the layout of
/// `PrepPatches::tessellate`, and [`Self::download`] returns that layout in every case. The
/// triangles are those of `PrepPatches::tessellate`, in its order.
#[derive(Debug)]
pub struct GpuGrid {
    /// Samples per patch side.
    pub n: usize,
    /// Vertex buffer, 6 floats per vertex.
    pub vertices: wgpu::Buffer,
    /// Index buffer, u32.
    pub indices: wgpu::Buffer,
    /// Number of vertices.
    pub num_vertices: usize,
    /// Number of indices (3 per triangle).
    pub num_indices: usize,
    plan: Arc<PrepChunks>,
    _tables: Vec<wgpu::Buffer>,
    /// Entry `main` of every sub-problem, then entry `indices` of every sub-problem.
    passes: Vec<Pass>,
}

impl GpuGrid {
    /// Dispatches of one [`GpuPrep::eval_grid`] (more than one when chunked).
    pub fn num_dispatches(&self) -> usize {
        self.passes[..self.plan.chunks.len()]
            .iter()
            .map(|p| p.dispatches.len())
            .sum()
    }

    /// Reads the tessellation back (waits for the submitted work), in the layout of
    /// `PrepPatches::tessellate`.
    pub fn download(&self, ctx: &GpuContext) -> Result<Tessellation<f32>> {
        let v = read_back(ctx, &self.vertices, (6 * self.num_vertices) as u64 * WORD)?;
        let i: Vec<u32> = read_back(ctx, &self.indices, self.num_indices as u64 * WORD)?
            .into_iter()
            .map(f32::to_bits)
            .collect();
        Ok(self.plan.to_canonical(self.n, unpack(&v, &i)))
    }
}

impl GpuPrep {
    /// Uploads the connectivity of `topo` and creates both passes (positions still zero:
    /// call [`Self::update`]).
    pub fn new(ctx: &GpuContext, topo: &PrepTopology) -> Result<Self> {
        Self::with_limits(ctx, topo, ChunkLimits::from_context(ctx))
    }

    /// [`Self::new`] with the work split against `limits` (clamped to the adapter's): lower
    /// values force more sub-problems and dispatches, which tests use to exercise the split.
    pub fn with_limits(ctx: &GpuContext, topo: &PrepTopology, limits: ChunkLimits) -> Result<Self> {
        let adapter = ChunkLimits::from_context(ctx);
        let lim = PassLimits {
            limits: ChunkLimits {
                max_binding_bytes: limits.max_binding_bytes.min(adapter.max_binding_bytes),
                max_workgroups_per_dimension: limits
                    .max_workgroups_per_dimension
                    .clamp(1, adapter.max_workgroups_per_dimension),
                max_stride: 6,
            },
            row_align: (ctx.limits().min_storage_buffer_offset_alignment as usize / WORD as usize)
                .max(1),
        };
        let plan = Arc::new(PrepChunks::new(topo, lim.limits.max_binding_bytes)?);
        let consts = storage_buffer_init(
            ctx,
            "prep valence constants",
            bytemuck::cast_slice(&plan.chunks[0].valence_consts),
        )?;
        let mut buffers = Vec::with_capacity(plan.chunks.len());
        let mut passes = Vec::with_capacity(2 * plan.chunks.len());
        for t in &plan.chunks {
            let nv = t.config.num_vertices as usize;
            let b = ChunkBuffers {
                positions: VertexBuffer::zeroed(ctx, t.vertex_ids.len(), 3)?,
                gather: if plan.chunks.len() > 1 {
                    let n = t.vertex_ids.len() as u32;
                    let offsets: Vec<u32> = (0..=n).collect();
                    let weights = vec![1.0; n as usize];
                    let table = StencilTable::new(&offsets, &t.vertex_ids, &weights)?;
                    Some(StencilKernel::with_limits(
                        ctx,
                        &table,
                        ChunkLimits {
                            max_stride: 3,
                            ..lim.limits
                        },
                    )?)
                } else {
                    None
                },
                vertex_data: empty_storage(
                    ctx,
                    "prep vertex data",
                    t.vertex_data_len() as u64 * WORD,
                    true,
                )?,
                patch_data: empty_storage(
                    ctx,
                    "prep patch data",
                    t.patch_data_len() as u64 * WORD,
                    true,
                )?,
                edge_corner: upload_u32(ctx, "prep edge corners", &t.edge_corner)?,
                h_index: upload_u32(ctx, "prep h index", &t.h_index)?,
            };
            let ring_offsets = upload_u32(ctx, "prep ring offsets", &t.ring_offsets)?;
            let ring_indices = upload_u32(ctx, "prep ring indices", &t.ring_indices)?;
            let face_verts = upload_u32(ctx, "prep face vertices", &t.face_verts)?;
            let corner_sector = upload_u32(ctx, "prep corner sectors", &t.corner_sector)?;
            passes.push(pass(
                ctx,
                &lim,
                "prep_vertex_pass",
                shaders::PREP_VERTEX_PASS,
                "main",
                t.config_for(nv, 0),
                &[
                    Bind::Whole(1, b.positions.raw()),
                    Bind::Whole(2, &ring_offsets),
                    Bind::Whole(3, &ring_indices),
                    Bind::Whole(4, &consts),
                    Bind::Whole(5, &b.vertex_data),
                ],
            )?);
            passes.push(pass(
                ctx,
                &lim,
                "prep_patch_pass",
                shaders::PREP_PATCH_PASS,
                "main",
                t.config_for(t.config.num_faces as usize, 0),
                &[
                    Bind::Whole(1, &face_verts),
                    Bind::Whole(2, &corner_sector),
                    Bind::Whole(3, &ring_offsets),
                    Bind::Whole(4, &b.h_index),
                    Bind::Whole(5, &consts),
                    Bind::Whole(6, &b.vertex_data),
                    Bind::Whole(7, &b.patch_data),
                ],
            )?);
            buffers.push(b);
        }
        let input = if plan.chunks.len() > 1 {
            Some(VertexBuffer::zeroed(ctx, plan.num_vertices, 3)?)
        } else {
            None
        };
        Ok(Self {
            plan,
            input,
            buffers,
            passes,
            lim,
            _consts: consts,
        })
    }

    /// Dispatches of one [`Self::update`] (vertex and patch pass; more than two when chunked).
    pub fn num_dispatches(&self) -> usize {
        self.passes.iter().map(|p| p.dispatches.len()).sum()
    }

    /// The sub-problems and their tables (for the CPU twins).
    pub fn chunks(&self) -> &PrepChunks {
        &self.plan
    }

    /// Writes `positions` and submits the vertex and patch passes (with more than one
    /// sub-problem, after each sub-problem's gather of its local vertices, as
    /// [`Self::update_from`] does).
    pub fn update(&mut self, ctx: &GpuContext, positions: &[[f32; 3]]) -> Result<()> {
        let nv = self.plan.num_vertices;
        if positions.len() != nv {
            return Err(GpuError::BufferMismatch(format!(
                "{} positions for a p-rep of {nv} vertices",
                positions.len()
            )));
        }
        match &self.input {
            Some(input) => {
                input.write(ctx, positions.as_flattened())?;
                record_update(ctx, &mut self.buffers, &self.passes, input)
            }
            None => {
                self.buffers[0]
                    .positions
                    .write(ctx, positions.as_flattened())?;
                submit(ctx, "prep passes", &self.passes)
            }
        }
    }

    /// [`Self::update`] from positions already on the GPU (3 floats per vertex of the
    /// p-rep; for example [`crate::GpuRefiner::output`] after refining a base mesh on the
    /// GPU): copied, or gathered per sub-problem by unit-weight `stencil_apply`, then both
    /// passes, in one submission. Nothing goes through the host.
    pub fn update_from(&mut self, ctx: &GpuContext, positions: &VertexBuffer) -> Result<()> {
        let nv = self.plan.num_vertices;
        if positions.vertex_count() != nv || positions.stride() != 3 {
            return Err(GpuError::BufferMismatch(format!(
                "{} vertices of stride {} for a p-rep of {nv} vertices of stride 3",
                positions.vertex_count(),
                positions.stride()
            )));
        }
        record_update(ctx, &mut self.buffers, &self.passes, positions)
    }

    /// Reads back `(vertex_data, patch_data)` in the global layouts of [`PrepConfig`].
    pub fn download_coefficients(&self, ctx: &GpuContext) -> Result<(Vec<f32>, Vec<f32>)> {
        let per = self
            .plan
            .chunks
            .iter()
            .zip(&self.buffers)
            .map(|(t, b)| {
                Ok((
                    read_back(ctx, &b.vertex_data, t.vertex_data_len() as u64 * WORD)?,
                    read_back(ctx, &b.patch_data, t.patch_data_len() as u64 * WORD)?,
                ))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(self.plan.to_canonical_coefficients(&per))
    }

    /// Allocates the buffers and bind groups of an `n×n` tessellation (`n >= 2`) and fills
    /// its index buffer (the indices depend on the connectivity only).
    pub fn grid(&self, ctx: &GpuContext, n: usize) -> Result<GpuGrid> {
        let n = n.max(2);
        let plan = &self.plan;
        let nvert = plan.grid_vertices(n);
        let cells = plan.num_faces * (n - 1) * (n - 1);
        if 6 * nvert as u64 >= u32::MAX as u64 || 6 * cells as u64 >= u32::MAX as u64 {
            return Err(GpuError::BufferMismatch(format!(
                "a {n}x{n} tessellation of {} faces exceeds 32-bit indexing",
                plan.num_faces
            )));
        }
        let params =
            storage_buffer_init(ctx, "prep params", bytemuck::cast_slice(&grid_params(n)))?;
        let vertices = empty_storage(ctx, "prep grid vertices", (6 * nvert) as u64 * WORD, false)?;
        let indices = empty_storage(ctx, "prep grid indices", (6 * cells) as u64 * WORD, false)?;
        let starts = plan.region_starts(n);
        let mut tables = Vec::new();
        let mut eval = Vec::new();
        let mut index = Vec::new();
        let mut first_cell = 0u64;
        for (k, ((t, b), slots)) in plan
            .chunks
            .iter()
            .zip(&self.buffers)
            .zip(plan.corner_slots(n))
            .enumerate()
        {
            let (start, region) = (starts[k], plan.region_len(k, n));
            eval.push(pass(
                ctx,
                &self.lim,
                "prep_eval_grid",
                shaders::PREP_EVAL_GRID,
                "main",
                t.config_for(region, n),
                &[
                    Bind::Whole(1, &params),
                    Bind::Whole(2, &b.edge_corner),
                    Bind::Whole(3, &b.h_index),
                    Bind::Whole(4, &b.vertex_data),
                    Bind::Whole(5, &b.patch_data),
                    Bind::PerItem {
                        binding: 6,
                        buffer: &vertices,
                        words: 6,
                        base: start as u64,
                    },
                ],
            )?);
            let slots = upload_u32(ctx, "prep corner slots", &slots)?;
            let face_cells = t.config.num_faces as usize * (n - 1) * (n - 1);
            let face_slot_base = plan.face_slot_base(k, start, n);
            index.push(pass(
                ctx,
                &self.lim,
                "prep_grid_indices",
                shaders::PREP_EVAL_GRID,
                "indices",
                PrepConfig {
                    face_slot_base: face_slot_base as u32,
                    ..t.config_for(face_cells, n)
                },
                &[
                    Bind::Whole(7, &slots),
                    Bind::PerItem {
                        binding: 9,
                        buffer: &indices,
                        words: 6,
                        base: first_cell,
                    },
                ],
            )?);
            tables.push(slots);
            first_cell += face_cells as u64;
        }
        eval.extend(index);
        tables.push(params);
        let grid = GpuGrid {
            n,
            vertices,
            indices,
            num_vertices: nvert,
            num_indices: 6 * cells,
            plan: Arc::clone(plan),
            _tables: tables,
            passes: eval,
        };
        submit(ctx, "prep grid indices", &grid.passes[plan.chunks.len()..])?;
        Ok(grid)
    }

    /// Evaluates the current patches into `grid`'s vertex buffer (positions and normals).
    pub fn eval_grid(&self, ctx: &GpuContext, grid: &GpuGrid) -> Result<()> {
        submit(
            ctx,
            "prep eval grid",
            &grid.passes[..self.plan.chunks.len()],
        )
    }
}
