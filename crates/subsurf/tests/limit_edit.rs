//! Crease edits (`PatchTable::set_sharpness`): the edited table equals, bit for bit, a fresh
//! build of the mesh with the edited tags; bad edits are refused before any work.

mod limit_common;

use limit_common::{load_shape, shape_names, Lcg};
use subsurf::limit::{EditOutcome, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::mesh::{Corner, Crease};
use subsurf::{Error, Mesh, MeshError, Real, StencilTable, Topology};

fn same_weights<R: Real>(a: &StencilTable<R>, b: &StencilTable<R>) -> bool {
    let bits = |t: &StencilTable<R>| {
        t.weights()
            .iter()
            .map(|w| w.to_f64().to_bits())
            .collect::<Vec<_>>()
    };
    a.offsets() == b.offsets()
        && a.indices() == b.indices()
        && a.num_inputs() == b.num_inputs()
        && bits(a) == bits(b)
}

/// Every array of the two tables is the same, weights compared by their bits.
fn assert_same<R: Real>(what: &str, a: &PatchTable<R>, b: &PatchTable<R>) {
    assert_eq!(
        a.base().arrays().edge_sharpness,
        b.base().arrays().edge_sharpness,
        "{what}"
    );
    assert_eq!(
        a.base().arrays().vert_sharpness,
        b.base().arrays().vert_sharpness,
        "{what}"
    );
    assert_eq!(
        a.base().arrays().vert_rule,
        b.base().arrays().vert_rule,
        "{what}"
    );
    assert_eq!(
        a.base().arrays().edge_tags,
        b.base().arrays().edge_tags,
        "{what}"
    );
    assert_eq!(
        a.base().arrays().vert_tags,
        b.base().arrays().vert_tags,
        "{what}"
    );
    assert_eq!(
        a.base().arrays().face_is_hole,
        b.base().arrays().face_is_hole,
        "{what}"
    );
    assert_eq!(a.kinds(), b.kinds(), "{what}");
    assert_eq!(a.cv_offsets(), b.cv_offsets(), "{what}");
    assert_eq!(a.cvs(), b.cvs(), "{what}");
    assert_eq!(a.params(), b.params(), "{what}");
    let bits = |s: &[f32]| s.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(a.sharpness()), bits(b.sharpness()), "{what}");
    assert_eq!(a.ptex_offsets(), b.ptex_offsets(), "{what}");
    assert_eq!(a.patch_map(), b.patch_map(), "{what}");
    assert_eq!(a.level_offsets(), b.level_offsets(), "{what}");
    assert_eq!(a.level_inputs(), b.level_inputs(), "{what}");
    assert_eq!(a.level_stencils().len(), b.level_stencils().len(), "{what}");
    for (x, y) in a.level_stencils().iter().zip(b.level_stencils()) {
        assert_eq!(x.num_parent_vertices(), y.num_parent_vertices(), "{what}");
        assert!(same_weights(x.face(), y.face()), "{what}: face stencils");
        assert!(
            same_weights(x.vertex(), y.vertex()),
            "{what}: vertex stencils"
        );
        assert!(same_weights(x.edge(), y.edge()), "{what}: edge stencils");
    }
    assert!(
        same_weights(a.local_points(), b.local_points()),
        "{what}: end caps"
    );
}

