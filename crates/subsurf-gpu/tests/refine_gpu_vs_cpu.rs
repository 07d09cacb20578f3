//! `GpuRefiner` against the CPU `Refiner` on the OpenSubdiv regression shapes.

mod common;

use common::{bits, context_or_skip};
use subsurf::{Refiner, Topology};
use subsurf_gpu::{ChunkLimits, GpuContext, GpuRefiner};

fn shapes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

/// Catmark and bilinear shapes of the regression set, sorted by name.
fn shape_paths() -> Vec<std::path::PathBuf> {
    subsurf::shapes::regression_shapes(&shapes_dir(), &["catmark_", "bilinear_"])
        .expect("testdata/shapes is readable")
}

fn bbox_diagonal(p: &[[f32; 3]]) -> f64 {
    subsurf::mesh::bbox_diagonal(p) as f64
}

/// Every GPU position is finite and within `1e-5` of the bbox diagonal of the CPU's.
fn assert_close(name: &str, gpu: &[[f32; 3]], cpu: &[[f32; 3]]) {
    assert_eq!(gpu.len(), cpu.len(), "{name}: vertex count");
    let tol = 1e-5 * bbox_diagonal(cpu).max(f64::MIN_POSITIVE);
    for (i, (g, c)) in gpu.iter().zip(cpu).enumerate() {
        for k in 0..3 {
            assert!(g[k].is_finite(), "{name}: GPU vertex {i} is {g:?}");
            let d = (g[k] as f64 - c[k] as f64).abs();
            assert!(
                d <= tol,
                "{name}: vertex {i} GPU {g:?} vs CPU {c:?} (|diff| {d:e} > {tol:e})"
            );
        }
    }
}

fn check_shape(
    ctx: &GpuContext,
    path: &std::path::Path,
    level: usize,
    limits: Option<ChunkLimits>,
) {
    let name = format!(
        "{} level {level}",
        path.file_name().unwrap().to_string_lossy()
    );
    let mesh = subsurf::io::read_path(path).unwrap_or_else(|e| panic!("{name}: {e}"));
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
    let cpu = refiner.refine_positions(&mesh.positions);
    let gpu = match limits {
        Some(l) => GpuRefiner::with_limits(ctx, &refiner, l),
        None => GpuRefiner::new(ctx, &refiner),
    }
    .unwrap();
    assert_eq!(gpu.num_output_vertices(), cpu.len());
    assert_close(&name, &gpu.refine(ctx, &mesh.positions).unwrap(), &cpu);
}

#[test]
fn regression_shapes_match_cpu_refiner() {
    let Some(ctx) = context_or_skip("regression_shapes_match_cpu_refiner") else {
        return;
    };
    let paths = shape_paths();
    assert!(paths.len() > 20, "regression shapes found: {}", paths.len());
    for path in &paths {
        check_shape(&ctx, path, 2, None);
    }
    for name in [
        "catmark_car.obj",
        "catmark_gregory_test6.obj",
        "bilinear_cube.obj",
    ] {
        check_shape(&ctx, &shapes_dir().join(name), 3, None);
    }
}

#[test]
fn chunked_tables_give_the_same_result() {
    let Some(ctx) = context_or_skip("chunked_tables_give_the_same_result") else {
        return;
    };
    let limits = ChunkLimits {
        max_binding_bytes: 4096,
        max_workgroups_per_dimension: 2,
        max_stride: 3,
    };
    let path = shapes_dir().join("catmark_car.obj");
    let mesh = subsurf::io::read_path(&path).unwrap();
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    let gpu = GpuRefiner::with_limits(&ctx, &refiner, limits).unwrap();
    // Far more dispatches than the 3 per level of an unchunked upload.
    assert!(
        gpu.num_dispatches() > 20,
        "{} dispatches",
        gpu.num_dispatches()
    );
    let cpu = refiner.refine_positions(&mesh.positions);
    assert_close(
        "catmark_car chunked",
        &gpu.refine(&ctx, &mesh.positions).unwrap(),
        &cpu,
    );
}

