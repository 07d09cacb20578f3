//! Three-component values summed in one 4-lane SSE register (x86-64 only; SSE2 is part of the
//! baseline there, so no feature detection is needed).
//!
//! A row's sum `acc += w · v` is formed lane by lane with the same IEEE single-precision
//! products and sums as the scalar loop, so the results are bit-identical; the gain is one
//! 16-byte load, one multiply and one add per entry instead of three of each. The fourth lane
//! holds whatever follows the value in memory and is never stored. The last value of a slice
//! is loaded component by component, so nothing is read past the slice. The intrinsics and
//! the `N == 3` slice casts are the only unsafe code, each with its reason.
#![allow(unsafe_code)]

use super::smooth_frame::Acc;
use std::arch::x86_64::{
    __m128, _mm_add_ps, _mm_loadu_ps, _mm_mul_ps, _mm_set1_ps, _mm_set_ps, _mm_setzero_ps,
    _mm_storeu_ps,
};

/// A running sum of `[f32; 3]` values in the first three lanes of a register.
#[derive(Clone, Copy)]
pub(crate) struct Lanes3(__m128);

impl Lanes3 {
    /// `self += w · x` lane by lane.
    #[inline(always)]
    fn mul_add(&mut self, w: f32, x: __m128) {
        // SAFETY: SSE is part of the x86-64 baseline.
        self.0 = unsafe { _mm_add_ps(self.0, _mm_mul_ps(_mm_set1_ps(w), x)) };
    }
}

impl Acc<3> for Lanes3 {
    #[inline(always)]
    fn zero() -> Self {
        // SAFETY: SSE is part of the x86-64 baseline.
        Lanes3(unsafe { _mm_setzero_ps() })
    }

    #[inline(always)]
    fn add(&mut self, w: f32, v: &[[f32; 3]], k: usize) {
        let x = if k + 1 < v.len() {
            // SAFETY: `v[k]` and `v[k + 1]` are in the slice, so the 16 bytes from `v[k]` are
            // too (12 of `v[k]`, 4 of `v[k + 1]`); `loadu` needs no alignment.
            unsafe { _mm_loadu_ps(v.as_ptr().add(k).cast::<f32>()) }
        } else {
            let [a, b, c] = v[k];
            // SAFETY: SSE is part of the x86-64 baseline.
            unsafe { _mm_set_ps(0.0, c, b, a) }
        };
        self.mul_add(w, x);
    }

    #[inline(always)]
    fn add_padded(&mut self, w: f32, v: &[[f32; 3]], k: usize) {
        self.add_at_padded(w, v, 3 * k);
    }

    #[inline(always)]
    fn add_at_padded(&mut self, w: f32, v: &[[f32; 3]], off: usize) {
        // Value `off / 3` and the one after it are in the slice.
        if off >= 3 * v.len().saturating_sub(1) {
            super::smooth_frame::past_the_values(off / 3, v.len());
        }
        // SAFETY: `off < 3 * (v.len() - 1)`, so `off + 4 <= 3 * v.len()`: the 16 bytes from
        // float `off` are in the slice; `loadu` needs no alignment.
        self.mul_add(w, unsafe {
            _mm_loadu_ps(v.as_ptr().cast::<f32>().add(off))
        });
    }

    #[inline(always)]
    fn get(self) -> [f32; 3] {
        let mut lanes = [0.0f32; 4];
        // SAFETY: `lanes` holds 16 bytes; `storeu` needs no alignment.
        unsafe { _mm_storeu_ps(lanes.as_mut_ptr(), self.0) };
        [lanes[0], lanes[1], lanes[2]]
    }
}

/// `v` as three-component values when `N` is 3.
#[inline]
pub(crate) fn as3<const N: usize>(v: &[[f32; N]]) -> Option<&[[f32; 3]]> {
    // SAFETY: with N == 3 the two slice types are the same type.
    (N == 3).then(|| unsafe { std::slice::from_raw_parts(v.as_ptr().cast(), v.len()) })
}

/// `v` as three-component values when `N` is 3.
#[inline]
pub(crate) fn as3_mut<const N: usize>(v: &mut [[f32; N]]) -> Option<&mut [[f32; 3]]> {
    // SAFETY: with N == 3 the two slice types are the same type.
    (N == 3).then(|| unsafe { std::slice::from_raw_parts_mut(v.as_mut_ptr().cast(), v.len()) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_sum_bit_for_bit_as_the_scalar_loop() {
        // Values of every magnitude (and the last one, loaded component by component):
        // the same bits as the scalar accumulation, whatever follows in memory.
        let v: Vec<[f32; 3]> = (0..37)
            .map(|i| {
                let t = i as f32 * 0.731 - 9.0;
                [t.sin() * 1e3, t.cos() * 1e-3, (t * t).sqrt() - 3.3]
            })
            .collect();
        let ws = [0.0625f32, 0.5, 0.25, 1.0 / 3.0, 0.1];
        for start in 0..v.len() {
            let mut lanes = Lanes3::zero();
            let mut scalar = <[f32; 3] as Acc<3>>::zero();
            for (j, k) in (start..v.len()).rev().chain([start]).enumerate() {
                let w = ws[j % ws.len()];
                lanes.add(w, &v, k);
                scalar.add(w, &v, k);
            }
            assert_eq!(lanes.get().map(f32::to_bits), scalar.map(f32::to_bits));
        }
    }
}
