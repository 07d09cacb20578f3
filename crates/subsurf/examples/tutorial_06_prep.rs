//! Tutorial 6: the p-rep — a closed quad mesh as smooth polynomial patches, exported in
//! Bezier form.
//!
//! [`PrepPatches`] converts a closed quad mesh into one polynomial patch per face (Myles, Yeo
//! & Peters 2008): bicubic where every corner has valence 4 (it is then the B-spline limit
//! surface), bicubic plus a sparse bi-5 perturbation elsewhere. The surface interpolates the
//! Catmull-Clark limit points and tangent planes at the vertices and is G1: the tangent
//! plane is continuous across every edge. `to_bezier` exports every patch as 6×6 bi-5
//! Bernstein-Bezier control points, which any CAD or rendering tool evaluates; this program
//! evaluates that export itself and checks G1 on it.
//!
//! `cargo run -p subsurf --example tutorial_06_prep`

use subsurf::prep::PrepPatches;
use subsurf::{shapes, Refiner, Topology};

type V = [f64; 3];

/// The Bernstein polynomial `B(n, i)` at `t` (zero for `i` outside `0..=n`).
fn bernstein(n: i32, i: i32, t: f64) -> f64 {
    if !(0..=n).contains(&i) {
        return 0.0;
    }
    let binom = (1..=i).fold(1.0, |c, k| c * f64::from(n - k + 1) / f64::from(k));
    binom * t.powi(i) * (1.0 - t).powi(n - i)
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Position and unit normal of the bi-5 patch `b` (36 points, `b[6 i + j]`, `i` along `u`)
/// at `(u, v)`; `d/dt B(5, i) = 5 (B(4, i - 1) - B(4, i))`.
fn eval_bezier(b: &[V], u: f64, v: f64) -> (V, V) {
    let (mut p, mut pu, mut pv) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for i in 0..6 {
        for j in 0..6 {
            let (bu, bv) = (bernstein(5, i, u), bernstein(5, j, v));
            let du = 5.0 * (bernstein(4, i - 1, u) - bernstein(4, i, u));
            let dv = 5.0 * (bernstein(4, j - 1, v) - bernstein(4, j, v));
            for c in 0..3 {
                let x = b[(6 * i + j) as usize][c];
                p[c] += bu * bv * x;
                pu[c] += du * bv * x;
                pv[c] += bu * dv * x;
            }
        }
    }
    let n = cross(pu, pv);
    let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
    (p, n.map(|x| x / len))
}

/// The `(u, v)` of point `t` along edge `k` of a quad (edge `k` joins corners `k` and `k + 1`;
/// corner 0 is `(0, 0)`, corner 1 `(1, 0)`, corner 3 `(0, 1)`).
fn on_edge(k: usize, t: f64) -> (f64, f64) {
    [(t, 0.0), (1.0, t), (1.0 - t, 1.0), (0.0, 1.0 - t)][k]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A closed quad mesh with valences 3 and 4: a cube refined twice (one corner pulled out).
    let mut cube = shapes::cube();
    cube.positions.set(3, [1.5, 1.2, 1.4]);
    let refiner = Refiner::new(Topology::new(&cube)?, 2)?;
    let mesh = refiner.to_mesh(2, refiner.refine_positions(&cube.positions));
    let topology = Topology::new(&mesh)?;

    let prep = PrepPatches::<f64>::build(&mesh)?;
    let perturbed = (0..prep.num_faces())
        .filter(|&f| prep.face_h(f).is_some())
        .count();
    println!(
        "{} patches, {perturbed} with a bi-5 perturbation, the others bicubic",
        prep.num_faces()
    );

    // The Bezier export: 36 control points per face; evaluated, the same surface.
    let bezier = prep.to_bezier();
    assert_eq!(bezier.len(), 36 * prep.num_faces());
    let patch = |f: usize| &bezier[36 * f..36 * f + 36];
    for f in 0..prep.num_faces() {
        for (u, v) in [(0.0, 0.0), (0.3, 0.8), (1.0, 0.5)] {
            let (p, _) = eval_bezier(patch(f), u, v);
            let q = prep.eval(f, u, v).position;
            assert!((0..3).all(|c| (p[c] - q[c]).abs() < 1e-12));
        }
    }

    // G1 on the export: along every edge, both faces give the same points (C0) and the same
    // normal (a continuous tangent plane). The second face runs the edge the other way.
    let (mut gap, mut angle) = (0.0f64, 0.0f64);
    for e in 0..topology.num_edges() {
        let (faces, local) = (topology.edge_faces(e), topology.edge_faces_local(e));
        assert_eq!(faces.len(), 2, "closed mesh: two faces per edge");
        for s in 0..=16 {
            let t = s as f64 / 16.0;
            let (ua, va) = on_edge(local[0] as usize, t);
            let (ub, vb) = on_edge(local[1] as usize, 1.0 - t);
            let (pa, na) = eval_bezier(patch(faces[0] as usize), ua, va);
            let (pb, nb) = eval_bezier(patch(faces[1] as usize), ub, vb);
            gap = gap.max((0..3).map(|c| (pa[c] - pb[c]).abs()).fold(0.0, f64::max));
            // The angle between the normals, from its sine and cosine (acos alone loses half
            // the digits near 0).
            let dot: f64 = (0..3).map(|c| na[c] * nb[c]).sum();
            let sin = cross(na, nb).iter().map(|x| x * x).sum::<f64>().sqrt();
            angle = angle.max(sin.atan2(dot));
        }
    }
    println!(
        "along {} edges: positions within {gap:.1e}, normals within {angle:.1e} rad",
        topology.num_edges()
    );
    assert!(gap < 1e-12 && angle < 1e-9);

    // The export as a file format: `.npy`, shape (faces, 6, 6, 3), little-endian f64.
    let mut npy = Vec::new();
    prep.write_bezier_npy(&mut npy)?;
    assert!(npy.starts_with(b"\x93NUMPY"));
    println!(
        "bezier.npy: {} bytes for {} control points",
        npy.len(),
        bezier.len()
    );
    Ok(())
}
