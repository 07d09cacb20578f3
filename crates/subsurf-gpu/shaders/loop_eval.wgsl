// Evaluates the Loop limit surface (subsurf::limit::loop_eval::LoopLimit) at a list of
// (patch, u, v) samples, one invocation per sample; the patch of each sample is found on
// the host, (u, v) are its base face's:
//
//   (s, t) = (u 2^d - U, v 2^d - V), or ((2^d - U) - u 2^d, (2^d - V) - v 2^d) for a
//            rotated patch (U + V >= 2^d)                       (PatchParam::normalize_triangle)
//   P      = x0 + sum_k w_k(s, t) (points[first + k] - x0),  x0 = corner 0 of the patch;
//            dP/du, dP/dv likewise (without x0) with weights scaled by +-2^d
//   n      = (dP/du x dP/dv) / |...|, or zero where it vanishes
//
// Bases: the quartic box spline over 12 points (Stam 1998) from its 15 monomials, with the
// phantom points of OpenSubdiv's boundary and corner variants folded into the weights; the
// quartic Gregory triangle over 18 points (Bernstein weights, the rational blend of the face
// points held constant in the derivatives). Every expression is written in the operation
// order of crates/subsurf/src/patch/{box_spline,gregory_tri,tri_basis}.rs, so the CPU twin
// (src/cpu/loop_eval.rs) reproduces the library's f32 weights bit for bit; the GPU differs
// only by fused multiply-adds and its division and square root.
//
// Layouts (32-bit words):
//   queries     3 per sample: patch (0xffffffff: none), bits of u, bits of v
//                                                              (bound at the chunk's first)
//   patch_info  4 per patch: kind (0 box spline, 1 Gregory triangle), first point,
//               PatchParam field0, field1
//   points      3 floats per point: 12 (box spline) or 18 (Gregory triangle) per patch
//   out         out_stride floats per sample: p, n (, du, dv)  (bound at the chunk's first)

const WORKGROUP_SIZE: u32 = 64u;
const KIND_BOX_SPLINE: u32 = 0u;
const PATCH_WORDS: u32 = 4u;
const F32_MAX: f32 = 3.40282347e38;
// 1/12 rounded to f32.
const TWELFTH: f32 = 0.083333336;

@group(0) @binding(0) var<uniform> config: LoopConfig;
@group(0) @binding(1) var<storage, read> queries: array<u32>;
@group(0) @binding(2) var<storage, read> patch_info: array<u32>;
@group(0) @binding(3) var<storage, read> points: array<f32>;
@group(0) @binding(4) var<storage, read_write> out: array<f32>;

// The tables are private-address-space arrays (initialised once per invocation), not
// consts: a const array indexed by a runtime value is rebuilt at every access, which made
// the kernel about 20 times slower on lavapipe.
//
// Stam's coefficients (times 12): row i (point i) is entries 15 i .. 15 i + 15, over the
// monomials 1, s, t, s^2, st, t^2, s^3, s^2 t, s t^2, t^3, s^4, s^3 t, s^2 t^2, s t^3, t^4.
var<private> BOX_COEFFS: array<i32, 180> = array<i32, 180>(
    1, -2, -4, 0, 6, 6, 2, 0, -6, -4, -1, -2, 0, 2, 1,
    1, 2, -2, 0, -6, 0, -4, 0, 6, 2, 2, 4, 0, -2, -1,
    0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -1, -2, 0, 0, 0,
    1, -4, -2, 6, 6, 0, -4, -6, 0, 2, 1, 2, 0, -2, -1,
    6, 0, 0, -12, -12, -12, 8, 12, 12, 8, -1, -2, 0, -2, -1,
    1, 4, 2, 6, 6, 0, -4, -6, -12, -4, -1, -2, 0, 4, 2,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0,
    1, -2, 2, 0, -6, 0, 2, 6, 0, -4, -1, -2, 0, 4, 2,
    1, 2, 4, 0, 6, 6, -4, -12, -6, -4, 2, 4, 0, -2, -1,
    0, 0, 0, 0, 0, 0, 2, 6, 6, 2, -1, -2, 0, -2, -1,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -2, -1,
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1,
);

