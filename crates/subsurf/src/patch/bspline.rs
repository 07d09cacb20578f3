//! Uniform cubic B-spline basis and the regular bicubic patch, including OpenSubdiv's
//! boundary and corner variants.
//!
//! # Curve basis
//!
//! One segment of a uniform cubic B-spline, `f(t) = Σ N_k(t) P_k`, `t ∈ [0, 1]`, with `t = 0`
//! at the knot of `P1` and `t = 1` at the knot of `P2` (de Boor 1978):
//!
//! ```text
//! N0 = (1-t)³ / 6                 N1 = (3t³ - 6t² + 4) / 6
//! N2 = (-3t³ + 3t² + 3t + 1) / 6  N3 = t³ / 6
//! ```
//!
//! The weights sum to one; their derivatives sum to zero. At `t = 0` the point is
//! `(P0 + 4 P1 + P2) / 6`, the Catmull-Clark limit position of a regular vertex.
//!
//! # Boundaries: phantom points
//!
//! A regular patch on a boundary lacks the row (or column) of points beyond the boundary
//! edge. OpenSubdiv (`Far::internal::EvalBasisBSpline` and its boundary adjustment) evaluates
//! such a patch as if the missing points were mirrored through the boundary:
//!
//! ```text
//! P_phantom = 2 · P_edge − P_inner
//! ```
//!
//! and folds that extrapolation into the weights, so the missing points get weight zero and
//! their (arbitrary) values never matter. Along the boundary edge the surface is then the
//! cubic B-spline of the boundary points, which is the limit of the Catmull-Clark boundary
//! (crease) rules `(1, 6, 1)/8` and `(1, 1)/2`. At a corner both directions are extrapolated,
//! which makes the patch interpolate the corner point (the limit of the corner rule).
//!
//! Boundary mask bits, one per [`super::PatchEdge`]:
//!
//! | bit | edge | missing points | phantom |
//! |---|---|---|---|
//! | [`BOUNDARY_V0`] = 1 | `v = 0` | row 0 (0..=3) | `row0 = 2·row1 − row2` |
//! | [`BOUNDARY_U1`] = 2 | `u = 1` | column 3 | `col3 = 2·col2 − col1` |
//! | [`BOUNDARY_V1`] = 4 | `v = 1` | row 3 (12..=15) | `row3 = 2·row2 − row1` |
//! | [`BOUNDARY_U0`] = 8 | `u = 0` | column 0 | `col0 = 2·col1 − col2` |
//!
//! OpenSubdiv stores the mask in a 5-bit field; the fifth bit only has a meaning for
//! triangular (Loop) patches and is ignored here. The adjustment is linear and acts on one
//! parametric direction at a time, so it is applied to the two curve weight vectors before
//! the tensor product; the result equals OpenSubdiv's adjustment of the 16 tensor weights.

use super::weights::{CurveWeights, PatchEval, PatchWeights};
use crate::real::Real;

/// Boundary mask bit of edge 0 (`v = 0`): row 0 is a phantom row.
pub const BOUNDARY_V0: u8 = 1;
/// Boundary mask bit of edge 1 (`u = 1`): column 3 is a phantom column.
pub const BOUNDARY_U1: u8 = 2;
/// Boundary mask bit of edge 2 (`v = 1`): row 3 is a phantom row.
pub const BOUNDARY_V1: u8 = 4;
/// Boundary mask bit of edge 3 (`u = 0`): column 0 is a phantom column.
pub const BOUNDARY_U0: u8 = 8;

/// Uniform cubic B-spline weights of one segment at `t`, with first and second derivatives.
#[inline]
pub fn bspline_curve<T: Real>(t: T) -> CurveWeights<T> {
    let c = |x: f64| T::from_f64(x);
    let one6 = c(1.0 / 6.0);
    let t2 = t * t;
    let t3 = t2 * t;
    let s = T::ONE - t;
    let half = c(0.5);
    CurveWeights {
        p: [
            one6 * s * s * s,
            one6 * (c(4.0) - c(6.0) * t2 + c(3.0) * t3),
            one6 * (T::ONE + c(3.0) * (t + t2 - t3)),
            one6 * t3,
        ],
        d1: [
            -half * s * s,
            c(1.5) * t2 - c(2.0) * t,
            -c(1.5) * t2 + t + half,
            half * t2,
        ],
        d2: [s, c(3.0) * t - c(2.0), -c(3.0) * t + T::ONE, t],
    }
}

/// Folds a phantom first point `P0 = 2 P1 − P2` into the weights (boundary at `t = 0`).
#[inline]
pub fn fold_phantom_low<T: Real>(w: &mut [T; 4]) {
    let w0 = w[0];
    w[1] += w0 + w0;
    w[2] -= w0;
    w[0] = T::ZERO;
}

