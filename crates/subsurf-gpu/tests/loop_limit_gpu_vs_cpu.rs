//! `loop_eval` and [`GpuLoopLimit`] against the library's Loop limit surface
//! ([`LoopLimit`]): the CPU twin's weights bit for bit against `tri_patch_weights::<f32>`,
//! its evaluation within f32 rounding of the library's f64 one, and the GPU within `1e-5` of
//! the bounding-box diagonal (positions) and `1e-3` rad (normals) on every `loop_*`
//! regression shape; `surface::build` on the GPU backend against the CPU backend.

mod common;

use common::{context_or_skip, Rng};
use subsurf::limit::LoopLimit;
use subsurf::limit::PatchOptions;
use subsurf::limit::{tri_tessellation_plan, TriTessellation};
use subsurf::patch::{tri_patch_weights, PatchParam, PatchParamFields, TriPatchKind};
use subsurf::surface::{build, Colors, Cpu, Method, SurfaceOptions};
use subsurf::{Mesh, Scheme, Topology};
use subsurf_gpu::cpu::loop_eval::{
    patch_weights, LoopTables, KIND_BOX_SPLINE, KIND_GREGORY_TRIANGLE,
};
use subsurf_gpu::loop_limit::{loop_eval_cpu, loop_tessellate_cpu};
use subsurf_gpu::{ChunkLimits, GpuBackend, GpuContext, GpuLoopLimit};

/// Isolation level and segments per edge of the shape tests.
const ISOLATION: u32 = 3;
const SEGMENTS: usize = 8;

fn shapes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

/// Every `loop_*` regression shape with its topology and Loop limit surface.
fn loop_shapes() -> Vec<(String, Mesh, Topology, LoopLimit)> {
    let paths = subsurf::shapes::regression_shapes(&shapes_dir(), &["loop_"]).unwrap();
    assert!(paths.len() >= 31, "loop shapes found: {}", paths.len());
    paths
        .iter()
        .map(|path| {
            let name = path.file_stem().unwrap().to_string_lossy().to_string();
            let mesh = subsurf::io::read_path(path).unwrap();
            assert_eq!(mesh.options.scheme, Scheme::Loop, "{name}");
            let topo = Topology::new(&mesh).unwrap();
            let limit = LoopLimit::new(&topo, &mesh.positions, ISOLATION).unwrap();
            (name, mesh, topo, limit)
        })
        .collect()
}

