//! Isolation chosen per region (`PatchTable::build_face_levels`, `limit::tolerance`): each
//! region's patches are those of a table isolated to its level everywhere; a tolerance keeps
//! every end cap within its share of the true limit surface (an isolation-10 reference) and
//! the whole tessellation within the tolerance; bad levels and budgets are refused.

mod limit_common;

use limit_common::{bbox_diagonal, dist, isolated, load_shape, Lcg};
use subsurf::limit::split_tolerance;
use subsurf::limit::{
    build_for_tolerance, choose_isolation, IsolationChoice, LimitSurface, PatchTable, PatchType,
    SharpnessEdit,
};
use subsurf::surface::{adaptive_surface, tessellate_adaptive, Cpu};
use subsurf::tess::{plan, AdaptiveTessellation, DeviationOptions, DeviationReference, RatePolicy};
use subsurf::{Error, Mesh, TessError, Topology};

fn surface(mesh: &Mesh, table: PatchTable<f64>) -> LimitSurface<f64> {
    LimitSurface::new(table, &mesh.positions)
}

/// The patches of each ptex face as `(type, param)`, in table order.
fn patches_of(t: &PatchTable<f64>) -> Vec<Vec<(PatchType, subsurf::patch::PatchParam)>> {
    let mut out = vec![Vec::new(); t.num_ptex_faces()];
    for p in 0..t.num_patches() {
        out[t.params()[p].face_id() as usize].push((t.patch_type(p), t.params()[p]));
    }
    out
}

/// With random levels per base face, every base face has the patches (types and parameters,
/// in order) of the table isolated to its level everywhere, and the same limit surface there.
#[test]
fn each_region_is_the_table_of_its_level() {
    let mut rng = Lcg(7);
    for name in [
        "catmark_pawn",
        "catmark_gregory_test4",
        "catmark_xord_boundary",
        "catmark_smoothtris0",
        "catmark_cube_creases1",
        "catmark_hole_test1",
        "catmark_nonman_verts",
        "catmark_chaikin1",
    ] {
        let mesh = load_shape(name);
        let t = Topology::new(&mesh).unwrap();
        let levels: Vec<u8> = (0..t.num_faces()).map(|_| 2 + rng.next(4) as u8).collect();
        let mixed = PatchTable::<f64>::build_face_levels(&t, &isolated(2), &levels).unwrap();
        assert_eq!(mixed.face_levels(), Some(&levels[..]), "{name}");
        let uniform: Vec<PatchTable<f64>> = (2..6)
            .map(|l| PatchTable::build_real(&t, &isolated(l)).unwrap())
            .collect();
        let (pm, pu) = (
            patches_of(&mixed),
            uniform.iter().map(patches_of).collect::<Vec<_>>(),
        );
        let sm = surface(&mesh, mixed.clone());
        let su: Vec<_> = uniform.into_iter().map(|u| surface(&mesh, u)).collect();
        let diag = f64::from(bbox_diagonal(&mesh.positions));
        let mut worst = 0.0f64;
        for f in 0..t.num_faces() {
            let l = levels[f] as usize - 2;
            for ptex in mixed.ptex_offsets()[f]..mixed.ptex_offsets()[f + 1] {
                let ptex = ptex as usize;
                assert_eq!(pm[ptex], pu[l][ptex], "{name}: ptex face {ptex}");
                for i in 0..=6 {
                    for j in 0..=6 {
                        let (u, v) = (i as f64 / 6.0, j as f64 / 6.0);
                        if let (Some(a), Some(b)) = (
                            sm.eval_position(ptex, u, v),
                            su[l].eval_position(ptex, u, v),
                        ) {
                            worst = worst.max(dist(a, b));
                        }
                    }
                }
            }
        }
        assert!(worst <= 1e-12 * diag, "{name}: {worst:e}");
    }
}

