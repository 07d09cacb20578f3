//! Face-varying (UV) refinement on the GPU against `Refiner::refine_uvs`, in every
//! `FVarLinearInterpolation` mode, unchunked and with forced chunks.

mod common;

use common::context_or_skip;
use subsurf::{FVarLinearInterpolation as Mode, Refiner, Topology};
use subsurf_gpu::{ChunkLimits, GpuUvRefiner};

fn shapes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

const MODES: [Mode; 6] = [
    Mode::None,
    Mode::CornersOnly,
    Mode::CornersPlus1,
    Mode::CornersPlus2,
    Mode::Boundaries,
    Mode::All,
];

#[test]
fn gpu_uvs_match_cpu_in_every_mode() {
    let Some(ctx) = context_or_skip("gpu_uvs_match_cpu_in_every_mode") else {
        return;
    };
    let small = ChunkLimits {
        max_binding_bytes: 1 << 12,
        max_workgroups_per_dimension: 1,
        max_stride: 2,
    };
    for name in [
        "catmark_fvar_bound0",
        "catmark_fvar_bound1",
        "catmark_fvar_project0",
    ] {
        let mesh = subsurf::io::read_path(shapes_dir().join(format!("{name}.obj"))).unwrap();
        let uvs = mesh.uvs.clone().expect("shape has UVs");
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 3).unwrap();
        for mode in MODES {
            let want = refiner.refine_uvs(&uvs, mode).unwrap().pop().unwrap();
            let fvar = refiner
                .fvar_refinement(&uvs.indices, uvs.values.len(), mode)
                .unwrap();
            for (what, limits) in [
                ("unchunked", ChunkLimits::from_context(&ctx)),
                ("chunked", small),
            ] {
                let mut gpu = GpuUvRefiner::with_limits(&ctx, &fvar, limits).unwrap();
                if what == "chunked" {
                    assert!(
                        gpu.num_dispatches() > 2 * gpu.max_level(),
                        "{name}: not chunked"
                    );
                }
                let got = gpu.refine(&ctx, &uvs.values).unwrap();
                assert_eq!(got.indices, want.indices, "{name} {mode:?} {what}: indices");
                assert_eq!(got.values.len(), want.values.len());
                // Convex-ish combinations of UVs in [0, 1]: f32 rounding of short sums.
                for (i, (g, w)) in got.values.iter().zip(&want.values).enumerate() {
                    for k in 0..2 {
                        assert!(
                            (g[k] - w[k]).abs() <= 1e-5,
                            "{name} {mode:?} {what}: value {i}: GPU {g:?} vs CPU {w:?}"
                        );
                    }
                }
            }
        }
    }
}
