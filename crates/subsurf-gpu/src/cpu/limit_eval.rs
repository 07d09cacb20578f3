//! CPU twin of `shaders/limit_eval.wgsl`: the limit surface of a
//! [`subsurf::limit::PatchTable`] at a list of `(ptex face, u, v)` samples.
//!
//! For each sample: the patch map gives the patch covering `(u, v)`; its [`PatchParam`](subsurf::patch::PatchParam)
//! maps `(u, v)` to the patch's own `(s, t) = (u 2^l − U, v 2^l − V)`, `l = depth − non_quad`;
//! the basis of the patch kind gives one weight per control point,
//!
//! ```text
//! P = x_0 + Σ_k w_k(s, t) (x_k − x_0)        ∂P/∂u = 2^l Σ_k ∂w_k/∂s (x_k − x_0)
//! ```
//!
//! (likewise `∂P/∂v`), relative to the patch's first control point `x_0` — exact, as the
//! weights sum to 1 and their derivatives to 0, and rounded relative to the patch instead
//! of its distance from the origin ([`subsurf::limit::LimitSurface::eval`]). The bases:
//!
//! - regular: bicubic B-spline, phantom points `2 P_edge − P_inner` of boundary edges folded
//!   into the curve weights ([`subsurf::patch::bspline_patch_weights`]);
//! - single-crease: the f32-stable direct evaluation of Nießner, Loop & Greiner 2012
//!   ([`subsurf::patch::single_crease_patch_weights`]), integer and fractional sharpness, constant cost;
//! - Gregory end cap: the 20-point Gregory basis of Loop, Schaefer, Ni & Castaño 2009 with
//!   OpenSubdiv's Bézier-approximation derivatives ([`subsurf::patch::gregory_patch_weights`]).
//!
//! The unit normal is `∂P/∂u × ∂P/∂v` normalised, or, where that vanishes, the normal a step
//! of `10⁻³` towards the face centre ([`subsurf::limit::LimitSurface::eval`]).
//!
//! Every expression is written in the library's operation order and f32, so this twin
//! reproduces `LimitSurface::eval` bit for bit; the GPU differs by fused multiply-adds and
//! its division and square root (a few ulps).

use crate::shared::LimitConfig;
use subsurf::limit::PatchTable;

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;
/// Words per patch in `patch_info`: kind, first cv, `PatchParam` field0, field1, sharpness.
pub const PATCH_WORDS: usize = 5;
/// Words per sample in `queries`: ptex, bits of `u`, bits of `v`.
pub const QUERY_WORDS: usize = 3;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::LIMIT_EVAL_WORKGROUP_SIZE);

const EMPTY: u32 = u32::MAX;
const LEAF: u32 = 1 << 31;
const KIND_REGULAR: u32 = 0;
const KIND_SINGLE_CREASE: u32 = 1;
const SHARPNESS_INFINITE: f32 = 10.0;
const ONE6: f32 = (1.0f64 / 6.0) as f32;
const EIGHTH: f32 = 0.125;
/// Bézier `(column, row)` of Gregory point `k = 5c + r` (`r = 3`: `f+`, `r = 4`: `f−`),
/// 2 bits per point, points `0..16` in the `_LO` words, `16..20` in the `_HI` words (as the
/// shader packs them).
const GREGORY_I_LO: u32 = 0x2bbabd44;
const GREGORY_I_HI: u32 = 0x54;
const GREGORY_J_LO: u32 = 0xeaf51150;
const GREGORY_J_HI: u32 = 0xae;

fn two_bits(lo: u32, hi: u32, k: u32) -> usize {
    ((if k < 16 { lo } else { hi } >> (2 * (k % 16))) & 3) as usize
}

type V = [f32; 3];
type W = [f32; 4];

/// The flat tables the kernel reads (bindings 2..=4), built from a patch table.
#[derive(Debug, Clone)]
pub struct LimitTables {
    /// Ptex faces (the roots at the start of `patch_map`).
    pub num_roots: u32,
    /// Binding 2: `[roots | 4 handles per inner node]`.
    pub patch_map: Vec<u32>,
    /// Binding 3: [`PATCH_WORDS`] per patch.
    pub patch_info: Vec<u32>,
    /// Binding 4: control point indices.
    pub cvs: Vec<u32>,
}

impl LimitTables {
    /// Flattens `table`'s patch map, per-patch data and control indices.
    pub fn new(table: &PatchTable) -> Self {
        let map = &table.patch_map();
        let mut patch_map = map.roots().to_vec();
        patch_map.extend(map.nodes().iter().flatten());
        let mut patch_info = Vec::with_capacity(PATCH_WORDS * table.num_patches());
        for p in 0..table.num_patches() {
            patch_info.extend([
                u32::from(table.kinds()[p]),
                table.cv_offsets()[p],
                table.params()[p].field0,
                table.params()[p].field1,
                table.sharpness()[p].to_bits(),
            ]);
        }
        Self {
            num_roots: map.roots().len() as u32,
            patch_map,
            patch_info,
            cvs: table.cvs().to_vec(),
        }
    }
}

