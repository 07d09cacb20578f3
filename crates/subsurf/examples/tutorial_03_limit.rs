//! Tutorial 3: the limit surface, evaluated anywhere — positions and derivatives at
//! `(face, u, v)`.
//!
//! Uniform refinement only approaches the surface. A [`PatchTable`] describes the limit
//! surface itself as patches (bicubic B-splines on regular faces, Gregory end caps around
//! extraordinary vertices, isolated `isolation_level` steps deep); a [`LimitSurface`] is the
//! table with the points of one set of base positions, evaluated at any ptex face `(u, v)`
//! (OpenSubdiv's `Far::PatchTable` + `Far::PatchMap`). A quad is one ptex face, with `(0, 0)`
//! at its first vertex and `u` along its first edge.
//!
//! `cargo run -p subsurf --example tutorial_03_limit`

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::{shapes, Refiner, Topology};

fn dist(a: [f32; 3], b: [f32; 3]) -> f32 {
    (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f32>().sqrt()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A cube (every vertex of valence 3: extraordinary) with one corner pulled out.
    let mut cube = shapes::cube();
    cube.positions.set(3, [1.5, 1.2, 1.4]);
    let topology = Topology::new(&cube)?;
    let table = PatchTable::build(&topology, &PatchOptions::default())?;
    let counts = table.counts();
    println!("{} patches: {counts:?}", table.num_patches());
    let surface = LimitSurface::new(table, &cube.positions);

    // Refined points converge to the limit: a base vertex keeps its index at every level,
    // and its refined position closes in on the limit point at its corner.
    let face = 0;
    let v = topology.face_vertices(face)[0] as usize; // the corner (u, v) = (0, 0) of face 0
    let corner = surface.eval(face, 0.0, 0.0).ok_or("face 0 is a hole")?.p;
    let refiner = Refiner::new(topology.clone(), 5)?;
    let levels = refiner.refine_all(&cube.positions);
    let gaps: Vec<f32> = levels.iter().map(|p| dist(p[v], corner)).collect();
    let shown: Vec<String> = gaps.iter().map(|g| format!("{g:.1e}")).collect();
    println!(
        "distance of vertex {v} to its limit point, levels 0..=5: {}",
        shown.join(", ")
    );
    assert!(gaps.windows(2).all(|w| w[1] < 0.5 * w[0]), "{gaps:?}");
    // The refiner's own limit stencils give the same point.
    assert!(dist(refiner.limit(&levels[5])[v], corner) < 1e-5);

    // Derivatives: `du`, `dv` are the partials in the ptex face's own parameters, here
    // checked against central differences, and `n` is the unit normal `du × dv`.
    let (u0, v0, h) = (0.3f32, 0.6f32, 1e-3f32);
    let at = |u: f32, v: f32| surface.eval(face, u, v).expect("inside face 0");
    let p = at(u0, v0);
    for c in 0..3 {
        let du = (at(u0 + h, v0).p[c] - at(u0 - h, v0).p[c]) / (2.0 * h);
        let dv = (at(u0, v0 + h).p[c] - at(u0, v0 - h).p[c]) / (2.0 * h);
        assert!((du - p.du[c]).abs() < 1e-2 && (dv - p.dv[c]).abs() < 1e-2);
    }
    // Faces are counter-clockwise seen from outside: the normal points away from the centre.
    let outward: f32 = (0..3).map(|c| p.n[c] * p.p[c]).sum();
    assert!(outward > 0.0);
    println!(
        "face {face} at ({u0}, {v0}): p {:?}, du {:?}, dv {:?}, n {:?}",
        p.p, p.du, p.dv, p.n
    );

    // Many queries at once: `eval_batch` (in parallel), the same values as one by one.
    let queries: Vec<(u32, f32, f32)> = (0..6).map(|f| (f, 0.5, 0.5)).collect();
    let batch = surface.eval_batch(&queries);
    for (&(f, u, v), got) in queries.iter().zip(&batch) {
        assert_eq!(
            got.map(|x| x.p),
            surface.eval(f as usize, u, v).map(|x| x.p)
        );
    }
    println!(
        "face centres: {:?}",
        batch.iter().map(|x| x.map(|x| x.p)).collect::<Vec<_>>()
    );
    Ok(())
}
