//! `limit_eval` and [`GpuLimit`] against the library's [`LimitSurface`]: the CPU twin bit for
//! bit, the GPU within f32 rounding, on OpenSubdiv regression shapes covering regular,
//! boundary, single-crease (integer and fractional sharpness) and Gregory end-cap patches,
//! n-gons and holes.

mod common;

use common::{bits, context_or_skip, load};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, Tessellation};
use subsurf::{Mesh, Topology};
use subsurf_gpu::limit::{eval_cpu, tessellate_cpu};
use subsurf_gpu::{ChunkLimits, GpuContext, GpuLimit};

fn shapes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

/// `(name, isolation level)`: what each shape exercises is in the comment.
const SHAPES: [(&str, u32); 9] = [
    ("catmark_cube", 3),           // valence-3 corners: Gregory end caps
    ("catmark_gregory_test1", 3),  // boundary and interior end caps
    ("catmark_cube_creases0", 3),  // integer semi-sharp creases: single-crease patches
    ("catmark_torus_creases0", 3), // fractional sharpness 4.7
    ("catmark_edgecorner", 2),     // boundary and corner patches
    ("catmark_pyramid", 2),        // triangles and a quad: non-quad ptex faces
    ("catmark_hole_test1", 2),     // a hole
    ("catmark_car", 1),            // a large mixed mesh with creases
    ("catmark_cube_corner0", 0),   // no refinement: level-0 patches and end caps only
];

fn bbox_diagonal(p: &[[f32; 3]]) -> f64 {
    subsurf::mesh::bbox_diagonal(p) as f64
}

fn dist(a: [f32; 3], b: [f32; 3]) -> f64 {
    (0..3)
        .map(|k| (a[k] as f64 - b[k] as f64).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// GPU against CPU: identical quads, positions within `1e-5` of the bounding-box diagonal,
/// normals within `2e-3` (about 0.1°; both zero where the CPU's is), nothing non-finite.
/// Returns the first violation.
fn compare(got: &Tessellation, want: &Tessellation, diag: f64) -> Result<(), String> {
    compare_skipping(got, want, diag, &[])
}

/// [`compare`] without the normals of the vertices flagged in `degenerate` (a vanishing
/// derivative: the normal there is the sign of rounding noise, or the CPU's fallback where
/// its derivative cancels exactly).
fn compare_skipping(
    got: &Tessellation,
    want: &Tessellation,
    diag: f64,
    degenerate: &[bool],
) -> Result<(), String> {
    if got.quads != want.quads {
        return Err("index buffers differ".into());
    }
    if got.positions.len() != want.positions.len() {
        return Err("vertex counts differ".into());
    }
    for (i, (g, w)) in got.positions.iter().zip(&want.positions).enumerate() {
        let d = dist(*g, *w);
        if d.is_nan() || d > 1e-5 * diag {
            return Err(format!("vertex {i}: GPU {g:?} vs CPU {w:?} ({d:e})"));
        }
    }
    for (i, (g, w)) in got.normals.iter().zip(&want.normals).enumerate() {
        if degenerate.get(i) == Some(&true) {
            continue;
        }
        let d = dist(*g, *w);
        if d.is_nan() || d > 2e-3 {
            return Err(format!("normal {i}: GPU {g:?} vs CPU {w:?} ({d:e})"));
        }
    }
    Ok(())
}

#[test]
fn shapes_cover_every_patch_kind() {
    let (mut crease, mut gregory, mut fractional, mut holes, mut ngons) = (0, 0, 0, 0, 0);
    for (name, iso) in SHAPES {
        let (mesh, table) = load(name, iso);
        let c = table.counts();
        crease += c.single_crease;
        gregory += c.gregory;
        fractional += table
            .sharpness()
            .iter()
            .filter(|s| s.fract() != 0.0)
            .count();
        holes += mesh.holes.len();
        ngons += mesh.face_counts.iter().filter(|&&n| n != 4).count();
    }
    assert!(crease > 0 && gregory > 0 && fractional > 0 && holes > 0 && ngons > 0);
}

#[test]
fn twin_reproduces_the_library_bit_for_bit() {
    for (name, iso) in SHAPES {
        let (mesh, table) = load(name, iso);
        let points = table.points(&mesh.positions);
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        for n in [2, 5] {
            let want = surface.tessellate(n).unwrap();
            let got = tessellate_cpu(&table, &points, n).unwrap();
            assert_eq!(got.quads, want.quads, "{name} n={n}: quads");
            assert_eq!(
                bits(got.positions.as_flattened()),
                bits(want.positions.as_flattened()),
                "{name} n={n}: positions"
            );
            assert_eq!(
                bits(got.normals.as_flattened()),
                bits(want.normals.as_flattened()),
                "{name} n={n}: normals"
            );
        }
    }
}

/// Every Catmull-Clark regression shape (non-manifold ones included).
fn catmark_shapes() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(shapes_dir())
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("catmark_") && n.ends_with(".obj"))
        .collect();
    names.sort();
    assert!(names.len() > 50, "{} shapes", names.len());
    names
}

