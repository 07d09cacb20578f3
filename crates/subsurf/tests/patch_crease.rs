//! The single-crease patch of `subsurf::patch` against a brute-force Catmull-Clark
//! refinement with a crease line (implemented here, independently of the library), the test
//! vectors of `shared/spec/creases.md` §6, continuity in the sharpness and the parameter, and
//! the stability of the `f32` path.

mod patch_common;
use patch_common::*;

use subsurf::patch::{
    bspline_curve, crease_curve, eval_bspline_patch, eval_single_crease_patch,
    single_crease_patch_weights, PatchEdge,
};

// ---------------------------------------------------------------------------------------
// Brute-force Catmull-Clark with one crease line (test-only reference)
// ---------------------------------------------------------------------------------------

/// A square grid of points `p[y][x]` at coordinates `(x0 + x h, x0 + y h)` with one vertical
/// crease line at coordinate `xc` of sharpness `sharp` (≥ 10: infinitely sharp).
struct CreaseGrid {
    p: Vec<Vec<P3>>,
    x0: f64,
    h: f64,
    xc: f64,
    sharp: f64,
}

fn avg(pts: &[P3]) -> P3 {
    let n = pts.len() as f64;
    std::array::from_fn(|c| pts.iter().map(|q| q[c]).sum::<f64>() / n)
}

fn lerp(a: &P3, b: &P3, t: f64) -> P3 {
    std::array::from_fn(|c| (1.0 - t) * a[c] + t * b[c])
}

impl CreaseGrid {
    fn crease_col(&self) -> Option<usize> {
        let c = (self.xc - self.x0) / self.h;
        (c >= 0.0 && c.fract() == 0.0).then_some(c as usize)
    }

    /// One level of Catmull-Clark: face, edge and vertex points with the crease rules
    /// (sharp edge midpoint, crease vertex (1,6,1)/8, linear blend for sharpness in (0,1))
    /// and uniform sharpness decay. The outermost ring is dropped.
    fn refine(&self) -> CreaseGrid {
        let n = self.p.len();
        let p = &self.p;
        let c = self.crease_col();
        let s = self.sharp;
        let face = |x: usize, y: usize| avg(&[p[y][x], p[y][x + 1], p[y + 1][x], p[y + 1][x + 1]]);
        let m = 2 * n - 5;
        let mut out = vec![vec![[0.0; 3]; m]; m];
        for (yy, row) in out.iter_mut().enumerate() {
            for (xx, q) in row.iter_mut().enumerate() {
                let (x, y) = (1 + xx / 2, 1 + yy / 2);
                *q = match (xx % 2, yy % 2) {
                    (1, 1) => face(x, y),
                    (1, 0) => {
                        // horizontal edge (x,y)-(x+1,y): never on the vertical crease
                        avg(&[p[y][x], p[y][x + 1], face(x, y - 1), face(x, y)])
                    }
                    (0, 1) => {
                        // vertical edge (x,y)-(x,y+1)
                        let smooth = avg(&[p[y][x], p[y + 1][x], face(x - 1, y), face(x, y)]);
                        if Some(x) == c && s > 0.0 {
                            let sharp = avg(&[p[y][x], p[y + 1][x]]);
                            lerp(&smooth, &sharp, s.min(1.0))
                        } else {
                            smooth
                        }
                    }
                    _ => {
                        let fq = avg(&[
                            face(x - 1, y - 1),
                            face(x, y - 1),
                            face(x - 1, y),
                            face(x, y),
                        ]);
                        let er = avg(&[
                            avg(&[p[y][x], p[y][x - 1]]),
                            avg(&[p[y][x], p[y][x + 1]]),
                            avg(&[p[y][x], p[y - 1][x]]),
                            avg(&[p[y][x], p[y + 1][x]]),
                        ]);
                        let smooth: P3 =
                            std::array::from_fn(|k| (fq[k] + 2.0 * er[k] + p[y][x][k]) / 4.0);
                        if Some(x) == c && s > 0.0 {
                            let crease: P3 = std::array::from_fn(|k| {
                                (p[y - 1][x][k] + 6.0 * p[y][x][k] + p[y + 1][x][k]) / 8.0
                            });
                            lerp(&smooth, &crease, s.min(1.0))
                        } else {
                            smooth
                        }
                    }
                };
            }
        }
        CreaseGrid {
            p: out,
            x0: self.x0 + self.h,
            h: self.h / 2.0,
            xc: self.xc,
            sharp: if s >= 10.0 { s } else { (s - 1.0).max(0.0) },
        }
    }