/// Levels no higher than the table's give the plain table; levels past the maximum, or a list
/// of the wrong length, are refused naming the face or the count.
#[test]
fn plain_levels_give_the_plain_table_and_bad_levels_are_refused() {
    let mesh = load_shape("catmark_pawn");
    let t = Topology::new(&mesh).unwrap();
    let plain = PatchTable::<f64>::build_real(&t, &isolated(4)).unwrap();
    let low =
        PatchTable::<f64>::build_face_levels(&t, &isolated(4), &vec![2; t.num_faces()]).unwrap();
    assert!(low.face_levels().is_none());
    assert_eq!(low.kinds(), plain.kinds());
    assert_eq!(low.params(), plain.params());
    assert_eq!(low.cvs(), plain.cvs());
    assert_eq!(low.patch_map(), plain.patch_map());

    let mut levels = vec![4u8; t.num_faces()];
    levels[17] = 11;
    let e = PatchTable::<f64>::build_face_levels(&t, &isolated(4), &levels).unwrap_err();
    assert!(
        matches!(&e, Error::Unsupported(m) if m.contains("level 11 of base face 17")),
        "{e}"
    );
    let e = PatchTable::<f64>::build_face_levels(&t, &isolated(4), &levels[1..]).unwrap_err();
    assert!(
        matches!(&e, Error::Unsupported(m) if m.contains(&format!("{} base faces", t.num_faces()))),
        "{e}"
    );
    for bad in [0.0f32, -1.0, f32::NAN, f32::INFINITY] {
        let e = choose_isolation::<f32>(&t, &isolated(4), &mesh.positions, bad).unwrap_err();
        assert!(
            matches!(&e, Error::Unsupported(m) if m.contains("positive finite")),
            "{e}"
        );
    }
}

/// The largest distance between `s`'s patches of the types `kinds` and the reference `r`,
/// over a 9 x 9 grid of each, as a fraction of `diag`.
fn deviation_of(
    s: &LimitSurface<f64>,
    r: &LimitSurface<f64>,
    diag: f64,
    kinds: &[PatchType],
) -> f64 {
    let t = &s.table();
    let mut worst = 0.0f64;
    for p in (0..t.num_patches()).filter(|&p| kinds.contains(&t.patch_type(p))) {
        let pp = t.params()[p];
        let ptex = pp.face_id() as usize;
        for i in 0..=8 {
            for j in 0..=8 {
                let (u, v) = pp.unnormalize(i as f64 / 8.0, j as f64 / 8.0);
                let a = s.eval_position(ptex, u, v).unwrap();
                let b = r.eval_position(ptex, u, v).unwrap();
                worst = worst.max(dist(a, b) / diag);
            }
        }
    }
    worst
}

/// What `build_for_tolerance` at isolation 4 does to shape `name` under `budget`.
struct Choice {
    /// The topology.
    t: Topology,
    /// The worst distance of the patches of the measured types to the isolation-10 surface,
    /// as a fraction of the diagonal, at isolation 4 everywhere and with the choice.
    before: f64,
    after: f64,
    /// The choice.
    choice: IsolationChoice,
    /// Base faces isolated deeper than 4.
    deeper: usize,
}

/// [`Choice`] of shape `name`, measured on the patches of the types `kinds`.
fn choose(name: &str, budget: f32, kinds: &[PatchType]) -> Choice {
    let mesh = load_shape(name);
    let t = Topology::new(&mesh).unwrap();
    let diag = f64::from(bbox_diagonal(&mesh.positions));
    let reference = surface(&mesh, PatchTable::build_real(&t, &isolated(10)).unwrap());
    let plain = surface(&mesh, PatchTable::build_real(&t, &isolated(4)).unwrap());
    let before = deviation_of(&plain, &reference, diag, kinds);
    let (table, choice) =
        build_for_tolerance::<f64>(&t, &isolated(4), &mesh.positions, budget).unwrap();
    let deeper = choice.face_levels.iter().filter(|&&l| l > 4).count();
    let after = deviation_of(&surface(&mesh, table), &reference, diag, kinds);
    Choice {
        t,
        before,
        after,
        choice,
        deeper,
    }
}

