//! subsurf's uniform refinement against OpenSubdiv 3.5, shape by shape: every `catmark_*` and
//! `bilinear_*` regression shape, levels 1–3 (4 for small shapes), vertex for vertex.

#[macro_use]
mod common;

use std::borrow::Cow;

use osd_ref::{OsdBoundary, OsdCreaseMethod, OsdMesh, OsdOptions, OsdScheme};
use subsurf::{
    BoundaryInterpolation, CreaseMethod, Mesh, Refiner, Scheme, Topology, TriangleSubdivision,
};

fn osd_options(m: &Mesh) -> OsdOptions {
    OsdOptions {
        scheme: match m.options.scheme {
            Scheme::Catmark => OsdScheme::Catmark,
            Scheme::Bilinear => OsdScheme::Bilinear,
            Scheme::Loop => OsdScheme::Loop,
        },
        boundary: match m.options.boundary {
            BoundaryInterpolation::None => OsdBoundary::None,
            BoundaryInterpolation::EdgeOnly => OsdBoundary::EdgeOnly,
            BoundaryInterpolation::EdgeAndCorner => OsdBoundary::EdgeAndCorner,
        },
        crease_method: match m.options.crease_method {
            CreaseMethod::Uniform => OsdCreaseMethod::Uniform,
            CreaseMethod::Chaikin => OsdCreaseMethod::Chaikin,
        },
        triangle_smooth: m.options.triangle_subdivision == TriangleSubdivision::Smooth,
        fvar_interp: 5,
    }
}

fn osd_mesh(m: &Mesh) -> OsdMesh<'_> {
    OsdMesh {
        positions: &m.positions,
        face_counts: &m.face_counts,
        face_indices: &m.face_indices,
        creases: Cow::Owned(
            m.creases
                .iter()
                .map(|c| (c.v0, c.v1, c.sharpness))
                .collect(),
        ),
        corners: Cow::Owned(m.corners.iter().map(|c| (c.vertex, c.sharpness)).collect()),
        holes: &m.holes,
        uvs: None,
        options: osd_options(m),
    }
}

fn diagonal(points: &[[f32; 3]]) -> f32 {
    let (lo, hi) = subsurf::mesh::bounding_box(points).unwrap_or(([0.0; 3], [1.0; 3]));
    ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2))
        .sqrt()
        .max(1e-30)
}

/// Compares one shape at every level up to `max_level`; returns the worst relative error.
fn compare(name: &str, max_level: usize) -> f32 {
    let path = common::shapes_dir().join(format!("{name}.obj"));
    let mesh = subsurf::io::obj::read_file(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
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
            t.face_verts, o.face_verts,
            "{name} level {level}: face-vertex lists differ"
        );
        assert_eq!(
            t.edge_verts, o.edge_verts,
            "{name} level {level}: edge-vertex lists differ"
        );
        assert_eq!(
            t.face_is_hole, o.face_is_hole,
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
    let mut names: Vec<String> = std::fs::read_dir(common::shapes_dir())
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| {
            (n.starts_with("catmark_") || n.starts_with("bilinear_")) && n.ends_with(".obj")
        })
        .map(|n| n.trim_end_matches(".obj").to_string())
        .collect();
    names.sort();
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
