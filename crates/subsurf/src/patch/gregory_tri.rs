//! The quartic Gregory triangle, OpenSubdiv's end cap of irregular Loop regions, and the
//! quartic Bézier triangle it extends.
//!
//! # Bézier triangle
//!
//! The 15 quartic Bernstein polynomials in barycentric `(u, v, w)`, `w = 1 − u − v`:
//! `B_ijk = 4!/(i! j! k!) uⁱ vʲ wᵏ`, `i + j + k = 4`, ordered in rows of constant `j`
//! (index 0 is `p004`, 4 is `p400`, 14 is `p040`):
//!
//! ```text
//!                     14
//!                  12    13
//!                9    10    11
//!             5     6     7     8
//!          0     1     2     3     4
//! ```
//!
//! # Gregory triangle (18 points)
//!
//! The three interior Bézier points (6, 7, 10) are each replaced by a pair of face points
//! blended rationally (Gregory 1974; Loop, Schaefer, Ni & Castaño 2009 for the quad case),
//! so that the cross-boundary tangents of the three edges are independent. The points are
//! grouped by corner as in OpenSubdiv: per corner `k` the corner point, its two edge points
//! and its two face points (`5k .. 5k + 5`), then the three mid-edge points 15, 16, 17
//! (of edges 0, 1, 2). The face-point pair of corner 0 blends with `u/(u+v)` and
//! `v/(u+v)`, of corner 1 with `v/(v+w)`, `w/(v+w)`, of corner 2 with `w/(w+u)`, `u/(w+u)`.
//!
//! Derivative weights are the Bézier derivatives with the same rational blend (the blend
//! itself is not differentiated), which is what OpenSubdiv evaluates.

use super::weights::{PatchEval, PatchWeights};
use crate::real::Real;

/// Exponents `(i, j, k)` of `uⁱ vʲ wᵏ` of Bézier point `n`.
fn bezier_exponents(n: usize) -> (u8, u8, u8) {
    let mut n = n;
    for j in 0..5u8 {
        let row = 5 - j as usize;
        if n < row {
            let i = n as u8;
            return (i, j, 4 - i - j);
        }
        n -= row;
    }
    (0, 4, 0)
}

fn factorial(n: u8) -> f64 {
    (1..=n).map(f64::from).product()
}

/// `∂^a_u ∂^b_v ∂^c_w` of `uⁱ vʲ wᵏ` (treating `u, v, w` as independent).
fn partial<T: Real>(uvw: [T; 3], e: (u8, u8, u8), d: (u8, u8, u8)) -> T {
    let (i, j, k) = e;
    let (a, b, c) = d;
    if a > i || b > j || c > k {
        return T::ZERO;
    }
    let falling = |n: u8, m: u8| (0..m).map(|x| (n - x) as f64).product::<f64>();
    let pow = |x: T, n: u8| (0..n).fold(T::ONE, |acc, _| acc * x);
    T::from_f64(falling(i, a) * falling(j, b) * falling(k, c))
        * pow(uvw[0], i - a)
        * pow(uvw[1], j - b)
        * pow(uvw[2], k - c)
}

/// Weights of the 15 points of a quartic Bézier triangle at `(s, t)`, with derivatives
/// with respect to `s` and `t` (`u = s`, `v = t`, `w = 1 − s − t`, so `∂/∂s = ∂u − ∂w`).
pub fn bezier_triangle_weights<T: Real>(s: T, t: T) -> PatchWeights<T, 15> {
    let uvw = [s, t, T::ONE - s - t];
    // Each derivative as a combination of (independent) partials in u, v, w.
    type Terms = &'static [(f64, (u8, u8, u8))];
    const P: Terms = &[(1.0, (0, 0, 0))];
    const DS: Terms = &[(1.0, (1, 0, 0)), (-1.0, (0, 0, 1))];
    const DT: Terms = &[(1.0, (0, 1, 0)), (-1.0, (0, 0, 1))];
    const DSS: Terms = &[(1.0, (2, 0, 0)), (-2.0, (1, 0, 1)), (1.0, (0, 0, 2))];
    const DST: Terms = &[
        (1.0, (1, 1, 0)),
        (-1.0, (1, 0, 1)),
        (-1.0, (0, 1, 1)),
        (1.0, (0, 0, 2)),
    ];
    const DTT: Terms = &[(1.0, (0, 2, 0)), (-2.0, (0, 1, 1)), (1.0, (0, 0, 2))];
    let eval = |terms: Terms| -> [T; 15] {
        std::array::from_fn(|n| {
            let e = bezier_exponents(n);
            let multinomial = factorial(4) / (factorial(e.0) * factorial(e.1) * factorial(e.2));
            let sum = terms.iter().fold(T::ZERO, |acc, &(c, d)| {
                acc + T::from_f64(c) * partial(uvw, e, d)
            });
            T::from_f64(multinomial) * sum
        })
    };
    PatchWeights {
        p: eval(P),
        du: eval(DS),
        dv: eval(DT),
        duu: eval(DSS),
        duv: eval(DST),
        dvv: eval(DTT),
    }
}

