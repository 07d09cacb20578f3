//! Patch-table construction time against the isolation level: subsurf's sparse
//! feature-adaptive construction next to OpenSubdiv 3.5's (`TopologyRefiner` creation,
//! `RefineAdaptive`, `PatchTableFactory::Create`; Gregory end caps, single-crease patches),
//! and, for reference, the uniform refinement to the same level that the construction
//! replaced.
//!
//! `cargo run --release -p subsurf --example limit_build_timing [-- FILE RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, 7 runs). Prints a markdown table of medians.
//! subsurf's time includes `Topology::new`, as OpenSubdiv's includes its refiner's creation;
//! it is measured on all threads and on one (OpenSubdiv's construction is serial).

use std::time::Instant;

use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdOptions};
use subsurf::limit::{PatchOptions, PatchTable};
use subsurf::refine::Refiner;
use subsurf::Topology;

fn median_ms<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut out = f(); // warm-up
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            out = f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], out)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .map(String::as_str)
        .unwrap_or("testdata/shapes/catmark_car.obj");
    let runs: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(7).max(1);
    let mesh = subsurf::io::read_path(path)?;
    let topo = Topology::new(&mesh)?;
    let osd_mesh = OsdMesh::from(&mesh);
    let serial = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    println!(
        "{path}: {} faces; medians of {runs} runs; {} threads\n",
        mesh.num_faces(),
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    println!(
        "| isolation | subsurf build ms | subsurf build ms, 1 thread | OpenSubdiv build ms \
         | subsurf patches | OpenSubdiv patches | subsurf refined vertices \
         | OpenSubdiv refined vertices | uniform refinement ms |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for level in 1..=10u32 {
        let o = PatchOptions {
            isolation_level: level,
            single_crease: true,
            cap_crease_sharpness: true,
        };
        let build = || {
            let t = Topology::new(&mesh).expect("topology");
            PatchTable::build(&t, &o).expect("patch table")
        };
        let (ms, table) = median_ms(runs, build);
        let (ms1, _) = serial.install(|| median_ms(runs, build));
        let oo = OsdOptions {
            isolation_level: level,
            use_single_crease: true,
            use_inf_sharp: false,
            end_cap: EndCap::Gregory,
        };
        let osd = match osd_ref::patch_table_only(&osd_mesh, &oo) {
            Ok(_) => {
                let (t, b) = median_ms(runs, || osd_ref::patch_table_only(&osd_mesh, &oo));
                let b = b?;
                (
                    format!("{t:.1}"),
                    b.num_patches.to_string(),
                    b.num_refined_vertices.to_string(),
                )
            }
            Err(e) => (format!("({e})"), "-".into(), "-".into()),
        };
        // Uniform refinement (topology and stencils), what the construction used to cost at
        // least; skipped where it would not fit in memory.
        let uniform = if level <= 5 {
            let (t, _) = median_ms(runs.min(3), || Refiner::new(topo.clone(), level as usize));
            format!("{t:.0}")
        } else {
            "-".into()
        };
        println!(
            "| {level} | {ms:.1} | {ms1:.1} | {} | {} | {} | {} | {} | {uniform} |",
            osd.0,
            table.num_patches(),
            osd.1,
            table.level_offsets.last().copied().unwrap_or(0),
            osd.2,
        );
    }
    Ok(())
}
