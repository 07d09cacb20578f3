//! Times `Topology::new` on a 1,000 × 1,000 quad torus: `cargo run --release --example
//! topology_timing -p subsurf -- [RUNS]` (set `RAYON_NUM_THREADS=1` for one thread).
use std::time::Instant;
use subsurf::{shapes, Topology};

fn main() {
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let mesh = shapes::torus(1000, 1000, 2.0, 0.5);
    let mut t = Vec::new();
    for _ in 0..runs {
        let s = Instant::now();
        std::hint::black_box(Topology::new(&mesh).unwrap());
        t.push(s.elapsed().as_secs_f64() * 1e3);
    }
    t.sort_by(f64::total_cmp);
    println!(
        "Topology::new, 1M-quad torus: median {:.1} ms of {runs}",
        t[runs / 2]
    );
}
