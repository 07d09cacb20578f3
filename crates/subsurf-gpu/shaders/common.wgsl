// Declarations shared by every kernel. build.rs prepends this file to each kernel
// before validating it, and the crate ships exactly the text build.rs validated.
//
// Keep in sync with src/shared.rs (the Rust side is `#[repr(C)]` + bytemuck `Pod`).

// Per-dispatch parameters of `stencil_apply` (one uniform per chunk of rows).
struct StencilConfig {
    // Number of stencil rows (destination vertices) in this chunk.
    row_count: u32,
    // Floats per vertex in the source and destination buffers.
    stride: u32,
    // Invocations along x of the dispatch grid (workgroups_x * WORKGROUP_SIZE);
    // the row of an invocation is `gid.y * grid_width + gid.x`.
    grid_width: u32,
    _pad: u32,
}
