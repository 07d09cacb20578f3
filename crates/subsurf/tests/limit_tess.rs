//! Tessellation (watertight by construction, checked exactly) and derivatives.

mod limit_common;

use std::collections::HashMap;

use limit_common::{bbox_diagonal, load_shape};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, Tessellation};
use subsurf::Topology;

fn surface(name: &str) -> (subsurf::Mesh, LimitSurface) {
    let mesh = load_shape(name);
    let t = Topology::new(&mesh).unwrap();
    let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
    let s = LimitSurface::new(table, &mesh.positions);
    (mesh, s)
}

/// Undirected edge → number of triangles using it.
fn edge_uses(t: &Tessellation) -> HashMap<(u32, u32), usize> {
    let mut m = HashMap::new();
    for tri in t.triangles() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *m.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    m
}

fn check_finite(t: &Tessellation) {
    for (p, n) in t.positions.iter().zip(&t.normals) {
        assert!(p.iter().all(|x| x.is_finite()), "{p:?}");
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        assert!((l - 1.0).abs() < 1e-4, "normal {n:?}");
    }
}

/// On closed manifold meshes every tessellation edge is used by exactly two triangles: no
/// crack and no T-junction anywhere, including the seams between ptex faces of n-gons and
/// their quad neighbours — an exact, combinatorial check that shared samples are shared.
#[test]
fn closed_shapes_tessellate_watertight() {
    for name in [
        "catmark_cube",
        "catmark_pyramid",
        "catmark_torus",
        "catmark_smoothtris0",
        "catmark_cube_creases1",
        "catmark_gregory_test8",
    ] {
        let (_, s) = surface(name);
        for n in [2, 5, 8] {
            let t = s.tessellate(n).unwrap();
            check_finite(&t);
            let uses = edge_uses(&t);
            let bad: Vec<_> = uses.iter().filter(|(_, &c)| c != 2).collect();
            assert!(bad.is_empty(), "{name} N={n}: {} open edges", bad.len());
            // Euler characteristic of a closed surface is preserved: V − E + F = 2 − 2g.
            let base = &s.table().base();
            let chi0 =
                base.num_vertices() as i64 - base.num_edges() as i64 + base.num_faces() as i64;
            let chi = t.positions.len() as i64 - uses.len() as i64 + t.triangles().len() as i64;
            assert_eq!(chi, chi0, "{name} N={n}");
        }
    }
}

/// With boundaries and holes, the open edges are exactly the samples along boundary and
/// hole edges: `N − 1` segments per base boundary edge.
#[test]
fn open_shapes_have_only_boundary_edges_open() {
    for name in ["catmark_tent", "catmark_hole_test1", "catmark_edgecorner"] {
        let (mesh, s) = surface(name);
        let t = Topology::new(&mesh).unwrap();
        let open_base = (0..t.num_edges())
            .filter(|&e| {
                let live = t
                    .edge_faces(e)
                    .iter()
                    .filter(|&&f| !t.face_is_hole(f as usize))
                    .count();
                live == 1
            })
            .count();
        let n = 7;
        let tess = s.tessellate(n).unwrap();
        check_finite(&tess);
        let uses = edge_uses(&tess);
        assert!(uses.values().all(|&c| c == 1 || c == 2), "{name}");
        let open = uses.values().filter(|&&c| c == 1).count();
        assert_eq!(open, open_base * (n - 1), "{name}");
    }
}

/// Even sample counts are raised to odd ones on meshes with non-quad faces so that half
/// edges meet full edges.
#[test]
fn even_counts_become_odd_with_ngons() {
    let (_, s) = surface("catmark_pyramid");
    assert_eq!(s.tessellate(6).unwrap().samples_per_side, 7);
    let (_, s) = surface("catmark_cube");
    assert_eq!(s.tessellate(6).unwrap().samples_per_side, 6);
}

/// First derivatives agree with central differences of the positions (step 1e-3).
#[test]
fn derivatives_match_finite_differences() {
    for name in [
        "catmark_pawn",
        "catmark_pyramid_creases0",
        "catmark_tent_creases0",
    ] {
        let (mesh, s) = surface(name);
        let diag = bbox_diagonal(&mesh.positions);
        let h = 1e-3f32;
        let mut worst = 0.0f32;
        let mut count = 0;
        for ptex in 0..s.table().num_ptex_faces() {
            for (u, v) in [(0.31f32, 0.42f32), (0.77, 0.13), (0.55, 0.81)] {
                let Some(r) = s.eval(ptex, u, v) else {
                    continue;
                };
                let p = |a: f32, b: f32| s.eval(ptex, a, b).unwrap().p;
                let (pu0, pu1) = (p(u - h, v), p(u + h, v));
                let (pv0, pv1) = (p(u, v - h), p(u, v + h));
                for c in 0..3 {
                    let fu = (pu1[c] - pu0[c]) / (2.0 * h);
                    let fv = (pv1[c] - pv0[c]) / (2.0 * h);
                    worst = worst.max((fu - r.du[c]).abs() / diag);
                    worst = worst.max((fv - r.dv[c]).abs() / diag);
                }
                count += 1;
            }
        }
        assert!(count > 0);
        assert!(worst < 2e-3, "{name}: worst {worst:e} of the diagonal");
    }
}