#[test]
fn twin_matches_the_library_on_every_catmark_shape() {
    for file in catmark_shapes() {
        let (mesh, table) = load(file.trim_end_matches(".obj"), 2);
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        let want = surface.tessellate(5).unwrap();
        let got = tessellate_cpu(&table, surface.points(), 5).unwrap();
        // Tessellation's PartialEq compares f32 values: NaN-free by the same comparison.
        assert!(
            got == want,
            "{file}: twin differs from LimitSurface::tessellate"
        );
    }
}

#[test]
fn twin_derivatives_match_library_eval() {
    for (name, iso) in SHAPES {
        let (mesh, table) = load(name, iso);
        let points = table.points(&mesh.positions);
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        let mut queries = Vec::new();
        for f in 0..table.num_ptex_faces() as u32 {
            for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.25), (0.999, 0.001)] {
                queries.push((f, u, v));
            }
        }
        let out = eval_cpu(&table, &points, &queries, 12);
        for (k, &(f, u, v)) in queries.iter().enumerate() {
            let o = &out[12 * k..12 * k + 12];
            let want = surface.eval(f as usize, u, v).unwrap_or_default();
            let got = [
                [o[0], o[1], o[2]],
                [o[3], o[4], o[5]],
                [o[6], o[7], o[8]],
                [o[9], o[10], o[11]],
            ];
            assert_eq!(
                got,
                [want.p, want.n, want.du, want.dv],
                "{name} {f} {u} {v}"
            );
        }
    }
}

fn gpu_tessellation(
    ctx: &GpuContext,
    gpu: &mut GpuLimit,
    table: &PatchTable,
    mesh: &Mesh,
    n: usize,
) -> Tessellation {
    gpu.update(ctx, &mesh.positions).unwrap();
    let t = gpu.tessellation(ctx, table, n).unwrap();
    gpu.eval(ctx, &t.samples).unwrap();
    t.download(ctx).unwrap()
}

#[test]
fn gpu_tessellation_matches_cpu() {
    let Some(ctx) = context_or_skip("gpu_tessellation_matches_cpu") else {
        return;
    };
    for (name, iso) in SHAPES {
        let (mesh, table) = load(name, iso);
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        let diag = bbox_diagonal(&mesh.positions);
        let mut gpu = GpuLimit::new(&ctx, &table).unwrap();
        gpu.update(&ctx, &mesh.positions).unwrap();
        // The point array (refinement + end-cap stencils) first.
        let points = gpu.download_points(&ctx).unwrap();
        for (i, (g, w)) in points.iter().zip(surface.points()).enumerate() {
            assert!(
                dist(*g, *w) <= 1e-6 * diag,
                "{name}: point {i}: {g:?} vs {w:?}"
            );
        }
        for n in [2, 5] {
            let got = gpu_tessellation(&ctx, &mut gpu, &table, &mesh, n);
            let want = surface.tessellate(n).unwrap();
            if let Err(e) = compare(&got, &want, diag) {
                panic!("{name} n={n}: {e}");
            }
        }
    }
}

