//! USD on the command line: `refine scene.usd? -o out.usda|usdc|usdz` refines every mesh prim
//! (or `--prim`) and keeps the rest of the stage; each refined prim equals the library
//! refining that prim's mesh, and Pixar's USD (python3 `pxr`) opens the usdc and usdz output
//! with the same prims, points and transforms; `--flatten --prim` (and `render --prim`, which
//! reads the same way) moves the prim by its world transform; `info` lists the mesh prims;
//! `limit` reads one prim.
//!
//! The pxr checks fail when `CI=true` and `python3 -c "import pxr"` fails, and are skipped
//! with a loud message otherwise.

mod common;

use common::{bin, repo, run_ok, tmp};
use std::path::Path;
use subsurf::io::usd::Stage;
use subsurf::{Refiner, Topology};

fn stage_path() -> std::path::PathBuf {
    repo("crates/subsurf/tests/data/usd/stage.usda")
}

fn have_pxr() -> bool {
    let ok = std::process::Command::new("python3")
        .args(["-c", "import pxr"])
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    if !ok {
        let msg = "cli_usd: python3 with pxr (pip install usd-core) is not available";
        if std::env::var("CI").as_deref() == Ok("true") {
            panic!("{msg} (required when CI=true)");
        }
        eprintln!("\n*** SKIPPED: {msg} ***\n");
    }
    ok
}

/// Asserts that pxr opens `file` without a word and sees the mesh prims subsurf reads from
/// it, with the same points and world transforms, and the stage's other prims.
fn check_in_pxr(file: &Path) {
    let out = std::process::Command::new("python3")
        .arg(repo("crates/subsurf/tests/usd_gen.py"))
        .arg("dump")
        .arg(file)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && err.trim().is_empty(), "pxr: {err}");
    let dump: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let ours = Stage::read_path(file).unwrap().meshes().unwrap();
    assert_eq!(dump["meshes"].as_object().unwrap().len(), ours.len());
    for m in &ours {
        let d = &dump["meshes"][m.path.as_str()];
        let points: Vec<[f32; 3]> = d["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| std::array::from_fn(|k| p[k].as_f64().unwrap() as f32))
            .collect();
        assert_eq!(points, m.mesh.positions, "{} {}", file.display(), m.path);
        for i in 0..4 {
            for j in 0..4 {
                let w = d["world"][i][j].as_f64().unwrap();
                assert!((w - m.world[i][j]).abs() < 1e-9, "{}: world", m.path);
            }
        }
    }
    let others: Vec<&str> = dump["others"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o[0].as_str().unwrap())
        .collect();
    assert_eq!(others, ["/World", "/World/Group", "/World/Ball"]);
}

