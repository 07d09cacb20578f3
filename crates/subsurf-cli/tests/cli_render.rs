//! `subsurf render` and `subsurf compare` end to end: PNG files of the asked size, quiet
//! mode, argument errors. Without a GPU adapter the rendering tests fail with installation
//! advice unless `SUBSURF_SKIP_GPU=1`.

mod common;

use common::{bin, repo, run_gpu, tmp};
use std::path::Path;

/// Width and height from a PNG's IHDR chunk.
fn png_size(path: &Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n");
    let be = |i: usize| u32::from_be_bytes(b[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

#[test]
fn render_refine_writes_a_png_of_the_asked_size() {
    let out = tmp("pawn.png");
    let Some(o) = run_gpu(
        bin()
            .arg("render")
            .arg(repo("examples/pawn.obj"))
            .arg("-o")
            .arg(&out)
            .args(["--level", "1", "--cage", "--size", "123x77", "--up", "z"]),
    ) else {
        return;
    };
    assert_eq!(png_size(&out), (123, 77));
    assert!(String::from_utf8_lossy(&o.stderr).contains("rendered 4704 triangles"));
}

#[test]
fn quiet_render_prints_nothing_and_notes_fallbacks_otherwise() {
    let out = tmp("car.png");
    let mut cmd = bin();
    cmd.arg("render")
        .arg(repo("examples/car.obj"))
        .arg("-o")
        .arg(&out)
        .args(["--level", "0", "--size", "64x48", "--color-by", "level"]);
    let Some(o) = run_gpu(&mut cmd) else { return };
    assert!(String::from_utf8_lossy(&o.stderr).contains("note: --color-by level"));
    let Some(o) = run_gpu(cmd.arg("--quiet")) else {
        return;
    };
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("note:") && !err.contains("rendered"), "{err}");
    assert_eq!(png_size(&out), (64, 48));
}

#[test]
fn compare_puts_two_panels_side_by_side() {
    let out = tmp("cmp.png");
    let pawn = repo("examples/pawn.obj");
    let tet = repo("testdata/shapes/catmark_toroidal_tet.obj");
    let Some(_) = run_gpu(
        bin()
            .arg("compare")
            .arg(format!("{}@refine:0", pawn.display()))
            .arg(format!("{}@prep-bicubic:4", tet.display()))
            .arg("-o")
            .arg(&out)
            .args(["--size", "50x40", "--gap", "6"]),
    ) else {
        return;
    };
    assert_eq!(png_size(&out), (106, 40));
}

#[test]
fn argument_errors_need_no_gpu() {
    let out = bin()
        .arg("render")
        .arg(repo("examples/pawn.obj"))
        .args(["-o", "x.png", "--size", "0x10"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("1..=16384"));
    // The p-rep refuses meshes with boundaries (the pawn is open at the bottom).
    let out = bin()
        .arg("render")
        .arg(repo("examples/pawn.obj"))
        .args(["-o", "x.png", "--method", "prep"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("closed"));
}

/// The triangle count of a `render` run's summary line.
fn rendered_triangles(o: &std::process::Output) -> usize {
    let err = String::from_utf8_lossy(&o.stderr);
    let at = err.find("rendered ").expect("summary line") + "rendered ".len();
    err[at..].split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn render_limit_takes_the_adaptive_rate_flags() {
    // --tolerance renders the library's adaptive surface for the same policy; --pixels
    // measures edges under the image's own camera, so a larger image needs more triangles.
    let shape = repo("testdata/shapes/catmark_torus.obj");
    let out = tmp("torus_tolerance.png");
    let render = |args: &[&str]| {
        run_gpu(
            bin()
                .arg("render")
                .arg(&shape)
                .arg("-o")
                .arg(&out)
                .args(["--method", "limit"])
                .args(args),
        )
    };
    let Some(o) = render(&["--tolerance", "2e-3", "--size", "96x64"]) else {
        return;
    };
    assert_eq!(png_size(&out), (96, 64));
    let mesh = subsurf::io::read_path(&shape).unwrap();
    let options = subsurf::surface::SurfaceOptions {
        method: subsurf::surface::Method::Adaptive {
            policy: subsurf::tess::RatePolicy::Tolerance(2e-3),
            origin: "--tolerance".into(),
            options: Default::default(),
        },
        ..Default::default()
    };
    let want = subsurf::surface::build(&mesh, &options, &subsurf::surface::Cpu).unwrap();
    assert_eq!(rendered_triangles(&o), want.triangles.len());

    let Some(small) = render(&["--pixels", "6", "--size", "64x48"]) else {
        return;
    };
    let Some(large) = render(&["--pixels", "6", "--size", "256x192"]) else {
        return;
    };
    let (small, large) = (rendered_triangles(&small), rendered_triangles(&large));
    assert!(small * 4 < large, "{small} vs {large} triangles");

    let bad = bin()
        .arg("render")
        .arg(&shape)
        .args(["-o", "x.png", "--tolerance", "1e-3"])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("apply to --method limit"));
}
