//! Three-component values of a [`Real`] as one value ([`Real::V3`]): for `f32` on x86-64 one
//! 4-lane SSE register, elsewhere the array itself.
//!
//! Every operation is lane by lane, with the same IEEE operations in the same order as the
//! array loops it replaces, so the results are bit-identical (tested); the gain is one load,
//! multiply and add per point instead of three of each where a patch's points are summed
//! ([`crate::limit::curve_eval`]). The fourth lane is kept at zero: a load masks it, and
//! every operation keeps it there.

use super::Real;
use std::fmt::Debug;

/// A point or vector of three `R` (module documentation).
pub trait Vec3<R>: Copy + Debug + Send + Sync {
    /// `[0, 0, 0]`.
    fn zero() -> Self;
    /// From an array.
    fn from_array(a: [R; 3]) -> Self;
    /// Value `k` of `v`.
    fn load(v: &[[R; 3]], k: usize) -> Self;
    /// As an array.
    fn to_array(self) -> [R; 3];
    /// `self + o`.
    fn add(self, o: Self) -> Self;
    /// `self − o`.
    fn sub(self, o: Self) -> Self;
    /// `w · self`.
    fn scale(self, w: R) -> Self;
    /// `self + w · x`.
    #[inline(always)]
    fn mul_add(self, w: R, x: Self) -> Self {
        self.add(x.scale(w))
    }
}

impl<R: Real> Vec3<R> for [R; 3] {
    #[inline(always)]
    fn zero() -> Self {
        [R::ZERO; 3]
    }
    #[inline(always)]
    fn from_array(a: [R; 3]) -> Self {
        a
    }
    #[inline(always)]
    fn load(v: &[[R; 3]], k: usize) -> Self {
        v[k]
    }
    #[inline(always)]
    fn to_array(self) -> [R; 3] {
        self
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        [self[0] + o[0], self[1] + o[1], self[2] + o[2]]
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        [self[0] - o[0], self[1] - o[1], self[2] - o[2]]
    }
    #[inline(always)]
    fn scale(self, w: R) -> Self {
        [w * self[0], w * self[1], w * self[2]]
    }
}

#[cfg(target_arch = "x86_64")]
pub use sse::Sse3;

/// The `f32` value of [`Real::V3`] where no SSE is at hand.
#[cfg(not(target_arch = "x86_64"))]
pub type Sse3 = [f32; 3];

#[cfg(target_arch = "x86_64")]
#[allow(unsafe_code)]
mod sse {
    use super::Vec3;
    use std::arch::x86_64::{
        __m128, _mm_add_ps, _mm_and_ps, _mm_castsi128_ps, _mm_loadu_ps, _mm_mul_ps, _mm_set1_ps,
        _mm_set_epi32, _mm_set_ps, _mm_setzero_ps, _mm_storeu_ps, _mm_sub_ps,
    };

    /// Three `f32` in the first lanes of an SSE register, the fourth zero.
    #[derive(Clone, Copy, Debug)]
    pub struct Sse3(__m128);

    // SAFETY (every intrinsic below): SSE and SSE2 are part of the x86-64 baseline; the loads
    // and stores name their bounds where they touch memory.
    impl Vec3<f32> for Sse3 {
        #[inline(always)]
        fn zero() -> Self {
            Sse3(unsafe { _mm_setzero_ps() })
        }
        #[inline(always)]
        fn from_array([a, b, c]: [f32; 3]) -> Self {
            Sse3(unsafe { _mm_set_ps(0.0, c, b, a) })
        }
        #[inline(always)]
        fn load(v: &[[f32; 3]], k: usize) -> Self {
            if k + 1 < v.len() {
                // SAFETY: `v[k]` and `v[k + 1]` are in the slice, so the 16 bytes from `v[k]`
                // are too (12 of `v[k]`, 4 of `v[k + 1]`, masked off); `loadu` needs no
                // alignment.
                unsafe {
                    let x = _mm_loadu_ps(v.as_ptr().add(k).cast::<f32>());
                    Sse3(_mm_and_ps(
                        x,
                        _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1)),
                    ))
                }
            } else {
                Self::from_array(v[k])
            }
        }
        #[inline(always)]
        fn to_array(self) -> [f32; 3] {
            let mut lanes = [0.0f32; 4];
            // SAFETY: `lanes` holds 16 bytes; `storeu` needs no alignment.
            unsafe { _mm_storeu_ps(lanes.as_mut_ptr(), self.0) };
            [lanes[0], lanes[1], lanes[2]]
        }
        #[inline(always)]
        fn add(self, o: Self) -> Self {
            Sse3(unsafe { _mm_add_ps(self.0, o.0) })
        }
        #[inline(always)]
        fn sub(self, o: Self) -> Self {
            Sse3(unsafe { _mm_sub_ps(self.0, o.0) })
        }
        #[inline(always)]
        fn scale(self, w: f32) -> Self {
            Sse3(unsafe { _mm_mul_ps(_mm_set1_ps(w), self.0) })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation of the `f32` value equals the array's bit for bit, on values of
    /// every magnitude and sign, and reads no further than the slice.
    #[test]
    fn lanes_equal_arrays_bit_for_bit() {
        let mut seed = 0x2545_f491u32;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            let m = (seed >> 8) as f32 / (1 << 24) as f32 - 0.5;
            m * 2f32.powi((seed % 40) as i32 - 20)
        };
        let v: Vec<[f32; 3]> = (0..64).map(|_| [next(), next(), next()]).collect();
        let bits = |a: [f32; 3]| a.map(f32::to_bits);
        for k in 0..v.len() {
            let j = (k * 7 + 3) % v.len();
            let (a, b) = (Sse3::load(&v, k), Sse3::load(&v, j));
            let (x, y) = (v[k], v[j]);
            let w = next();
            assert_eq!(bits(a.to_array()), bits(x));
            assert_eq!(bits(a.add(b).to_array()), bits(x.add(y)));
            assert_eq!(bits(a.sub(b).to_array()), bits(x.sub(y)));
            assert_eq!(bits(a.scale(w).to_array()), bits(x.scale(w)));
            assert_eq!(bits(a.mul_add(w, b).to_array()), bits(x.mul_add(w, y)));
            assert_eq!(bits(Sse3::from_array(x).to_array()), bits(x));
        }
        // The last value alone (no read past it).
        let last = &v[..1];
        assert_eq!(bits(Sse3::load(last, 0).to_array()), bits(v[0]));
        assert_eq!(bits(Sse3::zero().to_array()), [0; 3]);
    }
}
