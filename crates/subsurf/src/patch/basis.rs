//! One entry point for every patch kind: maps a base-face `(u, v)` into the patch with its
//! [`PatchParam`], evaluates the right basis and scales the derivatives back to the face's
//! parameterization (OpenSubdiv's `Far::internal::EvaluatePatchBasis`).

#[cfg(test)]
use super::bspline::bspline_patch_weights;
use super::bspline::{bspline_curve_bounded, BOUNDARY_U0, BOUNDARY_U1, BOUNDARY_V0, BOUNDARY_V1};
use super::gregory::{gregory_patch_weights, GregoryDerivatives};
use super::param::PatchParam;
#[cfg(test)]
use super::single_crease::single_crease_patch_weights;
use super::single_crease::{crease_curve_across, single_crease_shape};
use super::weights::{CurveWeights, PatchWeights};
use super::PatchEdge;
use crate::real::Real;

/// The kind of a patch, i.e. which basis its control points use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PatchKind {
    /// Regular bicubic B-spline, 16 points, boundary mask from the [`PatchParam`].
    Regular,
    /// Regular bicubic B-spline with one semi-sharp crease, 16 points; the crease edge is
    /// the (single) bit set in the [`PatchParam`] boundary field, the sharpness is stored
    /// separately ([`super::SharpnessTable`]).
    SingleCrease,
    /// 20-point Gregory basis end cap.
    GregoryBasis(GregoryDerivatives),
}

impl PatchKind {
    /// Number of control points of the kind.
    pub fn num_points(self) -> usize {
        match self {
            PatchKind::Regular | PatchKind::SingleCrease => 16,
            PatchKind::GregoryBasis(_) => 20,
        }
    }
}

/// Basis weights of a patch of any kind: the first [`PatchKind::num_points`] entries of
/// each array are used, the rest are zero.
pub type AnyPatchWeights<T> = PatchWeights<T, 20>;

fn widen<T: Real>(w: PatchWeights<T, 16>) -> AnyPatchWeights<T> {
    let mut r = AnyPatchWeights::<T>::default();
    r.p[..16].copy_from_slice(&w.p);
    r.du[..16].copy_from_slice(&w.du);
    r.dv[..16].copy_from_slice(&w.dv);
    r.duu[..16].copy_from_slice(&w.duu);
    r.duv[..16].copy_from_slice(&w.duv);
    r.dvv[..16].copy_from_slice(&w.dvv);
    r
}

/// Weights at the patch's own `(s, t)` (no reparameterization, no derivative scaling).
///
/// For [`PatchKind::SingleCrease`] the crease edge is the lowest bit set in
/// `param.boundary()`; with no bit set, or `sharpness` ≤ 0, the patch is the plain B-spline.
pub fn patch_weights_normalized<T: Real>(
    kind: PatchKind,
    param: &PatchParam,
    sharpness: T,
    s: T,
    t: T,
) -> AnyPatchWeights<T> {
    match basis(kind, param, sharpness, s, t) {
        Basis::Tensor([wu, wv]) => widen(PatchWeights::tensor(&wu, &wv)),
        Basis::Gregory(d) => gregory_patch_weights(s, t, d),
    }
}

/// Weights at the base-face (ptex) parameters `(u, v)`: normalizes with `param`, evaluates,
/// and scales derivatives by [`PatchParam::deriv_scale`] so they are derivatives with
/// respect to the face's `(u, v)`.
pub fn patch_weights<T: Real>(
    kind: PatchKind,
    param: &PatchParam,
    sharpness: T,
    u: T,
    v: T,
) -> AnyPatchWeights<T> {
    let (s, t) = param.normalize(u, v);
    let mut w = patch_weights_normalized(kind, param, sharpness, s, t);
    w.scale_derivatives(param.deriv_scale());
    w
}

/// The basis of a patch at its own parameters `(s, t)`.
enum Basis<T> {
    /// A tensor product (regular and single-crease patches): the curves along `s` and `t`.
    Tensor([CurveWeights<T>; 2]),
    /// A Gregory patch, evaluated whole.
    Gregory(GregoryDerivatives),
}

