//! The 20-point bicubic Gregory patch used as an end cap around extraordinary vertices
//! (OpenSubdiv's `GREGORY_BASIS` end cap; Loop, Schaefer, Ni & Castaño 2009, "Approximating
//! subdivision surfaces with Gregory patches for hardware tessellation").
//!
//! A Gregory patch is a bicubic Bézier patch whose four interior points are replaced by
//! pairs of *face points* `f+`, `f−`, blended rationally so that the cross-boundary
//! derivative along each edge depends on one point of each pair only. The points are grouped
//! by corner — five per corner `k`: the corner `P_k`, the edge points `e_k+` (along the edge
//! leaving corner `k`) and `e_k−` (along the edge arriving at it), and the face points:
//!
//! ```text
//!      P3        e3−     e2+        P2
//!       15 ──── 17 ───── 11 ──── 10
//!        │       │        │        │
//!        │       19 f3−   13 f2+   │
//!   e3+ 16 ── 18 f3+        14 f2− ── 12 e2−
//!        │                          │
//!    e0− 2 ── 4 f0−         8 f1+ ── 6 e1+
//!        │       3 f0+    9 f1−    │
//!        │       │        │        │
//!        0 ───── 1 ────── 7 ────── 5
//!      P0        e0+     e1−        P1
//! ```
//!
//! The Bézier point `b(1,1)` near corner 0 is `(u f0+ + v f0−)/(u + v)`, and likewise
//!
//! ```text
//! b(2,1) = ((1−u) f1− + v f1+) / (1−u + v)
//! b(2,2) = ((1−u) f2+ + (1−v) f2−) / (2−u−v)
//! b(1,2) = (u f3− + (1−v) f3+) / (1+u−v)
//! ```
//!
//! At a corner where a denominator vanishes the pair's weights are taken as `(0, 1)` (the
//! corresponding Bézier basis function is zero there). Each pair's two rational weights sum
//! to one, so when `f+ = f−` for every pair the patch is exactly the bicubic Bézier patch.
//!
//! Derivatives: [`GregoryDerivatives::Exact`] differentiates the rational basis (quotient
//! and product rules); [`GregoryDerivatives::BezierApproximation`] holds the rational
//! weights constant, i.e. differentiates the Bézier patch with the interior points frozen at
//! `(u, v)`, which is OpenSubdiv's default (its `OPENSUBDIV_GREGORY_EVAL_TRUE_DERIVATIVES`
//! switches to the exact form). Both agree on positions; the approximation is exact along the
//! patch boundary.
//!
//! Building the 20 points from limit stencils is the patch table builder's work; this file
//! only evaluates.

use super::bezier::bezier_curve;
use super::weights::{PatchEval, PatchWeights};
use crate::real::Real;

/// How derivatives of the rational interior weights are taken (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum GregoryDerivatives {
    /// True derivatives of the rational Gregory basis.
    #[default]
    Exact,
    /// OpenSubdiv's default: rational weights held constant when differentiating.
    BezierApproximation,
}

/// Gregory point index → Bézier `(column i along u, row j along v)` for the 12 boundary
/// points.
pub const GREGORY_BOUNDARY: [(usize, usize, usize); 12] = [
    (0, 0, 0),
    (1, 1, 0),
    (7, 2, 0),
    (5, 3, 0),
    (2, 0, 1),
    (6, 3, 1),
    (16, 0, 2),
    (12, 3, 2),
    (15, 0, 3),
    (17, 1, 3),
    (11, 2, 3),
    (10, 3, 3),
];

/// The face-point pairs `(f+, f−)` and the Bézier `(column, row)` they replace, corner by
/// corner.
pub const GREGORY_INTERIOR: [(usize, usize, usize, usize); 4] =
    [(3, 4, 1, 1), (8, 9, 2, 1), (13, 14, 2, 2), (18, 19, 1, 2)];

/// Rational weight of the `f+` point of corner `k` at `(u, v)` with its partial derivatives
/// `(g, g_u, g_v, g_uu, g_uv, g_vv)`; the `f−` weight is `1 − g`. `None` where the
/// denominator vanishes (at the corner itself).
///
/// `g = N / D` with `N`, `D` linear: corner 0 `u/(u+v)`, corner 1 `v/(1−u+v)`,
/// corner 2 `(1−u)/(2−u−v)`, corner 3 `(1−v)/(1+u−v)`.
fn rational<T: Real>(k: usize, u: T, v: T) -> Option<[T; 6]> {
    let (n, nu, nv, d, du, dv) = rational_terms(k, u, v);
    if d <= T::ZERO {
        return None;
    }
    let g = n / d;
    let gu = (nu - g * du) / d;
    let gv = (nv - g * dv) / d;
    let two = T::from_f64(2.0);
    Some([
        g,
        gu,
        gv,
        -two * du * gu / d,
        -(dv * gu + du * gv) / d,
        -two * dv * gv / d,
    ])
}

/// The numerator and denominator of [`rational`]'s `g` with their partial derivatives:
/// `(N, N_u, N_v, D, D_u, D_v)`.
fn rational_terms<T: Real>(k: usize, u: T, v: T) -> (T, T, T, T, T, T) {
    let one = T::ONE;
    match k {
        0 => (u, one, T::ZERO, u + v, one, one),
        1 => (v, T::ZERO, one, one - u + v, -one, one),
        2 => (one - u, -one, T::ZERO, (one - u) + (one - v), -one, -one),
        _ => (one - v, T::ZERO, -one, u + (one - v), one, -one),
    }
}

