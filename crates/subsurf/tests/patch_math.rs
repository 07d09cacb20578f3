//! Properties of the regular B-spline, Gregory and PatchParam code in `subsurf::patch`:
//! closed forms (polynomial reproduction, boundary curves), finite differences, brute-force
//! boundary refinement, OpenSubdiv's boundary weight adjustment and the PatchParam bit layout.

mod patch_common;
use patch_common::*;

use subsurf::patch::{
    bspline_curve, bspline_patch_weights, eval_bezier_patch, eval_bspline_patch,
    eval_gregory_patch, gregory_patch_weights, GregoryDerivatives, PatchParam, PatchParamFields,
    BOUNDARY_U0, BOUNDARY_U1, BOUNDARY_V0, BOUNDARY_V1, BSPLINE_TO_BEZIER,
};

// ---------------------------------------------------------------------------------------
// Regular B-spline patch
// ---------------------------------------------------------------------------------------

#[test]
fn bspline_partition_of_unity_all_boundary_masks() {
    for mask in 0..16u8 {
        for k in 0..=10 {
            for l in 0..=10 {
                let w = bspline_patch_weights(k as f64 / 10.0, l as f64 / 10.0, mask);
                assert_unity(&w, 1e-14, &format!("mask {mask}"));
            }
        }
    }
}

/// OpenSubdiv's boundary handling, as it is specified on the 16 tensor weights (index
/// `4*row + column`): for each boundary bit, the weight of every missing point is added
/// twice to its neighbour on the boundary line and subtracted once from the next point
/// inwards, then zeroed. Bits: 1 → row 0, 2 → column 3, 4 → row 3, 8 → column 0.
fn osd_style_fold(mask: u8, w: &mut [f64; 16]) {
    // (bit, missing index, boundary-line index, inner index) as functions of the lane k.
    type Lane = fn(usize) -> (usize, usize, usize);
    let rules: [(u8, Lane); 4] = [
        (1, |k| (k, k + 4, k + 8)),
        (2, |k| (4 * k + 3, 4 * k + 2, 4 * k + 1)),
        (4, |k| (k + 12, k + 8, k + 4)),
        (8, |k| (4 * k, 4 * k + 1, 4 * k + 2)),
    ];
    for (bit, lane) in rules {
        if mask & bit != 0 {
            for k in 0..4 {
                let (miss, edge, inner) = lane(k);
                w[edge] += 2.0 * w[miss];
                w[inner] -= w[miss];
                w[miss] = 0.0;
            }
        }
    }
}

#[test]
fn boundary_folding_matches_opensubdiv_tensor_adjustment() {
    for mask in 0..16u8 {
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.9, 1.0)] {
            let plain = bspline_patch_weights(u, v, 0);
            let ours = bspline_patch_weights(u, v, mask);
            for (mut a, b) in [
                (plain.p, ours.p),
                (plain.du, ours.du),
                (plain.dv, ours.dv),
                (plain.duu, ours.duu),
                (plain.duv, ours.duv),
                (plain.dvv, ours.dvv),
            ] {
                osd_style_fold(mask, &mut a);
                for k in 0..16 {
                    assert!((a[k] - b[k]).abs() < 1e-15, "mask {mask} weight {k}");
                }
            }
        }
    }
}

/// Polar forms (blossoms) of `1, x, x², x³` at the knots `(i−1, i, i+1)` of a uniform cubic
/// B-spline with knots at the integers: Marsden's identity gives the control points that
/// reproduce each monomial exactly.
fn polar(deg: usize, i: f64) -> f64 {
    match deg {
        0 => 1.0,
        1 => i,
        2 => i * i - 1.0 / 3.0,
        _ => i * i * i - i,
    }
}

#[test]
fn bspline_reproduces_bicubic_polynomials() {
    // f(x, y) = x^a y^b for a, b ≤ 3: control point (i, j) = polar_a(i) polar_b(j); the
    // patch over the middle face is f(1 + u, 1 + v) with all its derivatives.
    for a in 0..4 {
        for b in 0..4 {
            let mut pts = [[0.0; 3]; 16];
            for j in 0..4 {
                for i in 0..4 {
                    pts[4 * j + i][0] = polar(a, i as f64) * polar(b, j as f64);
                }
            }
            let mono = |x: f64, n: usize, d: usize| -> f64 {
                if d > n {
                    return 0.0;
                }
                let c: f64 = (0..d).map(|k| (n - k) as f64).product();
                c * x.powi((n - d) as i32)
            };
            for k in 0..=6 {
                for l in 0..=6 {
                    let (u, v) = (k as f64 / 6.0, l as f64 / 6.0);
                    let (x, y) = (1.0 + u, 1.0 + v);
                    let e = eval_bspline_patch(&pts, u, v, 0);
                    let f = |du: usize, dv: usize| mono(x, a, du) * mono(y, b, dv);
                    let tol = 1e-12;
                    assert!((e.p[0] - f(0, 0)).abs() < tol, "x^{a} y^{b} at ({u},{v})");
                    assert!((e.du[0] - f(1, 0)).abs() < tol);
                    assert!((e.dv[0] - f(0, 1)).abs() < tol);
                    assert!((e.duu[0] - f(2, 0)).abs() < tol);
                    assert!((e.duv[0] - f(1, 1)).abs() < tol);
                    assert!((e.dvv[0] - f(0, 2)).abs() < tol);
                }
            }
        }
    }
}

