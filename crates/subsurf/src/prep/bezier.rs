//! Conversion of a p-rep patch to its bi-5 Bernstein-Bézier form (Myles, Yeo & Peters 2008,
//! eq. (10); spec §6):
//!
//! ```text
//! b = E g Eᵀ + h,     E (6×4) = 1/10 [[10,0,0,0],[4,6,0,0],[1,6,3,0],[0,3,6,1],[0,0,6,4],[0,0,0,10]]
//! ```
//!
//! `E` raises a cubic to degree 5. Rendering should evaluate the p-rep form (`g` bi-3 plus
//! sparse `h` bi-5, see [`super::eval`]) because the conversion re-rounds the shared
//! boundary; `b` is for export and for the reference checker.

use super::patch_pass::H_SLOTS;
use crate::real::Real;
use crate::util::vec3::V3;

/// Degree-raising matrix `E` (6×4), times 10.
const E10: [[f64; 4]; 6] = [
    [10.0, 0.0, 0.0, 0.0],
    [4.0, 6.0, 0.0, 0.0],
    [1.0, 6.0, 3.0, 0.0],
    [0.0, 3.0, 6.0, 1.0],
    [0.0, 0.0, 6.0, 4.0],
    [0.0, 0.0, 0.0, 10.0],
];

/// The 36 bi-5 control points `b[6 i + j]` of one patch from its `g` (16, `g[4 i + j]`) and
/// its compact `h` (16 in [`H_SLOTS`] order, `None` for a B-quad).
pub fn face_bezier<T: Real>(g: &[V3<T>], h: Option<&[V3<T>]>) -> [V3<T>; 36] {
    let e: [[T; 4]; 6] = E10.map(|r| r.map(|x| T::from_f64(x / 10.0)));
    // t[i][b] = Σ_a E[i][a] g[a][b]
    let mut t = [[[T::zero(); 3]; 4]; 6];
    for i in 0..6 {
        for b in 0..4 {
            for a in 0..4 {
                for k in 0..3 {
                    t[i][b][k] += e[i][a] * g[4 * a + b][k];
                }
            }
        }
    }
    let mut out = [[T::zero(); 3]; 36];
    for i in 0..6 {
        for j in 0..6 {
            for b in 0..4 {
                for k in 0..3 {
                    out[6 * i + j][k] += e[j][b] * t[i][b][k];
                }
            }
        }
    }
    if let Some(h) = h {
        for (s, &(i, j)) in H_SLOTS.iter().enumerate() {
            for k in 0..3 {
                out[6 * i + j][k] += h[s][k];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Degree raising reproduces a bilinear function exactly: g_ij = (i/3, j/3, ij/9) gives
    /// b_ij = (i/5, j/5, ij/25).
    #[test]
    fn degree_raising_of_bilinear() {
        let g: Vec<V3<f64>> = (0..16)
            .map(|x| {
                let (i, j) = ((x / 4) as f64, (x % 4) as f64);
                [i / 3.0, j / 3.0, i * j / 9.0]
            })
            .collect();
        let b = face_bezier(&g, None);
        for i in 0..6 {
            for j in 0..6 {
                let (fi, fj) = (i as f64, j as f64);
                let want = [fi / 5.0, fj / 5.0, fi * fj / 25.0];
                for k in 0..3 {
                    assert!((b[6 * i + j][k] - want[k]).abs() < 1e-15);
                }
            }
        }
    }
}
