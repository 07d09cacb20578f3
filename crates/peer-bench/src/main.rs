//! OpenSubdiv 3.5 and the Rust subdivision crates on one mesh, one level, in one process:
//! every peer's setup and per-frame time, medians of alternating runs, and each peer's
//! distance from OpenSubdiv's positions.
//!
//! ```text
//! cargo run --release --manifest-path crates/peer-bench/Cargo.toml -- [MESH.obj] [LEVELS] [RUNS] [--cpu]
//! ```
//!
//! LEVELS is a comma-separated list (default `3,4,5`), RUNS the number of alternating runs
//! (default 7); `--cpu` times the single-threaded runs in CPU time of the running thread, leaving
//! out time spent waiting for a core on a loaded machine (two-thread runs stay wall-clock). Setup is each peer's topology refinement plus the tables its per-frame path
//! reads; a frame is the last level's positions from new base positions, tables built, into a
//! buffer kept between frames; a one shot is setup, one frame into a fresh buffer and dropping
//! it all, timed together (OpenSubdiv's `StencilTable` path has none), in this process after
//! the other peers' runs; a cold one shot is the same in a fresh process per run (`--cold`),
//! every page new and no allocator state inherited from another peer, with the process's
//! peak resident memory. A last table gives subsurf's per-frame bytes per output vertex (a
//! lower bound), its frame against the same frame through every stored row, and memcpy's
//! bandwidth. OpenSubdiv, opensubdiv-rs and subdiv-kernels run on the calling
//! thread only; subsurf runs in a one-thread and a two-thread rayon pool, the latter's workers
//! bound one per core. Every thread allocates from one malloc arena (glibc), so no peer and no
//! pool starts from fresh pages that another reuses.

mod cold;
mod error;
mod peers;
mod traffic;

use std::time::Instant;

use osd_ref::{OsdMesh, OsdStencils};
use peers::{Kernels, Osd, OsdRs, OsdTable, Prepared, Subsurf};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Whether single-thread timings are CPU time of the running thread (`--cpu`).
static CPU_TIME: std::sync::OnceLock<bool> = std::sync::OnceLock::new();

/// CPU time of the calling thread in ms (`/proc/thread-self/schedstat`: nanoseconds on a
/// core, kernel time such as page faults included). Yielding first makes the kernel update it.
fn thread_cpu_ms() -> f64 {
    std::thread::yield_now();
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns / 1e6)
}

/// Time of single-threaded `f` in ms, and its result: thread CPU time with `--cpu`, else
/// wall-clock.
fn ms<T>(f: impl FnOnce() -> T) -> (f64, T) {
    if *CPU_TIME.get().unwrap_or(&false) {
        let t = thread_cpu_ms();
        let r = f();
        return (thread_cpu_ms() - t, r);
    }
    wall(f)
}

/// Wall-clock time of `f` in ms, and its result (the two-thread runs).
fn wall<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let t = Instant::now();
    let r = f();
    (t.elapsed().as_secs_f64() * 1e3, r)
}