    /// Limit position and derivatives (per unit of the coarse grid) at grid vertex (x, y),
    /// by the regular limit stencils (1,4,1)/6 and (−1,0,1)/2, valid where every later
    /// rule in the vertex's 3×3 neighbourhood is smooth. On an infinitely sharp crease line
    /// the limit is the cubic B-spline of the line: (1,4,1)/6 along it.
    fn limit(&self, x: usize, y: usize) -> (P3, P3, P3) {
        let w = [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0];
        let d = [-0.5, 0.0, 0.5];
        let p = &self.p;
        if self.sharp >= 10.0 && Some(x) == self.crease_col() {
            let pos = std::array::from_fn(|c| (0..3).map(|b| w[b] * p[y + b - 1][x][c]).sum());
            let dv = std::array::from_fn(|c| {
                (0..3).map(|b| d[b] * p[y + b - 1][x][c]).sum::<f64>() / self.h
            });
            return (pos, [f64::NAN; 3], dv);
        }
        let mut pos = [0.0; 3];
        let mut du = [0.0; 3];
        let mut dv = [0.0; 3];
        for b in 0..3 {
            for a in 0..3 {
                let q = p[y + b - 1][x + a - 1];
                for c in 0..3 {
                    pos[c] += w[a] * w[b] * q[c];
                    du[c] += d[a] * w[b] * q[c] / self.h;
                    dv[c] += w[a] * d[b] * q[c] / self.h;
                }
            }
        }
        (pos, du, dv)
    }
}

/// Builds an 8×8 grid at coordinates −2..=5 whose points 2..=5 in both directions are the
/// patch points (coordinates 0..=3; the patch covers [1,2]²) and the rest random.
fn crease_grid(pts: &[P3; 16], xc: f64, sharp: f64, seed: u64) -> CreaseGrid {
    let mut r = Rng(seed);
    let mut p = vec![vec![[0.0; 3]; 8]; 8];
    for (y, row) in p.iter_mut().enumerate() {
        for (x, q) in row.iter_mut().enumerate() {
            let (i, j) = (x as i64 - 2, y as i64 - 2);
            *q = if (0..4).contains(&i) && (0..4).contains(&j) {
                pts[(4 * j + i) as usize]
            } else {
                let n = r.point();
                [i as f64 + 0.3 * n[0], j as f64 + 0.3 * n[1], n[2]]
            };
        }
    }
    CreaseGrid {
        p,
        x0: -2.0,
        h: 1.0,
        xc,
        sharp,
    }
}

fn transpose(pts: &[P3; 16]) -> [P3; 16] {
    std::array::from_fn(|k| pts[4 * (k % 4) + k / 4])
}

/// Refines `levels` times and compares every refined vertex over the patch with `eval`
/// (given patch (u, v)); returns the number of samples compared.
fn compare_with_brute_force(
    grid: CreaseGrid,
    levels: usize,
    eval: &dyn Fn(f64, f64) -> (P3, P3, P3),
    tol: f64,
    what: &str,
) -> usize {
    let mut g = grid;
    for _ in 0..levels {
        g = g.refine();
    }
    let c = g.crease_col();
    let mut count = 0;
    let n = g.p.len();
    for y in 1..n - 1 {
        for x in 1..n - 1 {
            let (gx, gy) = (g.x0 + x as f64 * g.h, g.x0 + y as f64 * g.h);
            if !(1.0..=2.0).contains(&gx) || !(1.0..=2.0).contains(&gy) {
                continue;
            }
            if g.sharp > 0.0 {
                // Still creased (infinitely sharp): only the crease line and vertices two
                // or more steps away from it have exact regular limit stencils.
                let cc = c.expect("crease column on the grid");
                if x.abs_diff(cc) == 1 {
                    continue;
                }
            }
            let (pos, du, dv) = g.limit(x, y);
            let (u, v) = (gx - 1.0, gy - 1.0);
            let (ep, edu, edv) = eval(u, v);
            assert!(
                dist(&pos, &ep) < tol,
                "{what}: position at ({u},{v}): {pos:?} vs {ep:?}"
            );
            if du[0].is_finite() {
                assert!(dist(&du, &edu) < tol * 10.0, "{what}: du at ({u},{v})");
            }
            assert!(dist(&dv, &edv) < tol * 10.0, "{what}: dv at ({u},{v})");
            count += 1;
        }
    }
    count
}

