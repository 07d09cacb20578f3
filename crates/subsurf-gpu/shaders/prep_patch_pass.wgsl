// p-rep patch pass (Myles, Yeo & Peters 2008, §4; eqs. (8), (9)), one invocation per face
// (v0, v1, v2, v3) with sector numbers k_c:
//
// * g (16 per face): at corner c, local g00 = L(v_c), g10 = T(v_c, k_c), g01 = T(v_c, k_c+1),
//   g11 = I(v_c, k_c), stored through corner_index(c, i, j, 3);
// * h (16 per perturbed face, h_index != 0xffffffff): per corner c, [h20, h30, h21, h31] of
//   the edge v_c -> v_{c+1} (cases 1-4 by end valences; case 3 is case 2 with the ends
//   swapped), stored at 16 * h_index + 4 c + m.
//
// The weights are those of src/prep/patch_pass.rs in the subsurf crate, term for term.
// CPU twin: src/cpu/prep_patch_pass.rs.

const WORKGROUP_SIZE: u32 = 64u;
const NO_H: u32 = 0xffffffffu;

@group(0) @binding(0) var<uniform> config: PrepConfig;
@group(0) @binding(1) var<storage, read> face_verts: array<u32>;
@group(0) @binding(2) var<storage, read> corner_sector: array<u32>;
@group(0) @binding(3) var<storage, read> ring_offsets: array<u32>;
@group(0) @binding(4) var<storage, read> h_index: array<u32>;
@group(0) @binding(5) var<storage, read> valence_consts: array<f32>;
@group(0) @binding(6) var<storage, read> vertex_data: array<f32>;
@group(0) @binding(7) var<storage, read_write> patch_data: array<f32>;

fn vd(slot: u32) -> vec3<f32> {
    return vec3<f32>(vertex_data[3u * slot], vertex_data[3u * slot + 1u], vertex_data[3u * slot + 2u]);
}

fn store(slot: u32, x: vec3<f32>) {
    patch_data[3u * slot] = x.x;
    patch_data[3u * slot + 1u] = x.y;
    patch_data[3u * slot + 2u] = x.z;
}

fn valence(v: u32) -> u32 {
    return (ring_offsets[v + 1u] - ring_offsets[v]) / 2u;
}

fn limit(v: u32) -> vec3<f32> {
    return vd(v);
}

fn tangent(base: u32, x: u32, n: u32) -> vec3<f32> {
    return vd(3u * config.num_vertices + base + x % n);
}

fn interior(base: u32, x: u32, n: u32) -> vec3<f32> {
    return vd(3u * config.num_vertices + config.num_sectors + base + x % n);
}

// Case 2 end coefficient h20 = h30 (eq. 8) seen from the extraordinary end.
fn case2_end(c: f32, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, s: vec3<f32>) -> vec3<f32> {
    let k = 3.0 / 40.0;
    var acc = vec3<f32>(0.0);
    acc += (k * -2.0) * p0;
    acc += (k * (6.0 - 6.0 / c)) * p1;
    acc += (k * -4.0) * p2;
    acc += (k * (3.0 / c)) * s;
    return acc;
}

// Case 2 h21 (eq. 8), near the extraordinary end.
fn case2_near(c: f32, h: vec3<f32>, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>,
              sa: vec3<f32>, sb: vec3<f32>) -> vec3<f32> {
    let k = 3.0 / 100.0;
    let two_c = 2.0 * c;
    var acc = vec3<f32>(0.0);
    acc += (1.0 - two_c / 5.0) * h;
    acc += (k * two_c) * p0;
    acc += (k * (12.0 - 6.0 * c)) * p1;
    acc += (k * (6.0 + two_c)) * p2;
    acc += (k * two_c) * p3;
    acc += (k * -6.0) * sa;
    acc += (k * -3.0) * sb;
    return acc;
}

// Case 2 symmetric h31 (from eq. 15), near the valence-4 end.
fn case2_far(c: f32, h: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>,
             sa: vec3<f32>, sb: vec3<f32>, tb: vec3<f32>) -> vec3<f32> {
    let k = 3.0 / 100.0;
    let two_c = 2.0 * c;
    var acc = vec3<f32>(0.0);
    acc += 1.0 * h;
    acc += (k * 6.0) * p1;
    acc += (k * (12.0 - two_c)) * p2;
    acc += (k * (2.0 + two_c)) * p3;
    acc += (k * -3.0) * sa;
    acc += (k * -6.0) * sb;
    acc += (-k) * tb;
    return acc;
}

// Case 4 end coefficient (eq. 9).
fn case4_end(ca: f32, cb: f32, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, s: vec3<f32>) -> vec3<f32> {
    let k = 3.0 / 40.0;
    let two_cb = 2.0 * cb;
    var acc = vec3<f32>(0.0);
    acc += (k * (-(two_cb / ca))) * p0;
    acc += (k * (4.0 + (two_cb - 6.0) / ca)) * p1;
    acc += (k * -4.0) * p2;
    acc += (k * (3.0 / ca)) * s;
    return acc;
}