/// `build_for_tolerance`: every end cap within the budget of the isolation-10 surface, where
/// the default isolation 4 misses it; only the faces that need it are isolated deeper.
#[test]
fn end_caps_within_the_budget_of_the_true_limit() {
    for (name, budget) in [
        ("catmark_pawn", 2.5e-4f32),
        ("catmark_gregory_test4", 2.5e-4),
        ("catmark_xord_boundary", 1e-3),
        ("catmark_car", 2.5e-4),
    ] {
        let Choice {
            t,
            before,
            after,
            choice,
            deeper,
        } = choose(name, budget, &[PatchType::Gregory]);
        eprintln!(
            "{name}: budget {budget:e}: end caps {before:.2e} at isolation 4 -> {after:.2e}, \
             {deeper} of {} faces deeper (levels up to {})",
            t.num_faces(),
            choice.face_levels.iter().max().unwrap()
        );
        assert!(before > f64::from(budget), "{name}: {before:e}");
        assert!(after <= f64::from(budget), "{name}: {after:e} > {budget:e}");
        assert!(deeper > 0, "{name}: {deeper}");
        if t.num_faces() > 100 {
            assert!(deeper < t.num_faces() / 2, "{name}: {deeper}");
        }
        assert!(choice.face_levels.iter().all(|&l| l >= 4));
    }
}

/// At infinitely sharp crease loops and Chaikin creases the table's regular and single-crease
/// patches only approximate the limit surface too: the choice measures them with the end caps
/// and isolates their faces deeper, within the budget of the isolation-10 surface.
#[test]
fn sharp_features_are_isolated_deeper() {
    let kinds = [
        PatchType::Regular,
        PatchType::SingleCrease,
        PatchType::Gregory,
    ];
    for (name, budget) in [
        ("catmark_inf_crease0", 7.5e-4f32),
        ("catmark_fvar_project0", 7.5e-4),
        ("catmark_chaikin1", 2.5e-4),
    ] {
        let Choice {
            t,
            before,
            after,
            deeper,
            ..
        } = choose(name, budget, &kinds);
        eprintln!(
            "{name}: {before:.2e} at isolation 4 -> {after:.2e}, {deeper} of {} faces deeper",
            t.num_faces()
        );
        assert!(before > f64::from(budget), "{name}: {before:e}");
        assert!(deeper > 0, "{name}");
        assert!(after <= f64::from(budget), "{name}: {after:e} > {budget:e}");
    }
}