/// The one place that picks a patch's basis: [`patch_weights_normalized`] and the partial
/// weights below all go through it.
#[inline(always)]
fn basis<T: Real>(kind: PatchKind, param: &PatchParam, sharpness: T, s: T, t: T) -> Basis<T> {
    match (
        patch_curve(kind, param, sharpness, 0, s),
        patch_curve(kind, param, sharpness, 1, t),
    ) {
        (Some(wu), Some(wv)) => Basis::Tensor([wu, wv]),
        _ => match kind {
            PatchKind::GregoryBasis(d) => Basis::Gregory(d),
            _ => unreachable!("tensor kinds have curves"),
        },
    }
}

/// One curve of a tensor-product patch's basis at its own parameter `x` (`dir` 0: along `s`,
/// 1: along `t`), as [`patch_weights_normalized`] forms it, bit for bit (each curve depends
/// on its own parameter only); `None` for a Gregory patch, which is no tensor product.
#[inline(always)]
pub fn patch_curve<T: Real>(
    kind: PatchKind,
    param: &PatchParam,
    sharpness: T,
    dir: usize,
    x: T,
) -> Option<CurveWeights<T>> {
    match patch_curve_shape(kind, param, sharpness, dir) {
        CurveShape::BSpline { low, high } => Some(bspline_curve_bounded(x, low, high)),
        CurveShape::Crease(edge) => Some(crease_curve_across(x, edge, sharpness)),
        CurveShape::None => None,
    }
}

/// What one curve of a patch's basis is ([`patch_curve`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CurveShape {
    /// The uniform cubic B-spline, its first (`low`) or last (`high`) point a phantom
    /// folded into the others (`bspline_curve_bounded`): one cubic polynomial.
    BSpline {
        /// Boundary at `x = 0`.
        low: bool,
        /// Boundary at `x = 1`.
        high: bool,
    },
    /// A single-crease patch's curve across its crease edge: cubic pieces of the
    /// sharpness (`single_crease_curve`).
    Crease(PatchEdge),
    /// No tensor product (Gregory).
    None,
}

impl CurveShape {
    /// The B-spline along `dir` of a patch with boundary mask `mask` (bits as
    /// `bspline::BOUNDARY_*`): its ends folded where the mask marks them.
    #[inline(always)]
    pub fn bounded(mask: u8, dir: usize) -> CurveShape {
        let (low, high) = if dir == 0 {
            (BOUNDARY_U0, BOUNDARY_U1)
        } else {
            (BOUNDARY_V0, BOUNDARY_V1)
        };
        CurveShape::BSpline {
            low: mask & low != 0,
            high: mask & high != 0,
        }
    }
}

/// The shape of [`patch_curve`] along `dir` for a patch (the one place that decides it;
/// single-crease patches through [`single_crease_shape`]).
#[inline(always)]
pub fn patch_curve_shape<T: Real>(
    kind: PatchKind,
    param: &PatchParam,
    sharpness: T,
    dir: usize,
) -> CurveShape {
    let bits = param.boundary() & 0xf;
    match kind {
        PatchKind::Regular => CurveShape::bounded(bits, dir),
        PatchKind::SingleCrease => match PatchEdge::from_index(bits.trailing_zeros()) {
            Some(edge) => single_crease_shape(dir, edge, sharpness),
            None => CurveShape::bounded(0, dir),
        },
        PatchKind::GregoryBasis(_) => CurveShape::None,
    }
}

/// The position weights of [`patch_weights`] alone (its `p`, bit for bit): for regular and
/// single-crease patches only the tensor of the two curves' position weights is formed, none
/// of the derivative weights, which a position query (the rate curves of adaptive
/// tessellation) does not read; for Gregory patches only the 20 position weights.
pub fn patch_position_weights<T: Real>(
    kind: PatchKind,
    param: &PatchParam,
    sharpness: T,
    u: T,
    v: T,
) -> [T; 20] {
    let (s, t) = param.normalize(u, v);
    let Basis::Tensor([wu, wv]) = basis(kind, param, sharpness, s, t) else {
        return super::gregory::gregory_position_weights(s, t);
    };
    let mut p = [T::ZERO; 20];
    for j in 0..4 {
        for i in 0..4 {
            p[4 * j + i] = wu.p[i] * wv.p[j];
        }
    }
    p
}

