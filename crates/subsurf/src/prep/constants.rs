//! Per-valence constants of the p-rep (Myles, Yeo & Peters 2008, eqs. (2)–(4); spec §2).
//!
//! ```text
//! c_n      = cos(2π/n)
//! λ_n      = (c_n + 5 + sqrt((c_n + 9)(c_n + 1))) / 16     subdominant Catmull-Clark eigenvalue
//! w_n      = 16 λ_n − 4                                     (= the Catmull-Clark tangent weight A_n)
//! σ_n      = 0.53 if n = 3, 1/(4 λ_n) if n > 3              tangent scale
//! c^k_n    = cos(2πk/n),  s^k_n = sin(2πk/n)                (k is an index, not a power)
//! ```
//!
//! Everything is computed once in `f64` and rounded to the target scalar, so both patches
//! along an edge read the very same constant.

use crate::real::Real;

/// Smallest valence the p-rep handles (interior Catmull-Clark stencils need `n >= 3`).
pub const MIN_VALENCE: usize = 3;
/// Largest valence supported; larger vertices are refused by [`super::check_input`].
pub const MAX_VALENCE: usize = 64;

/// `c_n = cos(2π/n)`.
pub fn c_n(n: usize) -> f64 {
    (2.0 * std::f64::consts::PI / n as f64).cos()
}

/// Subdominant eigenvalue `λ_n` of the Catmull-Clark subdivision matrix.
pub fn lambda_n(n: usize) -> f64 {
    let c = c_n(n);
    (c + 5.0 + ((c + 9.0) * (c + 1.0)).sqrt()) / 16.0
}

/// Tangent weight `w_n = 16 λ_n − 4`.
pub fn w_n(n: usize) -> f64 {
    16.0 * lambda_n(n) - 4.0
}

/// Tangent scale `σ_n` (spec §9 item 4: `1/(4 λ_n)`, with the paper's 0.53 at n = 3).
pub fn sigma_n(n: usize) -> f64 {
    if n == 3 {
        0.53
    } else {
        1.0 / (4.0 * lambda_n(n))
    }
}

/// The weights of one valence, rounded to `T`.
#[derive(Debug, Clone)]
pub struct Valence<T> {
    /// `n`.
    pub n: usize,
    /// `c_n` (0 for n = 4).
    pub c: T,
    /// Limit-point weights (2): `n/(n+5)` on `p0`, `4/(n(n+5))` on edge neighbours,
    /// `1/(n(n+5))` on diagonal neighbours.
    pub limit: [T; 3],
    /// `e1` weights of (3), premultiplied by `σ_n / (3 (2 + w_n))`: `(alpha_1, beta_1)` for
    /// `j = 1..n`, i.e. on `p_{2j-1}` and `p_{2j}`.
    pub e1: Vec<[T; 2]>,
    /// `e2` weights, as `e1` with sines.
    pub e2: Vec<[T; 2]>,
    /// `c^k_n` for k = 0..n-1.
    pub cos: Vec<T>,
    /// `s^k_n` for k = 0..n-1.
    pub sin: Vec<T>,
}

impl<T: Real> Valence<T> {
    /// Constants of valence `n` (`n >= 3`).
    pub fn new(n: usize) -> Self {
        let nf = n as f64;
        let d = 3.0; // degree of g (spec §9 item 6)
        let w = w_n(n);
        let s = sigma_n(n) / (d * (2.0 + w));
        let ang = |j: usize| 2.0 * std::f64::consts::PI * j as f64 / nf;
        let e1 = (1..=n)
            .map(|j| {
                let (a, b) = (ang(j - 1), ang(j));
                [
                    T::from_f64(s * w * a.cos()),
                    T::from_f64(s * (a.cos() + b.cos())),
                ]
            })
            .collect();
        let e2 = (1..=n)
            .map(|j| {
                let (a, b) = (ang(j - 1), ang(j));
                [
                    T::from_f64(s * w * a.sin()),
                    T::from_f64(s * (a.sin() + b.sin())),
                ]
            })
            .collect();
        let den = nf * (nf + 5.0);
        Valence {
            n,
            c: T::from_f64(if n == 4 { 0.0 } else { c_n(n) }),
            limit: [
                T::from_f64(nf / (nf + 5.0)),
                T::from_f64(4.0 / den),
                T::from_f64(1.0 / den),
            ],
            e1,
            e2,
            cos: (0..n).map(|k| T::from_f64(ang(k).cos())).collect(),
            sin: (0..n).map(|k| T::from_f64(ang(k).sin())).collect(),
        }
    }
}

