//! One side only, repeated, for `perf stat` and callgrind:
//! `refine_loop MESH LEVEL RUNS osd|subsurf|once [pos|lean]...` (`pos`: positions only, tables
//! built once before the loop; `lean`: a lean last level on both sides; `once`: subsurf's
//! `refine_once`; subsurf on one thread).
use osd_ref::{OsdMesh, OsdRefiner};
use subsurf::refine::refine_once;
use subsurf::{RefineOptions, Refiner, Topology};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<String> = std::env::args().collect();
    let mesh = subsurf::io::read_path(&a[1])?;
    let level: usize = a[2].parse()?;
    let runs: usize = a[3].parse()?;
    let side = a[4].as_str();
    let pos = a[5..].iter().any(|s| s == "pos");
    let lean = a[5..].iter().any(|s| s == "lean");
    let options = if lean {
        RefineOptions::lean()
    } else {
        RefineOptions::default()
    };
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let om = OsdMesh::from(&mesh);
    let t = std::time::Instant::now();
    if pos {
        if side == "osd" {
            let r = OsdRefiner::with_last_level(&om, level, !lean)?;
            for _ in 0..runs {
                std::hint::black_box(r.interpolate(&mesh.positions)?);
            }
        } else {
            let r = Refiner::with_options(Topology::new(&mesh)?, level, options)?;
            for _ in 0..runs {
                std::hint::black_box(one.install(|| r.refine_positions(&mesh.positions)));
            }
        }
    } else {
        for _ in 0..runs {
            match side {
                "osd" => {
                    let r = OsdRefiner::with_last_level(&om, level, !lean)?;
                    std::hint::black_box(r.interpolate(&mesh.positions)?);
                }
                "once" => {
                    std::hint::black_box(one.install(|| {
                        refine_once(
                            Topology::new(&mesh).unwrap(),
                            level,
                            &mesh.positions,
                            options,
                        )
                        .unwrap()
                    }));
                }
                _ => {
                    std::hint::black_box(one.install(|| {
                        let r =
                            Refiner::with_options(Topology::new(&mesh).unwrap(), level, options)
                                .unwrap();
                        r.refine_positions(&mesh.positions)
                    }));
                }
            }
        }
    }
    eprintln!(
        "wall {:.1} ms per run",
        t.elapsed().as_secs_f64() * 1e3 / runs as f64
    );
    Ok(())
}
