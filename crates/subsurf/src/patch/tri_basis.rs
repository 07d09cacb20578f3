//! Triangular patches (the Loop scheme): the triangle parameterization of a [`PatchParam`]
//! and one entry point for both triangular kinds (OpenSubdiv's `EvaluatePatchBasis` for
//! `LOOP` and `GREGORY_TRIANGLE` patches).
//!
//! # Sub-triangle parameterization
//!
//! Each Loop refinement splits a triangle into four: three corner children and a middle
//! child turned by 180°. A patch at depth `d` with origin `(U, V)` covers, in its base
//! face's `(u, v)` (with `u + v ≤ 1`), either the upright triangle with corners
//! `(U, V)`, `(U + 1, V)`, `(U, V + 1)` (times `2^-d`), or, when `U + V ≥ 2^d`, the rotated one
//! with corners `(2^d − U, 2^d − V)` … read backwards:
//!
//! ```text
//! upright:  (s, t) = (u 2^d − U, v 2^d − V)
//! rotated:  (s, t) = ((2^d − U) − u 2^d, (2^d − V) − v 2^d)
//! ```
//!
//! so derivatives of a rotated patch change sign (first and second alike, as OpenSubdiv
//! scales them).

use super::box_spline::box_spline_patch_weights;
use super::gregory_tri::gregory_triangle_weights;
use super::param::PatchParam;
use super::weights::PatchWeights;
use crate::real::Real;

/// The kind of a triangular patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TriPatchKind {
    /// Regular quartic box-spline patch, 12 points, boundary mask from the [`PatchParam`].
    BoxSpline,
    /// Quartic Gregory triangle end cap, 18 points.
    GregoryTriangle,
}

impl TriPatchKind {
    /// Number of control points of the kind.
    pub fn num_points(self) -> usize {
        match self {
            TriPatchKind::BoxSpline => 12,
            TriPatchKind::GregoryTriangle => 18,
        }
    }
}

/// Weights of a triangular patch of any kind: the first [`TriPatchKind::num_points`]
/// entries are used, the rest are zero.
pub type AnyTriPatchWeights<T> = PatchWeights<T, 18>;

impl PatchParam {
    /// Whether a triangular patch is its parent's middle child, turned by 180°
    /// (`U + V ≥ 2^depth`).
    pub fn is_triangle_rotated(&self) -> bool {
        (self.u() as u32 + self.v() as u32) >= (1u32 << self.depth())
    }

    /// Maps a base-face `(u, v)` to a triangular patch's own `(s, t)` (see the module
    /// documentation).
    pub fn normalize_triangle<T: Real>(&self, u: T, v: T) -> (T, T) {
        if self.is_triangle_rotated() {
            let scale = T::pow2(self.depth() as i32);
            let side = T::from_f64((1u32 << self.depth()) as f64);
            (
                side - T::from_f64(self.u() as f64) - u * scale,
                side - T::from_f64(self.v() as f64) - v * scale,
            )
        } else {
            self.normalize(u, v)
        }
    }

    /// Maps a triangular patch's `(s, t)` back to its base face.
    pub fn unnormalize_triangle<T: Real>(&self, s: T, t: T) -> (T, T) {
        if self.is_triangle_rotated() {
            let frac = T::pow2(-(self.depth() as i32));
            let side = T::from_f64((1u32 << self.depth()) as f64);
            (
                (side - T::from_f64(self.u() as f64) - s) * frac,
                (side - T::from_f64(self.v() as f64) - t) * frac,
            )
        } else {
            self.unnormalize(s, t)
        }
    }
}

/// Weights at the patch's own `(s, t)`.
pub fn tri_patch_weights_normalized<T: Real>(
    kind: TriPatchKind,
    param: &PatchParam,
    s: T,
    t: T,
) -> AnyTriPatchWeights<T> {
    match kind {
        TriPatchKind::GregoryTriangle => gregory_triangle_weights(s, t),
        TriPatchKind::BoxSpline => {
            let w = box_spline_patch_weights(s, t, param.boundary());
            let mut r = AnyTriPatchWeights::<T>::default();
            r.p[..12].copy_from_slice(&w.p);
            r.du[..12].copy_from_slice(&w.du);
            r.dv[..12].copy_from_slice(&w.dv);
            r.duu[..12].copy_from_slice(&w.duu);
            r.duv[..12].copy_from_slice(&w.duv);
            r.dvv[..12].copy_from_slice(&w.dvv);
            r
        }
    }
}

/// Weights at the base face's `(u, v)`: normalizes with `param`, evaluates, and scales the
/// derivatives to the face's parameterization (negated for a rotated patch).
pub fn tri_patch_weights<T: Real>(
    kind: TriPatchKind,
    param: &PatchParam,
    u: T,
    v: T,
) -> AnyTriPatchWeights<T> {
    let (s, t) = param.normalize_triangle(u, v);
    let mut w = tri_patch_weights_normalized(kind, param, s, t);
    let d1 = T::pow2(param.depth() as i32);
    let sign = if param.is_triangle_rotated() {
        -T::ONE
    } else {
        T::ONE
    };
    let (a, b) = (sign * d1, sign * d1 * d1);
    for k in 0..18 {
        w.du[k] *= a;
        w.dv[k] *= a;
        w.duu[k] *= b;
        w.duv[k] *= b;
        w.dvv[k] *= b;
    }
    w
}

#[cfg(test)]
mod tests {
    use super::super::param::PatchParamFields;
    use super::*;

    fn param(depth: u8, u: u16, v: u16) -> PatchParam {
        PatchParam::new(PatchParamFields {
            face_id: 1,
            u,
            v,
            depth,
            regular: true,
            ..Default::default()
        })
        .unwrap()
    }

    #[test]
    fn sub_triangles_tile_the_face_and_round_trip() {
        // At depth 1 the four children: (0,0), (1,0), (0,1) upright, (1,1) rotated.
        let mid = param(1, 1, 1);
        assert!(mid.is_triangle_rotated());
        assert!(!param(1, 1, 0).is_triangle_rotated());
        // The middle child's corner 0 is the midpoint of the face's edge 1.
        let (u, v) = mid.unnormalize_triangle(0.0f64, 0.0);
        assert_eq!((u, v), (0.5, 0.5));
        assert_eq!(mid.unnormalize_triangle(1.0f64, 0.0), (0.0, 0.5));
        for p in [param(2, 1, 2), param(2, 3, 1), param(3, 2, 5)] {
            let (u, v) = p.unnormalize_triangle(0.2f64, 0.3);
            let (s, t) = p.normalize_triangle(u, v);
            assert!((s - 0.2).abs() < 1e-14 && (t - 0.3).abs() < 1e-14);
        }
    }
}
