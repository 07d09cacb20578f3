// One step of uniform refinement (per-level stencils of the refinement module), one
// invocation per child vertex of a table chunk:
//
//   child[(first_row + i)*stride + c] = sum_j weights[j] * src(indices[j])[c]
//
// where src(k) = parent[k] for k < num_parent and child[k] otherwise: the vertex and edge
// tables of a level refer to the face points, which are child vertices P..P+F written by
// the preceding face-table dispatch (child layout [vertex rows | face rows | edge rows]).
// Accumulated in f32 in index order. CPU twin: src/cpu/refine_level.rs.

const WORKGROUP_SIZE: u32 = 64u;

@group(0) @binding(0) var<uniform> config: RefineConfig;
@group(0) @binding(1) var<storage, read> offsets: array<u32>;
@group(0) @binding(2) var<storage, read> indices: array<u32>;
@group(0) @binding(3) var<storage, read> weights: array<f32>;
@group(0) @binding(4) var<storage, read> parent: array<f32>;
@group(0) @binding(5) var<storage, read_write> child: array<f32>;

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let row = gid.y * config.grid_width + gid.x;
    if row >= config.row_count {
        return;
    }
    let begin = offsets[row];
    let end = offsets[row + 1u];
    let stride = config.stride;
    let np = config.num_parent;
    var acc = array<f32, 4>(0.0, 0.0, 0.0, 0.0);
    for (var j = begin; j < end; j++) {
        let w = weights[j];
        let k = indices[j];
        let base = k * stride;
        if k < np {
            for (var c = 0u; c < stride; c++) {
                acc[c] += w * parent[base + c];
            }
        } else {
            for (var c = 0u; c < stride; c++) {
                acc[c] += w * child[base + c];
            }
        }
    }
    let out = (config.first_row + row) * stride;
    for (var c = 0u; c < stride; c++) {
        child[out + c] = acc[c];
    }
}
