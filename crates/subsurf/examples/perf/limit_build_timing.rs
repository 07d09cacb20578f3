//! Patch-table construction time against the isolation level: subsurf's sparse
//! feature-adaptive construction next to OpenSubdiv 3.5's (`TopologyRefiner` creation,
//! `RefineAdaptive`, `PatchTableFactory::Create`; Gregory end caps, single-crease patches),
//! and, for reference, the uniform refinement to the same level that the construction
//! replaced.
//!
//! `cargo run --release -p subsurf --example limit_build_timing [-- FILE RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, 21 runs). Prints a markdown table of medians; the runs
//! of the two libraries alternate, so that both see the same machine load.
//! subsurf's time includes `Topology::new`, as OpenSubdiv's includes its refiner's creation;
//! it is measured on all threads and on one (OpenSubdiv's construction is serial).

mod common;

use std::time::Instant;

use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdOptions};
use subsurf::limit::{PatchOptions, PatchTable};
use subsurf::refine::Refiner;
use subsurf::Topology;

fn time_ms<T>(f: impl FnOnce() -> T) -> f64 {
    let t = Instant::now();
    std::hint::black_box(f());
    t.elapsed().as_secs_f64() * 1e3
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let runs: usize = common::arg(&args, 2, 21).max(1);
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
        let oo = OsdOptions {
            isolation_level: level,
            use_single_crease: true,
            use_inf_sharp: false,
            end_cap: EndCap::Gregory,
        };
        let table = build();
        let osd_build = osd_ref::patch_table_only(&osd_mesh, &oo);
        // The three measurements alternate run by run, so that they share the machine's load;
        // each starts after a pause in which the idle rayon workers of the previous one stop
        // spinning (they would otherwise take a core from the next measurement).
        let settle = || std::thread::sleep(std::time::Duration::from_millis(5));
        let (mut ours, mut ours1, mut theirs) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..runs {
            settle();
            ours.push(time_ms(build));
            settle();
            ours1.push(serial.install(|| time_ms(build)));
            if osd_build.is_ok() {
                settle();
                theirs.push(time_ms(|| osd_ref::patch_table_only(&osd_mesh, &oo)));
            }
        }
        let (ms, ms1) = (common::median(&mut ours), common::median(&mut ours1));
        let osd = match &osd_build {
            Ok(b) => (
                format!("{:.1}", common::median(&mut theirs)),
                b.num_patches.to_string(),
                b.num_refined_vertices.to_string(),
            ),
            Err(e) => (format!("({e})"), "-".into(), "-".into()),
        };
        // Uniform refinement (topology and stencils), what the construction used to cost at
        // least; skipped where it would not fit in memory.
        let uniform = if level <= 5 {
            let mut t: Vec<f64> = (0..runs.min(3))
                .map(|_| time_ms(|| Refiner::new(topo.clone(), level as usize)))
                .collect();
            format!("{:.0}", common::median(&mut t))
        } else {
            "-".into()
        };
        println!(
            "| {level} | {ms:.1} | {ms1:.1} | {} | {} | {} | {} | {} | {uniform} |",
            osd.0,
            table.num_patches(),
            osd.1,
            table.level_offsets().last().copied().unwrap_or(0),
            osd.2,
        );
    }
    Ok(())
}
