//! GPU compute kernels for subsurf, on wgpu.
//!
//! Every kernel exists twice (the layout of linebender/vello): a WGSL shader
//! `shaders/<name>.wgsl`, validated with naga at build time, and a Rust CPU twin
//! [`cpu`]`::<name>` with the same binding order and the same `WORKGROUP_SIZE`. The twin is
//! the reference the GPU results are tested against.
//!
//! A backend never walks topology: it runs kernels over flat tables produced by the
//! refinement module (the split of OpenSubdiv's `Far` tables and `Osd` evaluators).
//!
//! Entry points: [`GpuContext`] (adapter and device), [`VertexBuffer`] (vertex data resident
//! on the GPU), [`StencilKernel`] (applies a [`StencilTable`] to a vertex buffer),
//! [`GpuRefiner`] (uniform refinement level by level, `refine_level` kernel) and [`GpuPrep`]
//! (the p-rep: `prep_vertex_pass`, `prep_patch_pass`, watertight `prep_eval_grid`) and
//! [`GpuLimit`] (the limit surface of a patch table: B-spline, single-crease and Gregory
//! patches, `limit_eval`) and [`GpuLoopLimit`] (the Loop limit surface: box-spline and
//! Gregory-triangle patches, `loop_eval`) and [`GpuUvRefiner`] (face-varying refinement of
//! UVs) and [`GpuRates`] (adaptive tessellation rates from the limit surface, `rate_measure`).
//!
//! # Example
//!
//! Refinement and the limit surface of a cube on the GPU, checked against the CPU; without
//! an adapter [`GpuContext::new`] fails with [`GpuError::NoAdapter`] and the CPU results
//! stand alone:
//!
//! ```
//! use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
//! use subsurf::{shapes, Refiner, Topology};
//! use subsurf_gpu::{GpuContext, GpuError, GpuLimit, GpuRefiner};
//!
//! let cube = shapes::cube();
//! let topology = Topology::new(&cube)?;
//! let refiner = Refiner::new(topology.clone(), 2)?;
//! let cpu = refiner.refine_positions(&cube.positions);
//! let table = PatchTable::build(&topology, &PatchOptions { isolation_level: 2, ..Default::default() })?;
//! let cpu_limit = LimitSurface::new(table.clone(), &cube.positions).tessellate(3)?;
//!
//! let ctx = match GpuContext::new() {
//!     Ok(ctx) => ctx,
//!     Err(GpuError::NoAdapter { detail }) => {
//!         eprintln!("no GPU adapter ({detail}): CPU results only");
//!         return Ok(());
//!     }
//!     Err(e) => return Err(e.into()),
//! };
//! let close = |a: &[f32; 3], b: &[f32; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 1e-5);
//!
//! // Uniform refinement: tables uploaded once, then one call per frame of base positions.
//! let gpu_refiner = GpuRefiner::new(&ctx, &refiner)?;
//! let gpu = gpu_refiner.refine(&ctx, &cube.positions)?;
//! assert_eq!(gpu.len(), 98);
//! assert!(gpu.iter().zip(&cpu).all(|(a, b)| close(a, b)));
//!
//! // Limit surface: the CPU's watertight index buffer, samples evaluated on the GPU.
//! let mut limit = GpuLimit::new(&ctx, &table)?;
//! limit.update(&ctx, &cube.positions)?;
//! let tess = limit.tessellation(&ctx, &table, 3)?;
//! limit.eval(&ctx, &tess.samples)?;
//! let gpu_limit = tess.download(&ctx)?;
//! assert_eq!(gpu_limit.quads, cpu_limit.quads);
//! assert!(gpu_limit.positions.iter().zip(&cpu_limit.positions).all(|(a, b)| close(a, b)));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Adapter limits
//!
//! Work is split against the adapter's `max_storage_buffer_binding_size` (128 MiB on
//! lavapipe) and `max_compute_workgroups_per_dimension` rather than refused; each entry point
//! has a `with_limits` constructor taking lower [`ChunkLimits`], which the tests use to force
//! the splits on small meshes (each split is tested bit for bit against whole bindings).
//! Without any adapter, [`GpuContext::new`] returns [`GpuError::NoAdapter`]. Only the
//! adapter's `max_buffer_size` bounds a buffer; what is split:
//!
//! | entry point | split per chunk |
//! |---|---|
//! | [`StencilKernel`], [`GpuUvRefiner`] | table rows (own `offsets`/`indices`/`weights`), destination at the chunk's aligned first row; a source larger than one binding gathered per chunk, window by window, into a scratch buffer ([`gather`]) |
//! | [`GpuRefiner`] | every level's tables, by child row; a level whose buffers exceed one binding refined from inputs gathered the same way, writing the child through a window |
//! | [`GpuLimit`] samples | queries and outputs; when the patch tables or the point array exceed one binding, also compacted copies of the patch map, patch data, control indices and points a chunk reads ([`limit_chunks`]); `update` through the split stencils and refiners above |
//! | [`GpuLoopLimit`] samples | queries and outputs; the patch tables are bound whole (refused with [`GpuError::TooLarge`] past one binding: about 620,000 end caps at 128 MiB) |
//! | [`GpuPrep`] | the mesh, into sub-problems of faces with their corners' rings ([`prep_chunks`]: positions, rings, vertex and patch coefficients of each fit one binding); dispatch grids; the tessellation's vertex and index buffers |
//!
//! Splitting is rarely needed at 128 MiB: a p-rep is split from about 700,000 faces (192
//! bytes of patch coefficients per face), a refined level from about 11 million vertices,
//! a limit point array from about 11 million points.

