//! The regular Loop patch: the quartic three-direction box spline over 12 points, with
//! OpenSubdiv's boundary and corner variants.
//!
//! # Points and parameters
//!
//! A regular Loop triangle (all three corners of valence 6) is one quartic box-spline
//! patch (Stam 1998, "Evaluation of Loop subdivision surfaces"). Its 12 points, in
//! OpenSubdiv's order, with the patch's own triangle spanned by 4, 5, 8:
//!
//! ```text
//!          10 ─── 11
//!         ╱  ╲   ╱  ╲
//!        7 ─── 8 ─── 9
//!       ╱ ╲   ╱ ╲   ╱ ╲
//!      3 ─── 4 ─── 5 ─── 6
//!       ╲   ╱ ╲   ╱ ╲   ╱
//!        0 ─── 1 ─── 2
//! ```
//!
//! Corner 0 of the triangle is point 4 at `(s, t) = (0, 0)`, corner 1 is point 5 at
//! `(1, 0)`, corner 2 is point 8 at `(0, 1)`; edge `k` joins corner `k` and corner `k + 1`
//! (edge 0 is `t = 0`, edge 1 is `s + t = 1`, edge 2 is `s = 0`).
//!
//! The basis is a polynomial of degree 4 in `(s, t)`: `B_i(s, t) = Σ_m C[i][m] M_m(s, t)` with
//! the 15 monomials `M = (1, s, t, s², st, t², …, t⁴)` and Stam's coefficient matrix `C`
//! (a common factor 1/12). Derivatives differentiate the monomials, so one table serves the
//! position and all derivatives.
//!
//! # Boundaries: phantom points
//!
//! As for the bicubic patch ([`super::bspline`]), a patch on a boundary lacks the points
//! beyond it; they are extrapolated as `P = A + B − C` from points that exist, and the
//! extrapolation is folded into the weights so the missing points get weight zero. The
//! 5-bit boundary mask of the [`super::PatchParam`] encodes which edges and which corners
//! are on the boundary:
//!
//! | bits 3..5 | bits 0..3 mean |
//! |---|---|
//! | 0 | boundary edges (bit `k`: edge `k`) |
//! | 1 | boundary corners only (bit `k`: corner `k`) |
//! | 2 | boundary edges, and the corner opposite each one is a boundary corner too |
//!
//! Along a boundary edge the three phantom points beyond it mirror the row inside it
//! (`P = B_near + B_next − I`); where the adjacent edge is a boundary too, the corner is
//! reflected through itself (`P = 2 B − I`). At a boundary corner whose edges are interior
//! the two phantom points of the missing wedge are extrapolated across that corner.
//! The rules of edge 0 and corner 0 are written out below; the others are the same rules
//! turned by the triangle's rotation [`BOX_SPLINE_ROTATE`].

use super::weights::{PatchEval, PatchWeights};
use crate::real::Real;

/// Stam's coefficients (times 12) of the 12 box-spline basis functions in the monomials
/// `1, s, t, s², st, t², s³, s²t, st², t³, s⁴, s³t, s²t², st³, t⁴`.
pub const BOX_SPLINE_COEFFS: [[i8; 15]; 12] = [
    [1, -2, -4, 0, 6, 6, 2, 0, -6, -4, -1, -2, 0, 2, 1],
    [1, 2, -2, 0, -6, 0, -4, 0, 6, 2, 2, 4, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -1, -2, 0, 0, 0],
    [1, -4, -2, 6, 6, 0, -4, -6, 0, 2, 1, 2, 0, -2, -1],
    [6, 0, 0, -12, -12, -12, 8, 12, 12, 8, -1, -2, 0, -2, -1],
    [1, 4, 2, 6, 6, 0, -4, -6, -12, -4, -1, -2, 0, 4, 2],
    [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0],
    [1, -2, 2, 0, -6, 0, 2, 6, 0, -4, -1, -2, 0, 4, 2],
    [1, 2, 4, 0, 6, 6, -4, -12, -6, -4, 2, 4, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 2, 6, 6, 2, -1, -2, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -2, -1],
    [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1],
];

/// Exponents `(a, b)` of monomial `m = s^a t^b`, in the order of [`BOX_SPLINE_COEFFS`].
pub const BOX_SPLINE_MONOMIALS: [(u8, u8); 15] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (2, 0),
    (1, 1),
    (0, 2),
    (3, 0),
    (2, 1),
    (1, 2),
    (0, 3),
    (4, 0),
    (3, 1),
    (2, 2),
    (1, 3),
    (0, 4),
];

