//! The p-rep (Myles, Yeo & Peters 2008) on the GPU: vertex pass, patch pass and watertight
//! `n×n` evaluation as three kernels over the flat ring tables of
//! [`subsurf::prep::PrepTopology`], each with its CPU twin in [`crate::cpu`].
//!
//! [`GpuPrep::new`] uploads the connectivity once; per frame [`GpuPrep::update`] writes the
//! positions and runs both passes, and [`GpuPrep::eval_grid`] fills a [`GpuGrid`] (vertex
//! buffer of position + normal, index buffer of triangles) allocated once per `n`. All data
//! stays on the GPU until read back.
//!
//! Every pass is split into chunks of items (vertices, faces, grid vertices, grid cells):
//! a chunk's first item is a field of its uniform (`first_item`), so no dispatch exceeds
//! `max_compute_workgroups_per_dimension`², and the per-item outputs of the tessellation
//! (vertex and index buffers, the largest by far) are bound at the chunk's first item, at an
//! aligned offset, so no binding exceeds `max_storage_buffer_binding_size`. The inputs
//! gathered at arbitrary indices (positions, rings, vertex and patch coefficients) are bound
//! whole; past the binding limit they are refused with [`GpuError::TooLarge`] (the patch
//! coefficients first, at about 700,000 faces for 128 MiB). Splitting them needs chunk-local
//! sub-problems (a chunk of faces with its vertices' rings, local sectors and h blocks, and an
//! owner chunk for every shared edge and vertex of the tessellation so that seams stay
//! computed from one side), as `GpuLimit` does for its tables.

use crate::buffers::{read_back, storage_buffer_init};
use crate::context::GpuContext;
use crate::cpu::prep_eval_grid::{
    grid_params, prep_eval_grid_invocation, prep_grid_indices_invocation, EvalInputs,
};
use crate::cpu::prep_patch_pass::{prep_patch_pass, PatchInputs};
use crate::cpu::prep_vertex_pass::{prep_vertex_pass, valence_consts};
use crate::error::{GpuError, Result};
use crate::kernels::chunked_pass::{
    empty_storage, pass, submit, upload_u32, Bind, Pass, PassLimits,
};
use crate::kernels::stencil::ChunkLimits;
use crate::shaders;
use crate::shared::PrepConfig;
use subsurf::prep::{PrepTopology, Tessellation};

const WORD: u64 = 4;

/// The flat tables the p-rep kernels read, built from a [`PrepTopology`].
#[derive(Debug, Clone)]
pub struct PrepTables {
    /// Counts (`item_count`, `grid_width`, `samples` left 0).
    pub config: PrepConfig,
    /// Ring offsets (V + 1).
    pub ring_offsets: Vec<u32>,
    /// Rings (2 S).
    pub ring_indices: Vec<u32>,
    /// Flat per-valence constants.
    pub valence_consts: Vec<f32>,
    /// Vertex of each face corner (4 F).
    pub face_verts: Vec<u32>,
    /// Sector of each face corner (4 F).
    pub corner_sector: Vec<u32>,
    /// Edge of each face corner (4 F).
    pub face_edges: Vec<u32>,
    /// Canonical face corner of each edge (E).
    pub edge_corner: Vec<u32>,
    /// h block of each face (F), `u32::MAX` for a B-quad.
    pub h_index: Vec<u32>,
    /// Number of perturbed faces `P`.
    pub num_perturbed: usize,
}

