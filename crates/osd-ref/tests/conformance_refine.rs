//! subsurf's uniform refinement against OpenSubdiv 3.5, shape by shape: every `catmark_*` and
//! `bilinear_*` regression shape, levels 1–3 (4 for small shapes), vertex for vertex.

#[macro_use]
mod common;

use osd_ref::OsdMesh;
use subsurf::{Mesh, Refiner, Topology};

fn osd_mesh(m: &Mesh) -> OsdMesh<'_> {
    let mut o = OsdMesh::from(m);
    // Compare geometry only; UVs are compared separately.
    o.uvs = None;
    o
}

fn diagonal(points: &[[f32; 3]]) -> f32 {
    subsurf::mesh::bbox_diagonal(points).max(1e-30)
}

/// Compares one shape at every level up to `max_level`; returns the worst relative error.
fn compare(name: &str, max_level: usize) -> f32 {
    compare_with(name, max_level, |_| {})
}

/// As [`compare`], after `edit` changes the mesh's options.
fn compare_with(name: &str, max_level: usize, edit: impl Fn(&mut Mesh)) -> f32 {
    let path = common::shapes_dir().join(format!("{name}.obj"));
    let mut mesh = subsurf::io::obj::read_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
    edit(&mut mesh);
    let diag = diagonal(&mesh.positions);
    let osd = osd_ref::refine_uniform(&osd_mesh(&mesh), max_level)
        .unwrap_or_else(|e| panic!("{name}: OpenSubdiv: {e}"));
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), max_level).unwrap();
    let ours = refiner.refine_all(&mesh.positions);
    let mut worst = 0.0f32;
    for level in 1..=max_level {
        let (o, s) = (&osd[level], &ours[level]);
        let t = &refiner.levels[level];
        assert_eq!(
            s.len(),
            o.positions.len(),
            "{name} level {level}: vertex count"
        );
        assert_eq!(
            t.arrays().face_verts,
            o.face_verts,
            "{name} level {level}: face-vertex lists differ"
        );
        assert_eq!(
            t.arrays().edge_verts,
            o.edge_verts,
            "{name} level {level}: edge-vertex lists differ"
        );
        assert_eq!(
            t.arrays().face_is_hole,
            o.face_is_hole,
            "{name} level {level}: holes differ"
        );
        for (i, (a, b)) in s.iter().zip(&o.positions).enumerate() {
            let d = common::dist(*a, *b) / diag;
            assert!(d <= 1e-5, "{name} level {level} vertex {i}: subsurf {a:?} OpenSubdiv {b:?} (error {d:e} of the diagonal)");
            worst = worst.max(d);
        }
    }
    worst
}

#[test]
fn every_catmark_and_bilinear_shape_matches_opensubdiv() {
    require_osd!();
    let names = common::shape_names(&["catmark_", "bilinear_"]);
    assert!(
        names.len() >= 60,
        "expected the regression shapes, found {}",
        names.len()
    );
    let mut report = Vec::new();
    for name in &names {
        let faces = subsurf::io::obj::read_file(common::shapes_dir().join(format!("{name}.obj")))
            .unwrap()
            .face_indices
            .len();
        let level = if faces * 64 <= 20_000 { 4 } else { 3 };
        let worst = compare(name, level);
        report.push(format!(
            "{name:32} levels 1-{level}: max error {worst:.2e} of the bbox diagonal"
        ));
    }
    eprintln!("{}", report.join("\n"));
}

/// Linear face-varying UVs (`FVAR_LINEAR_ALL`): every refined face corner's value.
#[test]
fn linear_uvs_match_opensubdiv() {
    require_osd!();
    for name in [
        "catmark_car",
        "catmark_fvar_bound0",
        "catmark_gregory_test8",
        "catmark_val2_back2back",
        "catmark_pyramid",
    ] {
        let mesh =
            subsurf::io::obj::read_file(common::shapes_dir().join(format!("{name}.obj"))).unwrap();
        let fv = mesh
            .uvs
            .as_ref()
            .unwrap_or_else(|| panic!("{name} has UVs"));
        let level = 3;
        let mut om = osd_mesh(&mesh);
        om.uvs = Some((&fv.values, &fv.indices));
        let osd = osd_ref::refine_uniform(&om, level).unwrap();
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
        let mut corner: Vec<[f32; 2]> = fv.indices.iter().map(|&i| fv.values[i as usize]).collect();
        for k in 0..level {
            corner = subsurf::refine::refine_uvs_linear(&refiner.levels[k], &corner);
            let (values, indices) = osd[k + 1].uvs.as_ref().unwrap();
            assert_eq!(indices.len(), corner.len(), "{name} level {}", k + 1);
            for (c, (&i, ours)) in indices.iter().zip(&corner).enumerate() {
                let theirs = values[i as usize];
                let d = (ours[0] - theirs[0]).abs().max((ours[1] - theirs[1]).abs());
                assert!(
                    d < 1e-6,
                    "{name} level {} corner {c}: {ours:?} vs {theirs:?}",
                    k + 1
                );
            }
        }
    }
}