/// The position and first-derivative weights of [`patch_weights`] alone (its `p`, `du` and
/// `dv`, bit for bit), without the second-derivative weights for the tensor-product kinds
/// (see [`patch_position_weights`]): what a position-and-normal query reads.
pub fn patch_first_weights<T: Real>(
    kind: PatchKind,
    param: &PatchParam,
    sharpness: T,
    u: T,
    v: T,
) -> [[T; 20]; 3] {
    let (s, t) = param.normalize(u, v);
    let Basis::Tensor([wu, wv]) = basis(kind, param, sharpness, s, t) else {
        let w = patch_weights(kind, param, sharpness, u, v);
        return [w.p, w.du, w.dv];
    };
    let d = param.deriv_scale::<T>();
    let mut w = [[T::ZERO; 20]; 3];
    for j in 0..4 {
        for i in 0..4 {
            let k = 4 * j + i;
            w[0][k] = wu.p[i] * wv.p[j];
            w[1][k] = wu.d1[i] * wv.p[j] * d;
            w[2][k] = wu.p[i] * wv.d1[j] * d;
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::super::param::PatchParamFields;
    use super::*;

    fn param(boundary: u8, depth: u8, u: u16, v: u16) -> PatchParam {
        PatchParam::new(PatchParamFields {
            face_id: 3,
            u,
            v,
            depth,
            boundary,
            regular: true,
            ..Default::default()
        })
        .unwrap()
    }

    #[test]
    fn dispatch_matches_the_direct_bases() {
        let p = param(0b0100, 2, 1, 3);
        let (u, v) = (0.3f64, 0.8);
        let (s, t) = p.normalize(u, v);
        let w = patch_weights(PatchKind::Regular, &p, 0.0, u, v);
        let mut direct = bspline_patch_weights(s, t, 0b0100);
        direct.scale_derivatives(4.0);
        assert_eq!(&w.p[..16], &direct.p[..]);
        assert_eq!(&w.du[..16], &direct.du[..]);
        assert_eq!(&w.dvv[..16], &direct.dvv[..]);
        assert!(w.p[16..].iter().all(|&x| x == 0.0));

        let w = patch_weights_normalized(PatchKind::SingleCrease, &p, 2.5, s, t);
        let direct = single_crease_patch_weights(s, t, PatchEdge::V1, 2.5);
        assert_eq!(&w.p[..16], &direct.p[..]);
        assert_eq!(&w.duv[..16], &direct.duv[..]);

        let g = GregoryDerivatives::Exact;
        let w = patch_weights_normalized(PatchKind::GregoryBasis(g), &p, 0.0, s, t);
        assert_eq!(w, gregory_patch_weights(s, t, g));
        assert_eq!(PatchKind::GregoryBasis(g).num_points(), 20);
        assert_eq!(PatchKind::SingleCrease.num_points(), 16);
    }

    #[test]
    fn single_crease_without_edge_bit_is_regular() {
        let p = param(0, 0, 0, 0);
        let w = patch_weights(PatchKind::SingleCrease, &p, 3.0f64, 0.9, 0.2);
        let r = patch_weights(PatchKind::Regular, &p, 0.0f64, 0.9, 0.2);
        assert_eq!(w, r);
    }

    #[test]
    fn position_and_first_weights_are_those_of_the_full_weights() {
        let kinds = [
            PatchKind::Regular,
            PatchKind::SingleCrease,
            PatchKind::GregoryBasis(GregoryDerivatives::Exact),
        ];
        for kind in kinds {
            for boundary in 0..16u8 {
                for (depth, pu, pv, sharp) in [
                    (0u8, 0u16, 0u16, 2.25f32),
                    (2, 1, 3, 0.0),
                    (4, 9, 14, 10.0),
                    (1, 1, 0, 0.6),
                ] {
                    let p = param(boundary, depth, pu, pv);
                    for k in 0..=12 {
                        let (u, v) = (k as f32 / 12.0, ((7 * k) % 13) as f32 / 12.0);
                        let (u, v) = p.unnormalize(u, v);
                        let full = patch_weights(kind, &p, sharp, u, v);
                        let pos = patch_position_weights(kind, &p, sharp, u, v);
                        let bits = |w: [f32; 20]| w.map(f32::to_bits);
                        let what = format!("{kind:?} {boundary} {depth} {sharp} at {u}, {v}");
                        assert_eq!(bits(full.p), bits(pos), "{what}");
                        let [p1, du, dv] = patch_first_weights(kind, &p, sharp, u, v);
                        assert_eq!(bits(full.p), bits(p1), "{what}");
                        assert_eq!(bits(full.du), bits(du), "{what}");
                        assert_eq!(bits(full.dv), bits(dv), "{what}");
                    }
                }
            }
        }
    }
}