/// The rotation of the 12 points that takes corner `k` to corner `k + 1` (and edge `k` to
/// edge `k + 1`): point `i` plays the part of point `BOX_SPLINE_ROTATE[i]` one rotation on.
pub const BOX_SPLINE_ROTATE: [usize; 12] = [6, 9, 11, 2, 5, 8, 10, 1, 4, 7, 0, 3];

/// `P[phantom] = P[a] + P[b] − P[c]`.
#[derive(Clone, Copy)]
struct Phantom {
    phantom: usize,
    a: usize,
    b: usize,
    c: usize,
}

const fn ph(phantom: usize, a: usize, b: usize, c: usize) -> Phantom {
    Phantom { phantom, a, b, c }
}

/// Edge 0 (points 4–5) on the boundary: points 0, 1, 2 are phantoms. The first and last
/// depend on whether edge 2 (resp. edge 1) is a boundary as well: `[when not, when so]`.
const EDGE0_FIRST: [Phantom; 2] = [ph(0, 4, 3, 7), ph(0, 4, 4, 8)];
const EDGE0_MIDDLE: Phantom = ph(1, 4, 5, 8);
const EDGE0_LAST: [Phantom; 2] = [ph(2, 5, 6, 9), ph(2, 5, 5, 8)];
/// Corner 0 (point 4) on the boundary, its edges not: points 3 and 0 are phantoms.
const CORNER0: [Phantom; 2] = [ph(3, 4, 7, 8), ph(0, 4, 1, 5)];

/// The rule turned `k` times by [`BOX_SPLINE_ROTATE`].
fn rotated(p: Phantom, k: usize) -> Phantom {
    let r = |mut i: usize| {
        for _ in 0..k {
            i = BOX_SPLINE_ROTATE[i];
        }
        i
    };
    ph(r(p.phantom), r(p.a), r(p.b), r(p.c))
}

/// Boundary edges and corners (bit `k` for edge / corner `k`) of a 5-bit boundary mask.
pub fn decode_boundary(mask: u8) -> (u8, u8) {
    let low = mask & 7;
    match (mask >> 3) & 3 {
        0 => (low, 0),
        1 => (0, low),
        2 => (low, ((low & 1) << 2) | (low >> 1)),
        _ => (low, 0),
    }
}

fn fold<T: Real>(w: &mut [T; 12], p: Phantom) {
    let x = w[p.phantom];
    w[p.phantom] = T::ZERO;
    w[p.a] += x;
    w[p.b] += x;
    w[p.c] -= x;
}

/// Folds the phantom points of a boundary mask into one weight vector.
pub fn fold_boundary<T: Real>(w: &mut [T; 12], mask: u8) {
    let (edges, corners) = decode_boundary(mask);
    let on = |bits: u8, k: usize| bits & (1 << (k % 3)) != 0;
    for k in 0..3 {
        if !on(edges, k) {
            continue;
        }
        fold(w, rotated(EDGE0_FIRST[on(edges, k + 2) as usize], k));
        fold(w, rotated(EDGE0_MIDDLE, k));
        fold(w, rotated(EDGE0_LAST[on(edges, k + 1) as usize], k));
    }
    for k in 0..3 {
        if on(corners, k) {
            for p in CORNER0 {
                fold(w, rotated(p, k));
            }
        }
    }
}

/// `∂^ds_s ∂^dt_t` of every monomial at `(s, t)`.
fn monomial_derivatives<T: Real>(s: T, t: T, ds: u8, dt: u8) -> [T; 15] {
    let pow = |x: T, n: u8| (0..n).fold(T::ONE, |acc, _| acc * x);
    let falling = |n: u8, k: u8| (0..k).map(|i| n as f64 - i as f64).product::<f64>();
    BOX_SPLINE_MONOMIALS.map(|(a, b)| {
        if a < ds || b < dt {
            T::ZERO
        } else {
            T::from_f64(falling(a, ds) * falling(b, dt)) * pow(s, a - ds) * pow(t, b - dt)
        }
    })
}

fn weights_of<T: Real>(m: &[T; 15]) -> [T; 12] {
    let twelfth = T::from_f64(1.0 / 12.0);
    BOX_SPLINE_COEFFS.map(|row| {
        let sum = row
            .iter()
            .zip(m)
            .filter(|(&c, _)| c != 0)
            .fold(T::ZERO, |acc, (&c, &x)| acc + T::from_f64(c as f64) * x);
        sum * twelfth
    })
}