#[test]
fn gpu_matches_cpu_on_every_catmark_shape() {
    let Some(ctx) = context_or_skip("gpu_matches_cpu_on_every_catmark_shape") else {
        return;
    };
    for file in catmark_shapes() {
        let (mesh, table) = load(file.trim_end_matches(".obj"), 2);
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        let want = surface.tessellate(5).unwrap();
        // Where a derivative vanishes (the collapsed boundaries of the valence-2 shapes).
        let degenerate: Vec<bool> = table
            .tessellation_plan(5)
            .unwrap()
            .queries
            .iter()
            .map(|&(f, u, v)| {
                surface.eval_raw(f as usize, u, v).is_none_or(|r| {
                    let n2 = |a: [f32; 3]| (0..3).map(|c| f64::from(a[c]).powi(2)).sum::<f64>();
                    let c = [
                        r.du[1] * r.dv[2] - r.du[2] * r.dv[1],
                        r.du[2] * r.dv[0] - r.du[0] * r.dv[2],
                        r.du[0] * r.dv[1] - r.du[1] * r.dv[0],
                    ];
                    n2(c).sqrt() <= 1e-6 * n2(r.du).max(n2(r.dv))
                })
            })
            .collect();
        let mut gpu = GpuLimit::new(&ctx, &table).unwrap();
        let got = gpu_tessellation(&ctx, &mut gpu, &table, &mesh, 5);
        let diag = bbox_diagonal(&mesh.positions);
        if let Err(e) = compare_skipping(&got, &want, diag, &degenerate) {
            panic!("{file}: {e}");
        }
    }
}

#[test]
fn gpu_derivatives_match_cpu() {
    let Some(ctx) = context_or_skip("gpu_derivatives_match_cpu") else {
        return;
    };
    for (name, iso) in [SHAPES[1], SHAPES[3], SHAPES[5]] {
        let (mesh, table) = load(name, iso);
        let surface = LimitSurface::new(table.clone(), &mesh.positions);
        let mut gpu = GpuLimit::new(&ctx, &table).unwrap();
        gpu.update(&ctx, &mesh.positions).unwrap();
        let mut queries = Vec::new();
        for f in 0..table.num_ptex_faces() as u32 {
            for (u, v) in [(0.1, 0.2), (0.5, 0.5), (0.9, 0.05), (1.0, 1.0)] {
                queries.push((f, u, v));
            }
        }
        let s = gpu.samples(&ctx, &queries, true).unwrap();
        gpu.eval(&ctx, &s).unwrap();
        let got = s.download_points(&ctx).unwrap();
        let diag = bbox_diagonal(&mesh.positions);
        for (&(f, u, v), g) in queries.iter().zip(&got) {
            let w = surface.eval(f as usize, u, v).unwrap_or_default();
            // Derivatives are sums of terms up to 2^level times the mesh size.
            let scale = diag * 2f64.powi(iso as i32 + 1);
            assert!(dist(g.p, w.p) <= 1e-5 * diag, "{name} {f} {u} {v}: p");
            assert!(
                dist(g.du, w.du) <= 1e-5 * scale,
                "{name} {f} {u} {v}: du {:?} vs {:?}",
                g.du,
                w.du
            );
            assert!(
                dist(g.dv, w.dv) <= 1e-5 * scale,
                "{name} {f} {u} {v}: dv {:?} vs {:?}",
                g.dv,
                w.dv
            );
        }
    }
}

#[test]
fn gpu_update_follows_a_deformation_and_a_planted_error_is_caught() {
    let Some(ctx) = context_or_skip("gpu_update_follows_a_deformation") else {
        return;
    };
    let (mesh, table) = load("catmark_gregory_test1", 3);
    let mut gpu = GpuLimit::new(&ctx, &table).unwrap();
    gpu.update(&ctx, &mesh.positions).unwrap();
    let t = gpu.tessellation(&ctx, &table, 4).unwrap();
    let mut last = None;
    for frame in 1..3 {
        let s = frame as f32;
        let moved: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|q| {
                [
                    q[0] * (1.0 + 0.2 * s),
                    q[1] + 0.1 * (s * q[0]).sin(),
                    q[2] - s,
                ]
            })
            .collect();
        gpu.update(&ctx, &moved).unwrap();
        gpu.eval(&ctx, &t.samples).unwrap();
        let got = t.download(&ctx).unwrap();
        let want = LimitSurface::new(table.clone(), &moved)
            .tessellate(4)
            .unwrap();
        let diag = bbox_diagonal(&moved);
        compare(&got, &want, diag).unwrap();
        last = Some((got, moved, diag));
    }
    // Negative control: the same comparison rejects a surface whose base mesh differs by one
    // vertex moved by 1% of the diagonal.
    let (got, mut moved, diag) = last.unwrap();
    moved[3][1] += 0.01 * diag as f32;
    let planted = LimitSurface::new(table.clone(), &moved)
        .tessellate(4)
        .unwrap();
    assert!(compare(&got, &planted, diag).is_err());
    assert!(gpu.update(&ctx, &mesh.positions[1..]).is_err());
}

