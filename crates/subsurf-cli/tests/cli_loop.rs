//! `subsurf refine` with the Loop scheme: from the `loop_` file-name prefix and from
//! `--scheme loop`, the written level is the library's Loop refinement (itself tested against
//! OpenSubdiv in `osd-ref`), with `--limit` its limit positions; a quad under `--scheme loop`
//! is refused naming the face.

mod common;

use common::{bin, repo, run_gpu, run_ok, tmp};
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
        assert_eq!(
            got.face_indices,
            refiner.last().arrays().face_verts,
            "{flags:?}"
        );
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
/// `--uv-interpolation`.
#[test]
fn refine_keeps_loop_uvs() {
    let input = repo("testdata/shapes/loop_fvar_bound1.obj");
    let mesh = subsurf::io::read_path(&input).unwrap();
    let uvs = mesh.uvs.as_ref().expect("shape has UVs");
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    for (flags, mode) in [
        (vec!["--level", "2"], mesh.options.uv_interpolation),
        (
            vec!["--level", "2", "--uv-interpolation", "linear"],
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
    use subsurf::limit::LoopLimit;
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
    let surface = LoopLimit::at_precision(&topo, &mesh.positions, 3).unwrap();
    let (want, _) = surface.tessellate(&topo, 4).unwrap().to_mesh();
    assert_eq!(got.face_indices, want.face_indices);
    assert_eq!(*got.positions, *want.positions);
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

/// The `face u v px py pz dux duy duz dvx dvy dvz` lines of an `eval` output, parsed as f64.
fn eval_lines(path: &std::path::Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// Every line of `eval` output is the library's Loop limit sample, bit for bit (f64
/// written in its shortest round-trip form).
fn assert_library_samples(lines: &[Vec<f64>], surface: &subsurf::limit::LoopLimit) {
    for l in lines {
        assert_eq!(l.len(), 12);
        let r = surface.eval(l[0] as usize, l[1], l[2]).unwrap();
        let want: Vec<f64> = [r.p, r.du, r.dv].concat();
        assert_eq!(&l[3..], &want[..], "{l:?}");
    }
}

/// `subsurf eval` on a Loop mesh samples the triangular grid `u = i/(N−1)`, `v = j/(N−1)`,
/// `i + j ≤ N − 1` of every base triangle (`v` the outer loop) on the library's Loop limit
/// surface (tested against OpenSubdiv in `osd-ref`), from the prefix and from `--scheme loop`
/// alike; the derivatives are those of the surface (central differences along `u`).
#[test]
fn eval_writes_the_loop_limit_samples() {
    use subsurf::limit::LoopLimit;
    let input = repo("testdata/shapes/loop_icosahedron.obj");
    let renamed = tmp("icosahedron.obj");
    std::fs::copy(&input, &renamed).unwrap();
    let mesh = subsurf::io::read_path(&input).unwrap();
    let topo = Topology::new(&mesh).unwrap();
    let surface = LoopLimit::at_precision(&topo, &mesh.positions, 3).unwrap();
    let mut outputs = Vec::new();
    for (path, scheme) in [(&input, None), (&renamed, Some("loop"))] {
        let out = tmp("loop_eval.txt");
        let mut cmd = bin();
        cmd.arg("eval")
            .arg(path)
            .args(["--tess", "5", "--isolation", "3", "-o"])
            .arg(&out);
        if let Some(s) = scheme {
            cmd.args(["--scheme", s]);
        }
        run_ok(&mut cmd);
        outputs.push(std::fs::read_to_string(&out).unwrap());
        let lines = eval_lines(&out);
        assert_eq!(lines.len(), 20 * 15);
        let mut k = 0;
        for f in 0..20 {
            for j in 0..5 {
                for i in 0..5 - j {
                    let l = &lines[k];
                    assert_eq!(
                        (l[0], l[1], l[2]),
                        (f as f64, i as f64 / 4.0, j as f64 / 4.0)
                    );
                    k += 1;
                }
            }
        }
        assert_library_samples(&lines, &surface);
    }
    assert_eq!(outputs[0], outputs[1]);
    // ∂P/∂u against a central difference, inside a patch (off the seams u, v, u + v = k/8
    // of the level-3 sub-triangles).
    let h = 1e-6;
    for (f, u, v) in [(0, 0.3, 0.3), (7, 0.53, 0.19), (19, 0.1, 0.6)] {
        let r = surface.eval(f, u, v).unwrap();
        let (a, b) = (
            surface.eval(f, u + h, v).unwrap().p,
            surface.eval(f, u - h, v).unwrap().p,
        );
        for c in 0..3 {
            let d = (a[c] - b[c]) / (2.0 * h);
            assert!((d - r.du[c]).abs() < 1e-5, "face {f}: {d} vs {}", r.du[c]);
        }
    }
}

/// `eval --at FILE` evaluates the file's `face u v` queries; one off the triangle
/// (`u + v > 1`, a negative parameter) or naming a face that does not exist is an error
/// naming the query, and the GPU backend is refused for Loop.
#[test]
fn eval_at_queries_and_refuses_those_off_the_triangles() {
    use subsurf::limit::LoopLimit;
    let input = repo("testdata/shapes/loop_xord_boundary.obj");
    let mesh = subsurf::io::read_path(&input).unwrap();
    let topo = Topology::new(&mesh).unwrap();
    let surface = LoopLimit::at_precision(&topo, &mesh.positions, 4).unwrap();
    let queries = tmp("loop_queries.txt");
    let nf = topo.num_faces();
    std::fs::write(
        &queries,
        format!(
            "# face u v\n0 0.2 0.7\n\n{} 1 0 # a corner\n1 0.125 0.875\n",
            nf - 1
        ),
    )
    .unwrap();
    let out = tmp("loop_at.txt");
    run_ok(
        bin()
            .arg("eval")
            .arg(&input)
            .arg("--at")
            .arg(&queries)
            .arg("-o")
            .arg(&out),
    );
    let lines = eval_lines(&out);
    assert_eq!(lines.len(), 3);
    assert_eq!((lines[1][0], lines[1][1]), ((nf - 1) as f64, 1.0));
    assert_library_samples(&lines, &surface);
    for (bad, want) in [
        (
            "0 0.2 0.2\n2 0.6 0.5\n",
            "query 1: face 2 at (u, v) = (0.6, 0.5) is outside the triangle",
        ),
        (
            "1 -0.1 0.5\n",
            "query 0: face 1 at (u, v) = (-0.1, 0.5) is outside",
        ),
        (
            &format!("{nf} 0.1 0.1\n"),
            &format!("query 0: face {nf} does not exist (there are {nf} faces)"),
        ),
        ("0 0.1\n", "expected `face u v`"),
    ] {
        std::fs::write(&queries, bad).unwrap();
        let o = bin()
            .arg("eval")
            .arg(&input)
            .arg("--at")
            .arg(&queries)
            .arg("-o")
            .arg(tmp("loop_bad.txt"))
            .output()
            .unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(want), "{bad:?}: {err}");
    }
    // On the GPU: the same lines within f32 rounding (positions within 1e-5 of the
    // bounding-box diagonal, derivatives relative to their size).
    let (cpu_out, gpu_out) = (tmp("loop_cpu.txt"), tmp("loop_gpu.txt"));
    run_ok(bin().arg("eval").arg(&input).arg("-o").arg(&cpu_out));
    if run_gpu(
        bin()
            .arg("eval")
            .arg(&input)
            .args(["--backend", "gpu", "-o"])
            .arg(&gpu_out),
    )
    .is_some()
    {
        let (want, got) = (eval_lines(&cpu_out), eval_lines(&gpu_out));
        assert_eq!(got.len(), want.len());
        let mesh = subsurf::io::read_path(&input).unwrap();
        let diag = subsurf::mesh::bbox_diagonal(&mesh.positions) as f64;
        for (g, w) in got.iter().zip(&want) {
            assert_eq!(g[..3], w[..3]);
            for k in 3..12 {
                let scale = if k < 6 { diag } else { diag.max(w[k].abs()) };
                assert!((g[k] - w[k]).abs() <= 1e-5 * scale, "{g:?} vs {w:?}");
            }
        }
    }
}

/// `eval --at` on a Catmull-Clark mesh: the library's ptex samples, and a query outside the
/// unit square refused naming it.
#[test]
fn eval_at_on_ptex_faces() {
    let input = repo("testdata/shapes/catmark_cube.obj");
    let mesh = subsurf::io::read_path(&input).unwrap();
    let topo = Topology::new(&mesh).unwrap();
    let table = subsurf::limit::PatchTable::build(&topo, &Default::default()).unwrap();
    let surface = subsurf::limit::LimitSurface::new(table, &mesh.positions);
    let queries = tmp("cc_queries.txt");
    std::fs::write(&queries, "0 0.5 0.5\n5 0.25 1\n").unwrap();
    let out = tmp("cc_at.txt");
    run_ok(
        bin()
            .arg("eval")
            .arg(&input)
            .arg("--at")
            .arg(&queries)
            .arg("-o")
            .arg(&out),
    );
    // f32 values, each in its shortest round-trip form: parsed as f32 they are exact.
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<Vec<f32>> = text
        .lines()
        .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(lines.len(), 2);
    for l in &lines {
        let r = surface.eval(l[0] as usize, l[1], l[2]).unwrap();
        assert_eq!(&l[3..], &[r.p, r.du, r.dv].concat()[..]);
    }
    std::fs::write(&queries, "0 0.5 1.5\n").unwrap();
    let o = bin()
        .arg("eval")
        .arg(&input)
        .arg("--at")
        .arg(&queries)
        .arg("-o")
        .arg(tmp("cc_bad.txt"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("query 0: ptex face 0 at (u, v) = (0.5, 1.5)"),
        "{err}"
    );
}

/// `limit --backend gpu` on a Loop mesh: the GPU evaluates the library's tessellation (same
/// triangles, positions within 1e-5 of the bounding-box diagonal); `--tess 1` is refused
/// naming the range.
#[test]
fn limit_on_the_gpu_and_what_the_loop_surface_cannot_do() {
    use subsurf::limit::LoopLimit;
    let input = repo("testdata/shapes/loop_cube.obj");
    let path = tmp("loop_gpu.obj");
    if run_gpu(
        bin()
            .arg("limit")
            .arg(&input)
            .args(["--backend", "gpu", "--tess", "5", "--isolation", "3", "-o"])
            .arg(&path),
    )
    .is_some()
    {
        let got = subsurf::io::read_path(&path).unwrap();
        let mesh = subsurf::io::read_path(&input).unwrap();
        let topo = Topology::new(&mesh).unwrap();
        let surface = LoopLimit::at_precision(&topo, &mesh.positions, 3).unwrap();
        let (want, _) = surface.tessellate(&topo, 4).unwrap().to_mesh();
        assert_eq!(got.face_indices, want.face_indices);
        assert_eq!(got.positions.len(), want.positions.len());
        let tol = 1e-5 * subsurf::mesh::bbox_diagonal(&want.positions);
        for (g, w) in got.positions.iter().zip(&want.positions) {
            assert!((0..3).all(|k| (g[k] - w[k]).abs() <= tol), "{g:?} vs {w:?}");
        }
    }
    let o = bin()
        .arg("limit")
        .arg(&input)
        .args(["--tess", "1", "-o"])
        .arg(tmp("loop_tess1.obj"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("2..=1025"));
}
