// Evaluation of the p-rep on an n x n grid per face into a WATERTIGHT mesh (Myles, Yeo &
// Peters 2008, §4 "pass 2"):
//
//   x(u,v) = sum_{i,j<4} g_ij B3_i(u) B3_j(v) + sum_{16 slots} h_ij B5_i(u) B5_j(v)
//
// Run once per sub-problem (src/prep_chunks.rs; the whole mesh when it is one). Items of a
// sub-problem, in its region of the vertex buffer: one sample per OWNED vertex (its limit point
// g00, normal e1 x e2), then n-2 per owned edge, then (n-2)^2 per face. A shared-edge sample is
// computed ONCE, by the invocation of its edge, from the edge curve
// sum_i g_i0 B3_i(t) + h20 B5_2(t) + h30 B5_3(t) of the face owning the edge in its canonical
// direction; both faces' triangles index it, so the two sides are identical bit for bit.
//
// Entry `main`: one invocation per output vertex, writes 6 floats (position, unit normal).
// Entry `indices`: one invocation per grid cell, writes its two ccw triangles; the slots of
// its corner and edge samples come from `corner_slots` (8 per face: 4 corner-vertex slots, 4
// first-edge-sample slots with bit 31 set when the face runs along the edge's direction).
// Both write at out_shift + 6 * (item - first_item) of their output binding.
// CPU twin: src/cpu/prep_eval_grid.rs.

const WORKGROUP_SIZE: u32 = 64u;
const NO_H: u32 = 0xffffffffu;

@group(0) @binding(0) var<uniform> config: PrepConfig;
@group(0) @binding(1) var<storage, read> params: array<f32>;
@group(0) @binding(2) var<storage, read> edge_corner: array<u32>;
@group(0) @binding(3) var<storage, read> h_index: array<u32>;
@group(0) @binding(4) var<storage, read> vertex_data: array<f32>;
@group(0) @binding(5) var<storage, read> patch_data: array<f32>;
@group(0) @binding(6) var<storage, read_write> out_vertices: array<f32>;
@group(0) @binding(7) var<storage, read> corner_slots: array<u32>;
@group(0) @binding(9) var<storage, read_write> out_indices: array<u32>;

struct Basis {
    b3: array<f32, 4>,
    d3: array<f32, 4>,
    b5: array<f32, 6>,
    d5: array<f32, 6>,
}

// Bernstein values and derivatives of degree 3 and 5 at t.
fn basis(t: f32) -> Basis {
    let s = 1.0 - t;
    var b: Basis;
    b.b3 = array<f32, 4>(s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t);
    let q0 = s * s;
    let q1 = 2.0 * s * t;
    let q2 = t * t;
    b.d3 = array<f32, 4>(-3.0 * q0, 3.0 * (q0 - q1), 3.0 * (q1 - q2), 3.0 * q2);
    let s2 = s * s;
    let t2 = t * t;
    b.b5 = array<f32, 6>(s2 * s2 * s, 5.0 * s2 * s2 * t, 10.0 * s2 * s * t2,
                         10.0 * s2 * t2 * t, 5.0 * s * t2 * t2, t2 * t2 * t);
    let c0 = s2 * s2;
    let c1 = 4.0 * s2 * s * t;
    let c2 = 6.0 * s2 * t2;
    let c3 = 4.0 * s * t2 * t;
    let c4 = t2 * t2;
    b.d5 = array<f32, 6>(-5.0 * c0, 5.0 * (c0 - c1), 5.0 * (c1 - c2), 5.0 * (c2 - c3),
                         5.0 * (c3 - c4), 5.0 * c4);
    return b;
}

fn vd(slot: u32) -> vec3<f32> {
    return vec3<f32>(vertex_data[3u * slot], vertex_data[3u * slot + 1u], vertex_data[3u * slot + 2u]);
}

fn pd(slot: u32) -> vec3<f32> {
    return vec3<f32>(patch_data[3u * slot], patch_data[3u * slot + 1u], patch_data[3u * slot + 2u]);
}

// Slot s of the compact h block: corner s / 4, local [h20, h30, h21, h31][s % 4], as the
// (i, j) of the 6x6 array (flat i * 6 + j).
fn h_slot(s: u32) -> u32 {
    let m = s % 4u;
    return corner_index(s / 4u, 2u + m % 2u, m / 2u, 5u);
}

fn normalized(a: vec3<f32>) -> vec3<f32> {
    let l2 = a.x * a.x + a.y * a.y + a.z * a.z;
    if l2 > 0.0 {
        return (1.0 / sqrt(l2)) * a;
    }
    return a;
}

struct Sample {
    p: vec3<f32>,
    du: vec3<f32>,
    dv: vec3<f32>,
}