/// `--limit`: last-level vertices moved to the limit surface, as `PrimvarRefiner::Limit`.
#[test]
fn limit_positions_match_opensubdiv() {
    require_osd!();
    for name in [
        "catmark_car",
        "catmark_cube_creases1",
        "catmark_edgecorner",
        "catmark_pole64",
        "catmark_chaikin1",
        "catmark_hole_test2",
    ] {
        let mesh =
            subsurf::io::obj::read_file(common::shapes_dir().join(format!("{name}.obj"))).unwrap();
        let level = 2;
        let theirs = osd_ref::limit_stencil_positions(&osd_mesh(&mesh), level).unwrap();
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
        let ours = refiner.limit(&refiner.refine_positions(&mesh.positions));
        let diag = diagonal(&mesh.positions);
        assert_eq!(ours.len(), theirs.len());
        for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            let d = common::dist(*a, *b) / diag;
            assert!(d <= 1e-5, "{name} vertex {i}: {a:?} vs {b:?}");
        }
    }
}

/// Options the regression shapes do not exercise by themselves: the smooth triangle rule,
/// Chaikin creases on the car, and each boundary mode on open shapes.
#[test]
fn option_variants_match_opensubdiv() {
    require_osd!();
    use subsurf::{BoundaryInterpolation, CreaseMethod, TriangleSubdivision};
    for name in [
        "catmark_pyramid",
        "catmark_smoothtris0",
        "catmark_pole8",
        "catmark_gregory_test2",
        "catmark_val2_foldover",
    ] {
        compare_with(name, 3, |m| {
            m.options.triangle_subdivision = TriangleSubdivision::Smooth
        });
    }
    for name in [
        "catmark_car",
        "catmark_pawn",
        "catmark_cube_creases1",
        "catmark_torus_creases0",
    ] {
        compare_with(name, 3, |m| m.options.crease_method = CreaseMethod::Chaikin);
    }
    for name in [
        "catmark_edgeonly",
        "catmark_quadstrips",
        "catmark_xord_boundary",
        "catmark_car",
        "catmark_tent_creases0",
        "catmark_nonman_verts",
    ] {
        for mode in [
            BoundaryInterpolation::None,
            BoundaryInterpolation::EdgeOnly,
            BoundaryInterpolation::EdgeAndCorner,
        ] {
            compare_with(name, 3, |m| m.options.boundary = mode);
        }
    }
}

/// A lean last level on both sides (OpenSubdiv `fullTopologyInLastLevel = false`, subsurf
/// `RefineOptions::lean`): the same last-level positions.
#[test]
fn lean_last_level_matches_opensubdiv_lean() {
    require_osd!();
    for name in [
        "catmark_car",
        "catmark_chaikin1",
        "catmark_cube_creases1",
        "catmark_hole_test2",
        "catmark_nonman_verts",
        "catmark_pole64",
        "bilinear_nonquads1",
        "loop_chaikin1",
        "loop_cube_creases1",
        "loop_nonman_verts",
        "loop_pole64",
        "loop_saddle_edgecorner",
    ] {
        let mesh =
            subsurf::io::obj::read_file(common::shapes_dir().join(format!("{name}.obj"))).unwrap();
        for level in 1..=3 {
            let osd = osd_ref::OsdRefiner::with_last_level(&osd_mesh(&mesh), level, false)
                .unwrap_or_else(|e| panic!("{name}: OpenSubdiv: {e}"));
            let theirs = osd.interpolate(&mesh.positions).unwrap();
            assert!(osd.limit(&theirs).is_err(), "{name}: lean OpenSubdiv limit");
            let options = subsurf::RefineOptions::lean();
            let refiner =
                Refiner::with_options(Topology::new(&mesh).unwrap(), level, options).unwrap();
            let ours = refiner.refine_positions(&mesh.positions);
            let diag = diagonal(&mesh.positions);
            assert_eq!(ours.len(), theirs.len(), "{name} level {level}");
            for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
                let d = common::dist(*a, *b) / diag;
                assert!(d <= 1e-5, "{name} level {level} vertex {i}: {a:?} vs {b:?}");
            }
        }
    }
}
