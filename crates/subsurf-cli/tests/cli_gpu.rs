//! `--backend gpu` of `subsurf refine`, `prep`, `limit` (uniform and adaptive) and `eval` against
//! `--backend cpu`.
//!
//! Without a GPU adapter these tests fail with the driver installation hint, unless
//! `SUBSURF_SKIP_GPU=1`.

mod common;

use common::{bin, repo, run_ok, tmp};
use std::path::Path;
use std::process::Output;

/// Runs `args` with `--backend gpu`; `None` (after a loud note) when there is no adapter and
/// `SUBSURF_SKIP_GPU=1`.
fn run_gpu(args: &[&std::ffi::OsStr]) -> Option<Output> {
    common::run_gpu(bin().args(args).args(["--backend", "gpu"]))
}

fn run_cpu(args: &[&std::ffi::OsStr]) {
    run_ok(bin().args(args));
}

fn assert_same_mesh(gpu: &Path, cpu: &Path) {
    let (g, c) = (
        subsurf::io::read_path(gpu).unwrap(),
        subsurf::io::read_path(cpu).unwrap(),
    );
    assert_eq!(g.face_indices, c.face_indices, "connectivity differs");
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in &c.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let diag = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f32>().sqrt();
    for (i, (a, b)) in g.positions.iter().zip(&c.positions).enumerate() {
        for k in 0..3 {
            assert!(
                (a[k] - b[k]).abs() <= 1e-5 * diag,
                "vertex {i}: GPU {a:?} vs CPU {b:?}"
            );
        }
    }
}

fn path_str(p: &Path) -> String {
    p.to_str().expect("test paths are UTF-8").to_string()
}

/// `subsurf <cmd> <input> <extra…> -o <out>` on the GPU into `gpu`, then on the CPU into
/// `cpu`; `false` when the GPU run was skipped (no adapter and `SUBSURF_SKIP_GPU=1`).
fn run_both(cmd: &str, input: &Path, extra: &[&str], gpu: &Path, cpu: &Path) -> bool {
    let args = |o: &Path| {
        let mut v = vec![cmd.to_string(), path_str(input)];
        v.extend(extra.iter().map(|s| s.to_string()));
        v.extend(["-o".to_string(), path_str(o)]);
        v
    };
    let ga = args(gpu);
    let ga: Vec<&std::ffi::OsStr> = ga.iter().map(|s| s.as_ref()).collect();
    if run_gpu(&ga).is_none() {
        return false;
    }
    let ca = args(cpu);
    let ca: Vec<&std::ffi::OsStr> = ca.iter().map(|s| s.as_ref()).collect();
    run_cpu(&ca);
    true
}

/// `subsurf <cmd> <input> <extra…> -o <out>` with both backends; output meshes compared.
fn compare_backends(cmd: &str, input: &Path, extra: &[&str], stem: &str) {
    let (g, c) = (
        tmp(&format!("{stem}_gpu.obj")),
        tmp(&format!("{stem}_cpu.obj")),
    );
    if run_both(cmd, input, extra, &g, &c) {
        assert_same_mesh(&g, &c);
    }
}

#[test]
fn refine_gpu_matches_cpu() {
    compare_backends(
        "refine",
        &repo("examples/car.obj"),
        &["--level", "2"],
        "car",
    );
}

#[test]
fn prep_gpu_matches_cpu() {
    let input = repo("crates/subsurf/tests/data/prep/catmark_torus.obj");
    compare_backends("prep", &input, &["--tess", "5"], "torus");
}

/// Non-quad input: the quadrangulation step runs on the GPU and feeds the p-rep there.
#[test]
fn prep_quadrangulated_on_the_gpu_matches_cpu() {
    // A closed pyramid of four triangles and a quad.
    let input = repo("testdata/shapes/catmark_pyramid.obj");
    compare_backends(
        "prep",
        &input,
        &["--quadrangulate", "--tess", "4"],
        "pyramid",
    );
}

/// Positions and UVs, refined (and with `--limit` moved to the limit) on both backends.
#[test]
fn refine_uvs_gpu_match_cpu() {
    let input = repo("testdata/shapes/catmark_fvar_bound1.obj");
    for (extra, stem) in [
        (&["--level", "2"][..], "uv"),
        (&["--level", "2", "--limit"][..], "uv_limit"),
    ] {
        let (g, c) = (
            tmp(&format!("{stem}_gpu.obj")),
            tmp(&format!("{stem}_cpu.obj")),
        );
        if !run_both("refine", &input, extra, &g, &c) {
            return;
        }
        assert_same_mesh(&g, &c);
        let (gu, cu) = (
            subsurf::io::read_path(&g)
                .unwrap()
                .uvs
                .expect("GPU output has UVs"),
            subsurf::io::read_path(&c)
                .unwrap()
                .uvs
                .expect("CPU output has UVs"),
        );
        assert_eq!(gu.indices, cu.indices);
        assert_eq!(gu.values.len(), cu.values.len());
        for (a, b) in gu.values.iter().zip(&cu.values) {
            assert!(
                (a[0] - b[0]).abs() <= 1e-5 && (a[1] - b[1]).abs() <= 1e-5,
                "{stem}: {a:?} vs {b:?}"
            );
        }
    }
}