#![warn(missing_docs)]
pub mod buffers;
pub mod context;
pub mod cpu;
pub mod error;
pub mod gather;
pub mod headless;
pub mod kernels;
pub mod limit;
pub mod limit_chunks;
mod limit_twin;
pub mod loop_limit;
mod loop_twin;
pub mod prep;
pub mod prep_chunks;
pub mod rates;
pub mod refine;
pub mod shared;
pub mod surface;
pub mod table;
pub mod uv;

pub use buffers::VertexBuffer;
pub use context::GpuContext;
pub use error::GpuError;
pub use kernels::stencil::{ChunkLimits, StencilKernel};
pub use limit::{GpuLimit, GpuSamples, GpuTessellation};
pub use loop_limit::GpuLoopLimit;
pub use prep::{GpuGrid, GpuPrep, PrepTables};
pub use prep_chunks::PrepChunks;
pub use rates::GpuRates;
pub use refine::GpuRefiner;
pub use surface::GpuBackend;
pub use table::StencilTable;
pub use uv::GpuUvRefiner;

/// Constants extracted from the WGSL sources by `build.rs` (`<KERNEL>_WORKGROUP_SIZE`).
pub mod shader_consts {
    include!(concat!(env!("OUT_DIR"), "/shader_consts.rs"));
}

/// WGSL sources exactly as validated by `build.rs` (`common.wgsl` prepended).
pub mod shaders {
    /// `shaders/stencil_apply.wgsl`.
    pub const STENCIL_APPLY: &str = include_str!(concat!(env!("OUT_DIR"), "/stencil_apply.wgsl"));
    /// `shaders/prep_vertex_pass.wgsl`.
    pub const PREP_VERTEX_PASS: &str =
        include_str!(concat!(env!("OUT_DIR"), "/prep_vertex_pass.wgsl"));
    /// `shaders/prep_patch_pass.wgsl`.
    pub const PREP_PATCH_PASS: &str =
        include_str!(concat!(env!("OUT_DIR"), "/prep_patch_pass.wgsl"));
    /// `shaders/prep_eval_grid.wgsl`.
    pub const PREP_EVAL_GRID: &str = include_str!(concat!(env!("OUT_DIR"), "/prep_eval_grid.wgsl"));
    /// `shaders/limit_eval.wgsl`.
    pub const LIMIT_EVAL: &str = include_str!(concat!(env!("OUT_DIR"), "/limit_eval.wgsl"));
    /// `shaders/loop_eval.wgsl`.
    pub const LOOP_EVAL: &str = include_str!(concat!(env!("OUT_DIR"), "/loop_eval.wgsl"));
    /// `shaders/refine_level.wgsl`.
    pub const REFINE_LEVEL: &str = include_str!(concat!(env!("OUT_DIR"), "/refine_level.wgsl"));
    /// `shaders/rate_measure.wgsl`.
    pub const RATE_MEASURE: &str = include_str!(concat!(env!("OUT_DIR"), "/rate_measure.wgsl"));
}
