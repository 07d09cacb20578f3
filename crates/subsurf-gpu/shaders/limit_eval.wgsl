// Evaluates the Catmull-Clark limit surface at a list of (ptex face, u, v) samples from a
// patch table (subsurf::limit::PatchTable), one invocation per sample:
//
//   patch  = patch_map walk of (ptex, u, v)                (OpenSubdiv Far::PatchMap)
//   (s, t) = (u 2^l - U, v 2^l - V),  l = depth - non_quad  (PatchParam::normalize)
//   P      = x0 + sum_k w_k(s, t) (points[cvs[k]] - x0),  x0 = points[cvs[0]];
//            dP/du, dP/dv likewise (without x0) with weights scaled by 2^l
//   n      = (dP/du x dP/dv) / |...|, or the same a little inside the face where it vanishes
//
// Bases: regular bicubic B-spline with boundary phantom points folded into the weights;
// single-crease B-spline (Niessner, Loop & Greiner 2012) in the f32-stable "local parameter,
// forward matrices" form of crates/subsurf/src/patch/single_crease.rs; 20-point Gregory end
// caps (Loop, Schaefer, Ni & Castano 2009) with OpenSubdiv's Bezier-approximation
// derivatives. Every expression is written in the operation order of the library, so the CPU
// twin (src/cpu/limit_eval.rs) reproduces LimitSurface::eval bit for bit; the GPU differs
// only by fused multiply-adds and its division and square root.
//
// Layouts (32-bit words):
//   queries     3 per sample: ptex, bits of u, bits of v       (bound at the chunk's first)
//   patch_map   [roots (num_roots) | 4 per inner node]: handles EMPTY, LEAF | patch, node
//   patch_info  5 per patch: kind, first cv, PatchParam field0, field1, bits of sharpness
//   cvs         control point indices into `points`
//   points      3 floats per point: every refinement level, then the end-cap local points
//   out         out_stride floats per sample: p, n (, du, dv)  (bound at the chunk's first)

const WORKGROUP_SIZE: u32 = 64u;
const EMPTY: u32 = 0xffffffffu;
const LEAF: u32 = 0x80000000u;
const KIND_REGULAR: u32 = 0u;
const KIND_SINGLE_CREASE: u32 = 1u;
const PATCH_WORDS: u32 = 5u;
const SHARPNESS_INFINITE: f32 = 10.0;
const ONE6: f32 = 1.0 / 6.0;
const EIGHTH: f32 = 0.125;
const F32_MAX: f32 = 3.40282347e38;

@group(0) @binding(0) var<uniform> config: LimitConfig;
@group(0) @binding(1) var<storage, read> queries: array<u32>;
@group(0) @binding(2) var<storage, read> patch_map: array<u32>;
@group(0) @binding(3) var<storage, read> patch_info: array<u32>;
@group(0) @binding(4) var<storage, read> cvs: array<u32>;
@group(0) @binding(5) var<storage, read> points: array<f32>;
@group(0) @binding(6) var<storage, read_write> out: array<f32>;

// Weights of one cubic segment: positions p and first derivatives d.
struct Curve {
    p: vec4<f32>,
    d: vec4<f32>,
}

// 2^k exactly (no exp2, whose precision WGSL leaves open).
fn pow2(k: i32) -> f32 {
    return bitcast<f32>(u32(clamp(k + 127, 0, 254)) << 23u);
}

fn bspline_curve(t: f32) -> Curve {
    let t2 = t * t;
    let t3 = t2 * t;
    let s = 1.0 - t;
    var c: Curve;
    c.p = vec4<f32>(ONE6 * s * s * s, ONE6 * (4.0 - 6.0 * t2 + 3.0 * t3),
                    ONE6 * (1.0 + 3.0 * (t + t2 - t3)), ONE6 * t3);
    c.d = vec4<f32>(-0.5 * s * s, 1.5 * t2 - 2.0 * t, -1.5 * t2 + t + 0.5, 0.5 * t2);
    return c;
}

// Phantom first point P0 = 2 P1 - P2 folded into the weights.
fn fold_low(w: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(0.0, w.y + (w.x + w.x), w.z - w.x, w.w);
}