impl PrepTables {
    /// Flattens `t`, checking that every count fits the kernels' 32-bit indexing.
    pub fn new(t: &PrepTopology) -> Result<Self> {
        let too_big =
            |what: &str| GpuError::BufferMismatch(format!("{what} exceed 32-bit indexing"));
        let s = t.sector_vertex.len();
        if 3 * (3 * t.num_vertices + 2 * s) >= u32::MAX as usize {
            return Err(too_big("vertex data"));
        }
        if 3 * 16 * (t.num_faces() + t.perturbed_faces.len()) >= u32::MAX as usize {
            return Err(too_big("patch coefficients"));
        }
        Ok(Self {
            config: PrepConfig {
                num_vertices: t.num_vertices as u32,
                num_sectors: s as u32,
                num_faces: t.num_faces() as u32,
                num_edges: t.num_edges() as u32,
                ..Default::default()
            },
            ring_offsets: t.ring_offsets.clone(),
            ring_indices: t.ring_indices.clone(),
            valence_consts: valence_consts(t.max_valence.max(3)),
            face_verts: t.face_verts.clone(),
            corner_sector: t.corner_sector.clone(),
            face_edges: t.face_edges.clone(),
            edge_corner: t.edge_corner.clone(),
            h_index: t.h_index.clone(),
            num_perturbed: t.perturbed_faces.len(),
        })
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

    /// Vertices of the watertight `n×n` tessellation.
    pub fn grid_vertices(&self, n: usize) -> usize {
        let c = &self.config;
        let m = n - 2;
        c.num_vertices as usize + c.num_edges as usize * m + c.num_faces as usize * m * m
    }

    /// Grid cells (two triangles each) of the `n×n` tessellation.
    pub fn grid_cells(&self, n: usize) -> usize {
        self.config.num_faces as usize * (n - 1) * (n - 1)
    }

    fn config_for(&self, items: usize, samples: usize) -> PrepConfig {
        PrepConfig {
            item_count: items as u32,
            grid_width: items as u32,
            samples: samples as u32,
            ..self.config
        }
    }

    /// CPU twin of [`GpuPrep::update`]: `(vertex_data, patch_data)` for `positions`.
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

    /// CPU twin of [`GpuPrep::eval_grid`]: the watertight tessellation from pass outputs.
    pub fn eval_grid_cpu(
        &self,
        n: usize,
        vertex_data: &[f32],
        patch_data: &[f32],
    ) -> Tessellation<f32> {
        let n = n.max(2);
        let params = grid_params(n);
        let inp = EvalInputs {
            params: &params,
            edge_corner: &self.edge_corner,
            h_index: &self.h_index,
            vertex_data,
            patch_data,
        };
        let nvert = self.grid_vertices(n);
        let cfg = self.config_for(nvert, n);
        let mut out = vec![0.0f32; 6 * nvert];
        for item in 0..nvert as u32 {
            prep_eval_grid_invocation(item, &cfg, &inp, &mut out);
        }
        let cells = self.grid_cells(n);
        let cfg = self.config_for(cells, n);
        let mut idx = vec![0u32; 6 * cells];
        for item in 0..cells as u32 {
            prep_grid_indices_invocation(item, &cfg, &self.face_verts, &self.face_edges, &mut idx);
        }
        unpack(&out, &idx)
    }
}

fn unpack(vertices: &[f32], indices: &[u32]) -> Tessellation<f32> {
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

/// A p-rep resident on the GPU: connectivity tables, positions and both passes' outputs.
#[derive(Debug)]
pub struct GpuPrep {
    tables: PrepTables,
    positions: wgpu::Buffer,
    vertex_data: wgpu::Buffer,
    patch_data: wgpu::Buffer,
    edge_corner: wgpu::Buffer,
    h_index: wgpu::Buffer,
    face_verts: wgpu::Buffer,
    face_edges: wgpu::Buffer,
    passes: [Pass; 2],
    lim: PassLimits,
}

/// An `n×n` watertight tessellation on the GPU: `vertices` (6 floats: position, unit normal)
/// and `indices` (3 per ccw triangle), filled by [`GpuPrep::eval_grid`].
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
    _params: wgpu::Buffer,
    passes: [Pass; 2],
}

impl GpuGrid {
    /// Dispatches of one [`GpuPrep::eval_grid`] (more than one when chunked).
    pub fn num_dispatches(&self) -> usize {
        self.passes[0].dispatches.len()
    }

