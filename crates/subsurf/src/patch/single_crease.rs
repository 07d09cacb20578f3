//! Direct evaluation of a regular bicubic patch with one semi-sharp crease edge
//! (Nießner, Loop & Greiner 2012, "Efficient evaluation of semi-smooth creases in
//! Catmull-Clark subdivision surfaces"; the checked form is `shared/spec/creases.md`).
//!
//! # Curve case
//!
//! Take one uniform cubic B-spline segment `f(t) = N(t) P`, `P = (P0, P1, P2, P3)`, with a
//! crease of sharpness `s` at **`P2`, the `t = 1` end**: `s` subdivision steps use the sharp
//! rule at `P2`, later steps the smooth one (DeRose, Kass & Truong 1998). With the
//! right-half refinement matrices
//!
//! ```text
//! R  = 1/8 [[1,6,1,0],[0,4,4,0],[0,1,6,1],[0,0,4,4]]    (smooth)
//! Rp = 1/8 [[1,6,1,0],[0,4,4,0],[0,0,8,0],[0,0,4,4]]    (sharp at P2)
//! RL = 1/8 [[4,4,0,0],[1,6,1,0],[0,4,4,0],[0,1,6,1]]    (smooth, left half)
//! M∞ = [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,-1,2,0]]       (P3 → 2 P2 − P1)
//! ```
//!
//! the curve for integer `s = m` is
//!
//! ```text
//! f(t) = N(t) M∞ P              0 ≤ t ≤ 1 − 2^-m      (infinitely sharp part)
//! f(t) = N(t') Rp^m P           t' = 1 − 2^m (1 − t)   (transition part, next to the crease)
//! ```
//!
//! For fractional `s = m + φ` (`0 < φ < 1`) the curve is `(1−φ) C_m + φ C_(m+1)` (DeRose's
//! blended rule only touches the crease points and all later steps are linear), giving three
//! parts:
//!
//! ```text
//! f(t) = N(t) M∞ P                                0 ≤ t ≤ 1 − 2^-m
//! f(t) = N(t') RL [(1−φ) I + φ M∞] Rp^m P        t' = 2^(m+1) (t − 1 + 2^-m),  middle
//! f(t) = N(t') [(1−φ) R + φ Rp] Rp^m P           t' = 1 − 2^(m+1) (1 − t),     last
//! ```
//!
//! The middle part uses `R^m M∞ = M∞ Rp^m` (the smooth rules leave the curve of the phantom
//! point `2 P2 − P1` unchanged), so every part only needs `Rp^m`, whose closed form
//! (σ = 2^m)
//!
//! ```text
//! Rp^m = [[σ⁻³, 2σ⁻¹ − 2σ⁻³, 1 − 2σ⁻¹ + σ⁻³, 0],
//!         [0,   σ⁻¹,         1 − σ⁻¹,        0],
//!         [0,   0,           1,              0],
//!         [0,   0,           1 − σ⁻¹,        σ⁻¹]]
//! ```
//!
//! has entries in `[0, 1]`. This is the `f32`-stable "local parameter, forward matrices"
//! form of the spec (§5): the paper's `M_s = R^-s Rp^s` has entries growing like `σ²`
//! (2·10⁶ at `s = 10`) and loses four digits in `f32`.
//!
//! Writing `Rp^m = J + σ⁻¹ A + σ⁻³ B` (`J` has ones in column 2) and `c = N(t') L` for the
//! part's left factor `L`, the weights are `w = (Σc) e2 + σ⁻¹ c A + σ⁻³ c B`. For the
//! derivatives `Σc' = 0`, so `J` drops out exactly and `dw/dt = k (σ⁻¹ c'A + σ⁻³ c'B)` with
//! `k = dt'/dt ∈ {σ, 2σ}`: `k σ⁻¹ ∈ {1, 2}`, and no cancellation of large terms remains.
//! The cost is constant in `s` (no loop over subdivision levels).
//!
//! A sharpness `s ≥ SHARPNESS_INFINITE` (10) is infinitely sharp: `f(t) = N(t) M∞ P` for
//! all `t`. `s ≤ 0` (and NaN) is smooth: `f(t) = N(t) P`.
//!
//! # Patch
//!
//! For a regular 4×4 patch whose only tagged edges are the three grid edges of one grid line
//! along a patch edge, all with sharpness `s`, the Catmull-Clark crease rules are the tensor
//! product of the curve rule across the crease and the smooth rule along it (spec §4). The
//! crease edge is named by [`PatchEdge`] with OpenSubdiv's convention: a single-crease patch
//! stores `1 << k` for its crease edge `k` in the [`super::PatchParam`] boundary field (the
//! patch is interior, so the field is free), and the sharpness separately.
//!
//! The evaluation is exact for the sharpness it is given. OpenSubdiv's patch table builder
//! stores `min(edge sharpness, max isolation level − patch level)` for a single-crease patch;
//! whether to replicate that cap is the builder's choice.
//!
//! | crease edge | transformed direction | curve parameter `t` (crease at `t = 1`) |
//! |---|---|---|
//! | `U1` (`u = 1`, grid column 2) | `u` | `u` |
//! | `U0` (`u = 0`, grid column 1) | `u`, points reversed | `1 − u` |
//! | `V1` (`v = 1`, grid row 2) | `v` | `v` |
//! | `V0` (`v = 0`, grid row 1) | `v`, points reversed | `1 − v` |

