//! OpenSubdiv 3.5 and subsurf refining the same mesh in one process, alternately, so that the
//! ratio of their medians comes from one run on one machine.
//!
//! ```text
//! cargo run --release -p osd-ref --example side_by_side -- [MESH.obj] [LEVELS] [RUNS]
//! cargo run --release -p osd-ref --example side_by_side -- MESH.obj 5 5 --memory osd|subsurf|once [--lean]
//! ```
//!
//! Two tables, like against like: "full", where both build the last level's full topology
//! (OpenSubdiv `fullTopologyInLastLevel = true`, subsurf `Refiner::new`), and "lean", where
//! both build only what interpolation and output need there (OpenSubdiv's default
//! `fullTopologyInLastLevel = false`, subsurf `RefineOptions::lean`). `--full` or `--lean`
//! prints one of them only.
//!
//! (a) topology + positions: OpenSubdiv `TopologyRefinerFactory::Create` + `RefineUniform` +
//!     `PrimvarRefiner::Interpolate` on every level, versus `Refiner::new` + `refine_positions`
//!     (which also builds and keeps every step's stencil tables, for (b)), and versus
//!     `refine::refine_once` ("once": the same rows evaluated as they are formed, no table
//!     kept — how `PrimvarRefiner` interpolates).
//! (b) positions only, tables prebuilt: `PrimvarRefiner::Interpolate` (and `StencilTable::
//!     UpdateValues`) versus applying subsurf's per-level stencils (and its composed table).
//!
//! subsurf runs single-threaded (a one-thread rayon pool, where OpenSubdiv's (a) runs too) and
//! on all cores (workers bound one per core, `osd_ref::bind_to_cpu`); every thread allocates
//! from one malloc arena (`osd_ref::one_malloc_arena`). `--memory` runs one
//! side once (subsurf single-threaded) in this fresh process and prints its time and the
//! process's peak resident memory: run alternately from a shell, it times cold one-shot
//! refinements, whose pages are all new, free of the allocator state one side leaves the other. `--cpu` times the single-threaded
//! runs (OpenSubdiv and subsurf 1T) in CPU time of the running thread, so that time spent
//! waiting for a core on a loaded machine is left out; multi-threaded runs stay wall-clock.

use osd_ref::{OsdMesh, OsdRefiner, OsdStencils};

/// With `--features mimalloc`, subsurf's allocations (not OpenSubdiv's, which go through C++
/// `new`) use mimalloc, which reuses freed pages instead of returning them to the kernel.
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use std::time::Instant;
use subsurf::refine::refine_once;
use subsurf::{Mesh, RefineOptions, Refiner, Topology};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Whether single-thread timings are CPU time of the running thread (`--cpu`) rather than
/// wall-clock time: on a loaded machine, time spent waiting for a core is left out.
static CPU_TIME: std::sync::OnceLock<bool> = std::sync::OnceLock::new();

/// CPU time of the calling thread in ms (`/proc/thread-self/schedstat`, nanoseconds on a core).
/// The kernel updates that figure at scheduler ticks and switches; yielding first forces an
/// update, so short runs are not rounded to a tick.
fn thread_cpu_ms() -> f64 {
    std::thread::yield_now();
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map(|ns| ns / 1e6)
        .unwrap_or(f64::NAN)
}

/// Time of `f` in ms: thread CPU time with `--cpu`, else wall-clock.
fn ms<T>(f: impl FnOnce() -> T) -> (f64, T) {
    if *CPU_TIME.get().unwrap_or(&false) {
        let t = thread_cpu_ms();
        let r = f();
        return (thread_cpu_ms() - t, r);
    }
    wall(f)
}

/// Wall-clock time of `f` in ms (multi-threaded runs).
fn wall<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let t = Instant::now();
    let r = f();
    (t.elapsed().as_secs_f64() * 1e3, r)
}

fn peak_rss_mib() -> f64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse::<f64>().ok())
        .map(|kb| kb / 1024.0)
        .unwrap_or(f64::NAN)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    osd_ref::one_malloc_arena();
    // The all-core runs' workers one per core (see `osd_ref::bind_to_cpu`).
    rayon::ThreadPoolBuilder::new()
        .start_handler(osd_ref::bind_to_cpu)
        .build_global()?;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let default_mesh = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../testdata/shapes/catmark_car.obj"
    )
    .to_string();
    let path = args.first().cloned().unwrap_or(default_mesh);
    let levels: Vec<usize> = match args.get(1).filter(|s| !s.is_empty()) {
        Some(s) => vec![s.parse()?],
        None => vec![3, 4, 5],
    };
    CPU_TIME.get_or_init(|| args.iter().any(|a| a == "--cpu"));
    let runs: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(7);
    let memory = args
        .iter()
        .position(|a| a == "--memory")
        .and_then(|i| args.get(i + 1))
        .cloned();
    if !osd_ref::available() {
        return Err("OpenSubdiv is not installed (apt-get install libosd-dev)".into());
    }
    let mesh = subsurf::io::read_path(&path)?;
    let osd_mesh = OsdMesh::from(&mesh);
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;

    let modes: Vec<bool> = if args.iter().any(|a| a == "--lean") {
        vec![true]
    } else if args.iter().any(|a| a == "--full") {
        vec![false]
    } else {
        vec![false, true]
    };
    if let Some(side) = memory {
        // One refinement in a fresh process: every page it touches is new, as in a CLI run.
        let level = levels[0];
        let lean = modes[0];
        let options = if lean {
            RefineOptions::lean()
        } else {
            RefineOptions::default()
        };
        let (what, (t, n)) = match side.as_str() {
            "osd" => (
                "OpenSubdiv",
                ms(|| {
                    let r = OsdRefiner::with_last_level(&osd_mesh, level, !lean).unwrap();
                    r.interpolate(&mesh.positions).unwrap().len()
                }),
            ),
            "once" => (
                "subsurf refine_once",
                one.install(|| {
                    ms(|| {
                        let t = Topology::new(&mesh).unwrap();
                        refine_once(t, level, &mesh.positions, options)
                            .unwrap()
                            .1
                            .len()
                    })
                }),
            ),
            _ => (
                "subsurf",
                one.install(|| {
                    ms(|| {
                        let r = refiner(&mesh, level, lean).unwrap();
                        r.refine_positions(&mesh.positions).len()
                    })
                }),
            ),
        };
        println!(
            "{what} level {level}: {n} vertices, {t:.2} ms, peak RSS {:.1} MiB",
            peak_rss_mib()
        );
        return Ok(());
    }

    println!(
        "{path}: {} faces; medians of {runs} alternating runs; subsurf on 1 thread unless noted",
        mesh.num_faces()
    );
    for lean in modes {
        table(&mesh, &osd_mesh, &levels, runs, lean, &one)?;
    }
    Ok(())
}