/// `--limit` on the GPU: refinement and the limit step both there.
#[test]
fn refine_limit_gpu_matches_cpu() {
    compare_backends(
        "refine",
        &repo("examples/car.obj"),
        &["--level", "2", "--limit"],
        "car_limit",
    );
}

#[test]
fn limit_gpu_matches_cpu() {
    // Gregory end caps, single-crease patches and boundaries; same vertex order and faces.
    compare_backends(
        "limit",
        &repo("testdata/shapes/catmark_car.obj"),
        &["--isolation", "2", "--tess", "4"],
        "car_limit",
    );
    // Triangles: non-quad ptex faces (odd sample count).
    compare_backends(
        "limit",
        &repo("testdata/shapes/catmark_pyramid.obj"),
        &["--tess", "5"],
        "pyramid_limit",
    );
}

#[test]
fn adaptive_limit_rates_on_the_gpu_match_cpu() {
    // Rates measured by `GpuRates`, the tessellation evaluated on the CPU: the same rates
    // (no need of these shapes falls within f32 rounding of an integer), so the same mesh.
    compare_backends(
        "limit",
        &repo("testdata/shapes/catmark_pawn.obj"),
        &["--tolerance", "1e-3"],
        "pawn_adaptive",
    );
    compare_backends(
        "limit",
        &repo("testdata/shapes/catmark_pyramid.obj"),
        &["--max-edge-length", "0.1"],
        "pyramid_adaptive",
    );
}

/// Parses `eval` output lines.
fn eval_lines(path: &Path) -> Vec<Vec<f32>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

#[test]
fn eval_gpu_matches_cpu() {
    let input = repo("testdata/shapes/catmark_hole_test1.obj");
    let (g, c) = (tmp("eval_gpu.txt"), tmp("eval_cpu.txt"));
    if !run_both("eval", &input, &["--tess", "4"], &g, &c) {
        return;
    }
    let (gl, cl) = (eval_lines(&g), eval_lines(&c));
    // Same samples (holes skipped on both), values within f32 rounding: positions relative to
    // the mesh size (a few units), derivatives to theirs.
    assert_eq!(gl.len(), cl.len());
    assert!(!gl.is_empty());
    for (k, (a, b)) in gl.iter().zip(&cl).enumerate() {
        assert_eq!(a[..3], b[..3], "line {k}: sample");
        for i in 3..12 {
            assert!(
                (a[i] - b[i]).abs() <= 1e-4 * (1.0 + b[i].abs()),
                "line {k} column {i}: GPU {} vs CPU {}",
                a[i],
                b[i]
            );
        }
    }
}

#[test]
fn gpu_errors_are_clear() {
    // No adapter matches: the message says what failed and what to do.
    let out = bin()
        .args(["refine"])
        .arg(repo("examples/car.obj"))
        .args(["-o"])
        .arg(tmp("never.obj"))
        .args(["--backend", "gpu"])
        .env("SUBSURF_ADAPTER", "no-such-adapter-0xdead")
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--backend gpu"), "{err}");
    assert!(err.contains("no-such-adapter-0xdead"), "{err}");
    assert!(err.contains("--backend cpu"), "{err}");
    // f64 is a CPU-only option.
    let out = bin()
        .args(["prep"])
        .arg(repo("crates/subsurf/tests/data/prep/catmark_cube.obj"))
        .args(["--f64", "--backend", "gpu"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("f32 only"));
}

/// `subsurf bench --backend gpu` times the GPU refiner on the adapter it names.
#[test]
fn bench_runs_on_the_gpu() {
    let input = repo("testdata/shapes/catmark_cube.obj");
    let Some(out) = common::run_gpu(bin().arg("bench").arg(&input).args([
        "--level",
        "3",
        "--runs",
        "2",
        "--backend",
        "gpu",
    ])) else {
        return;
    };
    let text = String::from_utf8_lossy(&out.stdout);
    // 6 quads refined 3 times: 386 vertices.
    assert!(
        text.contains("386 vertices on") && text.contains("with read-back"),
        "{text}"
    );
}
