// p-rep vertex pass (Myles, Yeo & Peters 2008, eqs. (2)-(4)), one invocation per vertex p0
// of valence n with ring p1..p2n (odd: edge neighbours, even: diagonal neighbours):
//
//   g00 = n/(n+5) p0 + 4/(n(n+5)) sum p_{2l-1} + 1/(n(n+5)) sum p_{2l}
//   e1, e2 = sum_j (a_j p_{2j-1} + b_j p_{2j})        (weights premultiplied on the CPU)
//   T(k) = g00 + cos_k e1 + sin_k e2,  I(k) = (4 p0 + 2 (p_{2k+1} + p_{2k+3}) + p_{2k+2}) / 9
//
// for each of the vertex's sectors k. CPU twin: src/cpu/prep_vertex_pass.rs.

const WORKGROUP_SIZE: u32 = 64u;

@group(0) @binding(0) var<uniform> config: PrepConfig;
@group(0) @binding(1) var<storage, read> positions: array<f32>;
@group(0) @binding(2) var<storage, read> ring_offsets: array<u32>;
@group(0) @binding(3) var<storage, read> ring_indices: array<u32>;
@group(0) @binding(4) var<storage, read> valence_consts: array<f32>;
@group(0) @binding(5) var<storage, read_write> vertex_data: array<f32>;

fn pos(i: u32) -> vec3<f32> {
    return vec3<f32>(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
}

fn store(slot: u32, x: vec3<f32>) {
    vertex_data[3u * slot] = x.x;
    vertex_data[3u * slot + 1u] = x.y;
    vertex_data[3u * slot + 2u] = x.z;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.y * config.grid_width + gid.x;
    if local >= config.item_count {
        return;
    }
    let v = config.first_item + local;
    let nv = config.num_vertices;
    let r0 = ring_offsets[v];
    let n = (ring_offsets[v + 1u] - r0) / 2u;
    let p0 = pos(v);
    if n == 0u {
        store(v, p0);
        store(nv + v, vec3<f32>(0.0));
        store(2u * nv + v, vec3<f32>(0.0));
        return;
    }
    let cb = valence_base(n);
    var se = vec3<f32>(0.0);
    var sd = vec3<f32>(0.0);
    var e1 = vec3<f32>(0.0);
    var e2 = vec3<f32>(0.0);
    for (var j = 0u; j < n; j++) {
        let pe = pos(ring_indices[r0 + 2u * j]);
        let pd = pos(ring_indices[r0 + 2u * j + 1u]);
        let w = cb + 4u + 6u * j;
        se = se + pe;
        sd = sd + pd;
        e1 = (e1 + valence_consts[w] * pe) + valence_consts[w + 1u] * pd;
        e2 = (e2 + valence_consts[w + 2u] * pe) + valence_consts[w + 3u] * pd;
    }
    let g00 = (valence_consts[cb + 1u] * p0 + valence_consts[cb + 2u] * se)
        + valence_consts[cb + 3u] * sd;
    store(v, g00);
    store(nv + v, e1);
    store(2u * nv + v, e2);
    let tangent = 3u * nv;
    let interior = 3u * nv + config.num_sectors;
    let s0 = r0 / 2u;
    for (var k = 0u; k < n; k++) {
        let w = cb + 4u + 6u * k;
        store(tangent + s0 + k, (g00 + valence_consts[w + 4u] * e1) + valence_consts[w + 5u] * e2);
        let p1 = pos(ring_indices[r0 + 2u * k]);
        let p2 = pos(ring_indices[r0 + 2u * k + 1u]);
        let p3 = pos(ring_indices[r0 + (2u * k + 2u) % (2u * n)]);
        store(interior + s0 + k, (1.0 / 9.0) * ((4.0 * p0 + 2.0 * (p1 + p3)) + p2));
    }
}
