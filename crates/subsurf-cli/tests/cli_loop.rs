//! `subsurf refine` with the Loop scheme: from the `loop_` file-name prefix and from
//! `--scheme loop`, the written level is the library's Loop refinement (itself tested against
//! OpenSubdiv in `osd-ref`), with `--limit` its limit positions; a quad under `--scheme loop`
//! is refused naming the face.

mod common;

use common::{bin, repo, run_ok, tmp};
use subsurf::{Refiner, Scheme, Topology};

fn refine(input: &std::path::Path, flags: &[&str], out: &str) -> subsurf::Mesh {
    let path = tmp(out);
    run_ok(
        bin()
            .arg("refine")
            .arg(input)
            .args(flags)
            .arg("-o")
            .arg(&path),
    );
    subsurf::io::read_path(&path).unwrap()
}

#[test]
fn refine_writes_the_loop_refinement() {
    let input = repo("testdata/shapes/loop_cube_creases1.obj");
    let mut mesh = subsurf::io::read_path(&input).unwrap();
    assert_eq!(mesh.options.scheme, Scheme::Loop);
    mesh.uvs = None;
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    let want = refiner.refine_positions(&mesh.positions);
    let limit = refiner.limit(&want);
    // The same OBJ under a name without the prefix, with the scheme given on the command line.
    let renamed = tmp("cube_creases1.obj");
    std::fs::copy(&input, &renamed).unwrap();
    for (path, flags, expect) in [
        (&input, vec!["--level", "2"], &want),
        (&renamed, vec!["--level", "2", "--scheme", "loop"], &want),
        (&input, vec!["--level", "2", "--limit"], &limit),
    ] {
        let got = refine(path, &flags, "out.obj");
        assert_eq!(got.face_indices, refiner.last().face_verts, "{flags:?}");
        assert_eq!(got.positions.len(), expect.len(), "{flags:?}");
        for (i, (a, b)) in got.positions.iter().zip(expect.iter()).enumerate() {
            let d = (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0f32, f32::max);
            assert!(d <= 1e-6, "{flags:?} vertex {i}: {a:?} vs {b:?}");
        }
    }
}

#[test]
fn loop_refuses_a_quad_naming_it() {
    let out = bin()
        .arg("refine")
        .arg(repo("testdata/shapes/catmark_cube.obj"))
        .args(["--level", "1", "--scheme", "loop", "-o"])
        .arg(tmp("quad.obj"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("face 0 has 4 vertices"), "{err}");
}

/// A Loop mesh's UVs are refined with it (the library's face-varying Loop refinement, tested
/// against OpenSubdiv in `osd-ref`), corner for corner, in the mesh's own mode and with
/// `--uv-interp`.
#[test]
fn refine_keeps_loop_uvs() {
    let input = repo("testdata/shapes/loop_fvar_bound1.obj");
    let mesh = subsurf::io::read_path(&input).unwrap();
    let uvs = mesh.uvs.as_ref().expect("shape has UVs");
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    for (flags, mode) in [
        (vec!["--level", "2"], mesh.options.fvar_interpolation),
        (
            vec!["--level", "2", "--uv-interp", "linear"],
            subsurf::FVarLinearInterpolation::All,
        ),
    ] {
        let want = refiner.refine_uvs(uvs, mode).unwrap().pop().unwrap();
        let got = refine(&input, &flags, "uvs.obj");
        let got = got.uvs.expect("refined UVs written");
        assert_eq!(got.indices.len(), want.indices.len(), "{flags:?}");
        for (c, (&i, &j)) in got.indices.iter().zip(&want.indices).enumerate() {
            let (a, b) = (got.values[i as usize], want.values[j as usize]);
            let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
            assert!(d <= 1e-6, "{flags:?} corner {c}: {a:?} vs {b:?}");
        }
    }
}

/// `subsurf limit` on a Loop mesh writes the library's Loop limit tessellation (box-spline
/// patches and Gregory-triangle end caps, tested against OpenSubdiv in `osd-ref`): the same
/// samples, and a closed mesh — every edge used once in each direction, Euler characteristic
/// 2 — on a shape where every vertex is extraordinary.
#[test]
fn limit_writes_the_loop_limit_surface_watertight() {
    use subsurf::limit::loop_eval::LoopLimit;
    let input = repo("testdata/shapes/loop_icosahedron.obj");
    let path = tmp("loop_limit.obj");
    run_ok(
        bin()
            .arg("limit")
            .arg(&input)
            .args(["--tess", "5", "--isolation", "3", "-o"])
            .arg(&path),
    );
    let got = subsurf::io::read_path(&path).unwrap();
    let mesh = subsurf::io::read_path(&input).unwrap();
    let topo = Topology::new(&mesh).unwrap();
    let surface = LoopLimit::new(&topo, &mesh.positions, 3).unwrap();
    let (want, _) = surface.tessellate(&topo, 4).unwrap().to_mesh();
    assert_eq!(got.face_indices, want.face_indices);
    assert_eq!(got.positions, want.positions);
    let mut edges = std::collections::HashMap::new();
    for t in got.face_indices.chunks(3) {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "edge {a}-{b} used {n} times in one direction");
        assert_eq!(edges.get(&(b, a)), Some(&1), "open edge {a}-{b}");
    }
    let (v, e, f) = (got.positions.len(), edges.len() / 2, got.num_faces());
    assert_eq!(v as i64 - e as i64 + f as i64, 2);
    // A Loop mesh refuses what its limit surface does not have.
    let out = bin()
        .arg("limit")
        .arg(&input)
        .args(["--quads", "-o"])
        .arg(tmp("loop_quads.obj"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("triangles"));
}
