//! Limit normals against OpenSubdiv 3.5's double-precision evaluation
//! (`osd_ref::eval_limit_grid_f64`): refinement, end-cap points and basis all in `f64`.
//!
//! `f32` derivatives `Σ_k w'_k x_k` cancel when the patch is small next to `|x_k|` (the
//! derivative weights sum to 0): the rounding of each product is `ε |x_k|`, the result is of
//! the patch's size. [`LimitSurface::eval`] therefore weights `x_k − x_0` (exact for any
//! control point `x_0`, since the position weights sum to 1), so its error is relative to
//! the patch, not to the distance from the origin. These tests measure the angle between
//! subsurf's unit normal and OpenSubdiv's double-precision one, away from patch corners
//! (where the tangent plane of an extraordinary vertex is degenerate).

mod limit_common;

use limit_common::{angle, cross, dot};

use limit_common::{load_shape, osd_or_skip, shape_names};
use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdPatchOptions};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, PatchType};
use subsurf::{BoundaryInterpolation, Mesh, Topology};

/// Samples with both patch parameters within this of a patch edge are "at a corner".
const CORNER: f32 = 0.05;

/// `|∂P/∂u × ∂P/∂v| <= DEGENERATE max(|∂P/∂u|, |∂P/∂v|)²`: no tangent plane.
const DEGENERATE: f64 = 1e-6;

/// Worst normal angles (radians) away from patch corners.
#[derive(Debug, Default, Clone, Copy)]
struct NormalError {
    /// Samples compared (away from patch corners).
    samples: usize,
    /// On B-spline patches.
    regular: f64,
    /// On Gregory end caps.
    end_cap: f64,
    /// Worst position and first-derivative deviations over all samples, relative to the
    /// bounding-box diagonal (not asserted here; `limit_osd` bounds them against `f32`).
    position: f64,
    deriv: f64,
    /// `(ptex, u, v)` of the worst sample.
    worst_at: (u32, f32, f32),
}

impl NormalError {
    fn worst(&self) -> f64 {
        self.regular.max(self.end_cap)
    }
}

/// Normal angle error of subsurf's `LimitSurface::eval` against OpenSubdiv in double
/// precision on an `n × n` grid of every ptex face (B-spline patches and Gregory end caps,
/// no single-crease patches: OpenSubdiv's CPU basis ignores their sharpness).
fn normal_errors(name: &str, mesh: &Mesh, level: u32, n: usize) -> NormalError {
    let osd_mesh = OsdMesh::from(mesh);
    let o = OsdPatchOptions {
        isolation_level: level,
        use_single_crease: false,
        use_inf_sharp: false,
        end_cap: EndCap::Gregory,
    };
    let osd =
        osd_ref::eval_limit_grid_f64(&osd_mesh, n, &o).unwrap_or_else(|e| panic!("{name}: {e}"));
    let topo = Topology::new(mesh).unwrap();
    let table = PatchTable::build(
        &topo,
        &PatchOptions {
            isolation_level: level,
            single_crease: false,
            cap_crease_sharpness: false,
        },
    )
    .unwrap();
    let s = LimitSurface::new(table, &mesh.positions);
    let diag = f64::from(subsurf::mesh::bbox_diagonal(&mesh.positions));
    let mut e = NormalError::default();
    for o in &osd {
        let (f, u, v) = (o.face as usize, o.u, o.v);
        if let Some(r) = s.eval_raw(f, u, v) {
            let d = |a: [f32; 3], b: [f64; 3]| {
                (0..3)
                    .map(|c| (f64::from(a[c]) - b[c]).abs())
                    .fold(0.0, f64::max)
                    / diag
            };
            e.position = e.position.max(d(r.p, o.p));
            e.deriv = e.deriv.max(d(r.du, o.du).max(d(r.dv, o.dv)));
        }
        let p = s
            .table()
            .patch_map()
            .find(f, u, v)
            .unwrap_or_else(|| panic!("{name}: no patch at ptex {f} ({u}, {v})"))
            as usize;
        let (a, b) = s.table().params()[p].normalize(u, v);
        let edge = |x: f32| x.min(1.0 - x) < CORNER;
        if edge(a) && edge(b) {
            continue;
        }
        // A degenerate tangent plane (a derivative vanishes, or both are parallel: a
        // collapsed boundary of the valence-2 shapes) has no normal to compare.
        let want = cross(o.du, o.dv);
        let scale = dot(o.du, o.du).max(dot(o.dv, o.dv));
        if dot(want, want).sqrt() <= DEGENERATE * scale {
            continue;
        }
        let r = s.eval(f, u, v).unwrap();
        let got = r.n.map(f64::from);
        let err = angle(got, want);
        e.samples += 1;
        if err > e.worst() {
            e.worst_at = (o.face, u, v);
        }
        if s.table().patch_type(p) == PatchType::Gregory {
            e.end_cap = e.end_cap.max(err);
        } else {
            e.regular = e.regular.max(err);
        }
    }
    e
}