/// One frame of a freshly set-up peer into a fresh buffer, then both dropped: a one-shot
/// refinement as a command-line run does it.
fn one_shot<P: Prepared>(mut p: P, base: &[[f32; 3]]) {
    let mut out = vec![[0.0; 3]; p.num_outputs()];
    p.frame(base, &mut out);
    drop(out);
    drop(p);
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

/// The peers, in table order.
const PEERS: [&str; 5] = [
    "OpenSubdiv 3.5 (PrimvarRefiner)",
    "OpenSubdiv 3.5 (StencilTable)",
    "opensubdiv-rs 0.5",
    "subdiv-kernels 0.1",
    "subsurf",
];
const SUBSURF: usize = 4;

/// Medians of one peer at one level (`None`: the peer has no multi-threaded path).
#[derive(Default)]
struct Row {
    setup: Vec<f64>,
    setup2: Vec<f64>,
    once: Vec<f64>,
    cold: Vec<f64>,
    peak: Vec<f64>,
    frame: Vec<f64>,
    frame2: Vec<f64>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // One malloc arena (see `osd_ref::one_malloc_arena`): without it the two-thread pool's
    // workers allocated from arenas of their own, and subsurf's two-thread setup alone faulted
    // in every page anew (at car level 3 it read 25.5 ms against 11.2 ms for one thread,
    // 10.9 ms with one arena).
    osd_ref::one_malloc_arena();
    let all: Vec<String> = std::env::args().skip(1).collect();
    CPU_TIME.get_or_init(|| all.iter().any(|a| a == "--cpu"));
    if let Some(i) = all.iter().position(|a| a == "--cold") {
        // A child of the harness: one cold one-shot (see `cold`).
        let arg = |k: usize| all.get(i + k).cloned().ok_or("--cold PEER LEVEL MESH");
        return cold::run_child(&arg(1)?, arg(2)?.parse()?, &arg(3)?);
    }
    let args: Vec<String> = all.into_iter().filter(|a| !a.starts_with("--")).collect();
    let default_mesh = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../testdata/shapes/catmark_car.obj"
    );
    let path = args
        .first()
        .filter(|s| !s.is_empty())
        .map_or(default_mesh, |s| s.as_str());
    let levels: Vec<usize> = match args.get(1).filter(|s| !s.is_empty()) {
        Some(s) => s.split(',').map(str::parse).collect::<Result<_, _>>()?,
        None => vec![3, 4, 5],
    };
    let runs: usize = args.get(2).map(|s| s.parse()).transpose()?.unwrap_or(7);
    if !osd_ref::available() {
        return Err("OpenSubdiv is not installed (apt-get install libosd-dev)".into());
    }
    if levels.contains(&0) {
        return Err("levels start at 1".into());
    }
    let mesh = subsurf::io::read_path(path)?;
    let osd_mesh = OsdMesh::from(&mesh);
    // Every single-threaded run on one core: the main thread (the C++ and Rust peers' frames)
    // and the one-thread pool's worker (setups, one shots, subsurf's frames) bound to CPU 0,
    // so that no peer's frame finds its tables in the other core's cache or migrates. Unbound,
    // the worker ran wherever the kernel put it: subsurf's level-3 frame read 0.46-0.94 ms
    // between processes (subdiv-kernels' 1.07-1.21 ms), bound 0.45-0.54 ms.
    // The cold one-shot processes inherit the binding.
    osd_ref::bind_to_cpu(0);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .start_handler(|_| osd_ref::bind_to_cpu(0))
        .build()?;
    // Each worker of the two-thread pool on a core of its own (see `osd_ref::bind_to_cpu`).
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .start_handler(osd_ref::bind_to_cpu)
        .build()?;
    let diag = subsurf::mesh::bbox_diagonal(&mesh.positions) as f64;
    println!(
        "{path}: {} faces, {} vertices; medians of {runs} alternating runs, {}; \
         load average {} at start",
        mesh.num_faces(),
        mesh.num_vertices(),
        if *CPU_TIME.get().unwrap_or(&false) {
            "1T in thread CPU time, 2T wall-clock"
        } else {
            "wall-clock"
        },
        load_average()
    );
    println!();
    println!("| level | peer | vertices | setup 1T (ms) | setup 2T (ms) | frame 1T (ms) | frame 2T (ms) | setup / subsurf 1T | frame / subsurf 1T | one shot 1T (ms) | one shot / subsurf 1T | cold one shot 1T (ms) | cold / subsurf 1T | cold peak RSS (MiB) | max error vs OpenSubdiv (of bbox diagonal) |");
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    // Each frame refines these base positions, moved a little per run so no frame repeats.
    let frame_base = |run: usize| -> Vec<[f32; 3]> {
        let s = 1.0 + run as f32 * 1e-3;
        mesh.positions.iter().map(|p| p.map(|c| c * s)).collect()
    };
    let mut traffic_lines = Vec::new();
    for &level in &levels {
        let mut rows: Vec<Row> = (0..PEERS.len()).map(|_| Row::default()).collect();
        // Setup, alternating peer by peer within each run. Every single-threaded run happens
        // on the one-thread pool's worker, so that all peers allocate from the same malloc
        // arena and each reuses the pages the others freed alike (OpenSubdiv on the main
        // thread and subsurf on the worker would not: see the README's peer table).
        let on1 = |f: &(dyn Fn() -> f64 + Sync)| one.install(f);
        for _ in 0..runs {
            rows[0]
                .setup
                .push(on1(&|| ms(|| Osd::setup(&osd_mesh, level)).0));
            rows[1].setup.push(on1(&|| {
                ms(|| {
                    let r = Osd::setup(&osd_mesh, level);
                    OsdStencils::new(&r.0).expect("OpenSubdiv stencils")
                })
                .0
            }));
            rows[2]
                .setup
                .push(on1(&|| ms(|| OsdRs::setup(&mesh, level)).0));
            rows[3]
                .setup
                .push(on1(&|| ms(|| Kernels::setup(&mesh, level)).0));
            rows[SUBSURF]
                .setup
                .push(on1(&|| ms(|| Subsurf::setup(&mesh, level)).0));
            rows[SUBSURF]
                .setup2
                .push(two.install(|| wall(|| Subsurf::setup(&mesh, level)).0));
            // One shot: setup, one frame into a fresh buffer, everything dropped, all timed.
            let base = &mesh.positions;
            rows[0].once.push(on1(&|| {
                ms(|| one_shot(Osd::setup(&osd_mesh, level), base)).0
            }));
            rows[2]
                .once
                .push(on1(&|| ms(|| one_shot(OsdRs::setup(&mesh, level), base)).0));
            rows[3].once.push(on1(&|| {
                ms(|| one_shot(Kernels::setup(&mesh, level), base)).0
            }));
            rows[SUBSURF].once.push(on1(&|| {
                ms(|| one_shot(Subsurf::setup(&mesh, level), base)).0
            }));
            // Cold one shots, each in a fresh process.
            for (name, i) in cold::COLD_PEERS {
                let (t, peak) = cold::cold(name, level, path, *CPU_TIME.get().unwrap_or(&false))?;
                rows[i].cold.push(t);
                rows[i].peak.push(peak);
            }
        }
        // Frames, tables built once.
        let osd = Osd::setup(&osd_mesh, level);
        let table = OsdTable(OsdStencils::new(&osd.0)?);
        let mut peers: Vec<Box<dyn Prepared>> = vec![
            Box::new(osd),
            Box::new(table),
            Box::new(OsdRs::setup(&mesh, level)),
            Box::new(Kernels::setup(&mesh, level)),
        ];
        // subsurf is kept apart: it runs inside the rayon pools, which need `Send`.
        let mut ours = one.install(|| Subsurf::setup(&mesh, level));
        let mut outs: Vec<Vec<[f32; 3]>> = peers
            .iter()
            .map(|p| vec![[0.0; 3]; p.num_outputs()])
            .collect();
        outs.push(vec![[0.0; 3]; ours.num_outputs()]);
        let (mut stored, mut stored_scratch) = (Vec::new(), Vec::new());
        let mut stored_out = vec![[0.0f32; 3]; ours.num_outputs()];
        for run in 0..runs {
            let base = frame_base(run);
            let t = one.install(|| {
                ms(|| {
                    traffic::stored_rows_frame(
                        &ours.refiner,
                        &base,
                        &mut stored_out,
                        &mut stored_scratch,
                    )
                })
                .0
            });
            stored.push(t);
            for (i, p) in peers.iter_mut().enumerate() {
                let out = &mut outs[i];
                rows[i].frame.push(ms(|| p.frame(&base, out)).0);
            }
            let out = &mut outs[SUBSURF];
            let t = one.install(|| ms(|| ours.frame(&base, out)).0);
            rows[SUBSURF].frame.push(t);
            let t = two.install(|| wall(|| ours.frame(&base, out)).0);
            rows[SUBSURF].frame2.push(t);
        }
        let (plan_b, table_b) = traffic::frame_bytes(&ours.refiner);
        let n_out = outs[SUBSURF].len() as f64;
        let f1 = median(rows[SUBSURF].frame.clone());
        let f2 = median(rows[SUBSURF].frame2.clone());
        let copy = traffic::memcpy_gbps(plan_b / 2, runs);
        assert_eq!(
            stored_out, outs[SUBSURF],
            "the stored rows give the plan's values"
        );
        let fs = median(stored);
        traffic_lines.push(format!(
            "| {level} | {:.1} | {:.1} | {f1:.2} | {fs:.2} | {:.2}x | {:.2} | {:.2} | {copy:.2} |",
            plan_b as f64 / n_out,
            table_b as f64 / n_out,
            fs / f1,
            plan_b as f64 / f1 / 1e6,
            plan_b as f64 / f2 / 1e6,
        ));
        // Errors: every peer's last frame against OpenSubdiv's (PrimvarRefiner) of the same base.
        let want = outs[0].clone();
        let s_once = median(rows[SUBSURF].once.clone());
        let s_cold = median(rows[SUBSURF].cold.clone());
        let (s_setup, s_frame) = (
            median(rows[SUBSURF].setup.clone()),
            median(rows[SUBSURF].frame.clone()),
        );
        for (i, row) in rows.into_iter().enumerate() {
            let d = error::distance(&want, &outs[i], 1e-4 * diag);
            let opt = |v: Vec<f64>| {
                if v.is_empty() {
                    "—".to_string()
                } else {
                    format!("{:.2}", median(v))
                }
            };
            let (setup, frame) = (median(row.setup.clone()), median(row.frame.clone()));
            let err = if i == 0 {
                "reference".to_string()
            } else {
                format!(
                    "{:.1e} ({:.1e}){}",
                    d.max,
                    d.max / diag,
                    if d.same_order {
                        ""
                    } else {
                        ", other vertex order: to nearest"
                    }
                )
            };
            println!(
                "| {level} | {} | {} | {setup:.2} | {} | {frame:.2} | {} | {:.2}x | {:.2}x | {} | {} | {} | {} | {} | {err} |",
                PEERS[i],
                outs[i].len(),
                opt(row.setup2),
                opt(row.frame2),
                setup / s_setup,
                frame / s_frame,
                opt(row.once.clone()),
                if row.once.is_empty() {
                    "—".to_string()
                } else {
                    format!("{:.2}x", median(row.once) / s_once)
                },
                opt(row.cold.clone()),
                if row.cold.is_empty() {
                    "—".to_string()
                } else {
                    format!("{:.2}x", median(row.cold) / s_cold)
                },
                if row.peak.is_empty() {
                    "—".to_string()
                } else {
                    format!("{:.0}", median(row.peak))
                },
            );
        }
    }
    println!();
    println!("subsurf frame traffic (lower bound: indices read, each value read and written once; memcpy of a buffer half that size, read + write):");
    println!();
    println!("| level | bytes / output vertex (smooth plan) | bytes / output vertex (stored rows) | frame 1T (ms) | stored rows 1T (ms) | stored / plan | frame 1T GB/s | frame 2T GB/s | memcpy GB/s |");
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for l in &traffic_lines {
        println!("{l}");
    }
    println!();
    println!("load average {} at end", load_average());
    Ok(())
}
