//! `subsurf refine --uv-interpolation`: the UVs written equal the library's face-varying refinement
//! in that mode, and the smooth and linear modes differ.

use std::path::PathBuf;
use std::process::Command;
use subsurf::{FVarLinearInterpolation, Refiner, Topology};

fn shape(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../testdata/shapes")
        .join(name)
}

fn refine_with(mode: &str, out: &PathBuf) -> subsurf::Mesh {
    let status = Command::new(env!("CARGO_BIN_EXE_subsurf"))
        .arg("refine")
        .arg(shape("catmark_fvar_bound1.obj"))
        .args(["-l", "2", "--uv-interpolation", mode, "-o"])
        .arg(out)
        .status()
        .unwrap();
    assert!(status.success());
    subsurf::io::read_path(out).unwrap()
}

#[test]
fn refine_uv_interp_writes_the_modes_uvs() {
    let dir = std::env::temp_dir().join(format!("subsurf-cli-uv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = subsurf::io::read_path(shape("catmark_fvar_bound1.obj")).unwrap();
    let refiner = Refiner::new(Topology::new(&input).unwrap(), 2).unwrap();
    let corner_uvs = |m: &subsurf::Mesh| -> Vec<[f32; 2]> {
        let fv = m.uvs.as_ref().expect("UVs written");
        fv.indices.iter().map(|&i| fv.values[i as usize]).collect()
    };
    let mut written = Vec::new();
    for (flag, mode) in [
        ("corners-only", FVarLinearInterpolation::CornersOnly),
        ("linear", FVarLinearInterpolation::All),
    ] {
        let mesh = refine_with(flag, &dir.join(format!("{flag}.obj")));
        let ours = corner_uvs(&mesh);
        let lib = refiner
            .refine_uvs(input.uvs.as_ref().unwrap(), mode)
            .unwrap()
            .pop()
            .unwrap();
        assert_eq!(ours.len(), lib.indices.len());
        for (c, (a, &i)) in ours.iter().zip(&lib.indices).enumerate() {
            let b = lib.values[i as usize];
            assert!(
                (a[0] - b[0]).abs() < 1e-5 && (a[1] - b[1]).abs() < 1e-5,
                "{flag} corner {c}: {a:?} vs {b:?}"
            );
        }
        written.push(ours);
    }
    assert!(written[0]
        .iter()
        .zip(&written[1])
        .any(|(a, b)| (a[0] - b[0]).abs() > 1e-3 || (a[1] - b[1]).abs() > 1e-3));
}

/// `--limit` moves the UVs to their face-varying limit as well as the positions.
#[test]
fn refine_limit_writes_limit_uvs() {
    let dir = std::env::temp_dir().join(format!("subsurf-cli-uvlim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("limit.obj");
    let status = Command::new(env!("CARGO_BIN_EXE_subsurf"))
        .arg("refine")
        .arg(shape("catmark_fvar_bound1.obj"))
        .args([
            "-l",
            "2",
            "--uv-interpolation",
            "corners-only",
            "--limit",
            "-o",
        ])
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let mesh = subsurf::io::read_path(&out).unwrap();
    let input = subsurf::io::read_path(shape("catmark_fvar_bound1.obj")).unwrap();
    let refiner = Refiner::new(Topology::new(&input).unwrap(), 2).unwrap();
    let uvs = input.uvs.as_ref().unwrap();
    let fvar = refiner
        .fvar_refinement(
            &uvs.indices,
            uvs.values.len(),
            FVarLinearInterpolation::CornersOnly,
        )
        .unwrap();
    let last = fvar.refine(&uvs.values).unwrap().pop().unwrap();
    let limit = refiner.limit_face_varying(&fvar, &last.values).unwrap();
    let fv = mesh.uvs.as_ref().expect("UVs written");
    let mut moved = 0;
    for (c, (&w, &i)) in fv.indices.iter().zip(&last.indices).enumerate() {
        let (a, b, r) = (
            fv.values[w as usize],
            limit[i as usize],
            last.values[i as usize],
        );
        assert!(
            (a[0] - b[0]).abs() < 1e-5 && (a[1] - b[1]).abs() < 1e-5,
            "corner {c}: written {a:?} vs limit {b:?}"
        );
        moved += usize::from((a[0] - r[0]).abs() > 1e-4 || (a[1] - r[1]).abs() > 1e-4);
    }
    assert!(
        moved > 100,
        "only {moved} corners differ from the refined UVs"
    );
}
