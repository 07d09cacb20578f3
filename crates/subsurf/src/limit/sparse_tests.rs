//! The sparse construction against uniform refinement, its cost per level, and its
//! exactness check.

use super::features::FeatureMask;
use super::sparse::{build, Selection};
use super::table::{PatchOptions, PatchTable};
use crate::error::{Error, MeshError};
use crate::options::CreaseMethod;
use crate::topology::Topology;
use crate::util::budget::Budget;
use crate::Mesh;

/// The levels alone, within no memory limit.
fn build_levels(
    t: &Topology,
    max_level: usize,
    mask: &FeatureMask,
    selection: Selection,
) -> crate::error::Result<super::sparse::Hierarchy> {
    let mut budget = Budget::with_limit(u64::MAX);
    build(t, max_level, mask, selection, &mut budget, &|_, _, _, _| {
        Ok(())
    })
    .map(|(h, _)| h)
}

fn shapes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

fn shape(name: &str) -> Mesh {
    let p = shapes_dir().join(format!("{name}.obj"));
    crate::io::obj::read_file(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn catmark_shapes() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(shapes_dir())
        .unwrap()
        .filter_map(|e| {
            let n = e.ok()?.file_name().into_string().ok()?;
            let stem = n.strip_suffix(".obj")?;
            stem.starts_with("catmark_").then(|| stem.to_string())
        })
        .collect();
    names.sort();
    assert!(names.len() >= 60, "regression shapes missing");
    names
}

fn diagonal(p: &[[f32; 3]]) -> f32 {
    crate::mesh::bbox_diagonal(p)
}

/// Asserts that two tables hold the same patches, with control points at the same
/// positions (within `1e-6` of the bounding-box diagonal).
fn assert_same_patches(what: &str, mesh: &Mesh, a: &PatchTable, b: &PatchTable) {
    assert_eq!(a.kinds, b.kinds, "{what}: patch types");
    assert_eq!(a.params, b.params, "{what}: patch parameters");
    assert_eq!(a.sharpness, b.sharpness, "{what}: sharpness");
    assert_eq!(a.cv_offsets, b.cv_offsets, "{what}: control point counts");
    assert_eq!(a.ptex_offsets, b.ptex_offsets, "{what}: ptex faces");
    assert_eq!(
        a.patch_map.roots, b.patch_map.roots,
        "{what}: patch map roots"
    );
    assert_eq!(
        a.patch_map.nodes, b.patch_map.nodes,
        "{what}: patch map nodes"
    );
    let (pa, pb) = (a.points(&mesh.positions), b.points(&mesh.positions));
    let tol = 1e-6 * diagonal(&mesh.positions).max(1e-30);
    for (i, (&x, &y)) in a.cvs.iter().zip(&b.cvs).enumerate() {
        let (p, q) = (pa[x as usize], pb[y as usize]);
        let d = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f32>().sqrt();
        assert!(d <= tol, "{what}: control point {i}: {p:?} vs {q:?}");
    }
}

#[test]
fn sparse_and_uniform_tables_agree_on_every_catmark_shape() {
    for name in catmark_shapes() {
        let mesh = shape(&name);
        let t = Topology::new(&mesh).unwrap();
        for level in 1..=4 {
            for single_crease in [true, false] {
                let o = PatchOptions {
                    isolation_level: level,
                    single_crease,
                    cap_crease_sharpness: level % 2 == 0,
                };
                let what = format!("{name} level {level} single-crease {single_crease}");
                let sparse = PatchTable::build(&t, &o).unwrap_or_else(|e| panic!("{what}: {e}"));
                let uniform = PatchTable::build_with(&t, &o, Selection::Uniform).unwrap();
                assert_same_patches(&what, &mesh, &sparse, &uniform);
            }
        }
    }
}

#[test]
fn chaikin_crease_decay_is_exact_in_sparse_levels() {
    // Chaikin's rule reads the sharpness of every edge around a vertex: the sub-meshes must
    // carry the whole ring of each vertex whose children are used.
    let mut tested = 0;
    for name in catmark_shapes() {
        let mut mesh = shape(&name);
        if mesh.creases.iter().all(|c| c.sharpness >= 10.0) {
            continue;
        }
        mesh.options.crease_method = CreaseMethod::Chaikin;
        let t = Topology::new(&mesh).unwrap();
        let o = PatchOptions {
            isolation_level: 3,
            single_crease: false,
            cap_crease_sharpness: false,
        };
        let sparse = PatchTable::build(&t, &o).unwrap();
        let uniform = PatchTable::build_with(&t, &o, Selection::Uniform).unwrap();
        assert_same_patches(&format!("{name} (Chaikin)"), &mesh, &sparse, &uniform);
        tested += 1;
    }
    assert!(tested >= 5, "only {tested} shapes with semi-sharp creases");
}

/// Vertices of each level of `table`.
fn level_sizes(table: &PatchTable) -> Vec<u32> {
    table
        .level_offsets
        .windows(2)
        .map(|w| w[1] - w[0])
        .collect()
}

#[test]
fn isolating_extraordinary_vertices_costs_the_same_at_every_deep_level() {
    // The cube's eight valence-3 vertices: uniform refinement to level 10 would make 6 · 4^10
    // faces; sparse refinement keeps a fixed neighbourhood of each vertex per level.
    let t = Topology::new(&shape("catmark_cube")).unwrap();
    let o = PatchOptions {
        isolation_level: 10,
        ..Default::default()
    };
    let table = PatchTable::build(&t, &o).unwrap();
    let sizes = level_sizes(&table);
    assert_eq!(sizes.len(), 11, "{sizes:?}");
    for d in 5..=10 {
        assert_eq!(sizes[d], sizes[4], "level {d}: {sizes:?}");
    }
    assert!(sizes[10] < 8 * 400, "{sizes:?}");
    // Three Gregory end caps per corner at level 10 and regular patches elsewhere.
    assert_eq!(table.counts().gregory, 8 * 3);
}

#[test]
fn car_builds_at_isolation_ten() {
    let mesh = shape("catmark_car");
    let t = Topology::new(&mesh).unwrap();
    let o = PatchOptions {
        isolation_level: 10,
        ..Default::default()
    };
    let table = PatchTable::build(&t, &o).unwrap();
    let sizes = level_sizes(&table);
    // Linear growth: each level past the fourth adds about as many vertices as the one before.
    for d in 5..sizes.len() {
        assert!(
            sizes[d] <= sizes[d - 1] + sizes[d - 1] / 8,
            "level {d}: {sizes:?}"
        );
    }
    let surf = super::LimitSurface::new(table, &mesh.positions);
    let tol = 0.01 * diagonal(&mesh.positions);
    // The limit surface stays where the level-4 one is.
    let t4 = PatchTable::build(&t, &PatchOptions::default()).unwrap();
    let s4 = super::LimitSurface::new(t4, &mesh.positions);
    for ptex in (0..surf.table.num_ptex_faces()).step_by(7) {
        let (Some(a), Some(b)) = (surf.eval(ptex, 0.3, 0.6), s4.eval(ptex, 0.3, 0.6)) else {
            continue;
        };
        let d = (0..3)
            .map(|c| (a.p[c] - b.p[c]).powi(2))
            .sum::<f32>()
            .sqrt();
        assert!(d < tol, "ptex {ptex}: {d}");
    }
}

#[test]
fn sub_meshes_without_a_ring_are_detected_as_inexact() {
    // A child of a vertex reads the vertex's whole ring: refining only the selected faces
    // leaves the next level's points at their border wrong, and the construction refuses
    // them instead of emitting them. With the ring it computes them exactly.
    let mask = FeatureMask::new(true);
    for name in ["catmark_cube", "catmark_car", "catmark_chaikin0"] {
        let t = Topology::new(&shape(name)).unwrap();
        match build_levels(&t, 4, &mask, Selection::Rings(0)) {
            Err(Error::Internal(msg)) => assert!(msg.contains("not exact"), "{name}: {msg}"),
            other => panic!(
                "{name}: sub-meshes without a ring accepted ({:?} levels)",
                other.map(|h| h.num_vertices.len())
            ),
        }
        let h = build_levels(&t, 4, &mask, Selection::Rings(1)).unwrap();
        assert_eq!(h.num_vertices.len(), 5, "{name}");
    }
}

/// A torus of `n × n` quads with one quad split into two triangles (two valence-5 vertices
/// and two non-quad faces, the only irregular spot).
fn torus_with_one_irregular_spot(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b) = (
                std::f32::consts::TAU * i as f32 / n as f32,
                std::f32::consts::TAU * j as f32 / n as f32,
            );
            let r = 3.0 + b.cos();
            positions.push([r * a.cos(), r * a.sin(), b.sin()]);
        }
    }
    let id = |i: u32, j: u32| (i % n) * n + (j % n);
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if i == n / 2 && j == n / 2 {
                faces.push(vec![q[0], q[1], q[2]]);
                faces.push(vec![q[0], q[2], q[3]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    Mesh::from_faces(positions, &faces)
}

#[test]
fn a_big_mesh_isolates_one_spot_to_level_ten_in_linear_size() {
    // Uniform refinement to level 10 would make 128² · 4^10 ≈ 1.7 · 10^10 faces.
    let mesh = torus_with_one_irregular_spot(128);
    let t = Topology::new(&mesh).unwrap();
    let mut patches = Vec::new();
    for level in 6..=10 {
        let o = PatchOptions {
            isolation_level: level,
            ..Default::default()
        };
        let table = PatchTable::build(&t, &o).unwrap();
        let sizes = level_sizes(&table);
        assert_eq!(sizes.len(), level as usize + 1);
        // A few hundred vertices per level, the same from level 5 on.
        for d in 6..sizes.len() {
            assert_eq!(sizes[d], sizes[5], "level {d}: {sizes:?}");
        }
        assert!(sizes[1..].iter().all(|&s| s < 400), "{sizes:?}");
        patches.push(table.num_patches());
    }
    // Each level adds the same number of patches around the spot.
    let step = patches[1] - patches[0];
    assert!(step > 0);
    for w in patches.windows(2) {
        assert_eq!(w[1] - w[0], step, "{patches:?}");
    }
}

#[test]
fn a_construction_over_its_memory_budget_is_refused_with_the_estimate() {
    let t = Topology::new(&shape("catmark_car")).unwrap();
    let o = PatchOptions {
        isolation_level: 6,
        ..Default::default()
    };
    let mask = FeatureMask::new(o.single_crease);
    // The running total of the levels' estimates, without a limit.
    let mut free = Budget::with_limit(u64::MAX);
    build::<f32, _>(&t, 6, &mask, Selection::Sparse, &mut free, &|_, _, _, _| {
        Ok(())
    })
    .unwrap();
    let table = PatchTable::build(&t, &o).unwrap();
    // The estimate covers at least the refinement stencils the table keeps, and is of
    // their order.
    let kept = table.stencil_bytes() as u64;
    assert!(
        free.used() >= kept && free.used() < 30 * kept,
        "{} vs {kept}",
        free.used()
    );
    // Exactly that total fits; one byte less is refused before the last level is made.
    let fits = PatchTable::build_within(&t, &o, Selection::Sparse, Budget::with_limit(free.used()));
    assert_eq!(fits.unwrap().num_patches(), table.num_patches());
    for limit in [free.used() - 1, 1 << 20, 0] {
        match PatchTable::build_within(&t, &o, Selection::Sparse, Budget::with_limit(limit)) {
            Err(Error::Mesh(MeshError::TooLarge {
                what, bytes, human, ..
            })) => {
                assert!(bytes > limit && bytes <= free.used(), "{bytes} vs {limit}");
                assert!(what.contains("isolating features"), "{what}");
                assert!(human.contains("iB, ") || human.contains(" B, "), "{human}");
                assert!(human.ends_with(&format!(", {bytes} bytes")), "{human}");
            }
            other => panic!("limit {limit}: {:?}", other.map(|p| p.num_patches())),
        }
    }
}
