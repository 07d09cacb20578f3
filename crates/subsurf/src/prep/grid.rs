//! Fast evaluation of p-rep patches on a tensor grid of parameters (positions and unit
//! normals), the CPU counterpart of the evaluation pass of Myles, Yeo & Peters (2008, §4).
//!
//! A patch is a polynomial of bidegree (3, 3) (a B-quad, `h = 0`) or (5, 5):
//!
//! ```text
//! B-quad:     x(u,v) = Σ_{i,j<4} g_ij B³_i(u) B³_j(v)
//! otherwise:  x(u,v) = Σ_{i,j<6} b_ij B⁵_i(u) B⁵_j(v),   b = E g Eᵀ + h   (eq. (10), see bezier)
//! ```
//!
//! On a grid `{u_i} × {v_j}` the tensor-product sum factors (Bernstein form, tabulated bases):
//!
//! 1. per row `v_j` contract along `v`: `c_i = Σ_j b_ij B_j(v_j)` and `c'_i = Σ_j b_ij B'_j(v_j)`
//!    (a curve in `u` and its cross derivative);
//! 2. per sample, with `d` the degree:
//!
//! ```text
//! x    = Σ_i c_i B^d_i(u),
//! ∂x/∂u = Σ_{i<d} (c_{i+1} − c_i) · d B^{d−1}_i(u),
//! ∂x/∂v = Σ_i c'_i B^d_i(u),       n = ∂x/∂u × ∂x/∂v / |∂x/∂u × ∂x/∂v|.
//! ```
//!
//! The bases `B^d_i(u)`, `d B^{d−1}_i(u)` are tabulated once per grid, one contiguous array
//! per basis function, so step 2 is a loop over the samples of a row with the row's
//! coefficients as loop invariants, which the compiler vectorizes (one SIMD lane per
//! sample). A bi-5 patch costs 17 three-vector multiply-adds per sample (6 + 5 + 6), a
//! B-quad 11 (4 + 3 + 4); the bi-5 row coefficients come from `g` and the sparse `h` without
//! forming the 36 bi-5 control points.

use super::patch_pass::H_SLOTS;
use crate::real::Real;
use crate::util::vec3::V3;

/// Bernstein bases of degree 3 and 5 (values and derivatives) at one `v` parameter.
#[derive(Debug, Clone, Copy)]
struct Row<T> {
    b3: [T; 4],
    d3: [T; 4],
    b5: [T; 6],
    d5: [T; 6],
}

/// `B^d_i(t)` for `i = 0..=d`.
fn bernstein<T: Real, const N: usize>(t: T) -> [T; N] {
    let s = T::one() - t;
    // Pascal's triangle on (s, t): exact binomials, d multiplications per entry.
    let mut b = [T::zero(); N];
    b[0] = T::one();
    for d in 1..N {
        let mut prev = T::zero();
        for i in 0..=d {
            let cur = b[i];
            b[i] = s * cur + t * prev;
            prev = cur;
        }
    }
    b
}

impl<T: Real> Row<T> {
    fn new(t: T) -> Self {
        let (b2, b3, b4, b5) = (
            bernstein::<T, 3>(t),
            bernstein::<T, 4>(t),
            bernstein::<T, 5>(t),
            bernstein::<T, 6>(t),
        );
        let (three, five) = (T::from_f64(3.0), T::from_f64(5.0));
        let mut d3 = [T::zero(); 4];
        let mut d5 = [T::zero(); 6];
        for i in 0..4 {
            let lo = if i > 0 { b2[i - 1] } else { T::zero() };
            let hi = if i < 3 { b2[i] } else { T::zero() };
            d3[i] = three * (lo - hi);
        }
        for i in 0..6 {
            let lo = if i > 0 { b4[i - 1] } else { T::zero() };
            let hi = if i < 5 { b4[i] } else { T::zero() };
            d5[i] = five * (lo - hi);
        }
        Row { b3, d3, b5, d5 }
    }
}

