//! CPU twin of `shaders/loop_eval.wgsl`: the Loop limit surface of a
//! [`subsurf::limit::LoopLimit`] at a list of `(patch, u, v)` samples.
//!
//! The patch of each sample is found on the host (the triangle patch map,
//! [`subsurf::limit::PatchMap::find_triangle`]); `(u, v)` are the base face's. For each
//! sample: the patch's [`PatchParam`](subsurf::patch::PatchParam) maps `(u, v)` to its own
//! `(s, t)` (upright `(u 2^d − U, v 2^d − V)`, rotated `((2^d − U) − u 2^d, …)`,
//! [`subsurf::patch::tri_patch_weights`]); the basis of the patch kind gives one weight per point,
//!
//! ```text
//! P = x_0 + Σ_k w_k(s, t) (x_k − x_0)        ∂P/∂u = ±2^d Σ_k ∂w_k/∂s (x_k − x_0)
//! ```
//!
//! (likewise `∂P/∂v`; negative for a rotated patch), relative to the patch's corner 0 `x_0`
//! (point 4 of a box spline, point 0 of a Gregory triangle), as
//! [`LoopLimit::eval`] does. The bases:
//!
//! - regular: the quartic box spline (Stam 1998) over 12 points, its 15 monomials times
//!   Stam's coefficients, phantom points of boundary edges and corners folded into the
//!   weights ([`subsurf::patch::BOX_SPLINE_COEFFS`]);
//! - end cap: the quartic Gregory triangle over 18 points, Bernstein weights with the
//!   rational blend of the face points held constant in the derivatives
//!   ([`subsurf::patch::gregory_triangle_weights`]).
//!
//! The weights are computed in f32 in the library's operation order, so [`patch_weights`]
//! reproduces `tri_patch_weights::<f32>` bit for bit. The library evaluates
//! [`LoopLimit::eval`] in f64 (points and weights): this twin, in f32 throughout, is within
//! a few f32 roundings of it. The GPU differs from the twin by fused multiply-adds and its
//! division and square root.
//!
//! The unit normal is `∂P/∂u × ∂P/∂v` normalised, zero where it vanishes (as
//! [`LoopLimit::tessellate`] writes it).

use crate::shared::LoopConfig;
use subsurf::limit::LoopLimit;
// Stam's coefficients (times 12) of the 12 box-spline basis functions, their monomials'
// exponents and the point rotation: the library's tables (`subsurf::patch::BOX_SPLINE_COEFFS`), which
// the WGSL kernel repeats as private arrays.
use subsurf::patch::{
    BOX_SPLINE_COEFFS as BOX_COEFFS, BOX_SPLINE_MONOMIALS as MONOMIALS, BOX_SPLINE_ROTATE as ROTATE,
};

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;
/// Words per patch in `patch_info`: kind, first point, `PatchParam` field0, field1.
pub const PATCH_WORDS: usize = 4;
/// Words per sample in `queries`: patch, bits of `u`, bits of `v`.
pub const QUERY_WORDS: usize = 3;
/// Patch kind of a regular box-spline patch (12 points).
pub const KIND_BOX_SPLINE: u32 = 0;
/// Patch kind of a Gregory-triangle end cap (18 points).
pub const KIND_GREGORY_TRIANGLE: u32 = 1;
/// The patch of a sample no patch holds: the sample evaluates to zeros.
pub const NO_PATCH: u32 = u32::MAX;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::LOOP_EVAL_WORKGROUP_SIZE);

/// `1/12` rounded to f32, the common factor of Stam's coefficients.
const TWELFTH: f32 = (1.0f64 / 12.0) as f32;

/// Phantom rules `P[r0] = P[r1] + P[r2] − P[r3]` of edge 0 and corner 0: edge 0's first
/// point without / with edge 2 on the boundary, its middle point, its last point without /
/// with edge 1 on the boundary, then corner 0's two points.
const PHANTOMS: [[u32; 4]; 7] = [
    [0, 4, 3, 7],
    [0, 4, 4, 8],
    [1, 4, 5, 8],
    [2, 5, 6, 9],
    [2, 5, 5, 8],
    [3, 4, 7, 8],
    [0, 4, 1, 5],
];

/// Per Gregory point: the Bézier point whose weight it takes.
const GREGORY_BEZIER: [u32; 18] = [0, 1, 5, 6, 6, 4, 8, 3, 7, 7, 14, 12, 13, 10, 10, 2, 11, 9];
/// Per Gregory point: the rational blend factor multiplying its weight (6: none).
const GREGORY_BLEND: [u32; 18] = [6, 6, 6, 0, 1, 6, 6, 6, 2, 3, 6, 6, 6, 4, 5, 6, 6, 6];

