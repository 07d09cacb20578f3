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
fn prep_bicubic_is_the_old_no_perturbation() {
    let tet = repo("testdata/shapes/catmark_toroidal_tet.obj");
    let (new, old) = (tmp("bicubic_new.png"), tmp("bicubic_old.png"));
    let render = |out: &Path, args: &[&str]| {
        run_gpu(
            bin()
                .arg("render")
                .arg(&tet)
                .arg("-o")
                .arg(out)
                .args(["--tess", "4", "--size", "48x40", "--color-by", "patch-kind"])
                .args(args),
        )
    };
    let Some(o) = render(&new, &["--method", "prep-bicubic"]) else {
        return;
    };
    assert!(String::from_utf8_lossy(&o.stderr).contains("(prep-bicubic, 4)"));
    let Some(_) = render(&old, &["--method", "prep", "--no-perturbation"]) else {
        return;
    };
    assert_eq!(std::fs::read(&new).unwrap(), std::fs::read(&old).unwrap());
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

/// Decodes an 8-bit RGBA PNG: (width, height, pixels).
fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// `render --method limit` on a Loop mesh draws the Loop limit surface (evaluated on the
/// CPU): on a transparent background the covered pixels span the projection of the library's
/// limit triangles under the image's camera, to a pixel; the adaptive rate flags and the
/// p-rep, Catmull-Clark constructions, are refused before any GPU is opened.
#[test]
fn render_limit_draws_the_loop_limit_surface() {
    let shape = repo("testdata/shapes/loop_icosahedron.obj");
    let out = tmp("loop_limit.png");
    let (w, h) = (160u32, 120u32);
    let Some(o) = run_gpu(
        bin()
            .arg("render")
            .arg(&shape)
            .arg("-o")
            .arg(&out)
            .args(["--method", "limit", "--tess", "9", "--size", "160x120"])
            .args(["--background", "transparent", "--color-by", "patch-kind"]),
    ) else {
        return;
    };
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("Gregory-triangle"), "{err}");
    let mesh = subsurf::io::read_path(&shape).unwrap();
    let options = subsurf::surface::SurfaceOptions {
        method: subsurf::surface::Method::Limit {
            samples: 9,
            options: Default::default(),
        },
        ..Default::default()
    };
    let s = subsurf::surface::build(&mesh, &options, &subsurf::surface::Cpu).unwrap();
    assert_eq!(rendered_triangles(&o), s.triangles.len());
    assert_eq!(s.triangles.len(), 20 * 64);
    let rm = subsurf_render::RenderMesh::from(s);
    let camera = subsurf_render::RenderOptions {
        width: w,
        height: h,
        fit: subsurf_render::Fit::Tight,
        ..Default::default()
    }
    .camera(&rm)
    .unwrap();
    let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
    for &p in &rm.positions {
        let q = camera.project(p, w, h);
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    let (iw, ih, px) = read_png(&out);
    assert_eq!((iw, ih), (w, h));
    let (mut plo, mut phi) = ([u32::MAX; 2], [0u32; 2]);
    let mut covered = 0usize;
    for y in 0..h {
        for x in 0..w {
            if px[4 * (y * w + x) as usize + 3] > 0 {
                covered += 1;
                plo = [plo[0].min(x), plo[1].min(y)];
                phi = [phi[0].max(x), phi[1].max(y)];
            }
        }
    }
    assert!(covered > (w * h / 10) as usize, "{covered} pixels covered");
    for k in 0..2 {
        assert!(
            (plo[k] as f32 - lo[k]).abs() <= 1.5,
            "{k}: {plo:?} vs {lo:?}"
        );
        assert!(
            (phi[k] as f32 + 1.0 - hi[k]).abs() <= 1.5,
            "{k}: {phi:?} vs {hi:?}"
        );
    }
    for (flags, want) in [
        (
            &["--tolerance", "1e-3"][..],
            "Catmull-Clark limit surface only",
        ),
        (&["--method", "prep"][..], "a Loop mesh has none"),
    ] {
        let mut cmd = bin();
        cmd.arg("render").arg(&shape).args(["-o", "x.png"]);
        if flags[0] == "--tolerance" {
            cmd.args(["--method", "limit"]);
        }
        let bad = cmd.args(flags).output().unwrap();
        assert!(!bad.status.success());
        let err = String::from_utf8_lossy(&bad.stderr);
        assert!(err.contains(want), "{flags:?}: {err}");
    }
}

/// The silhouette's margins (left, right, top, bottom) in pixels: the first and last rows and
/// columns whose pixels differ from the corner's background.
fn margins(path: &Path) -> [u32; 4] {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let (w, h) = (info.width as usize, info.height as usize);
    let ch = info.line_size / w;
    let px = |x: usize, y: usize| &buf[y * info.line_size + x * ch..][..3];
    let bg = px(0, 0).to_vec();
    let (mut x0, mut x1, mut y0, mut y1) = (w, 0, h, 0);
    for y in 0..h {
        for x in 0..w {
            let d: u32 = px(x, y)
                .iter()
                .zip(&bg)
                .map(|(&a, &b)| (a as i32 - b as i32).unsigned_abs())
                .sum();
            if d > 30 {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
        }
    }
    assert!(x0 <= x1, "{}: nothing drawn", path.display());
    [x0, w - 1 - x1, y0, h - 1 - y1].map(|m| m as u32)
}

/// Issue 40: the silhouette is centred, with the same margin on opposite sides, however
/// strong the perspective: a stage of two cubes (one translated by (6, 6, 6), rotated and
/// scaled, made with Pixar's usd-core) and a single mesh, in the iso, front and top views.
#[test]
fn render_centres_the_silhouette_with_equal_margins() {
    let stage = repo("crates/subsurf/tests/data/usd/two_cubes.usda");
    let pawn = repo("examples/pawn.obj");
    let (w, h) = (800u32, 600u32);
    for (input, tag) in [(&stage, "cubes"), (&pawn, "pawn")] {
        for view in ["iso", "front", "top"] {
            let out = tmp(&format!("frame_{tag}_{view}.png"));
            let Some(_) = run_gpu(bin().arg("render").arg(input).arg("-o").arg(&out).args([
                "--view",
                view,
                "--size",
                &format!("{w}x{h}"),
            ])) else {
                return;
            };
            let [l, r, t, b] = margins(&out);
            let at = format!("{tag} {view}: left {l} right {r} top {t} bottom {b}");
            // Opposite margins within 5% of the image of each other, each at least 2%.
            assert!(l.abs_diff(r) as f32 <= 0.05 * w as f32, "{at}");
            assert!(t.abs_diff(b) as f32 <= 0.05 * h as f32, "{at}");
            assert!(l.min(r) as f32 >= 0.02 * w as f32, "{at}");
            assert!(t.min(b) as f32 >= 0.02 * h as f32, "{at}");
            // The binding pair of sides at the margin (1.05): the silhouette fills the image.
            assert!(
                (l + r) as f32 <= 0.1 * w as f32 || (t + b) as f32 <= 0.1 * h as f32,
                "{at}"
            );
        }
    }
}
