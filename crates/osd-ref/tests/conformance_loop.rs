//! subsurf's Loop refinement against OpenSubdiv 3.5 (`Sdc::SCHEME_LOOP`), shape by shape:
//! every `loop_*` regression shape at levels 1–3 (4 for small shapes), topology identical
//! (face and edge lists, holes) and positions within 1e-6 of the bounding-box diagonal; the
//! limit stencils (`--limit`), each boundary mode and the Chaikin crease method; and the
//! refusal of non-triangle faces, which OpenSubdiv refuses too.

#[macro_use]
mod common;

use osd_ref::OsdMesh;
use subsurf::{BoundaryInterpolation, CreaseMethod, Mesh, Refiner, Scheme, Topology};

fn osd_mesh(m: &Mesh) -> OsdMesh<'_> {
    let mut o = OsdMesh::from(m);
    o.uvs = None;
    o
}

fn read(name: &str) -> Mesh {
    let path = common::shapes_dir().join(format!("{name}.obj"));
    let mesh = subsurf::io::obj::read_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(mesh.options.scheme, Scheme::Loop, "{name}");
    mesh
}

/// Compares `mesh` refined to every level up to `max_level`; returns the worst relative error.
fn compare(name: &str, mesh: &Mesh, max_level: usize) -> f32 {
    let diag = subsurf::mesh::bbox_diagonal(&mesh.positions).max(1e-30);
    let osd = osd_ref::refine_uniform(&osd_mesh(mesh), max_level)
        .unwrap_or_else(|e| panic!("{name}: OpenSubdiv: {e}"));
    let refiner = Refiner::new(Topology::new(mesh).unwrap(), max_level)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let ours = refiner.refine_all(&mesh.positions);
    let mut worst = 0.0f32;
    // Rings derived level by level keep the documented ring order at manifold vertices, and
    // every local index points back, manifold or not.
    for level in 1..=max_level {
        let (o, s) = (&osd[level], &ours[level]);
        let t = &refiner.levels[level];
        assert_eq!(s.len(), o.positions.len(), "{name} level {level}: vertices");
        assert_eq!(
            t.arrays().face_verts,
            o.face_verts,
            "{name} level {level}: faces"
        );
        assert_eq!(
            t.arrays().edge_verts,
            o.edge_verts,
            "{name} level {level}: edges"
        );
        assert_eq!(
            t.arrays().face_is_hole,
            o.face_is_hole,
            "{name} level {level}: holes"
        );
        for (i, (a, b)) in s.iter().zip(&o.positions).enumerate() {
            let d = common::dist(*a, *b) / diag;
            assert!(
                d <= 1e-6,
                "{name} level {level} vertex {i}: subsurf {a:?} OpenSubdiv {b:?} ({d:e} of the diagonal)"
            );
            worst = worst.max(d);
        }
        if let Err(e) = t.check_consistency() {
            panic!("{name} level {level}: {e}");
        }
    }
    worst
}

#[test]
fn every_loop_shape_matches_opensubdiv() {
    require_osd!();
    let names = common::shape_names(&["loop_"]);
    assert!(
        names.len() >= 31,
        "expected the loop shapes, found {}",
        names.len()
    );
    let mut report = Vec::new();
    for name in &names {
        let mesh = read(name);
        let level = if mesh.face_indices.len() * 64 <= 20_000 {
            4
        } else {
            3
        };
        let worst = compare(name, &mesh, level);
        report.push(format!("{name:28} levels 1-{level}: max error {worst:.2e}"));
    }
    eprintln!("{}", report.join("\n"));
}

/// Each boundary mode on the open shapes, and Chaikin's crease rule on the creased ones.
#[test]
fn loop_option_variants_match_opensubdiv() {
    require_osd!();
    for name in [
        "loop_triangle_edgeonly",
        "loop_saddle_edgecorner",
        "loop_xord_boundary",
        "loop_nonman_edges",
        "loop_fvar_bound1",
    ] {
        for mode in [
            BoundaryInterpolation::None,
            BoundaryInterpolation::EdgeOnly,
            BoundaryInterpolation::EdgeAndCorner,
        ] {
            let mut mesh = read(name);
            mesh.options.boundary = mode;
            compare(name, &mesh, 3);
        }
    }
    for name in [
        "loop_cube_creases0",
        "loop_cube_creases1",
        "loop_cubes_semisharp",
        "loop_icos_semisharp",
        "loop_chaikin0",
    ] {
        for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
            let mut mesh = read(name);
            mesh.options.crease_method = method;
            compare(name, &mesh, 3);
        }
    }
}

/// `--limit`: last-level vertices moved to the limit surface, as `PrimvarRefiner::Limit`.
#[test]
fn loop_limit_positions_match_opensubdiv() {
    require_osd!();
    for name in common::shape_names(&["loop_"]) {
        let mesh = read(&name);
        let level = 2;
        let theirs = osd_ref::limit_stencil_positions(&osd_mesh(&mesh), level).unwrap();
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
        let ours = refiner.limit(&refiner.refine_positions(&mesh.positions));
        let diag = subsurf::mesh::bbox_diagonal(&mesh.positions).max(1e-30);
        assert_eq!(ours.len(), theirs.len(), "{name}");
        for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            let d = common::dist(*a, *b) / diag;
            assert!(d <= 1e-6, "{name} vertex {i}: {a:?} vs {b:?}");
        }
    }
}

/// A quad in a Loop mesh: both libraries refuse it, subsurf naming the face.
#[test]
fn loop_refuses_non_triangles_as_opensubdiv_does() {
    require_osd!();
    let mut mesh = read("loop_tetrahedron");
    mesh.uvs = None;
    // Append a quad over existing vertices as face 4.
    mesh.face_counts.push(4);
    mesh.face_indices.extend_from_slice(&[0, 1, 2, 3]);
    assert!(osd_ref::refine_uniform(&osd_mesh(&mesh), 1).is_err());
    let err = Refiner::new(Topology::new(&mesh).unwrap(), 1).unwrap_err();
    assert!(err.to_string().contains("face 4 has 4 vertices"), "{err}");
}