// Case 4 h21 (eq. 9).
fn case4_inner(ca: f32, cb: f32, ha: vec3<f32>, hb: vec3<f32>, p0: vec3<f32>, p1: vec3<f32>,
               p2: vec3<f32>, p3: vec3<f32>, sa: vec3<f32>, sb: vec3<f32>) -> vec3<f32> {
    let k = 3.0 / 100.0;
    var acc = vec3<f32>(0.0);
    acc += ((1.0 - 3.0 * ca / 5.0) - 2.0 * cb / 5.0) * ha;
    acc += (3.0 * ca / 5.0) * hb;
    acc += (k * (4.0 * cb)) * p0;
    acc += (k * (12.0 - 8.0 * ca)) * p1;
    acc += (k * ((6.0 + 6.0 * ca) - 4.0 * cb)) * p2;
    acc += (k * (2.0 * ca)) * p3;
    acc += (k * -6.0) * sa;
    acc += (k * -3.0) * sb;
    return acc;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let local = gid.y * config.grid_width + gid.x;
    if local >= config.item_count {
        return;
    }
    let f = config.first_item + local;
    for (var c = 0u; c < 4u; c++) {
        let v = face_verts[4u * f + c];
        let k = corner_sector[4u * f + c];
        let n = valence(v);
        let base = ring_offsets[v] / 2u;
        store(16u * f + corner_index(c, 0u, 0u, 3u), limit(v));
        store(16u * f + corner_index(c, 1u, 0u, 3u), tangent(base, k, n));
        store(16u * f + corner_index(c, 0u, 1u, 3u), tangent(base, k + 1u, n));
        store(16u * f + corner_index(c, 1u, 1u, 3u), interior(base, k, n));
    }
    let hi = h_index[f];
    if hi == NO_H {
        return;
    }
    let hb = 16u * config.num_faces + 16u * hi;
    for (var c = 0u; c < 4u; c++) {
        let v0 = face_verts[4u * f + c];
        let v1 = face_verts[4u * f + (c + 1u) % 4u];
        let n0 = valence(v0);
        let n1 = valence(v1);
        let k = corner_sector[4u * f + c];
        let m = corner_sector[4u * f + (c + 1u) % 4u];
        let b0 = ring_offsets[v0] / 2u;
        let b1 = ring_offsets[v1] / 2u;
        let g00 = limit(v0);
        let g10 = tangent(b0, k, n0);
        let g20 = tangent(b1, m + 1u, n1);
        let g30 = limit(v1);
        let g01 = tangent(b0, k + 1u, n0);
        let g11 = interior(b0, k, n0);
        let g21 = interior(b1, m, n1);
        let g31 = tangent(b1, m, n1);
        let gs10 = tangent(b0, k + n0 - 1u, n0);
        let gs11 = interior(b0, k + n0 - 1u, n0);
        let gs12 = interior(b1, m + 1u, n1);
        let gs13 = tangent(b1, m + 2u, n1);
        let c0 = valence_consts[valence_base(n0)];
        let c1 = valence_consts[valence_base(n1)];
        let s0 = g11 + gs11;
        let s1 = g21 + gs12;
        var h20 = vec3<f32>(0.0);
        var h30 = vec3<f32>(0.0);
        var h21 = vec3<f32>(0.0);
        var h31 = vec3<f32>(0.0);
        if n0 != 4u && n1 == 4u {
            let h = case2_end(c0, g00, g10, g20, s0);
            let t1 = g31 + gs13;
            h20 = h;
            h30 = h;
            h21 = case2_near(c0, h, g00, g10, g20, g30, s0, s1);
            h31 = case2_far(c0, h, g10, g20, g30, s0, s1, t1);
        } else if n0 == 4u && n1 != 4u {
            let h = case2_end(c1, g30, g20, g10, s1);
            let t0 = g01 + gs10;
            h20 = h;
            h30 = h;
            h31 = case2_near(c1, h, g30, g20, g10, g00, s1, s0);
            h21 = case2_far(c1, h, g20, g10, g00, s1, s0, t0);
        } else if n0 != 4u && n1 != 4u {
            h20 = case4_end(c0, c1, g00, g10, g20, s0);
            h30 = case4_end(c1, c0, g30, g20, g10, s1);
            h21 = case4_inner(c0, c1, h20, h30, g00, g10, g20, g30, s0, s1);
            h31 = case4_inner(c1, c0, h30, h20, g30, g20, g10, g00, s1, s0);
        }
        store(hb + 4u * c, h20);
        store(hb + 4u * c + 1u, h30);
        store(hb + 4u * c + 2u, h21);
        store(hb + 4u * c + 3u, h31);
    }
}
