//! `subsurf limit` with per-edge rates: the library's tessellation for the same policy, and
//! bad values refused before any output is written, naming the flag (or file and line).

mod common;

use common::{bin, repo, run_ok, tmp};

use subsurf::limit::PatchOptions;
use subsurf::tess::RatePolicy;
use subsurf::Topology;

#[test]
fn adaptive_flags_match_the_library_and_refuse_bad_values() {
    let shape = repo("testdata/shapes/catmark_torus.obj");
    let out_path = tmp("torus_adaptive.obj");
    let _ = std::fs::remove_file(&out_path);
    run_ok(
        bin()
            .arg("limit")
            .arg(&shape)
            .args(["--tolerance", "2e-3", "-o"])
            .arg(&out_path),
    );
    let written = subsurf::io::read_path(&out_path).unwrap();
    let mesh = subsurf::io::read_path(&shape).unwrap();
    let t = Topology::new(&mesh).unwrap();
    let (s, chords) = subsurf::surface::adaptive_surface(
        &t,
        &mesh.positions,
        &RatePolicy::Tolerance(2e-3),
        "--tolerance",
        &PatchOptions::default(),
    )
    .unwrap();
    let want = subsurf::surface::tessellate_adaptive(&s, &chords, "", &subsurf::surface::Cpu)
        .unwrap()
        .tessellation;
    assert_eq!(written.num_faces(), want.triangles.len());
    assert_eq!(written.positions.len(), want.positions.len());

    let rates_file = tmp("torus_rates.txt");
    std::fs::write(&rates_file, "0 1 4\n0 1 0\n").unwrap();
    let bad_rates = format!("{}:2: rate 0 of edge", rates_file.display());
    for (args, want) in [
        (
            vec!["--tolerance=-1"],
            "--tolerance: tolerance -1 is not a positive finite number",
        ),
        (
            vec!["--max-edge-length", "inf"],
            "--max-edge-length: maximum edge length inf",
        ),
        (
            vec!["--pixels", "3"],
            "--pixels: a screen-space size needs a camera",
        ),
        (
            vec!["--edge-rates", rates_file.to_str().unwrap()],
            bad_rates.as_str(),
        ),
    ] {
        let bad_out = tmp("torus_bad.obj");
        let _ = std::fs::remove_file(&bad_out);
        let out = bin()
            .arg("limit")
            .arg(&shape)
            .args(&args)
            .arg("-o")
            .arg(&bad_out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && err.contains(want),
            "{args:?}: {err}"
        );
        assert!(!bad_out.exists(), "{args:?}: output written");
    }

    // The pawn's pole cannot take end caps within 1e-4 / 4 at isolation 10: refused, naming
    // the face and the estimate, nothing written.
    let bad_out = tmp("pawn_unreachable.obj");
    let _ = std::fs::remove_file(&bad_out);
    let out = bin()
        .arg("limit")
        .arg(repo("testdata/shapes/catmark_pawn.obj"))
        .args(["--tolerance", "1e-4", "-o"])
        .arg(&bad_out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success()
            && err.contains(
                "--tolerance: tolerance 1e-4 is out of reach: the end caps of base face 5"
            )
            && err.contains("at isolation 10"),
        "{err}"
    );
    assert!(!bad_out.exists());
}
