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
    // The positions are written in f64: every digit of the f64 samples comes back.
    let (_, points) = s.tessellate_real(3).unwrap();
    let wide: Vec<[f64; 3]> = points.iter().map(|e| e.p).collect();
    assert_eq!(m.positions.as_f64(), Some(&wide[..]));
    // A Loop mesh too: its points refined in f64, its positions written in f64.
    let loop_obj = tmp("loop_f64.obj");
    run_ok(
        bin()
            .arg("limit")
            .arg(shape("loop_pole8"))
            .args(["--tess", "4", "--isolation", "3", "--f64", "-o"])
            .arg(&loop_obj),
    );
    let mesh = subsurf::io::read_path(shape("loop_pole8")).unwrap();
    let t = Topology::new(&mesh).unwrap();
    let limit = subsurf::limit::LoopLimit::new_f64(&t, &mesh.positions, 3).unwrap();
    let (want, _) = limit.tessellate(&t, 3).unwrap().to_mesh_f64();
    let got = subsurf::io::read_path(&loop_obj).unwrap();
    assert_eq!(got.face_indices, want.face_indices);
    assert_eq!(got.positions.to_f64(), want.positions.to_f64());
    assert!(got.positions.is_f64());
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

/// `eval --f64` on every Catmull-Clark and Loop regression shape prints the library's
/// double-precision surface from the file's values, digit for digit: the `f64` patch table
/// (`PatchTable::<f64>`, within 1e-12 of OpenSubdiv's double evaluation: the library's
/// `limit_f64` test) and the Loop patches refined in `f64` (`LoopLimit::new_f64`, within
/// 1e-12: osd-ref's `limit_loop` test).
#[test]
fn eval_f64_prints_the_double_precision_surface_of_every_shape() {
    let dir = repo("testdata/shapes");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            let stem = name.strip_suffix(".obj")?;
            (stem.starts_with("catmark_") || stem.starts_with("loop_")).then(|| stem.to_string())
        })
        .collect();
    names.sort();
    let (mut quads, mut loops) = (0, 0);
    for name in &names {
        let mesh = subsurf::io::read_path(shape(name)).unwrap();
        let Ok(t) = Topology::new(&mesh) else {
            continue;
        };
        let out_path = tmp(&format!("{name}_f64.txt"));
        run_ok(
            bin()
                .arg("eval")
                .arg(shape(name))
                .args(["--tess", "2", "--isolation", "3", "--f64", "-o"])
                .arg(&out_path),
        );
        let text = std::fs::read_to_string(&out_path).unwrap();
        let rows = text.lines().map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            assert_eq!(x.len(), 12, "{name}: {l}");
            x
        });
        if mesh.options.scheme == subsurf::Scheme::Loop {
            let s = subsurf::limit::LoopLimit::new_f64(&t, &mesh.positions, 3).unwrap();
            let mut n = 0;
            for x in rows {
                let r = s.eval(x[0] as usize, x[1], x[2]).unwrap();
                assert_eq!(&x[3..], &[r.p, r.du, r.dv].concat()[..], "{name}");
                n += 1;
            }
            // Faces without a limit (holes, boundaries of `none` interpolation) print none.
            assert!(n > 0 && n <= t.num_faces() * 3, "{name}: {n}");
            loops += 1;
        } else {
            let o = PatchOptions {
                isolation_level: 3,
                ..Default::default()
            };
            let s = LimitSurface::new(
                PatchTable::<f64>::build_real(&t, &o).unwrap(),
                &mesh.positions,
            );
            let mut n = 0;
            for x in rows {
                let r = s.eval(x[0] as usize, x[1], x[2]).unwrap();
                assert_eq!(&x[3..], &[r.p, r.du, r.dv].concat()[..], "{name}");
                n += 1;
            }
            assert!(n > 0 && n <= s.table().num_ptex_faces() * 4, "{name}: {n}");
            quads += 1;
        }
        let _ = std::fs::remove_file(&out_path);
    }
    assert!(
        quads >= 50 && loops >= 5,
        "{quads} catmark, {loops} Loop shapes"
    );
}