#[test]
fn single_crease_matches_brute_force_refinement() {
    let pts = random_grid(3);
    for &s in &[0.0f64, 0.4, 1.0, 1.5, 2.0, 2.7, 3.0, 4.25] {
        let levels = s.ceil() as usize + 1;
        for edge in PatchEdge::ALL {
            // Brute force creases a vertical line; v-edges are checked on the transposed
            // grid with u and v swapped.
            let (xc, transposed) = match edge {
                PatchEdge::U1 => (2.0, false),
                PatchEdge::U0 => (1.0, false),
                PatchEdge::V1 => (2.0, true),
                PatchEdge::V0 => (1.0, true),
            };
            let grid_pts = if transposed { transpose(&pts) } else { pts };
            let eval = |u: f64, v: f64| {
                if transposed {
                    let e = eval_single_crease_patch(&pts, v, u, edge, s);
                    (e.p, e.dv, e.du)
                } else {
                    let e = eval_single_crease_patch(&pts, u, v, edge, s);
                    (e.p, e.du, e.dv)
                }
            };
            let n = compare_with_brute_force(
                crease_grid(&grid_pts, xc, s, 99),
                levels,
                &eval,
                1e-10,
                &format!("s = {s}, edge {edge:?}"),
            );
            assert_eq!(n, ((1 << levels) + 1) * ((1 << levels) + 1));
        }
    }
}

#[test]
fn infinitely_sharp_crease_equals_boundary_patch_and_brute_force() {
    let pts = random_grid(21);
    for edge in PatchEdge::ALL {
        for k in 0..=8 {
            for l in 0..=8 {
                let (u, v) = (k as f64 / 8.0, l as f64 / 8.0);
                let b = eval_bspline_patch(&pts, u, v, edge.mask());
                for s in [10.0, 12.5] {
                    let c = eval_single_crease_patch(&pts, u, v, edge, s);
                    assert_eq!(b, c, "edge {edge:?} s {s}");
                }
            }
        }
    }
    // The boundary (phantom point) patch is the limit of the sharp rules on its side.
    for (edge, xc) in [(PatchEdge::U1, 2.0), (PatchEdge::U0, 1.0)] {
        let eval = |u: f64, v: f64| {
            let e = eval_bspline_patch(&pts, u, v, edge.mask());
            (e.p, e.du, e.dv)
        };
        let n = compare_with_brute_force(
            crease_grid(&pts, xc, 10.0, 5),
            6,
            &eval,
            1e-10,
            &format!("infinite crease {edge:?}"),
        );
        assert!(n > 60 * 60, "{n}");
    }
}

#[test]
fn zero_sharpness_is_the_plain_bspline_patch() {
    let pts = random_grid(4);
    for edge in PatchEdge::ALL {
        for s in [0.0, -1.0, f64::NAN] {
            for k in 0..=8 {
                for l in 0..=8 {
                    let (u, v) = (k as f64 / 8.0, l as f64 / 8.0);
                    assert_eq!(
                        eval_single_crease_patch(&pts, u, v, edge, s),
                        eval_bspline_patch(&pts, u, v, 0)
                    );
                }
            }
        }
    }
}