/// Tabulated bases for evaluating patches on the grid `us × vs` (entry `j · us.len() + i`
/// is at `(us[i], vs[j])`). Built once per grid and shared by all patches.
#[derive(Debug, Clone)]
pub struct GridBasis<T> {
    nu: usize,
    /// `B³_i(u_l)` at `[i nu + l]`, then `3 B²_i(u_l)`.
    b3: Vec<T>,
    d3: Vec<T>,
    /// `B⁵_i(u_l)`, then `5 B⁴_i(u_l)`.
    b5: Vec<T>,
    d5: Vec<T>,
    rows: Vec<Row<T>>,
}

/// `table[i nu + l] = f(u_l)[i]` for `i < N`.
fn tabulate<T: Real, const N: usize>(us: &[T], scale: f64, f: impl Fn(T) -> [T; N]) -> Vec<T> {
    let mut out = vec![T::zero(); N * us.len()];
    for (l, &t) in us.iter().enumerate() {
        for (i, b) in f(t).into_iter().enumerate() {
            out[i * us.len() + l] = T::from_f64(scale) * b;
        }
    }
    out
}

impl<T: Real> GridBasis<T> {
    /// Bases for the parameters `us` (along `v0 → v1`) and `vs` (along `v0 → v3`).
    pub fn new(us: &[T], vs: &[T]) -> Self {
        GridBasis {
            nu: us.len(),
            b3: tabulate(us, 1.0, bernstein::<T, 4>),
            d3: tabulate(us, 3.0, bernstein::<T, 3>),
            b5: tabulate(us, 1.0, bernstein::<T, 6>),
            d5: tabulate(us, 5.0, bernstein::<T, 5>),
            rows: vs.iter().map(|&t| Row::new(t)).collect(),
        }
    }

    /// The uniform grid `(i, j) / (n − 1)`, `i, j = 0..n` (`n >= 2`).
    pub fn uniform(n: usize) -> Self {
        let t = uniform_params::<T>(n);
        Self::new(&t, &t)
    }

    /// Number of samples of one patch.
    pub fn len(&self) -> usize {
        self.nu * self.rows.len()
    }

    /// Whether the grid is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Evaluates one patch (`g` 16 row-major, compact `h` or `None` for a B-quad) on the grid:
    /// positions into `pos`, unit normals into `nrm` (each [`Self::len`] long).
    pub fn eval_patch(
        &self,
        g: &[V3<T>],
        h: Option<&[V3<T>]>,
        pos: &mut [V3<T>],
        nrm: &mut [V3<T>],
    ) {
        let len = self.len();
        if len == 0 {
            return;
        }
        let (pos, nrm) = (&mut pos[..len], &mut nrm[..len]);
        let g: &[V3<T>; 16] = g[..16].try_into().expect("16 coefficients");
        // Relative to g00 (the bi-3 weights sum to 1, the derivative weights to 0; `h` is a
        // perturbation): the rounding is of the patch's size, not of its distance from the
        // origin. g00 is added back to the positions at the end.
        let x0 = g[0];
        let g: [V3<T>; 16] = std::array::from_fn(|k| std::array::from_fn(|c| g[k][c] - x0[c]));
        let g = &g;
        match h {
            None => {
                let (b, d) = (self.slices::<4>(&self.b3), self.slices::<3>(&self.d3));
                for ((row, prow), nrow) in self
                    .rows
                    .iter()
                    .zip(pos.chunks_exact_mut(self.nu))
                    .zip(nrm.chunks_exact_mut(self.nu))
                {
                    let (c, cv) = contract3(g, row);
                    eval_row(&b, &d, &c, &cv, prow, nrow);
                }
            }
            Some(h) => {
                let h: &[V3<T>; 16] = h[..16].try_into().expect("16 coefficients");
                let (b, d) = (self.slices::<6>(&self.b5), self.slices::<5>(&self.d5));
                for ((row, prow), nrow) in self
                    .rows
                    .iter()
                    .zip(pos.chunks_exact_mut(self.nu))
                    .zip(nrm.chunks_exact_mut(self.nu))
                {
                    let (c, cv) = contract_prep(g, h, row);
                    eval_row(&b, &d, &c, &cv, prow, nrow);
                }
            }
        }
        for p in pos.iter_mut() {
            for c in 0..3 {
                p[c] += x0[c];
            }
        }
    }