/// Folds a phantom last point `P3 = 2 P2 − P1` into the weights (boundary at `t = 1`).
#[inline]
pub fn fold_phantom_high<T: Real>(w: &mut [T; 4]) {
    let w3 = w[3];
    w[2] += w3 + w3;
    w[1] -= w3;
    w[3] = T::ZERO;
}

/// [`fold_phantom_low`] / [`fold_phantom_high`] applied to all three weight vectors.
#[inline]
pub fn fold_curve<T: Real>(w: &mut CurveWeights<T>, low: bool, high: bool) {
    for v in [&mut w.p, &mut w.d1, &mut w.d2] {
        if low {
            fold_phantom_low(v);
        }
        if high {
            fold_phantom_high(v);
        }
    }
}

/// Curve weights of a B-spline segment whose end(s) lie on a boundary: the infinitely sharp
/// curve `N(t) M∞` of Nießner et al. 2012 when `high` is set (phantom `P3 = 2 P2 − P1`).
#[inline]
pub fn bspline_curve_bounded<T: Real>(t: T, low: bool, high: bool) -> CurveWeights<T> {
    let mut w = bspline_curve(t);
    fold_curve(&mut w, low, high);
    w
}

/// Weights of the 16 points of a regular bicubic B-spline patch at `(u, v)` with the given
/// boundary mask (0 for an interior patch). Points beyond a boundary edge get weight 0.
pub fn bspline_patch_weights<T: Real>(u: T, v: T, boundary: u8) -> PatchWeights<T, 16> {
    let [wu, wv] = bspline_curves(u, v, boundary);
    PatchWeights::tensor(&wu, &wv)
}

/// The two curves (along `u`, along `v`) whose tensor product is
/// [`bspline_patch_weights`]`(u, v, boundary)`: each folded where `boundary` marks its ends.
#[inline(always)]
pub fn bspline_curves<T: Real>(u: T, v: T, boundary: u8) -> [CurveWeights<T>; 2] {
    [
        bspline_curve_bounded(u, boundary & BOUNDARY_U0 != 0, boundary & BOUNDARY_U1 != 0),
        bspline_curve_bounded(v, boundary & BOUNDARY_V0 != 0, boundary & BOUNDARY_V1 != 0),
    ]
}

/// Evaluates a regular bicubic B-spline patch (see [`bspline_patch_weights`]).
pub fn eval_bspline_patch<T: Real, const D: usize>(
    points: &[[T; D]; 16],
    u: T,
    v: T,
    boundary: u8,
) -> PatchEval<T, D> {
    bspline_patch_weights(u, v, boundary).eval(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curve_partition_of_unity_and_derivative_sums() {
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let w = bspline_curve(t);
            assert!((w.p.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(w.d1.iter().sum::<f64>().abs() < 1e-15);
            assert!(w.d2.iter().sum::<f64>().abs() < 1e-15);
        }
    }

    #[test]
    fn curve_knot_values() {
        let w = bspline_curve(0.0f64);
        assert_eq!(w.p, [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0]);
        assert_eq!(w.d1, [-0.5, 0.0, 0.5, 0.0]);
        assert_eq!(w.d2, [1.0, -2.0, 1.0, 0.0]);
    }

    #[test]
    fn folded_weights_match_explicit_phantom_points() {
        // Weights after folding, applied to P, equal plain weights applied to the
        // extrapolated points.
        let p = [0.3f64, -1.2, 2.5, 0.7];
        for k in 0..=10 {
            let t = k as f64 / 10.0;
            let plain = bspline_curve(t);
            let folded = bspline_curve_bounded(t, true, true);
            let ext = [2.0 * p[1] - p[2], p[1], p[2], 2.0 * p[2] - p[1]];
            let a: f64 = (0..4).map(|i| folded.p[i] * p[i]).sum();
            let b: f64 = (0..4).map(|i| plain.p[i] * ext[i]).sum();
            assert!((a - b).abs() < 1e-14);
            assert_eq!(folded.p[0], 0.0);
            assert_eq!(folded.p[3], 0.0);
        }
    }

    #[test]
    fn tensor_index_order_is_u_along_rows() {
        // P(i, j) = (i, j): the patch must reproduce the bilinear map (u + 1, v + 1).
        let mut pts = [[0.0f64; 2]; 16];
        for j in 0..4 {
            for i in 0..4 {
                pts[4 * j + i] = [i as f64, j as f64];
            }
        }
        let e = eval_bspline_patch(&pts, 0.25, 0.75, 0);
        assert!((e.p[0] - 1.25).abs() < 1e-15 && (e.p[1] - 1.75).abs() < 1e-15);
        assert!((e.du[0] - 1.0).abs() < 1e-15 && e.du[1].abs() < 1e-15);
        assert!(e.dv[0].abs() < 1e-15 && (e.dv[1] - 1.0).abs() < 1e-15);
    }
}