// Phantom last point P3 = 2 P2 - P1 folded into the weights.
fn fold_high(w: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(w.x, w.y - w.w, w.z + (w.w + w.w), 0.0);
}

fn bounded(t: f32, low: bool, high: bool) -> Curve {
    var c = bspline_curve(t);
    if low {
        c.p = fold_low(c.p);
        c.d = fold_low(c.d);
    }
    if high {
        c.p = fold_high(c.p);
        c.d = fold_high(c.d);
    }
    return c;
}

fn bezier_curve(t: f32) -> Curve {
    let s = 1.0 - t;
    let t2 = t * t;
    let s2 = s * s;
    var c: Curve;
    c.p = vec4<f32>(s2 * s, 3.0 * t * s2, 3.0 * t2 * s, t2 * t);
    c.d = vec4<f32>(-3.0 * s2, 3.0 * s2 - 6.0 * t * s, 6.0 * t * s - 3.0 * t2, 3.0 * t2);
    return c;
}

// Columns 0, 1, 3 of x L for the middle part, L = RL [(1-phi) I + phi M_inf].
fn crease_middle(x: vec4<f32>, q: f32) -> vec3<f32> {
    return vec3<f32>(EIGHTH * (4.0 * x.x + x.y),
                     EIGHTH * (4.0 * x.x + 6.0 * x.y + 4.0 * x.z + q * x.w),
                     EIGHTH * q * x.w);
}

// Columns 0, 1, 3 of x L for the last part, L = (1-phi) R + phi Rp.
fn crease_last(x: vec4<f32>, q: f32) -> vec3<f32> {
    return vec3<f32>(EIGHTH * x.x, EIGHTH * (6.0 * x.x + 4.0 * x.y + q * x.z),
                     EIGHTH * (q * x.z + 4.0 * x.w));
}

// w = e2 sum + a1 (c A) + a3 (c B) with Rp^m = J + a1 A + a3 B.
fn crease_apply(c: vec3<f32>, a1: f32, a3: f32, sum: f32) -> vec4<f32> {
    let e = c.x + c.x + c.y;
    return vec4<f32>(a3 * c.x, a1 * e - 2.0 * a3 * c.x, sum - a1 * (e + c.z) + a3 * c.x, a1 * c.z);
}

// Segment with a crease of sharpness 0 < s < 10 at its t = 1 end; d = 1 - t.
fn crease_curve(t: f32, d: f32, s: f32) -> Curve {
    let m_real = floor(s);
    let m = i32(m_real);
    let phi = s - m_real;
    if d >= pow2(-m) {
        return bounded(t, false, true);
    }
    var kexp = m + 1;
    var cp: vec3<f32>;
    var cd: vec3<f32>;
    let q = 1.0 - phi;
    if phi == 0.0 {
        let n = bspline_curve(1.0 - pow2(m) * d);
        kexp = m;
        cp = vec3<f32>(n.p.x, n.p.y, n.p.w);
        cd = vec3<f32>(n.d.x, n.d.y, n.d.w);
    } else if d >= pow2(-(m + 1)) {
        let n = bspline_curve(2.0 - pow2(m + 1) * d);
        cp = crease_middle(n.p, q);
        cd = crease_middle(n.d, q);
    } else {
        let n = bspline_curve(1.0 - pow2(m + 1) * d);
        cp = crease_last(n.p, q);
        cd = crease_last(n.d, q);
    }
    var c: Curve;
    c.p = crease_apply(cp, pow2(-m), pow2(-3 * m), 1.0);
    c.d = crease_apply(cd, pow2(kexp - m), pow2(kexp - 3 * m), 0.0);
    return c;
}

fn reversed(c: Curve) -> Curve {
    var r: Curve;
    r.p = c.p.wzyx;
    r.d = -c.d.wzyx;
    return r;
}

fn point(k: u32) -> vec3<f32> {
    let i = 3u * cvs[k];
    return vec3<f32>(points[i], points[i + 1u], points[i + 2u]);
}

struct Eval {
    p: vec3<f32>,
    du: vec3<f32>,
    dv: vec3<f32>,
    found: bool,
}