/// subsurf's refiner of `mesh` to `level`, with a lean or a full last level.
fn refiner(mesh: &Mesh, level: usize, lean: bool) -> subsurf::Result<Refiner> {
    let options = if lean {
        RefineOptions::lean()
    } else {
        RefineOptions::default()
    };
    Refiner::with_options(Topology::new(mesh)?, level, options)
}

/// One table: every level, (a) and (b), with a full or a lean last level on both sides.
fn table(
    mesh: &Mesh,
    osd_mesh: &OsdMesh,
    levels: &[usize],
    runs: usize,
    lean: bool,
    one: &rayon::ThreadPool,
) -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "\n{} last level ({})\n",
        if lean { "Lean" } else { "Full" },
        if lean {
            "OpenSubdiv fullTopologyInLastLevel = false, subsurf RefineOptions::lean()"
        } else {
            "OpenSubdiv fullTopologyInLastLevel = true, subsurf Refiner::new"
        }
    );
    let n = rayon::current_num_threads();
    println!("| level | vertices | OSD topo+pos (ms) | subsurf 1T (ms) | ratio | subsurf {n}T (ms) | ratio | subsurf once 1T (ms) | ratio | subsurf once {n}T (ms) | ratio | OSD pos (ms) | subsurf pos 1T (ms) | ratio | subsurf pos {n}T (ms) | OSD stencils (ms) | subsurf composed 1T (ms) |");
    println!(
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    let options = if lean {
        RefineOptions::lean()
    } else {
        RefineOptions::default()
    };
    for &level in levels {
        let once = || {
            refine_once(
                Topology::new(mesh).unwrap(),
                level,
                &mesh.positions,
                options,
            )
            .unwrap()
        };
        let (mut oa, mut sa, mut pa) = (Vec::new(), Vec::new(), Vec::new());
        let (mut sc, mut pc) = (Vec::new(), Vec::new());
        let mut nverts = 0;
        for _ in 0..runs {
            // On the same worker as subsurf 1T, allocating from the same heap.
            let (t, p) = one.install(|| {
                ms(|| {
                    let r = OsdRefiner::with_last_level(osd_mesh, level, !lean).unwrap();
                    r.interpolate(&mesh.positions).unwrap()
                })
            });
            oa.push(t);
            nverts = p.len();
            drop(p);
            let (t, _) = one.install(|| {
                ms(|| {
                    let r = refiner(mesh, level, lean).unwrap();
                    r.refine_positions(&mesh.positions)
                })
            });
            sa.push(t);
            let (t, _) = wall(|| {
                let r = refiner(mesh, level, lean).unwrap();
                r.refine_positions(&mesh.positions)
            });
            pa.push(t);
            sc.push(one.install(|| ms(once).0));
            pc.push(wall(once).0);
        }
        let (sc, pc) = (median(sc), median(pc));
        let osd = OsdRefiner::with_last_level(osd_mesh, level, !lean)?;
        let osd_st = OsdStencils::new(&osd)?;
        let ours = refiner(mesh, level, lean)?;
        let table = ours.stencil_table();
        let (mut ob, mut sb, mut pb, mut os, mut ss) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut out = vec![[0.0f32; 3]; table.num_rows()];
        for _ in 0..runs {
            ob.push(ms(|| osd.interpolate(&mesh.positions).unwrap()).0);
            sb.push(one.install(|| ms(|| ours.refine_positions(&mesh.positions)).0));
            pb.push(wall(|| ours.refine_positions(&mesh.positions)).0);
            os.push(ms(|| osd_st.update(&mesh.positions).unwrap()).0);
            ss.push(one.install(|| ms(|| table.apply_serial(&mesh.positions, &mut out)).0));
        }
        let (oa, sa, pa, ob, sb, pb, os, ss) = (
            median(oa),
            median(sa),
            median(pa),
            median(ob),
            median(sb),
            median(pb),
            median(os),
            median(ss),
        );
        println!(
            "| {level} | {nverts} | {oa:.1} | {sa:.1} | {:.2}x | {pa:.1} | {:.2}x | {sc:.1} | {:.2}x | {pc:.1} | {:.2}x | {ob:.2} | {sb:.2} | {:.2}x | {pb:.2} | {os:.2} | {ss:.2} |",
            oa / sa, oa / pa, oa / sc, oa / pc, ob / sb
        );
    }
    Ok(())
}