use super::basis::CurveShape;
use super::bspline::{bspline_curve, bspline_curve_bounded};
use super::weights::{CurveWeights, PatchEval, PatchWeights};
use super::PatchEdge;
use crate::real::Real;
use crate::SHARPNESS_INFINITE;

/// Row vectors `x · L` for the three weight vectors of `n`, where `L` is given by a closure
/// mapping a row vector to `(c0, c1, c3)` (column 2 is never needed, see the module docs).
#[inline]
fn left<T: Real>(n: &CurveWeights<T>, l: impl Fn(&[T; 4]) -> [T; 3]) -> [[T; 3]; 3] {
    [l(&n.p), l(&n.d1), l(&n.d2)]
}

/// Curve weights at `t` of a cubic B-spline segment with a crease of sharpness `s` at its
/// `t = 1` end (control point `P2`). `d = 1 − t` is passed separately so that callers who
/// know it exactly (the reversed orientations) keep it exact.
fn crease_curve_td<T: Real>(t: T, d: T, s: T) -> CurveWeights<T> {
    let c = |x: f64| T::from_f64(x);
    if s.partial_cmp(&T::ZERO) != Some(std::cmp::Ordering::Greater) {
        return bspline_curve(t);
    }
    if s >= c(SHARPNESS_INFINITE as f64) {
        return bspline_curve_bounded(t, false, true);
    }
    let m_real = s.floor();
    let m = m_real.to_f64() as i32; // 0..=9
    let phi = s - m_real;
    // The infinitely sharp part: 1 − t ≥ 2^-m.
    if d >= T::pow2(-m) {
        return bspline_curve_bounded(t, false, true);
    }
    let eighth = c(0.125);
    // (k = dt'/dt as a power of two, c = N(t') L restricted to columns 0, 1, 3)
    let (kexp, cw) = if phi == T::ZERO {
        // Transition part of integer sharpness: L = I.
        let tl = T::ONE - T::pow2(m) * d;
        let n = bspline_curve(tl);
        (m, left(&n, |x| [x[0], x[1], x[3]]))
    } else if d >= T::pow2(-(m + 1)) {
        // Middle part: L = RL [(1−φ) I + φ M∞]
        //   = 1/8 [[4,4,0,0],[1,6,1,0],[0,4,4,0],[0,1−φ,6+2φ,1−φ]].
        let tl = c(2.0) - T::pow2(m + 1) * d;
        let n = bspline_curve(tl);
        let q = T::ONE - phi;
        (
            m + 1,
            left(&n, |x| {
                [
                    eighth * (c(4.0) * x[0] + x[1]),
                    eighth * (c(4.0) * x[0] + c(6.0) * x[1] + c(4.0) * x[2] + q * x[3]),
                    eighth * q * x[3],
                ]
            }),
        )
    } else {
        // Last part: L = (1−φ) R + φ Rp
        //   = 1/8 [[1,6,1,0],[0,4,4,0],[0,1−φ,6+2φ,1−φ],[0,0,4,4]].
        let tl = T::ONE - T::pow2(m + 1) * d;
        let n = bspline_curve(tl);
        let q = T::ONE - phi;
        (
            m + 1,
            left(&n, |x| {
                [
                    eighth * x[0],
                    eighth * (c(6.0) * x[0] + c(4.0) * x[1] + q * x[2]),
                    eighth * (q * x[2] + c(4.0) * x[3]),
                ]
            }),
        )
    };
    // w = e2 (Σc) + a1 (cA) + a3 (cB), cA = [0, 2c0+c1, −(2c0+c1+c3), c3], cB = [c0, −2c0, c0, 0].
    let apply = |cc: &[T; 3], a1: T, a3: T, sum: T| -> [T; 4] {
        let (c0, c1, c3) = (cc[0], cc[1], cc[2]);
        let e = c0 + c0 + c1;
        [
            a3 * c0,
            a1 * e - c(2.0) * a3 * c0,
            sum - a1 * (e + c3) + a3 * c0,
            a1 * c3,
        ]
    };
    let a1 = T::pow2(-m);
    let a3 = T::pow2(-3 * m);
    let k1a1 = T::pow2(kexp - m);
    let k1a3 = T::pow2(kexp - 3 * m);
    let k2a1 = T::pow2(2 * kexp - m);
    let k2a3 = T::pow2(2 * kexp - 3 * m);
    CurveWeights {
        p: apply(&cw[0], a1, a3, T::ONE),
        d1: apply(&cw[1], k1a1, k1a3, T::ZERO),
        d2: apply(&cw[2], k2a1, k2a3, T::ZERO),
    }
}

