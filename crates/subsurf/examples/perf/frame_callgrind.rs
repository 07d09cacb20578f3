//! Per-frame evaluation (`Refiner::refine_positions_into`) on a one-thread rayon pool, for
//! instruction counts and quick timings:
//! `cargo run --release -p subsurf --example frame_callgrind -- FILE LEVEL FRAMES [EVICT_MIB]`
//! (EVICT_MIB: a buffer of that size is written before each frame, outside its time, so that
//! the frame starts with cold caches as in a harness that runs other work between frames).
//!
//! The first frame (which finds the per-step plans) runs outside `frames`, so under callgrind
//! `--toggle-collect='frame_callgrind::frames'` counts the frames alone. Prints the median
//! frame time and checks the last frame against `refine_positions` bit for bit.

mod common;
use std::time::Instant;
use subsurf::{Refiner, Topology};

/// `runs` frames into `out`; their times in milliseconds.
#[inline(never)]
fn frames(
    r: &Refiner,
    base: &[[f32; 3]],
    out: &mut [[f32; 3]],
    runs: usize,
    evict: &mut [u64],
) -> Vec<f64> {
    let mut scratch = Vec::new();
    (0..runs)
        .map(|i| {
            // Touch `evict` first (a harness runs other peers between frames).
            for (j, x) in evict.iter_mut().enumerate().step_by(8) {
                *x = x.wrapping_add((i + j) as u64);
            }
            std::hint::black_box(&mut *evict);
            let t = Instant::now();
            r.refine_positions_into(base, out, &mut scratch)
                .expect("lengths match");
            std::hint::black_box(&mut *out);
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let mesh = subsurf::io::read_path(common::mesh_path(&args))?;
    let level: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let runs: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(11);
    let evict_mib: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    pool.install(|| -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
        let r = Refiner::new(Topology::new(&mesh)?, level)?;
        let mut out = vec![[0.0f32; 3]; r.last().num_vertices()];
        let mut scratch = Vec::new();
        r.refine_positions_into(&mesh.positions, &mut out, &mut scratch)?;
        let mut evict = vec![0u64; evict_mib << 17];
        let mut t = frames(&r, &mesh.positions, &mut out, runs, &mut evict);
        t.sort_by(f64::total_cmp);
        let want = r.refine_positions(&mesh.positions);
        let same = want.len() == out.len()
            && want
                .iter()
                .zip(&out)
                .all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits));
        println!(
            "level {level}: {} vertices, frame median {:.3} ms (min {:.3}) of {runs}, bit-identical: {same}",
            out.len(),
            t.get(t.len() / 2).copied().unwrap_or(0.0),
            t.first().copied().unwrap_or(0.0),
        );
        Ok(())
    })
    .map_err(|e| e as Box<dyn std::error::Error>)
}