type V = [f32; 3];
/// Weights of up to 18 points (box splines use the first 12).
pub type W18 = [f32; 18];

/// The flat tables the kernel reads (bindings 2 and 3), built from a Loop limit surface.
#[derive(Debug, Clone)]
pub struct LoopTables {
    /// Number of patches.
    pub num_patches: u32,
    /// Binding 2: [`PATCH_WORDS`] per patch.
    pub patch_info: Vec<u32>,
    /// Binding 3: 3 floats per point, the points of patch after patch (12 or 18 each).
    pub points: Vec<f32>,
}

impl LoopTables {
    /// Flattens `limit`'s patches: kind, first point and parameter per patch, and their
    /// points rounded to f32.
    pub fn new(limit: &LoopLimit) -> Self {
        let mut patch_info = Vec::with_capacity(PATCH_WORDS * limit.patches.len());
        let mut points = Vec::new();
        for p in &limit.patches {
            let kind = if p.regular {
                KIND_BOX_SPLINE
            } else {
                KIND_GREGORY_TRIANGLE
            };
            patch_info.extend([
                kind,
                (points.len() / 3) as u32,
                p.param.field0,
                p.param.field1,
            ]);
            points.extend(p.points.iter().flatten().map(|&x| x as f32));
        }
        Self {
            num_patches: limit.patches.len() as u32,
            patch_info,
            points,
        }
    }
}

/// Read-only inputs of the kernel (bindings 1..=3 in order).
#[derive(Debug, Clone, Copy)]
pub struct LoopInputs<'a> {
    /// Binding 1: [`QUERY_WORDS`] per sample.
    pub queries: &'a [u32],
    /// Binding 2.
    pub patch_info: &'a [u32],
    /// Binding 3.
    pub points: &'a [f32],
}

fn pow2(k: i32) -> f32 {
    f32::from_bits(((k + 127).clamp(0, 254) as u32) << 23)
}

/// `x^n` as the library's fold from 1.
fn pow(x: f32, n: u32) -> f32 {
    let mut r = 1.0f32;
    for _ in 0..n {
        r *= x;
    }
    r
}

/// `n (n − 1) … (n − k + 1)`.
fn falling(n: u32, k: u32) -> f32 {
    let mut r = 1.0f32;
    for i in 0..k {
        r *= (n - i) as f32;
    }
    r
}

/// `∂^ds_s ∂^dt_t` of monomial `m` at `(s, t)`.
fn monomial(m: usize, s: f32, t: f32, ds: u32, dt: u32) -> f32 {
    let (a, b) = (u32::from(MONOMIALS[m].0), u32::from(MONOMIALS[m].1));
    if a < ds || b < dt {
        return 0.0;
    }
    falling(a, ds) * falling(b, dt) * pow(s, a - ds) * pow(t, b - dt)
}

fn rotated(i: u32, k: u32) -> u32 {
    let mut r = i;
    for _ in 0..k {
        r = ROTATE[r as usize] as u32;
    }
    r
}

/// Folds phantom rule `rule` turned `k` times into `w`.
fn fold(w: &mut W18, rule: usize, k: u32) {
    let [p, a, b, c] = PHANTOMS[rule].map(|i| rotated(i, k) as usize);
    let x = w[p];
    w[p] = 0.0;
    w[a] += x;
    w[b] += x;
    w[c] -= x;
}

/// Folds the phantoms of a 5-bit boundary mask ([`subsurf::patch::BOX_SPLINE_COEFFS`]).
fn fold_boundary(w: &mut W18, mask: u32) {
    let low = mask & 7;
    let (edges, corners) = match (mask >> 3) & 3 {
        1 => (0, low),
        2 => (low, ((low & 1) << 2) | (low >> 1)),
        _ => (low, 0),
    };
    let on = |bits: u32, k: u32| bits & (1 << (k % 3)) != 0;
    for k in 0..3 {
        if on(edges, k) {
            fold(w, on(edges, k + 2) as usize, k);
            fold(w, 2, k);
            fold(w, 3 + on(edges, k + 1) as usize, k);
        }
    }
    for k in 0..3 {
        if on(corners, k) {
            fold(w, 5, k);
            fold(w, 6, k);
        }
    }
}

