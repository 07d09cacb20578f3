//! Closed-form checks of face-varying refinement on a periodic grid (a torus), where
//! Catmull-Clark is the tensor-product cubic B-spline: one refinement step takes a vertex to
//! `Σ w_p w_q u(i+p, j+q)` with `w = (1, 6, 1) / 8`, an edge to `Σ w_q (u(i, j+q) + u(i+1,
//! j+q)) / 2`, a face to its average (Lane & Riesenfeld 1980; Catmull & Clark 1978).

use super::*;
use crate::mesh::{FaceVarying, Mesh};
use crate::options::FVarLinearInterpolation as Mode;
use crate::refine::refine_uvs_linear;

const W: [f32; 3] = [0.125, 0.75, 0.125];
const MODES: [Mode; 6] = [
    Mode::None,
    Mode::CornersOnly,
    Mode::CornersPlus1,
    Mode::CornersPlus2,
    Mode::Boundaries,
    Mode::All,
];

/// An `n × m` torus: vertex `(i, j)` is `i * m + j`, face `(i, j)` spans `(i, j)..(i+1, j+1)`.
fn torus(n: usize, m: usize) -> Mesh {
    let mut positions = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (a, b) = (
                std::f32::consts::TAU * i as f32 / n as f32,
                std::f32::consts::TAU * j as f32 / m as f32,
            );
            let r = 2.0 + b.cos();
            positions.push([r * a.cos(), r * a.sin(), b.sin()]);
        }
    }
    let v = |i: usize, j: usize| ((i % n) * m + j % m) as u32;
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..m {
            faces.push([v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    Mesh::from_faces(positions, &faces)
}

/// Arbitrary smooth-ish data on grid column `j` (not periodic in `j`).
fn data(i: i64, j: i64) -> [f32; 2] {
    [
        j as f32 * 0.1 + 0.05 * (i as f32 * 1.3).sin(),
        i as f32 * 0.07 + 0.02 * (j * j) as f32,
    ]
}

fn close(a: [f32; 2], b: [f32; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-5 && (a[1] - b[1]).abs() < 1e-5
}

/// Expected level-1 value at child vertex `cv` of a grid whose level-0 values are `u(i, j)`
/// around the stencil (`linear`: the bilinear rules of `All`).
fn expected(
    t: &Topology,
    m: usize,
    cv: usize,
    u: &dyn Fn(i64, i64) -> [f32; 2],
    linear: bool,
    near: i64,
) -> [f32; 2] {
    let (nv, nf) = (t.num_vertices(), t.num_faces());
    // Grid coordinates of a vertex, with `j` unwrapped next to column `near`.
    let ij = |v: u32| {
        let (i, j) = ((v as usize / m) as i64, (v as usize % m) as i64);
        let j = if (j - near).abs() > 1 {
            j - m as i64 * (j - near).signum()
        } else {
            j
        };
        (i, j)
    };
    let mut acc = [0.0f32; 2];
    let mut add = |w: f32, x: [f32; 2]| {
        acc[0] += w * x[0];
        acc[1] += w * x[1];
    };
    if cv < nv {
        let (i, j) = ij(cv as u32);
        if linear {
            return u(i, j);
        }
        for (p, wp) in W.iter().enumerate() {
            for (q, wq) in W.iter().enumerate() {
                add(wp * wq, u(i + p as i64 - 1, j + q as i64 - 1));
            }
        }
    } else if cv < nv + nf {
        for &v in t.face_vertices(cv - nv) {
            let (i, j) = ij(v);
            add(0.25, u(i, j));
        }
    } else {
        let [a, b] = t.edge_verts[cv - nv - nf];
        let ((ia, ja), (ib, jb)) = (ij(a), ij(b));
        if linear {
            add(0.5, u(ia, ja));
            add(0.5, u(ib, jb));
        } else if ja == jb {
            for (q, wq) in W.iter().enumerate() {
                add(0.5 * wq, u(ia, ja + q as i64 - 1));
                add(0.5 * wq, u(ib, ja + q as i64 - 1));
            }
        } else {
            for (p, wp) in W.iter().enumerate() {
                add(0.5 * wp, u(ia + p as i64 - 1, ja));
                add(0.5 * wp, u(ia + p as i64 - 1, jb));
            }
        }
    }
    acc
}

/// Seamless UVs (one value per vertex, stored in a shuffled order) on a closed regular grid:
/// level 1 is the bicubic B-spline refinement in every smooth mode (bilinear in `All`), and
/// every later level equals refining the same data as vertex data.
#[test]
fn seamless_grid_refines_like_bicubic_bspline() {
    let (n, m) = (6usize, 5usize);
    let mesh = torus(n, m);
    let nv = n * m;
    let slot = |v: usize| (v * 7 + 3) % nv; // a permutation of 0..nv (gcd(7, 30) = 1)
    let per_vertex: Vec<[f32; 2]> = (0..nv)
        .map(|v| {
            let (i, j) = ((v / m) as i64, (v % m) as i64);
            // Periodic data so that the grid has no seam.
            let (a, b) = (i as f32 / n as f32, j as f32 / m as f32);
            [
                (a * std::f32::consts::TAU).sin() + 0.3 * (b * std::f32::consts::TAU).cos(),
                (b * std::f32::consts::TAU).sin() * 0.5 + a,
            ]
        })
        .collect();
    let mut values = vec![[0.0f32; 2]; nv];
    for v in 0..nv {
        values[slot(v)] = per_vertex[v];
    }
    let uvs = FaceVarying {
        values,
        indices: mesh
            .face_indices
            .iter()
            .map(|&v| slot(v as usize) as u32)
            .collect(),
    };
    let u = |i: i64, j: i64| {
        per_vertex[(i.rem_euclid(n as i64) as usize) * m + j.rem_euclid(m as i64) as usize]
    };
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 3).unwrap();
    let vertex_path = refiner.refine_all(&per_vertex);
    for mode in MODES {
        let levels = refiner.refine_uvs(&uvs, mode).unwrap();
        assert_eq!(levels.len(), 4);
        let t0 = &refiner.levels[0];
        let c1 = &refiner.levels[1];
        for (c, &cv) in c1.face_verts.iter().enumerate() {
            let got = levels[1].values[levels[1].indices[c] as usize];
            let want = expected(t0, m, cv as usize, &u, mode == Mode::All, 0);
            assert!(close(got, want), "{mode:?} corner {c}: {got:?} vs {want:?}");
        }
        if mode == Mode::All {
            continue;
        }
        for (k, level) in levels.iter().enumerate().skip(2) {
            let t = &refiner.levels[k];
            for (c, &v) in t.face_verts.iter().enumerate() {
                let got = level.values[level.indices[c] as usize];
                let want = vertex_path[k][v as usize];
                assert!(close(got, want), "{mode:?} level {k} corner {c}");
            }
        }
    }
}

/// A UV seam around the torus (column `j = 0` carries `u(i, 0)` on one side and `u(i, m)` on
/// the other): with smooth boundaries each side refines by the cubic B-spline curve rules
/// along the seam (`3/4 v + 1/8 (a + b)`, midpoints), with linear boundaries values on the
/// seam are copied; vertices two columns away keep the surface rule.
#[test]
fn seam_refines_as_a_crease_of_the_uv_data() {
    let (n, m) = (6usize, 6usize);
    let mesh = torus(n, m);
    let cols = m + 1;
    let values: Vec<[f32; 2]> = (0..n * cols)
        .map(|k| data((k / cols) as i64, (k % cols) as i64))
        .collect();
    let mut indices = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let x = |i: usize, j: usize| ((i % n) * cols + j) as u32;
            indices.extend_from_slice(&[x(i, j), x(i + 1, j), x(i + 1, j + 1), x(i, j + 1)]);
        }
    }
    let uvs = FaceVarying { values, indices };
    let u = |i: i64, j: i64| data(i.rem_euclid(n as i64), j);
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 1).unwrap();
    let (t0, c1) = (&refiner.levels[0], &refiner.levels[1]);
    let nv = t0.num_vertices();
    for mode in MODES {
        let levels = refiner.refine_uvs(&uvs, mode).unwrap();
        let linear_seam = matches!(mode, Mode::Boundaries | Mode::All);
        for f in 0..c1.num_faces() {
            // Parent face (i, j) of this child face and the side of the seam it lies on.
            let pf = f / 4;
            let pj = (pf % m) as i64;
            let side = if pj == m as i64 - 1 { m as i64 } else { 0 };
            for k in 0..4 {
                let c = 4 * f + k;
                let cv = c1.face_verts[c] as usize;
                let got = levels[1].values[levels[1].indices[c] as usize];
                let on_seam = |v: u32| v as usize % m == 0;
                let is_seam_vertex = cv < nv && on_seam(cv as u32);
                let is_seam_edge = cv >= nv + t0.num_faces() && {
                    let [a, b] = t0.edge_verts[cv - nv - t0.num_faces()];
                    on_seam(a) && on_seam(b)
                };
                let want = if is_seam_vertex {
                    let i = (cv / m) as i64;
                    if linear_seam {
                        u(i, side)
                    } else {
                        let (a, v, b) = (u(i - 1, side), u(i, side), u(i + 1, side));
                        [
                            0.75 * v[0] + 0.125 * (a[0] + b[0]),
                            0.75 * v[1] + 0.125 * (a[1] + b[1]),
                        ]
                    }
                } else if is_seam_edge {
                    let [a, b] = t0.edge_verts[cv - nv - t0.num_faces()];
                    let (x, y) = (
                        u((a as usize / m) as i64, side),
                        u((b as usize / m) as i64, side),
                    );
                    [0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1])]
                } else if cv < nv && !(2..=m as i64 - 2).contains(&((cv % m) as i64)) {
                    continue; // next to the seam: mixed rules
                } else if cv >= nv + t0.num_faces() && {
                    let [a, b] = t0.edge_verts[cv - nv - t0.num_faces()];
                    on_seam(a) || on_seam(b)
                } {
                    continue; // edges leaving the seam
                } else {
                    let near = if cv < nv {
                        (cv % m) as i64
                    } else {
                        pj.clamp(1, m as i64 - 2)
                    };
                    expected(t0, m, cv, &u, mode == Mode::All, near)
                };
                assert!(
                    close(got, want),
                    "{mode:?} child face {f} corner {k}: {got:?} vs {want:?}"
                );
            }
        }
    }
}