    /// Reads the tessellation back (waits for the submitted work).
    pub fn download(&self, ctx: &GpuContext) -> Result<Tessellation<f32>> {
        let v = read_back(ctx, &self.vertices, (6 * self.num_vertices) as u64 * WORD)?;
        let i: Vec<u32> = read_back(ctx, &self.indices, self.num_indices as u64 * WORD)?
            .into_iter()
            .map(f32::to_bits)
            .collect();
        Ok(unpack(&v, &i))
    }
}

impl GpuPrep {
    /// Uploads the connectivity of `topo` and creates both passes (positions still zero:
    /// call [`Self::update`]).
    pub fn new(ctx: &GpuContext, topo: &PrepTopology) -> Result<Self> {
        Self::with_limits(ctx, topo, ChunkLimits::from_context(ctx))
    }

    /// [`Self::new`] with the dispatches chunked against `limits` (clamped to the adapter's):
    /// lower values force more chunks, which tests use to exercise chunking. The limits bound
    /// the per-chunk bindings (grid outputs) and dispatch grids; the buffers bound whole must
    /// fit the adapter's binding limit.
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
        let tables = PrepTables::new(topo)?;
        let nv = tables.config.num_vertices as usize;
        let positions = empty_storage(ctx, "prep positions", (3 * nv) as u64 * WORD, true)?;
        let ring_offsets = upload_u32(ctx, "prep ring offsets", &tables.ring_offsets)?;
        let ring_indices = upload_u32(ctx, "prep ring indices", &tables.ring_indices)?;
        let consts = storage_buffer_init(
            ctx,
            "prep valence constants",
            bytemuck::cast_slice(&tables.valence_consts),
        )?;
        let face_verts = upload_u32(ctx, "prep face vertices", &tables.face_verts)?;
        let corner_sector = upload_u32(ctx, "prep corner sectors", &tables.corner_sector)?;
        let face_edges = upload_u32(ctx, "prep face edges", &tables.face_edges)?;
        let edge_corner = upload_u32(ctx, "prep edge corners", &tables.edge_corner)?;
        let h_index = upload_u32(ctx, "prep h index", &tables.h_index)?;
        let vertex_data = empty_storage(
            ctx,
            "prep vertex data",
            tables.vertex_data_len() as u64 * WORD,
            true,
        )?;
        let patch_data = empty_storage(
            ctx,
            "prep patch data",
            tables.patch_data_len() as u64 * WORD,
            true,
        )?;
        let vp = pass(
            ctx,
            &lim,
            "prep_vertex_pass",
            shaders::PREP_VERTEX_PASS,
            "main",
            tables.config_for(nv, 0),
            &[
                Bind::Whole(1, &positions),
                Bind::Whole(2, &ring_offsets),
                Bind::Whole(3, &ring_indices),
                Bind::Whole(4, &consts),
                Bind::Whole(5, &vertex_data),
            ],
        )?;
        let pp = pass(
            ctx,
            &lim,
            "prep_patch_pass",
            shaders::PREP_PATCH_PASS,
            "main",
            tables.config_for(tables.config.num_faces as usize, 0),
            &[
                Bind::Whole(1, &face_verts),
                Bind::Whole(2, &corner_sector),
                Bind::Whole(3, &ring_offsets),
                Bind::Whole(4, &h_index),
                Bind::Whole(5, &consts),
                Bind::Whole(6, &vertex_data),
                Bind::Whole(7, &patch_data),
            ],
        )?;
        Ok(Self {
            tables,
            positions,
            vertex_data,
            patch_data,
            edge_corner,
            h_index,
            face_verts,
            face_edges,
            passes: [vp, pp],
            lim,
        })
    }

