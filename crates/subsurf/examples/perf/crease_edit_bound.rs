//! What a crease edit that changes the isolation structure must at least write, measured
//! against a fresh build: every crease of a mesh moved from `A` to 3.5 (default `A` = 2, the
//! edit of the car that isolates 8 level-2 faces two levels deeper).
//!
//! `cargo run --release -p subsurf --example crease_edit_bound [-- FILE A RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, 2, 21 runs).
//!
//! An edit whose result is the fresh build's table, array by array and bit for bit, must
//! write every element of the target table that differs from the element at the same place
//! in the table it starts from (or that lies past its end); so must it for the levels an
//! editable table keeps (`PatchTable::kept_levels`), which the next edit walks and which
//! therefore follow the table's numbering. The example builds both tables (plain and
//! editable), counts those bytes in each array (in both directions of the slider), and
//! times, in one process and alternating, with the caches evicted before each (a 256 MB
//! sweep: a slider evaluates and draws between edits) and warm (right after an untimed run of
//! the same):
//!
//! - a fresh `PatchTable::build` of the edited mesh;
//! - copying the table's differing bytes, and the table's and kept levels' together, from
//!   one buffer into another already allocated (on all threads: the least a rewrite of them
//!   costs, before computing any of them);
//! - renumbering the latter (each word read, translated through an index map the size of
//!   the refined points, written: what a splice does to every index it moves);
//! - an edit of the same creases that keeps the structure (the mesh's own values <-> 3.5,
//!   updated in place), for the sharpness walk such an edit also has to do.

mod common;

use std::time::Instant;

use subsurf::limit::sparse::Trace;
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

/// Every array of a topology `to` against `from`, summed into one row.
fn topology_diff(name: String, from: &Topology, to: &Topology) -> Row {
    let rows = [
        differ(String::new(), &from.face_offsets, &to.face_offsets, |x| x),
        differ(String::new(), &from.face_verts, &to.face_verts, |x| x),
        differ(String::new(), &from.face_edges, &to.face_edges, |x| x),
        differ(String::new(), &from.edge_verts, &to.edge_verts, |x| x),
        differ(
            String::new(),
            &from.edge_face_offsets,
            &to.edge_face_offsets,
            |x| x,
        ),
        differ(String::new(), &from.edge_faces, &to.edge_faces, |x| x),
        differ(
            String::new(),
            &from.edge_face_local,
            &to.edge_face_local,
            |x| x,
        ),
        differ(
            String::new(),
            &from.vert_face_offsets,
            &to.vert_face_offsets,
            |x| x,
        ),
        differ(String::new(), &from.vert_faces, &to.vert_faces, |x| x),
        differ(
            String::new(),
            &from.vert_face_local,
            &to.vert_face_local,
            |x| x,
        ),
        differ(
            String::new(),
            &from.vert_edge_offsets,
            &to.vert_edge_offsets,
            |x| x,
        ),
        differ(String::new(), &from.vert_edges, &to.vert_edges, |x| x),
        differ(
            String::new(),
            &from.edge_sharpness,
            &to.edge_sharpness,
            f32::to_bits,
        ),
        differ(
            String::new(),
            &from.vert_sharpness,
            &to.vert_sharpness,
            f32::to_bits,
        ),
        differ(String::new(), &from.face_is_hole, &to.face_is_hole, |x| x),
        differ(String::new(), &from.edge_tags, &to.edge_tags, |x| x),
        differ(String::new(), &from.vert_tags, &to.vert_tags, |x| x),
        differ(String::new(), &from.vert_rule, &to.vert_rule, |x| x),
    ];
    let first = rows.iter().filter_map(|r| r.3).min();
    let sum = |k: fn(&Row) -> usize| rows.iter().map(k).sum();
    (name, sum(|r| r.1), sum(|r| r.2), first)
}

