//! A refined level written as OBJ keeps the tags that remain (issue 12): on every catmark
//! regression shape with creases, corners, holes or a boundary, under both crease methods and
//! with boundary interpolation `None` too, level 1 written with its tags, read back and refined
//! twice is level 3 of the input — the same faces and holes, vertex for vertex (up to the
//! numbering of edge points, which follows edge order), within 1e-6 of the bounding-box
//! diagonal. OpenSubdiv refining the written file agrees with its own level 3, so the sharpness
//! written is OpenSubdiv's child sharpness. The full, lean and one-shot paths write the same tags.

use std::collections::HashMap;
use std::path::PathBuf;
use subsurf::refine::{level_tags, refine_once_mesh};
use subsurf::{
    BoundaryInterpolation, Crease, CreaseMethod, Mesh, RefineOptions, Refiner, Topology,
};

/// One refined level: faces (sizes, corners), hole flags, positions.
struct Level {
    counts: Vec<u32>,
    verts: Vec<u32>,
    holes: Vec<bool>,
    positions: Vec<[f32; 3]>,
}

impl Level {
    fn ours(t: &Topology, positions: Vec<[f32; 3]>) -> Level {
        Level {
            counts: (0..t.num_faces()).map(|f| t.face_size(f) as u32).collect(),
            verts: t.arrays().face_verts.to_vec(),
            holes: t.arrays().face_is_hole.to_vec(),
            positions,
        }
    }
}

/// Whether `a` and `b` are the same level up to a renumbering of vertices: face by face the
/// same sizes and hole flags, corners that map one to one, and mapped positions within `tol`
/// of the bounding-box diagonal. Returns what differs.
fn same_level(a: &Level, b: &Level, tol: f32) -> Result<f32, String> {
    if a.counts != b.counts {
        return Err("face sizes differ".into());
    }
    if a.holes != b.holes {
        return Err("holes differ".into());
    }
    let (mut ab, mut ba) = (HashMap::new(), HashMap::new());
    for (c, (&va, &vb)) in a.verts.iter().zip(&b.verts).enumerate() {
        let x = *ab.entry(va).or_insert(vb);
        let y = *ba.entry(vb).or_insert(va);
        if x != vb || y != va {
            return Err(format!("corner {c} joins {va} to {vb}"));
        }
    }
    let diag = subsurf::mesh::bbox_diagonal(&b.positions);
    let worst = ab
        .iter()
        .map(|(&va, &vb)| {
            let (p, q) = (a.positions[va as usize], b.positions[vb as usize]);
            (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f32>().sqrt()
        })
        .fold(0.0f32, f32::max);
    if worst > tol * diag {
        return Err(format!(
            "positions differ by {:e} of the diagonal",
            worst / diag
        ));
    }
    Ok(worst / diag)
}

/// The tagged level-1 mesh, the same from the full refiner, the lean one and `refine_once_mesh`.
fn level1(name: &str, mesh: &Mesh) -> Mesh {
    let base = Topology::new(mesh).unwrap();
    let full = Refiner::new(base.clone(), 1).unwrap();
    let lean = Refiner::with_options(base.clone(), 1, RefineOptions::lean()).unwrap();
    let p = full.refine_positions(&mesh.positions);
    let m = full.to_tagged_mesh(1, p.clone()).unwrap();
    assert_eq!(
        lean.to_tagged_mesh(1, p.clone()).unwrap(),
        m,
        "{name}: lean"
    );
    for options in [RefineOptions::lean(), RefineOptions::default()] {
        let once = refine_once_mesh(base.clone(), 1, &mesh.positions, options).unwrap();
        assert_eq!(once, m, "{name}: refine_once_mesh {options:?}");
    }
    m
}

/// Writes `mesh` as OBJ and reads it back.
fn through_obj(mesh: &Mesh) -> Mesh {
    let mut text = Vec::new();
    subsurf::io::obj::write(mesh, &mut text).unwrap();
    subsurf::io::obj::read(std::str::from_utf8(&text).unwrap()).unwrap()
}

fn shapes() -> Vec<(String, Mesh)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let paths = subsurf::shapes::regression_shapes(&dir, &["catmark_"]).unwrap();
    paths
        .iter()
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            (name, subsurf::io::read_path(p).unwrap())
        })
        .chain([("grid_sharp_sides".to_string(), grid_with_sharp_sides())])
        .collect()
}

