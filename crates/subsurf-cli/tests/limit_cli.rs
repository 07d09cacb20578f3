//! `subsurf limit` and `subsurf eval` end to end.

mod common;

use common::{bin, repo, run_ok, tmp};
use std::path::PathBuf;

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::Topology;

fn shape(name: &str) -> PathBuf {
    repo(&format!("testdata/shapes/{name}.obj"))
}

/// `eval` writes one line per sample of every non-hole ptex face, `v` the outer loop, with
/// the library's values.
#[test]
fn eval_writes_the_library_samples() {
    let out_path = tmp("pyramid.txt");
    run_ok(
        bin()
            .arg("eval")
            .arg(shape("catmark_pyramid"))
            .args(["--tess", "3", "-o"])
            .arg(&out_path),
    );
    let text = std::fs::read_to_string(&out_path).unwrap();
    let lines: Vec<Vec<f32>> = text
        .lines()
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    let mesh = subsurf::io::read_path(shape("catmark_pyramid")).unwrap();
    let t = Topology::new(&mesh).unwrap();
    let s = LimitSurface::new(
        PatchTable::build(&t, &PatchOptions::default()).unwrap(),
        &mesh.positions,
    );
    assert_eq!(lines.len(), s.table().num_ptex_faces() * 9);
    for (k, l) in lines.iter().enumerate() {
        assert_eq!(l.len(), 12);
        let (f, i, j) = (k / 9, k % 3, (k / 3) % 3);
        assert_eq!(
            (l[0] as usize, l[1], l[2]),
            (f, i as f32 / 2.0, j as f32 / 2.0)
        );
        let r = s.eval(f, l[1], l[2]).unwrap();
        let want = [r.p, r.du, r.dv].concat();
        assert_eq!(&l[3..], &want[..], "line {k}");
    }
}

/// `limit` writes a closed, watertight triangle mesh for a closed input.
#[test]
fn limit_writes_a_watertight_mesh() {
    let out_path = tmp("cube.obj");
    run_ok(
        bin()
            .arg("limit")
            .arg(shape("catmark_cube"))
            .args(["--tess", "4", "--isolation", "2", "-o"])
            .arg(&out_path),
    );
    let m = subsurf::io::read_path(&out_path).unwrap();
    // 6 faces × 3 × 3 cells × 2 triangles; V = 8 + 12·2 + 6·4 shared samples.
    assert_eq!(m.num_faces(), 108);
    assert_eq!(m.positions.len(), 8 + 24 + 24);
    let t = Topology::new(&m).unwrap();
    assert!(t.is_closed() && t.is_manifold());
}

#[test]
fn bad_arguments_fail_cleanly() {
    let out = bin()
        .arg("eval")
        .arg(shape("catmark_cube"))
        .args(["--tess", "1", "-o"])
        .arg(tmp("x.txt"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--tess"));
    let out = bin()
        .arg("limit")
        .arg(shape("catmark_cube"))
        .args(["--isolation", "11", "-o"])
        .arg(tmp("x.obj"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("isolation"));
}

/// `eval --f64` prints the double-precision library samples (all 17 significant digits
/// survive the round trip), `limit --f64` the `f64` surface rounded to `f32`; `--f64` with
/// `--backend gpu` is refused, naming both flags.
#[test]
fn f64_flags_write_the_double_precision_surface() {
    let out_path = tmp("chaikin_f64.txt");
    run_ok(
        bin()
            .arg("eval")
            .arg(shape("catmark_chaikin1"))
            .args(["--tess", "2", "--f64", "-o"])
            .arg(&out_path),
    );
    let mesh = subsurf::io::read_path(shape("catmark_chaikin1")).unwrap();
    let t = Topology::new(&mesh).unwrap();
    let table = PatchTable::<f64>::build_real(&t, &PatchOptions::default()).unwrap();
    let s = LimitSurface::new(table, &mesh.positions);
    let text = std::fs::read_to_string(&out_path).unwrap();
    assert_eq!(text.lines().count(), s.table().num_ptex_faces() * 4);
    for l in text.lines() {
        let x: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
        let r = s.eval(x[0] as usize, x[1], x[2]).unwrap();
        assert_eq!(&x[3..], &[r.p, r.du, r.dv].concat()[..], "{l}");
    }
    let obj = tmp("chaikin_f64.obj");
    run_ok(
        bin()
            .arg("limit")
            .arg(shape("catmark_chaikin1"))
            .args(["--tess", "3", "--f64", "-o"])
            .arg(&obj),
    );
    let m = subsurf::io::read_path(&obj).unwrap();
    let want = s.tessellate(3).unwrap();
    assert_eq!(m.positions, want.positions);
    let out = bin()
        .arg("limit")
        .arg(shape("catmark_chaikin1"))
        .args(["--f64", "--backend", "gpu", "-o"])
        .arg(tmp("x64.obj"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--f64") && err.contains("--backend gpu"),
        "{err}"
    );
}