/// Where each of the 18 Gregory points takes its Bézier weight: `(bezier index, blend)`,
/// blend `None` for a plain point or `Some(r)` for the face point weighted by rational
/// factor `r` (see [`blend_factors`]).
const GREGORY_FROM_BEZIER: [(usize, Option<usize>); 18] = [
    (0, None),
    (1, None),
    (5, None),
    (6, Some(0)),
    (6, Some(1)),
    (4, None),
    (8, None),
    (3, None),
    (7, Some(2)),
    (7, Some(3)),
    (14, None),
    (12, None),
    (13, None),
    (10, Some(4)),
    (10, Some(5)),
    (2, None),
    (11, None),
    (9, None),
];

/// The six rational blend factors at `(s, t)`: `u/(u+v), v/(u+v), v/(v+w), w/(v+w),
/// w/(w+u), u/(w+u)`, each pair `(1, 0)` where its denominator vanishes (at the corner
/// opposite the pair's edge the face points have no weight anyway).
pub fn blend_factors<T: Real>(s: T, t: T) -> [T; 6] {
    let (u, v, w) = (s, t, T::ONE - s - t);
    let pair = |a: T, b: T| {
        let d = a + b;
        if d > T::ZERO {
            (a / d, b / d)
        } else {
            (T::ONE, T::ZERO)
        }
    };
    let (g0, g1) = pair(u, v);
    let (g2, g3) = pair(v, w);
    let (g4, g5) = pair(w, u);
    [g0, g1, g2, g3, g4, g5]
}

/// Weights of the 18 points of a quartic Gregory triangle at `(s, t)`.
pub fn gregory_triangle_weights<T: Real>(s: T, t: T) -> PatchWeights<T, 18> {
    let b = bezier_triangle_weights(s, t);
    let g = blend_factors(s, t);
    let convert = |wb: &[T; 15]| -> [T; 18] {
        GREGORY_FROM_BEZIER.map(|(n, r)| match r {
            None => wb[n],
            Some(r) => wb[n] * g[r],
        })
    };
    PatchWeights {
        p: convert(&b.p),
        du: convert(&b.du),
        dv: convert(&b.dv),
        duu: convert(&b.duu),
        duv: convert(&b.duv),
        dvv: convert(&b.dvv),
    }
}

/// Evaluates a quartic Gregory triangle (see [`gregory_triangle_weights`]).
pub fn eval_gregory_triangle<T: Real, const D: usize>(
    points: &[[T; D]; 18],
    s: T,
    t: T,
) -> PatchEval<T, D> {
    gregory_triangle_weights(s, t).eval(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bezier_exponents_follow_rows() {
        assert_eq!(bezier_exponents(0), (0, 0, 4));
        assert_eq!(bezier_exponents(4), (4, 0, 0));
        assert_eq!(bezier_exponents(5), (0, 1, 3));
        assert_eq!(bezier_exponents(8), (3, 1, 0));
        assert_eq!(bezier_exponents(10), (1, 2, 1));
        assert_eq!(bezier_exponents(13), (1, 3, 0));
        assert_eq!(bezier_exponents(14), (0, 4, 0));
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let (s, t, h) = (0.3f64, 0.2, 1e-5);
        let w = gregory_triangle_weights(s, t);
        let b = |s, t| bezier_triangle_weights(s, t);
        let (bs, bt) = (
            (b(s + h, t).p, b(s - h, t).p),
            (b(s, t + h).p, b(s, t - h).p),
        );
        let bz = b(s, t);
        for n in 0..15 {
            assert!(((bs.0[n] - bs.1[n]) / (2.0 * h) - bz.du[n]).abs() < 1e-8);
            assert!(((bt.0[n] - bt.1[n]) / (2.0 * h) - bz.dv[n]).abs() < 1e-8);
            let dss = (b(s + h, t).du[n] - b(s - h, t).du[n]) / (2.0 * h);
            let dst = (b(s, t + h).du[n] - b(s, t - h).du[n]) / (2.0 * h);
            let dtt = (b(s, t + h).dv[n] - b(s, t - h).dv[n]) / (2.0 * h);
            assert!((dss - bz.duu[n]).abs() < 1e-7);
            assert!((dst - bz.duv[n]).abs() < 1e-7);
            assert!((dtt - bz.dvv[n]).abs() < 1e-7);
        }
        assert!((w.p.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn coincident_face_points_give_the_bezier_triangle() {
        let bez: [[f64; 1]; 15] = std::array::from_fn(|n| [(n * n) as f64 * 0.1 - 0.7]);
        let greg: [[f64; 1]; 18] = std::array::from_fn(|k| bez[GREGORY_FROM_BEZIER[k].0]);
        for (s, t) in [(0.1, 0.2), (0.0, 0.0), (0.5, 0.5), (0.0, 1.0), (0.33, 0.33)] {
            let a = eval_gregory_triangle(&greg, s, t);
            let b = bezier_triangle_weights(s, t).eval(&bez);
            assert!((a.p[0] - b.p[0]).abs() < 1e-13);
            assert!((a.du[0] - b.du[0]).abs() < 1e-12);
            assert!((a.dvv[0] - b.dvv[0]).abs() < 1e-11);
        }
    }
}
