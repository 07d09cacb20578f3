//! Weight vectors of curve segments and patches, and their application to control points.

use crate::real::Real;

/// Weights of the four control points of a cubic curve segment at one parameter `t`, with
/// their first and second derivatives with respect to `t`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CurveWeights<T> {
    /// Position weights.
    pub p: [T; 4],
    /// First-derivative weights.
    pub d1: [T; 4],
    /// Second-derivative weights.
    pub d2: [T; 4],
}

impl<T: Real> CurveWeights<T> {
    /// The same curve read backwards: if `self` is evaluated at `t` for points
    /// `(P0, P1, P2, P3)`, the result is the evaluation at `1 - t` for `(P3, P2, P1, P0)`
    /// (first derivatives change sign).
    pub fn reversed(&self) -> Self {
        let mut r = *self;
        for i in 0..4 {
            r.p[i] = self.p[3 - i];
            r.d1[i] = -self.d1[3 - i];
            r.d2[i] = self.d2[3 - i];
        }
        r
    }

    /// Applies a linear map to the control points: the weights of `M P` seen as weights of
    /// `P`, i.e. `w ← w M` for each of the three weight vectors.
    pub fn times_matrix(&self, m: &[[T; 4]; 4]) -> Self {
        let mul = |w: &[T; 4]| {
            let mut r = [T::ZERO; 4];
            for (k, row) in m.iter().enumerate() {
                for j in 0..4 {
                    r[j] += w[k] * row[j];
                }
            }
            r
        };
        CurveWeights {
            p: mul(&self.p),
            d1: mul(&self.d1),
            d2: mul(&self.d2),
        }
    }
}

/// Weights of the `N` control points of a patch at one `(u, v)`: position, first and
/// second partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchWeights<T, const N: usize> {
    /// Position weights.
    pub p: [T; N],
    /// `∂/∂u` weights.
    pub du: [T; N],
    /// `∂/∂v` weights.
    pub dv: [T; N],
    /// `∂²/∂u²` weights.
    pub duu: [T; N],
    /// `∂²/∂u∂v` weights.
    pub duv: [T; N],
    /// `∂²/∂v²` weights.
    pub dvv: [T; N],
}

impl<T: Real, const N: usize> Default for PatchWeights<T, N> {
    fn default() -> Self {
        let z = [T::ZERO; N];
        PatchWeights {
            p: z,
            du: z,
            dv: z,
            duu: z,
            duv: z,
            dvv: z,
        }
    }
}

impl<T: Real> PatchWeights<T, 16> {
    /// Tensor product of two curve weight sets: the weight of point `(i, j)` (index
    /// `4*j + i`, `i` along `u`) is `wu[i] · wv[j]`.
    pub fn tensor(wu: &CurveWeights<T>, wv: &CurveWeights<T>) -> Self {
        let mut w = Self::default();
        for j in 0..4 {
            for i in 0..4 {
                let k = 4 * j + i;
                w.p[k] = wu.p[i] * wv.p[j];
                w.du[k] = wu.d1[i] * wv.p[j];
                w.dv[k] = wu.p[i] * wv.d1[j];
                w.duu[k] = wu.d2[i] * wv.p[j];
                w.duv[k] = wu.d1[i] * wv.d1[j];
                w.dvv[k] = wu.p[i] * wv.d2[j];
            }
        }
        w
    }
}

impl<T: Real, const N: usize> PatchWeights<T, N> {
    /// Multiplies first-derivative weights by `d` and second-derivative weights by `d²`:
    /// the chain rule for a parameter scaled by `d` (see [`super::PatchParam::deriv_scale`]).
    pub fn scale_derivatives(&mut self, d: T) {
        let d2 = d * d;
        for k in 0..N {
            self.du[k] *= d;
            self.dv[k] *= d;
            self.duu[k] *= d2;
            self.duv[k] *= d2;
            self.dvv[k] *= d2;
        }
    }

    /// The point the sums are taken relative to: the first of non-zero position weight (0
    /// if there is none).
    pub fn origin(&self) -> usize {
        self.p.iter().position(|&w| w != T::ZERO).unwrap_or(0)
    }