/// A wavy 5×4 grid whose boundary edges along two sides are tagged infinitely sharp, with a
/// semi-sharp interior crease and vertex. Under boundary interpolation `None` the faces at
/// the corner where the tagged sides meet stay faces while the other boundary faces become
/// holes, so the refined level must keep its boundary tags for its faces to stay faces.
fn grid_with_sharp_sides() -> Mesh {
    let mut m = subsurf::shapes::grid(5, 4);
    for p in m.positions.as_f32_mut() {
        p[2] = 0.3 * (p[0] * 1.3).sin() * (p[1] * 0.9).cos();
    }
    let t = Topology::new(&m).unwrap();
    for e in t.boundary_edges() {
        let [a, b] = t.edge_vertices(e as usize);
        let (pa, pb) = (m.positions[a as usize], m.positions[b as usize]);
        if (pa[1] == 0.0 && pb[1] == 0.0) || (pa[0] == 0.0 && pb[0] == 0.0) {
            m.creases.push(Crease {
                v0: a,
                v1: b,
                sharpness: 10.0,
            });
        }
    }
    // Interior vertices 8 = (2, 1) and 14 = (2, 2); 15 = (3, 2).
    m.creases.push(Crease {
        v0: 8,
        v1: 14,
        sharpness: 2.5,
    });
    m.creases.push(Crease {
        v0: 14,
        v1: 15,
        sharpness: 1.2,
    });
    m.corners.push(subsurf::Corner {
        vertex: 15,
        sharpness: 1.7,
    });
    m
}

/// The cases: each shape's own options and, with the other crease method, boundary `None`
/// where it has a boundary.
fn cases(name: &str, mesh: &Mesh) -> Vec<(String, Mesh)> {
    let t = Topology::new(mesh).unwrap();
    let tagged = !mesh.creases.is_empty() || !mesh.corners.is_empty() || !mesh.holes.is_empty();
    let boundary = !t.boundary_edges().is_empty();
    if !(tagged || boundary) {
        return vec![];
    }
    let mut out = Vec::new();
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        let mut boundaries = vec![mesh.options.boundary];
        if boundary && mesh.options.boundary != BoundaryInterpolation::None {
            boundaries.push(BoundaryInterpolation::None);
        }
        for b in boundaries {
            let mut m = mesh.clone();
            m.options.crease_method = method;
            m.options.boundary = b;
            out.push((format!("{name} {method:?} {b:?}"), m));
        }
    }
    out
}

/// Whether the written level holds its own edges: a level with two edges joining the same two
/// vertices (the refined non-manifold quad poles) comes back from its face lists with one.
fn edges_survive(mesh: &Mesh, back: &Mesh) -> bool {
    let refined = Refiner::new(Topology::new(mesh).unwrap(), 1).unwrap();
    refined.last().num_edges() == Topology::new(back).unwrap().num_edges()
}

/// Level 3 of `mesh` by subsurf, and level 2 of the level 1 written and read back.
fn ours_both_ways(mesh: &Mesh, back: &Mesh) -> (Level, Level) {
    let direct = Refiner::new(Topology::new(mesh).unwrap(), 3).unwrap();
    let p3 = direct.refine_positions(&mesh.positions);
    let again = Refiner::new(Topology::new(back).unwrap(), 2).unwrap();
    let p2 = again.refine_positions(&back.positions);
    (
        Level::ours(again.last(), p2),
        Level::ours(direct.last(), p3),
    )
}

#[test]
fn refined_level_written_with_tags_refines_on_as_the_level() {
    let (mut checked, mut with_tags, mut worst) = (0, 0, (0.0f32, String::new()));
    let (mut failures, mut skipped) = (Vec::new(), Vec::new());
    for (name, shape) in shapes() {
        for (name, mesh) in cases(&name, &shape) {
            let l1 = level1(&name, &mesh);
            let back = through_obj(&l1);
            if !edges_survive(&mesh, &back) {
                skipped.push(name);
                continue;
            }
            assert_eq!(back.creases, l1.creases, "{name}: creases read back");
            assert_eq!(back.corners, l1.corners, "{name}: corners read back");
            assert_eq!(back.holes, l1.holes, "{name}: holes read back");
            assert_eq!(back.options, l1.options, "{name}: options read back");
            with_tags += usize::from(!l1.creases.is_empty() || !l1.corners.is_empty());
            let (again, direct) = ours_both_ways(&mesh, &back);
            match same_level(&again, &direct, 1e-6) {
                Ok(d) if d > worst.0 => worst = (d, name),
                Ok(_) => {}
                Err(e) => failures.push(format!("{name}: {e}")),
            }
            checked += 1;
        }
    }
    println!(
        "{checked} cases, {with_tags} with tags at level 1, worst {:e} of the diagonal ({})",
        worst.0, worst.1
    );
    println!("skipped (edges joining the same two vertices): {skipped:?}");
    assert!(skipped.len() <= 12, "skipped: {skipped:?}");
    assert!(
        failures.is_empty(),
        "L2 of the written L1 vs L3:\n{}",
        failures.join("\n")
    );
    assert!(checked >= 60, "only {checked} cases");
    assert!(
        with_tags >= 30,
        "only {with_tags} cases keep tags at level 1"
    );
}

