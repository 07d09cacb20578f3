//! Continuity and reduction properties of the p-rep surface (Myles, Yeo & Peters 2008):
//! B-spline reduction at valence 4, G1 along every edge, bit-exact C0, watertight
//! tessellation, parallel = sequential.

mod prep_shapes;

use prep_shapes::*;
use subsurf::prep::kernel::{corner_index, H_SLOTS};
use subsurf::prep::PrepPatches;
use subsurf::Real;

/// All valences 4: the surface is the uniform bicubic B-spline of the control net.
/// Measured: f64 max error 1.3e-15, f32 max error 5.5e-7 on a torus of outer radius 2.7.
#[test]
fn all_valence_4_is_bicubic_bspline() {
    let (nu, nv) = (9, 7);
    let mesh = wobble(torus(nu, nv), 0.05);
    let p64 = PrepPatches::<f64>::build(&mesh).unwrap();
    let p32 = PrepPatches::<f32>::build(&mesh).unwrap();
    assert!(p64.h().is_empty(), "a B-quad mesh has no perturbation");
    let basis = |t: f64| {
        let s = 1.0 - t;
        [
            s * s * s / 6.0,
            (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
            (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
            t * t * t / 6.0,
        ]
    };
    let (mut e64, mut e32) = (0.0f64, 0.0f64);
    for i in 0..nu {
        for j in 0..nv {
            let f = i * nv + j;
            for (u, v) in [
                (0.0, 0.0),
                (0.3, 0.7),
                (0.5, 0.5),
                (1.0, 0.2),
                (0.9, 1.0),
                (0.13, 0.01),
            ] {
                let (bu, bv) = (basis(u), basis(v));
                let mut want = [0.0f64; 3];
                for a in 0..4 {
                    for b in 0..4 {
                        let vi = ((i + nu + a - 1) % nu) * nv + (j + nv + b - 1) % nv;
                        for k in 0..3 {
                            want[k] += bu[a] * bv[b] * mesh.positions[vi][k] as f64;
                        }
                    }
                }
                let g64 = p64.eval(f, u, v).position;
                let g32 = p32.eval(f, u as f32, v as f32).position;
                for k in 0..3 {
                    e64 = e64.max((g64[k] - want[k]).abs());
                    e32 = e32.max((g32[k] as f64 - want[k]).abs());
                }
            }
        }
    }
    eprintln!("B-spline reduction: f64 {e64:.2e}, f32 {e32:.2e}");
    assert!(e64 < 1e-12, "f64 B-spline error {e64:e}");
    assert!(e32 < 1e-6, "f32 B-spline error {e32:e}");
}

/// G1: largest angle between the two normals along every shared edge, 65 samples per edge,
/// on closed meshes with valences 3–8 (adjacent extraordinary vertices included).
/// Measured: f64 max 1.3e-13 rad (catmark_lefthanded; <= 9.1e-15 on every other mesh);
/// f32 max 7.8e-5 rad (catmark_lefthanded, 434 faces with small quads next to large ones;
/// <= 5.8e-6 rad on every other mesh).
#[test]
fn g1_along_every_edge() {
    let mut report = String::new();
    let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
    for (name, mesh) in closed_meshes() {
        let a64 = max_normal_angle(&PrepPatches::<f64>::build(&mesh).unwrap(), 65);
        let a32 = max_normal_angle(&PrepPatches::<f32>::build(&mesh).unwrap(), 65);
        report += &format!("{name}: f64 {a64:.2e} rad, f32 {a32:.2e} rad\n");
        worst64 = worst64.max(a64);
        worst32 = worst32.max(a32);
    }
    eprintln!("{report}");
    assert!(worst64 < 1e-12, "f64 G1 angle {worst64:e} rad\n{report}");
    assert!(worst32 < 2e-4, "f32 G1 angle {worst32:e} rad\n{report}");
}

/// Negative control: dropping the perturbation h breaks G1 (spec §13 measures 0.17 rad),
/// so the angle measure above can fail.
#[test]
fn g1_measure_detects_missing_perturbation() {
    let mut p = PrepPatches::<f64>::build(&wobble(mixed40(), 0.02)).unwrap();
    p.h_mut().iter_mut().for_each(|x| *x = [0.0; 3]);
    let a = max_normal_angle(&p, 33);
    assert!(a > 1e-2, "h = 0 should not be G1, got {a:e}");
}

fn bits<T: Real>(x: [T; 3]) -> [u64; 3] {
    x.map(|v| v.to_f64().to_bits())
}

/// C0 bit-exact: the shared boundary coefficients (g_i0 and h20, h30 in the local frames)
/// are identical bits from both faces, in f32 and f64.
fn c0_bit_exact<T: Real>() {
    for (name, mesh) in closed_meshes() {
        let p = PrepPatches::<T>::build(&mesh).unwrap();
        for [a, b] in edge_corners(&p) {
            let ((f1, c1), (f2, c2)) = ((a / 4, a % 4), (b / 4, b % 4));
            for i in 0..4 {
                let (x1, y1) = corner_index(c1, i, 0, 3);
                let (x2, y2) = corner_index(c2, 3 - i, 0, 3);
                assert_eq!(
                    bits(p.face_g(f1)[4 * x1 + y1]),
                    bits(p.face_g(f2)[4 * x2 + y2]),
                    "{name}: g boundary of faces {f1}/{f2}"
                );
            }
            let zero = [T::zero(); 3];
            let h = |f: usize, s: usize| p.face_h(f).map_or(zero, |h| h[s]);
            // local h20 of one side is local h30 of the other.
            assert_eq!(
                bits(h(f1, 4 * c1)),
                bits(h(f2, 4 * c2 + 1)),
                "{name}: h20/h30 {f1}/{f2}"
            );
            assert_eq!(
                bits(h(f1, 4 * c1 + 1)),
                bits(h(f2, 4 * c2)),
                "{name}: h30/h20 {f1}/{f2}"
            );
            // Symmetric Case-2/3 formula: h31 of one side equals h21 of the other (spec §5.5).
            let (d1, d2) = (h(f1, 4 * c1 + 3), h(f2, 4 * c2 + 2));
            for k in 0..3 {
                let d = (d1[k].to_f64() - d2[k].to_f64()).abs();
                assert!(d < 1e-5, "{name}: h31/h21 {f1}/{f2} differ by {d:e}");
            }
        }
    }
}

#[test]
fn c0_bit_exact_f32() {
    c0_bit_exact::<f32>();
}

#[test]
fn c0_bit_exact_f64() {
    c0_bit_exact::<f64>();
}

/// H_SLOTS are the 16 entries with one index in {2,3} and the other in {0,1,4,5}.
#[test]
fn h_slots_are_the_sparse_pattern() {
    let mut s: Vec<_> = H_SLOTS.to_vec();
    s.sort();
    s.dedup();
    assert_eq!(s.len(), 16);
    for (i, j) in s {
        let mid = |x| x == 2 || x == 3;
        assert!(mid(i) != mid(j), "({i},{j})");
    }
}

/// The tessellation is watertight: every directed triangle edge has its reverse (a closed
/// 2-manifold), its edge samples equal the face evaluation to round-off, and the samples of a
/// shared edge evaluated from either face's boundary coefficients in the canonical direction
/// are bit-identical.
#[test]
fn tessellation_is_watertight() {
    for (name, mesh) in closed_meshes() {
        let p = PrepPatches::<f32>::build(&mesh).unwrap();
        for n in [2, 3, 5, 9] {
            let t = p.tessellate(n);
            assert_eq!(t.triangles.len(), 2 * p.num_faces() * (n - 1) * (n - 1));
            let mut directed = std::collections::HashMap::new();
            for tri in &t.triangles {
                for k in 0..3 {
                    *directed.entry((tri[k], tri[(k + 1) % 3])).or_insert(0) += 1;
                }
            }
            for (&(a, b), &cnt) in &directed {
                assert_eq!(
                    cnt, 1,
                    "{name} n={n}: directed edge {a}->{b} used {cnt} times"
                );
                assert!(
                    directed.contains_key(&(b, a)),
                    "{name} n={n}: open edge {a}->{b}"
                );
            }
            // Positions agree with the per-face grid evaluation (not shared) to round-off.
            let grid = p.eval_grid(n);
            let mut worst = 0.0f64;
            for f in 0..p.num_faces() {
                let ft = &t.triangles[2 * f * (n - 1) * (n - 1)..];
                for j in 0..n - 1 {
                    for i in 0..n - 1 {
                        let tri = ft[2 * (j * (n - 1) + i)];
                        let g = grid.positions[f * n * n + j * n + i];
                        let q = t.positions[tri[0] as usize];
                        for k in 0..3 {
                            worst = worst.max((g[k] - q[k]).abs() as f64);
                        }
                    }
                }
            }
            assert!(worst < 1e-5, "{name} n={n}: tessellation vs grid {worst:e}");
        }
        // Edge curve from the non-owning face's coefficients, canonical direction: same bits.
        let n = 7;
        let t = p.tessellate(n);
        for [a, b] in edge_corners(&p) {
            for corner in [a, b] {
                let (f, c) = (corner / 4, corner % 4);
                let v0 = p.topology().face_verts()[4 * f + c];
                let v1 = p.topology().face_verts()[4 * f + (c + 1) % 4];
                let e = p.topology().face_edges()[corner] as usize;
                for s in 1..n - 1 {
                    let _ = (v0, v1);
                    let x = edge_curve(&p, f, c, s as f32 / (n - 1) as f32);
                    let idx = p.topology().num_vertices() + e * (n - 2) + s - 1;
                    assert_eq!(
                        bits(x),
                        bits(t.positions[idx]),
                        "{name}: edge {e} sample {s} from face {f}"
                    );
                }
            }
        }
    }
}

/// Boundary curve of corner `c`'s edge, evaluated like the tessellator does.
fn edge_curve(p: &PrepPatches<f32>, f: usize, c: usize, t: f32) -> [f32; 3] {
    let (s, t2) = (1.0 - t, t * t);
    let b3 = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
    let s2 = s * s;
    let b5 = [0.0, 0.0, 10.0 * s2 * s * t2, 10.0 * s2 * t2 * t];
    let g = p.face_g(f);
    let mut x = [0.0f32; 3];
    // Coefficients of this face read in the edge's canonical direction.
    let v0 = p.topology().face_verts()[4 * f + c];
    let v1 = p.topology().face_verts()[4 * f + (c + 1) % 4];
    let fwd = v0 < v1;
    for i in 0..4 {
        let ii = if fwd { i } else { 3 - i };
        let (a, b) = corner_index(c, ii, 0, 3);
        for k in 0..3 {
            x[k] += b3[i] * g[4 * a + b][k];
        }
    }
    if let Some(h) = p.face_h(f) {
        let (h2, h3) = if fwd {
            (h[4 * c], h[4 * c + 1])
        } else {
            (h[4 * c + 1], h[4 * c])
        };
        for k in 0..3 {
            x[k] += b5[2] * h2[k];
            x[k] += b5[3] * h3[k];
        }
    }
    x
}

/// Tessellation normals: corner normals (e1 × e2) agree with every adjacent patch normal, and
/// all normals are unit length.
#[test]
fn tessellation_normals_consistent() {
    let mesh = wobble(mixed40(), 0.02);
    let p = PrepPatches::<f64>::build(&mesh).unwrap();
    let t = p.tessellate(5);
    for f in 0..p.num_faces() {
        for c in 0..4 {
            let v = p.topology().face_verts()[4 * f + c] as usize;
            let s = eval_on_edge(&p, f, c, 0.0);
            let a = angle(s.normal(), t.normals[v]);
            assert!(a < 1e-12, "corner normal of vertex {v} vs face {f}: {a:e}");
        }
    }
    for nr in &t.normals {
        let l = (nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2]).sqrt();
        assert!((l - 1.0).abs() < 1e-12);
    }
}

/// The parallel passes give the same bits as the sequential reference.
#[test]
fn parallel_equals_sequential() {
    let mesh = quad_mesh_big();
    let a = PrepPatches::<f32>::build(&mesh).unwrap();
    let b = PrepPatches::<f32>::build_sequential(&mesh).unwrap();
    assert_eq!(a.g(), b.g());
    assert_eq!(a.h(), b.h());
    assert_eq!(a.vertex().tangent, b.vertex().tangent);
    assert_eq!(a.vertex().interior, b.vertex().interior);
}

fn quad_mesh_big() -> subsurf::Mesh {
    subsurf::prep::quadrangulate(&wobble(mixed40(), 0.02)).unwrap()
}

/// The limit point g00 (eq. 2) is the Catmull-Clark limit: one Catmull-Clark step, applied by
/// hand to a valence-5 vertex and its ring, gives a refined ring with the same limit point
/// (spec §3: left eigenvector with eigenvalue 1). Every patch corner at the vertex is g00.
#[test]
fn limit_point_is_invariant_under_catmull_clark() {
    let mesh = wobble(spindle(5, 2), 0.03);
    let p = PrepPatches::<f64>::build(&mesh).unwrap();
    let v = 0; // the top pole, valence 5
    let ring = p.topology().ring(v).to_vec();
    let n = ring.len() / 2;
    assert_eq!(n, 5);
    let pos = |i: u32| mesh.positions[i as usize].map(|x| x as f64);
    let avg = |pts: &[[f64; 3]]| {
        let mut a = [0.0; 3];
        for q in pts {
            for k in 0..3 {
                a[k] += q[k] / pts.len() as f64;
            }
        }
        a
    };
    let p0 = pos(v as u32);
    let e: Vec<_> = (0..n).map(|j| pos(ring[2 * j])).collect();
    let d: Vec<_> = (0..n).map(|j| pos(ring[2 * j + 1])).collect();
    let face: Vec<_> = (0..n)
        .map(|j| avg(&[p0, e[j], d[j], e[(j + 1) % n]]))
        .collect();
    let edge: Vec<_> = (0..n)
        .map(|j| avg(&[p0, e[j], face[(j + n - 1) % n], face[j]]))
        .collect();
    let nf = n as f64;
    let mut vp = [0.0; 3];
    for k in 0..3 {
        let se: f64 = e.iter().map(|q| q[k]).sum();
        let sd: f64 = d.iter().map(|q| q[k]).sum();
        vp[k] =
            (1.0 - 7.0 / (4.0 * nf)) * p0[k] + 3.0 / (2.0 * nf * nf) * se + sd / (4.0 * nf * nf);
    }
    let limit = |c: [f64; 3], ee: &[[f64; 3]], dd: &[[f64; 3]]| {
        let mut g = [0.0; 3];
        for k in 0..3 {
            let se: f64 = ee.iter().map(|q| q[k]).sum();
            let sd: f64 = dd.iter().map(|q| q[k]).sum();
            g[k] = (nf * nf * c[k] + 4.0 * se + sd) / (nf * (nf + 5.0));
        }
        g
    };
    let refined = limit(vp, &edge, &face);
    let g00 = p.vertex().limit[v];
    for k in 0..3 {
        assert!(
            (refined[k] - g00[k]).abs() < 1e-14,
            "limit moved by a CC step"
        );
    }
    for f in 0..p.num_faces() {
        for c in 0..4 {
            if p.topology().face_verts()[4 * f + c] as usize == v {
                let s = eval_on_edge(&p, f, c, 0.0).position;
                for k in 0..3 {
                    assert!(
                        (s[k] - g00[k]).abs() < 1e-15,
                        "patch corner must be the limit point"
                    );
                }
            }
        }
    }
}

/// The row-contracted grid evaluation equals pointwise evaluation to round-off.
#[test]
fn grid_equals_pointwise_eval() {
    let p = PrepPatches::<f64>::build(&wobble(mixed40(), 0.02)).unwrap();
    let n = 6;
    let grid = p.eval_grid(n);
    for f in 0..p.num_faces() {
        for j in 0..n {
            for i in 0..n {
                let s = p.eval(f, i as f64 / 5.0, j as f64 / 5.0);
                let (a, b) = (grid.positions[f * n * n + j * n + i], s.position);
                let d = (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max);
                assert!(d < 1e-14, "face {f} ({i},{j}): {d:e}");
                assert!(angle(grid.normals[f * n * n + j * n + i], s.normal()) < 1e-12);
            }
        }
    }
}

/// High valences: G1 holds for poles of valence 12, 16 and 32 (f64); valence 65 is refused.
/// Measured: 5.7e-15, 6.5e-15, 1.1e-14 rad.
#[test]
fn high_valence_poles() {
    for n in [12, 16, 32] {
        let a = max_normal_angle(&PrepPatches::<f64>::build(&spindle(n, 2)).unwrap(), 33);
        eprintln!("spindle {n}: {a:.2e} rad");
        assert!(a < 1e-11, "valence {n}: {a:e} rad");
    }
    let err = PrepPatches::<f32>::build(&spindle(65, 1))
        .unwrap_err()
        .to_string();
    assert!(err.contains("vertex 0 (valence 65)"), "{err}");
}
