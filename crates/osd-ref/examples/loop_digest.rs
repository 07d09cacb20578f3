//! A digest of everything subsurf's Loop refinement produces for a mesh (last level's tables,
//! composed stencils, limit stencils, positions, `refine_once`'s level), full and lean, to
//! check that a change to the refinement code keeps every result bit-identical:
//! `loop_digest MESH...` prints one line per mesh, level and mode.
use std::hash::{Hash, Hasher};
use subsurf::refine::refine_once;
use subsurf::{RefineOptions, Refiner, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for path in std::env::args().skip(1) {
        let mesh = subsurf::io::read_path(&path)?;
        for level in 1..=4 {
            for lean in [false, true] {
                let options = if lean {
                    RefineOptions::lean()
                } else {
                    RefineOptions::default()
                };
                let mut h = std::collections::hash_map::DefaultHasher::new();
                let r = Refiner::with_options(Topology::new(&mesh)?, level, options)?;
                format!("{:?}", r.last()).hash(&mut h);
                format!("{:?}", r.stencil_table()).hash(&mut h);
                let p = r.refine_positions(&mesh.positions);
                for x in p.iter().flatten() {
                    x.to_bits().hash(&mut h);
                }
                if !lean {
                    format!("{:?}", r.limit_table()).hash(&mut h);
                }
                let (t, q) = refine_once(Topology::new(&mesh)?, level, &mesh.positions, options)?;
                format!("{t:?}").hash(&mut h);
                for x in q.iter().flatten() {
                    x.to_bits().hash(&mut h);
                }
                let name = path.rsplit('/').next().unwrap_or(&path);
                println!(
                    "{name} {level} {} {:016x}",
                    if lean { "lean" } else { "full" },
                    h.finish()
                );
            }
        }
    }
    Ok(())
}
