//! A lean last level (`RefineOptions::lean`) against a full one on every catmark, bilinear and Loop
//! regression shape: the same face lists, holes and vertex count, bit-identical stencils and
//! positions, and the same limit positions and UVs (rebuilt on demand). One-shot refinement
//! (`refine_once`, no tables kept) against the `Refiner`, bit for bit.

use std::path::PathBuf;
use subsurf::refine::refine_once;
use subsurf::{CreaseMethod, FVarLinearInterpolation, Mesh, RefineOptions, Refiner, Topology};

fn shapes() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    subsurf::shapes::regression_shapes(&dir, &["catmark_", "bilinear_", "loop_"]).unwrap()
}

#[test]
fn lean_last_level_matches_full_on_every_shape() {
    let paths = shapes();
    assert!(paths.len() >= 90, "regression shapes: {}", paths.len());
    for path in paths {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let mut mesh = subsurf::io::read_path(&path).unwrap();
        let level = if mesh.face_indices.len() * 16 <= 20_000 {
            3
        } else {
            2
        };
        // The shape's own crease method, then Chaikin's (whose decay depends on neighbours,
        // so the lean step stores the child sharpness instead of deriving it).
        for method in [mesh.options.crease_method, CreaseMethod::Chaikin] {
            mesh.options.crease_method = method;
            let name = format!("{name} {method:?}");
            for level in 1..=level {
                check_lean(&name, &mesh, level);
            }
        }
    }
}

fn check_lean(name: &str, mesh: &Mesh, level: usize) {
    let base = Topology::new(mesh).unwrap();
    let full = Refiner::new(base.clone(), level).unwrap();
    let lean = Refiner::with_options(base, level, RefineOptions::lean()).unwrap();
    let (f, l) = (full.last(), lean.last());
    assert!(!lean.is_full(level) && full.is_full(level));
    assert_eq!(l.num_vertices(), f.num_vertices(), "{name} L{level}");
    assert_eq!(
        l.arrays().face_offsets,
        f.arrays().face_offsets,
        "{name} L{level}"
    );
    assert_eq!(
        l.arrays().face_verts,
        f.arrays().face_verts,
        "{name} L{level}"
    );
    assert_eq!(
        l.arrays().face_is_hole,
        f.arrays().face_is_hole,
        "{name} L{level}"
    );
    assert!(l.arrays().edge_verts.is_empty() && l.arrays().vert_edges.is_empty());
    // Every level's stencils, the last one built from the parent alone, bit for bit.
    assert_eq!(
        lean.stencils(),
        full.stencils(),
        "{name} L{level}: stencils"
    );
    let pf = full.refine_positions(&mesh.positions);
    let pl = lean.refine_positions(&mesh.positions);
    assert_eq!(pl, pf, "{name} L{level}: positions");
    assert_eq!(lean.limit(&pl), full.limit(&pf), "{name} L{level}: limit");
    let mf = full.to_mesh(level, pf);
    let ml = lean.to_mesh(level, pl);
    assert_eq!(ml.face_indices, mf.face_indices, "{name} L{level}: mesh");
    if let Some(uv) = &mesh.uvs {
        let mode = FVarLinearInterpolation::CornersPlus1;
        let uf = full.refine_uvs(uv, mode).unwrap().pop().unwrap();
        let ul = lean.refine_uvs(uv, mode).unwrap().pop().unwrap();
        assert_eq!(ul.indices, uf.indices, "{name} L{level}: UV indices");
        assert_eq!(ul.values, uf.values, "{name} L{level}: UVs");
    }
}

#[test]
fn lean_refiner_of_level_zero_is_the_base() {
    let mesh = subsurf::shapes::cube();
    let base = Topology::new(&mesh).unwrap();
    let r = Refiner::with_options(base.clone(), 0, RefineOptions::lean()).unwrap();
    assert!(r.is_full(0));
    assert_eq!(r.last().arrays().edge_verts, base.arrays().edge_verts);
    assert_eq!(r.refine_positions(&mesh.positions), mesh.positions);
}

#[test]
fn refine_once_equals_the_refiner_bit_for_bit() {
    for path in shapes() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let mesh = subsurf::io::read_path(&path).unwrap();
        let level = if mesh.face_indices.len() * 16 <= 20_000 {
            3
        } else {
            2
        };
        for options in [RefineOptions::default(), RefineOptions::lean()] {
            let base = Topology::new(&mesh).unwrap();
            let r = Refiner::with_options(base.clone(), level, options).unwrap();
            let (t, p) = refine_once(base, level, &mesh.positions, options).unwrap();
            let expected = r.refine_positions(&mesh.positions);
            // Bit patterns, so that -0.0 and 0.0 (or NaN) cannot pass for each other.
            let bits = |v: &[[f32; 3]]| -> Vec<[u32; 3]> {
                v.iter().map(|q| q.map(f32::to_bits)).collect()
            };
            assert_eq!(bits(&p), bits(&expected), "{name} {options:?}");
            let last = r.last();
            assert_eq!(
                t.arrays().face_verts,
                last.arrays().face_verts,
                "{name} {options:?}"
            );
            assert_eq!(
                t.arrays().face_is_hole,
                last.arrays().face_is_hole,
                "{name} {options:?}"
            );
            assert_eq!(
                t.arrays().edge_verts,
                last.arrays().edge_verts,
                "{name} {options:?}"
            );
            assert_eq!(
                t.arrays().vert_rule,
                last.arrays().vert_rule,
                "{name} {options:?}"
            );
            assert_eq!(t.num_vertices(), last.num_vertices(), "{name} {options:?}");
        }
    }
}

#[test]
fn refine_once_refuses_data_of_the_wrong_length() {
    let mesh = subsurf::shapes::cube();
    let base = Topology::new(&mesh).unwrap();
    let short = &mesh.positions[..mesh.positions.len() - 1];
    assert!(refine_once(base, 2, short, RefineOptions::lean()).is_err());
}

/// The written (tagged) last level of a lean refiner, of a full one and of `refine_once_mesh`
/// (full and lean) are one mesh on every creased Loop shape: a lean Loop level derives the
/// sharpness that remains from its parent, numbering edge points after the vertices.
#[test]
fn lean_loop_levels_are_written_with_the_full_level_tags() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let mut tagged = 0;
    for path in subsurf::shapes::regression_shapes(&dir, &["loop_"]).unwrap() {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let mesh = subsurf::io::read_path(&path).unwrap();
        let base = Topology::new(&mesh).unwrap();
        for level in 1..=2 {
            let full = Refiner::new(base.clone(), level).unwrap();
            let lean = Refiner::with_options(base.clone(), level, RefineOptions::lean()).unwrap();
            let p = full.refine_positions(&mesh.positions);
            let m = full.to_tagged_mesh(level, p.clone()).unwrap();
            tagged += (!m.creases.is_empty() || !m.corners.is_empty()) as usize;
            let l = lean.to_tagged_mesh(level, p).unwrap();
            assert_eq!(l, m, "{name} L{level}: lean");
            for options in [RefineOptions::lean(), RefineOptions::default()] {
                let once = subsurf::refine::refine_once_mesh(
                    base.clone(),
                    level,
                    &mesh.positions,
                    options,
                )
                .unwrap();
                assert_eq!(once, m, "{name} L{level}: refine_once_mesh {options:?}");
            }
        }
    }
    assert!(tagged >= 10, "only {tagged} tagged Loop levels");
}
