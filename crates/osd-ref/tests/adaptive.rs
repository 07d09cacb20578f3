//! Self-tests of the limit-surface side of the shim: patch evaluation against the closed-form
//! bicubic B-spline, sample counts, derivative scaling, and the `Limit` projection.

#[macro_use]
mod common;

use common::{dist, load_shape};
use osd_ref::{
    eval_limit_grid, limit_stencil_positions, patch_counts, patch_stats, patch_table_only, EndCap,
    LimitSample, OsdMesh, PatchOptions,
};
use subsurf::Mesh;

/// Uniform cubic B-spline basis and its derivative at `t` ∈ [0, 1].
fn bspline(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    let b = [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ];
    let d = [
        -s * s / 2.0,
        (3.0 * t * t - 4.0 * t) / 2.0,
        (-3.0 * t * t + 2.0 * t + 1.0) / 2.0,
        t * t / 2.0,
    ];
    (b, d)
}

/// The face `(c, d)` across the directed edge `a → b`: the face holding `b → a` reads
/// `b, a, c, d`, so `c` neighbours `a` and `d` neighbours `b`.
fn across(faces: &[&[u32]], a: u32, b: u32) -> (u32, u32) {
    for f in faces {
        for k in 0..4 {
            if f[k] == b && f[(k + 1) % 4] == a {
                return (f[(k + 2) % 4], f[(k + 3) % 4]);
            }
        }
    }
    panic!("edge {a}-{b} has no opposite face")
}

/// The 4×4 control points `grid[row][col]` of a regular interior quad `f = [v0, v1, v2, v3]`,
/// with `u` along v0→v1 (columns) and `v` along v0→v3 (rows), v0 at (1, 1).
fn regular_neighbourhood(faces: &[&[u32]], f: &[u32]) -> [[u32; 4]; 4] {
    let mut grid = [[u32::MAX; 4]; 4];
    for k in 0..4 {
        let w: Vec<u32> = (0..4).map(|i| f[(k + i) % 4]).collect();
        // In the frame of w0: below w0, left of w0, and the diagonal point.
        let (below, _) = across(faces, w[0], w[1]);
        let (_, left) = across(faces, w[3], w[0]);
        let (left2, diag) = across(faces, w[0], below);
        assert_eq!(left, left2, "not a regular neighbourhood");
        // Local (col, row) coordinates in w0's frame, rotated k quarter turns.
        for (x, y, v) in [(1, 1, w[0]), (1, 0, below), (0, 1, left), (0, 0, diag)] {
            let (mut cx, mut cy) = (x, y);
            for _ in 0..k {
                (cx, cy) = (3 - cy, cx);
            }
            grid[cy][cx] = v;
        }
    }
    grid
}

fn faces_of(mesh: &Mesh) -> Vec<&[u32]> {
    assert!(mesh.face_counts.iter().all(|&c| c == 4));
    mesh.face_indices.chunks(4).collect()
}

/// On the torus (all vertices of valence 4) every face is a regular B-spline patch of its
/// 16 neighbouring control points (Catmull & Clark 1978), so OpenSubdiv's position and
/// first derivatives must match the tensor-product formula.
#[test]
fn torus_patches_match_bicubic_bspline() {
    require_osd!();
    let mesh = load_shape("catmark_torus");
    let faces = faces_of(&mesh);
    let n = 5;
    let samples = eval_limit_grid(&OsdMesh::from(&mesh), n, 3, false, EndCap::Gregory).unwrap();
    assert_eq!(samples.len(), faces.len() * n * n);
    let mut worst = 0.0f64;
    for s in &samples {
        let grid = regular_neighbourhood(&faces, faces[s.face as usize]);
        let ((bu, du), (bv, dv)) = (bspline(s.u as f64), bspline(s.v as f64));
        let (mut p, mut pu, mut pv) = ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
        for r in 0..4 {
            for c in 0..4 {
                let x = mesh.positions[grid[r][c] as usize];
                for k in 0..3 {
                    p[k] += bu[c] * bv[r] * x[k] as f64;
                    pu[k] += du[c] * bv[r] * x[k] as f64;
                    pv[k] += bu[c] * dv[r] * x[k] as f64;
                }
            }
        }
        for k in 0..3 {
            worst = worst
                .max((p[k] - s.p[k] as f64).abs())
                .max((pu[k] - s.du[k] as f64).abs())
                .max((pv[k] - s.dv[k] as f64).abs());
        }
    }
    assert!(worst < 1e-5, "largest deviation from the B-spline: {worst}");
}

/// `Limit` on level 0 of the torus puts each vertex at the B-spline's value at a patch
/// corner: (1/36)(16 v + 4 Σ edge neighbours + Σ diagonal neighbours).
#[test]
fn torus_limit_positions_match_bspline_corners() {
    require_osd!();
    let mesh = load_shape("catmark_torus");
    let faces = faces_of(&mesh);
    let limit = limit_stencil_positions(&OsdMesh::from(&mesh), 0).unwrap();
    assert_eq!(limit.len(), mesh.positions.len());
    for f in &faces {
        let g = regular_neighbourhood(&faces, f);
        let w = [[1.0, 4.0, 1.0], [4.0, 16.0, 4.0], [1.0, 4.0, 1.0]];
        let mut p = [0.0f32; 3];
        for r in 0..3 {
            for c in 0..3 {
                let x = mesh.positions[g[r][c] as usize];
                for k in 0..3 {
                    p[k] += w[r][c] / 36.0 * x[k];
                }
            }
        }
        assert!(dist(p, limit[f[0] as usize]) < 1e-5, "vertex {}", f[0]);
    }
}

