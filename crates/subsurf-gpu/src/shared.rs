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
    /// Padding to 16 bytes.
    pub _pad: u32,
}

const _: () = assert!(std::mem::size_of::<StencilConfig>() == 16);