// Exponents (a, b) of monomial m = s^a t^b.
var<private> MONO_A: array<u32, 15> = array<u32, 15>(0u, 1u, 0u, 2u, 1u, 0u, 3u, 2u, 1u, 0u, 4u, 3u, 2u, 1u, 0u);
var<private> MONO_B: array<u32, 15> = array<u32, 15>(0u, 0u, 1u, 0u, 1u, 2u, 0u, 1u, 2u, 3u, 0u, 1u, 2u, 3u, 4u);

// The rotation of the 12 points taking corner k to corner k + 1.
var<private> ROTATE: array<u32, 12> = array<u32, 12>(6u, 9u, 11u, 2u, 5u, 8u, 10u, 1u, 4u, 7u, 0u, 3u);

// Phantom rules P[x] = P[y] + P[z] - P[w] of edge 0 (first point without / with edge 2 on
// the boundary, middle, last without / with edge 1 on the boundary) and corner 0 (two).
var<private> PHANTOMS: array<vec4<u32>, 7> = array<vec4<u32>, 7>(
    vec4<u32>(0u, 4u, 3u, 7u),
    vec4<u32>(0u, 4u, 4u, 8u),
    vec4<u32>(1u, 4u, 5u, 8u),
    vec4<u32>(2u, 5u, 6u, 9u),
    vec4<u32>(2u, 5u, 5u, 8u),
    vec4<u32>(3u, 4u, 7u, 8u),
    vec4<u32>(0u, 4u, 1u, 5u),
);

// Per Gregory point: the Bezier point whose weight it takes, and the blend factor that
// multiplies it (6: none).
var<private> GREGORY_BEZIER: array<u32, 18> = array<u32, 18>(0u, 1u, 5u, 6u, 6u, 4u, 8u, 3u, 7u, 7u, 14u, 12u,
                                      13u, 10u, 10u, 2u, 11u, 9u);
var<private> GREGORY_BLEND: array<u32, 18> = array<u32, 18>(6u, 6u, 6u, 0u, 1u, 6u, 6u, 6u, 2u, 3u, 6u, 6u,
                                     6u, 4u, 5u, 6u, 6u, 6u);

// 2^k exactly (no exp2, whose precision WGSL leaves open).
fn pow2(k: i32) -> f32 {
    return bitcast<f32>(u32(clamp(k + 127, 0, 254)) << 23u);
}

// x^n as a product from 1.
fn pown(x: f32, n: u32) -> f32 {
    var r = 1.0;
    for (var i = 0u; i < n; i++) {
        r = r * x;
    }
    return r;
}

// n (n - 1) ... (n - k + 1).
fn falling(n: u32, k: u32) -> f32 {
    var r = 1.0;
    for (var i = 0u; i < k; i++) {
        r = r * f32(n - i);
    }
    return r;
}

fn monomial(m: u32, s: f32, t: f32, ds: u32, dt: u32) -> f32 {
    let a = MONO_A[m];
    let b = MONO_B[m];
    if a < ds || b < dt {
        return 0.0;
    }
    return falling(a, ds) * falling(b, dt) * pown(s, a - ds) * pown(t, b - dt);
}

fn rotated(i: u32, k: u32) -> u32 {
    var r = i;
    for (var n = 0u; n < k; n++) {
        r = ROTATE[r];
    }
    return r;
}

fn fold(w: ptr<function, array<f32, 18>>, rule: u32, k: u32) {
    let r = PHANTOMS[rule];
    let p = rotated(r.x, k);
    let a = rotated(r.y, k);
    let b = rotated(r.z, k);
    let c = rotated(r.w, k);
    let x = (*w)[p];
    (*w)[p] = 0.0;
    (*w)[a] = (*w)[a] + x;
    (*w)[b] = (*w)[b] + x;
    (*w)[c] = (*w)[c] - x;
}

fn on(bits: u32, k: u32) -> bool {
    return (bits & (1u << (k % 3u))) != 0u;
}

fn fold_boundary(w: ptr<function, array<f32, 18>>, mask: u32) {
    let low = mask & 7u;
    let kind = (mask >> 3u) & 3u;
    var edges = low;
    var corners = 0u;
    if kind == 1u {
        edges = 0u;
        corners = low;
    } else if kind == 2u {
        corners = ((low & 1u) << 2u) | (low >> 1u);
    }
    for (var k = 0u; k < 3u; k++) {
        if on(edges, k) {
            fold(w, select(0u, 1u, on(edges, k + 2u)), k);
            fold(w, 2u, k);
            fold(w, select(3u, 4u, on(edges, k + 1u)), k);
        }
    }
    for (var k = 0u; k < 3u; k++) {
        if on(corners, k) {
            fold(w, 5u, k);
            fold(w, 6u, k);
        }
    }
}

