//! Structs shared between Rust and WGSL.
//!
//! Keep in sync with shaders/common.wgsl: same field order, same types, sizes a multiple
//! of 16 bytes (uniform layout rules).

use bytemuck::{Pod, Zeroable};

/// Per-dispatch parameters of `stencil_apply` (keep in sync with shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct StencilConfig {
    /// Number of stencil rows (destination vertices) in the dispatch.
    pub row_count: u32,
    /// Floats per vertex in source and destination.
    pub stride: u32,
    /// Invocations along x of the dispatch grid (`workgroups_x * WORKGROUP_SIZE`); the row
    /// of invocation `gid` is `gid.y * grid_width + gid.x`.
    pub grid_width: u32,
    /// 1: each row is applied relative to its first input, `x_0 + Σ w (x − x_0)` (for
    /// tables whose rows sum to 1: the rounding is then relative to the row's
    /// neighbourhood, not to the distance from the origin); 0: `Σ w x`.
    pub relative: u32,
}

const _: () = assert!(std::mem::size_of::<StencilConfig>() == 16);

/// Per-dispatch parameters of `refine_level` (keep in sync with shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct RefineConfig {
    /// Rows (child vertices) in this chunk.
    pub row_count: u32,
    /// Floats per vertex (1..=4).
    pub stride: u32,
    /// Invocations along x of the dispatch grid.
    pub grid_width: u32,
    /// Child vertex written by row 0 of the chunk.
    pub first_row: u32,
    /// Number of parent vertices `P`: inputs `k < P` are parent vertices, others child vertices.
    pub num_parent: u32,
    /// Padding to 32 bytes.
    pub _pad: [u32; 3],
}

const _: () = assert!(std::mem::size_of::<RefineConfig>() == 32);

/// Per-dispatch parameters of the p-rep kernels (keep in sync with shaders/common.wgsl).
///
/// Flat buffers of the p-rep, 3 floats per point: `vertex_data = [limit V | e1 V | e2 V |
/// tangent S | interior S]`, `patch_data = [g 16 F | h 16 P]`. The counts are those of one
/// sub-problem (see `prep_chunks`): `V` its core vertices, `S` their sectors, `F` its faces,
/// `E` the edges whose samples it writes; the whole mesh when it is one sub-problem.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct PrepConfig {
    /// Vertices `V`.
    pub num_vertices: u32,
    /// Sectors `S` (face corners).
    pub num_sectors: u32,
    /// Faces `F`.
    pub num_faces: u32,
    /// Edges `E`.
    pub num_edges: u32,
    /// Invocations of the dispatch.
    pub item_count: u32,
    /// Invocations along x of the dispatch grid.
    pub grid_width: u32,
    /// Samples per patch side of `prep_eval_grid` (>= 2).
    pub samples: u32,
    /// Item (vertex, face, grid vertex or cell) of invocation 0: a dispatch covers items
    /// `first_item .. first_item + item_count`; per-item outputs of `prep_eval_grid` are bound
    /// at the chunk's first item.
    pub first_item: u32,
    /// Vertices whose tessellation sample this sub-problem writes: local vertices
    /// `0..owned_vertices` (`prep_eval_grid`).
    pub owned_vertices: u32,
    /// Words between the start of the per-item output binding and the chunk's first item
    /// (the binding starts at an aligned offset at or before it).
    pub out_shift: u32,
    /// Slot in the vertex buffer of the sub-problem's first face-interior sample
    /// (`prep_eval_grid` entry `indices`).
    pub face_slot_base: u32,
    /// Padding to 48 bytes.
    pub _pad: u32,
}

const _: () = assert!(std::mem::size_of::<PrepConfig>() == 48);

/// Per-dispatch parameters of `limit_eval` (keep in sync with shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct LimitConfig {
    /// Samples (queries) in this chunk.
    pub item_count: u32,
    /// Invocations along x of the dispatch grid.
    pub grid_width: u32,
    /// Floats written per sample: 6 (position, normal) or 12 (position, normal, `∂/∂u`,
    /// `∂/∂v`).
    pub out_stride: u32,
    /// Ptex faces: entries `0..num_roots` of the patch map are the roots.
    pub num_roots: u32,
}

const _: () = assert!(std::mem::size_of::<LimitConfig>() == 16);

/// Per-dispatch parameters of `loop_eval` (keep in sync with shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct LoopConfig {
    /// Samples (queries) in this chunk.
    pub item_count: u32,
    /// Invocations along x of the dispatch grid.
    pub grid_width: u32,
    /// Floats written per sample: 6 (position, normal) or 12 (position, normal, `∂/∂u`,
    /// `∂/∂v`).
    pub out_stride: u32,
    /// Patches: a sample whose patch index is not below this evaluates to zeros.
    pub num_patches: u32,
}

const _: () = assert!(std::mem::size_of::<LoopConfig>() == 16);

/// Per-dispatch parameters of `rate_measure` (keep in sync with shaders/common.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RateConfig {
    /// Curves in this chunk.
    pub curve_count: u32,
    /// Samples per curve.
    pub points_per_curve: u32,
    /// Floats per sample in the samples buffer (position first).
    pub sample_stride: u32,
    /// 0: second derivative, 1: speed, 2: speed in pixels under `view_proj`.
    pub kind: u32,
    /// Invocations along x of the dispatch grid.
    pub grid_width: u32,
    /// Image width in pixels (kind 2).
    pub width: f32,
    /// Image height in pixels (kind 2).
    pub height: f32,
    /// Padding to the matrix's 16-byte alignment.
    pub _pad: u32,
    /// World-to-clip matrix, column-major (`view_proj[column][row]`; kind 2).
    pub view_proj: [[f32; 4]; 4],
}

const _: () = assert!(std::mem::size_of::<RateConfig>() == 96);
