//! subsurf's feature-adaptive isolation for the Loop scheme against OpenSubdiv 3.5's
//! adaptive Loop patch table: for every `loop_*` regression shape at isolation levels 1–4,
//! the same number of regular box-spline patches and the same number of Gregory-triangle end
//! caps as `Far::PatchTableFactory` builds with its defaults.

#[macro_use]
mod common;

use osd_ref::{patch_stats, EndCap, OsdMesh, PatchOptions};
use subsurf::limit::loop_patch_counts;
use subsurf::Topology;

#[test]
fn patch_counts_match_opensubdiv_at_isolation_1_to_4() {
    require_osd!();
    let names = common::shape_names(&["loop_"]);
    assert!(names.len() >= 25, "{names:?}");
    let mut failures = Vec::new();
    let mut end_caps = 0;
    for name in &names {
        let mesh = common::load_shape(name);
        let topo = Topology::new(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut osd = OsdMesh::from(&mesh);
        osd.uvs = None;
        for level in 1..=4u32 {
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
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // Both kinds are really compared: OpenSubdiv builds end caps on these shapes.
    assert!(end_caps > 1000, "only {end_caps} end caps");
}
