//! The `subsurf` binary end to end: exit codes, messages and output files.

mod common;

use common::{bin, repo, run_ok, tmp};
use std::path::{Path, PathBuf};

fn example(name: &str) -> PathBuf {
    repo(&format!("examples/{name}"))
}

#[test]
fn info_json_reports_the_car() {
    let out = run_ok(bin().args(["info", "--json"]).arg(example("car.obj")));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["vertices"], 1642);
    assert_eq!(v["faces"], 1575);
    assert_eq!(v["semi_sharp_edges"], 314);
    assert_eq!(v["face_sizes"]["4"], 1575);
    assert_eq!(v["boundary_edges"], 60);
    assert_eq!(v["manifold"], true);
}

#[test]
fn refine_writes_obj_and_ply_with_the_expected_counts() {
    for ext in ["obj", "ply"] {
        let out_path = tmp(&format!("car2.{ext}"));
        run_ok(
            bin()
                .arg("refine")
                .arg(example("car.obj"))
                .args(["--level", "2", "-o"])
                .arg(&out_path),
        );
        let mesh = subsurf::io::read_path(&out_path).unwrap();
        // 1575 quads -> 16x at level 2; vertices V2 = V1 + F1 + E1.
        assert_eq!(mesh.num_faces(), 1575 * 16);
        assert_eq!(mesh.num_vertices(), 25357);
        if ext == "ply" {
            // The one-shot path the CLI takes equals the library's stencil path, bit for bit.
            let base = subsurf::io::read_path(example("car.obj")).unwrap();
            let r = subsurf::Refiner::new(subsurf::Topology::new(&base).unwrap(), 2).unwrap();
            let want = r.to_mesh(2, r.refine_positions(&base.positions));
            assert_eq!(mesh.face_indices, want.face_indices);
            assert_eq!(mesh.positions, want.positions);
        }
    }
}

#[test]
fn refine_limit_moves_points_onto_the_surface() {
    let a = tmp("limit_a.obj");
    let b = tmp("limit_b.obj");
    assert!(bin()
        .arg("refine")
        .arg(example("pawn.obj"))
        .args(["-l", "1", "-o"])
        .arg(&a)
        .status()
        .unwrap()
        .success());
    assert!(bin()
        .arg("refine")
        .arg(example("pawn.obj"))
        .args(["-l", "1", "--limit", "-o"])
        .arg(&b)
        .status()
        .unwrap()
        .success());
    let (ma, mb) = (
        subsurf::io::read_path(&a).unwrap(),
        subsurf::io::read_path(&b).unwrap(),
    );
    assert_eq!(ma.face_indices, mb.face_indices);
    assert!(ma.positions.iter().zip(&mb.positions).any(|(p, q)| p != q));
}

#[test]
fn errors_name_the_problem_and_exit_non_zero() {
    let out = bin()
        .args(["info", "/nonexistent/mesh.obj"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("/nonexistent/mesh.obj") && err.contains("No such file"),
        "{err}"
    );

    let bad = tmp("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
    let out = bin().arg("info").arg(&bad).output().unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 4"), "{err}");

    let out = bin()
        .arg("refine")
        .arg(example("car.obj"))
        .args(["--level", "14", "-o"])
        .arg(tmp("huge.obj"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("would need about"), "{err}");
}

/// Requests that cannot fit are refused before anything large is allocated, with the true
/// size of the estimate: past 2^64 bytes it is said as such (not wrapped, not saturated at
/// 16 EiB, no overflow panic), and uniform limit tessellations and `eval`'s samples (Catmull-Clark
/// and Loop) are checked as an oversize `--level` is (issue 40).
#[test]
fn oversize_requests_are_refused_with_the_true_estimate() {
    let car = example("car.obj");
    let loop_mesh = repo("testdata/shapes/loop_pole360.obj");
    let cases: [(&Path, &[&str]); 6] = [
        (&car, &["refine", "--level", "40"]),
        (&car, &["limit", "--tess", "4000"]),
        (&car, &["limit", "--max-edge-length", "1e-9"]),
        (&car, &["eval", "--tess", "4096"]),
        (&loop_mesh, &["eval", "--tess", "4096"]),
        (&loop_mesh, &["refine", "--level", "30"]),
    ];
    // The Loop isolation is sparse: the deepest isolation fits (it was refused when every
    // level was refined whole).
    let deep = bin()
        .args(["eval"])
        .arg(&loop_mesh)
        .args(["--isolation", "10", "-o"])
        .arg(tmp("deep.obj"))
        .output()
        .unwrap();
    assert_eq!(
        deep.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&deep.stderr)
    );
    for (input, args) in cases {
        let out = bin()
            .arg(args[0])
            .arg(input)
            .args(&args[1..])
            .arg("-o")
            .arg(tmp("oversize.obj"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        let what = format!("{args:?}");
        assert_eq!(out.status.code(), Some(1), "{what}: {err}");
        assert!(err.contains("would need about"), "{what}: {err}");
        assert!(
            !err.contains("panicked") && !err.contains("backtrace"),
            "{what}: {err}"
        );
        assert!(!err.contains("16.0 EiB"), "{what}: saturated: {err}");
    }
    // 4^40 faces: about 2^100 bytes, said as more than 2^64.
    let out = bin()
        .arg("refine")
        .arg(&car)
        .args(["--level", "40", "-o"])
        .arg(tmp("oversize.obj"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("more than 2^64 bytes"), "{err}");
}