fn ptex_faces(mesh: &Mesh) -> usize {
    mesh.face_counts
        .iter()
        .map(|&c| if c == 4 { 1 } else { c as usize })
        .sum()
}

/// One sample per grid point of every ptex face (a quad is one ptex face, an n-gon n of
/// them), in order, on shapes with triangles, pentagons and boundaries.
#[test]
fn sample_count_is_ptex_faces_times_grid() {
    require_osd!();
    let n = 4;
    for (name, expected_ptex) in [("catmark_gregory_test8", 14), ("catmark_gregory_test2", 12)] {
        let mesh = load_shape(name);
        assert_eq!(ptex_faces(&mesh), expected_ptex);
        for end_cap in [EndCap::Gregory, EndCap::BSpline] {
            let samples = eval_limit_grid(&OsdMesh::from(&mesh), n, 4, false, end_cap).unwrap();
            assert_eq!(samples.len(), expected_ptex * n * n, "{name} {end_cap:?}");
            for (k, s) in samples.iter().enumerate() {
                let (face, j, i) = (k / (n * n), (k / n) % n, k % n);
                assert_eq!(
                    (s.face as usize, s.u, s.v),
                    (face, i as f32 / 3.0, j as f32 / 3.0)
                );
                assert!(s.p.iter().chain(&s.du).chain(&s.dv).all(|x| x.is_finite()));
            }
        }
    }
}

/// Holes give no samples, and the patch counts grow with the isolation level.
#[test]
fn holes_are_skipped_and_patch_counts_grow() {
    require_osd!();
    let mesh = load_shape("catmark_hole_test1");
    let samples = eval_limit_grid(&OsdMesh::from(&mesh), 3, 2, false, EndCap::Gregory).unwrap();
    assert_eq!(samples.len(), (ptex_faces(&mesh) - mesh.holes.len()) * 9);
    assert!(
        mesh.face_counts.iter().all(|&c| c == 4),
        "ptex index = face index"
    );
    assert!(samples.iter().all(|s| !mesh.holes.contains(&s.face)));

    let pawn = load_shape("catmark_pawn");
    let (p1, b1) = patch_counts(&OsdMesh::from(&pawn), 1, false, EndCap::Gregory).unwrap();
    let (p3, b3) = patch_counts(&OsdMesh::from(&pawn), 3, false, EndCap::Gregory).unwrap();
    assert!(
        p1 >= pawn.num_faces() && p3 > p1 && b3 > b1,
        "{p1} {p3} {b1} {b3}"
    );
    let legacy = patch_stats(
        &OsdMesh::from(&pawn),
        &PatchOptions {
            isolation_level: 3,
            end_cap: EndCap::LegacyGregory,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(legacy.num_local_points, 0);
}

/// The derivatives are with respect to the ptex face's own (u, v), also on patches deep in
/// the adaptive hierarchy: central differences of the positions agree with them.
#[test]
fn derivatives_match_finite_differences() {
    require_osd!();
    let mesh = load_shape("catmark_gregory_test8");
    let n = 65;
    let h = 1.0 / (n - 1) as f32;
    let samples = eval_limit_grid(&OsdMesh::from(&mesh), n, 6, false, EndCap::Gregory).unwrap();
    let at = |f: usize, i: usize, j: usize| -> &LimitSample { &samples[f * n * n + j * n + i] };
    let mut worst = 0.0f32;
    let mut size = 0.0f32;
    for f in 0..ptex_faces(&mesh) {
        // Stay away from the extraordinary corner (0, 0) of n-gon sub-faces and the borders.
        for j in (8..n - 8).step_by(7) {
            for i in (8..n - 8).step_by(7) {
                let s = at(f, i, j);
                let (pu, pv) = (at(f, i + 1, j), at(f, i, j + 1));
                let (mu, mv) = (at(f, i - 1, j), at(f, i, j - 1));
                for k in 0..3 {
                    let fd_u = (pu.p[k] - mu.p[k]) / (2.0 * h);
                    let fd_v = (pv.p[k] - mv.p[k]) / (2.0 * h);
                    worst = worst
                        .max((fd_u - s.du[k]).abs())
                        .max((fd_v - s.dv[k]).abs());
                    size = size.max(s.du[k].abs()).max(s.dv[k].abs());
                }
            }
        }
    }
    assert!(
        worst < 1e-2 * size,
        "finite differences off by {worst} (derivative scale {size})"
    );
}

#[test]
fn table_only_build_is_the_same_table() {
    require_osd!();
    let car = load_shape("catmark_car");
    let mesh = OsdMesh::from(&car);
    let mut last_vertices = 0;
    for level in [1, 4, 6] {
        let o = PatchOptions {
            isolation_level: level,
            use_single_crease: true,
            use_inf_sharp: false,
            end_cap: EndCap::Gregory,
        };
        let full = patch_stats(&mesh, &o).unwrap();
        let only = patch_table_only(&mesh, &o).unwrap();
        assert_eq!(only.num_patches, full.num_patches, "level {level}");
        assert_eq!(only.bytes, full.bytes, "level {level}");
        // Adaptive refinement adds vertices at every level.
        assert!(only.num_refined_vertices > last_vertices, "level {level}");
        last_vertices = only.num_refined_vertices;
    }
}
