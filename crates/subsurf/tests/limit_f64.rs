//! The double-precision limit surface (`PatchTable::<f64>::build_real`: masks, end-cap
//! weights, points and basis in `f64`) against OpenSubdiv 3.5's double-precision evaluation
//! (`osd_ref::eval_limit_grid_f64`: `PrimvarRefinerReal<double>`, `SetPatchPrecision<double>`,
//! `EvaluateBasis<double>`), and the `f32` table against the `f64` one's patches.
//!
//! The two differ by the order of their sums only, so positions and derivatives agree to
//! 1e-12 of the bounding-box diagonal and unit normals to 1e-9 rad (away from degenerate
//! tangent planes). Measured at isolation level 4 over every catmark shape: B-spline and
//! single-crease patches 7.9e-15 and 3.3e-13 rad, Gregory end caps (whose local points are
//! not shared between neighbours as OpenSubdiv's are, but have the same values)
//! 6.4e-14 and 5.6e-11 rad (the valence-360 pole).

mod limit_common;

use limit_common::{angle, cross, dot};

use limit_common::{load_shape, osd_or_skip, shape_names};
use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdPatchOptions};
use subsurf::limit::{LimitPoint, LimitSurface, PatchOptions, PatchTable, PatchType};
use subsurf::patch::{patch_weights, PatchKind};
use subsurf::{Mesh, Topology};

/// `|∂P/∂u × ∂P/∂v| <= DEGENERATE max(|∂P/∂u|, |∂P/∂v|)²`: no tangent plane to compare.
const DEGENERATE: f64 = 1e-6;

/// Worst deviations from OpenSubdiv in double precision.
#[derive(Debug, Default, Clone, Copy)]
struct Deviation {
    samples: usize,
    /// Position and first derivatives on B-spline and single-crease patches, relative to
    /// the bounding-box diagonal.
    regular: f64,
    /// Normal angle (radians) on B-spline and single-crease patches.
    regular_normal: f64,
    /// The same on Gregory end caps.
    end_cap: f64,
    end_cap_normal: f64,
    /// Single-crease patches among the samples' patches.
    single_crease_samples: usize,
}

/// Like OpenSubdiv 3.5's CPU `EvaluateBasis`, which evaluates a single-crease patch as a
/// B-spline patch with its crease edge a boundary; other patches as `eval_raw`.
fn osd_like_eval(s: &LimitSurface<f64>, f: usize, u: f64, v: f64) -> Option<LimitPoint<f64>> {
    let p = s.table().patch_map().find(f, u, v)? as usize;
    if s.table().patch_type(p) != PatchType::SingleCrease {
        return s.eval_raw(f, u, v);
    }
    let w = patch_weights(PatchKind::Regular, &s.table().params()[p], 0.0f64, u, v);
    let cvs = s.table().patch_cvs(p);
    let x0 = s.points()[cvs[0] as usize];
    let mut r = LimitPoint::<f64>::default();
    for (k, &cv) in cvs.iter().enumerate() {
        let x = s.points()[cv as usize];
        for c in 0..3 {
            let d = x[c] - x0[c];
            r.p[c] += w.p[k] * d;
            r.du[c] += w.du[k] * d;
            r.dv[c] += w.dv[k] * d;
        }
    }
    (0..3).for_each(|c| r.p[c] += x0[c] + s.origin()[c]);
    Some(r)
}