/// Box-spline weights (position, `∂/∂s`, `∂/∂t`) at `(s, t)`, boundary folded; the three
/// sums share one pass over the coefficients (each is the library's sum, in its order).
fn box_spline_weights(s: f32, t: f32, mask: u32) -> [W18; 3] {
    let (mut mp, mut mu, mut mv) = ([0.0f32; 15], [0.0f32; 15], [0.0f32; 15]);
    for k in 0..15 {
        mp[k] = monomial(k, s, t, 0, 0);
        mu[k] = monomial(k, s, t, 1, 0);
        mv[k] = monomial(k, s, t, 0, 1);
    }
    let mut w = [[0.0f32; 18]; 3];
    for (i, row) in BOX_COEFFS.iter().enumerate() {
        let (mut ap, mut au, mut av) = (0.0f32, 0.0f32, 0.0f32);
        for (k, &c) in row.iter().enumerate() {
            if c != 0 {
                let cf = f32::from(c);
                ap += cf * mp[k];
                au += cf * mu[k];
                av += cf * mv[k];
            }
        }
        w[0][i] = ap * TWELFTH;
        w[1][i] = au * TWELFTH;
        w[2][i] = av * TWELFTH;
    }
    if mask != 0 {
        for x in &mut w {
            fold_boundary(x, mask);
        }
    }
    w
}

/// Exponents `(i, j, k)` of `uⁱ vʲ wᵏ` of Bézier point `n` (rows of constant `j`).
fn bezier_exponents(n: u32) -> [u32; 3] {
    let mut r = n;
    for j in 0..5 {
        let row = 5 - j;
        if r < row {
            return [r, j, 4 - r - j];
        }
        r -= row;
    }
    [0, 4, 0]
}

/// `∂^d0_u ∂^d1_v ∂^d2_w` of `uⁱ vʲ wᵏ`, `u, v, w` independent.
fn partial(uvw: V, e: [u32; 3], d: [u32; 3]) -> f32 {
    if d[0] > e[0] || d[1] > e[1] || d[2] > e[2] {
        return 0.0;
    }
    falling(e[0], d[0])
        * falling(e[1], d[1])
        * falling(e[2], d[2])
        * pow(uvw[0], e[0] - d[0])
        * pow(uvw[1], e[1] - d[1])
        * pow(uvw[2], e[2] - d[2])
}

fn factorial(n: u32) -> u32 {
    (1..=n).product()
}

/// Weights of Bézier point `n`: position, `∂/∂s = ∂u − ∂w`, `∂/∂t = ∂v − ∂w`. The library
/// sums `c · partial` with `c = ±1`: exact, so a plain sum and difference.
fn bezier_weights(n: u32, uvw: V) -> V {
    let e = bezier_exponents(n);
    let multinomial = (24 / (factorial(e[0]) * factorial(e[1]) * factorial(e[2]))) as f32;
    let dw = partial(uvw, e, [0, 0, 1]);
    let p = 0.0 + partial(uvw, e, [0, 0, 0]);
    let ds = (0.0 + partial(uvw, e, [1, 0, 0])) - dw;
    let dt = (0.0 + partial(uvw, e, [0, 1, 0])) - dw;
    [multinomial * p, multinomial * ds, multinomial * dt]
}

/// `u/(u+v), v/(u+v), v/(v+w), w/(v+w), w/(w+u), u/(w+u)`, a pair `(1, 0)` where its
/// denominator is not positive.
fn blend_factors(s: f32, t: f32) -> [f32; 6] {
    let (u, v, w) = (s, t, 1.0 - s - t);
    let pair = |a: f32, b: f32| {
        let d = a + b;
        if d > 0.0 {
            (a / d, b / d)
        } else {
            (1.0, 0.0)
        }
    };
    let (g0, g1) = pair(u, v);
    let (g2, g3) = pair(v, w);
    let (g4, g5) = pair(w, u);
    [g0, g1, g2, g3, g4, g5]
}

/// Gregory-triangle weights (position, `∂/∂s`, `∂/∂t`) at `(s, t)` with blend factors `g`.
fn gregory_weights(s: f32, t: f32, g: &[f32; 6]) -> [W18; 3] {
    let uvw = [s, t, 1.0 - s - t];
    let mut b = [[0.0f32; 3]; 15];
    for (n, x) in b.iter_mut().enumerate() {
        *x = bezier_weights(n as u32, uvw);
    }
    let mut w = [[0.0f32; 18]; 3];
    for k in 0..18 {
        let mut x = b[GREGORY_BEZIER[k] as usize];
        let r = GREGORY_BLEND[k] as usize;
        if r < 6 {
            x = x.map(|y| y * g[r]);
        }
        for (d, y) in x.into_iter().enumerate() {
            w[d][k] = y;
        }
    }
    w
}