// Rational weight of the f+ point of corner k (0 where the denominator vanishes).
fn gregory_rational(k: u32, u: f32, v: f32) -> f32 {
    var n = u;
    var d = u + v;
    if k == 1u {
        n = v;
        d = 1.0 - u + v;
    } else if k == 2u {
        n = 1.0 - u;
        d = (1.0 - u) + (1.0 - v);
    } else if k == 3u {
        n = 1.0 - v;
        d = u + (1.0 - v);
    }
    if d <= 0.0 {
        return 0.0;
    }
    return n / d;
}

// Bezier (column, row) of Gregory point k = 5 c + r: r < 3 boundary points, r = 3 f+,
// r = 4 f- (see crates/subsurf/src/patch/gregory.rs for the figure), 2 bits per point:
// points 0..16 in the _LO words, 16..20 in the _HI words (no per-invocation arrays).
const GREGORY_I_LO: u32 = 0x2bbabd44u;
const GREGORY_I_HI: u32 = 0x54u;
const GREGORY_J_LO: u32 = 0xeaf51150u;
const GREGORY_J_HI: u32 = 0xaeu;

fn two_bits(lo: u32, hi: u32, k: u32) -> u32 {
    return (select(hi, lo, k < 16u) >> (2u * (k % 16u))) & 3u;
}

// One gather for every kind. Tensor-product patches: point k = 4 j + i has weight
// wu[i] wv[j]. Gregory patches (wu, wv Bezier): point k has the Bezier weight of its slot
// (i, j), times g or 1 - g for the face points f+ and f- of corner k / 5 (weights held
// constant in the derivatives: OpenSubdiv's Bezier approximation). Products are formed in
// the library's order; the factor 1 of the other points is exact.
fn gather(first: u32, gregory: bool, wu: Curve, wv: Curve, g: vec4<f32>, scale: f32) -> Eval {
    var r: Eval;
    r.p = vec3<f32>(0.0);
    r.du = vec3<f32>(0.0);
    r.dv = vec3<f32>(0.0);
    r.found = true;
    let count = select(16u, 20u, gregory);
    // Relative to the first control point: the weights sum to 1 (derivatives: 0), and the
    // rounding is then of the patch's size, not of its distance from the origin.
    let x0 = point(first);
    for (var k = 0u; k < count; k++) {
        var i = k % 4u;
        var j = k / 4u;
        var gk = 1.0;
        if gregory {
            i = two_bits(GREGORY_I_LO, GREGORY_I_HI, k);
            j = two_bits(GREGORY_J_LO, GREGORY_J_HI, k);
            let slot = k % 5u;
            if slot == 3u {
                gk = g[k / 5u];
            } else if slot == 4u {
                gk = 1.0 - g[k / 5u];
            }
        }
        let x = point(first + k) - x0;
        r.p += (wu.p[i] * wv.p[j] * gk) * x;
        r.du += (wu.d[i] * gk * wv.p[j] * scale) * x;
        r.dv += (wv.d[j] * gk * wu.p[i] * scale) * x;
    }
    r.p += x0;
    return r;
}

// The patch covering (u, v) of ptex face `ptex` (clamped parameters), or EMPTY.
fn find_patch(ptex: u32, u0: f32, v0: f32) -> u32 {
    if ptex >= config.num_roots {
        return EMPTY;
    }
    var h = patch_map[ptex];
    var u = u0;
    var v = v0;
    loop {
        if h == EMPTY {
            return EMPTY;
        }
        if (h & LEAF) != 0u {
            return h & ~LEAF;
        }
        let hi_u = u >= 0.5;
        let hi_v = v >= 0.5;
        var q = 0u;
        if hi_u && hi_v {
            q = 2u;
        } else if hi_u {
            q = 1u;
        } else if hi_v {
            q = 3u;
        }
        u = 2.0 * u - select(0.0, 1.0, hi_u);
        v = 2.0 * v - select(0.0, 1.0, hi_v);
        h = patch_map[config.num_roots + 4u * h + q];
    }
    return EMPTY;
}

