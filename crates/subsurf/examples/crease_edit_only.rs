//! Crease edits only (for profiling `PatchTable::apply_sharpness`): every crease of a mesh
//! moved from `A` to 3.5 and back `RUNS` times after one untimed first edit.
//!
//! `cargo run --release -p subsurf --example crease_edit_only [-- FILE A RUNS [cold]]`
//! (default `testdata/shapes/catmark_car.obj`, `A` = `own` (the mesh's values), 10 runs;
//! `cold`: the caches evicted before each edit by a 256 MB sweep, as a slider's evaluation
//! and drawing between edits do).

mod common;

use subsurf::limit::{PatchOptions, PatchTable, SharpnessEdit};
use subsurf::Topology;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let from: Option<f32> = args.get(2).and_then(|s| s.parse().ok());
    let runs: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(10);
    let mut sweep = vec![
        0u64;
        if args.get(4).is_some_and(|a| a == "cold") {
            32 << 20
        } else {
            0
        }
    ];
    let mesh = subsurf::io::read_path(path)?;
    let topo = Topology::new(&mesh)?;
    let mut table = PatchTable::build(&topo, &PatchOptions::default())?;
    let edits = |s: Option<f32>| -> Vec<SharpnessEdit> { SharpnessEdit::creases(&mesh.creases, s) };
    table.apply_sharpness(&edits(from))?;
    let mut outcomes = Vec::new();
    for _ in 0..runs {
        for s in [Some(3.5), from] {
            for (i, x) in sweep.iter_mut().enumerate().step_by(8) {
                *x = x.wrapping_add(i as u64);
            }
            std::hint::black_box(&sweep);
            let o = table.apply_sharpness(&edits(s))?;
            if !outcomes.contains(&o) {
                outcomes.push(o);
            }
        }
    }
    println!("{outcomes:?}");
    Ok(())
}
