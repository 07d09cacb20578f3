//! USD on the command line: `refine scene.usd? -o out.usda|usdz` refines every mesh prim (or
//! `--prim`) and keeps the rest of the stage; each refined prim equals the library refining
//! that prim's mesh; `info` lists the mesh prims; `limit` reads one prim.

mod common;

use common::{bin, repo, run_ok, tmp};
use subsurf::io::usd::Stage;
use subsurf::{Refiner, Topology};

fn stage_path() -> std::path::PathBuf {
    repo("crates/subsurf/tests/data/usd/stage.usda")
}

#[test]
fn refine_writes_every_mesh_prim_back_into_its_stage() {
    let src = Stage::read_path(stage_path()).unwrap();
    let before = src.meshes().unwrap();
    // .usdc output is refused before any work.
    let st = bin()
        .args(["refine", "-l", "1", "-o"])
        .arg(tmp("refined.usdc"))
        .arg(stage_path())
        .output()
        .unwrap();
    assert!(!st.status.success());
    assert!(String::from_utf8_lossy(&st.stderr).contains(".usdc"));
    for (ext, input) in [("usda", "usdc"), ("usdz", "usdz"), ("usda", "usda")] {
        let out = tmp(&format!("refined_{input}.{ext}"));
        let input = stage_path().with_extension(input);
        run_ok(
            bin()
                .args(["refine", "-l", "1", "-o"])
                .arg(&out)
                .arg(&input),
        );
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
            .args(["refine", "-l", "1", "--prim", "/World/A", "-o"])
            .arg(&obj)
            .arg(stage_path()),
    );
    // All 6 x 4 faces of level 1, the 4 children of the hole face tagged as holes (as
    // `refine` writes every OBJ).
    let one = subsurf::io::read_path(&obj).unwrap();
    assert_eq!(one.num_faces(), 6 * 4);
    assert_eq!(one.holes.len(), 4);
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
    assert_eq!(v["scheme"], "Bilinear");
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
