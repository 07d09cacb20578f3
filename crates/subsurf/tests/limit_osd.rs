//! Limit surface against OpenSubdiv 3.5 (`osd_ref::eval_limit_grid_with`: adaptive
//! refinement, Gregory-basis end caps, single-crease patches, same isolation level).

mod limit_common;

use limit_common::{bbox_diagonal, load_shape, osd_or_skip, shape_names};
use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdPatchOptions};
use subsurf::limit::{LimitPoint, LimitSurface, PatchOptions, PatchTable, PatchType};
use subsurf::patch::{patch_weights, PatchKind};
use subsurf::Topology;

/// Worst deviations from OpenSubdiv, relative to the bounding-box diagonal.
#[derive(Debug, Default)]
struct Deviation {
    samples: usize,
    /// Position, on B-spline and single-crease patches.
    regular: f32,
    /// Position, on Gregory end caps (next to extraordinary features).
    end_cap: f32,
    /// First derivatives, on B-spline and single-crease patches.
    deriv: f32,
    /// First derivatives, on Gregory end caps.
    end_cap_deriv: f32,
    patches: (usize, usize),
}

fn compare(name: &str, level: u32, n: usize) -> Deviation {
    let mesh = load_shape(name);
    let osd_mesh = OsdMesh::from(&mesh);
    let o = OsdPatchOptions {
        isolation_level: level,
        use_single_crease: true,
        use_inf_sharp: false,
        end_cap: EndCap::Gregory,
    };
    let osd =
        osd_ref::eval_limit_grid_with(&osd_mesh, n, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
    let stats = osd_ref::patch_stats(&osd_mesh, &o).unwrap();
    let topo = Topology::new(&mesh).unwrap();
    let table = PatchTable::build(
        &topo,
        &PatchOptions {
            isolation_level: level,
            single_crease: true,
            cap_crease_sharpness: true,
        },
    )
    .unwrap();
    let s = LimitSurface::new(table, &mesh.positions);
    let diag = bbox_diagonal(&mesh.positions);
    let mut dev = Deviation {
        samples: osd.len(),
        patches: (s.table().num_patches(), stats.num_patches),
        ..Default::default()
    };
    for o in &osd {
        let r = osd_like_eval(&s, o.face as usize, o.u, o.v)
            .unwrap_or_else(|| panic!("{name}: no patch at ptex {} ({}, {})", o.face, o.u, o.v));
        let d = (0..3)
            .map(|c| (r.p[c] - o.p[c]).powi(2))
            .sum::<f32>()
            .sqrt()
            / diag;
        let p = s
            .table()
            .patch_map()
            .find(o.face as usize, o.u, o.v)
            .unwrap() as usize;
        let dd = (0..3)
            .map(|c| (r.du[c] - o.du[c]).abs().max((r.dv[c] - o.dv[c]).abs()))
            .fold(0.0, f32::max)
            / diag;
        if s.table().patch_type(p) == PatchType::Gregory {
            dev.end_cap = dev.end_cap.max(d);
            dev.end_cap_deriv = dev.end_cap_deriv.max(dd);
        } else {
            dev.regular = dev.regular.max(d);
            dev.deriv = dev.deriv.max(dd);
        }
    }
    dev
}

/// Evaluates like OpenSubdiv 3.5's CPU `PatchTable::EvaluateBasis`, which ignores the
/// sharpness of single-crease patches and treats their crease edge as a boundary; other
/// patches as [`LimitSurface::eval_raw`].
fn osd_like_eval(s: &LimitSurface, f: usize, u: f32, v: f32) -> Option<LimitPoint> {
    let p = s.table().patch_map().find(f, u, v)? as usize;
    if s.table().patch_type(p) != PatchType::SingleCrease {
        return s.eval_raw(f, u, v);
    }
    let w = patch_weights(PatchKind::Regular, &s.table().params()[p], 0.0f32, u, v);
    let mut r = LimitPoint::default();
    for (k, &cv) in s.table().patch_cvs(p).iter().enumerate() {
        let x = s.points()[cv as usize];
        for c in 0..3 {
            r.p[c] += w.p[k] * x[c];
            r.du[c] += w.du[k] * x[c];
            r.dv[c] += w.dv[k] * x[c];
        }
    }
    // The points are relative to the surface's local origin.
    (0..3).for_each(|c| r.p[c] += s.origin()[c] as f32);
    Some(r)
}

/// Every catmark regression shape (isolation level 4, 11 × 11 or 6 × 6 samples per ptex
/// face, so samples fall inside the small end caps too): the same number of patches as OpenSubdiv,
/// positions within 1e-5 of the diagonal on B-spline and single-crease patches and within
/// 5e-5 on Gregory end caps (next to extraordinary vertices; the largest, 1.3e-5, is at the
/// valence-360 pole, from `f32` weights), first derivatives within 1e-4 (2e-4 on end caps:
/// OpenSubdiv's `f32` end-cap points of the valence-360 pole are off by 1.5e-4 in the
/// derivatives, subsurf's, relative to a point of each stencil row, by 2.5e-7 of
/// OpenSubdiv's double-precision ones; see `limit_normals`). This includes the non-manifold
/// shapes, whose patches come from manifold spans.
#[test]
fn matches_opensubdiv_on_every_catmark_shape() {
    if !osd_or_skip("matches_opensubdiv_on_every_catmark_shape") {
        return;
    }
    let mut failures = Vec::new();
    for name in shape_names() {
        // Fewer samples on the large shapes keep the test fast; 6 and 11 samples per side
        // both put samples inside depth-4 end caps (u = 0.2, 0.1, …).
        let n = if load_shape(&name).num_faces() > 150 {
            6
        } else {
            11
        };
        let d = compare(&name, 4, n);
        eprintln!("{name:28} {d:?}");
        assert!(d.samples > 0, "{name}: OpenSubdiv gave no samples");
        if d.patches.0 != d.patches.1
            || d.regular > 1e-5
            || d.end_cap > 5e-5
            || d.deriv > 1e-4
            || d.end_cap_deriv > 2e-4
        {
            failures.push(format!("{name}: {d:?}"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Other isolation levels select the same patches as OpenSubdiv's adaptive refinement.
#[test]
fn matches_opensubdiv_at_other_isolation_levels() {
    if !osd_or_skip("matches_opensubdiv_at_other_isolation_levels") {
        return;
    }
    for (name, level) in [
        ("catmark_car", 1),
        ("catmark_pyramid_creases2", 2),
        ("catmark_tent_creases0", 3),
        ("catmark_chaikin1", 2),
        ("catmark_gregory_test6", 5),
    ] {
        let d = compare(name, level, 7);
        assert_eq!(d.patches.0, d.patches.1, "{name} level {level}");
        assert!(
            d.regular < 1e-5 && d.end_cap < 5e-5,
            "{name} level {level}: {d:?}"
        );
    }
}

/// Deep isolation (levels 6 to 10, built sparsely): the same patches as OpenSubdiv's
/// adaptive refinement, and the same surface.
#[test]
fn matches_opensubdiv_at_deep_isolation_levels() {
    if !osd_or_skip("matches_opensubdiv_at_deep_isolation_levels") {
        return;
    }
    for name in [
        "catmark_car",
        "catmark_cube",
        "catmark_chaikin0",
        "catmark_gregory_test6",
        "catmark_nonman_quadpole8",
        "catmark_hole_test1",
    ] {
        for level in [6, 8, 10] {
            let d = compare(name, level, 5);
            assert_eq!(d.patches.0, d.patches.1, "{name} level {level}");
            assert!(
                d.regular < 1e-5 && d.end_cap < 5e-5,
                "{name} level {level}: {d:?}"
            );
        }
    }
}

/// Every catmark shape isolated to the maximum level 10 (sparsely; uniform refinement would
/// need up to 10⁶ times the base): OpenSubdiv's patch count, with and without single-crease
/// patches.
#[test]
fn every_catmark_shape_at_isolation_ten_has_opensubdivs_patch_count() {
    if !osd_or_skip("every_catmark_shape_at_isolation_ten_has_opensubdivs_patch_count") {
        return;
    }
    for name in shape_names() {
        let mesh = load_shape(&name);
        let topo = Topology::new(&mesh).unwrap();
        let osd_mesh = OsdMesh::from(&mesh);
        for single_crease in [true, false] {
            let table = PatchTable::build(
                &topo,
                &PatchOptions {
                    isolation_level: 10,
                    single_crease,
                    cap_crease_sharpness: true,
                },
            )
            .unwrap_or_else(|e| panic!("{name}: {e}"));
            let o = OsdPatchOptions {
                isolation_level: 10,
                use_single_crease: single_crease,
                use_inf_sharp: false,
                end_cap: EndCap::Gregory,
            };
            let osd = osd_ref::patch_table_only(&osd_mesh, &o).unwrap();
            assert_eq!(
                table.num_patches(),
                osd.num_patches,
                "{name} single-crease {single_crease}"
            );
        }
    }
}