// Weights of the points: position and the two first derivatives.
struct Weights {
    p: array<f32, 18>,
    du: array<f32, 18>,
    dv: array<f32, 18>,
}

// Box-spline weights at (s, t), boundary folded; the three sums share one pass over the
// coefficients (each is the library's sum, in its order).
fn box_spline_weights(s: f32, t: f32, mask: u32) -> Weights {
    var mp: array<f32, 15>;
    var mu: array<f32, 15>;
    var mv: array<f32, 15>;
    for (var k = 0u; k < 15u; k++) {
        mp[k] = monomial(k, s, t, 0u, 0u);
        mu[k] = monomial(k, s, t, 1u, 0u);
        mv[k] = monomial(k, s, t, 0u, 1u);
    }
    // Three arrays, not a Weights: naga 30's SPIR-V output fails on a pointer to a member.
    var wp: array<f32, 18>;
    var wu: array<f32, 18>;
    var wv: array<f32, 18>;
    for (var i = 0u; i < 12u; i++) {
        var ap = 0.0;
        var au = 0.0;
        var av = 0.0;
        for (var k = 0u; k < 15u; k++) {
            let c = BOX_COEFFS[15u * i + k];
            if c != 0 {
                let cf = f32(c);
                ap = ap + cf * mp[k];
                au = au + cf * mu[k];
                av = av + cf * mv[k];
            }
        }
        wp[i] = ap * TWELFTH;
        wu[i] = au * TWELFTH;
        wv[i] = av * TWELFTH;
    }
    if mask != 0u {
        fold_boundary(&wp, mask);
        fold_boundary(&wu, mask);
        fold_boundary(&wv, mask);
    }
    return Weights(wp, wu, wv);
}

// Exponents (i, j, k) of u^i v^j w^k of Bezier point n (rows of constant j).
fn bezier_exponents(n: u32) -> vec3<u32> {
    var r = n;
    for (var j = 0u; j < 5u; j++) {
        let row = 5u - j;
        if r < row {
            return vec3<u32>(r, j, 4u - r - j);
        }
        r -= row;
    }
    return vec3<u32>(0u, 4u, 0u);
}

fn partial(uvw: vec3<f32>, e: vec3<u32>, d: vec3<u32>) -> f32 {
    if d.x > e.x || d.y > e.y || d.z > e.z {
        return 0.0;
    }
    return falling(e.x, d.x) * falling(e.y, d.y) * falling(e.z, d.z)
        * pown(uvw.x, e.x - d.x) * pown(uvw.y, e.y - d.y) * pown(uvw.z, e.z - d.z);
}

fn factorial(n: u32) -> u32 {
    var r = 1u;
    for (var i = 2u; i <= n; i++) {
        r *= i;
    }
    return r;
}

// Weights of Bezier point n: position, d/ds = du - dw, d/dt = dv - dw. The library sums
// c * partial with c = +-1: exact, so a plain sum and difference.
fn bezier_weights(n: u32, uvw: vec3<f32>) -> vec3<f32> {
    let e = bezier_exponents(n);
    let multinomial = f32(24u / (factorial(e.x) * factorial(e.y) * factorial(e.z)));
    let dw = partial(uvw, e, vec3<u32>(0u, 0u, 1u));
    let p = 0.0 + partial(uvw, e, vec3<u32>(0u, 0u, 0u));
    let ds = (0.0 + partial(uvw, e, vec3<u32>(1u, 0u, 0u))) - dw;
    let dt = (0.0 + partial(uvw, e, vec3<u32>(0u, 1u, 0u))) - dw;
    return vec3<f32>(multinomial * p, multinomial * ds, multinomial * dt);
}

// (a / (a + b), b / (a + b)), or (1, 0) where a + b is not positive.
fn blend_pair(a: f32, b: f32) -> vec2<f32> {
    let d = a + b;
    if d > 0.0 {
        return vec2<f32>(a / d, b / d);
    }
    return vec2<f32>(1.0, 0.0);
}