fn diagonal(mesh: &Mesh) -> f64 {
    subsurf::mesh::bbox_diagonal(&mesh.positions) as f64
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The angle between two unit vectors (robust near 0).
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let s = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    s.atan2(a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
}

/// Per sample of the tessellation of `limit` with [`SEGMENTS`]: whether the tangent plane
/// degenerates there (`|∂P/∂u × ∂P/∂v|` below `1e-8` of the diagonal squared in the library's
/// f64), where the unit normal is the direction of rounding noise. Points and curves
/// (corners of one face, non-manifold edges), and the folded sheets around the valence-2
/// vertices of `loop_val2_interior` (a fifth of its samples); the callers check that these
/// are few over all shapes.
fn degenerate(limit: &LoopLimit, topo: &Topology, diag: f64) -> Vec<bool> {
    let plan = tri_tessellation_plan(topo, SEGMENTS).unwrap();
    let flags: Vec<bool> = plan
        .samples
        .iter()
        .map(|s| {
            let Some((f, [u, v])) = *s else {
                return false;
            };
            let e = limit.eval(f as usize, u, v).unwrap();
            let (a, b) = (e.du, e.dv);
            let c = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() < 1e-8 * diag * diag
        })
        .collect();
    flags
}

/// Worst position error (relative to `diag`) and normal angle of `got` against `want`,
/// normals not compared where `degenerate`; an error if the triangles differ, a reached
/// sample is not finite, which samples are reached differs, or one normal vanishes where the
/// other does not off a degenerate sample.
fn compare(
    got: &TriTessellation,
    want: &TriTessellation,
    diag: f64,
    degenerate: &[bool],
) -> Result<(f64, f64), String> {
    if got.triangles != want.triangles || got.segments != want.segments {
        return Err("triangles differ".into());
    }
    if got.positions.len() != want.positions.len() || got.normals.len() != want.normals.len() {
        return Err("sample counts differ".into());
    }
    let (mut pos, mut nrm) = (0.0f64, 0.0f64);
    for (i, (g, w)) in got.positions.iter().zip(&want.positions).enumerate() {
        if w[0].is_nan() {
            if !g[0].is_nan() {
                return Err(format!("sample {i} is reached on one side only"));
            }
            continue;
        }
        let d = dist(*g, *w) / diag;
        if !d.is_finite() {
            return Err(format!("sample {i}: {g:?} vs {w:?}"));
        }
        pos = pos.max(d);
        if degenerate[i] {
            continue;
        }
        let (gn, wn) = (got.normals[i], want.normals[i]);
        let zero = |n: [f64; 3]| n == [0.0; 3];
        if zero(gn) || zero(wn) {
            if zero(gn) != zero(wn) {
                return Err(format!("sample {i}: normal {gn:?} vs {wn:?}"));
            }
            continue;
        }
        nrm = nrm.max(angle(gn, wn));
    }
    Ok((pos, nrm))
}

#[test]
fn twin_weights_are_the_library_f32_weights_bit_for_bit() {
    let mut rng = Rng::new(11);
    let mut checked = 0;
    for depth in 0u8..=4 {
        let side = 1u32 << depth;
        for _ in 0..12 {
            // Any origin: upright (U + V < 2^d) and rotated (U + V ≥ 2^d) sub-triangles.
            let (iu, iv) = (rng.below(side) as u16, rng.below(side) as u16);
            for boundary in 0u8..32 {
                for (kind, code) in [
                    (TriPatchKind::BoxSpline, KIND_BOX_SPLINE),
                    (TriPatchKind::GregoryTriangle, KIND_GREGORY_TRIANGLE),
                ] {
                    if kind == TriPatchKind::GregoryTriangle && boundary != 0 {
                        continue;
                    }
                    let param = PatchParam::new(PatchParamFields {
                        face_id: 3,
                        u: iu,
                        v: iv,
                        depth,
                        boundary,
                        regular: kind == TriPatchKind::BoxSpline,
                        ..Default::default()
                    })
                    .unwrap();
                    // Corners, edge points and interior points of the sub-triangle (and a
                    // little outside it), in base-face coordinates.
                    let mut st = vec![(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.5, 0.5), (0.0, 0.3)];
                    for _ in 0..6 {
                        st.push((rng.range(-0.05, 1.0), rng.range(-0.05, 1.0)));
                    }
                    for (s, t) in st {
                        let (u, v) = param.unnormalize_triangle(s, t);
                        let want = tri_patch_weights::<f32>(kind, &param, u, v);
                        let (p, du, dv) = patch_weights(code, param.field1, u, v);
                        let b = |w: &[f32]| w.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                        assert_eq!(b(&p), b(&want.p), "{kind:?} {param:?} ({u}, {v}) p");
                        assert_eq!(b(&du), b(&want.du), "{kind:?} {param:?} ({u}, {v}) du");
                        assert_eq!(b(&dv), b(&want.dv), "{kind:?} {param:?} ({u}, {v}) dv");
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(checked > 10_000, "{checked}");
}

#[test]
fn twin_matches_the_library_on_every_loop_shape() {
    let (mut worst_p, mut worst_n, mut worst_d) = (0.0f64, 0.0f64, 0.0f64);
    let mut flat_count = (0, 0);
    let mut kinds = (0, 0);
    for (name, mesh, topo, limit) in loop_shapes() {
        let diag = diagonal(&mesh);
        let want = limit.tessellate(&topo, SEGMENTS).unwrap();
        let got = loop_tessellate_cpu(&limit, &topo, SEGMENTS).unwrap();
        let flat = degenerate(&limit, &topo, diag);
        flat_count.0 += flat.iter().filter(|&&d| d).count();
        flat_count.1 += flat.len();
        let (p, n) = compare(&got, &want, diag, &flat).unwrap_or_else(|e| panic!("{name}: {e}"));
        // f32 points and arithmetic against the library's f64: a few roundings.
        assert!(
            p <= 1e-6,
            "{name}: twin position error {p:e} of the diagonal"
        );
        assert!(n <= 1e-3, "{name}: twin normal error {n:e} rad");
        worst_p = worst_p.max(p);
        worst_n = worst_n.max(n);
        // Derivatives at random samples of every patch.
        let mut rng = Rng::new(5);
        let mut queries = Vec::new();
        let mut uv = Vec::new();
        for patch in &limit.patches {
            kinds.0 += patch.regular as usize;
            kinds.1 += !patch.regular as usize;
            for _ in 0..3 {
                let (a, b) = (rng.range(0.0, 1.0) as f64, rng.range(0.0, 1.0) as f64);
                let (s, t) = if a + b > 1.0 {
                    (1.0 - a, 1.0 - b)
                } else {
                    (a, b)
                };
                let (u, v) = patch.param.unnormalize_triangle(s, t);
                let (u, v) = (u as f32, v as f32);
                let f = patch.param.face_id() as usize;
                // The patch the library evaluates there (on a seam: maybe a neighbour).
                let k = limit
                    .patch_map
                    .find_triangle(f, u as f64, v as f64)
                    .unwrap();
                queries.push((k, u, v));
                uv.push((f, u as f64, v as f64));
            }
        }
        let out = loop_eval_cpu(&limit, &queries, 12);
        for (o, &(f, u, v)) in out.chunks_exact(12).zip(&uv) {
            let w = limit.eval(f, u, v).unwrap();
            let x = |k: usize| [o[k], o[k + 1], o[k + 2]].map(f64::from);
            worst_p = worst_p.max(dist(x(0), w.p) / diag);
            for (g, w) in [(x(6), w.du), (x(9), w.dv)] {
                let scale = diag.max((w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt());
                let d = dist(g, w) / scale;
                assert!(
                    d <= 1e-5,
                    "{name}: derivative {g:?} vs {w:?} at {f} ({u}, {v})"
                );
                worst_d = worst_d.max(d);
            }
        }
    }
    assert!(kinds.0 > 0 && kinds.1 > 0, "{kinds:?}");
    assert!(
        flat_count.0 * 50 <= flat_count.1,
        "degenerate: {flat_count:?}"
    );
    eprintln!(
        "twin vs library (f64): positions {worst_p:e} of the diagonal, normals {worst_n:e} \
         rad, derivatives {worst_d:e}"
    );
}

fn gpu_or_skip(test: &str) -> Option<GpuContext> {
    context_or_skip(test)
}

#[test]
fn gpu_matches_the_library_on_every_loop_shape() {
    let Some(ctx) = gpu_or_skip("gpu_matches_the_library_on_every_loop_shape") else {
        return;
    };
    let (mut worst_p, mut worst_n, mut worst_twin) = (0.0f64, 0.0f64, 0.0f64);
    let mut worst_shape = String::new();
    let mut flat_count = (0, 0);
    for (name, mesh, topo, limit) in loop_shapes() {
        let diag = diagonal(&mesh);
        let want = limit.tessellate(&topo, SEGMENTS).unwrap();
        let gpu = GpuLoopLimit::new(&ctx, &limit).unwrap();
        let got = gpu.tessellate(&ctx, &limit, &topo, SEGMENTS).unwrap();
        let flat = degenerate(&limit, &topo, diag);
        flat_count.0 += flat.iter().filter(|&&d| d).count();
        flat_count.1 += flat.len();
        let (p, n) = compare(&got, &want, diag, &flat).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            p <= 1e-5,
            "{name}: GPU position error {p:e} of the diagonal"
        );
        assert!(n <= 1e-3, "{name}: GPU normal error {n:e} rad");
        if p > worst_p {
            worst_shape = name.clone();
        }
        worst_p = worst_p.max(p);
        worst_n = worst_n.max(n);
        let twin = loop_tessellate_cpu(&limit, &topo, SEGMENTS).unwrap();
        let (t, _) = compare(&got, &twin, diag, &flat).unwrap_or_else(|e| panic!("{name}: {e}"));
        worst_twin = worst_twin.max(t);
    }
    assert!(
        flat_count.0 * 50 <= flat_count.1,
        "degenerate: {flat_count:?}"
    );
    eprintln!(
        "GPU vs library at isolation {ISOLATION}, {SEGMENTS} segments: positions {worst_p:e} of \
         the diagonal ({worst_shape}), normals {worst_n:e} rad; GPU vs twin {worst_twin:e}"
    );
}

#[test]
fn a_planted_point_error_is_caught() {
    let Some(ctx) = gpu_or_skip("a_planted_point_error_is_caught") else {
        return;
    };
    let (name, mesh, topo, mut limit) = loop_shapes()
        .into_iter()
        .find(|s| s.0 == "loop_icosahedron")
        .unwrap();
    let diag = diagonal(&mesh);
    let want = limit.tessellate(&topo, SEGMENTS).unwrap();
    // Move one point of one end cap and one box spline by 1e-3 of the diagonal.
    for regular in [false, true] {
        let p = limit
            .patches
            .iter_mut()
            .find(|p| p.regular == regular)
            .unwrap();
        let k = if regular { 4 } else { 0 };
        p.points[k][0] += 1e-3 * diag;
    }
    let gpu = GpuLoopLimit::new(&ctx, &limit).unwrap();
    let got = gpu.tessellate(&ctx, &limit, &topo, SEGMENTS).unwrap();
    let (p, _) = compare(&got, &want, diag, &degenerate(&limit, &topo, diag)).unwrap();
    assert!(p > 1e-5, "{name}: a moved point went unnoticed ({p:e})");
}

#[test]
fn gpu_derivatives_and_chunks_match_the_twin() {
    let Some(ctx) = gpu_or_skip("gpu_derivatives_and_chunks_match_the_twin") else {
        return;
    };
    let shapes = loop_shapes();
    for name in [
        "loop_icosahedron",
        "loop_chaikin0",
        "loop_triangle_edgecorner",
    ] {
        let Some((_, mesh, _, limit)) = shapes.iter().find(|s| s.0 == name) else {
            continue;
        };
        let diag = diagonal(mesh);
        let mut rng = Rng::new(17);
        let mut queries: Vec<(u32, f32, f32)> = (0..3000)
            .map(|_| {
                let k = rng.below(limit.patches.len() as u32);
                let p = &limit.patches[k as usize];
                let (a, b) = (rng.range(0.0, 1.0) as f64, rng.range(0.0, 1.0) as f64);
                let (s, t) = if a + b > 1.0 {
                    (1.0 - a, 1.0 - b)
                } else {
                    (a, b)
                };
                let (u, v) = p.param.unnormalize_triangle(s, t);
                (k, u as f32, v as f32)
            })
            .collect();
        // A patch out of range evaluates to zeros.
        queries.push((u32::MAX, 0.25, 0.25));
        let twin = loop_eval_cpu(limit, &queries, 12);
        let gpu = GpuLoopLimit::new(&ctx, limit).unwrap();
        let s = gpu.samples(&ctx, &queries, true).unwrap();
        assert_eq!(s.num_dispatches(), 1);
        gpu.eval(&ctx, &s).unwrap();
        let got = s.download(&ctx).unwrap();
        assert_eq!(got.len(), twin.len());
        assert!(got[got.len() - 12..].iter().all(|&x| x == 0.0));
        for (i, (g, w)) in got.chunks_exact(12).zip(twin.chunks_exact(12)).enumerate() {
            for k in 0..12 {
                // Positions and derivatives scale with the mesh; normals are unit vectors.
                let scale = if (3..6).contains(&k) {
                    1.0
                } else {
                    diag.max(w[k].abs() as f64)
                };
                let d = (g[k] as f64 - w[k] as f64).abs() / scale;
                assert!(
                    d <= 1e-5,
                    "{name} sample {i} float {k}: GPU {g:?} twin {w:?}"
                );
            }
        }
        // Forced small bindings (the patch tables still fit): several dispatches, the same
        // floats bit for bit.
        let t = LoopTables::new(limit);
        let table_bytes = 4 * t.points.len().max(t.patch_info.len()) as u64;
        let small = GpuLoopLimit::with_limits(
            &ctx,
            limit,
            ChunkLimits {
                max_binding_bytes: table_bytes.next_multiple_of(1024),
                max_workgroups_per_dimension: 4,
                max_stride: 12,
            },
        )
        .unwrap();
        let s2 = small.samples(&ctx, &queries, true).unwrap();
        assert!(s2.num_dispatches() > 1, "{name}: {}", s2.num_dispatches());
        small.eval(&ctx, &s2).unwrap();
        let chunked = s2.download(&ctx).unwrap();
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&chunked), bits(&got), "{name}: chunked vs whole");
    }
}

#[test]
fn bad_requests_are_typed_errors() {
    let Some(ctx) = gpu_or_skip("bad_requests_are_typed_errors") else {
        return;
    };
    let (_, _, topo, limit) = loop_shapes()
        .into_iter()
        .find(|s| s.0 == "loop_icosahedron")
        .unwrap();
    let gpu = GpuLoopLimit::new(&ctx, &limit).unwrap();
    assert!(gpu.samples(&ctx, &[(0, f32::NAN, 0.0)], false).is_err());
    assert!(gpu.tessellate(&ctx, &limit, &topo, 0).is_err());
    let tiny = ChunkLimits {
        max_binding_bytes: 64,
        max_workgroups_per_dimension: 1,
        max_stride: 12,
    };
    match GpuLoopLimit::with_limits(&ctx, &limit, tiny) {
        Err(subsurf_gpu::GpuError::TooLarge { .. }) => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn surface_build_on_the_gpu_matches_the_cpu() {
    let Some(ctx) = gpu_or_skip("surface_build_on_the_gpu_matches_the_cpu") else {
        return;
    };
    let backend = GpuBackend { ctx };
    for (name, mesh, _, _) in loop_shapes() {
        if !matches!(
            name.as_str(),
            "loop_icosahedron" | "loop_triangle_edgecorner" | "loop_xord_boundary" | "loop_pole8"
        ) {
            continue;
        }
        let options = SurfaceOptions {
            method: Method::Limit {
                samples: SEGMENTS + 1,
                options: PatchOptions {
                    isolation_level: ISOLATION,
                    ..Default::default()
                },
            },
            colors: Colors::PatchKind,
            cage: true,
        };
        let cpu = build(&mesh, &options, &Cpu).unwrap();
        let gpu = build(&mesh, &options, &backend).unwrap();
        assert_eq!(gpu.triangles, cpu.triangles, "{name}");
        assert_eq!(gpu.triangle_class, cpu.triangle_class, "{name}");
        assert_eq!(gpu.cage, cpu.cage, "{name}");
        assert_eq!(gpu.positions.len(), cpu.positions.len(), "{name}");
        let diag = diagonal(&mesh);
        let f = |a: [f32; 3]| a.map(f64::from);
        for (g, c) in gpu.positions.iter().zip(&cpu.positions) {
            assert!(dist(f(*g), f(*c)) <= 1e-5 * diag, "{name}: {g:?} vs {c:?}");
        }
        for (g, c) in gpu.normals.iter().zip(&cpu.normals) {
            if *c == [0.0; 3] {
                assert_eq!(*g, [0.0; 3], "{name}");
            } else {
                assert!(angle(f(*g), f(*c)) <= 1e-3, "{name}: {g:?} vs {c:?}");
            }
        }
    }
}
