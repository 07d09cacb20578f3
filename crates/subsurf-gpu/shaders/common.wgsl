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
    // 1: rows relative to their first input, x0 + sum w (x - x0) (rows summing to 1).
    relative: u32,
}

// Per-dispatch parameters of `refine_level` (one uniform per chunk of one table).
struct RefineConfig {
    // Rows (child vertices) in this chunk.
    row_count: u32,
    // Floats per vertex (1..=4).
    stride: u32,
    // Invocations along x of the dispatch grid.
    grid_width: u32,
    // Child vertex written by row 0 of the chunk.
    first_row: u32,
    // Number of parent vertices P: inputs k < P are parent vertices, others child vertices.
    num_parent: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Per-dispatch parameters of the p-rep kernels (prep_vertex_pass, prep_patch_pass,
// prep_eval_grid), counts of one sub-problem (src/prep_chunks.rs). Flat buffers, 3 floats per
// point:
//   vertex_data = [limit V | e1 V | e2 V | tangent S | interior S]
//   patch_data  = [g 16 F | h 16 P]
struct PrepConfig {
    num_vertices: u32,
    num_sectors: u32,
    num_faces: u32,
    num_edges: u32,
    // Invocations of this dispatch, and invocations along x of its grid.
    item_count: u32,
    grid_width: u32,
    // Samples per patch side of prep_eval_grid (>= 2).
    samples: u32,
    // Item of invocation 0 (the dispatch covers first_item .. first_item + item_count); the
    // outputs of prep_eval_grid are bound at an aligned offset at or before the chunk's first
    // item, out_shift words before it.
    first_item: u32,
    // Local vertices 0..owned_vertices have their tessellation sample written by this
    // sub-problem; V above counts every core vertex (the vertex_data layout).
    owned_vertices: u32,
    out_shift: u32,
    // Vertex-buffer slot of the sub-problem's first face-interior sample (entry `indices`).
    face_slot_base: u32,
    _pad: u32,
}

// Offset (in floats) of valence n's constants in `valence_consts`: valence m holds
// 4 + 6 m floats, so valence n starts at sum_{m<n} (4 + 6m) = 4n + 3n(n-1).
// Layout: [c_n, limit0, limit1, limit2, then per j < n: e1a, e1b, e2a, e2b, cos_j, sin_j].
fn valence_base(n: u32) -> u32 {
    return 4u * n + 3u * n * (n - 1u);
}

// Face-array index of local index (i, j) at corner c of a (d+1)x(d+1) array, as a flat
// row-major index i * (d+1) + j.
fn corner_index(c: u32, i: u32, j: u32, d: u32) -> u32 {
    var a = i;
    var b = j;
    if c == 1u {
        a = d - j;
        b = i;
    } else if c == 2u {
        a = d - i;
        b = d - j;
    } else if c == 3u {
        a = j;
        b = d - i;
    }
    return a * (d + 1u) + b;
}

// Per-dispatch parameters of limit_eval (one uniform per chunk of samples).
struct LimitConfig {
    // Samples in this chunk, and invocations along x of its grid.
    item_count: u32,
    grid_width: u32,
    // Floats written per sample: 6 (p, n) or 12 (p, n, du, dv).
    out_stride: u32,
    // Ptex faces: patch_map[0..num_roots] are the roots, inner nodes follow (4 words each).
    num_roots: u32,
}

// Per-dispatch parameters of loop_eval (one uniform per chunk of samples).
struct LoopConfig {
    // Samples in this chunk, and invocations along x of its grid.
    item_count: u32,
    grid_width: u32,
    // Floats written per sample: 6 (p, n) or 12 (p, n, du, dv).
    out_stride: u32,
    // Patches: a sample whose patch is not below this evaluates to zeros.
    num_patches: u32,
}

// Per-dispatch parameters of `rate_measure` (one uniform per chunk of rate curves).
struct RateConfig {
    // Curves in this chunk.
    curve_count: u32,
    // Samples per curve.
    points_per_curve: u32,
    // Floats per sample in the samples buffer (position first).
    sample_stride: u32,
    // 0: second derivative, 1: speed, 2: speed in pixels under view_proj.
    kind: u32,
    // Invocations along x of the dispatch grid.
    grid_width: u32,
    // Image width and height in pixels (kind 2).
    width: f32,
    height: f32,
    _pad0: u32,
    // World-to-clip matrix, column-major (kind 2).
    view_proj: mat4x4<f32>,
}