    /// The `N` rows of a table, each `nu` long.
    #[inline(always)]
    fn slices<'a, const N: usize>(&self, table: &'a [T]) -> [&'a [T]; N] {
        let nu = self.nu;
        std::array::from_fn(|i| &table[i * nu..(i + 1) * nu])
    }
}

/// One row of samples: `c` (`N` points of the `u` curve), `c'` (its `v` derivative), bases
/// `b[i][l] = B^{N−1}_i(u_l)` and derivative bases `d[i][l]`.
#[inline(always)]
fn eval_row<T: Real, const N: usize, const D: usize>(
    b: &[&[T]; N],
    d: &[&[T]; D],
    c: &[V3<T>; N],
    cv: &[V3<T>; N],
    prow: &mut [V3<T>],
    nrow: &mut [V3<T>],
) {
    let nu = prow.len();
    let nrow = &mut nrow[..nu];
    let b: [&[T]; N] = std::array::from_fn(|i| &b[i][..nu]);
    let d: [&[T]; D] = std::array::from_fn(|i| &d[i][..nu]);
    let mut dc = [[T::zero(); 3]; D];
    for i in 0..D {
        for k in 0..3 {
            dc[i][k] = c[i + 1][k] - c[i][k];
        }
    }
    for l in 0..nu {
        let (mut p, mut du, mut dv) = ([T::zero(); 3], [T::zero(); 3], [T::zero(); 3]);
        for i in 0..N {
            let w = b[i][l];
            for k in 0..3 {
                p[k] += w * c[i][k];
                dv[k] += w * cv[i][k];
            }
        }
        for i in 0..D {
            let w = d[i][l];
            for k in 0..3 {
                du[k] += w * dc[i][k];
            }
        }
        prow[l] = p;
        nrow[l] = unit_cross(du, dv);
    }
}

/// `a × b / |a × b|` (unchanged when zero, as [`crate::util::vec3::normalize`]), branch-free.
#[inline(always)]
fn unit_cross<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    let x = a[1] * b[2] - a[2] * b[1];
    let y = a[2] * b[0] - a[0] * b[2];
    let z = a[0] * b[1] - a[1] * b[0];
    let l2 = x * x + y * y + z * z;
    let r = T::one() / l2.sqrt();
    let s = if l2 > T::zero() { r } else { T::one() };
    [x * s, y * s, z * s]
}

/// Row contraction of a bi-3 patch: `c_i = Σ_j g_ij B³_j(v)`, `c'_i = Σ_j g_ij B³_j'(v)`.
#[inline(always)]
fn contract3<T: Real>(g: &[V3<T>; 16], r: &Row<T>) -> ([V3<T>; 4], [V3<T>; 4]) {
    let mut c = [[T::zero(); 3]; 4];
    let mut cv = [[T::zero(); 3]; 4];
    for i in 0..4 {
        for j in 0..4 {
            for k in 0..3 {
                c[i][k] += r.b3[j] * g[4 * i + j][k];
                cv[i][k] += r.d3[j] * g[4 * i + j][k];
            }
        }
    }
    (c, cv)
}

/// Row contraction of a p-rep patch without forming its 36 bi-5 coefficients: the bi-3
/// part is contracted along `v`, raised to degree 5 along `u` with `E` (eq. (10)), and the
/// sparse `h` is added at its slots, `c_i += h_ij B⁵_j(v)`.
#[inline(always)]
fn contract_prep<T: Real>(
    g: &[V3<T>; 16],
    h: &[V3<T>; 16],
    r: &Row<T>,
) -> ([V3<T>; 6], [V3<T>; 6]) {
    let (c3, cv3) = contract3(g, r);
    let (c, cv) = (raise(&c3), raise(&cv3));
    let (mut c, mut cv) = (c, cv);
    for (s, &(i, j)) in H_SLOTS.iter().enumerate() {
        for k in 0..3 {
            c[i][k] += r.b5[j] * h[s][k];
            cv[i][k] += r.d5[j] * h[s][k];
        }
    }
    (c, cv)
}

