//! Cubic Bernstein (Bézier) basis and the bicubic Bézier patch.
//!
//! `B0 = (1-t)³, B1 = 3t(1-t)², B2 = 3t²(1-t), B3 = t³` (Farin 2002). The bicubic patch uses
//! the same 4×4 point order as the B-spline patch (index `4*j + i`, `i` along `u`). It is
//! the building block of the Gregory patch ([`super::gregory`]).
//!
//! A uniform cubic B-spline segment equals the Bézier segment with points `Q · P`
//! ([`BSPLINE_TO_BEZIER`]): the inner points sit at the thirds of the middle leg, the end
//! points at the curve's knots.

use super::weights::{CurveWeights, PatchEval, PatchWeights};
use crate::real::Real;

/// Change of basis from a uniform cubic B-spline segment to its Bézier points:
/// `bezier[k] = Σ_j BSPLINE_TO_BEZIER[k][j] · bspline[j]`.
pub const BSPLINE_TO_BEZIER: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [0.0, 4.0 / 6.0, 2.0 / 6.0, 0.0],
    [0.0, 2.0 / 6.0, 4.0 / 6.0, 0.0],
    [0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
];

/// Cubic Bernstein weights at `t`, with first and second derivatives.
#[inline]
pub fn bezier_curve<T: Real>(t: T) -> CurveWeights<T> {
    let c = |x: f64| T::from_f64(x);
    let s = T::ONE - t;
    let t2 = t * t;
    let s2 = s * s;
    CurveWeights {
        p: [s2 * s, c(3.0) * t * s2, c(3.0) * t2 * s, t2 * t],
        d1: [
            -c(3.0) * s2,
            c(3.0) * s2 - c(6.0) * t * s,
            c(6.0) * t * s - c(3.0) * t2,
            c(3.0) * t2,
        ],
        d2: [
            c(6.0) * s,
            c(18.0) * t - c(12.0),
            c(6.0) - c(18.0) * t,
            c(6.0) * t,
        ],
    }
}

/// Weights of the 16 points of a bicubic Bézier patch at `(u, v)`.
pub fn bezier_patch_weights<T: Real>(u: T, v: T) -> PatchWeights<T, 16> {
    PatchWeights::tensor(&bezier_curve(u), &bezier_curve(v))
}

/// Evaluates a bicubic Bézier patch.
pub fn eval_bezier_patch<T: Real, const D: usize>(
    points: &[[T; D]; 16],
    u: T,
    v: T,
) -> PatchEval<T, D> {
    bezier_patch_weights(u, v).eval(points)
}

#[cfg(test)]
mod tests {
    use super::super::bspline::bspline_curve;
    use super::*;

    #[test]
    fn bspline_to_bezier_change_of_basis() {
        // N(t) = B(t) · Q for every t (weights, derivatives).
        for k in 0..=8 {
            let t = k as f64 / 8.0;
            let n = bspline_curve(t);
            let b = bezier_curve(t);
            for j in 0..4 {
                let via =
                    |w: &[f64; 4]| (0..4).map(|i| w[i] * BSPLINE_TO_BEZIER[i][j]).sum::<f64>();
                assert!((via(&b.p) - n.p[j]).abs() < 1e-15);
                assert!((via(&b.d1) - n.d1[j]).abs() < 1e-14);
                assert!((via(&b.d2) - n.d2[j]).abs() < 1e-14);
            }
        }
    }
}
