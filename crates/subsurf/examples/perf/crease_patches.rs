//! Single-crease patches keep the patch table small however sharp the creases are
//! (Nießner, Loop & Greiner 2012): on `catmark_car` with every crease set to sharpness
//! `s = 1..10`, subsurf's table (isolation 4, single-crease patches, exact sharpness) next to
//! OpenSubdiv's feature-adaptive table without single-crease patches, isolated to the level
//! the creases need (`max(4, ⌈s⌉)`, 10 for infinitely sharp ones).
//!
//! `cargo run --release --example crease_patches [-- FILE N]` (N = samples per ptex side for
//! the tessellation timing, default 9). Prints a markdown table. OpenSubdiv's timing is
//! `eval_limit_grid_with` (adaptive refinement, patch table, N × N grid per ptex face,
//! serial), subsurf's is `PatchTable::build` + points, then `tessellate(N)` (parallel).

mod common;

use std::time::Instant;

use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdOptions};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::Topology;

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(9);
    let base = subsurf::io::read_path(path)?;
    println!(
        "{path}: {} faces, {} creases; tessellation {n} samples per ptex side\n",
        base.num_faces(),
        base.creases.len()
    );
    println!(
        "| s | subsurf patches (reg/crease/Gregory) | subsurf bytes | build ms | tessellate ms \
         | OSD level | OSD patches | OSD bytes | OSD build+grid ms |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for s in 1..=10 {
        let mut mesh = base.clone();
        for c in &mut mesh.creases {
            c.sharpness = s as f32;
        }
        let t = Instant::now();
        let topo = Topology::new(&mesh)?;
        let table = PatchTable::build(&topo, &PatchOptions::default())?;
        let surf = LimitSurface::new(table, &mesh.positions);
        let build = ms(t);
        let t = Instant::now();
        let tess = surf.tessellate(n)?;
        let tess_ms = ms(t);
        assert!(!tess.positions.is_empty());
        let c = surf.table().counts();

        let osd_level = if s >= 10 { 10 } else { s.max(4) };
        let o = OsdOptions {
            isolation_level: osd_level,
            use_single_crease: false,
            use_inf_sharp: false,
            end_cap: EndCap::Gregory,
        };
        let osd_mesh = OsdMesh::from(&mesh);
        let (osd_patches, osd_bytes, osd_ms) = match osd_ref::patch_stats(&osd_mesh, &o) {
            Ok(st) => {
                let t = Instant::now();
                let grid = osd_ref::eval_limit_grid_with(&osd_mesh, n, &o)?;
                assert!(!grid.is_empty());
                (
                    st.num_patches.to_string(),
                    st.bytes.to_string(),
                    format!("{:.1}", ms(t)),
                )
            }
            Err(e) => (format!("({e})"), "-".into(), "-".into()),
        };
        println!(
            "| {s} | {} ({}/{}/{}) | {} | {build:.1} | {tess_ms:.1} | {osd_level} | {osd_patches} | {osd_bytes} | {osd_ms} |",
            surf.table().num_patches(),
            c.regular,
            c.single_crease,
            c.gregory,
            surf.table().size_bytes(),
        );
    }
    println!(
        "\nsubsurf bytes: control indices (4 B), patch parameters (8 B), type (1 B), offsets \
         (4 B), sharpness (4 B) per patch and the patch map; OSD bytes: control indices and \
         patch parameters only. Neither counts stencil tables."
    );
    Ok(())
}