/// Read-only inputs of the kernel (bindings 1..=5 in order).
#[derive(Debug, Clone, Copy)]
pub struct LimitInputs<'a> {
    /// Binding 1: [`QUERY_WORDS`] per sample.
    pub queries: &'a [u32],
    /// Binding 2.
    pub patch_map: &'a [u32],
    /// Binding 3.
    pub patch_info: &'a [u32],
    /// Binding 4.
    pub cvs: &'a [u32],
    /// Binding 5: 3 floats per point (all levels, then the local points).
    pub points: &'a [f32],
}

#[derive(Clone, Copy)]
struct Curve {
    p: W,
    d: W,
}

fn pow2(k: i32) -> f32 {
    f32::from_bits(((k + 127).clamp(0, 254) as u32) << 23)
}

fn bspline_curve(t: f32) -> Curve {
    let t2 = t * t;
    let t3 = t2 * t;
    let s = 1.0 - t;
    Curve {
        p: [
            ONE6 * s * s * s,
            ONE6 * (4.0 - 6.0 * t2 + 3.0 * t3),
            ONE6 * (1.0 + 3.0 * (t + t2 - t3)),
            ONE6 * t3,
        ],
        d: [
            -0.5 * s * s,
            1.5 * t2 - 2.0 * t,
            -1.5 * t2 + t + 0.5,
            0.5 * t2,
        ],
    }
}

fn fold_low(w: W) -> W {
    [0.0, w[1] + (w[0] + w[0]), w[2] - w[0], w[3]]
}

fn fold_high(w: W) -> W {
    [w[0], w[1] - w[3], w[2] + (w[3] + w[3]), 0.0]
}

fn bounded(t: f32, low: bool, high: bool) -> Curve {
    let mut c = bspline_curve(t);
    if low {
        c = Curve {
            p: fold_low(c.p),
            d: fold_low(c.d),
        };
    }
    if high {
        c = Curve {
            p: fold_high(c.p),
            d: fold_high(c.d),
        };
    }
    c
}

fn bezier_curve(t: f32) -> Curve {
    let s = 1.0 - t;
    let t2 = t * t;
    let s2 = s * s;
    Curve {
        p: [s2 * s, 3.0 * t * s2, 3.0 * t2 * s, t2 * t],
        d: [
            -3.0 * s2,
            3.0 * s2 - 6.0 * t * s,
            6.0 * t * s - 3.0 * t2,
            3.0 * t2,
        ],
    }
}

fn crease_middle(x: W, q: f32) -> [f32; 3] {
    [
        EIGHTH * (4.0 * x[0] + x[1]),
        EIGHTH * (4.0 * x[0] + 6.0 * x[1] + 4.0 * x[2] + q * x[3]),
        EIGHTH * q * x[3],
    ]
}

fn crease_last(x: W, q: f32) -> [f32; 3] {
    [
        EIGHTH * x[0],
        EIGHTH * (6.0 * x[0] + 4.0 * x[1] + q * x[2]),
        EIGHTH * (q * x[2] + 4.0 * x[3]),
    ]
}

fn crease_apply(c: [f32; 3], a1: f32, a3: f32, sum: f32) -> W {
    let e = c[0] + c[0] + c[1];
    [
        a3 * c[0],
        a1 * e - 2.0 * a3 * c[0],
        sum - a1 * (e + c[2]) + a3 * c[0],
        a1 * c[2],
    ]
}

/// Segment with a crease of sharpness `0 < s < 10` at its `t = 1` end; `d = 1 − t`.
fn crease_curve(t: f32, d: f32, s: f32) -> Curve {
    let m_real = s.floor();
    let m = m_real as i32;
    let phi = s - m_real;
    if d >= pow2(-m) {
        return bounded(t, false, true);
    }
    let q = 1.0 - phi;
    let (kexp, cp, cd) = if phi == 0.0 {
        let n = bspline_curve(1.0 - pow2(m) * d);
        (m, [n.p[0], n.p[1], n.p[3]], [n.d[0], n.d[1], n.d[3]])
    } else if d >= pow2(-(m + 1)) {
        let n = bspline_curve(2.0 - pow2(m + 1) * d);
        (m + 1, crease_middle(n.p, q), crease_middle(n.d, q))
    } else {
        let n = bspline_curve(1.0 - pow2(m + 1) * d);
        (m + 1, crease_last(n.p, q), crease_last(n.d, q))
    };
    Curve {
        p: crease_apply(cp, pow2(-m), pow2(-3 * m), 1.0),
        d: crease_apply(cd, pow2(kexp - m), pow2(kexp - 3 * m), 0.0),
    }
}