fn gregory_weights(s: f32, t: f32, g: array<f32, 6>) -> Weights {
    let uvw = vec3<f32>(s, t, 1.0 - s - t);
    var b: array<vec3<f32>, 15>;
    for (var n = 0u; n < 15u; n++) {
        b[n] = bezier_weights(n, uvw);
    }
    var w: Weights;
    for (var k = 0u; k < 18u; k++) {
        var x = b[GREGORY_BEZIER[k]];
        let r = GREGORY_BLEND[k];
        if r < 6u {
            x = x * g[r];
        }
        w.p[k] = x.x;
        w.du[k] = x.y;
        w.dv[k] = x.z;
    }
    return w;
}

struct Eval {
    p: vec3<f32>,
    du: vec3<f32>,
    dv: vec3<f32>,
    found: bool,
}

fn point(k: u32) -> vec3<f32> {
    let i = 3u * k;
    return vec3<f32>(points[i], points[i + 1u], points[i + 2u]);
}

fn eval_raw(index: u32, u: f32, v: f32) -> Eval {
    var r: Eval;
    r.p = vec3<f32>(0.0);
    r.du = vec3<f32>(0.0);
    r.dv = vec3<f32>(0.0);
    r.found = false;
    if index >= config.num_patches {
        return r;
    }
    let base = PATCH_WORDS * index;
    let kind = patch_info[base];
    let first = patch_info[base + 1u];
    let field1 = patch_info[base + 3u];
    let depth = i32(field1 & 0xfu);
    let boundary = (field1 >> 7u) & 0x1fu;
    let iv = (field1 >> 12u) & 0x3ffu;
    let iu = (field1 >> 22u) & 0x3ffu;
    let pv = f32(iv);
    let pu = f32(iu);
    let is_rotated = iu + iv >= (1u << u32(depth));
    let scale = pow2(depth);
    var s = u * scale - pu;
    var t = v * scale - pv;
    if is_rotated {
        s = scale - pu - u * scale;
        t = scale - pv - v * scale;
    }
    var w: Weights;
    let regular = kind == KIND_BOX_SPLINE;
    if regular {
        w = box_spline_weights(s, t, boundary);
    } else {
        let c = 1.0 - s - t;
        let g0 = blend_pair(s, t);
        let g1 = blend_pair(t, c);
        let g2 = blend_pair(c, s);
        w = gregory_weights(s, t, array<f32, 6>(g0.x, g0.y, g1.x, g1.y, g2.x, g2.y));
    }
    let a = select(1.0, -1.0, is_rotated) * scale;
    let count = select(18u, 12u, regular);
    // Relative to corner 0 of the patch: the weights sum to 1 (derivatives: 0), and the
    // rounding is then of the patch's size, not of its distance from the origin.
    let x0 = point(first + select(0u, 4u, regular));
    for (var k = 0u; k < count; k++) {
        let x = point(first + k) - x0;
        r.p += w.p[k] * x;
        r.du += (w.du[k] * a) * x;
        r.dv += (w.dv[k] * a) * x;
    }
    r.p += x0;
    r.found = true;
    return r;
}

fn cross3(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

// a / |a|, or zero where |a| is not in (1e-30, inf).
fn unit(a: vec3<f32>) -> vec3<f32> {
    let l = sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    if l > 1e-30 && l <= F32_MAX {
        return vec3<f32>(a.x / l, a.y / l, a.z / l);
    }
    return vec3<f32>(0.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let item = gid.y * config.grid_width + gid.x;
    if item >= config.item_count {
        return;
    }
    let index = queries[3u * item];
    let u = bitcast<f32>(queries[3u * item + 1u]);
    let v = bitcast<f32>(queries[3u * item + 2u]);
    let r = eval_raw(index, u, v);
    var n = vec3<f32>(0.0);
    if r.found {
        n = unit(cross3(r.du, r.dv));
    }
    let o = config.out_stride * item;
    out[o] = r.p.x;
    out[o + 1u] = r.p.y;
    out[o + 2u] = r.p.z;
    out[o + 3u] = n.x;
    out[o + 4u] = n.y;
    out[o + 5u] = n.z;
    if config.out_stride >= 12u {
        out[o + 6u] = r.du.x;
        out[o + 7u] = r.du.y;
        out[o + 8u] = r.du.z;
        out[o + 9u] = r.dv.x;
        out[o + 10u] = r.dv.y;
        out[o + 11u] = r.dv.z;
    }
}
