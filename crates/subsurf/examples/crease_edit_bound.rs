//! What a crease edit that changes the isolation structure must at least write, measured
//! against a fresh build: every crease of a mesh moved from `A` to 3.5 (default `A` = 2, the
//! edit of the car that isolates 8 level-2 faces two levels deeper).
//!
//! `cargo run --release -p subsurf --example crease_edit_bound [-- FILE A RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, 2, 21 runs).
//!
//! An edit whose result is the fresh build's table, array by array and bit for bit, must
//! write every element of the target table that differs from the element at the same place
//! in the table it starts from (or that lies past its end). The example builds both tables,
//! counts those bytes in each of the table's arrays (in both directions of the slider), and
//! times, in one process and alternating, with the caches evicted before each (a 256 MB
//! sweep: a slider evaluates and draws between edits) and without (the build that runs
//! before each edit still evicts much of what the edit reads):
//!
//! - a fresh `PatchTable::build` of the edited mesh;
//! - copying that many bytes from one buffer into another already allocated (on all
//!   threads: the least a rewrite of them costs, before computing any of them);
//! - an edit of the same creases that keeps the structure (the mesh's own values <-> 3.5,
//!   updated in place), for the sharpness walk such an edit also has to do.

mod common;

use std::time::Instant;

use subsurf::limit::{EditOutcome, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::refine::StencilTable;
use subsurf::Topology;

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t.get(t.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Bytes of `to` that differ from `from` at the same index, or lie past its end; and the
/// first such index.
fn differ<T: Copy, B: PartialEq>(
    from: &[T],
    to: &[T],
    bits: impl Fn(T) -> B,
) -> (usize, Option<usize>) {
    let mut n = 0;
    let mut first = None;
    for (i, &x) in to.iter().enumerate() {
        if from.get(i).is_none_or(|&y| bits(y) != bits(x)) {
            n += 1;
            first.get_or_insert(i);
        }
    }
    (n * std::mem::size_of::<T>(), first)
}

/// `(array, bytes of it in `to`, bytes differing, first differing index)` for every array of
/// the table.
fn table_diff(from: &PatchTable, to: &PatchTable) -> Vec<(String, usize, usize, Option<usize>)> {
    let mut rows = Vec::new();
    let mut add = |name: String, (n, first): (usize, Option<usize>), total: usize| {
        rows.push((name, total, n, first));
    };
    fn stencils(
        add: &mut dyn FnMut(String, (usize, Option<usize>), usize),
        name: &str,
        a: &StencilTable,
        b: &StencilTable,
    ) {
        add(
            format!("{name}.offsets"),
            differ(&a.offsets, &b.offsets, |x| x),
            4 * b.offsets.len(),
        );
        add(
            format!("{name}.indices"),
            differ(&a.indices, &b.indices, |x| x),
            4 * b.indices.len(),
        );
        add(
            format!("{name}.weights"),
            differ(&a.weights, &b.weights, f32::to_bits),
            4 * b.weights.len(),
        );
    }
    let empty = subsurf::refine::LevelStencils::<f32> {
        num_parent_vertices: 0,
        face: StencilTable::default(),
        vertex: StencilTable::default(),
        edge: StencilTable::default(),
    };
    for (d, b) in to.level_stencils.iter().enumerate() {
        let a = from.level_stencils.get(d).unwrap_or(&empty);
        stencils(&mut add, &format!("step {d} face"), &a.face, &b.face);
        stencils(&mut add, &format!("step {d} vertex"), &a.vertex, &b.vertex);
        stencils(&mut add, &format!("step {d} edge"), &a.edge, &b.edge);
    }
    for (d, b) in to.level_inputs.iter().enumerate() {
        let a = from.level_inputs.get(d).map_or(&[][..], |a| &a[..]);
        add(format!("step {d} inputs"), differ(a, b, |x| x), 4 * b.len());
    }
    stencils(
        &mut add,
        "end-cap points",
        &from.local_points,
        &to.local_points,
    );
    add(
        "patch types".into(),
        differ(&from.kinds, &to.kinds, |x| x),
        to.kinds.len(),
    );
    add(
        "patch cv offsets".into(),
        differ(&from.cv_offsets, &to.cv_offsets, |x| x),
        4 * to.cv_offsets.len(),
    );
    add(
        "patch cvs".into(),
        differ(&from.cvs, &to.cvs, |x| x),
        4 * to.cvs.len(),
    );
    add(
        "patch params".into(),
        differ(&from.params, &to.params, |p| (p.field0, p.field1)),
        8 * to.params.len(),
    );
    add(
        "patch sharpness".into(),
        differ(&from.sharpness, &to.sharpness, f32::to_bits),
        4 * to.sharpness.len(),
    );
    add(
        "patch map roots".into(),
        differ(&from.patch_map.roots, &to.patch_map.roots, |x| x),
        4 * to.patch_map.roots.len(),
    );
    add(
        "patch map nodes".into(),
        differ(&from.patch_map.nodes, &to.patch_map.nodes, |x| x),
        16 * to.patch_map.nodes.len(),
    );
    rows
}

/// Evicts the caches (a 256 MB sweep).
fn evict(sweep: &mut [u64]) {
    for (i, x) in sweep.iter_mut().enumerate().step_by(8) {
        *x = x.wrapping_add(i as u64);
    }
    std::hint::black_box(&sweep);
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let from: f32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2.0);
    let runs: usize = args
        .get(3)
        .and_then(|s| s.parse().ok())
        .unwrap_or(21)
        .max(1);
    let mesh = subsurf::io::read_path(path)?;
    let options = PatchOptions::default();
    let at = |s: Option<f32>| -> Result<Topology, subsurf::Error> {
        let mut m = mesh.clone();
        for c in &mut m.creases {
            c.sharpness = s.unwrap_or(c.sharpness);
        }
        Topology::new(&m)
    };
    let (ta, tb) = (at(Some(from))?, at(Some(3.5))?);
    let (a, b) = (
        PatchTable::build(&ta, &options)?,
        PatchTable::build(&tb, &options)?,
    );
    let edits = |s: Option<f32>| SharpnessEdit::creases(&mesh.creases, s);

    // The edit A -> 3.5 must change the structure, as the example assumes.
    let mut probe = a.clone();
    probe.apply_sharpness(&edits(Some(from)))?;
    let outcome = probe.apply_sharpness(&edits(Some(3.5)))?;
    println!(
        "{path}: {} creases, {from} -> 3.5: {outcome:?}; patches {} -> {}, refined points {} -> {}",
        mesh.creases.len(),
        a.kinds.len(),
        b.kinds.len(),
        a.level_offsets.last().unwrap_or(&0),
        b.level_offsets.last().unwrap_or(&0),
    );
    if outcome != EditOutcome::Rebuilt {
        println!("(the structure is kept: nothing below applies)");
    }

    println!("\n| array | bytes | differing {from} -> 3.5 | first | differing 3.5 -> {from} |");
    println!("|---|---:|---:|---:|---:|");
    let (up, down) = (table_diff(&a, &b), table_diff(&b, &a));
    let (mut total, mut diff_up, mut diff_down) = (0, 0, 0);
    for ((name, bytes, n, first), (_, _, m, _)) in up.iter().zip(&down) {
        total += bytes;
        diff_up += n;
        diff_down += m;
        if *n > 0 || *m > 0 {
            let first = first.map_or("-".into(), |f| f.to_string());
            println!("| {name} | {bytes} | {n} | {first} | {m} |");
        }
    }
    println!("| **all** | {total} | {diff_up} | | {diff_down} |");

    // Times, alternating, caches evicted before each ("cold") and not ("warm").
    let mut sweep = vec![0u64; 32 << 20];
    let words = diff_up.max(diff_down) / 4;
    let src: Vec<u32> = (0..words as u32).collect();
    let mut dst = vec![0u32; words];
    // The first edit keeps the levels (untimed).
    let mut table = PatchTable::build(&at(None)?, &options)?;
    table.apply_sharpness(&edits(Some(3.5)))?;
    table.apply_sharpness(&edits(None))?;
    let (mut build, mut copy, mut edit) = ([vec![], vec![]], [vec![], vec![]], [vec![], vec![]]);
    let mut to_own = false;
    for _ in 0..runs {
        for (k, cold) in [(0, true), (1, false)] {
            let tick = |sweep: &mut Vec<u64>| {
                if cold {
                    evict(sweep);
                }
                Instant::now()
            };
            let t = tick(&mut sweep);
            std::hint::black_box(PatchTable::build(&tb, &options)?);
            build[k].push(t.elapsed().as_secs_f64() * 1e3);
            let t = tick(&mut sweep);
            let half = words / 2;
            let (d0, d1) = dst.split_at_mut(half);
            rayon::join(
                || d0.copy_from_slice(&src[..half]),
                || d1.copy_from_slice(&src[half..]),
            );
            std::hint::black_box(&dst);
            copy[k].push(t.elapsed().as_secs_f64() * 1e3);
            let s = if to_own { None } else { Some(3.5) };
            to_own = !to_own;
            let t = tick(&mut sweep);
            let o = table.apply_sharpness(&edits(s))?;
            edit[k].push(t.elapsed().as_secs_f64() * 1e3);
            if o != EditOutcome::Updated {
                return Err(format!("own <-> 3.5 edit not in place: {o:?}").into());
            }
        }
    }
    println!(
        "\nmedians of {runs}, {} threads, ms:\n\n| | caches evicted | not evicted |",
        rayon::current_num_threads()
    );
    println!("|---|---:|---:|");
    let [bc, bw] = build.map(median);
    let [cc, cw] = copy.map(median);
    let [ec, ew] = edit.map(median);
    println!("| fresh build at 3.5 | {bc:.3} | {bw:.3} |");
    println!(
        "| a tenth of it (the goal) | {:.3} | {:.3} |",
        bc / 10.0,
        bw / 10.0
    );
    println!(
        "| copying {:.2} MB (the differing bytes) | {cc:.3} | {cw:.3} |",
        (4 * words) as f64 / 1e6
    );
    println!("| in-place edit, own <-> 3.5 | {ec:.3} | {ew:.3} |");
    println!(
        "| copy + in-place edit, / build | {:.2}x | {:.2}x |",
        bc / (cc + ec),
        bw / (cw + ew)
    );
    Ok(())
}