/// Levels too large for the (forced) binding limit are refined from inputs gathered through
/// windows of the level buffers: every level, bit for bit the unsplit refinement.
#[test]
fn gathered_levels_match_whole_levels_bit_for_bit() {
    let Some(ctx) = context_or_skip("gathered_levels_match_whole_levels_bit_for_bit") else {
        return;
    };
    for (name, level, bytes) in [
        ("catmark_car.obj", 2, 8192),
        ("catmark_torus.obj", 3, 3072),
        ("catmark_pyramid_creases2.obj", 4, 4096),
    ] {
        let mesh = subsurf::io::read_path(shapes_dir().join(name)).unwrap();
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
        let limits = ChunkLimits {
            max_binding_bytes: bytes,
            max_workgroups_per_dimension: 4,
            max_stride: 3,
        };
        // The last level exceeds the limit.
        assert!(
            refiner.levels[level].num_vertices() * 12 > bytes as usize,
            "{name}"
        );
        let small = GpuRefiner::with_limits(&ctx, &refiner, limits).unwrap();
        let whole = GpuRefiner::new(&ctx, &refiner).unwrap();
        assert!(
            small.num_dispatches() > 3 * whole.num_dispatches(),
            "{name}"
        );
        small.update(&ctx, &mesh.positions).unwrap();
        whole.update(&ctx, &mesh.positions).unwrap();
        let cpu = refiner.refine_all(&mesh.positions);
        for l in 1..=level {
            let got = small.download_level(&ctx, l).unwrap();
            let want = whole.download_level(&ctx, l).unwrap();
            assert_eq!(
                bits(got.as_flattened()),
                bits(want.as_flattened()),
                "{name} level {l}: gathered vs whole"
            );
            assert_close(&format!("{name} level {l}"), &got, &cpu[l]);
        }
    }
}

#[test]
fn update_follows_a_deformation() {
    let Some(ctx) = context_or_skip("update_follows_a_deformation") else {
        return;
    };
    let mesh = subsurf::io::read_path(shapes_dir().join("catmark_gregory_test1.obj")).unwrap();
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 3).unwrap();
    let gpu = GpuRefiner::new(&ctx, &refiner).unwrap();
    for frame in 0..3 {
        let t = frame as f32 * 0.7;
        let moved: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|p| {
                [
                    p[0] + 0.3 * (t + p[1]).sin(),
                    p[1] * (1.0 + 0.1 * t),
                    p[2] - t,
                ]
            })
            .collect();
        gpu.update(&ctx, &moved).unwrap();
        let cpu = refiner.refine_positions(&moved);
        assert_close("deformed", &gpu.download(&ctx).unwrap(), &cpu);
        // Intermediate levels stay readable too.
        let l1 = refiner.refine_all(&moved);
        assert_close(
            "deformed level 1",
            &gpu.download_level(&ctx, 1).unwrap(),
            &l1[1],
        );
    }
    assert!(gpu.update(&ctx, &mesh.positions[1..]).is_err());
    assert!(gpu.download_level(&ctx, 4).is_err());
}

/// Read-backs through the context's kept staging buffer: a frame loop reading into one kept
/// buffer gets each frame's positions (not a stale copy), smaller reads after larger ones and
/// larger after smaller read exactly their own bytes, a released staging buffer is made
/// again, and a buffer of the wrong length is refused before any work.
#[test]
fn read_backs_into_kept_buffers_follow_every_frame() {
    let Some(ctx) = context_or_skip("read_backs_into_kept_buffers_follow_every_frame") else {
        return;
    };
    let mesh = subsurf::io::read_path(shapes_dir().join("catmark_car.obj")).unwrap();
    let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
    let gpu = GpuRefiner::new(&ctx, &refiner).unwrap();
    let mut kept = vec![[f32::NAN; 3]; refiner.last().num_vertices()];
    for frame in 0..3 {
        let moved: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|p| {
                [
                    p[0] + frame as f32,
                    p[1],
                    p[2] * (1.0 + 0.25 * frame as f32),
                ]
            })
            .collect();
        gpu.update(&ctx, &moved).unwrap();
        gpu.download_into(&ctx, &mut kept).unwrap();
        let all = refiner.refine_all(&moved);
        assert_close(&format!("frame {frame}"), &kept, &all[2]);
        // A smaller level through the larger staging buffer, then the larger one again.
        assert_close(
            &format!("frame {frame} level 1"),
            &gpu.download_level(&ctx, 1).unwrap(),
            &all[1],
        );
        assert_eq!(
            bits(gpu.download(&ctx).unwrap().as_flattened()),
            bits(kept.as_flattened())
        );
        if frame == 1 {
            ctx.release_staging();
        }
    }
    let mut short = vec![[0.0f32; 3]; kept.len() - 1];
    let err = gpu.download_into(&ctx, &mut short).unwrap_err();
    assert!(err.to_string().contains("floats"), "{err}");
}
