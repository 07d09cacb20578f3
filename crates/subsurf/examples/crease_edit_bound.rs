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

/// One array of a table: its name, its bytes in the target table, the bytes of those that
/// differ from the other table's at the same place (or lie past its end), the first such
/// index.
type Row = (String, usize, usize, Option<usize>);

/// Array `to` against `from`, elements compared by `bits`.
fn differ<T: Copy, B: PartialEq>(name: String, from: &[T], to: &[T], bits: impl Fn(T) -> B) -> Row {
    let mut n = 0;
    let mut first = None;
    for (i, &x) in to.iter().enumerate() {
        if from.get(i).is_none_or(|&y| bits(y) != bits(x)) {
            n += 1;
            first.get_or_insert(i);
        }
    }
    (
        name,
        std::mem::size_of_val(to),
        n * std::mem::size_of::<T>(),
        first,
    )
}

/// The three arrays of a stencil table.
fn stencils(name: &str, a: &StencilTable, b: &StencilTable) -> [Row; 3] {
    [
        differ(format!("{name}.offsets"), &a.offsets, &b.offsets, |x| x),
        differ(format!("{name}.indices"), &a.indices, &b.indices, |x| x),
        differ(
            format!("{name}.weights"),
            &a.weights,
            &b.weights,
            f32::to_bits,
        ),
    ]
}

/// Every array of the table `to` against `from`.
fn table_diff(from: &PatchTable, to: &PatchTable) -> Vec<Row> {
    let mut rows = Vec::new();
    let empty = StencilTable::default();
    for (d, b) in to.level_stencils.iter().enumerate() {
        let a = from.level_stencils.get(d);
        for (kind, a, b) in [
            ("face", a.map(|a| &a.face), &b.face),
            ("vertex", a.map(|a| &a.vertex), &b.vertex),
            ("edge", a.map(|a| &a.edge), &b.edge),
        ] {
            rows.extend(stencils(
                &format!("step {d} {kind}"),
                a.unwrap_or(&empty),
                b,
            ));
        }
    }
    for (d, b) in to.level_inputs.iter().enumerate() {
        let a = from.level_inputs.get(d).map_or(&[][..], |a| &a[..]);
        rows.push(differ(format!("step {d} inputs"), a, b, |x| x));
    }
    rows.extend(stencils(
        "end-cap points",
        &from.local_points,
        &to.local_points,
    ));
    rows.extend([
        differ("patch types".into(), &from.kinds, &to.kinds, |x| x),
        differ(
            "patch cv offsets".into(),
            &from.cv_offsets,
            &to.cv_offsets,
            |x| x,
        ),
        differ("patch cvs".into(), &from.cvs, &to.cvs, |x| x),
        differ("patch params".into(), &from.params, &to.params, |p| {
            (p.field0, p.field1)
        }),
        differ(
            "patch sharpness".into(),
            &from.sharpness,
            &to.sharpness,
            f32::to_bits,
        ),
        differ(
            "patch map roots".into(),
            &from.patch_map.roots,
            &to.patch_map.roots,
            |x| x,
        ),
        differ(
            "patch map nodes".into(),
            &from.patch_map.nodes,
            &to.patch_map.nodes,
            |x| x,
        ),
    ]);
    rows
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let from: f32 = common::arg(&args, 2, 2.0);
    let runs: usize = common::arg(&args, 3, 21).max(1);
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
    let mut probe = PatchTable::build_editable(&ta, &options)?;
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
    let mut sweep = common::Sweep::new();
    let words = diff_up.max(diff_down) / 4;
    let src: Vec<u32> = (0..words as u32).collect();
    let mut dst = vec![0u32; words];
    let mut table = PatchTable::build_editable(&at(None)?, &options)?;
    let (mut build, mut copy, mut edit) = ([vec![], vec![]], [vec![], vec![]], [vec![], vec![]]);
    let mut to_own = false;
    for _ in 0..runs {
        for (k, cold) in [(0, true), (1, false)] {
            let tick = |sweep: &mut common::Sweep| {
                if cold {
                    sweep.run();
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
    let [bc, bw] = build.map(|mut t| common::median(&mut t));
    let [cc, cw] = copy.map(|mut t| common::median(&mut t));
    let [ec, ew] = edit.map(|mut t| common::median(&mut t));
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
