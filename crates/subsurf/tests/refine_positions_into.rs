//! `Refiner::refine_positions_into` against the stored stencil tables applied step by step
//! (`Refiner::refine_all`, what `refine_positions` gives): the same bits on creased, boundary
//! and lean shapes at every depth, buffers reused across calls, and typed errors (no panic)
//! on wrong lengths.

use std::path::PathBuf;
use subsurf::{Error, Mesh, MeshError, RefineOptions, Refiner, Topology};

fn shape(name: &str) -> Mesh {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    subsurf::io::read_path(dir.join(name)).expect("shape reads")
}

fn bits<const N: usize>(v: &[[f32; N]]) -> Vec<[u32; N]> {
    v.iter().map(|p| p.map(f32::to_bits)).collect()
}

#[test]
fn bit_identical_to_refine_positions_at_every_depth() {
    // Creases (car), boundaries and a non-quad base (pyramid), a closed cube.
    let meshes = [
        shape("catmark_car.obj"),
        shape("catmark_pyramid_creases0.obj"),
        subsurf::shapes::cube(),
    ];
    // One scratch for every call: grown once, then only sliced.
    let mut scratch = Vec::new();
    for m in &meshes {
        for lean in [false, true] {
            let options = if lean {
                RefineOptions::lean()
            } else {
                RefineOptions::default()
            };
            for level in 0..=3 {
                let r = Refiner::with_options(Topology::new(m).unwrap(), level, options).unwrap();
                let want = r.refine_all(&m.positions).pop().unwrap();
                // NaN-filled: every value must be written.
                let mut out = vec![[f32::NAN; 3]; want.len()];
                r.refine_positions_into(&m.positions, &mut out, &mut scratch)
                    .unwrap();
                assert_eq!(bits(&out), bits(&want), "level {level}, lean {lean}");
                // A second frame into the same buffers.
                let moved: Vec<[f32; 3]> = m
                    .positions
                    .iter()
                    .map(|p| [p[0] * 0.5 + 1.0, p[1] - 2.0, p[2] * 3.0])
                    .collect();
                r.refine_positions_into(&moved, &mut out, &mut scratch)
                    .unwrap();
                assert_eq!(bits(&out), bits(&r.refine_all(&moved).pop().unwrap()));
            }
        }
    }
}

#[test]
fn other_widths_match_too() {
    let m = shape("catmark_car.obj");
    let r = Refiner::new(Topology::new(&m).unwrap(), 2).unwrap();
    let uv: Vec<[f32; 2]> = m.positions.iter().map(|p| [p[0], p[2]]).collect();
    let mut out = vec![[0.0f32; 2]; r.last().num_vertices()];
    let mut scratch = Vec::new();
    r.refine_positions_into(&uv, &mut out, &mut scratch)
        .unwrap();
    assert_eq!(bits(&out), bits(&r.refine_all(&uv).pop().unwrap()));
    // The scratch holds the second-to-last level and the one value read past it.
    assert_eq!(scratch.len(), r.levels[1].num_vertices() + 1);
}

#[test]
fn wrong_lengths_are_typed_errors() {
    let m = subsurf::shapes::cube();
    let r = Refiner::new(Topology::new(&m).unwrap(), 2).unwrap();
    let n = r.last().num_vertices();
    let mut scratch = Vec::new();
    let mut out = vec![[0.0f32; 3]; n + 1];
    match r.refine_positions_into(&m.positions, &mut out, &mut scratch) {
        Err(Error::Mesh(MeshError::LengthMismatch {
            expected, found, ..
        })) => assert_eq!((expected, found), (n, n + 1)),
        other => panic!("expected LengthMismatch, got {other:?}"),
    }
    let mut out = vec![[0.0f32; 3]; n];
    match r.refine_positions_into(&m.positions[..7], &mut out, &mut scratch) {
        Err(Error::Mesh(MeshError::LengthMismatch {
            expected, found, ..
        })) => assert_eq!((expected, found), (8, 7)),
        other => panic!("expected LengthMismatch, got {other:?}"),
    }
}

#[test]
fn bit_identical_on_every_regression_shape() {
    // Smooth rows evaluated from their indices, the others from their stored rows: the same
    // bits as the tables on every rule OpenSubdiv's shapes exercise (creases, corners, holes,
    // non-manifold, valence 2 and 360, smooth triangles, Chaikin, bilinear, Loop).
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let paths =
        subsurf::shapes::regression_shapes(&dir, &["catmark_", "bilinear_", "loop_"]).unwrap();
    assert!(paths.len() > 50);
    let mut scratch = Vec::new();
    for path in paths {
        let m = subsurf::io::read_path(&path).unwrap();
        let r = Refiner::new(Topology::new(&m).unwrap(), 2).unwrap();
        let want = r.refine_all(&m.positions).pop().unwrap();
        let mut out = vec![[f32::NAN; 3]; want.len()];
        r.refine_positions_into(&m.positions, &mut out, &mut scratch)
            .unwrap();
        assert_eq!(bits(&out), bits(&want), "{}", path.display());
    }
}
