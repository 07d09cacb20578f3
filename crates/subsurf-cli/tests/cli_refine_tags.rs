//! `subsurf refine --keep-holes` writes the tags that remain (issue 12): refining the written
//! level 1 two more levels gives the file that refining the input three levels writes — the same faces and
//! holes, vertex for vertex up to the numbering of edge points, within 1e-6 of the bounding-box
//! diagonal, UVs included. The options given on the command line travel in the file. Both of
//! the CLI's refinement paths: one-shot with a lean last level (no UVs) and the full refiner.
//! Without `--keep-holes` hole faces are left out of every format (issue 40).

mod common;

use common::{bin, repo, run_ok, tmp};
use std::collections::HashMap;
use std::path::Path;
use subsurf::Mesh;

fn refine(input: &Path, level: u32, flags: &[&str], out: &str) -> Mesh {
    let path = tmp(out);
    run_ok(
        bin()
            .arg("refine")
            .arg(input)
            .args(["--level", &level.to_string()])
            .args(flags)
            .arg("-o")
            .arg(&path),
    );
    subsurf::io::read_path(&path).unwrap()
}

/// Asserts that `a` and `b` have the same faces and holes up to a renumbering of vertices and
/// positions within `tol` of the diagonal; returns the largest difference relative to it.
fn assert_same(what: &str, a: &Mesh, b: &Mesh, tol: f32) -> f32 {
    assert_eq!(a.face_counts, b.face_counts, "{what}: faces");
    assert_eq!(a.holes, b.holes, "{what}: holes");
    let (mut ab, mut ba) = (HashMap::new(), HashMap::new());
    for (c, (&va, &vb)) in a.face_indices.iter().zip(&b.face_indices).enumerate() {
        let x = *ab.entry(va).or_insert(vb);
        let y = *ba.entry(vb).or_insert(va);
        assert!(x == vb && y == va, "{what}: corner {c} joins {va} to {vb}");
    }
    let diag = subsurf::mesh::bbox_diagonal(&b.positions);
    let worst = ab
        .iter()
        .map(|(&va, &vb)| {
            let (p, q) = (a.positions[va as usize], b.positions[vb as usize]);
            (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f32>().sqrt()
        })
        .fold(0.0f32, f32::max);
    assert!(
        worst <= tol * diag,
        "{what}: positions differ by {worst:e} (diagonal {diag})"
    );
    worst / diag
}

#[test]
fn refined_file_refines_on_as_the_level() {
    // Under Chaikin's rule, semi-sharp creases without UVs (the lean one-shot path) and the
    // car with UVs (the full refiner); a closed shape with a hole, and an open creased one
    // under boundary interpolation `none` (its boundary faces become holes).
    for (shape, flags, tag) in [
        (
            "testdata/shapes/catmark_pyramid_creases2.obj",
            &["--crease-method", "chaikin"][..],
            "pyramid",
        ),
        (
            "examples/car.obj",
            &["--crease-method", "chaikin"][..],
            "car",
        ),
        ("testdata/shapes/catmark_hole_test1.obj", &[][..], "hole"),
        (
            "testdata/shapes/catmark_tent_creases0.obj",
            &["--boundary", "none"][..],
            "tent",
        ),
    ] {
        let input = repo(shape);
        let keep: Vec<&str> = flags.iter().copied().chain(["--keep-holes"]).collect();
        let l1 = refine(&input, 1, &keep, &format!("{tag}_l1.obj"));
        assert!(
            !l1.creases.is_empty() || !l1.holes.is_empty(),
            "{shape}: no tags written"
        );
        // No flags the second time: the options come from the file's tags.
        let again = refine(
            &tmp(&format!("{tag}_l1.obj")),
            2,
            &["--keep-holes"],
            &format!("{tag}_l12.obj"),
        );
        let direct = refine(&input, 3, &keep, &format!("{tag}_l3.obj"));
        assert_eq!(again.options, direct.options, "{shape}: options");
        assert_eq!(
            again.creases.len(),
            direct.creases.len(),
            "{shape}: creases"
        );
        let d = assert_same(shape, &again, &direct, 1e-6);
        // UVs are written with their shared values, so they refine on the same way too.
        assert_eq!(again.uvs.is_some(), direct.uvs.is_some(), "{shape}: UVs");
        if let (Some(a), Some(b)) = (&again.uvs, &direct.uvs) {
            for (c, (&i, &j)) in a.indices.iter().zip(&b.indices).enumerate() {
                let (p, q) = (a.values[i as usize], b.values[j as usize]);
                let w = (p[0] - q[0]).abs().max((p[1] - q[1]).abs());
                assert!(w <= 1e-6, "{shape}: corner {c} UV {p:?} vs {q:?}");
            }
        }
        println!("{shape}: level 2 of level 1 vs level 3: {d:e} of the diagonal");
    }
}

#[test]
fn every_format_leaves_holes_out_by_default() {
    let input = repo("testdata/shapes/catmark_hole_test1.obj");
    let all = refine(&input, 1, &["--keep-holes"], "hole_l1_all.obj");
    assert!(!all.holes.is_empty());
    let holes: std::collections::HashSet<u32> = all.holes.iter().copied().collect();
    let drawn: Vec<u32> = (0..all.num_faces() as u32)
        .filter(|f| !holes.contains(f))
        .collect();
    for out in ["hole_l1.obj", "hole_l1.ply", "hole_l1.usda", "hole_l1.glb"] {
        let m = refine(&input, 1, &[], out);
        assert!(m.holes.is_empty(), "{out}: holes tagged");
        if out.ends_with(".glb") {
            // Triangulated (two triangles per drawn quad), only the vertices it uses.
            assert_eq!(m.num_faces(), 2 * drawn.len(), "{out}: faces");
            continue;
        }
        assert_eq!(m.num_vertices(), all.num_vertices(), "{out}: vertices");
        assert_eq!(m.num_faces(), drawn.len(), "{out}: faces");
        // The faces drawn are the input's non-hole faces, in order.
        let faces = |m: &Mesh| -> Vec<Vec<u32>> {
            let mut at = 0;
            m.face_counts
                .iter()
                .map(|&n| {
                    at += n as usize;
                    m.face_indices[at - n as usize..at].to_vec()
                })
                .collect()
        };
        let want: Vec<Vec<u32>> = drawn
            .iter()
            .map(|&f| faces(&all)[f as usize].clone())
            .collect();
        assert_eq!(faces(&m), want, "{out}: faces");
    }
    // An OBJ with no `f` line of a hole: what trimesh, Blender and MeshLab read.
    let text = std::fs::read_to_string(tmp("hole_l1.obj")).unwrap();
    assert!(!text.contains("t hole"), "hole tags written");
    assert_eq!(
        text.lines().filter(|l| l.starts_with("f ")).count(),
        drawn.len()
    );
}

#[test]
fn keep_holes_is_refused_where_holes_cannot_be_tagged() {
    let input = repo("testdata/shapes/catmark_hole_test1.obj");
    for out in ["hole_keep.ply", "hole_keep.glb"] {
        let o = bin()
            .args(["--keep-holes", "refine"])
            .arg(&input)
            .args(["--level", "1", "-o"])
            .arg(tmp(out))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{out}: accepted");
        assert!(err.contains("cannot tag hole faces"), "{out}: {err}");
    }
}