fn reversed(c: Curve) -> Curve {
    Curve {
        p: [c.p[3], c.p[2], c.p[1], c.p[0]],
        d: [-c.d[3], -c.d[2], -c.d[1], -c.d[0]],
    }
}

#[derive(Clone, Copy, Default)]
struct Eval {
    p: V,
    du: V,
    dv: V,
    found: bool,
}

fn point(inp: &LimitInputs<'_>, k: u32) -> V {
    let i = 3 * inp.cvs[k as usize] as usize;
    [inp.points[i], inp.points[i + 1], inp.points[i + 2]]
}

fn axpy(acc: &mut V, w: f32, x: V) {
    for c in 0..3 {
        acc[c] += w * x[c];
    }
}

/// One gather for every kind (see the shader's `gather`).
fn gather(
    inp: &LimitInputs<'_>,
    first: u32,
    gregory: bool,
    wu: Curve,
    wv: Curve,
    g: [f32; 4],
    scale: f32,
) -> Eval {
    let mut r = Eval {
        found: true,
        ..Default::default()
    };
    let count = if gregory { 20 } else { 16 };
    // Relative to the first control point (see the module documentation).
    let x0 = point(inp, first);
    for k in 0..count {
        let (mut i, mut j, mut gk) = ((k % 4) as usize, (k / 4) as usize, 1.0f32);
        if gregory {
            i = two_bits(GREGORY_I_LO, GREGORY_I_HI, k);
            j = two_bits(GREGORY_J_LO, GREGORY_J_HI, k);
            match k % 5 {
                3 => gk = g[(k / 5) as usize],
                4 => gk = 1.0 - g[(k / 5) as usize],
                _ => {}
            }
        }
        let xk = point(inp, first + k);
        let x: V = std::array::from_fn(|c| xk[c] - x0[c]);
        axpy(&mut r.p, wu.p[i] * wv.p[j] * gk, x);
        axpy(&mut r.du, wu.d[i] * gk * wv.p[j] * scale, x);
        axpy(&mut r.dv, wv.d[j] * gk * wu.p[i] * scale, x);
    }
    axpy(&mut r.p, 1.0, x0);
    r
}

fn gregory_rational(k: usize, u: f32, v: f32) -> f32 {
    let (n, d) = match k {
        0 => (u, u + v),
        1 => (v, 1.0 - u + v),
        2 => (1.0 - u, (1.0 - u) + (1.0 - v)),
        _ => (1.0 - v, u + (1.0 - v)),
    };
    if d <= 0.0 {
        0.0
    } else {
        n / d
    }
}

fn find_patch(cfg: &LimitConfig, map: &[u32], ptex: u32, u0: f32, v0: f32) -> u32 {
    if ptex >= cfg.num_roots {
        return EMPTY;
    }
    let mut h = map[ptex as usize];
    let (mut u, mut v) = (u0, v0);
    loop {
        if h == EMPTY {
            return EMPTY;
        }
        if h & LEAF != 0 {
            return h & !LEAF;
        }
        let (hi_u, hi_v) = (u >= 0.5, v >= 0.5);
        let q = match (hi_u, hi_v) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        };
        u = 2.0 * u - if hi_u { 1.0 } else { 0.0 };
        v = 2.0 * v - if hi_v { 1.0 } else { 0.0 };
        h = map[(cfg.num_roots + 4 * h + q) as usize];
    }
}

