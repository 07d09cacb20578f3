//! Times one refinement setup path, for profiling (run it under callgrind for instruction
//! counts): `cargo run --release --example setup_timing -- FILE LEVEL MODE`, MODE one of
//! `full` (`Refiner::new`), `stencils` (`Refiner::new` and its stencil tables), `lean` (`Refiner::with_options(.., RefineOptions::lean())`) or
//! `once` (`refine_once` of the positions, lean); an optional fourth argument repeats the
//! setup that many times in the process and prints the median (warm allocator).

mod common;
use std::time::Instant;
use subsurf::refine::{refine_once, RefineOptions};
use subsurf::{Refiner, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let level: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(4);
    let mode = args.get(3).map(String::as_str).unwrap_or("full");
    let runs: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(1).max(1);
    let mesh = subsurf::io::read_path(path)?;
    let base = Topology::new(&mesh)?;
    let mut times = Vec::with_capacity(runs);
    let mut vertices = 0;
    for _ in 0..runs {
        let base = base.clone();
        let t = Instant::now();
        vertices = match mode {
            "full" => Refiner::new(base, level)?.last().num_vertices(),
            "stencils" => {
                let r = Refiner::new(base, level)?;
                r.stencils().len() + r.last().num_vertices()
            }
            "lean" => Refiner::with_options(base, level, RefineOptions::lean())?
                .last()
                .num_vertices(),
            "once" => refine_once(base, level, &mesh.positions, RefineOptions::lean())?
                .1
                .len(),
            _ => return Err(format!("unknown mode {mode} (full, stencils, lean or once)").into()),
        };
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{mode} level {level}: {vertices} vertices in {:.3} ms (median of {runs})",
        times[runs / 2]
    );
    Ok(())
}