fn eval_patch(f: u32, bu_in: Basis, bv_in: Basis) -> Sample {
    // Indexed through function variables: naga spills a dynamically indexed array value to a
    // temporary at every access otherwise.
    var bu = bu_in;
    var bv = bv_in;
    var r: Sample;
    r.p = vec3<f32>(0.0);
    r.du = vec3<f32>(0.0);
    r.dv = vec3<f32>(0.0);
    // The bi-3 part relative to g00 (its weights sum to 1; h is a perturbation): rounding
    // of the patch's size, not of its distance from the origin.
    let x0 = pd(16u * f);
    for (var i = 0u; i < 4u; i++) {
        for (var j = 0u; j < 4u; j++) {
            let x = pd(16u * f + 4u * i + j) - x0;
            r.p += (bu.b3[i] * bv.b3[j]) * x;
            r.du += (bu.d3[i] * bv.b3[j]) * x;
            r.dv += (bu.b3[i] * bv.d3[j]) * x;
        }
    }
    let hi = h_index[f];
    if hi != NO_H {
        let hb = 16u * config.num_faces + 16u * hi;
        for (var s = 0u; s < 16u; s++) {
            let ij = h_slot(s);
            let i = ij / 6u;
            let j = ij % 6u;
            let x = pd(hb + s);
            r.p += (bu.b5[i] * bv.b5[j]) * x;
            r.du += (bu.d5[i] * bv.b5[j]) * x;
            r.dv += (bu.b5[i] * bv.d5[j]) * x;
        }
    }
    r.p += x0;
    return r;
}

fn emit(item: u32, p: vec3<f32>, nrm: vec3<f32>) {
    let o = config.out_shift + 6u * item;
    out_vertices[o] = p.x;
    out_vertices[o + 1u] = p.y;
    out_vertices[o + 2u] = p.z;
    out_vertices[o + 3u] = nrm.x;
    out_vertices[o + 4u] = nrm.y;
    out_vertices[o + 5u] = nrm.z;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.y * config.grid_width + gid.x;
    if local >= config.item_count {
        return;
    }
    let item = config.first_item + local;
    let n = config.samples;
    let m = n - 2u;
    let nv = config.owned_vertices;
    let ne = config.num_edges;
    if item < nv {
        let e1 = vd(config.num_vertices + item);
        let e2 = vd(2u * config.num_vertices + item);
        emit(local, vd(item), normalized(cross(e1, e2)));
        return;
    }
    if item < nv + ne * m {
        let e = (item - nv) / m;
        let s = (item - nv) % m + 1u;
        let corner = edge_corner[e];
        let f = corner / 4u;
        let c = corner % 4u;
        var b = basis(params[s]);
        var p = vec3<f32>(0.0);
        for (var i = 0u; i < 4u; i++) {
            p = p + b.b3[i] * pd(16u * f + corner_index(c, i, 0u, 3u));
        }
        let hi = h_index[f];
        if hi != NO_H {
            let hb = 16u * config.num_faces + 16u * hi;
            p = p + b.b5[2] * pd(hb + 4u * c);
            p = p + b.b5[3] * pd(hb + 4u * c + 1u);
        }
        let uv = corner_index(c, s, 0u, n - 1u);
        let smp = eval_patch(f, basis(params[uv / n]), basis(params[uv % n]));
        emit(local, p, normalized(cross(smp.du, smp.dv)));
        return;
    }
    let q = item - nv - ne * m;
    let f = q / (m * m);
    let r = q % (m * m);
    let j = r / m + 1u;
    let i = r % m + 1u;
    let smp = eval_patch(f, basis(params[i]), basis(params[j]));
    emit(local, smp.p, normalized(cross(smp.du, smp.dv)));
}

// Slot in the vertex buffer of grid sample (i, j) of face f.
fn grid_vertex(f: u32, i: u32, j: u32) -> u32 {
    let n = config.samples;
    let last = n - 1u;
    let m = n - 2u;
    if i == 0u && j == 0u {
        return corner_slots[8u * f];
    }
    if i == last && j == 0u {
        return corner_slots[8u * f + 1u];
    }
    if i == last && j == last {
        return corner_slots[8u * f + 2u];
    }
    if i == 0u && j == last {
        return corner_slots[8u * f + 3u];
    }
    var c = 4u;
    var s = 0u;
    if j == 0u {
        c = 0u;
        s = i;
    } else if i == last {
        c = 1u;
        s = j;
    } else if j == last {
        c = 2u;
        s = last - i;
    } else if i == 0u {
        c = 3u;
        s = last - j;
    }
    if c < 4u {
        let w = corner_slots[8u * f + 4u + c];
        var k = m - s;
        if (w & 0x80000000u) != 0u {
            k = s - 1u;
        }
        return (w & 0x7fffffffu) + k;
    }
    return config.face_slot_base + f * m * m + (j - 1u) * m + (i - 1u);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn indices(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.y * config.grid_width + gid.x;
    if local >= config.item_count {
        return;
    }
    let item = config.first_item + local;
    let cells = config.samples - 1u;
    let f = item / (cells * cells);
    let r = item % (cells * cells);
    let j = r / cells;
    let i = r % cells;
    let a = grid_vertex(f, i, j);
    let b = grid_vertex(f, i + 1u, j);
    let c = grid_vertex(f, i + 1u, j + 1u);
    let d = grid_vertex(f, i, j + 1u);
    let o = config.out_shift + 6u * local;
    out_indices[o] = a;
    out_indices[o + 1u] = b;
    out_indices[o + 2u] = c;
    out_indices[o + 3u] = a;
    out_indices[o + 4u] = c;
    out_indices[o + 5u] = d;
}
