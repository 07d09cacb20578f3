//! A peer's distance from OpenSubdiv's last-level positions: vertex by vertex where the peer
//! numbers vertices as OpenSubdiv does, else from each of its vertices to the nearest of
//! OpenSubdiv's (a uniform grid; the peer's vertex order is then reported as different).

use std::collections::HashMap;

/// Largest distance, and whether it was taken index by index (same vertex order).
#[derive(Debug, Clone, Copy)]
pub struct Distance {
    pub max: f64,
    pub same_order: bool,
}

fn dist(a: &[f32; 3], b: &[f32; 3]) -> f64 {
    let d: f64 = (0..3).map(|c| (a[c] as f64 - b[c] as f64).powi(2)).sum();
    d.sqrt()
}

/// `got` against `want` (OpenSubdiv's), `tol` the distance below which index order is
/// accepted as the same.
pub fn distance(want: &[[f32; 3]], got: &[[f32; 3]], tol: f64) -> Distance {
    if want.len() == got.len() {
        let max = want
            .iter()
            .zip(got)
            .map(|(a, b)| dist(a, b))
            .fold(0.0, f64::max);
        if max <= tol {
            return Distance {
                max,
                same_order: true,
            };
        }
    }
    Distance {
        max: nearest_max(want, got),
        same_order: false,
    }
}

/// Max over `got` of the distance to the nearest point of `want`.
fn nearest_max(want: &[[f32; 3]], got: &[[f32; 3]]) -> f64 {
    let (lo, hi) = want
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1]), lo[2].min(p[2])],
                [hi[0].max(p[0]), hi[1].max(p[1]), hi[2].max(p[2])],
            )
        });
    let diag = dist(&lo, &hi).max(f64::MIN_POSITIVE);
    let h = diag / (want.len() as f64).cbrt().max(1.0);
    let cell = |p: &[f32; 3]| -> [i64; 3] {
        [0, 1, 2].map(|c| ((p[c] as f64 - lo[c] as f64) / h).floor() as i64)
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (i, p) in want.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(i as u32);
    }
    let mut max = 0.0f64;
    for p in got {
        let c = cell(p);
        let mut best = f64::MAX;
        // Widen the search ring until a point is found and no nearer one can lie outside.
        for r in 0i64.. {
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        if let Some(v) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            for &i in v {
                                best = best.min(dist(p, &want[i as usize]));
                            }
                        }
                    }
                }
            }
            if best <= r as f64 * h || r > 64 {
                break;
            }
        }
        max = max.max(best);
    }
    max
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice() -> Vec<[f32; 3]> {
        (0..1000)
            .map(|i| [(i % 10) as f32, ((i / 10) % 10) as f32, (i / 100) as f32])
            .collect()
    }

    #[test]
    fn same_order_is_taken_index_by_index() {
        let a = lattice();
        let mut b = a.clone();
        b[17][2] += 1e-6;
        let d = distance(&a, &b, 1e-3);
        assert!(d.same_order);
        assert!((d.max - 1e-6).abs() < 1e-7, "{}", d.max);
    }

    #[test]
    fn a_permutation_is_matched_to_nearest() {
        let a = lattice();
        // Reversed and moved by 0.01 along x: nearest distance 0.01, index distance large.
        let b: Vec<[f32; 3]> = a.iter().rev().map(|p| [p[0] + 0.01, p[1], p[2]]).collect();
        let d = distance(&a, &b, 1e-3);
        assert!(!d.same_order);
        assert!((d.max - 0.01).abs() < 1e-6, "{}", d.max);
    }
}