fn compare(name: &str, mesh: &Mesh, level: u32, n: usize) -> Deviation {
    let o = OsdPatchOptions {
        isolation_level: level,
        use_single_crease: true,
        use_inf_sharp: false,
        end_cap: EndCap::Gregory,
    };
    let osd = osd_ref::eval_limit_grid_f64(&OsdMesh::from(mesh), n, &o)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let options = PatchOptions {
        isolation_level: level,
        single_crease: true,
        cap_crease_sharpness: true,
    };
    let table = PatchTable::<f64>::build_real(&Topology::new(mesh).unwrap(), &options).unwrap();
    let s = LimitSurface::new(table, &mesh.positions);
    let diag = f64::from(subsurf::mesh::bbox_diagonal(&mesh.positions));
    let mut e = Deviation {
        samples: osd.len(),
        ..Default::default()
    };
    for o in &osd {
        let (f, u, v) = (o.face as usize, f64::from(o.u), f64::from(o.v));
        let r = osd_like_eval(&s, f, u, v)
            .unwrap_or_else(|| panic!("{name}: no patch at ptex {f} ({u}, {v})"));
        let d = |a: [f64; 3], b: [f64; 3]| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max);
        let dev = d(r.p, o.p).max(d(r.du, o.du)).max(d(r.dv, o.dv)) / diag;
        let p = s.table().patch_map().find(f, u, v).unwrap() as usize;
        let want = cross(o.du, o.dv);
        let scale = dot(o.du, o.du).max(dot(o.dv, o.dv));
        let normal = if dot(want, want).sqrt() > DEGENERATE * scale {
            angle(cross(r.du, r.dv), want)
        } else {
            0.0
        };
        match s.table().patch_type(p) {
            PatchType::Gregory => {
                e.end_cap = e.end_cap.max(dev);
                e.end_cap_normal = e.end_cap_normal.max(normal);
            }
            kind => {
                e.single_crease_samples += (kind == PatchType::SingleCrease) as usize;
                e.regular = e.regular.max(dev);
                e.regular_normal = e.regular_normal.max(normal);
            }
        }
    }
    e
}

