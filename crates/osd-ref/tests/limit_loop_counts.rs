//! subsurf's feature-adaptive isolation for the Loop scheme against OpenSubdiv 3.5's
//! adaptive Loop patch table: for every `loop_*` regression shape at isolation levels 1–4,
//! the same number of patches (regular box-spline patches plus Gregory-triangle end caps)
//! as `Far::PatchTableFactory` builds with its defaults.
//!
//! Known differences, excluded below and asserted to still differ (so the exclusion is
//! noticed once they are fixed): `loop_val2_interior` (an interior vertex of valence 2) and
//! `loop_nonman_edges` at isolation 3 and 4, where subsurf isolates more faces than
//! OpenSubdiv.

#[macro_use]
mod common;

use osd_ref::{patch_stats, EndCap, OsdMesh, PatchOptions};
use subsurf::limit::loop_patches::loop_patch_counts;
use subsurf::Topology;

const KNOWN_DIFFERENCES: [(&str, u32); 4] = [
    ("loop_val2_interior", 3),
    ("loop_val2_interior", 4),
    ("loop_nonman_edges", 3),
    ("loop_nonman_edges", 4),
];

#[test]
fn patch_counts_match_opensubdiv_at_isolation_1_to_4() {
    require_osd!();
    let names = common::shape_names(&["loop_"]);
    assert!(names.len() >= 25, "{names:?}");
    let mut failures = Vec::new();
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
            let theirs = patch_stats(&osd, &o)
                .unwrap_or_else(|e| panic!("{name}: OpenSubdiv: {e}"))
                .num_patches;
            let ours = loop_patch_counts(&topo, level).unwrap_or_else(|e| panic!("{name}: {e}"));
            let known = KNOWN_DIFFERENCES.contains(&(name.as_str(), level));
            if known {
                assert_ne!(ours.total(), theirs, "{name} isolation {level} now matches");
                continue;
            }
            if ours.total() != theirs {
                failures.push(format!(
                    "{name} isolation {level}: subsurf {} ({} regular), OpenSubdiv {theirs}",
                    ours.total(),
                    ours.regular
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
