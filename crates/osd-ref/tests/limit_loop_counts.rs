//! subsurf's feature-adaptive isolation for the Loop scheme against OpenSubdiv 3.5's
//! adaptive Loop patch table: for every `loop_*` regression shape at isolation levels 1–4
//! (and 5–10), and for creased Catmull-Clark shapes fan-triangulated with their tags at
//! levels 1–10, the same number of regular box-spline patches and the same number of
//! Gregory-triangle end caps as `Far::PatchTableFactory` builds with its defaults.

#[macro_use]
mod common;

use osd_ref::{patch_stats, EndCap, OsdMesh, PatchOptions};
use subsurf::limit::loop_patch_counts;
use subsurf::Topology;

/// The mismatches of `loop_patch_counts` against OpenSubdiv on `mesh` at `levels`, and the
/// number of OpenSubdiv's end caps.
fn mismatches(
    name: &str,
    mesh: &subsurf::Mesh,
    levels: std::ops::RangeInclusive<u32>,
) -> (Vec<String>, usize) {
    let topo = Topology::new(mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut osd = OsdMesh::from(mesh);
    osd.uvs = None;
    let (mut failures, mut end_caps) = (Vec::new(), 0);
    for level in levels {
        let o = PatchOptions {
            isolation_level: level,
            end_cap: EndCap::Gregory,
            ..Default::default()
        };
        let s = patch_stats(&osd, &o).unwrap_or_else(|e| panic!("{name}: OpenSubdiv: {e}"));
        let theirs = (s.num_regular_patches, s.num_patches - s.num_regular_patches);
        let ours = loop_patch_counts(&topo, level).unwrap_or_else(|e| panic!("{name}: {e}"));
        let ours = (ours.regular, ours.irregular);
        end_caps += theirs.1;
        if ours != theirs {
            failures.push(format!(
                "{name} isolation {level}: subsurf {} regular + {} end caps, \
                 OpenSubdiv {} + {}",
                ours.0, ours.1, theirs.0, theirs.1
            ));
        }
    }
    (failures, end_caps)
}

/// Every `loop_*` shape at `levels` matches OpenSubdiv, with more than `min_end_caps` of
/// OpenSubdiv's end caps among them (both kinds are really compared).
fn every_loop_shape(levels: std::ops::RangeInclusive<u32>, min_end_caps: usize) {
    let names = common::shape_names(&["loop_"]);
    assert!(names.len() >= 25, "{names:?}");
    let (mut failures, mut end_caps) = (Vec::new(), 0);
    for name in &names {
        let (f, e) = mismatches(name, &common::load_shape(name), levels.clone());
        failures.extend(f);
        end_caps += e;
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(end_caps > min_end_caps, "only {end_caps} end caps");
}

/// The sparse isolation reaches level 10 on every Loop shape with OpenSubdiv's counts.
#[test]
fn patch_counts_match_opensubdiv_at_isolation_5_to_10() {
    require_osd!();
    every_loop_shape(5..=10, 10_000);
}

/// Creases, corners, holes and boundaries of Catmull-Clark shapes, made Loop meshes by
/// fanning their faces with their tags, at every isolation level.
#[test]
fn patch_counts_match_opensubdiv_on_triangulated_creased_catmark_shapes() {
    require_osd!();
    let names = [
        "catmark_cube_creases0",
        "catmark_cube_creases1",
        "catmark_cube_corner3",
        "catmark_chaikin1",
        "catmark_inf_crease1",
        "catmark_dart_edgecorner",
        "catmark_hole_test1",
        "catmark_tent_creases0",
        "catmark_torus_creases0",
        "catmark_pyramid_creases2",
    ];
    let (mut failures, mut end_caps) = (Vec::new(), 0);
    for name in names {
        let mesh = osd_ref::fan_triangulated_loop(&common::load_shape(name));
        let tagged = !mesh.creases.is_empty() || !mesh.corners.is_empty() || !mesh.holes.is_empty();
        assert!(tagged, "{name} has no tags");
        let (f, e) = mismatches(name, &mesh, 1..=10);
        failures.extend(f);
        end_caps += e;
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(end_caps > 1000, "only {end_caps} end caps");
}

#[test]
fn patch_counts_match_opensubdiv_at_isolation_1_to_4() {
    require_osd!();
    every_loop_shape(1..=4, 1000);
}
