//! Adaptive against uniform tessellation: triangles needed at a given measured maximum
//! deviation from the true limit surface, and the time of rates + tessellation.
//!
//! `cargo run --release -p subsurf --example tess_adaptive [-- FILE...]` (default
//! `testdata/shapes/catmark_car.obj` and `catmark_pawn.obj`). The deviation of a
//! tessellation is measured densely: in every triangle, at 10 barycentric points per side
//! (66 points), the distance between the flat triangle and the limit surface at the same ptex
//! parameters (an upper bound of the distance to the surface), as a fraction of the
//! bounding-box diagonal. The limit surface is an isolation-10 table's (end caps within
//! ~1e-5 of the diagonal on the car and the pawn). Adaptive tessellations go through
//! `surface::adaptive_surface` (isolation chosen per region, the chords at 3/4 of the
//! tolerance, the check of every triangle); uniform ones are drawn from the isolation-10 table, the best
//! a uniform rate can do. Times are medians of 11 runs on all threads: the adaptive surface's
//! construction (tables for the choice and the final one), then rates + tessellation.

use std::time::Instant;

use rayon::prelude::*;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::surface::{adaptive_surface, tessellate_adaptive, Cpu};
use subsurf::tess::{plan, EdgeRates, RatePolicy};
use subsurf::Topology;

fn deviation(
    reference: &LimitSurface,
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    uv: &[(u32, [[f32; 2]; 3])],
) -> f64 {
    const K: usize = 10;
    let worst = triangles
        .par_iter()
        .zip(uv)
        .map(|(tri, (ptex, c))| {
            let x = tri.map(|i| positions[i as usize]);
            let mut w = 0.0f64;
            for i in 0..=K {
                for j in 0..=K - i {
                    let (a, b) = (i as f32 / K as f32, j as f32 / K as f32);
                    let g = 1.0 - a - b;
                    let u = g * c[0][0] + a * c[1][0] + b * c[2][0];
                    let v = g * c[0][1] + a * c[1][1] + b * c[2][1];
                    let q = reference.eval_position(*ptex as usize, u, v).unwrap();
                    let d: f64 = (0..3)
                        .map(|k| f64::from(g * x[0][k] + a * x[1][k] + b * x[2][k] - q[k]).powi(2))
                        .sum();
                    w = w.max(d.sqrt());
                }
            }
            w
        })
        .reduce(|| 0.0, f64::max);
    worst / f64::from(subsurf::mesh::bbox_diagonal(reference.points()))
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
        let o10 = PatchOptions {
            isolation_level: 10,
            ..Default::default()
        };
        let reference = LimitSurface::new(PatchTable::build(&t, &o10).unwrap(), &mesh.positions);
        println!("\n{file}\n\nuniform rate | triangles | max deviation");
        println!("---|---|---");
        let mut uniform = Vec::new();
        for r in [1u32, 2, 3, 4, 6, 8, 11, 16, 23, 32, 45, 64] {
            let mut p = plan(reference.table(), &EdgeRates::uniform(&t, r), "").unwrap();
            let uv = std::mem::take(&mut p.triangle_uv);
            let out = reference.eval_plan(p);
            let d = deviation(&reference, &out.positions, &out.triangles, &uv);
            println!("{r} | {} | {d:.2e}", out.triangles.len());
            uniform.push((out.triangles.len(), d));
        }
        println!("\ntolerance | triangles | max deviation | deepest level | uniform triangles at that deviation | ratio | surface (ms) | rates + tessellation (ms, median)");
        println!("---|---|---|---|---|---|---|---");
        let options = PatchOptions::default();
        for e in [1e-2f32, 3e-3, 1e-3, 3e-4, 1e-4] {
            let policy = RatePolicy::Tolerance(e);
            let build = || adaptive_surface(&t, &mesh.positions, &policy, "", &options);
            let (s, chords) = match build() {
                Ok(x) => x,
                Err(err) => {
                    println!("{e:.0e} | {err} | | | | | |");
                    continue;
                }
            };
            let a = tessellate_adaptive(&s, &chords, "", &Cpu).unwrap();
            let n = a.tessellation.triangles.len();
            let d = deviation(
                &reference,
                &a.tessellation.positions,
                &a.tessellation.triangles,
                &a.triangle_uv,
            );
            let deepest = s
                .table()
                .face_levels()
                .as_ref()
                .map_or(4, |l| *l.iter().max().unwrap());
            // The cheapest measured uniform rate at least as accurate.
            let u = uniform
                .iter()
                .filter(|(_, ud)| *ud <= d)
                .map(|(un, _)| *un)
                .min();
            let time = |f: &dyn Fn()| {
                median(
                    (0..11)
                        .map(|_| {
                            let t0 = Instant::now();
                            f();
                            t0.elapsed().as_secs_f64() * 1e3
                        })
                        .collect(),
                )
            };
            let t_surface = time(&|| {
                std::hint::black_box(build().unwrap());
            });
            let t_tess = time(&|| {
                std::hint::black_box(tessellate_adaptive(&s, &chords, "", &Cpu).unwrap());
            });
            let (us, ratio) = u.map_or(("> rate 64".to_string(), "-".to_string()), |u| {
                (u.to_string(), format!("{:.1}", u as f64 / n as f64))
            });
            println!("{e:.0e} | {n} | {d:.2e} | {deepest} | {us} | {ratio} | {t_surface:.1} | {t_tess:.1}");
        }
    }
}
