//! Adaptive against uniform tessellation: triangles needed at a given measured maximum
//! deviation from the limit surface, and the time of rates + tessellation.
//!
//! `cargo run --release -p subsurf --example tess_adaptive [-- FILE...]` (default
//! `testdata/shapes/catmark_car.obj` and `catmark_pawn.obj`). The deviation of a
//! tessellation is measured densely: in every triangle, at 10 barycentric points per side
//! (66 points), the distance between the flat triangle and the limit surface at the same ptex
//! parameters (an upper bound of the distance to the surface), as a fraction of the
//! bounding-box diagonal. Times are medians of 11 runs on all threads.

use std::time::Instant;

use rayon::prelude::*;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::tess::{plan, EdgeRates, RatePolicy};
use subsurf::Topology;

fn deviation(s: &LimitSurface, rates: &EdgeRates) -> (usize, f64) {
    let p = plan(&s.table, rates, "measure").unwrap();
    let uv = p.triangle_uv.clone();
    let out = s.eval_plan(p);
    const K: usize = 10;
    let worst = out
        .triangles
        .par_iter()
        .zip(&uv)
        .map(|(tri, (ptex, c))| {
            let x = tri.map(|i| out.positions[i as usize]);
            let mut w = 0.0f64;
            for i in 0..=K {
                for j in 0..=K - i {
                    let (a, b) = (i as f32 / K as f32, j as f32 / K as f32);
                    let g = 1.0 - a - b;
                    let u = g * c[0][0] + a * c[1][0] + b * c[2][0];
                    let v = g * c[0][1] + a * c[1][1] + b * c[2][1];
                    let q = s.eval(*ptex as usize, u, v).unwrap().p;
                    let d: f64 = (0..3)
                        .map(|k| f64::from(g * x[0][k] + a * x[1][k] + b * x[2][k] - q[k]).powi(2))
                        .sum();
                    w = w.max(d.sqrt());
                }
            }
            w
        })
        .reduce(|| 0.0, f64::max);
    (
        out.triangles.len(),
        worst / f64::from(subsurf::mesh::bbox_diagonal(&s.points)),
    )
}

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let mut files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        files = ["catmark_car", "catmark_pawn"]
            .iter()
            .map(|n| format!("testdata/shapes/{n}.obj"))
            .collect();
    }
    for file in files {
        let mesh = subsurf::io::obj::read_file(std::path::Path::new(&file)).unwrap();
        let t = Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let s = LimitSurface::new(table, &mesh.positions);
        println!("\n{file}\n\nuniform rate | triangles | max deviation");
        println!("---|---|---");
        let mut uniform = Vec::new();
        for r in [1u32, 2, 3, 4, 6, 8, 11, 16, 23, 32] {
            let (n, d) = deviation(&s, &EdgeRates::uniform(&s.table.base, r));
            println!("{r} | {n} | {d:.2e}");
            uniform.push((n, d));
        }
        println!("\ntolerance | triangles | max deviation | uniform triangles at that deviation | ratio | rates + tessellation (ms, median)");
        println!("---|---|---|---|---|---");
        for e in [1e-2f32, 3e-3, 1e-3, 3e-4, 1e-4] {
            let policy = RatePolicy::Tolerance(e);
            let rates = policy.rates(&s, "--tolerance").unwrap();
            let (n, d) = deviation(&s, &rates);
            // The cheapest measured uniform rate at least as accurate.
            let u = uniform
                .iter()
                .filter(|(_, ud)| *ud <= d)
                .map(|(un, _)| *un)
                .min();
            let times: Vec<f64> = (0..11)
                .map(|_| {
                    let t0 = Instant::now();
                    let r = policy.rates(&s, "--tolerance").unwrap();
                    std::hint::black_box(s.tessellate_rates(&r, "").unwrap());
                    t0.elapsed().as_secs_f64() * 1e3
                })
                .collect();
            let (us, ratio) = u.map_or(("> rate 32".to_string(), "-".to_string()), |u| {
                (u.to_string(), format!("{:.1}", u as f64 / n as f64))
            });
            println!(
                "{e:.0e} | {n} | {d:.2e} | {us} | {ratio} | {:.1}",
                median(times)
            );
        }
    }
}