fn eval_raw(cfg: &LimitConfig, inp: &LimitInputs<'_>, ptex: u32, u0: f32, v0: f32) -> Eval {
    let (u, v) = (u0.clamp(0.0, 1.0), v0.clamp(0.0, 1.0));
    let patch = find_patch(cfg, inp.patch_map, ptex, u, v);
    if patch == EMPTY {
        return Eval::default();
    }
    let base = PATCH_WORDS * patch as usize;
    let info = &inp.patch_info[base..base + PATCH_WORDS];
    let (kind, first, field1) = (info[0], info[1], info[3]);
    let sharpness = f32::from_bits(info[4]);
    let depth = (field1 & 0xf) as i32;
    let non_quad = ((field1 >> 4) & 1) as i32;
    let boundary = (field1 >> 7) & 0x1f;
    let pv = ((field1 >> 12) & 0x3ff) as f32;
    let pu = ((field1 >> 22) & 0x3ff) as f32;
    let scale = pow2((depth - non_quad).max(0));
    let (s, t) = (u * scale - pu, v * scale - pv);
    if kind != KIND_REGULAR && kind != KIND_SINGLE_CREASE {
        let g: [f32; 4] = std::array::from_fn(|k| gregory_rational(k, s, t));
        return gather(inp, first, true, bezier_curve(s), bezier_curve(t), g, scale);
    }
    // Tensor-product kinds share one gather (see the shader).
    let mut mask = boundary;
    let mut crease_edge = 4;
    if kind == KIND_SINGLE_CREASE {
        let bits = boundary & 0xf;
        mask = 0;
        // Greater than zero (NaN is smooth).
        if bits != 0 && sharpness.partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater) {
            let edge = bits.trailing_zeros();
            if sharpness >= SHARPNESS_INFINITE {
                mask = 1 << edge;
            } else {
                crease_edge = edge;
            }
        }
    }
    let mut wu = bounded(s, mask & 8 != 0, mask & 2 != 0);
    let mut wv = bounded(t, mask & 1 != 0, mask & 4 != 0);
    if crease_edge < 4 {
        let along_u = crease_edge == 1 || crease_edge == 3;
        let high = crease_edge == 1 || crease_edge == 2;
        let x = if along_u { s } else { t };
        let (tc, dc) = if high { (x, 1.0 - x) } else { (1.0 - x, x) };
        let mut c = crease_curve(tc, dc, sharpness);
        if !high {
            c = reversed(c);
        }
        if along_u {
            wu = c;
        } else {
            wv = c;
        }
    }
    gather(inp, first, false, wu, wv, [0.0; 4], scale)
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

/// One invocation: sample `item` of the dispatch (binding 6 = `out`, `out_stride` floats per
/// sample: position, normal, then `∂P/∂u`, `∂P/∂v` when the stride is 12).
pub fn limit_eval_invocation(item: u32, cfg: &LimitConfig, inp: &LimitInputs<'_>, out: &mut [f32]) {
    if item >= cfg.item_count {
        return;
    }
    let q = QUERY_WORDS * item as usize;
    let ptex = inp.queries[q];
    let u = f32::from_bits(inp.queries[q + 1]).clamp(0.0, 1.0);
    let v = f32::from_bits(inp.queries[q + 2]).clamp(0.0, 1.0);
    let r = eval_raw(cfg, inp, ptex, u, v);
    let mut n = [0.0f32; 3];
    if r.found {
        n = unit(cross3(r.du, r.dv));
        if n == [0.0; 3] {
            // Step a little towards the face centre, where the tangent plane is regular.
            let q = eval_raw(cfg, inp, ptex, u + (0.5 - u) * 1e-3, v + (0.5 - v) * 1e-3);
            if q.found {
                n = unit(cross3(q.du, q.dv));
            }
        }
    }
    let o = (cfg.out_stride * item) as usize;
    out[o..o + 3].copy_from_slice(&r.p);
    out[o + 3..o + 6].copy_from_slice(&n);
    if cfg.out_stride >= 12 {
        out[o + 6..o + 9].copy_from_slice(&r.du);
        out[o + 9..o + 12].copy_from_slice(&r.dv);
    }
}

/// Runs every invocation of one dispatch.
pub fn limit_eval(cfg: &LimitConfig, inp: &LimitInputs<'_>, out: &mut [f32]) {
    for item in 0..cfg.item_count {
        limit_eval_invocation(item, cfg, inp, out);
    }
}

/// The `queries` words of `(ptex, u, v)` samples.
pub fn pack_queries(queries: &[(u32, f32, f32)]) -> Vec<u32> {
    queries
        .iter()
        .flat_map(|&(f, u, v)| [f, u.to_bits(), v.to_bits()])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use subsurf::patch::{GREGORY_BOUNDARY, GREGORY_INTERIOR};

    #[test]
    fn packed_gregory_slots_match_the_library_tables() {
        for &(g, i, j) in &GREGORY_BOUNDARY {
            assert!(g % 5 < 3, "boundary point {g} in an f± slot");
            let k = g as u32;
            assert_eq!(
                (
                    two_bits(GREGORY_I_LO, GREGORY_I_HI, k),
                    two_bits(GREGORY_J_LO, GREGORY_J_HI, k)
                ),
                (i, j),
                "point {g}"
            );
        }
        for (c, &(plus, minus, i, j)) in GREGORY_INTERIOR.iter().enumerate() {
            assert_eq!((plus, minus), (5 * c + 3, 5 * c + 4));
            for k in [plus as u32, minus as u32] {
                assert_eq!(two_bits(GREGORY_I_LO, GREGORY_I_HI, k), i);
                assert_eq!(two_bits(GREGORY_J_LO, GREGORY_J_HI, k), j);
            }
        }
    }
}
