//! [`GpuRates`] against the library's CPU rates ([`RatePolicy::rates`]): the `rate_measure`
//! kernel against its CPU twin on the GPU's own samples (to f32 rounding), the GPU's measures
//! against the CPU's `f64` measures, and the rates themselves, under the tolerance, edge-length
//! and screen-space policies, on shapes with creases, boundaries, n-gons, holes and end caps.

mod common;

use common::{context_or_skip, load};
use subsurf::limit::LimitSurface;
use subsurf::tess::CURVE_POINTS;
use subsurf::tess::{CurveMeasure, EdgeRates, RatePolicy, ScreenCamera};
use subsurf_gpu::cpu::rate_measure::rate_measure;
use subsurf_gpu::rates::rate_config;
use subsurf_gpu::{ChunkLimits, GpuContext, GpuLimit, GpuRates};

/// A perspective camera looking at the mesh's centre from `dist` bounding-box diagonals
/// away along +z (column-major world-to-clip, as `subsurf-render`'s).
fn camera(points: &[[f32; 3]], dist: f32) -> ScreenCamera {
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let c: [f32; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let d = subsurf::mesh::bbox_diagonal(points);
    let eye_z = c[2] + dist * d;
    // View: translate the eye to the origin, looking down -z. Projection: 60 degrees, 4:3.
    let (f, aspect, near, far) = (
        1.0 / (30f32.to_radians()).tan(),
        4.0 / 3.0,
        0.01 * d,
        10.0 * d,
    );
    let (a, b) = ((far + near) / (near - far), 2.0 * far * near / (near - far));
    ScreenCamera {
        view_proj: [
            [f / aspect, 0.0, 0.0, 0.0],
            [0.0, f, 0.0, 0.0],
            [0.0, 0.0, a, -1.0],
            [-c[0] * f / aspect, -c[1] * f, -eye_z * a + b, eye_z],
        ],
        width: 800,
        height: 600,
    }
}

/// `(shape, isolation)`.
const SHAPES: [(&str, u32); 6] = [
    ("catmark_car", 3),            // creases, many patches
    ("catmark_pyramid", 2),        // triangles: n-gon ptex faces, half edges
    ("catmark_hole_test1", 2),     // holes: dead curves
    ("catmark_edgecorner", 2),     // boundary and corner patches
    ("catmark_gregory_test1", 3),  // end caps
    ("catmark_torus_creases0", 2), // fractional creases
];

fn policies(points: &[[f32; 3]]) -> Vec<(&'static str, RatePolicy)> {
    let d = subsurf::mesh::bbox_diagonal(points);
    vec![
        ("tolerance", RatePolicy::Tolerance(1e-3)),
        ("max edge length", RatePolicy::MaxEdgeLength(d / 40.0)),
        (
            "screen, whole view",
            RatePolicy::Screen {
                camera: camera(points, 1.5),
                pixels: 6.0,
            },
        ),
        (
            // The eye inside the bounding box: curves partly behind the eye.
            "screen, eye inside",
            RatePolicy::Screen {
                camera: camera(points, 0.1),
                pixels: 6.0,
            },
        ),
    ]
}

/// Per curve, how far rounding of the pixel positions alone can move the screen measure: a
/// driver may fuse the products of `view_proj * p` into `fma` (WGSL allows it; NVIDIA's Vulkan
/// driver does), which the twin does not, and the clip coordinates cancel (the camera's
/// translation against the point's terms), so the positions differ by a few roundings of the
/// terms' magnitudes, not of the result. Bound per sample and axis, in pixels:
/// `8 eps (A_x + |x / w| A_w) / |w| * width / 2 + 4 eps * width`, with `A` the sum of the
/// terms' magnitudes; a segment's length moves by at most its two ends' bounds (both axes),
/// the measure by `s` times that. Zero for the other measures (no products before the
/// differences).
///
/// `moved` adds positions that differ by up to that many world units (two evaluators of the
/// same surface: the GPU's and the CPU's rate curves, which sum in different orders), moved
/// to pixels by the projection's sensitivity `(|R_x| + |x / w| |R_w|) / |w| * width / 2`
/// (`R` the matrix rows' spatial parts), large near the eye.
fn pixel_rounding(m: &CurveMeasure, samples: &[f32], curves: usize, moved: f64) -> Vec<f32> {
    let CurveMeasure::ScreenSpeed(cam) = m else {
        return vec![0.0; curves];
    };
    let eps = f64::from(f32::EPSILON);
    let vp = cam.view_proj.map(|c| c.map(f64::from));
    let (w_px, h_px) = (f64::from(cam.width), f64::from(cam.height));
    let sample = |i: usize| -> f64 {
        let p = [0, 1, 2].map(|k| f64::from(samples[6 * i + k]));
        let clip = |k: usize| {
            let value = vp[0][k] * p[0] + vp[1][k] * p[1] + vp[2][k] * p[2] + vp[3][k];
            let terms = (vp[0][k] * p[0]).abs()
                + (vp[1][k] * p[1]).abs()
                + (vp[2][k] * p[2]).abs()
                + vp[3][k].abs();
            (value, terms)
        };
        let (w, aw) = clip(3);
        if w <= 1e-6 {
            return 0.0; // behind (or at) the eye: counted zero by both
        }
        let row = |k: usize| vp[0][k].abs() + vp[1][k].abs() + vp[2][k].abs();
        let axis = |k: usize, size: f64| {
            let (x, ax) = clip(k);
            let jacobian = (row(k) + (x / w).abs() * row(3)) / w * size / 2.0;
            8.0 * eps * (ax + (x / w).abs() * aw) / w * size / 2.0
                + 4.0 * eps * size
                + jacobian * moved
        };
        axis(0, w_px).hypot(axis(1, h_px))
    };
    let s = (CURVE_POINTS - 1) as f64;
    (0..curves)
        .map(|c| {
            let worst = (c * CURVE_POINTS..(c + 1) * CURVE_POINTS)
                .map(sample)
                .fold(0.0, f64::max);
            (2.0 * s * worst) as f32
        })
        .collect()
}

/// Share of positions where `a` and `b` differ, and the largest difference.
fn mismatch(a: &[u32], b: &[u32]) -> (f64, u32) {
    assert_eq!(a.len(), b.len());
    let differ = a.iter().zip(b).filter(|(x, y)| x != y).count();
    let worst = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| x.abs_diff(y))
        .max()
        .unwrap_or(0);
    (differ as f64 / a.len().max(1) as f64, worst)
}

