//! subsurf's quad tessellation pattern against OpenSubdiv 3.5's `Bfr::Tessellation`: the
//! same `(u, v)` samples (boundary in the same order, interior as a set) and the same number
//! of triangles, for the outer and inner rates of every ptex face of every shape under
//! uniform and random per-edge rates, and for a sweep of rate combinations.

mod common;

use std::collections::BTreeSet;

use osd_ref::{bfr_tessellation, BfrParam};
use subsurf::limit::{PatchOptions, PatchTable};
use subsurf::tess::{plan, EdgeRates, QuadPattern};
use subsurf::Topology;

/// An interior sample's place on the grid of half steps of the inner rates, checked to lie
/// within 1e-5 of it (Bfr accumulates `u += du`, so its values differ in the last bits).
fn key(c: [f32; 2], inner: [u32; 2]) -> (i64, i64) {
    let k = [0, 1].map(|i| (c[i] * 2.0 * inner[i] as f32).round());
    for i in 0..2 {
        assert!(
            (k[i] / (2.0 * inner[i] as f32) - c[i]).abs() < 1e-5,
            "{c:?} off the grid"
        );
    }
    (k[0] as i64, k[1] as i64)
}

/// Compares one pattern; `explicit_inner` passes the inner rates to Bfr (6 rates) rather
/// than letting it infer them from the outer ones (4 rates).
fn check(outer: [u32; 4], inner: [u32; 2], explicit_inner: bool) {
    let mut rates: Vec<i32> = outer.iter().map(|&r| r as i32).collect();
    let ours = if explicit_inner {
        rates.extend(inner.map(|r| r as i32));
        QuadPattern::new(outer, Some(inner))
    } else {
        QuadPattern::new(outer, None)
    };
    let bfr = bfr_tessellation(BfrParam::Quad, 4, &rates, 3, false).unwrap();
    let what = format!("outer {outer:?} inner {:?}", ours.inner);
    assert_eq!(ours.num_boundary, bfr.num_boundary, "{what}");
    assert_eq!(ours.coords.len(), bfr.coords.len(), "{what}: samples");
    assert_eq!(ours.triangles.len(), bfr.facets.len(), "{what}: facets");
    for (a, b) in ours.coords.iter().zip(&bfr.coords).take(bfr.num_boundary) {
        assert!(
            (a[0] - b[0]).abs() < 1e-5 && (a[1] - b[1]).abs() < 1e-5,
            "{what}: boundary sample {a:?} vs {b:?}"
        );
    }
    let set = |c: &[[f32; 2]]| {
        c.iter()
            .map(|&c| key(c, ours.inner))
            .collect::<BTreeSet<_>>()
    };
    assert_eq!(
        set(&ours.coords[ours.num_boundary..]),
        set(&bfr.coords[bfr.num_boundary..]),
        "{what}: interior samples"
    );
}

#[test]
fn rate_sweep_matches_bfr() {
    if !common::osd_or_skip("rate_sweep_matches_bfr") {
        return;
    }
    let rates = [1u32, 2, 3, 4, 5, 8, 13, 64];
    for &a in &rates {
        for &b in &rates {
            for &c in &[1u32, 3, 8] {
                for &d in &[1u32, 2, 64] {
                    let outer = [a, b, c, d];
                    check(outer, subsurf::tess::default_inner(outer), false);
                    for inner in [[1, 1], [1, b], [a, 1], [2, 2], [3, 7], [a, b]] {
                        check(outer, inner, true);
                    }
                }
            }
        }
    }
}

/// Every ptex face of every shape (n-gons through their sub-faces), with the rates the mesh
/// gives it under uniform rates and under random per-edge rates.
#[test]
fn every_shapes_ptex_patterns_match_bfr() {
    if !common::osd_or_skip("every_shapes_ptex_patterns_match_bfr") {
        return;
    }
    let mut seen = BTreeSet::new();
    let mut state = 12345u64;
    for name in common::shape_names(&["catmark_"]) {
        let mesh = common::load_shape(&name);
        let t = Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let mut random = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            1 + ((state >> 33) % 24) as u32
        };
        let edges: Vec<u32> = (0..t.num_edges()).map(|_| random()).collect();
        for rates in [
            EdgeRates::uniform(&t, 4),
            EdgeRates::uniform(&t, 7),
            EdgeRates {
                edges,
                faces: Vec::new(),
            },
        ] {
            let p = plan(&table, &rates, "test").unwrap();
            for (outer, inner) in p.ptex_rates.iter().flatten() {
                if seen.insert((*outer, *inner)) {
                    check(*outer, *inner, true);
                }
            }
        }
    }
    assert!(seen.len() > 100, "only {} distinct patterns", seen.len());
}
