//! A crease slider: every crease of a mesh moved through a range of sharpness values with
//! `PatchTable::set_sharpness`, the limit surface re-evaluated at each step, then back to
//! the mesh's own values; the time of each edit next to a fresh `PatchTable::build`.
//!
//! `cargo run --release -p subsurf --example crease_slider [-- FILE RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, 11 runs). Prints, for every crease moved from `A` to
//! 3.5 and back (two edits per run, alternating with a fresh build of each end), the medians
//! of the edit, of a fresh `PatchTable::build` and of the point update after an edit, and
//! how the table was updated ([`subsurf::limit::EditOutcome`]): for `A` = 2 the structure
//! changes at level 2 (a crease of 3.5 is isolated two levels deeper) and the table is
//! rebuilt from level 2 down, for `A` = 3 from level 3 down, the levels above kept; for
//! `A` = the mesh's own values (6 on the car) it is kept and the table updated in place.

mod common;

use std::time::Instant;

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::Topology;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let runs: usize = common::arg(&args, 2, 11).max(1);
    let mesh = subsurf::io::read_path(path)?;
    let topo = Topology::new(&mesh)?;
    let options = PatchOptions::default();
    // Built editable: the first edit that keeps the structure is made in place too.
    let mut table = PatchTable::build_editable(&topo, &options)?;
    let edits = |s: Option<f32>| -> Vec<SharpnessEdit> { SharpnessEdit::creases(&mesh.creases, s) };

    // The slider loop: one edit and one evaluation per step, at the centre of a face on the
    // first crease.
    let c = mesh.creases.first().ok_or("the mesh has no crease")?;
    let e = topo.find_edge(c.v0, c.v1).ok_or("crease without an edge")?;
    let f = topo.edge_faces(e as usize)[0] as usize;
    let ptex = table.ptex_offsets()[f] as usize;
    println!("{path}: {} creases", mesh.creases.len());
    for step in 0..=8 {
        let s = 0.5 * step as f32;
        table.set_sharpness(&edits(Some(s)))?;
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        let p = surface.eval(ptex, 0.5, 0.5).map(|r| r.p);
        println!("  sharpness {s:3.1}: face {f} centre at {p:?}");
    }
    table.set_sharpness(&edits(None))?;

    for from in [Some(2.0), Some(3.0), None] {
        // To the first value of the pair (not timed).
        table.set_sharpness(&edits(from))?;
        let (mut edit, mut build, mut points) = (Vec::new(), Vec::new(), Vec::new());
        let mut outcomes = Vec::new();
        for _ in 0..runs {
            for s in [Some(3.5), from] {
                let e = edits(s);
                let t = Instant::now();
                let outcome = table.apply_sharpness(&e)?;
                edit.push(t.elapsed().as_secs_f64() * 1e3);
                if !outcomes.contains(&outcome) {
                    outcomes.push(outcome);
                }
                let t = Instant::now();
                std::hint::black_box(table.points(&mesh.positions));
                points.push(t.elapsed().as_secs_f64() * 1e3);
                let mut m = mesh.clone();
                for (c, e) in m.creases.iter_mut().zip(&e) {
                    if let SharpnessEdit::Edge { sharpness, .. } = e {
                        c.sharpness = *sharpness;
                    }
                }
                let t = Instant::now();
                std::hint::black_box(PatchTable::build(&Topology::new(&m)?, &options)?);
                build.push(t.elapsed().as_secs_f64() * 1e3);
            }
        }
        let (e, b, p) = (
            common::median(&mut edit),
            common::median(&mut build),
            common::median(&mut points),
        );
        let a = from.map_or("own".to_string(), |s| format!("{s}"));
        println!(
            "creases {a} -> 3.5 -> {a}, medians of {} edits: edit {e:.2} ms, fresh build \
             {b:.2} ms (build / edit = {:.1}), points after an edit {p:.2} ms; {outcomes:?}",
            2 * runs,
            b / e
        );
    }

    // What keeping the levels costs: build time (the table kept; dropping it is timed apart),
    // and resident memory over 8 tables alive.
    let make = |editable: bool| match editable {
        true => PatchTable::build_editable(&topo, &options),
        false => PatchTable::build(&topo, &options),
    };
    let [mut plain, mut editable, mut drop_plain, mut drop_editable] = [(); 4].map(|_| Vec::new());
    for _ in 0..runs {
        for (keep, times, drops) in [
            (false, &mut plain, &mut drop_plain),
            (true, &mut editable, &mut drop_editable),
        ] {
            let t = Instant::now();
            let table = make(keep)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            let t = Instant::now();
            drop(std::hint::black_box(table));
            drops.push(t.elapsed().as_secs_f64() * 1e3);
        }
    }
    let resident = |editable: bool| -> Result<f64, Box<dyn std::error::Error>> {
        let before = resident_mb();
        let tables = (0..8)
            .map(|_| make(editable))
            .collect::<Result<Vec<_>, _>>()?;
        let grown = resident_mb() - before;
        drop(tables);
        Ok(grown / 8.0)
    };
    let (rp, re) = (resident(false)?, resident(true)?);
    println!(
        "build {:.2} ms (its drop {:.2} ms), editable build {:.2} ms (its drop {:.2} ms), \
         medians of {runs}; resident memory per table {rp:.1} MB, editable {re:.1} MB",
        common::median(&mut plain),
        common::median(&mut drop_plain),
        common::median(&mut editable),
        common::median(&mut drop_editable),
    );
    Ok(())
}

/// The process's resident memory (Linux; NaN elsewhere).
fn resident_mb() -> f64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| s.split_whitespace().nth(1)?.parse::<f64>().ok())
        .map_or(f64::NAN, |pages| pages * 4096.0 / 1e6)
}
