use super::*;
use crate::mesh::Crease;
use crate::options::BoundaryInterpolation;
use crate::shapes;
use crate::topology::tests::check_invariants;

/// Uniform cubic B-spline basis at `t` in [0, 1] for the four control points of a span.
fn basis(t: f32) -> [f32; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

/// Bicubic B-spline surface of a grid of control heights at parameter (x, y) in control-point units.
fn bspline(z: &dyn Fn(i64, i64) -> f32, x: f32, y: f32) -> f32 {
    let (i, j) = (x.floor() as i64, y.floor() as i64);
    let (bu, bv) = (basis(x - i as f32), basis(y - j as f32));
    let mut acc = 0.0;
    for b in 0..4 {
        for a in 0..4 {
            acc += bu[a] * bv[b] * z(i - 1 + a as i64, j - 1 + b as i64);
        }
    }
    acc
}

fn height(i: i64, j: i64) -> f32 {
    (((i * 7919 + j * 104_729) % 1000) as f32 / 1000.0).sin()
}

fn wavy_grid(n: usize) -> Mesh {
    let mut m = shapes::grid(n, n);
    for p in m.positions.as_f32_mut() {
        p[2] = height(p[0] as i64, p[1] as i64);
    }
    m
}

#[test]
fn refined_levels_are_consistent_topology() {
    for m in [
        shapes::cube(),
        shapes::grid(3, 2),
        shapes::pole(7),
        shapes::torus(5, 4, 2.0, 0.7),
    ] {
        let r = Refiner::new(Topology::new(&m).unwrap(), 3).unwrap();
        for (k, t) in r.levels.iter().enumerate().skip(1) {
            check_invariants(t);
            let p = &r.levels[k - 1];
            assert_eq!(
                t.num_vertices(),
                p.num_vertices() + p.num_faces() + p.num_edges()
            );
            assert_eq!(t.num_faces(), p.num_corners());
            assert!(t.is_all_quads());
            assert_eq!(t.is_closed(), r.levels[0].is_closed());
            assert_eq!(t.boundary_edges().len(), 2 * p.boundary_edges().len());
        }
    }
}

#[test]
fn cube_level_one_matches_catmull_clark_formulas() {
    let m = shapes::cube();
    let t = Topology::new(&m).unwrap();
    let r = Refiner::new(t.clone(), 1).unwrap();
    let p = r.refine_positions(&m.positions);
    let avg = |pts: &[[f32; 3]]| {
        let mut a = [0.0f32; 3];
        for q in pts {
            for k in 0..3 {
                a[k] += q[k] / pts.len() as f32;
            }
        }
        a
    };
    let face_pt = |f: usize| {
        avg(&t
            .face_vertices(f)
            .iter()
            .map(|&v| m.positions[v as usize])
            .collect::<Vec<_>>())
    };
    for f in 0..6 {
        assert_eq!(p[8 + f], face_pt(f));
    }
    for e in 0..12 {
        let ev = t.edge_verts[e];
        let fs = t.edge_faces(e);
        let expect = avg(&[
            m.positions[ev[0] as usize],
            m.positions[ev[1] as usize],
            face_pt(fs[0] as usize),
            face_pt(fs[1] as usize),
        ]);
        for k in 0..3 {
            assert!((p[14 + e][k] - expect[k]).abs() < 1e-6);
        }
    }
    for v in 0..8 {
        let n = t.valence(v) as f32;
        let q = avg(&t
            .vertex_faces(v)
            .iter()
            .map(|&f| face_pt(f as usize))
            .collect::<Vec<_>>());
        let rr = avg(&t
            .vertex_edges(v)
            .iter()
            .map(|&e| {
                let ev = t.edge_verts[e as usize];
                avg(&[m.positions[ev[0] as usize], m.positions[ev[1] as usize]])
            })
            .collect::<Vec<_>>());
        let s = m.positions[v];
        for k in 0..3 {
            let expect = (q[k] + 2.0 * rr[k] + (n - 3.0) * s[k]) / n;
            assert!((p[v][k] - expect).abs() < 1e-6, "vertex {v}");
        }
    }
}

#[test]
fn regular_grid_limit_is_the_bicubic_bspline() {
    let n = 10;
    let m = wavy_grid(n);
    let r = Refiner::new(Topology::new(&m).unwrap(), 2).unwrap();
    let lvl = r.refine_all(&m.positions);
    let limit = r.limit(&lvl[2]);
    let z = |i: i64, j: i64| height(i, j);
    // Level-1 vertices keep their indices; their parameters are known.
    let t0 = &r.levels[0];
    let mut checked = 0;
    let mut check = |idx: usize, x: f32, y: f32| {
        if x >= 2.0 && y >= 2.0 && x <= (n - 2) as f32 && y <= (n - 2) as f32 {
            let expect = bspline(&z, x, y);
            assert!(
                (limit[idx][2] - expect).abs() < 2e-5,
                "at ({x},{y}): {} vs {expect}",
                limit[idx][2]
            );
            assert!((limit[idx][0] - x).abs() < 1e-5 && (limit[idx][1] - y).abs() < 1e-5);
            checked += 1;
        }
    };
    for v in 0..t0.num_vertices() {
        check(v, m.positions[v][0], m.positions[v][1]);
    }
    for f in 0..t0.num_faces() {
        let c = t0.face_vertices(f)[0] as usize;
        check(
            t0.num_vertices() + f,
            m.positions[c][0] + 0.5,
            m.positions[c][1] + 0.5,
        );
    }
    for e in 0..t0.num_edges() {
        let [a, b] = t0.edge_verts[e];
        let (pa, pb) = (m.positions[a as usize], m.positions[b as usize]);
        check(
            t0.num_vertices() + t0.num_faces() + e,
            0.5 * (pa[0] + pb[0]),
            0.5 * (pa[1] + pb[1]),
        );
    }
    assert!(checked > 100);
}

#[test]
fn infinitely_sharp_edge_limit_is_the_cubic_bspline_curve() {
    let n = 10;
    let j0 = 5u32;
    let mut m = wavy_grid(n);
    let id = |i: u32, j: u32| j * (n as u32 + 1) + i;
    for i in 0..n as u32 {
        m.creases.push(Crease {
            v0: id(i, j0),
            v1: id(i + 1, j0),
            sharpness: 10.0,
        });
    }
    let r = Refiner::new(Topology::new(&m).unwrap(), 3).unwrap();
    let last = r.refine_positions(&m.positions);
    let limit = r.limit(&last);
    let z = |i: i64| height(i, j0 as i64);
    for i in 2..(n - 2) as i64 {
        let v = id(i as u32, j0) as usize;
        let expect = (z(i - 1) + 4.0 * z(i) + z(i + 1)) / 6.0;
        assert!((limit[v][2] - expect).abs() < 1e-5, "vertex {i}");
        assert!(
            (limit[v][1] - j0 as f32).abs() < 1e-6,
            "stays on the crease line"
        );
    }
    // Edge points of the crease: B-spline curve at half-integer parameters.
    let t0 = &r.levels[0];
    for i in 2..(n - 3) as u32 {
        let e = t0.find_edge(id(i, j0), id(i + 1, j0)).unwrap() as usize;
        let idx = t0.num_vertices() + t0.num_faces() + e;
        let ii = i as i64;
        let expect = (z(ii - 1) + 23.0 * z(ii) + 23.0 * z(ii + 1) + z(ii + 2)) / 48.0;
        assert!((limit[idx][2] - expect).abs() < 1e-5, "edge {i}");
    }
}

#[test]
fn boundary_corner_rules() {
    for (mode, fixed) in [
        (BoundaryInterpolation::EdgeAndCorner, true),
        (BoundaryInterpolation::EdgeOnly, false),
    ] {
        let mut m = wavy_grid(4);
        m.options.boundary = mode;
        let r = Refiner::new(Topology::new(&m).unwrap(), 1).unwrap();
        let p = r.refine_positions(&m.positions);
        let (c, a, b) = (m.positions[0], m.positions[1], m.positions[5]);
        let expect: [f32; 3] = if fixed {
            c
        } else {
            std::array::from_fn(|k| 0.75 * c[k] + 0.125 * (a[k] + b[k]))
        };
        for k in 0..3 {
            assert!((p[0][k] - expect[k]).abs() < 1e-6, "{mode:?}");
        }
        // A boundary edge point is the edge midpoint.
        let t = &r.levels[0];
        let e = t.find_edge(1, 2).unwrap() as usize;
        let mid: [f32; 3] = std::array::from_fn(|k| 0.5 * (m.positions[1][k] + m.positions[2][k]));
        assert_eq!(p[t.num_vertices() + t.num_faces() + e], mid);
    }
}

#[test]
fn semi_sharp_crease_decays_level_by_level() {
    let mut m = wavy_grid(6);
    let id = |i: u32, j: u32| j * 7 + i;
    for i in 0..6 {
        m.creases.push(Crease {
            v0: id(i, 3),
            v1: id(i + 1, 3),
            sharpness: 2.0,
        });
    }
    let r = Refiner::new(Topology::new(&m).unwrap(), 3).unwrap();
    let sharp_at = |k: usize| {
        r.levels[k]
            .edge_sharpness
            .iter()
            .cloned()
            .filter(|&s| s > 0.0 && s < 10.0)
            .fold(0.0f32, f32::max)
    };
    assert_eq!(sharp_at(0), 2.0);
    assert_eq!(sharp_at(1), 1.0);
    assert_eq!(sharp_at(2), 0.0);
}

#[test]
fn composed_stencils_equal_level_by_level() {
    let mut m = shapes::pole(5);
    m.creases.push(Crease {
        v0: 0,
        v1: 1,
        sharpness: 1.5,
    });
    let r = Refiner::new(Topology::new(&m).unwrap(), 3).unwrap();
    let direct = r.refine_positions(&m.positions);
    let table = r.stencil_table();
    let mut composed = vec![[0.0f32; 3]; table.num_rows()];
    table.apply(&m.positions, &mut composed);
    for (a, b) in direct.iter().zip(&composed) {
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() < 1e-5);
        }
    }
    // Every row of a refinement stencil is an affine combination.
    for i in 0..table.num_rows() {
        let s: f32 = table.weights[table.offsets[i] as usize..table.offsets[i + 1] as usize]
            .iter()
            .sum();
        assert!((s - 1.0).abs() < 1e-5);
    }
}

#[test]
fn too_large_level_is_refused_up_front() {
    let t = Topology::new(&shapes::cube()).unwrap();
    match Refiner::new(t, 20) {
        Err(Error::Mesh(MeshError::TooLarge { .. })) => {}
        other => panic!("expected TooLarge, got {:?}", other.map(|r| r.max_level())),
    }
}