/// The position weights of the 20 Gregory points at `(u, v)`: [`gregory_patch_weights`]'s
/// `p` (which it takes from here), without the derivative weights a position query does not
/// read.
pub fn gregory_position_weights<T: Real>(u: T, v: T) -> [T; 20] {
    let (bu, bv) = (bezier_curve(u).p, bezier_curve(v).p);
    let mut p = [T::ZERO; 20];
    for &(g, i, j) in &GREGORY_BOUNDARY {
        p[g] = bu[i] * bv[j];
    }
    for (k, &(plus, minus, i, j)) in GREGORY_INTERIOR.iter().enumerate() {
        let (n, _, _, d, _, _) = rational_terms(k, u, v);
        let g = if d <= T::ZERO { T::ZERO } else { n / d };
        let (a, b) = (bu[i], bv[j]);
        p[plus] = a * b * g;
        p[minus] = a * b * (T::ONE - g);
    }
    p
}

/// Weights of the 20 Gregory points at `(u, v)`.
pub fn gregory_patch_weights<T: Real>(
    u: T,
    v: T,
    derivatives: GregoryDerivatives,
) -> PatchWeights<T, 20> {
    let bu = bezier_curve(u);
    let bv = bezier_curve(v);
    let mut w = PatchWeights::<T, 20> {
        p: gregory_position_weights(u, v),
        ..Default::default()
    };
    for &(g, i, j) in &GREGORY_BOUNDARY {
        w.du[g] = bu.d1[i] * bv.p[j];
        w.dv[g] = bu.p[i] * bv.d1[j];
        w.duu[g] = bu.d2[i] * bv.p[j];
        w.duv[g] = bu.d1[i] * bv.d1[j];
        w.dvv[g] = bu.p[i] * bv.d2[j];
    }
    let two = T::from_f64(2.0);
    for (k, &(plus, minus, i, j)) in GREGORY_INTERIOR.iter().enumerate() {
        // (f+ weight, f- weight) with derivatives: (g, 1 - g); at a degenerate corner
        // (0, 1) without derivative contribution.
        let r = rational(k, u, v).unwrap_or([T::ZERO; 6]);
        let mut pair = [r, [T::ONE - r[0], -r[1], -r[2], -r[3], -r[4], -r[5]]];
        if derivatives == GregoryDerivatives::BezierApproximation {
            for q in pair.iter_mut() {
                for x in q[1..].iter_mut() {
                    *x = T::ZERO;
                }
            }
        }
        let (a, a1, a2) = (bu.p[i], bu.d1[i], bu.d2[i]);
        let (b, b1, b2) = (bv.p[j], bv.d1[j], bv.d2[j]);
        for (idx, q) in [plus, minus].into_iter().zip(pair) {
            let [g, gu, gv, guu, guv, gvv] = q;
            w.du[idx] = (a1 * g + a * gu) * b;
            w.dv[idx] = (b1 * g + b * gv) * a;
            w.duu[idx] = (a2 * g + two * a1 * gu + a * guu) * b;
            w.duv[idx] = a1 * b1 * g + a1 * b * gv + a * b1 * gu + a * b * guv;
            w.dvv[idx] = (b2 * g + two * b1 * gv + b * gvv) * a;
        }
    }
    w
}

/// Evaluates a 20-point Gregory patch.
pub fn eval_gregory_patch<T: Real, const D: usize>(
    points: &[[T; D]; 20],
    u: T,
    v: T,
    derivatives: GregoryDerivatives,
) -> PatchEval<T, D> {
    gregory_patch_weights(u, v, derivatives).eval(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The position-only weights are those of the full evaluation, bit for bit (which takes
    /// them from there), on a grid that holds the corners (where the rational weights fall
    /// back) and the edges; the full evaluation's agreement with OpenSubdiv is
    /// `tests/limit_osd.rs`'s.
    #[test]
    fn position_weights_are_the_full_weights() {
        let n = 24;
        for i in 0..=n {
            for j in 0..=n {
                let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                for d in [
                    GregoryDerivatives::Exact,
                    GregoryDerivatives::BezierApproximation,
                ] {
                    let full = gregory_patch_weights(u, v, d).p;
                    let pos = gregory_position_weights(u, v);
                    assert_eq!(pos.map(f32::to_bits), full.map(f32::to_bits), "({u}, {v})");
                }
                let (u, v) = (f64::from(u) * 0.999 + 1e-4, f64::from(v));
                let full = gregory_patch_weights(u, v, GregoryDerivatives::Exact).p;
                assert_eq!(gregory_position_weights(u, v), full, "({u}, {v})");
            }
        }
    }

    #[test]
    fn every_point_has_a_slot() {
        let mut seen = [false; 20];
        for &(g, _, _) in &GREGORY_BOUNDARY {
            seen[g] = true;
        }
        for &(p, m, _, _) in &GREGORY_INTERIOR {
            seen[p] = true;
            seen[m] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn rational_pairs_favour_the_edge_point_side() {
        // Along edge 0 (v = 0) the cross derivative only sees f0+ and f1-.
        let w = gregory_patch_weights(0.3f64, 0.0, GregoryDerivatives::Exact);
        assert_eq!(w.p[4], 0.0);
        assert_eq!(w.dv[4], 0.0);
        assert_eq!(w.dv[8], 0.0);
        assert!(w.dv[3] > 0.0 && w.dv[9] > 0.0);
    }
}