/// Weights of the 12 points of a regular Loop patch at `(s, t)` (`s + t ≤ 1` inside the
/// patch) with the given 5-bit boundary mask (0 for an interior patch). Phantom points get
/// weight 0.
pub fn box_spline_patch_weights<T: Real>(s: T, t: T, boundary: u8) -> PatchWeights<T, 12> {
    let at = |ds, dt| weights_of(&monomial_derivatives(s, t, ds, dt));
    let mut w = PatchWeights {
        p: at(0, 0),
        du: at(1, 0),
        dv: at(0, 1),
        duu: at(2, 0),
        duv: at(1, 1),
        dvv: at(0, 2),
    };
    if boundary != 0 {
        for v in [
            &mut w.p, &mut w.du, &mut w.dv, &mut w.duu, &mut w.duv, &mut w.dvv,
        ] {
            fold_boundary(v, boundary);
        }
    }
    w
}

/// Evaluates a regular Loop patch (see [`box_spline_patch_weights`]).
pub fn eval_box_spline_patch<T: Real, const D: usize>(
    points: &[[T; D]; 12],
    s: T,
    t: T,
    boundary: u8,
) -> PatchEval<T, D> {
    box_spline_patch_weights(s, t, boundary).eval(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 12 points on the regular triangular lattice, with the patch's corners at
    /// (0,0), (1,0), (0,1) (lattice basis e1 = (1,0), e2 = (0,1) in (s, t)).
    fn lattice() -> [[f64; 2]; 12] {
        let st = [
            (0, -1),
            (1, -1),
            (2, -1),
            (-1, 0),
            (0, 0),
            (1, 0),
            (2, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
            (-1, 2),
            (0, 2),
        ];
        st.map(|(a, b)| [a as f64, b as f64])
    }

    #[test]
    fn partition_of_unity_and_linear_precision() {
        let pts = lattice();
        for (s, t) in [(0.0, 0.0), (0.2, 0.3), (1.0, 0.0), (0.0, 1.0), (0.5, 0.5)] {
            let w = box_spline_patch_weights(s, t, 0);
            assert!((w.p.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            for d in [&w.du, &w.dv, &w.duu, &w.duv, &w.dvv] {
                assert!(d.iter().sum::<f64>().abs() < 1e-14);
            }
            // Box splines reproduce linear functions: the lattice maps to (s, t).
            let e = w.eval(&pts);
            assert!((e.p[0] - s).abs() < 1e-14 && (e.p[1] - t).abs() < 1e-14);
            assert!((e.du[0] - 1.0).abs() < 1e-14 && e.du[1].abs() < 1e-14);
            assert!(e.dv[0].abs() < 1e-14 && (e.dv[1] - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn corner_is_the_loop_limit_of_a_regular_vertex() {
        // Loop's limit position of a valence-6 vertex: (1/2) P + (1/12) Σ ring.
        let w = box_spline_patch_weights(0.0f64, 0.0, 0);
        assert!((w.p[4] - 0.5).abs() < 1e-15);
        for ring in [0, 1, 3, 5, 7, 8] {
            assert!((w.p[ring] - 1.0 / 12.0).abs() < 1e-15, "point {ring}");
        }
    }

    #[test]
    fn rotation_is_a_symmetry_of_the_basis() {
        // Rotating corners (s, t, w) → (w, s, t) permutes the points by BOX_SPLINE_ROTATE.
        let (s, t) = (0.15f64, 0.6);
        let w = box_spline_patch_weights(s, t, 0).p;
        let r = box_spline_patch_weights(1.0 - s - t, s, 0).p;
        for i in 0..12 {
            assert!((w[i] - r[BOX_SPLINE_ROTATE[i]]).abs() < 1e-15, "point {i}");
        }
    }

    #[test]
    fn boundary_weights_ignore_phantoms_and_keep_linear_precision() {
        let pts = lattice();
        for mask in [
            1u8,
            2,
            4,
            3,
            5,
            6,
            7,
            8 + 1,
            8 + 2,
            8 + 4,
            8 + 7,
            16 + 1,
            16 + 2,
            16 + 4,
        ] {
            let (edges, corners) = decode_boundary(mask);
            let w = box_spline_patch_weights(0.3f64, 0.25, mask);
            for k in 0..3 {
                if edges & (1 << k) != 0 {
                    for p in [EDGE0_FIRST[0], EDGE0_MIDDLE, EDGE0_LAST[0]] {
                        assert_eq!(w.p[rotated(p, k).phantom], 0.0, "mask {mask}");
                    }
                }
                if corners & (1 << k) != 0 {
                    for p in CORNER0 {
                        assert_eq!(w.p[rotated(p, k).phantom], 0.0, "mask {mask}");
                    }
                }
            }
            // Extrapolation is affine, so linear functions are still reproduced.
            let e = w.eval(&pts);
            assert!((e.p[0] - 0.3).abs() < 1e-14 && (e.p[1] - 0.25).abs() < 1e-14);
            assert!((e.du[0] - 1.0).abs() < 1e-14 && (e.dv[1] - 1.0).abs() < 1e-14);
        }
    }
}