/// Position and base-face derivative weights of a patch of `kind` with `PatchParam` word
/// `field1` at the base face's `(u, v)`, as `tri_patch_weights::<f32>` computes them.
pub fn patch_weights(kind: u32, field1: u32, u: f32, v: f32) -> (W18, W18, W18) {
    let depth = (field1 & 0xf) as i32;
    let boundary = (field1 >> 7) & 0x1f;
    let pv = ((field1 >> 12) & 0x3ff) as f32;
    let pu = ((field1 >> 22) & 0x3ff) as f32;
    let rotated = ((field1 >> 22) & 0x3ff) + ((field1 >> 12) & 0x3ff) >= 1 << depth;
    let scale = pow2(depth);
    let (s, t) = if rotated {
        (scale - pu - u * scale, scale - pv - v * scale)
    } else {
        (u * scale - pu, v * scale - pv)
    };
    let [p, mut du, mut dv] = if kind == KIND_BOX_SPLINE {
        box_spline_weights(s, t, boundary)
    } else {
        gregory_weights(s, t, &blend_factors(s, t))
    };
    let sign = if rotated { -1.0 } else { 1.0 };
    let a = sign * scale;
    for k in 0..18 {
        du[k] *= a;
        dv[k] *= a;
    }
    (p, du, dv)
}

#[derive(Clone, Copy, Default)]
struct Eval {
    p: V,
    du: V,
    dv: V,
    found: bool,
}

fn point(inp: &LoopInputs<'_>, k: u32) -> V {
    let i = 3 * k as usize;
    [inp.points[i], inp.points[i + 1], inp.points[i + 2]]
}

fn eval_raw(cfg: &LoopConfig, inp: &LoopInputs<'_>, patch: u32, u: f32, v: f32) -> Eval {
    if patch >= cfg.num_patches {
        return Eval::default();
    }
    let base = PATCH_WORDS * patch as usize;
    let (kind, first, field1) = (
        inp.patch_info[base],
        inp.patch_info[base + 1],
        inp.patch_info[base + 3],
    );
    let (wp, wu, wv) = patch_weights(kind, field1, u, v);
    let regular = kind == KIND_BOX_SPLINE;
    let count = if regular { 12 } else { 18 };
    let x0 = point(inp, first + if regular { 4 } else { 0 });
    let mut r = Eval {
        found: true,
        ..Default::default()
    };
    for k in 0..count {
        let xk = point(inp, first + k as u32);
        for c in 0..3 {
            let x = xk[c] - x0[c];
            r.p[c] += wp[k] * x;
            r.du[c] += wu[k] * x;
            r.dv[c] += wv[k] * x;
        }
    }
    for c in 0..3 {
        r.p[c] += x0[c];
    }
    r
}

fn cross3(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: V) -> V {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    if l > 1e-30 && l <= f32::MAX {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        [0.0; 3]
    }
}

/// One invocation: sample `item` of the dispatch (binding 4 = `out`, `out_stride` floats per
/// sample: position, normal, then `∂P/∂u`, `∂P/∂v` when the stride is 12).
pub fn loop_eval_invocation(item: u32, cfg: &LoopConfig, inp: &LoopInputs<'_>, out: &mut [f32]) {
    if item >= cfg.item_count {
        return;
    }
    let q = QUERY_WORDS * item as usize;
    let patch = inp.queries[q];
    let u = f32::from_bits(inp.queries[q + 1]);
    let v = f32::from_bits(inp.queries[q + 2]);
    let r = eval_raw(cfg, inp, patch, u, v);
    let n = if r.found {
        unit(cross3(r.du, r.dv))
    } else {
        [0.0; 3]
    };
    let o = (cfg.out_stride * item) as usize;
    out[o..o + 3].copy_from_slice(&r.p);
    out[o + 3..o + 6].copy_from_slice(&n);
    if cfg.out_stride >= 12 {
        out[o + 6..o + 9].copy_from_slice(&r.du);
        out[o + 9..o + 12].copy_from_slice(&r.dv);
    }
}

/// Runs every invocation of one dispatch.
pub fn loop_eval(cfg: &LoopConfig, inp: &LoopInputs<'_>, out: &mut [f32]) {
    for item in 0..cfg.item_count {
        loop_eval_invocation(item, cfg, inp, out);
    }
}

/// The `queries` words of `(patch, u, v)` samples.
pub fn pack_queries(queries: &[(u32, f32, f32)]) -> Vec<u32> {
    queries
        .iter()
        .flat_map(|&(p, u, v)| [p, u.to_bits(), v.to_bits()])
        .collect()
}