/// `--tolerance E` through the surface API: the tessellation within `E` of the true limit
/// surface (isolation 10), as the two-sided geometric deviation; the chords alone, on the
/// isolation-4 table, are not.
#[test]
fn tolerance_bounds_the_whole_approximation() {
    // (At 1e-3 the isolation-4 table's end caps are close enough along the normal.)
    let (name, e) = ("catmark_pawn", 5e-4f32);
    let mesh = load_shape(name);
    let t = Topology::new(&mesh).unwrap();
    let reference = surface(&mesh, PatchTable::build_real(&t, &isolated(10)).unwrap());
    let reference = DeviationReference::new(&reference, &DeviationOptions::default());
    // The two-sided deviation of a tessellation (positions, triangles, per triangle its ptex
    // face and corners' (u, v)).
    let worst = |out: &AdaptiveTessellation, uv: &[(u32, [[f32; 2]; 3])]| -> f64 {
        reference
            .measure(&out.positions, &out.triangles, Some(uv))
            .hausdorff()
    };
    let policy = RatePolicy::Tolerance(e);
    let (s, chords) =
        adaptive_surface(&t, &mesh.positions, &policy, "tolerance", &isolated(4)).unwrap();
    // The chords get 3/4 of it, or what the pole's end caps leave (at least half).
    let RatePolicy::Tolerance(c) = chords else {
        panic!("{chords:?}")
    };
    assert!(c >= e / 2.0 && c <= split_tolerance(e).1, "{c:e}");
    assert!(s.table().face_levels().is_some());
    let a = tessellate_adaptive(&s, &chords, "tolerance", &Cpu).unwrap();
    let whole = worst(&a.tessellation, &a.triangle_uv);
    // Before: the isolation-4 table, the whole tolerance given to the chords, no corner check.
    let plain = LimitSurface::new(
        PatchTable::build(&t, &isolated(4)).unwrap(),
        &mesh.positions,
    );
    let mut p = plan(plain.table(), &policy.rates(&plain, "").unwrap(), "").unwrap();
    let uv = std::mem::take(&mut p.triangle_uv);
    let before = worst(&plain.eval_plan(p), &uv);
    eprintln!(
        "{name} E={e}: {whole:.2e} with per-region isolation ({} triangles), {before:.2e} before",
        a.tessellation.triangles.len()
    );
    assert!(whole <= f64::from(e), "{whole:e}");
    assert!(before > f64::from(e), "{before:e}");
    let e = adaptive_surface(
        &t,
        &mesh.positions,
        &RatePolicy::Tolerance(-1.0),
        "--tolerance",
        &isolated(4),
    )
    .unwrap_err();
    assert!(e.to_string().contains("--tolerance"), "{e}");
    // At 3e-4 the pawn's pole keeps its end caps past 3e-4 / 4 at isolation 10: they take
    // their estimate (at most half), the chords the rest.
    let (s, chords) = adaptive_surface(
        &t,
        &mesh.positions,
        &RatePolicy::Tolerance(3e-4),
        "tolerance",
        &isolated(4),
    )
    .unwrap();
    let (_, choice) =
        build_for_tolerance::<f32>(&t, &isolated(4), &mesh.positions, 7.5e-5).unwrap();
    let worst = choice.deviation.iter().copied().fold(0.0f32, f32::max);
    assert!(worst > 7.5e-5 && worst <= 1.5e-4, "{worst:e}");
    assert_eq!(chords, RatePolicy::Tolerance(3e-4 - worst));
    assert_eq!(s.table().face_levels().as_ref().map(|l| l[576]), Some(10));
    // The pawn's pole keeps its end caps about 1.4e-4 off at isolation 10: 1e-4 is out of
    // reach (more than half of it), and said so.
    let e = adaptive_surface(
        &t,
        &mesh.positions,
        &RatePolicy::Tolerance(1e-4),
        "--tolerance",
        &isolated(4),
    )
    .unwrap_err();
    match &e {
        subsurf::surface::SurfaceError::Library(Error::Tess(TessError::ToleranceUnreachable {
            face,
            level,
            estimate,
            ..
        })) => {
            assert_eq!(*level, 10);
            assert!(*estimate > 5e-5);
            assert!((576..=587).contains(face), "{face}");
        }
        _ => panic!("{e}"),
    }
    assert!(
        e.to_string()
            .starts_with("--tolerance: tolerance 1e-4 is out of reach"),
        "{e}"
    );
}

/// A crease edit of a table with per-region levels equals a fresh build of the edited mesh at
/// the same levels.
#[test]
fn edits_keep_the_levels() {
    let mesh = load_shape("catmark_cube_creases1");
    let t = Topology::new(&mesh).unwrap();
    let levels: Vec<u8> = (0..t.num_faces()).map(|f| 3 + (f % 3) as u8).collect();
    let mut table = PatchTable::<f64>::build_face_levels(&t, &isolated(3), &levels).unwrap();
    let c = &mesh.creases[0];
    let edit = [SharpnessEdit::Edge {
        v0: c.v0,
        v1: c.v1,
        sharpness: c.sharpness + 1.5,
    }];
    assert!(table.set_sharpness(&edit).unwrap());
    let mut edited = mesh.clone();
    edited.creases[0].sharpness += 1.5;
    let fresh = PatchTable::<f64>::build_face_levels(
        &Topology::new(&edited).unwrap(),
        &isolated(3),
        &levels,
    )
    .unwrap();
    assert_eq!(table.face_levels(), fresh.face_levels());
    assert_eq!(table.kinds(), fresh.kinds());
    assert_eq!(table.params(), fresh.params());
    assert_eq!(table.cvs(), fresh.cvs());
    assert_eq!(table.patch_map(), fresh.patch_map());
    let bits = |s: &[f32]| s.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(table.sharpness()), bits(fresh.sharpness()));
    assert_eq!(table.level_offsets(), fresh.level_offsets());
}