/// Every catmark regression shape at isolation level 4: B-spline, single-crease and Gregory
/// patches within 1e-12 of the diagonal and 1e-9 rad of OpenSubdiv's double-precision
/// surface (the worst figures are printed).
#[test]
fn f64_matches_opensubdiv_f64_on_every_catmark_shape() {
    if !osd_or_skip("f64_matches_opensubdiv_f64_on_every_catmark_shape") {
        return;
    }
    let (mut failures, mut worst, mut creases) = (Vec::new(), Deviation::default(), 0);
    for name in shape_names() {
        let mesh = load_shape(&name);
        let n = if mesh.num_faces() > 150 { 4 } else { 6 };
        let e = compare(&name, &mesh, 4, n);
        eprintln!("{name:28} {e:?}");
        creases += e.single_crease_samples;
        worst.regular = worst.regular.max(e.regular);
        worst.regular_normal = worst.regular_normal.max(e.regular_normal);
        worst.end_cap = worst.end_cap.max(e.end_cap);
        worst.end_cap_normal = worst.end_cap_normal.max(e.end_cap_normal);
        if e.samples == 0
            || e.regular > 1e-12
            || e.regular_normal > 1e-9
            || e.end_cap > 1e-12
            || e.end_cap_normal > 1e-9
        {
            failures.push(format!("{name}: {e:?}"));
        }
    }
    eprintln!("worst over all shapes: {worst:?}");
    assert!(creases > 0, "no single-crease patch was sampled");
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The `f64` table has the `f32` table's patches, and its weights round to the `f32`
/// table's (the masks are evaluated by the same code in either type; blended crease masks
/// round differently, within a few `f32` ulps).
#[test]
fn f64_table_has_the_f32_tables_patches() {
    let close = |name: &str, a: &[f32], b: &[f64]| {
        assert_eq!(a.len(), b.len(), "{name}");
        for (&x, &y) in a.iter().zip(b) {
            assert!(
                (f64::from(x) - y).abs() <= 4e-7 * y.abs().max(1e-3),
                "{name}: {x} {y}"
            );
        }
    };
    for name in ["catmark_car", "catmark_gregory_test6", "catmark_chaikin1"] {
        let mesh = load_shape(name);
        let topo = Topology::new(&mesh).unwrap();
        let o = PatchOptions::default();
        let a = PatchTable::build(&topo, &o).unwrap();
        let b = PatchTable::<f64>::build_real(&topo, &o).unwrap();
        assert_eq!(a.kinds(), b.kinds(), "{name}");
        assert_eq!(a.cvs(), b.cvs(), "{name}");
        assert_eq!(a.params(), b.params(), "{name}");
        assert_eq!(a.sharpness(), b.sharpness(), "{name}");
        assert_eq!(a.patch_map(), b.patch_map(), "{name}");
        assert_eq!(
            a.local_points().indices(),
            b.local_points().indices(),
            "{name}"
        );
        close(name, a.local_points().weights(), b.local_points().weights());
        assert_eq!(a.level_stencils().len(), b.level_stencils().len(), "{name}");
        for (x, y) in a.level_stencils().iter().zip(b.level_stencils()) {
            for (s, t) in [
                (&x.face(), &y.face()),
                (&x.vertex(), &y.vertex()),
                (&x.edge(), &y.edge()),
            ] {
                assert_eq!(s.offsets(), t.offsets(), "{name}");
                assert_eq!(s.indices(), t.indices(), "{name}");
                close(name, s.weights(), t.weights());
            }
        }
    }
}

/// Worst normal angle (rad) of the `f32` surface of `mesh` on base positions `ours` against
/// OpenSubdiv's double-precision evaluation of the mesh's own (`f64`) positions, isolation 4,
/// where the tangent plane is not degenerate.
fn f32_normal_error(name: &str, mesh: &Mesh, ours: &subsurf::Positions) -> f64 {
    // Without single-crease patches, which OpenSubdiv 3.5 evaluates as B-spline patches
    // (`osd_like_eval`).
    let o = OsdPatchOptions {
        isolation_level: 4,
        use_single_crease: false,
        use_inf_sharp: false,
        end_cap: EndCap::Gregory,
    };
    let osd = osd_ref::eval_limit_grid_f64(&OsdMesh::from(mesh), 5, &o)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let options = PatchOptions {
        isolation_level: 4,
        single_crease: false,
        cap_crease_sharpness: true,
    };
    let s = LimitSurface::new(
        PatchTable::build(&Topology::new(mesh).unwrap(), &options).unwrap(),
        ours,
    );
    let mut worst = 0.0f64;
    for o in &osd {
        let r = s.eval(o.face as usize, o.u, o.v).unwrap();
        let want = cross(o.du, o.dv);
        let scale = dot(o.du, o.du).max(dot(o.dv, o.dv));
        if dot(want, want).sqrt() > DEGENERATE * scale {
            worst = worst.max(angle(r.n.map(f64::from), want));
        }
    }
    worst
}

/// A mesh far from the origin (10⁶ of its diagonals out, in `f64`): the `f32` surface keeps
/// its points relative to a local origin, so its normals stay within 1e-3 rad of OpenSubdiv's
/// double evaluation, on the car and on every catmark shape; from the same positions rounded
/// to `f32` first (the shape lost before the surface sees it) they do not.
#[test]
fn f32_normals_of_a_far_mesh_match_opensubdiv_f64() {
    if !osd_or_skip("f32_normals_of_a_far_mesh_match_opensubdiv_f64") {
        return;
    }
    let far = |m: &Mesh| {
        let d = f64::from(subsurf::mesh::bbox_diagonal(&m.positions)).max(1e-3);
        let t = [1e6 * d + 1.0 / 3.0, -0.25e6 * d, 0.5e6 * d];
        let p = m.positions.to_f64();
        Mesh {
            positions: subsurf::Positions::from_f64(
                p.iter()
                    .map(|p| [p[0] + t[0], p[1] + t[1], p[2] + t[2]])
                    .collect(),
            ),
            ..m.clone()
        }
    };
    let (mut worst, mut failures) = ((0.0f64, String::new()), Vec::new());
    for name in shape_names() {
        let mesh = far(&load_shape(&name));
        if Topology::new(&mesh).is_err() || mesh.num_faces() > 3000 {
            continue;
        }
        assert!(mesh.positions.is_f64(), "{name}");
        let e = f32_normal_error(&name, &mesh, &mesh.positions);
        if e > worst.0 {
            worst = (e, name.clone());
        }
        if e > 1e-3 {
            failures.push(format!("{name}: {e:e} rad"));
        }
    }
    eprintln!("worst normal: {:e} rad ({})", worst.0, worst.1);
    assert!(failures.is_empty(), "{failures:#?}");
    let car = far(&load_shape("catmark_car"));
    let table = PatchTable::build(&Topology::new(&car).unwrap(), &PatchOptions::default());
    let s = LimitSurface::new(table.unwrap(), &car.positions);
    assert_ne!(s.origin(), [0.0; 3]);
    let rounded = subsurf::Positions::from(car.positions.to_vec());
    let lost = f32_normal_error("catmark_car (rounded)", &car, &rounded);
    eprintln!("positions rounded to f32 first: {lost:e} rad");
    assert!(lost > 1e-2, "{lost:e}");
}
