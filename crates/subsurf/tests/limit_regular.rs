//! Regular and single-crease patches against closed forms and brute-force refinement.

mod limit_common;

use limit_common::bbox_diagonal;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, PatchType};
use subsurf::shapes::torus;
use subsurf::{Crease, Mesh, Refiner, Topology};

/// Uniform cubic B-spline basis at `t` and its derivative, in `f64`.
fn bspline(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [
            s * s * s / 6.0,
            (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
            (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
            t * t * t / 6.0,
        ],
        [
            -s * s / 2.0,
            (3.0 * t * t - 4.0 * t) / 2.0,
            (-3.0 * t * t + 2.0 * t + 1.0) / 2.0,
            t * t / 2.0,
        ],
    )
}

fn surface(mesh: &Mesh, level: u32) -> LimitSurface {
    let t = Topology::new(mesh).unwrap();
    let table = PatchTable::build(
        &t,
        &PatchOptions {
            isolation_level: level,
            ..Default::default()
        },
    )
    .unwrap();
    LimitSurface::new(table, &mesh.positions)
}

/// On a torus every vertex has valence 4: every face is one depth-0 B-spline patch whose 16
/// control points are its 4×4 neighbourhood (Catmull & Clark 1978), and evaluation equals
/// the tensor-product formula.
#[test]
fn torus_faces_are_bicubic_bspline_patches() {
    let (nu, nv) = (7, 5);
    let mesh = torus(nu, nv, 2.0, 0.7);
    let s = surface(&mesh, 4);
    assert_eq!(s.table().num_patches(), nu * nv);
    let id = |i: isize, j: isize| {
        (j.rem_euclid(nv as isize) as usize * nu + i.rem_euclid(nu as isize) as usize) as u32
    };
    let diag = bbox_diagonal(&mesh.positions) as f64;
    let mut worst = 0.0f64;
    for j in 0..nv as isize {
        for i in 0..nu as isize {
            let f = j as usize * nu + i as usize;
            let p = s.table().patch_map().find(f, 0.3, 0.6).unwrap() as usize;
            assert_eq!(s.table().patch_type(p), PatchType::Regular);
            assert_eq!(s.table().params()[p].depth(), 0);
            let expect: Vec<u32> = (0..16)
                .map(|k| id(i - 1 + (k % 4) as isize, j - 1 + (k / 4) as isize))
                .collect();
            assert_eq!(s.table().patch_cvs(p), &expect[..], "face {f}");
            for (u, v) in [(0.0, 0.0), (0.25, 0.7), (1.0, 0.5), (0.9, 1.0), (0.5, 0.5)] {
                let (bu, du) = bspline(u);
                let (bv, dv) = bspline(v);
                let mut x = [[0.0f64; 3]; 3];
                for (k, &cv) in expect.iter().enumerate() {
                    let q = mesh.positions[cv as usize];
                    let (a, b) = (k % 4, k / 4);
                    for c in 0..3 {
                        x[0][c] += bu[a] * bv[b] * q[c] as f64;
                        x[1][c] += du[a] * bv[b] * q[c] as f64;
                        x[2][c] += bu[a] * dv[b] * q[c] as f64;
                    }
                }
                let r = s.eval(f, u as f32, v as f32).unwrap();
                for c in 0..3 {
                    worst = worst.max((r.p[c] as f64 - x[0][c]).abs() / diag);
                    worst = worst.max((r.du[c] as f64 - x[1][c]).abs() / diag);
                    worst = worst.max((r.dv[c] as f64 - x[2][c]).abs() / diag);
                }
            }
        }
    }
    assert!(worst < 2e-7, "worst deviation {worst:e} of the diagonal");
}

/// A torus with one loop of crease edges (along `u` at row `j = 2`, or along `v` at column
/// `i = 2`) of sharpness `s`.
fn creased_torus(s: f32, along_u: bool) -> Mesh {
    let (nu, nv) = (8, 8);
    let mut m = torus(nu, nv, 2.0, 0.8);
    let id = |i: usize, j: usize| ((j % nv) * nu + (i % nu)) as u32;
    for k in 0..8 {
        let (v0, v1) = if along_u {
            (id(k, 2), id(k + 1, 2))
        } else {
            (id(2, k), id(2, k + 1))
        };
        m.creases.push(Crease {
            v0,
            v1,
            sharpness: s,
        });
    }
    m
}

/// The limit position at `(a, b) / 2^k` of base face `f`, from uniform refinement to level
/// `k` and the limit masks (`Refiner` + `limit_stencils`): corner 0 of the level-`k`
/// descendant face in quadrant `(a, b)` — a child face keeps its parent's orientation and
/// child `j` covers quadrant `j` (0: low u, low v; 1: high u; 2: both high; 3: high v).
fn brute_force(
    refiner: &Refiner,
    limit: &[[f32; 3]],
    f: usize,
    a: usize,
    b: usize,
    k: usize,
) -> [f32; 3] {
    let mut face = f;
    for d in 0..k {
        let bit = k - 1 - d;
        let (hu, hv) = ((a >> bit) & 1, (b >> bit) & 1);
        let j = match (hu, hv) {
            (0, 0) => 0,
            (1, 0) => 1,
            (1, 1) => 2,
            _ => 3,
        };
        face = refiner.levels[d].arrays().face_offsets[face] as usize + j;
    }
    limit[refiner.levels[k].face_vertices(face)[0] as usize]
}

fn crease_matches_refinement(s: f32, along_u: bool, level: u32) {
    let mesh = creased_torus(s, along_u);
    let surf = surface(&mesh, level);
    let counts = surf.table().counts();
    assert_eq!(counts.single_crease, 16, "s = {s}: {counts:?}");
    assert_eq!(counts.gregory, 0);
    let k = 5;
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), k).unwrap();
    let limit = refiner.limit(&refiner.refine_positions(&mesh.positions));
    let diag = bbox_diagonal(&mesh.positions);
    let mut worst = 0.0f32;
    for f in 0..mesh.num_faces() {
        for b in (0..32).step_by(3) {
            for a in (0..32).step_by(3) {
                let want = brute_force(&refiner, &limit, f, a, b, k);
                let got = surf.eval(f, a as f32 / 32.0, b as f32 / 32.0).unwrap().p;
                let d = (0..3)
                    .map(|c| (got[c] - want[c]).powi(2))
                    .sum::<f32>()
                    .sqrt();
                worst = worst.max(d / diag);
            }
        }
    }
    assert!(worst < 1e-5, "s = {s}: worst {worst:e} of the diagonal");
}

