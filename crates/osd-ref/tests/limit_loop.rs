//! The Loop limit surface against OpenSubdiv 3.5's adaptive Loop patch table
//! (`Far::PatchTable` with Gregory end caps + `PatchMap`, refined and evaluated in double
//! precision on a triangular grid of every face): every `loop_*` regression shape at isolation
//! levels 1–4, positions within 1e-5 of the bounding-box diagonal and normals within 1e-3 rad,
//! on the regular box-spline patches and on the Gregory-triangle end caps, checked separately;
//! with the points refined in double precision (`LoopLimit::new_f64`), within 1e-12 of the
//! diagonal and 1e-9 rad. Every sample must evaluate. The worst figures over all shapes are
//! printed.

#[macro_use]
mod common;

use osd_ref::{eval_limit_grid_f64, EndCap, OsdMesh, PatchOptions};
use subsurf::limit::LoopLimit;
use subsurf::Topology;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let n = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let c = cross(a, b);
    n(c).atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

/// Worst position (relative to the diagonal) and normal (rad) error, samples compared, and
/// the shapes where the worst errors occur.
#[derive(Default, Clone)]
struct Worst {
    p: f64,
    n: f64,
    count: usize,
    p_at: String,
    n_at: String,
}

/// The precision of our points and the tolerances it is held to: position (of the
/// diagonal) and normal (rad).
#[derive(Clone, Copy)]
struct Bounds {
    f64: bool,
    p: f64,
    n: f64,
}

/// Points refined in `f32`.
const F32: Bounds = Bounds {
    f64: false,
    p: 1e-5,
    n: 1e-3,
};
/// Points refined in `f64`.
const F64: Bounds = Bounds {
    f64: true,
    p: 1e-12,
    n: 1e-9,
};

impl Worst {
    fn differs(&self, b: Bounds) -> bool {
        self.p > b.p || self.n > b.n
    }

    fn merge(&mut self, w: &Worst, name: &str) {
        if w.p > self.p {
            (self.p, self.p_at) = (w.p, name.to_string());
        }
        if w.n > self.n {
            (self.n, self.n_at) = (w.n, name.to_string());
        }
        self.count += w.count;
    }
}

/// Compares every `loop_*` shape at `level`, its points refined in `f64` when the bounds say:
/// the worst figures on regular patches and on end caps over all shapes, and a line
/// per shape and patch kind outside the bounds.
fn compare_at(level: u32, bounds: Bounds) -> (Worst, Worst, Vec<String>) {
    let mut failures = Vec::new();
    let (mut all_reg, mut all_cap) = (Worst::default(), Worst::default());
    for name in common::shape_names(&["loop_"]) {
        let mesh = common::load_shape(&name);
        let topo = Topology::new(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
        let ours = if bounds.f64 {
            LoopLimit::new_f64(&topo, &mesh.positions, level)
        } else {
            LoopLimit::new(&topo, &mesh.positions, level)
        }
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut osd = OsdMesh::from(&mesh);
        osd.uvs = None;
        let o = PatchOptions {
            isolation_level: level,
            end_cap: EndCap::Gregory,
            ..Default::default()
        };
        // Finer grids at deeper levels, so that samples fall inside the shrinking end caps.
        let per_side = 6.max((3 << (level - 1)) + 1);
        let samples = eval_limit_grid_f64(&osd, per_side, &o).unwrap();
        let diag = subsurf::mesh::bbox_diagonal(&mesh.positions).max(1e-30) as f64;
        let (mut reg, mut cap) = (Worst::default(), Worst::default());
        for s in &samples {
            let (face, u, v) = (s.face as usize, s.u as f64, s.v as f64);
            let e = ours
                .eval(face, u, v)
                .unwrap_or_else(|| panic!("{name}: face {face} ({u}, {v}) not evaluated"));
            let w = if ours.find(face, u, v).unwrap().regular {
                &mut reg
            } else {
                &mut cap
            };
            w.count += 1;
            let d = (0..3)
                .map(|k| (e.p[k] - s.p[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            w.p = w.p.max(d / diag);
            let theirs = cross(s.du, s.dv);
            let mine = cross(e.du, e.dv);
            let n = |x: [f64; 3]| (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            if n(theirs) > 1e-6 * diag * diag && n(mine) > 1e-6 * diag * diag {
                w.n = w.n.max(angle(mine, theirs));
            }
        }
        for (kind, w, all) in [
            ("regular patches", &reg, &mut all_reg),
            ("end caps", &cap, &mut all_cap),
        ] {
            if w.differs(bounds) {
                failures.push(format!(
                    "{name} isolation {level} {kind}: position {:e}, normal {:e} rad",
                    w.p, w.n
                ));
            }
            all.merge(w, &name);
        }
    }
    (all_reg, all_cap, failures)
}

#[test]
fn limit_surface_matches_opensubdiv_on_every_loop_shape() {
    require_osd!();
    check_every_level(F32);
}

#[test]
fn f64_limit_surface_matches_opensubdiv_f64_on_every_loop_shape() {
    require_osd!();
    check_every_level(F64);
}

fn check_every_level(bounds: Bounds) {
    let mut failures = Vec::new();
    for level in 1..=4 {
        let (reg, cap, f) = compare_at(level, bounds);
        for (kind, w) in [("regular", &reg), ("end caps", &cap)] {
            eprintln!(
                "isolation {level} {kind}: {} samples, position {:.1e} ({}), normal {:.1e} rad ({})",
                w.count, w.p, w.p_at, w.n, w.n_at
            );
        }
        failures.extend(f);
        // The end caps are really exercised: thousands of samples lie on them (fewer at each
        // level, as isolation shrinks the irregular triangles).
        assert!(
            cap.count > 2000,
            "isolation {level}: only {} end-cap samples",
            cap.count
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
