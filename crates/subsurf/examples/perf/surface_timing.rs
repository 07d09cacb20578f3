//! The Rust side of the Python package's overhead benchmark (`crates/subsurf-py/bench/overhead.py`):
//! the same two calls as `subsurf.refine(mesh, level)` and `Refiner.refine(points)` make,
//! timed in-process, median of RUNS runs each, printed as one JSON line.
//!
//! `cargo run --release -p subsurf --example surface_timing -- FILE LEVEL RUNS [both|refine|frame]`
//! (one call alone for instruction counts under callgrind; the other's time prints as 0).
use std::time::Instant;
use subsurf::surface::{refine_mesh, Cpu};
use subsurf::{Refiner, Topology};

fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t.get(t.len() / 2).copied().unwrap_or(0.0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .map(String::as_str)
        .unwrap_or("examples/car.obj");
    let level: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let runs: usize = args
        .get(3)
        .and_then(|s| s.parse().ok())
        .unwrap_or(11)
        .max(1);
    let mode = args.get(4).map_or("both", String::as_str);
    let mesh = subsurf::io::read_path(path)?;
    // Warm-up, as the Python side does.
    let mut faces = refine_mesh(&mesh, level, false, None, &Cpu)?.num_faces();
    let runs_of = |m: &str| if mode == "both" || mode == m { runs } else { 0 };
    let refine = median_ms(runs_of("refine"), || {
        faces = refine_mesh(&mesh, level, false, None, &Cpu)
            .map(|m| m.num_faces())
            .unwrap_or(0);
    });
    let refiner = Refiner::new(Topology::new(&mesh)?, level)?;
    // As `Refiner.refine`: into a fresh buffer each call (it becomes the returned array).
    let n = refiner.last().num_vertices();
    let mut scratch = Vec::new();
    let mut frame_once = || {
        let mut out = vec![[0.0f32; 3]; n];
        refiner
            .refine_positions_into(&mesh.positions, &mut out, &mut scratch)
            .map(|()| out.len())
    };
    frame_once()?;
    let frame = median_ms(runs_of("frame"), || {
        std::hint::black_box(frame_once().unwrap_or(0));
    });
    println!(
        "{{\"refine_ms\": {refine:.4}, \"frame_ms\": {frame:.4}, \"faces\": {faces}, \"vertices\": {n}, \"runs\": {runs}}}"
    );
    Ok(())
}