fn check_shape(ctx: &GpuContext, name: &str, isolation: u32) {
    let (mesh, table) = load(name, isolation);
    let surface = LimitSurface::new(table.clone(), &mesh.positions);
    let mut limit = GpuLimit::new(ctx, &table).unwrap();
    limit.update(ctx, &mesh.positions).unwrap();
    let rates = GpuRates::new(ctx, &limit, &table).unwrap();
    let curves = rates.curves();
    assert_eq!(curves.queries().len(), curves.num_curves() * CURVE_POINTS);
    let diagonal = subsurf::mesh::bbox_diagonal(surface.points());
    assert_eq!(diagonal, subsurf::mesh::bbox_diagonal(&mesh.positions));
    for (what, policy) in policies(&mesh.positions) {
        let m = policy.measure().unwrap();
        let gpu = rates.measure(ctx, &limit, &m).unwrap();
        // The kernel against its twin, on the samples the GPU evaluated.
        let samples = rates.samples().download(ctx).unwrap();
        let mut twin = vec![0.0f32; curves.num_curves()];
        rate_measure(
            &rate_config(curves.num_curves(), 6, &m),
            &samples,
            &mut twin,
        );
        let scale = twin
            .iter()
            .fold(0.0f32, |a, &b| a.max(b))
            .max(f32::MIN_POSITIVE);
        let rounding = pixel_rounding(&m, &samples, curves.num_curves(), 0.0);
        // The CPU's positions agree with the GPU's within a few units in the last place of
        // the surface's extent (`subsurf::limit::curve_eval`'s test allows 8).
        let moved = pixel_rounding(
            &m,
            &samples,
            curves.num_curves(),
            16.0 * f64::from(f32::EPSILON) * f64::from(diagonal),
        );
        for (c, (&g, &t)) in gpu.iter().zip(&twin).enumerate() {
            assert!(
                (g - t).abs() <= 1e-5 * t.abs() + 1e-6 * scale + rounding[c],
                "{name} {what}: curve {c}: kernel {g} vs twin {t} (pixel rounding {})",
                rounding[c]
            );
        }
        // The GPU's f32 measures against the CPU's f64 ones (positions within rounding).
        let cpu = curves.measure(&surface, &m);
        let cpu_scale = cpu.iter().fold(0.0f64, |a, &b| a.max(b));
        let tol = match m {
            CurveMeasure::SecondDerivative => 1e-3,
            _ => 1e-4,
        };
        for (c, (&g, &x)) in gpu.iter().zip(&cpu).enumerate() {
            if !curves.live()[c] {
                assert_eq!(x, 0.0);
                continue;
            }
            assert!(
                (f64::from(g) - x).abs() <= 1e-4 * x.abs() + tol * cpu_scale + f64::from(moved[c]),
                "{name} {what}: curve {c}: GPU {g} vs CPU {x} (positions moved {})",
                moved[c]
            );
        }
        // The rates: equal but for needs within rounding of an integer; a policy asking for
        // more than the memory limit is refused by both, with the same estimate.
        let want = policy.rates(&surface, what);
        let got = rates.rates(ctx, &limit, &table, &policy, diagonal, what);
        let (want, got) = match (want, got) {
            (Ok(w), Ok(g)) => (w, g),
            (Err(w), Err(g)) => {
                eprintln!("{name} {what}: refused by both: {w}");
                assert_eq!(w.to_string(), g.to_string(), "{name} {what}");
                continue;
            }
            (w, g) => panic!("{name} {what}: CPU {w:?}, GPU {g:?}"),
        };
        let (edges, worst_edge) = mismatch(&got.edges, &want.edges);
        let (faces, worst_face) = mismatch(&got.faces, &want.faces);
        eprintln!(
            "{name} {what}: rates {}..={}, edges differing {:.3}% (by <= {worst_edge}), \
             faces {:.3}% (by <= {worst_face})",
            want.edges.iter().min().unwrap(),
            want.edges.iter().max().unwrap(),
            100.0 * edges,
            100.0 * faces,
        );
        assert!(edges <= 0.01 && worst_edge <= 1, "{name} {what}: edges");
        assert!(faces <= 0.01, "{name} {what}: faces");
        // Derived interiors (0) may turn explicit by one rate step, never more.
        for (&g, &w) in got.faces.iter().zip(&want.faces) {
            assert!(
                g == w || g.abs_diff(w) <= 1 || g.min(w) == 0,
                "{name} {what}"
            );
        }
    }
}

