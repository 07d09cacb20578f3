//! Loop refinement on the GPU: the `refine_level` kernel over Loop stencil tables (no face
//! points, an empty face table) against its CPU twin bit for bit and against the library
//! within 1e-5 of the bounding-box diagonal, on every `loop_*` regression shape; and the
//! limit stencils through the stencil kernel.

mod common;

use common::{bits, context_or_skip};
use subsurf::{Refiner, Topology};
use subsurf_gpu::{GpuRefiner, StencilKernel};

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
        // The CPU twin of the kernel, level by level.
        let mut twin: Vec<f32> = mesh.positions.as_flattened().to_vec();
        for (l, s) in refiner.stencils.iter().enumerate() {
            twin = subsurf_gpu::cpu::refine_level::refine_level_step(s, &twin, 3).unwrap();
            let got = gpu.download_level(&ctx, l + 1).unwrap();
            assert_eq!(
                bits(got.as_flattened()),
                bits(&twin),
                "{name} level {}: GPU vs its CPU twin",
                l + 1
            );
            assert_close(&format!("{name} level {}", l + 1), &got, &cpu[l + 1]);
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
