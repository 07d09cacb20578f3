//! Loop refinement on the GPU: the `refine_level` kernel over Loop stencil tables (no face
//! points, an empty face table) against its CPU twin and against the library within 1e-5 of
//! the bounding-box diagonal, on every `loop_*` regression shape; and the limit stencils
//! through the stencil kernel.
//!
//! Kernel against twin: each level's twin reads the GPU's own parent level, so the two differ
//! by one step's rounding at most. A software adapter (lavapipe) evaluates `acc += w * x` as
//! written and matches the twin bit for bit; a hardware driver may fuse it into one `fma`
//! (WGSL allows the contraction; NVIDIA's Vulkan driver does it), so there each value is held
//! to the dot product's rounding bound instead: two evaluations of `sum_j w_j x_j` over `n`
//! terms, in any order, fused or not, differ by at most `2 n u sum_j |w_j x_j|` (Higham 2002,
//! section 3.1; `u` the unit roundoff).

mod common;

use common::{bits, context_or_skip};
use subsurf::refine::LevelStencils;
use subsurf::{Refiner, Topology};
use subsurf_gpu::cpu::refine_level::refine_level_step;
use subsurf_gpu::{GpuRefiner, StencilKernel};

/// Per child value, twice the rounding bound of its row: `2 (n + 1) eps sum_j |w_j x_j|`
/// (`eps` = 2u, so a factor 2 of slack for the bound's own f32 evaluation), formed by the twin
/// itself on `|w|` and `|x|` and, for the row lengths `n`, on unit weights and values.
fn rounding_bound(s: &LevelStencils, parent: &[f32]) -> Vec<f32> {
    let with = |f: &dyn Fn(f32) -> f32| s.map_weights(|&w| f(w));
    let abs: Vec<f32> = parent.iter().map(|x| x.abs()).collect();
    let magnitude = refine_level_step(&with(&f32::abs), &abs, 3).unwrap();
    let lengths = refine_level_step(&with(&|_| 1.0), &vec![1.0; parent.len()], 3).unwrap();
    magnitude
        .iter()
        .zip(&lengths)
        .map(|(m, n)| 2.0 * (n + 1.0) * f32::EPSILON * m)
        .collect()
}

/// The kernel's level against the twin's from the same parent: bit for bit on a software
/// adapter, within the rounding bound everywhere (see the module documentation).
fn assert_twin(what: &str, exact: bool, s: &LevelStencils, parent: &[f32], got: &[f32]) {
    let twin = refine_level_step(s, parent, 3).unwrap();
    if exact {
        assert_eq!(bits(got), bits(&twin), "{what}: GPU vs its CPU twin");
    }
    let bound = rounding_bound(s, parent);
    for (i, ((g, t), b)) in got.iter().zip(&twin).zip(&bound).enumerate() {
        assert!(
            (g - t).abs() <= *b,
            "{what}: value {i}: GPU {g} vs twin {t}, beyond the rounding bound {b}"
        );
    }
}

fn shapes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

fn assert_close(name: &str, gpu: &[[f32; 3]], cpu: &[[f32; 3]]) {
    assert_eq!(gpu.len(), cpu.len(), "{name}: vertex count");
    let tol = 1e-5 * (subsurf::mesh::bbox_diagonal(cpu) as f64).max(f64::MIN_POSITIVE);
    for (i, (g, c)) in gpu.iter().zip(cpu).enumerate() {
        for k in 0..3 {
            let d = (g[k] as f64 - c[k] as f64).abs();
            assert!(d <= tol, "{name}: vertex {i} GPU {g:?} vs CPU {c:?}");
        }
    }
}

#[test]
fn loop_shapes_refine_on_the_gpu_as_on_the_cpu() {
    let Some(ctx) = context_or_skip("loop_shapes_refine_on_the_gpu_as_on_the_cpu") else {
        return;
    };
    let exact = ctx.adapter_info().device_type == wgpu::DeviceType::Cpu;
    let paths = subsurf::shapes::regression_shapes(&shapes_dir(), &["loop_"]).unwrap();
    assert!(paths.len() >= 31, "loop shapes found: {}", paths.len());
    for path in &paths {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let mesh = subsurf::io::read_path(path).unwrap();
        let level = 2;
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
        let cpu = refiner.refine_all(&mesh.positions);
        let gpu = GpuRefiner::new(&ctx, &refiner).unwrap();
        gpu.update(&ctx, &mesh.positions).unwrap();
        // The CPU twin of the kernel, level by level, from the GPU's parent level.
        let mut parent: Vec<f32> = mesh.positions.as_flattened().to_vec();
        for (l, s) in refiner.stencils().iter().enumerate() {
            let got = gpu.download_level(&ctx, l + 1).unwrap();
            let what = format!("{name} level {}", l + 1);
            assert_twin(&what, exact, s, &parent, got.as_flattened());
            assert_close(&what, &got, &cpu[l + 1]);
            parent = got.as_flattened().to_vec();
        }
        // Limit stencils applied by the stencil kernel.
        let limit = StencilKernel::apply_once(&ctx, refiner.limit_table(), gpu.output()).unwrap();
        let limit: Vec<[f32; 3]> = limit.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        assert_close(
            &format!("{name} limit"),
            &limit,
            &refiner.limit(&cpu[level]),
        );
    }
}