#[test]
fn refine_writes_every_mesh_prim_back_into_its_stage() {
    let src = Stage::read_path(stage_path()).unwrap();
    let before = src.meshes().unwrap();
    let pxr = have_pxr();
    for (ext, input) in [
        ("usda", "usdc"),
        ("usdz", "usdz"),
        ("usda", "usda"),
        ("usdc", "usda"),
        ("usdz", "usda"),
    ] {
        let out = tmp(&format!("refined_{input}.{ext}"));
        let input = stage_path().with_extension(input);
        run_ok(
            bin()
                .args(["refine", "-l", "1", "-o"])
                .arg(&out)
                .arg(&input),
        );
        if pxr && ext != "usda" {
            check_in_pxr(&out);
        }
        let after = Stage::read_path(&out).unwrap().meshes().unwrap();
        let paths: Vec<_> = after.iter().map(|m| m.path.as_str()).collect();
        assert_eq!(
            paths,
            ["/World/A", "/World/Group/B", "/World/D", "/C"],
            "{ext}"
        );
        for (b, a) in before.iter().zip(&after) {
            assert_eq!(a.world, b.world, "{ext} {}: transform kept", a.path);
            let loop_scheme = b.mesh.options.scheme == subsurf::Scheme::Loop;
            if !b.subdivide || loop_scheme {
                // Polygon meshes are kept as they are, and so is a Loop mesh where Loop does
                // not refine.
                continue;
            }
            assert!(
                !a.subdivide,
                "{ext} {}: written as subdivisionScheme none",
                a.path
            );
            let r = Refiner::new(Topology::new(&b.mesh).unwrap(), 1).unwrap();
            let want = r.refine_positions(&b.mesh.positions);
            assert_eq!(a.mesh.positions, want, "{ext} {}", a.path);
        }
    }
    // One prim chosen: only it is refined, the stage keeps the others as they were.
    let out = tmp("one.usda");
    run_ok(
        bin()
            .args(["refine", "-l", "2", "--prim", "/World/Group/B", "-o"])
            .arg(&out)
            .arg(stage_path()),
    );
    let after = Stage::read_path(&out).unwrap().meshes().unwrap();
    assert_eq!(after.len(), 4);
    assert_eq!(after[0].mesh, before[0].mesh, "/World/A untouched");
    assert_eq!(after[1].mesh.num_faces(), before[1].mesh.num_faces() * 16);
    // --flatten --prim: the prim in world space (as render --prim reads it), else in its own
    // coordinates; told by the bounding box info reports.
    let b = &before[1];
    let world: Vec<[f32; 3]> = b
        .mesh
        .positions
        .iter()
        .map(|&p| subsurf::io::usd::transform_point(&b.world, p))
        .collect();
    assert_ne!(
        world, b.mesh.positions,
        "/World/Group/B is moved by its transforms"
    );
    let moved = subsurf::Mesh {
        positions: world.into(),
        ..b.mesh.clone()
    };
    for (flatten, mesh) in [(true, &moved), (false, &b.mesh)] {
        let mut cmd = bin();
        cmd.args(["info", "--json", "--prim", "/World/Group/B"]);
        if flatten {
            cmd.arg("--flatten");
        }
        let out = run_ok(cmd.arg(stage_path()));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let (lo, hi) = mesh.bounding_box().unwrap();
        let f = |k: &str| -> Vec<f32> {
            v[k].as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap() as f32)
                .collect()
        };
        assert_eq!(
            (f("bbox_min"), f("bbox_max")),
            (lo.to_vec(), hi.to_vec()),
            "flatten {flatten}"
        );
    }
    // To OBJ: one prim needed.
    let obj = tmp("b.obj");
    let st = bin()
        .args(["refine", "-l", "1", "-o"])
        .arg(&obj)
        .arg(stage_path())
        .output()
        .unwrap();
    assert!(!st.status.success());
    assert!(String::from_utf8_lossy(&st.stderr).contains("--prim"));
    run_ok(
        bin()
            .args([
                "refine",
                "-l",
                "1",
                "--prim",
                "/World/A",
                "--keep-holes",
                "-o",
            ])
            .arg(&obj)
            .arg(stage_path()),
    );
    // All 6 x 4 faces of level 1, the 4 children of the hole face tagged as holes (as
    // `refine --keep-holes` writes every OBJ); without the flag the 4 are left out.
    let one = subsurf::io::read_path(&obj).unwrap();
    assert_eq!(one.num_faces(), 6 * 4);
    assert_eq!(one.holes.len(), 4);
    run_ok(
        bin()
            .args(["refine", "-l", "1", "--prim", "/World/A", "-o"])
            .arg(&obj)
            .arg(stage_path()),
    );
    let drawn = subsurf::io::read_path(&obj).unwrap();
    assert_eq!(drawn, one.without_holes());
}

#[test]
fn info_lists_mesh_prims_and_limit_reads_one() {
    let out = run_ok(bin().args(["info", "--json"]).arg(stage_path()));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let prims: Vec<&str> = v["prims"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["path"].as_str().unwrap())
        .collect();
    assert_eq!(prims, ["/World/A", "/World/Group/B", "/World/D", "/C"]);
    let out = run_ok(
        bin()
            .args(["info", "--json", "--prim", "/World/Group/B"])
            .arg(stage_path()),
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["faces"], 9);
    assert_eq!(v["scheme"], "bilinear");
    let text = run_ok(bin().arg("info").arg(stage_path()));
    assert!(String::from_utf8_lossy(&text.stdout).contains("/World/Group/B"));
    // limit on one prim of the stage.
    let pts = tmp("limit.obj");
    run_ok(
        bin()
            .args(["limit", "--prim", "/World/A", "-o"])
            .arg(&pts)
            .arg(stage_path()),
    );
    assert!(pts.exists());
}
