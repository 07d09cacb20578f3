//! `subsurf refine` writes the tags that remain (issue 12): refining the written level 1 two
//! more levels gives the file that refining the input three levels writes — the same faces and
//! holes, vertex for vertex up to the numbering of edge points, within 1e-6 of the bounding-box
//! diagonal, UVs included. The options given on the command line travel in the file. Both of
//! the CLI's refinement paths: one-shot with a lean last level (no UVs) and the full refiner.

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
        let l1 = refine(&input, 1, flags, &format!("{tag}_l1.obj"));
        assert!(
            !l1.creases.is_empty() || !l1.holes.is_empty(),
            "{shape}: no tags written"
        );
        // No flags the second time: the options come from the file's tags.
        let again = refine(
            &tmp(&format!("{tag}_l1.obj")),
            2,
            &[],
            &format!("{tag}_l12.obj"),
        );
        let direct = refine(&input, 3, flags, &format!("{tag}_l3.obj"));
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
fn ply_output_leaves_holes_out() {
    let input = repo("testdata/shapes/catmark_hole_test1.obj");
    let obj = refine(&input, 1, &[], "hole_l1_all.obj");
    let ply = refine(&input, 1, &[], "hole_l1.ply");
    assert!(!obj.holes.is_empty());
    assert_eq!(ply.num_faces(), obj.num_faces() - obj.holes.len());
    assert_eq!(ply.num_vertices(), obj.num_vertices());
}