#[test]
fn gpu_rates_match_the_cpu_rates() {
    let Some(ctx) = context_or_skip("gpu_rates_match_the_cpu_rates") else {
        return;
    };
    for (name, isolation) in SHAPES {
        check_shape(&ctx, name, isolation);
    }
}

/// Forced small bindings split the measure into many dispatches: the same measures, bit for
/// bit, as one dispatch; uniform and explicit policies need no GPU work and equal the CPU's.
#[test]
fn chunked_measures_equal_one_dispatch() {
    let Some(ctx) = context_or_skip("chunked_measures_equal_one_dispatch") else {
        return;
    };
    let (mesh, table) = load("catmark_car", 2);
    let surface = LimitSurface::new(table.clone(), &mesh.positions);
    let mut limit = GpuLimit::new(&ctx, &table).unwrap();
    limit.update(&ctx, &mesh.positions).unwrap();
    let whole = GpuRates::new(&ctx, &limit, &table).unwrap();
    let small = ChunkLimits {
        max_binding_bytes: 256 * 1024,
        max_workgroups_per_dimension: 7,
        max_stride: 12,
    };
    let split = GpuRates::with_limits(&ctx, &limit, &table, small).unwrap();
    assert_eq!(whole.num_dispatches(), 1);
    assert!(split.num_dispatches() > 10, "{}", split.num_dispatches());
    for (_, policy) in policies(&mesh.positions) {
        let m = policy.measure().unwrap();
        let a = whole.measure(&ctx, &limit, &m).unwrap();
        let b = split.measure(&ctx, &limit, &m).unwrap();
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
    }
    // Points refined on the CPU uploaded as they are (what `GpuBackend::adaptive_rates`
    // does): read back bit for bit; a point array of another length is refused.
    let set = GpuLimit::new(&ctx, &table).unwrap();
    set.set_points(&ctx, surface.points()).unwrap();
    assert_eq!(set.download_points(&ctx).unwrap(), surface.points());
    assert!(set.set_points(&ctx, &surface.points()[1..]).is_err());
    let diagonal = subsurf::mesh::bbox_diagonal(&mesh.positions);
    let mut explicit = EdgeRates::uniform(table.base(), 3);
    explicit.edges[7] = 11;
    for policy in [RatePolicy::Uniform(5), RatePolicy::Explicit(explicit)] {
        let got = whole
            .rates(&ctx, &limit, &table, &policy, diagonal, "--tess")
            .unwrap();
        assert_eq!(got, policy.rates(&surface, "--tess").unwrap());
    }
    // Bad values are refused before any work, as on the CPU.
    let err = whole
        .rates(
            &ctx,
            &limit,
            &table,
            &RatePolicy::Tolerance(-1.0),
            diagonal,
            "--tolerance",
        )
        .unwrap_err();
    assert!(err.to_string().contains("--tolerance"), "{err}");
}
