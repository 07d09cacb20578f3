//! One side only, repeated, for `perf stat`: `refine_loop MESH LEVEL RUNS osd|subsurf [pos]`
//! (`pos`: positions only, tables built once before the loop; subsurf on one thread).
use osd_ref::{OsdMesh, OsdRefiner};
use subsurf::{Refiner, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<String> = std::env::args().collect();
    let mesh = subsurf::io::read_path(&a[1])?;
    let level: usize = a[2].parse()?;
    let runs: usize = a[3].parse()?;
    let osd = a[4] == "osd";
    let pos = a.get(5).is_some_and(|s| s == "pos");
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let om = OsdMesh::from(&mesh);
    let t = std::time::Instant::now();
    if pos {
        if osd {
            let r = OsdRefiner::new(&om, level)?;
            for _ in 0..runs {
                std::hint::black_box(r.interpolate(&mesh.positions)?);
            }
        } else {
            let r = Refiner::new(Topology::new(&mesh)?, level)?;
            for _ in 0..runs {
                std::hint::black_box(one.install(|| r.refine_positions(&mesh.positions)));
            }
        }
    } else {
        for _ in 0..runs {
            if osd {
                let r = OsdRefiner::new(&om, level)?;
                std::hint::black_box(r.interpolate(&mesh.positions)?);
            } else {
                std::hint::black_box(one.install(|| {
                    let r = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
                    r.refine_positions(&mesh.positions)
                }));
            }
        }
    }
    eprintln!(
        "wall {:.1} ms per run",
        t.elapsed().as_secs_f64() * 1e3 / runs as f64
    );
    Ok(())
}
