//! Points of a p-rep construction over the crate's scalar [`Real`] (`f32` as on the GPU, `f64`
//! for checks): plain `[T; 3]` arrays, and the few vector helpers that keep the kernels
//! readable without pulling in a linear-algebra crate.

pub use crate::real::Real;

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

/// `acc + s a`, the multiply-add used by every weighted sum (no fused multiply-add, so CPU
/// results do not depend on the target's FMA support).
#[inline(always)]
pub fn axpy<T: Real>(acc: V3<T>, s: T, a: V3<T>) -> V3<T> {
    [acc[0] + s * a[0], acc[1] + s * a[1], acc[2] + s * a[2]]
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
    let l2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    if l2 > T::zero() {
        scale(T::one() / l2.sqrt(), a)
    } else {
        a
    }
}

/// `[T::zero(); 3]`.
#[inline(always)]
pub fn zero3<T: Real>() -> V3<T> {
    [T::zero(); 3]
}
