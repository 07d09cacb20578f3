//! Peak memory of the Loop limit surface, OpenSubdiv 3.5 against subsurf, one side per
//! process (run each side in a fresh process, alternately):
//!
//! ```text
//! cargo run --release -p osd-ref --example loop_memory -- MESH.obj LEVEL osd|subsurf|subsurf-f64
//! ```
//!
//! A mesh with faces other than triangles is fan-triangulated with its tags
//! ([`osd_ref::fan_triangulated_loop`]). `osd`: `TopologyRefiner::RefineAdaptive`,
//! `PatchTableFactory::Create` (default options, Gregory-triangle end caps), the patch map and
//! the points of every level and end cap; `subsurf`: `LoopLimit::new` (the sparse levels,
//! every patch with its points, the patch map), `subsurf-f64`: `LoopLimit::new_f64` (the
//! points refined in `f64`, as `eval` refines a file's digits that `f32` cannot hold). Prints the patch counts, the time and the
//! process's peak resident memory (`VmHWM`).

/// With `--features mimalloc`, subsurf's allocations use mimalloc, as the `subsurf` CLI's do
/// (OpenSubdiv's go through C++ `new`).
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use osd_ref::{patch_stats, EndCap, OsdMesh, PatchOptions};
use std::time::Instant;
use subsurf::limit::LoopLimit;
use subsurf::{Scheme, Topology};

fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            let l = s.lines().find(|l| l.starts_with("VmHWM:"))?.to_owned();
            l.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path, level, side] = args.as_slice() else {
        return Err("usage: loop_memory MESH.obj LEVEL osd|subsurf|subsurf-f64".into());
    };
    let level: u32 = level.parse()?;
    let mut mesh = subsurf::io::read_path(path)?;
    if mesh.options.scheme != Scheme::Loop || mesh.face_counts.iter().any(|&n| n != 3) {
        mesh = osd_ref::fan_triangulated_loop(&mesh);
    }
    mesh.uvs = None;
    let before = peak_rss_mib();
    let t = Instant::now();
    let (regular, irregular) = match side.as_str() {
        "osd" => {
            let o = PatchOptions {
                isolation_level: level,
                end_cap: EndCap::Gregory,
                ..Default::default()
            };
            let s = patch_stats(&OsdMesh::from(&mesh), &o)?;
            (s.num_regular_patches, s.num_patches - s.num_regular_patches)
        }
        "subsurf" | "subsurf-f64" => {
            let topo = Topology::new(&mesh)?;
            let l = match side.as_str() {
                "subsurf" => LoopLimit::new(&topo, &mesh.positions, level)?,
                _ => LoopLimit::new_f64(&topo, &mesh.positions, level)?,
            };
            let regular = l.patches.iter().filter(|p| p.regular).count();
            (regular, l.patches.len() - regular)
        }
        _ => return Err(format!("unknown side {side}").into()),
    };
    let ms = t.elapsed().as_secs_f64() * 1e3;
    let name = path.rsplit('/').next().unwrap_or(path);
    println!(
        "{name} ({} triangles) isolation {level} {side}: {regular} regular + {irregular} end caps, \
         {ms:.0} ms, peak RSS {:.1} MiB (mesh loaded: {before:.1} MiB)",
        mesh.face_counts.len(),
        peak_rss_mib()
    );
    Ok(())
}