#[test]
fn boundary_patches_reproduce_bilinear_functions() {
    // Mirroring extrapolates linear data exactly, so every boundary variant still
    // reproduces a + b x + c y + d x y; the phantom points' given values are ignored.
    let f = |x: f64, y: f64| 0.5 + 2.0 * x - 1.5 * y + 0.75 * x * y;
    for mask in 0..16u8 {
        let mut pts = [[0.0; 3]; 16];
        for j in 0..4 {
            for i in 0..4 {
                let phantom = (mask & BOUNDARY_U0 != 0 && i == 0)
                    || (mask & BOUNDARY_U1 != 0 && i == 3)
                    || (mask & BOUNDARY_V0 != 0 && j == 0)
                    || (mask & BOUNDARY_V1 != 0 && j == 3);
                pts[4 * j + i][0] = if phantom { 1e6 } else { f(i as f64, j as f64) };
            }
        }
        for k in 0..=4 {
            for l in 0..=4 {
                let (u, v) = (k as f64 / 4.0, l as f64 / 4.0);
                let e = eval_bspline_patch(&pts, u, v, mask);
                let (x, y) = (1.0 + u, 1.0 + v);
                assert!((e.p[0] - f(x, y)).abs() < 1e-12, "mask {mask}");
                assert!((e.du[0] - (2.0 + 0.75 * y)).abs() < 1e-12);
                assert!((e.dv[0] - (-1.5 + 0.75 * x)).abs() < 1e-12);
                assert!((e.duv[0] - 0.75).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn bspline_derivatives_match_finite_differences() {
    let pts = random_grid(7);
    for mask in [
        0u8,
        BOUNDARY_V0,
        BOUNDARY_U1 | BOUNDARY_V1,
        BOUNDARY_U0 | BOUNDARY_V0,
    ] {
        for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.93, 0.37), (0.3, 0.8)] {
            check_fd(
                &|u, v| eval_bspline_patch(&pts, u, v, mask),
                u,
                v,
                1e-7,
                "bspline",
            );
        }
    }
}

/// Catmull-Clark boundary curve with a corner at its first point: the corner stays,
/// interior points take `(1, 6, 1)/8`, edges split at midpoints. The last point has no
/// right neighbour and is dropped each level.
fn refine_boundary_curve(q: &[P3]) -> Vec<P3> {
    let n = q.len();
    let mut out = Vec::with_capacity(2 * n);
    out.push(q[0]);
    for i in 0..n - 2 {
        out.push(std::array::from_fn(|c| 0.5 * (q[i][c] + q[i + 1][c])));
        out.push(std::array::from_fn(|c| {
            (q[i][c] + 6.0 * q[i + 1][c] + q[i + 2][c]) / 8.0
        }));
    }
    out
}

#[test]
fn boundary_and_corner_patches_follow_the_boundary_rules() {
    // Closed form: with the phantom point Q(-1) = 2 Q0 − Q1 the boundary curve is
    // Σ N_k(u) (Q(-1), Q0, Q1, Q2)_k; at u = 0 this is (2Q0 − Q1 + 4Q0 + Q1)/6 = Q0, the
    // corner. The boundary rules' limit (refined points, then the limit stencil (1,4,1)/6,
    // the corner staying put) must agree with the corner patch along its edge v = 0.
    let pts = random_grid(11);
    let mask = BOUNDARY_U0 | BOUNDARY_V0;
    // Boundary row 1: corner (1,1), then (2,1), (3,1), plus two more points further on.
    let mut r = Rng(5);
    let mut q: Vec<P3> = vec![pts[5], pts[6], pts[7]];
    q.push(r.point());
    q.push(r.point());
    let levels = 7;
    for _ in 0..levels {
        q = refine_boundary_curve(&q);
    }
    let m = 1usize << levels;
    for i in 0..=m {
        let limit: P3 = if i == 0 {
            q[0]
        } else {
            std::array::from_fn(|c| (q[i - 1][c] + 4.0 * q[i][c] + q[i + 1][c]) / 6.0)
        };
        let u = i as f64 / m as f64;
        let e = eval_bspline_patch(&pts, u, 0.0, mask);
        assert!(dist(&e.p, &limit) < 1e-12, "u = {u}");
        // Closed form with the phantom point.
        let n = bspline_curve(u);
        let ext = [
            std::array::from_fn(|c| 2.0 * pts[5][c] - pts[6][c]),
            pts[5],
            pts[6],
            pts[7],
        ];
        let closed: P3 = std::array::from_fn(|c| (0..4).map(|k| n.p[k] * ext[k][c]).sum());
        assert!(dist(&e.p, &closed) < 1e-12);
    }
    // Corner interpolation, and a plain boundary edge is the B-spline of its row.
    assert!(dist(&eval_bspline_patch(&pts, 0.0, 0.0, mask).p, &pts[5]) < 1e-15);
    for k in 0..=8 {
        let u = k as f64 / 8.0;
        let e = eval_bspline_patch(&pts, u, 0.0, BOUNDARY_V0);
        let n = bspline_curve(u);
        let row: P3 = std::array::from_fn(|c| (0..4).map(|i| n.p[i] * pts[4 + i][c]).sum());
        assert!(dist(&e.p, &row) < 1e-14);
    }
}

// ---------------------------------------------------------------------------------------
// PatchParam
// ---------------------------------------------------------------------------------------

#[test]
fn patch_param_round_trip_all_fields() {
    let mut r = Rng(1234);
    let mut n = 0;
    for depth in 0..=15u8 {
        for non_quad_root in [false, true] {
            if non_quad_root && depth == 0 {
                continue;
            }
            let level = depth - non_quad_root as u8;
            let uv_max = ((1u32 << level) - 1).min(1023) as u16;
            for boundary in 0..32u8 {
                for transition in 0..16u8 {
                    for regular in [false, true] {
                        let face_id = match n % 4 {
                            0 => 0,
                            1 => (1 << 28) - 1,
                            _ => ((r.next() + 1.0) * 0.5 * (1u32 << 28) as f64) as u32,
                        };
                        let pick = |x: f64| ((x + 1.0) * 0.5 * (uv_max as f64 + 1.0)) as u16;
                        let u = if n % 3 == 0 {
                            uv_max
                        } else {
                            pick(r.next()).min(uv_max)
                        };
                        let v = if n % 5 == 0 {
                            uv_max
                        } else {
                            pick(r.next()).min(uv_max)
                        };
                        let f = PatchParamFields {
                            face_id,
                            u,
                            v,
                            depth,
                            non_quad_root,
                            boundary,
                            transition,
                            regular,
                        };
                        let p = PatchParam::new(f).unwrap();
                        assert_eq!(p.fields(), f);
                        let bytes: [u8; 8] = bytemuck::cast(p);
                        assert_eq!(bytemuck::cast::<[u8; 8], PatchParam>(bytes), p);
                        n += 1;
                    }
                }
            }
        }
    }
    assert!(n > 30_000);
}

#[test]
fn patch_param_normalize_tiles_the_face() {
    let mut r = Rng(4321);
    for depth in [0u8, 1, 3, 10] {
        for nq in [false, true] {
            if nq && depth == 0 {
                continue;
            }
            let level = depth - nq as u8;
            let side = 1u32 << level;
            for _ in 0..50 {
                let (fu, fv) = ((r.next() + 1.0) * 0.5, (r.next() + 1.0) * 0.5);
                let (iu, iv) = ((fu * side as f64) as u16, (fv * side as f64) as u16);
                let p = PatchParam::new(PatchParamFields {
                    u: iu.min(side as u16 - 1),
                    v: iv.min(side as u16 - 1),
                    depth,
                    non_quad_root: nq,
                    ..Default::default()
                })
                .unwrap();
                assert!(p.contains(fu, fv));
                let (s, t) = p.normalize(fu, fv);
                assert!((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
                let (bu, bv) = p.unnormalize(s, t);
                assert!((bu - fu).abs() < 1e-12 && (bv - fv).abs() < 1e-12);
                assert_eq!(p.param_fraction() as f64, 1.0 / side as f64);
                // Chain rule: the face-parameter derivative of the patch, by differences.
                let pts = random_grid(depth as u64 + 1);
                let g = |a: f64, b: f64| {
                    let (s, t) = p.normalize(a, b);
                    eval_bspline_patch(&pts, s, t, 0)
                };
                let h = 1e-6 / side as f64;
                let scale: f64 = p.deriv_scale();
                let mut w = bspline_patch_weights(s, t, 0);
                w.scale_derivatives(scale);
                let e = w.eval(&pts);
                let fd = (g(fu + h, fv).p[2] - g(fu - h, fv).p[2]) / (2.0 * h);
                assert!(
                    (fd - e.du[2]).abs() < 1e-5 * (1.0 + e.du[2].abs()),
                    "depth {depth}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Gregory basis
// ---------------------------------------------------------------------------------------

/// Bézier points of the bicubic B-spline patch `pts` (Q ⊗ Q).
fn bspline_to_bezier(pts: &[P3; 16]) -> [P3; 16] {
    std::array::from_fn(|k| {
        let (i, j) = (k % 4, k / 4);
        std::array::from_fn(|c| {
            let mut s = 0.0;
            for b in 0..4 {
                for a in 0..4 {
                    s += BSPLINE_TO_BEZIER[i][a] * BSPLINE_TO_BEZIER[j][b] * pts[4 * b + a][c];
                }
            }
            s
        })
    })
}

/// The 20 Gregory points of a Bézier patch, each face-point pair equal to the Bézier
/// interior point.
fn bezier_to_gregory(b: &[P3; 16]) -> [P3; 20] {
    use subsurf::patch::{GREGORY_BOUNDARY, GREGORY_INTERIOR};
    let mut g = [[0.0; 3]; 20];
    for &(k, i, j) in &GREGORY_BOUNDARY {
        g[k] = b[4 * j + i];
    }
    for &(plus, minus, i, j) in &GREGORY_INTERIOR {
        g[plus] = b[4 * j + i];
        g[minus] = b[4 * j + i];
    }
    g
}

#[test]
fn gregory_with_equal_pairs_is_the_bspline_patch() {
    let pts = random_grid(55);
    let bez = bspline_to_bezier(&pts);
    let greg = bezier_to_gregory(&bez);
    for mode in [
        GregoryDerivatives::Exact,
        GregoryDerivatives::BezierApproximation,
    ] {
        for k in 0..=10 {
            for l in 0..=10 {
                let (u, v) = (k as f64 / 10.0, l as f64 / 10.0);
                let a = eval_bspline_patch(&pts, u, v, 0);
                let b = eval_bezier_patch(&bez, u, v);
                let g = eval_gregory_patch(&greg, u, v, mode);
                for (x, y, z) in [
                    (a.p, b.p, g.p),
                    (a.du, b.du, g.du),
                    (a.dv, b.dv, g.dv),
                    (a.duu, b.duu, g.duu),
                    (a.duv, b.duv, g.duv),
                    (a.dvv, b.dvv, g.dvv),
                ] {
                    assert!(dist(&x, &y) < 1e-12, "bezier ≠ bspline at ({u},{v})");
                    assert!(
                        dist(&x, &z) < 1e-12,
                        "gregory ≠ bspline at ({u},{v}) {mode:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn gregory_partition_of_unity() {
    for mode in [
        GregoryDerivatives::Exact,
        GregoryDerivatives::BezierApproximation,
    ] {
        for k in 0..=12 {
            for l in 0..=12 {
                let w = gregory_patch_weights(k as f64 / 12.0, l as f64 / 12.0, mode);
                assert_unity(&w, 1e-12, "gregory");
            }
        }
    }
}

#[test]
fn gregory_exact_derivatives_match_finite_differences() {
    let mut r = Rng(66);
    let g: [P3; 20] = std::array::from_fn(|_| r.point());
    for (u, v) in [(0.2, 0.3), (0.5, 0.5), (0.8, 0.1), (0.35, 0.9), (0.95, 0.6)] {
        check_fd(
            &|u, v| eval_gregory_patch(&g, u, v, GregoryDerivatives::Exact),
            u,
            v,
            1e-6,
            "gregory",
        );
    }
    // The approximation is exact in first derivatives along the patch boundary, and
    // differs inside when the pairs differ.
    for t in [0.0, 0.25, 0.6, 1.0] {
        for (u, v) in [(t, 0.0), (1.0, t), (t, 1.0), (0.0, t)] {
            let a = eval_gregory_patch(&g, u, v, GregoryDerivatives::Exact);
            let b = eval_gregory_patch(&g, u, v, GregoryDerivatives::BezierApproximation);
            assert_eq!(a.p, b.p);
            assert!(dist(&a.du, &b.du) < 1e-12 && dist(&a.dv, &b.dv) < 1e-12);
        }
    }
    let a = eval_gregory_patch(&g, 0.3, 0.4, GregoryDerivatives::Exact);
    let b = eval_gregory_patch(&g, 0.3, 0.4, GregoryDerivatives::BezierApproximation);
    assert!(dist(&a.du, &b.du) > 1e-6);
}
