//! Local crease edits on a large cage: the car refined twice (about 25k faces, its creases
//! carried with their decayed sharpness) used as a base mesh, isolation 4. Times, against a
//! fresh `PatchTable::build` of the same mesh (medians):
//!
//! - one crease smoothed and back (`0 ↔` its own value): the structure changes (its ends are
//!   no longer isolated), the edit is local (`EditOutcome::Local`);
//! - every crease `2 ↔ 3.5`: the structure changes along every crease.
//!
//! Each edit's outcome is counted (a compaction shows as `Rebuilt`); every few edits the
//! surface is checked against the fresh build's at the centre of every ptex face.
//!
//! `cargo run --release -p subsurf --example crease_local [-- FILE RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, 21 runs).

mod common;

use std::collections::BTreeMap;
use std::time::Instant;

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::mesh::Mesh;
use subsurf::surface::{refine_mesh, Cpu};
use subsurf::Topology;

/// The edits of the `i`-th edit of a case.
type EditAt<'a> = dyn Fn(usize) -> Vec<SharpnessEdit> + 'a;

/// `mesh` with the edits' crease values.
fn edited(mesh: &Mesh, edits: &[SharpnessEdit]) -> Mesh {
    let mut m = mesh.clone();
    for e in edits {
        if let SharpnessEdit::Edge { v0, v1, sharpness } = *e {
            for c in &mut m.creases {
                if (c.v0, c.v1) == (v0, v1) || (c.v0, c.v1) == (v1, v0) {
                    c.sharpness = sharpness;
                }
            }
        }
    }
    m
}

/// The edited table's surface is the fresh build's at the centre of every ptex face.
fn check(mesh: &Mesh, table: &PatchTable) -> Result<(), Box<dyn std::error::Error>> {
    let fresh = PatchTable::build(&Topology::new(mesh)?, table.options())?;
    let (a, b) = (
        LimitSurface::new(table.clone(), &mesh.positions),
        LimitSurface::new(fresh, &mesh.positions),
    );
    for f in 0..table.num_ptex_faces() {
        let (x, y) = (a.eval_raw(f, 0.5, 0.3), b.eval_raw(f, 0.5, 0.3));
        if x.map(|p| [p.p, p.du, p.dv]) != y.map(|p| [p.p, p.du, p.dv]) {
            return Err(format!("ptex face {f}: the edited surface differs").into());
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let runs: usize = common::arg(&args, 2, 21).max(1);
    let mesh = refine_mesh(&subsurf::io::read_path(path)?, 2, false, None, &Cpu)?;
    let topo = Topology::new(&mesh)?;
    let options = PatchOptions::default();
    let mut build = Vec::new();
    for _ in 0..runs.min(11) {
        let t = Instant::now();
        std::hint::black_box(PatchTable::build(&topo, &options)?);
        build.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let build = common::median(&mut build);
    println!(
        "{path} refined twice: {} faces, {} creases; fresh build {build:.2} ms (median)",
        topo.num_faces(),
        mesh.creases.len()
    );

    let c = mesh.creases[mesh.creases.len() / 2];
    let one = |s: f32| {
        vec![SharpnessEdit::Edge {
            v0: c.v0,
            v1: c.v1,
            sharpness: s,
        }]
    };
    let all = |s: f32| SharpnessEdit::creases(&mesh.creases, Some(s));
    let cases: [(&str, Box<EditAt>); 2] = [
        (
            "one crease 0 <-> own",
            Box::new(|i| one(if i % 2 == 0 { 0.0 } else { c.sharpness })),
        ),
        (
            "all creases 2 <-> 3.5",
            Box::new(|i| all(if i % 2 == 0 { 2.0 } else { 3.5 })),
        ),
    ];
    for (what, edit) in cases {
        let mut table = PatchTable::build_editable(&topo, &options)?;
        let (mut times, mut outcomes) = (Vec::new(), BTreeMap::new());
        let mut current = mesh.clone();
        for i in 0..2 * runs {
            let e = edit(i);
            let t = Instant::now();
            let outcome = table.apply_sharpness(&e)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            let name = format!("{outcome:?}");
            let name = name.split([' ', '{']).next().unwrap_or("").to_string();
            *outcomes.entry(name).or_insert(0) += 1;
            current = edited(&current, &e);
            if i % 8 == 3 {
                check(&current, &table)?;
            }
        }
        let mean = times.iter().sum::<f64>() / times.len() as f64;
        let median = common::median(&mut times);
        println!(
            "  {what}: edit {median:.3} ms median, {mean:.3} ms mean ({} edits {outcomes:?}); \
             build / edit {:.1}x median, {:.1}x mean",
            times.len(),
            build / median,
            build / mean
        );
    }
    Ok(())
}