/// Single-crease patches (integer and fractional sharpness, crease along `u` and `v`, also
/// sharper than the isolation level) equal the limit of brute-force refinement with the
/// crease rules (DeRose, Kass & Truong 1998): after `k = 5 > s` steps every edge is smooth
/// and the limit masks are exact.
#[test]
fn single_crease_patches_match_refinement() {
    for s in [1.0, 2.0, 1.5, 2.7] {
        crease_matches_refinement(s, true, 4);
    }
    for s in [1.0, 3.3] {
        crease_matches_refinement(s, false, 4);
    }
    // Sharpness above the isolation level is kept, not capped: still exact.
    crease_matches_refinement(4.6, true, 1);
}

/// With OpenSubdiv's cap, the stored sharpness is `min(s, L − level)`.
#[test]
fn capped_sharpness_is_opensubdivs() {
    let mesh = creased_torus(4.6, true);
    let t = Topology::new(&mesh).unwrap();
    let o = PatchOptions {
        isolation_level: 2,
        cap_crease_sharpness: true,
        ..Default::default()
    };
    let table = PatchTable::build(&t, &o).unwrap();
    let creased: Vec<f32> = (0..table.num_patches())
        .filter(|&p| table.patch_type(p) == PatchType::SingleCrease)
        .map(|p| table.sharpness()[p])
        .collect();
    assert_eq!(creased, vec![2.0; 16]);
}

/// The fractional crease blends: on the crease the limit point moves monotonically outwards
/// as the sharpness grows, and a fractional sharpness `m + φ` gives
/// `(1 − φ) C_m + φ C_(m+1)` there (DeRose, Kass & Truong 1998: the blended rule only
/// touches the crease points; see `patch::single_crease`).
#[test]
fn fractional_sharpness_blends_between_integers() {
    let at = |s: f32| {
        let surf = surface(&creased_torus(s, true), 4);
        // Face (3, 1) has the crease on its v = 1 edge; sample on it.
        surf.eval(8 + 3, 0.4, 1.0).unwrap().p
    };
    // Distance from the tube's centre circle (radius 2).
    let dist = |p: [f32; 3]| {
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
        ((r - 2.0).powi(2) + p[2] * p[2]).sqrt()
    };
    let d: Vec<f32> = [0.0, 1.0, 1.5, 2.0, 3.0]
        .iter()
        .map(|&s| dist(at(s)))
        .collect();
    assert!(d.windows(2).all(|w| w[1] > w[0]), "{d:?}");
    for (m, phi) in [(1.0f32, 0.5f32), (2.0, 0.25)] {
        let (a, b, x) = (at(m), at(m + 1.0), at(m + phi));
        for c in 0..3 {
            let blend = (1.0 - phi) * a[c] + phi * b[c];
            assert!(
                (x[c] - blend).abs() < 2e-6,
                "s = {}: {x:?} vs {a:?} / {b:?}",
                m + phi
            );
        }
    }
}