/// Curve weights at `t ∈ [0, 1]` of a uniform cubic B-spline segment `(P0, P1, P2, P3)` with a
/// crease of sharpness `s` at `P2` (the `t = 1` end), with first and second `t`-derivatives.
///
/// `s ≤ 0` gives the smooth segment, `s ≥ 10` the infinitely sharp one, fractional `s` the
/// DeRose blend. Cost is constant in `s`.
pub fn crease_curve<T: Real>(t: T, s: T) -> CurveWeights<T> {
    crease_curve_td(t, T::ONE - t, s)
}

/// Weights of the 16 points of a regular bicubic patch at `(u, v)` whose grid line along
/// `edge` is a crease of sharpness `s` (see the module documentation).
pub fn single_crease_patch_weights<T: Real>(
    u: T,
    v: T,
    edge: PatchEdge,
    s: T,
) -> PatchWeights<T, 16> {
    let [wu, wv] = single_crease_curves(u, v, edge, s);
    PatchWeights::tensor(&wu, &wv)
}

/// The two curves whose tensor product is [`single_crease_patch_weights`] (along `u`, along
/// `v`), for callers that need only some of the tensor's weights.
pub fn single_crease_curves<T: Real>(u: T, v: T, edge: PatchEdge, s: T) -> [CurveWeights<T>; 2] {
    [
        single_crease_curve(u, 0, edge, s),
        single_crease_curve(v, 1, edge, s),
    ]
}

/// One curve of [`single_crease_curves`] alone (`dir` 0: along `u` at `x = u`, 1: along `v`
/// at `x = v`), bit for bit: each depends on its own parameter only. Which curve it is (the
/// plain or boundary B-spline, or the crease's) is decided once, by
/// [`single_crease_shape`].
#[inline(always)]
pub fn single_crease_curve<T: Real>(x: T, dir: usize, edge: PatchEdge, s: T) -> CurveWeights<T> {
    match single_crease_shape(dir, edge, s) {
        CurveShape::BSpline { low, high } => bspline_curve_bounded(x, low, high),
        CurveShape::Crease(edge) => crease_curve_across(x, edge, s),
        CurveShape::None => unreachable!("a single-crease curve is a tensor factor"),
    }
}

/// The curve across a crease along `edge` of sharpness `s` (0 < `s` < infinite) at `x`, the
/// parameter across it ([`CurveShape::Crease`]).
#[inline(always)]
pub fn crease_curve_across<T: Real>(x: T, edge: PatchEdge, s: T) -> CurveWeights<T> {
    match edge {
        PatchEdge::U1 | PatchEdge::V1 => crease_curve_td(x, T::ONE - x, s),
        PatchEdge::U0 | PatchEdge::V0 => crease_curve_td(T::ONE - x, x, s).reversed(),
    }
}