/// `nx × ny` thin parallelogram faces, edges `h (1, 0, 0)` and `h (cos 4°, sin 4°, 0)` apart
/// by 4°, on a gentle bump of height `h / 3`, the grid's corner at `origin` (so that the faces
/// are `h / |origin|` of their distance from the origin).
fn thin_grid(nx: usize, ny: usize, h: f64, origin: [f64; 3]) -> Mesh {
    let (c, s) = (4f64.to_radians().cos(), 4f64.to_radians().sin());
    let mut p = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (i as f64 + j as f64 * c, j as f64 * s);
            let z = (0.7 * i as f64).sin() * (0.45 * j as f64).cos() / 3.0;
            p.push([
                (origin[0] + h * x) as f32,
                (origin[1] + h * y) as f32,
                (origin[2] + h * z) as f32,
            ]);
        }
    }
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut faces = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh::from_faces(p, &faces)
}

/// Issue 12 item 3: thin faces (edges 4° apart) 10⁻³ of their distance from the origin, as
/// on a production model whose faces are 10⁻³ of its size.
///
/// With sharp grid corners every patch is a B-spline patch of base points, so only the
/// evaluation rounds: weighting the points themselves the normals were off by 7.9·10⁻⁴ rad,
/// relative to the patch's first point by 6·10⁻⁷. With smooth corners (valence-2 boundary
/// vertices, isolated to level 4) the patches next to them are 1/16 of a face and their
/// points are rounded refined points: 2.8·10⁻³ rad before, 1.2·10⁻³ after (the rounding of
/// stored `f32` points, `ε |x|` on patches 6·10⁻⁵ wide, is what is left).
#[test]
fn issue_12_thin_faces_far_from_origin_have_accurate_normals() {
    if !osd_or_skip("issue_12_thin_faces_far_from_origin_have_accurate_normals") {
        return;
    }
    let mut mesh = thin_grid(12, 10, 1e-3, [0.61, 0.43, 0.29]);
    let smooth = normal_errors("thin grid", &mesh, 4, 9);
    mesh.options.boundary = BoundaryInterpolation::EdgeAndCorner;
    let sharp = normal_errors("thin grid, sharp corners", &mesh, 4, 9);
    eprintln!("thin grid, smooth corners: {smooth:?}\nthin grid, sharp corners: {sharp:?}");
    assert!(smooth.samples > 1000 && sharp.samples > 1000);
    assert!(sharp.worst() <= 1e-5, "{sharp:?}");
    assert!(smooth.worst() <= 2e-3, "{smooth:?}");
}

/// A regression shape with Gregory end caps, moved 10³ times its size from the origin:
/// 2.8·10⁻³ rad weighting the points themselves (in the stencils and the patches),
/// 5.6·10⁻⁴ relative to a point of each row and patch.
#[test]
fn issue_12_translated_shape_has_accurate_normals() {
    if !osd_or_skip("issue_12_translated_shape_has_accurate_normals") {
        return;
    }
    let mut mesh = load_shape("catmark_gregory_test6");
    let d = subsurf::mesh::bbox_diagonal(&mesh.positions);
    for p in mesh.positions.as_f32_mut() {
        p[0] += 1000.0 * d;
        p[1] -= 700.0 * d;
        p[2] += 400.0 * d;
    }
    let e = normal_errors("translated", &mesh, 4, 9);
    eprintln!("catmark_gregory_test6 translated: {e:?}");
    assert!(e.samples > 0, "{e:?}");
    assert!(e.worst() <= 1e-3, "{e:?}");
}

/// Every catmark regression shape at isolation levels 4 and 2 (where 11 samples per side
/// also fall inside the end caps, away from their corners): normals within 10⁻³ rad of
/// OpenSubdiv's double-precision ones away from patch corners.
#[test]
fn normals_match_opensubdiv_f64_on_every_catmark_shape() {
    if !osd_or_skip("normals_match_opensubdiv_f64_on_every_catmark_shape") {
        return;
    }
    let mut failures = Vec::new();
    for name in shape_names() {
        let mesh = load_shape(&name);
        let n = if mesh.num_faces() > 150 { 6 } else { 11 };
        for level in [4, 2] {
            let e = normal_errors(&name, &mesh, level, n);
            eprintln!("{name:28} level {level} {e:?}");
            if e.samples == 0 || e.worst() > 1e-3 {
                failures.push(format!("{name} level {level}: {e:?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