#[test]
fn bad_face_varying_input_is_an_error() {
    let mesh = torus(3, 3);
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 1).unwrap();
    let short = FaceVarying {
        values: vec![[0.0; 2]; 9],
        indices: vec![0; 5],
    };
    assert!(refiner.refine_uvs(&short, Mode::CornersOnly).is_err());
    let out_of_range = FaceVarying {
        values: vec![[0.0; 2]; 9],
        indices: mesh.face_indices.iter().map(|&v| v + 1).collect(),
    };
    assert!(refiner.refine_uvs(&out_of_range, Mode::None).is_err());
}

/// In the `All` mode the stencils reproduce [`refine_uvs_linear`] corner for corner.
#[test]
fn linear_mode_equals_per_corner_linear_refinement() {
    let mut mesh = torus(4, 5);
    // Mixed face sizes: split one quad into two triangles.
    let q: Vec<u32> = mesh.face_indices[..4].to_vec();
    mesh.face_counts.splice(0..1, [3, 3]);
    mesh.face_indices
        .splice(0..4, [q[0], q[1], q[2], q[0], q[2], q[3]]);
    let values: Vec<[f32; 2]> = (0..mesh.face_indices.len())
        .map(|c| data(c as i64 % 7, c as i64 / 7))
        .collect();
    let uvs = FaceVarying {
        values: values.clone(),
        indices: (0..values.len() as u32).collect(),
    };
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    let levels = refiner.refine_uvs(&uvs, Mode::All).unwrap();
    let mut corner = values;
    for k in 0..2 {
        corner = refine_uvs_linear(&refiner.levels[k], &corner);
        let l = &levels[k + 1];
        assert_eq!(l.indices.len(), corner.len());
        for (c, (&i, &want)) in l.indices.iter().zip(&corner).enumerate() {
            assert!(
                close(l.values[i as usize], want),
                "level {} corner {c}",
                k + 1
            );
        }
    }
}

