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
    let runs: usize = common::arg(&args, 3, 10);
    let mut sweep = args
        .get(4)
        .is_some_and(|a| a == "cold")
        .then(common::Sweep::new);
    let mesh = subsurf::io::read_path(path)?;
    let topo = Topology::new(&mesh)?;
    let mut table = PatchTable::build(&topo, &PatchOptions::default())?;
    let edits = |s: Option<f32>| -> Vec<SharpnessEdit> { SharpnessEdit::creases(&mesh.creases, s) };
    table.apply_sharpness(&edits(from))?;
    let mut outcomes = Vec::new();
    for _ in 0..runs {
        for s in [Some(3.5), from] {
            sweep.iter_mut().for_each(common::Sweep::run);
            let o = table.apply_sharpness(&edits(s))?;
            if !outcomes.contains(&o) {
                outcomes.push(o);
            }
        }
    }
    println!("{outcomes:?}");
    Ok(())
}