/// The two tables make the same surface of `mesh`'s positions, bit for bit: the same ptex
/// faces, patch counts by type, every evaluation (position and derivatives) on a dense grid
/// of every ptex face, and the tessellation; the table `a` (edited, perhaps locally) with no
/// more than twice the patches of `b` (a fresh build).
fn assert_same_surface<R: Real>(what: &str, mesh: &Mesh, a: &PatchTable<R>, b: &PatchTable<R>) {
    assert_eq!(a.ptex_offsets(), b.ptex_offsets(), "{what}");
    assert_eq!(a.counts(), b.counts(), "{what}: patch counts");
    assert_eq!(a.num_live_patches(), b.num_patches(), "{what}");
    assert!(a.num_patches() <= 2 * b.num_patches(), "{what}: patches");
    let (sa, sb) = (
        subsurf::limit::LimitSurface::new(a.clone(), &mesh.positions),
        subsurf::limit::LimitSurface::new(b.clone(), &mesh.positions),
    );
    let bits = |p: &subsurf::limit::LimitPoint<R>| {
        [p.p, p.du, p.dv].map(|x| x.map(|c| c.to_f64().to_bits()))
    };
    const N: usize = 9;
    for ptex in 0..b.num_ptex_faces() {
        for i in 0..N {
            for j in 0..N {
                let (u, v) = (i as f64 / (N - 1) as f64, (j as f64 + 0.37) / N as f64);
                let (u, v) = (R::from_f64(u), R::from_f64(v));
                let (x, y) = (sa.eval_raw(ptex, u, v), sb.eval_raw(ptex, u, v));
                assert_eq!(x.is_some(), y.is_some(), "{what}: ptex {ptex}");
                if let (Some(x), Some(y)) = (x, y) {
                    assert_eq!(bits(&x), bits(&y), "{what}: ptex {ptex} at ({i}, {j})");
                }
            }
        }
    }
    let (ta, tb) = (sa.tessellate(4).unwrap(), sb.tessellate(4).unwrap());
    assert_eq!(ta.quads, tb.quads, "{what}: tessellation");
    let pbits = |t: &subsurf::limit::Tessellation| {
        (t.positions.iter().chain(&t.normals))
            .map(|p| p.map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert!(pbits(&ta) == pbits(&tb), "{what}: tessellation");
}

/// Every array of the two topologies is the same, sharpness compared by its bits.
fn assert_same_topology(what: &str, a: &Topology, b: &Topology) {
    let bits = |s: &[f32]| s.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(a.num_vertices(), b.num_vertices(), "{what}");
    assert_eq!(a.arrays().face_offsets, b.arrays().face_offsets, "{what}");
    assert_eq!(a.arrays().face_verts, b.arrays().face_verts, "{what}");
    assert_eq!(a.arrays().face_edges, b.arrays().face_edges, "{what}");
    assert_eq!(a.arrays().edge_verts, b.arrays().edge_verts, "{what}");
    assert_eq!(
        a.arrays().edge_face_offsets,
        b.arrays().edge_face_offsets,
        "{what}"
    );
    assert_eq!(a.arrays().edge_faces, b.arrays().edge_faces, "{what}");
    assert_eq!(
        a.arrays().edge_face_local,
        b.arrays().edge_face_local,
        "{what}"
    );
    assert_eq!(
        a.arrays().vert_face_offsets,
        b.arrays().vert_face_offsets,
        "{what}"
    );
    assert_eq!(a.arrays().vert_faces, b.arrays().vert_faces, "{what}");
    assert_eq!(
        a.arrays().vert_face_local,
        b.arrays().vert_face_local,
        "{what}"
    );
    assert_eq!(
        a.arrays().vert_edge_offsets,
        b.arrays().vert_edge_offsets,
        "{what}"
    );
    assert_eq!(a.arrays().vert_edges, b.arrays().vert_edges, "{what}");
    assert_eq!(
        bits(a.arrays().edge_sharpness),
        bits(b.arrays().edge_sharpness),
        "{what}"
    );
    assert_eq!(
        bits(a.arrays().vert_sharpness),
        bits(b.arrays().vert_sharpness),
        "{what}"
    );
    assert_eq!(a.arrays().face_is_hole, b.arrays().face_is_hole, "{what}");
    assert_eq!(a.arrays().edge_tags, b.arrays().edge_tags, "{what}");
    assert_eq!(a.arrays().vert_tags, b.arrays().vert_tags, "{what}");
    assert_eq!(a.arrays().vert_rule, b.arrays().vert_rule, "{what}");
}

/// The levels two editable tables keep for edits are the same: an edit leaves them as a
/// fresh editable build of the edited mesh makes them, so the next edit starts from the
/// levels of the mesh it edits.
fn assert_same_kept<R: Real>(what: &str, a: &PatchTable<R>, b: &PatchTable<R>) {
    let (Some(x), Some(y)) = (a.kept_levels(), b.kept_levels()) else {
        panic!("{what}: levels kept by one table only");
    };
    assert_eq!(x.levels.len(), y.levels.len(), "{what}: levels");
    for (d, (p, q)) in x.levels.iter().zip(&y.levels).enumerate().skip(1) {
        assert_same_topology(&format!("{what}: kept level {d}"), p, q);
    }
    assert_eq!(x.subs.len(), y.subs.len(), "{what}: sub-meshes");
    for (d, (p, q)) in x.subs.iter().zip(&y.subs).enumerate() {
        assert_same_topology(&format!("{what}: kept sub-mesh {d}"), p, q);
    }
    assert_eq!(x.in_sub, y.in_sub, "{what}: level-to-sub-mesh maps");
    assert_eq!(x.chosen, y.chosen, "{what}: refined faces");
    assert_eq!(x.leaves, y.leaves, "{what}: leaves");
    assert_eq!(x.tags, y.tags, "{what}: vertex tags");
}

/// `mesh` with the edits applied to its tags (the fresh build's input).
fn edit_mesh(mesh: &Mesh, edits: &[SharpnessEdit]) -> Mesh {
    let mut m = mesh.clone();
    for e in edits {
        match *e {
            SharpnessEdit::Edge { v0, v1, sharpness } => {
                m.creases
                    .retain(|c| !((c.v0, c.v1) == (v0, v1) || (c.v0, c.v1) == (v1, v0)));
                m.creases.push(Crease { v0, v1, sharpness });
            }
            SharpnessEdit::Vertex { vertex, sharpness } => {
                m.corners.retain(|c| c.vertex != vertex);
                m.corners.push(Corner { vertex, sharpness });
            }
        }
    }
    m
}

const VALUES: [f32; 8] = [0.0, 0.3, 1.0, 1.7, 2.0, 3.5, 7.25, 10.0];

/// Random edits on a creased mesh: tagged creases and corners moved, untagged edges and
/// vertices made sharp; with `nudge`, only tagged creases moved within their sharpness
/// interval (`ceil(s)` kept: the same levels decay them, mostly keeping the structure).
fn random_edits(mesh: &Mesh, t: &Topology, rng: &mut Lcg, nudge: bool) -> Vec<SharpnessEdit> {
    let mut edits = Vec::new();
    for _ in 0..1 + rng.next(6) {
        let sharpness = VALUES[rng.next(VALUES.len())];
        if nudge {
            let Some(c) = (!mesh.creases.is_empty())
                .then(|| mesh.creases[rng.next(mesh.creases.len())])
                .filter(|c| c.sharpness > 0.0 && c.sharpness < 10.0)
            else {
                continue;
            };
            let top = c.sharpness.ceil();
            edits.push(SharpnessEdit::Edge {
                v0: c.v0,
                v1: c.v1,
                sharpness: top - [0.0, 0.25, 0.5, 0.875][rng.next(4)],
            });
            continue;
        }
        edits.push(match rng.next(4) {
            0 | 1 if !mesh.creases.is_empty() => {
                let c = mesh.creases[rng.next(mesh.creases.len())];
                SharpnessEdit::Edge {
                    v0: c.v0,
                    v1: c.v1,
                    sharpness,
                }
            }
            2 => {
                let [v0, v1] = t.edge_vertices(rng.next(t.num_edges()));
                SharpnessEdit::Edge { v0, v1, sharpness }
            }
            _ => SharpnessEdit::Vertex {
                vertex: rng.next(t.num_vertices()) as u32,
                sharpness,
            },
        });
    }
    edits
}

/// Every creased catmark shape, four rounds of random edits each (edges and vertices, one
/// or many at once, single-crease patches on and off, alternately anywhere and within the
/// creases' sharpness intervals): the edited table is the fresh build of the edited mesh,
/// bit for bit, whether it was updated in place (structure kept), rebuilt below the levels
/// whose structure is kept, or rebuilt (structure changed at the base), and all three
/// happen; the levels it keeps for the next edit are those a fresh editable build keeps.
#[test]
fn edited_tables_equal_fresh_builds_on_every_creased_shape() {
    let mut rng = Lcg(0x5eed);
    let (mut shapes, mut updated, mut rebuilt, mut resumed, mut local) = (0, 0, 0, 0, 0);
    for name in shape_names() {
        let mesh = load_shape(&name);
        if mesh.creases.is_empty() && mesh.corners.is_empty() {
            continue;
        }
        if mesh.options.boundary == subsurf::BoundaryInterpolation::None {
            continue;
        }
        shapes += 1;
        let topo = Topology::new(&mesh).unwrap();
        let options = PatchOptions {
            single_crease: rng.next(3) != 0,
            ..Default::default()
        };
        let mut table = PatchTable::build(&topo, &options).unwrap();
        // Every other shape's changes of structure local whatever their region's size.
        if shapes % 2 == 0 {
            table.set_local_edit_share(1.0);
        }
        let mut current = mesh.clone();
        let mut spliced = false;
        let mut built = table.num_points();
        for round in 0..4 {
            let edits = random_edits(&mesh, &topo, &mut rng, round % 2 == 1);
            match table.apply_sharpness(&edits).unwrap() {
                EditOutcome::Updated => updated += 1,
                EditOutcome::RebuiltFrom { .. } => {
                    resumed += 1;
                    spliced = false;
                }
                EditOutcome::Rebuilt => {
                    rebuilt += (round > 0) as usize;
                    spliced = false;
                }
                EditOutcome::Local { .. } => {
                    local += 1;
                    spliced = true;
                }
                EditOutcome::Unchanged => {}
            }
            // Compacted when it would grow past twice the points of its last build.
            if !spliced {
                built = table.num_points();
            }
            assert!(table.num_points() <= 2 * built, "{name}: points");
            current = edit_mesh(&current, &edits);
            let t = Topology::new(&current).unwrap();
            let fresh = PatchTable::build(&t, &options).unwrap();
            let what = format!("{name} round {round} {edits:?}");
            // A table edited locally makes the fresh build's surface (its numbering
            // differs); any other, the fresh build's arrays.
            assert_same_surface(&what, &current, &table, &fresh);
            if spliced {
                assert!(!table.is_editable(), "{what}");
                continue;
            }
            assert_same(&what, &table, &fresh);
            // A table keeps levels from its first edit that changes it.
            if table.is_editable() {
                let editable = PatchTable::build_editable(&t, &options).unwrap();
                assert_same_kept(&what, &table, &editable);
            }
        }
    }
    assert!(shapes >= 20, "{shapes} creased shapes");
    eprintln!("{updated} in place, {rebuilt} rebuilt, {resumed} resumed, {local} local");
    assert!(
        updated >= 10 && rebuilt >= 5 && resumed >= 3 && local >= 10,
        "{updated} edits in place, {rebuilt} rebuilds, {resumed} rebuilt below kept levels, \
         {local} local"
    );
}

/// A table built editable is a plain build's, bit for bit, and keeps its levels: its first
/// edit that keeps the structure is made in place (a plain build's first edit rebuilds), and
/// equals the fresh build of the edited mesh, on every creased shape (`f32`) and on the car
/// (`f64`).
#[test]
fn editable_builds_make_their_first_edit_in_place() {
    let mut rng = Lcg(0xed17);
    let (mut shapes, mut in_place) = (0, 0);
    for name in shape_names() {
        let mesh = load_shape(&name);
        if mesh
            .creases
            .iter()
            .all(|c| !(c.sharpness > 0.0 && c.sharpness < 10.0))
            || mesh.options.boundary == subsurf::BoundaryInterpolation::None
        {
            continue;
        }
        shapes += 1;
        let topo = Topology::new(&mesh).unwrap();
        let o = PatchOptions::default();
        let plain = PatchTable::build(&topo, &o).unwrap();
        let mut editable = PatchTable::build_editable(&topo, &o).unwrap();
        assert!(editable.is_editable() && !plain.is_editable(), "{name}");
        assert_same(&format!("{name} editable build"), &editable, &plain);
        let edits = random_edits(&mesh, &topo, &mut rng, true);
        let outcome = editable.apply_sharpness(&edits).unwrap();
        let edited = edit_mesh(&mesh, &edits);
        let fresh = PatchTable::build(&Topology::new(&edited).unwrap(), &o).unwrap();
        let what = format!("{name} {edits:?}");
        if matches!(outcome, EditOutcome::Local { .. }) {
            // A change of structure, made locally: the fresh build's surface.
            assert_same_surface(&what, &edited, &editable, &fresh);
        } else {
            assert_same(&what, &editable, &fresh);
        }
        if outcome == EditOutcome::Updated {
            in_place += 1;
            // The same edit on the plain build rebuilds it.
            let mut p = plain.clone();
            assert_eq!(p.apply_sharpness(&edits).unwrap(), EditOutcome::Rebuilt);
        }
    }
    assert!(
        shapes >= 5 && in_place >= 3,
        "{in_place} of {shapes} shapes edited in place"
    );

    let mesh = load_shape("catmark_car");
    let topo = Topology::new(&mesh).unwrap();
    let o = PatchOptions::default();
    let mut table = PatchTable::<f64>::build_editable_real(&topo, &o).unwrap();
    assert_same(
        "car, f64",
        &table,
        &PatchTable::<f64>::build_real(&topo, &o).unwrap(),
    );
    let edits = SharpnessEdit::creases(&mesh.creases, Some(3.5));
    assert_eq!(table.apply_sharpness(&edits).unwrap(), EditOutcome::Updated);
    let m = edit_mesh(&mesh, &edits);
    let fresh = PatchTable::<f64>::build_real(&Topology::new(&m).unwrap(), &o).unwrap();
    assert_same("car at 3.5, f64", &table, &fresh);
}

/// The car's 314 creases from their sharpness to 2, 3.5, 2, 3.5 and back, on the `f64`
/// table: the fresh build each way (with the levels kept for edits), 2 <-> 3.5 rebuilt from
/// level 2 (the levels above kept: 8 level-2 faces are isolated further at 3.5), and the
/// original table at the end (updated in place: moving the creases from 3.5 to their own 6
/// keeps the structure).
#[test]
fn car_creases_there_and_back_on_the_f64_table() {
    let mesh = load_shape("catmark_car");
    let topo = Topology::new(&mesh).unwrap();
    let o = PatchOptions::default();
    let original = PatchTable::<f64>::build_real(&topo, &o).unwrap();
    let mut table = original.clone();
    let to = |s: Option<f32>| -> Vec<SharpnessEdit> { SharpnessEdit::creases(&mesh.creases, s) };
    // The first edit keeps the levels, the next ones update the table in place.
    let at = |s: f32| {
        let m = edit_mesh(&mesh, &to(Some(s)));
        PatchTable::<f64>::build_real(&Topology::new(&m).unwrap(), &o).unwrap()
    };
    assert_eq!(
        table.apply_sharpness(&to(Some(2.0))).unwrap(),
        EditOutcome::Rebuilt
    );
    assert_same("car at 2", &table, &at(2.0));
    for s in [3.5, 2.0, 3.5] {
        assert_eq!(
            table.apply_sharpness(&to(Some(s))).unwrap(),
            EditOutcome::RebuiltFrom { level: 2 },
            "to {s}"
        );
        assert_same(&format!("car at {s}"), &table, &at(s));
        let m = edit_mesh(&mesh, &to(Some(s)));
        let editable = PatchTable::<f64>::build_editable_real(&Topology::new(&m).unwrap(), &o);
        assert_same_kept(&format!("car at {s}"), &table, &editable.unwrap());
    }
    assert_eq!(
        table.apply_sharpness(&to(None)).unwrap(),
        EditOutcome::Updated
    );
    assert_same("car back", &table, &original);
    // The same values again change nothing.
    assert!(!table.set_sharpness(&to(None)).unwrap());
}

/// A missing edge, a vertex out of range, NaN and negative sharpness: a `BadSharpnessEdit`
/// naming the edit and the value, the table untouched even when good edits come first.
#[test]
fn bad_edits_are_refused_before_any_work() {
    let mesh = load_shape("catmark_cube_creases1");
    let topo = Topology::new(&mesh).unwrap();
    let table = PatchTable::build(&topo, &PatchOptions::default()).unwrap();
    let good = SharpnessEdit::Vertex {
        vertex: 0,
        sharpness: 2.0,
    };
    for (bad, words) in [
        (
            SharpnessEdit::Edge {
                v0: 0,
                v1: 7,
                sharpness: 1.0,
            },
            vec!["0", "7", "not joined"],
        ),
        (
            SharpnessEdit::Edge {
                v0: 0,
                v1: 99,
                sharpness: 1.0,
            },
            vec!["99"],
        ),
        (
            SharpnessEdit::Vertex {
                vertex: 8,
                sharpness: 1.0,
            },
            vec!["vertex 8"],
        ),
        (
            SharpnessEdit::Edge {
                v0: 0,
                v1: 1,
                sharpness: f32::NAN,
            },
            vec!["NaN"],
        ),
        (
            SharpnessEdit::Vertex {
                vertex: 1,
                sharpness: -0.5,
            },
            vec!["-0.5"],
        ),
    ] {
        let mut t = table.clone();
        let err = t.set_sharpness(&[good, bad]).unwrap_err();
        let msg = err.to_string();
        assert!(
            matches!(
                err,
                Error::Mesh(MeshError::BadSharpnessEdit { edit: 1, .. })
            ),
            "{err:?}"
        );
        assert!(words.iter().all(|w| msg.contains(w)), "{msg}");
        assert_same("refused", &t, &table);
    }
}

/// `rounds` random edits of a table made local whatever their region's size, each checked
/// against the fresh build of the edited mesh: the same surface bit for bit
/// ([`assert_same_surface`]), no more than twice the fresh build's patches, and no more than
/// twice the points of the table's last build (compacted, a rebuild, when it would). Returns
/// the edits made locally.
fn local_sequence<R: Real>(name: &str, mesh: &Mesh, rounds: usize, rng: &mut Lcg) -> usize {
    let topo = Topology::new(mesh).unwrap();
    let options = PatchOptions {
        single_crease: rng.next(3) != 0,
        ..Default::default()
    };
    let mut table = PatchTable::<R>::build_editable_real(&topo, &options).unwrap();
    table.set_local_edit_share(1.0);
    let (mut current, mut built, mut local) = (mesh.clone(), table.num_points(), 0);
    for round in 0..rounds {
        let edits = random_edits(mesh, &topo, rng, round % 3 == 1);
        let outcome = table.apply_sharpness(&edits).unwrap();
        match outcome {
            EditOutcome::Local { faces } => {
                local += 1;
                assert!(faces > 0, "{name}");
            }
            EditOutcome::Unchanged => {}
            // In place (levels kept, structure kept) or compacted.
            _ => built = table.num_points(),
        }
        assert!(
            table.num_points() <= 2 * built,
            "{name} round {round}: points"
        );
        current = edit_mesh(&current, &edits);
        let fresh = PatchTable::<R>::build_real(&Topology::new(&current).unwrap(), &options);
        let what = format!("{name} round {round} {outcome:?} {edits:?}");
        assert_same_surface(&what, &current, &table, &fresh.unwrap());
    }
    local
}

/// Random edit sequences on every creased shape, every change of structure made locally
/// (after one, every edit: the table keeps no levels), and on the car's `f64` table: the
/// fresh build's surface after every edit.
#[test]
fn local_edits_make_the_fresh_surface_on_every_creased_shape() {
    let mut rng = Lcg(0x10ca1);
    let (mut shapes, mut local) = (0, 0);
    for name in shape_names() {
        let mesh = load_shape(&name);
        if (mesh.creases.is_empty() && mesh.corners.is_empty())
            || mesh.options.boundary == subsurf::BoundaryInterpolation::None
        {
            continue;
        }
        shapes += 1;
        local += local_sequence::<f32>(&name, &mesh, 6, &mut rng);
    }
    local += local_sequence::<f64>("car, f64", &load_shape("catmark_car"), 4, &mut rng);
    assert!(
        shapes >= 20 && local >= shapes,
        "{local} local edits on {shapes} shapes"
    );
}

/// On a table that shares its sub-meshes by default (one half of the base faces), an edit
/// whose region is smaller is local, a larger one takes the other paths (the car's 314
/// creases: rebuilt below the kept levels, `car_creases_there_and_back_on_the_f64_table`).
#[test]
fn one_crease_of_the_car_is_a_local_edit() {
    let mesh = load_shape("catmark_car");
    let topo = Topology::new(&mesh).unwrap();
    let o = PatchOptions::default();
    let mut table = PatchTable::build_editable(&topo, &o).unwrap();
    let c = mesh.creases[0];
    // Smooth: the crease's ends are no longer isolated (a change of structure at the base).
    let edits = [SharpnessEdit::Edge {
        v0: c.v0,
        v1: c.v1,
        sharpness: 0.0,
    }];
    let outcome = table.apply_sharpness(&edits).unwrap();
    assert!(
        matches!(outcome, EditOutcome::Local { faces } if faces < 64),
        "{outcome:?}"
    );
    let edited = edit_mesh(&mesh, &edits);
    let fresh = PatchTable::build(&Topology::new(&edited).unwrap(), &o).unwrap();
    assert_same_surface("car, one crease", &edited, &table, &fresh);
    // Every edit after is local, back to the original surface.
    let back = SharpnessEdit::creases(&mesh.creases[..1], None);
    assert!(matches!(
        table.apply_sharpness(&back).unwrap(),
        EditOutcome::Local { .. }
    ));
    let original = PatchTable::build(&topo, &o).unwrap();
    assert_same_surface("car, back", &mesh, &table, &original);
}

/// 1,000 random edits on the car, the table edited locally throughout: the fresh build's
/// surface after each of them (no drift), the table never past twice the fresh build's
/// patches nor twice the points of its last build. Slow in debug: `--ignored`.
#[test]
#[ignore]
fn a_thousand_local_edits_on_the_car() {
    let mut rng = Lcg(0x1000);
    let mesh = load_shape("catmark_car");
    let local = local_sequence::<f32>("car", &mesh, 1000, &mut rng);
    eprintln!("{local} of 1000 edits local");
    assert!(local >= 500, "{local}");
}
