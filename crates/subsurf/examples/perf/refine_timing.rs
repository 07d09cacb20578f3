//! Times each stage of uniform refinement per level: `cargo run --release --example refine_timing -- FILE LEVEL`.

mod common;
use std::time::Instant;
use subsurf::refine::{level_stencils, refine_topology};
use subsurf::Topology;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let level: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(5);
    let mesh = subsurf::io::read_path(path)?;
    let t = Instant::now();
    let mut topo = Topology::new(&mesh)?;
    println!("base topology: {:.2} ms", t.elapsed().as_secs_f64() * 1e3);
    for l in 1..=level {
        let t = Instant::now();
        let child = refine_topology(&topo);
        let t1 = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let s = level_stencils(&topo, &child);
        let t2 = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "level {l}: {} vertices; topology {t1:.2} ms, stencils {t2:.2} ms ({} entries)",
            child.num_vertices(),
            s.num_entries()
        );
        topo = child;
    }
    Ok(())
}