/// The levels kept for edits by `to` against those of `from` (a row per level and kind).
fn kept_diff(from: &Trace, to: &Trace) -> Vec<Row> {
    let mut rows = Vec::new();
    let empty = Topology::default();
    for (d, b) in to.levels.iter().enumerate().skip(1) {
        let a = from.levels.get(d).unwrap_or(&empty);
        rows.push(topology_diff(format!("kept level {d}"), a, b));
    }
    for (d, b) in to.subs.iter().enumerate() {
        let a = from.subs.get(d).unwrap_or(&empty);
        rows.push(topology_diff(format!("kept sub-mesh {d}"), a, b));
    }
    let none = (Vec::new(), Vec::new());
    for (d, (bv, be)) in to.in_sub.iter().enumerate() {
        let (av, ae) = from.in_sub.get(d).unwrap_or(&none);
        let (v, e) = (
            differ(String::new(), av, bv, |x| x),
            differ(String::new(), ae, be, |x| x),
        );
        rows.push((
            format!("kept level-to-sub-mesh maps {d}"),
            v.1 + e.1,
            v.2 + e.2,
            v.3.or(e.3),
        ));
    }
    let lists = |name: &str, a: &[Vec<u32>], b: &[Vec<u32>]| -> Vec<Row> {
        (b.iter().enumerate())
            .map(|(d, b)| {
                let a = a.get(d).map_or(&[][..], |a| &a[..]);
                differ(format!("{name} {d}"), a, b, |x| x)
            })
            .collect()
    };
    rows.extend(lists("kept refined faces", &from.chosen, &to.chosen));
    rows.extend(lists("kept leaves", &from.leaves, &to.leaves));
    for (d, b) in to.tags.iter().enumerate() {
        let a = from.tags.get(d).map_or(&[][..], |a| &a[..]);
        rows.push(differ(format!("kept tags {d}"), a, b, |t| (t.bits, t.rule)));
    }
    rows
}