#[test]
fn single_crease_partition_of_unity_and_finite_differences() {
    let pts = random_grid(8);
    for edge in PatchEdge::ALL {
        for s in [0.5, 1.0, 2.3, 5.0, 9.5] {
            for k in 0..=16 {
                for l in 0..=4 {
                    let (u, v) = (k as f64 / 16.0, l as f64 / 4.0);
                    let w = single_crease_patch_weights(u, v, edge, s);
                    let scale = 2f64.powf(2.0 * s);
                    let s6 = sums(&w);
                    assert!((s6[0] - 1.0).abs() < 1e-14);
                    assert!(s6[1..].iter().all(|x| x.abs() < 1e-12 * scale));
                }
            }
            // Finite differences inside each part (away from the joins, where the second
            // derivative is continuous but varies quickly).
            for (u, v) in [(0.2, 0.3), (0.45, 0.6), (0.7, 0.9)] {
                check_fd(
                    &|u, v| eval_single_crease_patch(&pts, u, v, edge, s),
                    u,
                    v,
                    1e-6,
                    &format!("crease {edge:?} s={s}"),
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Single-crease curve: spec test vectors, continuity, f32 stability
// ---------------------------------------------------------------------------------------

const SPEC_P: [P3; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 2.0, 0.0],
    [3.0, 2.0, 1.0],
    [4.0, 0.0, 0.0],
];

fn curve_at(t: f64, s: f64, p: &[P3; 4]) -> P3 {
    let w = crease_curve(t, s);
    std::array::from_fn(|c| (0..4).map(|k| w.p[k] * p[k][c]).sum())
}

fn bspline_at(t: f64, p: &[P3; 4]) -> P3 {
    let w = bspline_curve(t);
    std::array::from_fn(|c| (0..4).map(|k| w.p[k] * p[k][c]).sum())
}

#[test]
fn spec_test_vectors() {
    let tol = 1e-9;
    let check = |s: f64, t: f64, want: P3| {
        let got = curve_at(t, s, &SPEC_P);
        assert!(dist(&got, &want) < tol, "s={s} t={t}: {got:?} vs {want:?}");
    };
    let third = 1.0 / 3.0;
    check(1.0, 0.0, [7.0 / 6.0, 5.0 / 3.0, 1.0 / 6.0]);
    check(1.0, 0.25, [1.5703125, 1.859375, 0.3203125]);
    check(1.0, 0.5, [2.0208333333, 1.9583333333, 0.5208333333]);
    check(1.0, 0.75, [2.4921875, 1.9739583333, 0.7317708333]);
    check(1.0, 1.0, [2.9166666667, 1.8333333333, 0.8333333333]);
    check(2.0, 0.625, [2.2587890625, 1.982421875, 0.6337890625]);
    check(2.0, 0.75, [2.5026041667, 1.9947916667, 0.7526041667]);
    check(2.0, 0.875, [2.7451171875, 1.9889322917, 0.8649088542]);
    check(2.0, 1.0, [2.9583333333, 1.9166666667, 0.9166666667]);
    check(1.5, 0.625, [2.2581380208, 1.9811197917, 0.6324869792]);
    check(1.5, 0.75, [2.4973958333, 1.984375, 0.7421875]);
    check(1.5, 0.875, [2.7301432292, 1.958984375, 0.8349609375]);
    check(1.5, 1.0, [2.9375, 1.875, 0.875]);
    for s in [1.0, 1.5, 2.0, 3.7] {
        check(s, 0.25, [1.5703125, 1.859375, 0.3203125]);
    }
    // s = 1.5 in the paper's form: the middle part is N(t) P∞^ and the last part N(t) Ps^
    // with the spec's transformed control points.
    let p_inf_hat = [
        [0.625, 1.25, 1.25],
        [0.875, 1.75, -0.25],
        [3.125, 2.25, 1.25],
        [4.375, 0.75, 0.75],
    ];
    let p_s_hat = [
        [5.4375, 10.875, 10.875],
        [0.4375, 0.875, -1.125],
        [3.4375, 2.875, 1.875],
        [3.4375, -1.125, -1.125],
    ];
    for k in 1..=32 {
        let t = 0.5 + 0.25 * k as f64 / 32.0;
        assert!(dist(&curve_at(t, 1.5, &SPEC_P), &bspline_at(t, &p_inf_hat)) < 1e-12);
        let t = 0.75 + 0.25 * k as f64 / 32.0;
        assert!(dist(&curve_at(t, 1.5, &SPEC_P), &bspline_at(t, &p_s_hat)) < 1e-12);
    }
    // Smooth and infinitely sharp ends for comparison (spec §6).
    check(0.0, 1.0, [17.0 * third / 2.0, 5.0 / 3.0, 2.0 * third]);
    check(10.0, 1.0, [3.0, 2.0, 1.0]);
}

#[test]
fn continuous_in_sharpness() {
    let pts = random_grid(12);
    let eps = 1e-7;
    for s in [0.0, 0.5, 1.0, 1.999_999, 2.0, 3.0, 4.5, 7.0, 9.0] {
        for edge in [PatchEdge::U1, PatchEdge::V0] {
            for k in 0..=64 {
                let (u, v) = (k as f64 / 64.0, 1.0 - k as f64 / 64.0);
                let a = eval_single_crease_patch(&pts, u, v, edge, s);
                let b = eval_single_crease_patch(&pts, u, v, edge, s + eps);
                assert!(dist(&a.p, &b.p) < 10.0 * eps, "s = {s} at ({u},{v})");
                if s >= eps {
                    let c = eval_single_crease_patch(&pts, u, v, edge, s - eps);
                    assert!(dist(&a.p, &c.p) < 10.0 * eps, "s = {s}− at ({u},{v})");
                }
            }
        }
    }
}

#[test]
fn c2_across_the_segment_joins() {
    let mut r = Rng(77);
    let p: [P3; 4] = std::array::from_fn(|_| r.point());
    for s in [1.0f64, 2.0, 2.5, 3.3, 6.0, 8.75] {
        let m = s.floor() as i32;
        let joins = [1.0 - 2f64.powi(-m), 1.0 - 2f64.powi(-(m + 1))];
        for t0 in joins {
            // Steps scaled to the part's length, so the third derivative (~ 2^(3m)) moves
            // the second one by less than the tolerance.
            let h = 1e-9 * 2f64.powi(-(m + 1));
            let (a, b) = (crease_curve(t0 - h, s), crease_curve(t0 + h, s));
            let d2scale = 1.0 + b.d2.iter().map(|x| x.abs()).sum::<f64>();
            for c in 0..3 {
                let f = |w: &[f64; 4]| (0..4).map(|k| w[k] * p[k][c]).sum::<f64>();
                assert!((f(&a.p) - f(&b.p)).abs() < 1e-8, "s={s} t={t0}");
                assert!((f(&a.d1) - f(&b.d1)).abs() < 1e-6 * 2f64.powf(s));
                assert!((f(&a.d2) - f(&b.d2)).abs() < 1e-5 * d2scale);
            }
        }
    }
}

#[test]
fn f32_evaluation_is_stable_for_every_sharpness() {
    // The f32 path against the f64 one, with |P| ~ 1: positions and first derivatives keep
    // f32 precision (a few ulps) at every sharpness (spec §5: the paper's M_s form loses
    // ~2.6e-4 at s = 10).
    let mut r = Rng(31);
    let p: [P3; 4] = std::array::from_fn(|_| r.point());
    let p32: [[f32; 3]; 4] = std::array::from_fn(|k| std::array::from_fn(|c| p[k][c] as f32));
    let mut worst_p = 0.0f64;
    let mut worst_d = 0.0f64;
    for si in 0..=40 {
        let s = si as f64 * 0.25;
        for k in 0..=400 {
            // Dense near the crease end, where the transition parts live.
            let d = 2f64.powf(-(k as f64) / 40.0);
            // The same input in both precisions, so only the arithmetic differs.
            let t32 = (1.0 - d) as f32;
            let w64 = crease_curve(t32 as f64, s);
            let w32 = crease_curve(t32, s as f32);
            for c in 0..3 {
                let e64: f64 = (0..4).map(|k| w64.p[k] * p[k][c]).sum();
                let e32: f32 = (0..4).map(|k| w32.p[k] * p32[k][c]).sum();
                worst_p = worst_p.max((e64 - e32 as f64).abs());
                let d64: f64 = (0..4).map(|k| w64.d1[k] * p[k][c]).sum();
                let d32: f32 = (0..4).map(|k| w32.d1[k] * p32[k][c]).sum();
                worst_d = worst_d.max((d64 - d32 as f64).abs());
            }
        }
    }
    assert!(worst_p < 3e-7, "position error {worst_p}");
    assert!(worst_d < 5e-7, "derivative error {worst_d}");
}