    /// Dispatches of one [`Self::update`] (vertex and patch pass; more than two when chunked).
    pub fn num_dispatches(&self) -> usize {
        self.passes.iter().map(|p| p.dispatches.len()).sum()
    }

    /// The flat tables (for the CPU twins).
    pub fn tables(&self) -> &PrepTables {
        &self.tables
    }

    /// Writes `positions` and submits the vertex and patch passes.
    pub fn update(&self, ctx: &GpuContext, positions: &[[f32; 3]]) -> Result<()> {
        let nv = self.tables.config.num_vertices as usize;
        if positions.len() != nv {
            return Err(GpuError::BufferMismatch(format!(
                "{} positions for a p-rep of {nv} vertices",
                positions.len()
            )));
        }
        if nv > 0 {
            ctx.queue
                .write_buffer(&self.positions, 0, bytemuck::cast_slice(positions));
        }
        submit(ctx, "prep passes", &self.passes)
    }

    /// Reads back `(vertex_data, patch_data)` (layouts in [`PrepConfig`]).
    pub fn download_coefficients(&self, ctx: &GpuContext) -> Result<(Vec<f32>, Vec<f32>)> {
        Ok((
            read_back(
                ctx,
                &self.vertex_data,
                self.tables.vertex_data_len() as u64 * WORD,
            )?,
            read_back(
                ctx,
                &self.patch_data,
                self.tables.patch_data_len() as u64 * WORD,
            )?,
        ))
    }

    /// Allocates the buffers and bind groups of an `n×n` tessellation (`n >= 2`) and fills
    /// its index buffer (the indices depend on the connectivity only).
    pub fn grid(&self, ctx: &GpuContext, n: usize) -> Result<GpuGrid> {
        let n = n.max(2);
        let nvert = self.tables.grid_vertices(n);
        let cells = self.tables.grid_cells(n);
        if 6 * nvert as u64 >= u32::MAX as u64 || 6 * cells as u64 >= u32::MAX as u64 {
            return Err(GpuError::BufferMismatch(format!(
                "a {n}x{n} tessellation of {} faces exceeds 32-bit indexing",
                self.tables.config.num_faces
            )));
        }
        let params =
            storage_buffer_init(ctx, "prep params", bytemuck::cast_slice(&grid_params(n)))?;
        let vertices = empty_storage(ctx, "prep grid vertices", (6 * nvert) as u64 * WORD, false)?;
        let indices = empty_storage(ctx, "prep grid indices", (6 * cells) as u64 * WORD, false)?;
        let ev = pass(
            ctx,
            &self.lim,
            "prep_eval_grid",
            shaders::PREP_EVAL_GRID,
            "main",
            self.tables.config_for(nvert, n),
            &[
                Bind::Whole(1, &params),
                Bind::Whole(2, &self.edge_corner),
                Bind::Whole(3, &self.h_index),
                Bind::Whole(4, &self.vertex_data),
                Bind::Whole(5, &self.patch_data),
                Bind::PerItem(6, &vertices, 6),
            ],
        )?;
        let ix = pass(
            ctx,
            &self.lim,
            "prep_grid_indices",
            shaders::PREP_EVAL_GRID,
            "indices",
            self.tables.config_for(cells, n),
            &[
                Bind::Whole(7, &self.face_verts),
                Bind::Whole(8, &self.face_edges),
                Bind::PerItem(9, &indices, 6),
            ],
        )?;
        let grid = GpuGrid {
            n,
            vertices,
            indices,
            num_vertices: nvert,
            num_indices: 6 * cells,
            _params: params,
            passes: [ev, ix],
        };
        submit(ctx, "prep grid indices", &grid.passes[1..])?;
        Ok(grid)
    }

    /// Evaluates the current patches into `grid`'s vertex buffer (positions and normals).
    pub fn eval_grid(&self, ctx: &GpuContext, grid: &GpuGrid) -> Result<()> {
        submit(ctx, "prep eval grid", &grid.passes[..1])
    }
}