/// Without seams, face-varying data takes the vertex limit masks: UVs equal to the
/// positions' x and y limit exactly as the positions do. In the linear mode they stay put.
#[test]
fn seamless_uvs_limit_like_positions() {
    let mesh = torus(5, 7);
    let values: Vec<[f32; 2]> = mesh.positions.iter().map(|p| [p[0], p[1]]).collect();
    let uvs = FaceVarying {
        values,
        indices: mesh.face_indices.clone(),
    };
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    let limit = refiner.limit(&refiner.refine_positions(&mesh.positions));
    let t = &refiner.levels[2];
    for mode in MODES {
        let fvar = refiner
            .fvar_refinement(&uvs.indices, uvs.values.len(), mode)
            .unwrap();
        let last = fvar.refine(&uvs.values).unwrap().pop().unwrap();
        let got = refiner.limit_face_varying(&fvar, &last.values).unwrap();
        for (c, &x) in last.indices.iter().enumerate() {
            let (g, r) = (got[x as usize], last.values[x as usize]);
            let want = if mode == Mode::All {
                r
            } else {
                let p = limit[t.face_verts[c] as usize];
                [p[0], p[1]]
            };
            assert!(
                close(g, want),
                "{mode:?} corner {c}: {g:?} vs {want:?} (refined {r:?})"
            );
        }
    }
    // The limit needs the last level's values.
    let fvar = refiner
        .fvar_refinement(&uvs.indices, uvs.values.len(), Mode::None)
        .unwrap();
    assert!(refiner.limit_face_varying(&fvar, &uvs.values).is_err());
}
