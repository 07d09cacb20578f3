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
            .args(["--samples", "3", "-o"])
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
    assert_eq!(lines.len(), s.table.num_ptex_faces() * 9);
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
        .args(["--samples", "1", "-o"])
        .arg(tmp("x.txt"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--samples"));
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
