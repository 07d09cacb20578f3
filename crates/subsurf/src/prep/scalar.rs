//! The scalar type of a p-rep construction: `f32` (as on the GPU) or `f64` (for checks).
//!
//! Every kernel of [`crate::prep`] is generic over [`Real`], so the same code path produces
//! the single-precision surface that is rendered and the double-precision surface that is
//! compared with the reference checker. Points are plain `[T; 3]` arrays; the few vector
//! helpers below keep the kernels readable without pulling in a linear-algebra crate.

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// A floating-point scalar: implemented for `f32` and `f64`.
pub trait Real:
    Copy
    + Send
    + Sync
    + Debug
    + Default
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + 'static
{
    /// Rounds an `f64` to this type.
    fn from_f64(x: f64) -> Self;
    /// Widens to `f64` (exact).
    fn to_f64(self) -> f64;
    /// Widens an `f32` (exact).
    fn from_f32(x: f32) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// `0`.
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// `1`.
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// Name used in messages and bench labels.
    const NAME: &'static str;
}

impl Real for f32 {
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    fn to_f64(self) -> f64 {
        self as f64
    }
    fn from_f32(x: f32) -> Self {
        x
    }
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    const NAME: &'static str = "f32";
}

impl Real for f64 {
    fn from_f64(x: f64) -> Self {
        x
    }
    fn to_f64(self) -> f64 {
        self
    }
    fn from_f32(x: f32) -> Self {
        x as f64
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    const NAME: &'static str = "f64";
}

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