// Position and ptex-face derivatives at (u, v) of ptex face `ptex` (LimitSurface::eval_raw).
fn eval_raw(ptex: u32, u0: f32, v0: f32) -> Eval {
    let u = clamp(u0, 0.0, 1.0);
    let v = clamp(v0, 0.0, 1.0);
    var r: Eval;
    r.p = vec3<f32>(0.0);
    r.du = vec3<f32>(0.0);
    r.dv = vec3<f32>(0.0);
    r.found = false;
    let found = find_patch(ptex, u, v);
    if found == EMPTY {
        return r;
    }
    let base = PATCH_WORDS * found;
    let kind = patch_info[base];
    let first = patch_info[base + 1u];
    let field1 = patch_info[base + 3u];
    let sharpness = bitcast<f32>(patch_info[base + 4u]);
    let depth = i32(field1 & 0xfu);
    let non_quad = i32((field1 >> 4u) & 1u);
    let boundary = (field1 >> 7u) & 0x1fu;
    let pv = f32((field1 >> 12u) & 0x3ffu);
    let pu = f32((field1 >> 22u) & 0x3ffu);
    let level = max(depth - non_quad, 0);
    let scale = pow2(level);
    let s = u * scale - pu;
    let t = v * scale - pv;
    if kind != KIND_REGULAR && kind != KIND_SINGLE_CREASE {
        let g = vec4<f32>(gregory_rational(0u, s, t), gregory_rational(1u, s, t),
                          gregory_rational(2u, s, t), gregory_rational(3u, s, t));
        return gather(first, true, bezier_curve(s), bezier_curve(t), g, scale);
    }
    // B-spline kinds: the boundary mask folds phantom points, a single crease
    // (0 < sharpness < 10) replaces the curve across its edge, an infinitely sharp one is a
    // boundary, a smooth one nothing.
    var mask = boundary;
    var crease_edge = 4u;
    if kind == KIND_SINGLE_CREASE {
        let bits = boundary & 0xfu;
        mask = 0u;
        if bits != 0u && sharpness > 0.0 {
            let edge = countTrailingZeros(bits);
            if sharpness >= SHARPNESS_INFINITE {
                mask = 1u << edge;
            } else {
                crease_edge = edge;
            }
        }
    }
    var wu = bounded(s, (mask & 8u) != 0u, (mask & 2u) != 0u);
    var wv = bounded(t, (mask & 1u) != 0u, (mask & 4u) != 0u);
    if crease_edge < 4u {
        // Edges 1 (u = 1) and 3 (u = 0) crease the u curve, 2 (v = 1) and 0 (v = 0) the v
        // curve; at the 0 end the curve is evaluated reversed at 1 - x.
        let along_u = crease_edge == 1u || crease_edge == 3u;
        let high = crease_edge == 1u || crease_edge == 2u;
        let x = select(t, s, along_u);
        var c = crease_curve(select(1.0 - x, x, high), select(x, 1.0 - x, high), sharpness);
        if !high {
            c = reversed(c);
        }
        if along_u {
            wu = c;
        } else {
            wv = c;
        }
    }
    return gather(first, false, wu, wv, vec4<f32>(0.0), scale);
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

fn is_zero(a: vec3<f32>) -> bool {
    return a.x == 0.0 && a.y == 0.0 && a.z == 0.0;
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let item = gid.y * config.grid_width + gid.x;
    if item >= config.item_count {
        return;
    }
    let ptex = queries[3u * item];
    let u = clamp(bitcast<f32>(queries[3u * item + 1u]), 0.0, 1.0);
    let v = clamp(bitcast<f32>(queries[3u * item + 2u]), 0.0, 1.0);
    let r = eval_raw(ptex, u, v);
    var n = vec3<f32>(0.0);
    if r.found {
        n = unit(cross3(r.du, r.dv));
        if is_zero(n) {
            // Step a little towards the face centre, where the tangent plane is regular.
            let q = eval_raw(ptex, u + (0.5 - u) * 1e-3, v + (0.5 - v) * 1e-3);
            if q.found {
                n = unit(cross3(q.du, q.dv));
            }
        }
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
