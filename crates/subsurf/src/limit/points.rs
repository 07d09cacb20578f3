//! The patch points of a [`super::PatchTable`] from base values: each level's stencils, then
//! the end-cap stencils, every row applied relative to its first input,
//!
//! ```text
//! y = x_0 + Σ_k w_k (x_k − x_0)        (Σ_k w_k = 1: exact in exact arithmetic)
//! ```
//!
//! In `f32` the rounding of `Σ_k w_k x_k` is `ε Σ_k |w_k| |x_k|`, of the distance from the
//! origin; with `x_k − x_0` (exact for nearby points, Sterbenz 1974) it is of the row's
//! neighbourhood. The patch points then differ by their own rounding only, which keeps the
//! derivatives of small patches far from the origin accurate (see [`super::eval`]), and the
//! long end-cap rows of high-valence vertices (valence 360: 2·10⁻³ rad of normal error
//! weighting `x_k`, 10⁻⁵ relative to `x_0`).

use rayon::prelude::*;

use crate::real::Real;
use crate::refine::{LevelStencils, StencilTable};

const CHUNK: usize = 4096;

/// Rows of `t` into `out` (`out.len() == t.num_rows()`), input `k` read as `x(k)`, each
/// relative to its first input, in parallel over chunks of rows.
pub fn apply_relative<'s, R: Real, const N: usize>(
    t: &StencilTable<R>,
    out: &mut [[R; N]],
    x: impl Fn(usize) -> &'s [R; N] + Sync,
) {
    apply_relative_from(t, 0, out, x);
}

/// [`apply_relative`] of the rows `first..first + out.len()` of `t`.
pub fn apply_relative_from<'s, R: Real, const N: usize>(
    t: &StencilTable<R>,
    first: usize,
    out: &mut [[R; N]],
    x: impl Fn(usize) -> &'s [R; N] + Sync,
) {
    out.par_chunks_mut(CHUNK).enumerate().for_each(|(c, o)| {
        for (i, y) in o.iter_mut().enumerate() {
            let r = first + c * CHUNK + i;
            let (lo, hi) = (t.offsets[r] as usize, t.offsets[r + 1] as usize);
            *y = row(&t.indices[lo..hi], &t.weights[lo..hi], &x);
        }
    });
}

/// `x_0 + Σ_k w_k (x_k − x_0)` over one row (`[0; N]` for an empty one).
fn row<'s, R: Real, const N: usize>(
    idx: &[u32],
    wts: &[R],
    x: &impl Fn(usize) -> &'s [R; N],
) -> [R; N] {
    let Some(&first) = idx.first() else {
        return [R::ZERO; N];
    };
    let x0 = *x(first as usize);
    let mut acc = [R::ZERO; N];
    for (&k, &w) in idx.iter().zip(wts) {
        let v = x(k as usize);
        for c in 0..N {
            acc[c] += w * (v[c] - x0[c]);
        }
    }
    std::array::from_fn(|c| acc[c] + x0[c])
}

/// One refinement step (face points, then children of vertices and edge points over the
/// parents and face points, child layout `[vertex | face | edge]`), rows relative.
pub fn level_apply_relative<R: Real, const N: usize>(
    s: &LevelStencils<R>,
    src: &[[R; N]],
    dst: &mut [[R; N]],
) {
    let nv = s.vertex.num_rows();
    let nf = s.face.num_rows();
    let (vd, rest) = dst.split_at_mut(nv);
    let (fd, ed) = rest.split_at_mut(nf);
    apply_relative(&s.face, fd, |k| &src[k]);
    let fd: &[[R; N]] = fd;
    let p = s.num_parent_vertices;
    let x = |k: usize| if k < p { &src[k] } else { &fd[k - p] };
    apply_relative(&s.vertex, vd, x);
    apply_relative(&s.edge, ed, x);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Far from the origin, a relative row keeps the digits a plain `f32` sum loses: an
    /// edge-point-like row `(3 a + 3 b + c + d) / 8` of points 10⁴ from the origin and
    /// 10⁻³ apart, against the same sum in `f64`.
    #[test]
    fn relative_rows_keep_digits_far_from_origin() {
        let t = StencilTable {
            offsets: vec![0, 4],
            indices: vec![0, 1, 2, 3],
            weights: vec![0.375, 0.375, 0.125, 0.125],
            num_inputs: 4,
        };
        let o = 1.0e4f32;
        let src = [
            [o, o, o],
            [o + 1e-3, o, o],
            [o, o + 1e-3, o],
            [o + 7e-4, o - 3e-4, o + 1e-3],
        ];
        let mut rel = [[0.0f32; 3]];
        apply_relative(&t, &mut rel, |k| &src[k]);
        let mut plain = [[0.0f32; 3]];
        t.apply(&src, &mut plain);
        let exact: Vec<f64> = (0..3)
            .map(|c| (0..4).map(|k| t.weights[k] as f64 * src[k][c] as f64).sum())
            .collect();
        let ulp = 1e4 * f32::EPSILON as f64;
        for c in 0..3 {
            assert!(
                (rel[0][c] as f64 - exact[c]).abs() <= 0.5 * ulp,
                "{rel:?} {exact:?}"
            );
        }
        // The plain sum is off by more (rounding of products of size 10⁴).
        let plain_err = (0..3)
            .map(|c| (plain[0][c] as f64 - exact[c]).abs())
            .fold(0.0, f64::max);
        let rel_err = (0..3)
            .map(|c| (rel[0][c] as f64 - exact[c]).abs())
            .fold(0.0, f64::max);
        assert!(rel_err <= plain_err, "{rel_err} vs {plain_err}");
    }
}