    /// Applies the weights to `N` control points of dimension `D`, relative to one of them:
    /// `P = x_0 + Σ_k w_k (x_k − x_0)` and `∂P = Σ_k ∂w_k (x_k − x_0)`, which is the plain sum
    /// for the weights of a patch basis (position weights summing to 1, derivative weights
    /// to 0) and rounds relative to the patch, not to its distance from the origin. `x_0` is
    /// the first point of non-zero position weight ([`PatchWeights::origin`]), never a
    /// phantom point whose weights a boundary mask made zero.
    pub fn eval<const D: usize>(&self, points: &[[T; D]; N]) -> PatchEval<T, D> {
        let mut r = PatchEval::<T, D>::default();
        let Some(&x0) = points.get(self.origin()) else {
            return r;
        };
        for (k, pt) in points.iter().enumerate() {
            for c in 0..D {
                let x = pt[c] - x0[c];
                r.p[c] += self.p[k] * x;
                r.du[c] += self.du[k] * x;
                r.dv[c] += self.dv[k] * x;
                r.duu[c] += self.duu[k] * x;
                r.duv[c] += self.duv[k] * x;
                r.dvv[c] += self.dvv[k] * x;
            }
        }
        for c in 0..D {
            r.p[c] += x0[c];
        }
        r
    }
}

impl<T: Real, const N: usize> PatchWeights<T, N> {
    /// Applies the weights to the points `points[indices[k]]`, `k < min(N, indices.len())`
    /// (a patch's control-vertex indices into a vertex buffer). `None` if an index is out of
    /// range. Relative to one of the points, as [`PatchWeights::eval`].
    pub fn eval_indexed<const D: usize>(
        &self,
        points: &[[T; D]],
        indices: &[u32],
    ) -> Option<PatchEval<T, D>> {
        let mut r = PatchEval::<T, D>::default();
        let Some(&first) = indices.get(self.origin()).or(indices.first()) else {
            return Some(r);
        };
        let x0 = *points.get(first as usize)?;
        for (k, &i) in indices.iter().take(N).enumerate() {
            let pt = points.get(i as usize)?;
            for c in 0..D {
                let x = pt[c] - x0[c];
                r.p[c] += self.p[k] * x;
                r.du[c] += self.du[k] * x;
                r.dv[c] += self.dv[k] * x;
                r.duu[c] += self.duu[k] * x;
                r.duv[c] += self.duv[k] * x;
                r.dvv[c] += self.dvv[k] * x;
            }
        }
        for c in 0..D {
            r.p[c] += x0[c];
        }
        Some(r)
    }
}

/// A point on a patch with its first and second partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchEval<T, const D: usize> {
    /// Position.
    pub p: [T; D],
    /// `∂P/∂u`.
    pub du: [T; D],
    /// `∂P/∂v`.
    pub dv: [T; D],
    /// `∂²P/∂u²`.
    pub duu: [T; D],
    /// `∂²P/∂u∂v`.
    pub duv: [T; D],
    /// `∂²P/∂v²`.
    pub dvv: [T; D],
}

impl<T: Real, const D: usize> Default for PatchEval<T, D> {
    fn default() -> Self {
        let z = [T::ZERO; D];
        PatchEval {
            p: z,
            du: z,
            dv: z,
            duu: z,
            duv: z,
            dvv: z,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indexed_evaluation_gathers_and_checks_indices() {
        let w = PatchWeights::<f64, 4> {
            p: [0.1, 0.2, 0.3, 0.4],
            du: [1.0, 0.0, -1.0, 0.0],
            ..Default::default()
        };
        let pts = [[1.0], [2.0], [3.0], [4.0], [5.0]];
        let e = w.eval_indexed(&pts, &[4, 3, 2, 1]).unwrap();
        assert!((e.p[0] - (0.5 + 0.8 + 0.9 + 0.8)).abs() < 1e-15);
        assert!((e.du[0] - 2.0).abs() < 1e-15);
        let direct = w.eval(&[[5.0], [4.0], [3.0], [2.0]]);
        assert_eq!(e, direct);
        assert!(w.eval_indexed(&pts, &[0, 1, 2, 5]).is_none());
    }
}
