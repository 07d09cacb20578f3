//! The Loop limit surface on regular patches against OpenSubdiv 3.5's adaptive Loop patch
//! table (`Far::PatchTable` + `PatchMap`, evaluated on a triangular grid of every face):
//! every `loop_*` regression shape at isolation 2 (3 in release builds), positions within
//! 1e-5 of the bounding-box diagonal and normals within 1e-3 rad wherever subsurf has a
//! regular box-spline patch. Irregular patches (end caps) are not built yet and are skipped;
//! the test checks that the regular ones cover most samples.
//!
//! Known difference, asserted to still differ: `loop_val2_interior` (valence-2 vertices
//! and non-manifold edges).

#[macro_use]
mod common;

use osd_ref::{eval_limit_grid_with, EndCap, OsdMesh, PatchOptions};
use subsurf::limit::loop_eval::LoopLimit;
use subsurf::Topology;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let n = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let c = cross(a, b);
    n(c).atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

const KNOWN_DIFFERENCES: [&str; 1] = ["loop_val2_interior"];

#[test]
fn regular_patches_match_opensubdiv_on_every_loop_shape() {
    require_osd!();
    let level = if cfg!(debug_assertions) { 2 } else { 3 };
    let mut total = 0usize;
    let mut compared = 0usize;
    let mut failures = Vec::new();
    for name in common::shape_names(&["loop_"]) {
        let mesh = common::load_shape(&name);
        let topo = Topology::new(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
        let ours =
            LoopLimit::new(&topo, &mesh.positions, level).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut osd = OsdMesh::from(&mesh);
        osd.uvs = None;
        let o = PatchOptions {
            isolation_level: level,
            end_cap: EndCap::Gregory,
            ..Default::default()
        };
        let samples = eval_limit_grid_with(&osd, 6, &o).unwrap();
        let diag = subsurf::mesh::bbox_diagonal(&mesh.positions).max(1e-30) as f64;
        let (mut worst_p, mut worst_n) = (0.0f64, 0.0f64);
        for s in &samples {
            total += 1;
            let Some(e) = ours.eval(s.face as usize, s.u as f64, s.v as f64) else {
                continue;
            };
            compared += 1;
            let d = (0..3)
                .map(|k| (e.p[k] - s.p[k] as f64).powi(2))
                .sum::<f64>()
                .sqrt();
            worst_p = worst_p.max(d / diag);
            let theirs = cross(s.du.map(f64::from), s.dv.map(f64::from));
            let mine = cross(e.du, e.dv);
            let n = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            if n(theirs) > 1e-6 * diag * diag && n(mine) > 1e-6 * diag * diag {
                worst_n = worst_n.max(angle(mine, theirs));
            }
        }
        let differs = worst_p > 1e-5 || worst_n > 1e-3;
        if KNOWN_DIFFERENCES.contains(&name.as_str()) {
            assert!(differs, "{name} now matches");
            continue;
        }
        if differs {
            failures.push(format!(
                "{name}: position {worst_p:e}, normal {worst_n:e} rad"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        compared * 2 > total,
        "only {compared} of {total} samples on regular patches"
    );
}