/// Degree raising of a cubic Bézier curve to degree 5 (`E` of eq. (10)).
#[inline(always)]
fn raise<T: Real>(c: &[V3<T>; 4]) -> [V3<T>; 6] {
    let w = |x: f64| T::from_f64(x);
    let mut out = [[T::zero(); 3]; 6];
    for k in 0..3 {
        out[0][k] = c[0][k];
        out[1][k] = w(0.4) * c[0][k] + w(0.6) * c[1][k];
        out[2][k] = w(0.1) * c[0][k] + w(0.6) * c[1][k] + w(0.3) * c[2][k];
        out[3][k] = w(0.3) * c[1][k] + w(0.6) * c[2][k] + w(0.1) * c[3][k];
        out[4][k] = w(0.6) * c[2][k] + w(0.4) * c[3][k];
        out[5][k] = c[3][k];
    }
    out
}

/// `i / (n − 1)` for `i = 0..n`, rounded as [`super::eval`]'s parameters.
pub fn uniform_params<T: Real>(n: usize) -> Vec<T> {
    let d = T::from_f64((n - 1) as f64);
    (0..n).map(|i| T::from_f64(i as f64) / d).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Pascal-triangle bases are the closed-form Bernstein polynomials, and the
    /// derivative rows are their exact derivatives (checked against central differences).
    /// The grid kernel equals the pointwise evaluation of [`super::super::eval::eval_patch`]
    /// on a non-square, non-uniform grid, for a B-quad (`h = None`), a perturbed patch, and
    /// a perturbed patch with `h = 0` (the bi-5 path must then reproduce the bi-3 one).
    #[test]
    fn grid_matches_pointwise() {
        use super::super::eval::{eval_patch, Basis};
        let val = |x: usize| ((x as f64 * 12.9898).sin() * 43758.5453).fract();
        let g: Vec<V3<f64>> = (0..16)
            .map(|i| [val(3 * i), val(3 * i + 1), val(3 * i + 2)])
            .collect();
        let h: Vec<V3<f64>> = (0..16)
            .map(|i| [val(90 + 3 * i), val(91 + 3 * i), val(92 + 3 * i)])
            .collect();
        let zero = vec![[0.0; 3]; 16];
        let us = [0.0, 0.1, 0.35, 0.5, 0.9, 1.0, 0.77];
        let vs = [1.0, 0.0, 0.25];
        let basis = GridBasis::new(&us, &vs);
        assert_eq!(basis.len(), 21);
        let (mut p, mut n) = (vec![[0.0; 3]; 21], vec![[0.0; 3]; 21]);
        for h in [None, Some(&h[..]), Some(&zero[..])] {
            basis.eval_patch(&g, h, &mut p, &mut n);
            for (j, &v) in vs.iter().enumerate() {
                for (i, &u) in us.iter().enumerate() {
                    let s = eval_patch(&g, h, &Basis::new(u), &Basis::new(v));
                    let k = j * us.len() + i;
                    let want = s.normal();
                    for c in 0..3 {
                        assert!((p[k][c] - s.position[c]).abs() < 1e-14, "({u},{v})");
                        assert!((n[k][c] - want[c]).abs() < 1e-12, "({u},{v})");
                    }
                }
            }
        }
    }

    #[test]
    fn bases_are_bernstein() {
        let binom = |d: u32, i: u32| (1..=i).fold(1.0, |a, k| a * (d - k + 1) as f64 / k as f64);
        for t in [0.0, 0.13, 0.5, 0.77, 1.0] {
            let r = Row::<f64>::new(t);
            for i in 0..6 {
                let want = binom(5, i as u32) * (1.0 - t).powi(5 - i) * t.powi(i);
                assert!((r.b5[i as usize] - want).abs() < 1e-15);
            }
            if t > 0.0 && t < 1.0 {
                let e = 1e-6;
                let (a, b) = (Row::<f64>::new(t + e), Row::<f64>::new(t - e));
                for i in 0..6 {
                    let fd = (a.b5[i] - b.b5[i]) / (2.0 * e);
                    assert!((r.d5[i] - fd).abs() < 1e-7, "d5[{i}] at {t}");
                }
                for i in 0..4 {
                    let fd = (a.b3[i] - b.b3[i]) / (2.0 * e);
                    assert!((r.d3[i] - fd).abs() < 1e-7, "d3[{i}] at {t}");
                }
            }
        }
    }
}
