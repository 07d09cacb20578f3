//! The scalar type of the constructions: `f32` (what the GPU and the tables use) or `f64`
//! (reference evaluation in tests and double-precision export).
//!
//! Every basis function in [`crate::patch`] and every kernel in [`crate::prep`] is generic
//! over [`Real`], so the `f32` path and its `f64` twin run exactly the same arithmetic and
//! can be compared term by term.

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

pub mod vec3;

pub use vec3::Vec3;

/// A floating-point scalar: implemented for `f32` and `f64`.
pub trait Real:
    Copy
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
    + SubAssign
    + MulAssign
    + Send
    + Sync
    + 'static
{
    /// Additive identity.
    const ZERO: Self;
    /// Multiplicative identity.
    const ONE: Self;
    /// Converts from `f64`, rounding to the nearest representable value.
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64` (exact for both implementations).
    fn to_f64(self) -> f64;
    /// `2^k` for a small integer `k` (exact).
    fn pow2(k: i32) -> Self;
    /// Largest integer not greater than `self`.
    fn floor(self) -> Self;
    /// `true` unless NaN or infinite.
    fn is_finite(self) -> bool;
    /// Widens an `f32` (exact).
    fn from_f32(x: f32) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Name used in messages and bench labels.
    const NAME: &'static str;
    /// Three values as one (`vec3`: an SSE register for `f32` on x86-64).
    type V3: Vec3<Self>;
    /// `0` (same as [`Real::ZERO`]).
    #[inline(always)]
    fn zero() -> Self {
        Self::ZERO
    }
    /// `1` (same as [`Real::ONE`]).
    #[inline(always)]
    fn one() -> Self {
        Self::ONE
    }
}

impl Real for f32 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    #[inline]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn pow2(k: i32) -> Self {
        // Exact for -126 <= k <= 127, far more than the sharpness range needs.
        f32::from_bits((((k + 127).clamp(0, 254)) as u32) << 23)
    }
    #[inline]
    fn floor(self) -> Self {
        f32::floor(self)
    }
    #[inline]
    fn is_finite(self) -> bool {
        f32::is_finite(self)
    }
    #[inline]
    fn from_f32(x: f32) -> Self {
        x
    }
    #[inline]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    const NAME: &'static str = "f32";
    type V3 = vec3::Sse3;
}

impl Real for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn pow2(k: i32) -> Self {
        f64::from_bits((((k + 1023).clamp(0, 2046)) as u64) << 52)
    }
    #[inline]
    fn floor(self) -> Self {
        f64::floor(self)
    }
    #[inline]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline]
    fn from_f32(x: f32) -> Self {
        x as f64
    }
    #[inline]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    const NAME: &'static str = "f64";
    type V3 = [f64; 3];
}

/// Base vertex data that tables are applied to: `N` values per vertex, held in `f32` or `f64`
/// (slices and vectors of either, and a mesh's [`crate::mesh::Positions`], which give their
/// full-precision values). Every consumer reads each value once, converted to its own scalar
/// with one rounding at most ([`Real::from_f64`]; exact for `f32` into either, and for `f64`
/// into `f64`).
pub trait VertexData<const N: usize> {
    /// Number of vertices.
    fn num_vertices(&self) -> usize;
    /// Vertex `i` in `R` (one rounding at most). Panics past the end, as indexing does.
    fn vertex<R: Real>(&self, i: usize) -> [R; N];
    /// The values in `f64` (exact).
    fn vertex_f64(&self, i: usize) -> [f64; N] {
        self.vertex::<f64>(i)
    }
    /// The data as `f32` values when it is held that way (no conversion needed).
    fn as_f32(&self) -> Option<&[[f32; N]]> {
        None
    }
}

impl<const N: usize> VertexData<N> for [[f32; N]] {
    #[inline]
    fn num_vertices(&self) -> usize {
        self.len()
    }
    #[inline]
    fn vertex<R: Real>(&self, i: usize) -> [R; N] {
        self[i].map(R::from_f32)
    }
    #[inline]
    fn as_f32(&self) -> Option<&[[f32; N]]> {
        Some(self)
    }
}

impl<const N: usize> VertexData<N> for [[f64; N]] {
    #[inline]
    fn num_vertices(&self) -> usize {
        self.len()
    }
    #[inline]
    fn vertex<R: Real>(&self, i: usize) -> [R; N] {
        self[i].map(R::from_f64)
    }
}

impl<const N: usize, T: Copy> VertexData<N> for Vec<[T; N]>
where
    [[T; N]]: VertexData<N>,
{
    #[inline]
    fn num_vertices(&self) -> usize {
        self.len()
    }
    #[inline]
    fn vertex<R: Real>(&self, i: usize) -> [R; N] {
        self.as_slice().vertex(i)
    }
    #[inline]
    fn as_f32(&self) -> Option<&[[f32; N]]> {
        self.as_slice().as_f32()
    }
}

impl<const N: usize, T: VertexData<N> + ?Sized> VertexData<N> for &T {
    #[inline]
    fn num_vertices(&self) -> usize {
        (**self).num_vertices()
    }
    #[inline]
    fn vertex<R: Real>(&self, i: usize) -> [R; N] {
        (**self).vertex(i)
    }
    #[inline]
    fn as_f32(&self) -> Option<&[[f32; N]]> {
        (**self).as_f32()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pow2_is_exact() {
        for k in -30..30 {
            assert_eq!(<f32 as Real>::pow2(k), 2f32.powi(k));
            assert_eq!(<f64 as Real>::pow2(k), 2f64.powi(k));
        }
    }
}