#[test]
fn chunked_evaluation_matches_unchunked() {
    let Some(ctx) = context_or_skip("chunked_evaluation_matches_unchunked") else {
        return;
    };
    let (mesh, table) = load("catmark_car", 1);
    // Grids of at most 2 x 2 workgroups (256 samples) and 512 KiB bindings: the samples,
    // the refinement and the end-cap stencils are all split; the point array and the patch
    // tables (bound whole) still fit.
    let limits = ChunkLimits {
        max_binding_bytes: 1 << 19,
        max_workgroups_per_dimension: 2,
        max_stride: 3,
    };
    let mut small = GpuLimit::with_limits(&ctx, &table, limits).unwrap();
    let mut full = GpuLimit::new(&ctx, &table).unwrap();
    small.update(&ctx, &mesh.positions).unwrap();
    full.update(&ctx, &mesh.positions).unwrap();
    let (a, b) = (
        small.tessellation(&ctx, &table, 3).unwrap(),
        full.tessellation(&ctx, &table, 3).unwrap(),
    );
    assert!(
        a.samples.num_dispatches() > 4,
        "{} dispatches",
        a.samples.num_dispatches()
    );
    small.eval(&ctx, &a.samples).unwrap();
    full.eval(&ctx, &b.samples).unwrap();
    let (ta, tb) = (a.download(&ctx).unwrap(), b.download(&ctx).unwrap());
    compare(&ta, &tb, bbox_diagonal(&mesh.positions)).unwrap();
}

#[test]
fn bad_requests_are_errors() {
    let Some(ctx) = context_or_skip("bad_requests_are_errors") else {
        return;
    };
    let (_, table) = load("catmark_cube", 2);
    let gpu = GpuLimit::new(&ctx, &table).unwrap();
    assert!(gpu.samples(&ctx, &[(0, f32::NAN, 0.5)], false).is_err());
    assert!(gpu.tessellation(&ctx, &table, 1).is_err());
}

/// Base positions produced on the GPU (here by a `GpuRefiner`) feed the limit surface
/// without a trip through the host: the same point array and samples, bit for bit, as
/// uploading them.
#[test]
fn update_from_gpu_positions_matches_update() {
    let Some(ctx) = context_or_skip("update_from_gpu_positions_matches_update") else {
        return;
    };
    let (base, _) = load("catmark_gregory_test1", 1);
    let refiner = subsurf::Refiner::new(Topology::new(&base).unwrap(), 1).unwrap();
    let gpu_refiner = subsurf_gpu::GpuRefiner::new(&ctx, &refiner).unwrap();
    gpu_refiner.update(&ctx, &base.positions).unwrap();
    let refined = gpu_refiner.download(&ctx).unwrap();
    let mesh = refiner.to_mesh(1, refined.clone());
    let options = PatchOptions {
        isolation_level: 3,
        ..Default::default()
    };
    let table = PatchTable::build(&Topology::new(&mesh).unwrap(), &options).unwrap();
    let mut from_gpu = GpuLimit::new(&ctx, &table).unwrap();
    let mut uploaded = GpuLimit::new(&ctx, &table).unwrap();
    from_gpu.update_from(&ctx, gpu_refiner.output()).unwrap();
    uploaded.update(&ctx, &refined).unwrap();
    let (a, b) = (
        from_gpu.download_points(&ctx).unwrap(),
        uploaded.download_points(&ctx).unwrap(),
    );
    assert_eq!(bits(a.as_flattened()), bits(b.as_flattened()));
    let (ta, tb) = (
        from_gpu.tessellation(&ctx, &table, 5).unwrap(),
        uploaded.tessellation(&ctx, &table, 5).unwrap(),
    );
    from_gpu.eval(&ctx, &ta.samples).unwrap();
    uploaded.eval(&ctx, &tb.samples).unwrap();
    assert_eq!(
        bits(&ta.samples.download(&ctx).unwrap()),
        bits(&tb.samples.download(&ctx).unwrap())
    );
    let wrong = subsurf_gpu::VertexBuffer::zeroed(&ctx, refined.len() + 1, 3).unwrap();
    assert!(from_gpu.update_from(&ctx, &wrong).is_err());
}