/// Prints the rows `up` (`from` -> 3.5) beside `down` (back) that differ either way, and the
/// totals; returns the bytes differing up and down.
fn print_rows(title: &str, from: f32, up: &[Row], down: &[Row]) -> (usize, usize) {
    println!("\n| {title} | bytes | differing {from} -> 3.5 | first | differing 3.5 -> {from} |");
    println!("|---|---:|---:|---:|---:|");
    let (mut total, mut diff_up, mut diff_down) = (0, 0, 0);
    for ((name, bytes, n, first), (_, _, m, _)) in up.iter().zip(down) {
        total += bytes;
        diff_up += n;
        diff_down += m;
        if *n > 0 || *m > 0 {
            let first = first.map_or("-".into(), |f| f.to_string());
            println!("| {name} | {bytes} | {n} | {first} | {m} |");
        }
    }
    println!("| **all** | {total} | {diff_up} | | {diff_down} |");
    (diff_up, diff_down)
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
    if matches!(outcome, EditOutcome::Updated | EditOutcome::Unchanged) {
        println!("(the structure is kept: nothing below applies)");
    }

    let (diff_up, diff_down) = print_rows("array", from, &table_diff(&a, &b), &table_diff(&b, &a));

    // The levels an editable table keeps must follow its numbering for the next edit.
    let (ea, eb) = (
        PatchTable::build_editable(&ta, &options)?,
        PatchTable::build_editable(&tb, &options)?,
    );
    let (Some(ka), Some(kb)) = (ea.kept_levels(), eb.kept_levels()) else {
        return Err("editable builds keep no levels".into());
    };
    let (kept_up, kept_down) = print_rows(
        "kept for edits",
        from,
        &kept_diff(ka, kb),
        &kept_diff(kb, ka),
    );

    // Times, alternating, caches evicted before each ("cold") and not ("warm").
    let mut sweep = common::Sweep::new();
    let words = diff_up.max(diff_down) / 4;
    let kept_words = kept_up.max(kept_down) / 4;
    let src: Vec<u32> = (0..(words + kept_words) as u32).collect();
    let mut dst = vec![0u32; words + kept_words];
    let mut table = PatchTable::build_editable(&at(None)?, &options)?;
    let (mut build, mut edit) = ([vec![], vec![]], [vec![], vec![]]);
    let (mut copy, mut copy_all) = ([vec![], vec![]], [vec![], vec![]]);
    let mut remap_all = [vec![], vec![]];
    // A power of two at least the refined points, so that a mask keeps an index in it.
    let points = (*b.level_offsets.last().unwrap_or(&1) as usize).next_power_of_two();
    let (map, mask): (Vec<u32>, usize) = ((0..points as u32).rev().collect(), points - 1);
    let mut to_own = false;
    for _ in 0..runs {
        for (k, cold) in [(0, true), (1, false)] {
            // Cold: after the sweep; warm: right after an untimed run of the same.
            let mut time = |f: &mut dyn FnMut() -> Result<(), Box<dyn std::error::Error>>| {
                if cold {
                    sweep.run();
                } else {
                    f()?;
                }
                let t = Instant::now();
                f()?;
                Ok::<f64, Box<dyn std::error::Error>>(t.elapsed().as_secs_f64() * 1e3)
            };
            build[k].push(time(&mut || {
                std::hint::black_box(PatchTable::build(&tb, &options)?);
                Ok(())
            })?);
            for (n, times) in [
                (words, &mut copy[k]),
                (words + kept_words, &mut copy_all[k]),
            ] {
                times.push(time(&mut || {
                    let half = n / 2;
                    let (d0, d1) = dst[..n].split_at_mut(half);
                    rayon::join(
                        || d0.copy_from_slice(&src[..half]),
                        || d1.copy_from_slice(&src[half..n]),
                    );
                    std::hint::black_box(&dst);
                    Ok(())
                })?);
            }
            // The same words renumbered: each read, translated through a map the size of
            // the refined points, written (what a splice does to an index it moves).
            let n = words + kept_words;
            remap_all[k].push(time(&mut || {
                let half = n / 2;
                let (d0, d1) = dst[..n].split_at_mut(half);
                let renumber = |d: &mut [u32], s: &[u32]| {
                    for (d, &x) in d.iter_mut().zip(s) {
                        *d = map[x as usize & mask];
                    }
                };
                rayon::join(
                    || renumber(d0, &src[..half]),
                    || renumber(d1, &src[half..n]),
                );
                std::hint::black_box(&dst);
                Ok(())
            })?);
            edit[k].push(time(&mut || {
                let s = if to_own { None } else { Some(3.5) };
                to_own = !to_own;
                match table.apply_sharpness(&edits(s))? {
                    EditOutcome::Updated => Ok(()),
                    o => Err(format!("own <-> 3.5 edit not in place: {o:?}").into()),
                }
            })?);
        }
    }
    println!(
        "\nmedians of {runs}, {} threads, ms:\n\n| | caches evicted | warm |",
        rayon::current_num_threads()
    );
    println!("|---|---:|---:|");
    let [bc, bw] = build.map(|mut t| common::median(&mut t));
    let [cc, cw] = copy.map(|mut t| common::median(&mut t));
    let [ac, aw] = copy_all.map(|mut t| common::median(&mut t));
    let [rc, rw] = remap_all.map(|mut t| common::median(&mut t));
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
    println!(
        "| copying {:.2} MB (the table's and the kept levels' differing bytes) | {ac:.3} | {aw:.3} |",
        (4 * (words + kept_words)) as f64 / 1e6
    );
    println!("| renumbering them (each through an index map) | {rc:.3} | {rw:.3} |");
    println!("| in-place edit, own <-> 3.5 | {ec:.3} | {ew:.3} |");
    println!(
        "| build / (table copy + in-place edit) | {:.2}x | {:.2}x |",
        bc / (cc + ec),
        bw / (cw + ew)
    );
    println!(
        "| build / (table and kept-level copy + in-place edit) | {:.2}x | {:.2}x |",
        bc / (ac + ec),
        bw / (aw + ew)
    );
    println!(
        "| build / (table and kept-level renumbering + in-place edit) | {:.2}x | {:.2}x |",
        bc / (rc + ec),
        bw / (rw + ew)
    );
    Ok(())
}