/// Without the remaining tags the check above fails: the test can tell.
#[test]
fn dropping_the_tags_changes_the_surface() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
    let mesh = subsurf::io::read_path(dir.join("catmark_cube_creases1.obj")).unwrap();
    let mut l1 = level1("catmark_cube_creases1", &mesh);
    assert!(!l1.creases.is_empty());
    let (again, direct) = ours_both_ways(&mesh, &l1);
    assert!(same_level(&again, &direct, 1e-6).is_ok());
    l1.creases.clear();
    let (again, direct) = ours_both_ways(&mesh, &l1);
    let err = same_level(&again, &direct, 1e-6).unwrap_err();
    assert!(err.contains("positions"), "{err}");
}

/// The sharpness written decays as OpenSubdiv's: OpenSubdiv refining the written level 1 twice
/// gives its own level 3 of the input.
#[test]
fn opensubdiv_refines_the_written_level_as_its_own() {
    if !osd_ref::available_or_skip("opensubdiv_refines_the_written_level_as_its_own") {
        return;
    }
    let osd_level = |m: &Mesh, level: usize| {
        let l = osd_ref::refine_uniform(&osd_ref::OsdMesh::from(m), level)
            .unwrap()
            .pop()
            .unwrap();
        Level {
            counts: l.face_counts,
            verts: l.face_verts,
            holes: l.face_is_hole,
            positions: l.positions,
        }
    };
    let (mut checked, mut worst) = (0, (0.0f32, String::new()));
    let mut failures = Vec::new();
    for (name, shape) in shapes() {
        for (name, mesh) in cases(&name, &shape) {
            let back = through_obj(&level1(&name, &mesh));
            if !edges_survive(&mesh, &back) {
                continue;
            }
            match same_level(&osd_level(&back, 2), &osd_level(&mesh, 3), 1e-6) {
                Ok(d) if d > worst.0 => worst = (d, name),
                Ok(_) => {}
                Err(e) => failures.push(format!("{name}: {e}")),
            }
            checked += 1;
        }
    }
    println!(
        "{checked} cases, worst {:e} of the diagonal ({})",
        worst.0, worst.1
    );
    assert!(
        failures.is_empty(),
        "OpenSubdiv L2 of the written L1 vs its L3:\n{}",
        failures.join("\n")
    );
    assert!(checked >= 60, "only {checked} cases");
}

/// A level that is not the last one of a lean refiner holds its sharpness; the last one of a
/// lean refiner does not, and `level_tags` says so instead of writing none.
#[test]
fn level_tags_refuses_a_lean_level() {
    let mut mesh = subsurf::shapes::cube();
    mesh.creases.push(subsurf::Crease {
        v0: 0,
        v1: 1,
        sharpness: 2.5,
    });
    let lean =
        Refiner::with_options(Topology::new(&mesh).unwrap(), 2, RefineOptions::lean()).unwrap();
    assert!(level_tags(lean.last()).is_err());
    let l1 = level_tags(&lean.levels[1]).unwrap();
    assert_eq!(l1.creases.len(), 2);
    assert!(l1.creases.iter().all(|c| c.sharpness == 1.5));
    let m = lean.to_tagged_mesh(2, vec![[0.0; 3]; lean.last().num_vertices()]);
    let m = m.unwrap();
    assert_eq!(m.creases.len(), 4);
    assert!(m.creases.iter().all(|c| c.sharpness == 0.5));
    assert!(lean.to_tagged_mesh(2, vec![]).is_err());
    assert!(lean.to_tagged_mesh(3, vec![]).is_err());
}
