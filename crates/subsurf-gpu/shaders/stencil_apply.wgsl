// Applies a stencil table to vertex data, one invocation per destination vertex:
//
//   dst[i*stride + k] = sum_{j in offsets[i]..offsets[i+1]} weights[j] * src[indices[j]*stride + k]
//
// accumulated in f32 in index order; with config.relative = 1 (rows summing to 1),
//   dst[i*stride + k] = x0 + sum_j weights[j] * (src[indices[j]*stride + k] - x0),
//   x0 = src[indices[offsets[i]]*stride + k],
// whose rounding is of the row's neighbourhood instead of the distance from the origin. The CPU twin is src/cpu/stencil_apply.rs (same
// binding order, same WORKGROUP_SIZE, same loop structure).
//
// The table is uploaded in chunks of rows; `offsets` of a chunk are rebased so that the
// chunk's first entry is entry 0, and `dst` is bound at the chunk's first row.

const WORKGROUP_SIZE: u32 = 64u;
// Components accumulated together; larger strides are processed in blocks of BLOCK.
const BLOCK: u32 = 4u;

@group(0) @binding(0) var<uniform> config: StencilConfig;
@group(0) @binding(1) var<storage, read> offsets: array<u32>;
@group(0) @binding(2) var<storage, read> indices: array<u32>;
@group(0) @binding(3) var<storage, read> weights: array<f32>;
@group(0) @binding(4) var<storage, read> src: array<f32>;
@group(0) @binding(5) var<storage, read_write> dst: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let row = gid.y * config.grid_width + gid.x;
    if row >= config.row_count {
        return;
    }
    let begin = offsets[row];
    let end = offsets[row + 1u];
    let stride = config.stride;
    for (var k0 = 0u; k0 < stride; k0 += BLOCK) {
        let width = min(BLOCK, stride - k0);
        var acc = array<f32, 4>(0.0, 0.0, 0.0, 0.0);
        var x0 = array<f32, 4>(0.0, 0.0, 0.0, 0.0);
        if config.relative != 0u && begin < end {
            let base0 = indices[begin] * stride + k0;
            for (var c = 0u; c < width; c++) {
                x0[c] = src[base0 + c];
            }
        }
        for (var j = begin; j < end; j++) {
            let w = weights[j];
            let base = indices[j] * stride + k0;
            for (var c = 0u; c < width; c++) {
                acc[c] += w * (src[base + c] - x0[c]);
            }
        }
        let out = row * stride + k0;
        for (var c = 0u; c < width; c++) {
            dst[out + c] = select(acc[c], acc[c] + x0[c], config.relative != 0u);
        }
    }
}