/// Constants for every valence `0..=max` (entries below `MIN_VALENCE` are unused).
#[derive(Debug, Clone)]
pub struct ValenceTable<T> {
    table: Vec<Valence<T>>,
}

impl<T: Real> ValenceTable<T> {
    /// Table for valences up to `max` (at most `MAX_VALENCE`).
    pub fn new(max: usize) -> Self {
        let max = max.clamp(MIN_VALENCE, MAX_VALENCE);
        ValenceTable {
            table: (0..=max)
                .map(|n| Valence::new(n.max(MIN_VALENCE)))
                .collect(),
        }
    }

    /// Constants of valence `n`.
    #[inline]
    pub fn get(&self, n: usize) -> &Valence<T> {
        &self.table[n]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spec §2 table, printed to 12 digits.
    #[test]
    fn table_matches_spec() {
        let rows = [
            (
                3,
                -0.5,
                0.410097050801,
                2.561552812809,
                0.53,
                0.038729501535,
            ),
            (4, 0.0, 0.5, 4.0, 0.5, 1.0 / 36.0),
            (
                5,
                0.309016994375,
                0.549988354518,
                4.799813672293,
                0.454555079114,
                0.022282722293,
            ),
            (
                6,
                0.5,
                0.579682326102,
                5.274917217635,
                0.431270695591,
                0.019760623280,
            ),
            (
                7,
                0.623489801859,
                0.598510283482,
                5.576164535708,
                0.417703767002,
                0.018377978507,
            ),
            (
                8,
                std::f64::consts::FRAC_1_SQRT_2, // printed 0.707106781187
                0.611116526695,
                5.777864427113,
                0.409087283815,
                0.017532116845,
            ),
        ];
        for (n, c, l, w, s, f) in rows {
            assert!((c_n(n) - c).abs() < 1e-12, "c_{n}");
            assert!((lambda_n(n) - l).abs() < 1e-12, "lambda_{n}");
            assert!((w_n(n) - w).abs() < 1e-12, "w_{n}");
            assert!((sigma_n(n) - s).abs() < 1e-12, "sigma_{n}");
            assert!(
                (sigma_n(n) / (3.0 * (2.0 + w_n(n))) - f).abs() < 1e-12,
                "factor_{n}"
            );
        }
    }

    /// `w_n` is the usual Catmull-Clark tangent weight `A_n = 1 + c_n + cos(π/n) sqrt(2(9 + c_n))`.
    #[test]
    fn w_is_catmull_clark_weight() {
        for n in 3..=16 {
            let c = c_n(n);
            let a = 1.0 + c + (std::f64::consts::PI / n as f64).cos() * (2.0 * (9.0 + c)).sqrt();
            assert!((w_n(n) - a).abs() < 1e-12, "n = {n}");
        }
    }

    /// Limit weights sum to one; tangent weights sum to zero (translation invariance).
    #[test]
    fn weights_are_affine() {
        for n in 3..=16 {
            let v = Valence::<f64>::new(n);
            let l = v.limit[0] + n as f64 * (v.limit[1] + v.limit[2]);
            assert!((l - 1.0).abs() < 1e-15);
            let s1: f64 = v.e1.iter().map(|w| w[0] + w[1]).sum();
            let s2: f64 = v.e2.iter().map(|w| w[0] + w[1]).sum();
            assert!(s1.abs() < 1e-14 && s2.abs() < 1e-14, "n = {n}: {s1} {s2}");
        }
    }
}
