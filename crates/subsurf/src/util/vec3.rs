//! Plain `[T; 3]` vectors over the crate's scalar [`Real`] (`f32` as on the GPU, `f64` for
//! checks): the few helpers that keep the kernels readable without a linear-algebra crate.
//! Multiply-adds are written out (no fused multiply-add), so CPU results do not depend on the
//! target's FMA support.

use crate::real::Real;

/// A point or vector.
pub type V3<T> = [T; 3];

/// `a + b`.
#[inline(always)]
pub fn add<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
#[inline(always)]
pub fn sub<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s a`.
#[inline(always)]
pub fn scale<T: Real>(s: T, a: V3<T>) -> V3<T> {
    [s * a[0], s * a[1], s * a[2]]
}

/// `acc + s a`, the multiply-add of every weighted sum.
#[inline(always)]
pub fn axpy<T: Real>(acc: V3<T>, s: T, a: V3<T>) -> V3<T> {
    [acc[0] + s * a[0], acc[1] + s * a[1], acc[2] + s * a[2]]
}

/// `a · b`.
#[inline(always)]
pub fn dot<T: Real>(a: V3<T>, b: V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product `a x b`.
#[inline(always)]
pub fn cross<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a / |a|`, or `a` unchanged when it is zero.
#[inline(always)]
pub fn normalize<T: Real>(a: V3<T>) -> V3<T> {
    let l2 = dot(a, a);
    if l2 > T::zero() {
        scale(T::one() / l2.sqrt(), a)
    } else {
        a
    }
}

/// `a / |a|` when `|a|` is finite and above `tiny`, else `None`.
#[inline(always)]
pub fn unit<T: Real>(a: V3<T>, tiny: T) -> Option<V3<T>> {
    let l = dot(a, a).sqrt();
    (l > tiny && l.is_finite()).then(|| [a[0] / l, a[1] / l, a[2] / l])
}

/// `[T::zero(); 3]`.
#[inline(always)]
pub fn zero3<T: Real>() -> V3<T> {
    [T::zero(); 3]
}