/// The shape of the curve along `dir` of a single-crease patch creased along `edge` with
/// sharpness `s`: the two limits are the plain (`s <= 0`) and the boundary (phantom point,
/// `s` infinite) B-spline, bit-identical to those patches in every orientation; otherwise the
/// curves across the crease (along `u` for edges `u = 0, 1`, along `v` for `v = 0, 1`) are the
/// crease's and the others plain.
#[inline(always)]
pub fn single_crease_shape<T: Real>(dir: usize, edge: PatchEdge, s: T) -> CurveShape {
    let folds = |m: u8| CurveShape::bounded(m, dir);
    if s.partial_cmp(&T::ZERO) != Some(std::cmp::Ordering::Greater) {
        folds(0)
    } else if s >= T::from_f64(SHARPNESS_INFINITE as f64) {
        folds(edge.mask())
    } else if edge.index() % 2 == 1 - dir as u32 {
        CurveShape::Crease(edge)
    } else {
        folds(0)
    }
}

/// Evaluates a single-crease patch (see [`single_crease_patch_weights`]).
pub fn eval_single_crease_patch<T: Real, const D: usize>(
    points: &[[T; D]; 16],
    u: T,
    v: T,
    edge: PatchEdge,
    s: T,
) -> PatchEval<T, D> {
    single_crease_patch_weights(u, v, edge, s).eval(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(R^-1)^s Rp^s` by the spec's closed form (§2), exact for integer `s`.
    fn m_s(s: i32) -> [[f64; 4]; 4] {
        let g = 2f64.powi(s);
        let o = 1.0 - g;
        let k = 1.0 / (6.0 * g);
        let a = o * (6.0 * g * g - 5.0 * g + 1.0);
        [
            [
                6.0 * g * k,
                a * k,
                o * (-12.0 * g * g + 10.0 * g - 2.0) * k,
                a * k,
            ],
            [
                0.0,
                (2.0 * g * g + 3.0 * g + 1.0) * k,
                o * (4.0 * g - 2.0) * k,
                o * (1.0 - 2.0 * g) * k,
            ],
            [
                0.0,
                o * (g + 1.0) * k,
                (2.0 * g * g + 6.0 * g - 2.0) * k,
                o * (g + 1.0) * k,
            ],
            [
                0.0,
                o * (1.0 - 2.0 * g) * k,
                o * (4.0 * g - 2.0) * k,
                (2.0 * g * g + 3.0 * g + 1.0) * k,
            ],
        ]
    }

    #[test]
    fn transition_part_equals_paper_matrix_form() {
        // On the transition part, the stable form equals N(t) M_s (paper's form) for
        // positions and derivatives.
        for s in 1..=6 {
            let ms = m_s(s);
            for k in 0..=16 {
                let t = 1.0 - 2f64.powi(-s) * (k as f64 / 16.0);
                let ours = crease_curve(t, s as f64);
                let paper = bspline_curve(t).times_matrix(&ms);
                for j in 0..4 {
                    assert!((ours.p[j] - paper.p[j]).abs() < 1e-9, "s={s} t={t}");
                    assert!((ours.d1[j] - paper.d1[j]).abs() < 1e-8, "s={s} t={t}");
                    assert!((ours.d2[j] - paper.d2[j]).abs() < 1e-6 * 2f64.powi(s));
                }
            }
        }
    }

    #[test]
    fn weights_partition_of_unity() {
        for s in [0.0, 0.3, 1.0, 1.5, 2.75, 6.0, 9.99, 10.0] {
            for k in 0..=64 {
                let t = k as f64 / 64.0;
                let w = crease_curve(t, s);
                assert!((w.p.iter().sum::<f64>() - 1.0).abs() < 1e-14);
                assert!(w.d1.iter().sum::<f64>().abs() < 1e-12);
                assert!(w.d2.iter().sum::<f64>().abs() < 1e-9);
            }
        }
    }

    #[test]
    fn crease_end_tends_to_crease_point() {
        // f(1) → P2 as s grows: the distance is O(2^-s) (spec §2).
        for s in 1..10 {
            let w = crease_curve(1.0f64, s as f64);
            let off = (1.0 - w.p[2]).abs() + w.p[1].abs() + w.p[3].abs();
            assert!(off <= 2f64.powi(-s) + 1e-15, "s={s}: {off}");
        }
    }
}
