//! Tutorial 7: the same surfaces on the GPU (wgpu compute), checked against the CPU.
//!
//! The CPU builds the tables once (stencils, patch tables: topology work); the GPU uploads
//! them and then only runs kernels over flat arrays, frame after frame, with the data left
//! on the device (OpenSubdiv's split of `Far` tables and `Osd` evaluators). Every kernel has
//! a CPU twin, so results agree to f32 rounding.
//!
//! Without a GPU adapter the program says so and exits successfully. `WGPU_BACKEND` picks
//! the wgpu backend (`vulkan`, `metal`, `dx12`, `gl`); Mesa's lavapipe is a CPU Vulkan driver
//! that works everywhere.
//!
//! `WGPU_BACKEND=vulkan cargo run -p subsurf-gpu --example tutorial_07_gpu`

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::surface::{build, Cpu, Method, SurfaceOptions};
use subsurf::{io, Refiner, Topology};
use subsurf_gpu::{GpuBackend, GpuError, GpuLimit, GpuRefiner};

fn max_diff(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs()))
        .fold(0.0, f32::max)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let gpu = match GpuBackend::new() {
        Ok(gpu) => gpu,
        Err(GpuError::NoAdapter { detail }) => {
            println!("tutorial_07_gpu: skipped, no GPU adapter ({detail})");
            return Ok(());
        }
        Err(e) => return Err(e.into()),
    };
    let ctx = &gpu.ctx;
    println!("adapter: {}", ctx.adapter_info().name);

    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/car.obj");
    let mesh = io::read_path(path)?;
    let topology = Topology::new(&mesh)?;

    // 1. Uniform refinement: the CPU refines the topology and makes the stencil tables, the
    // GPU uploads them once. Each frame writes new base positions and runs the kernels;
    // `update` leaves the result on the GPU (`output()` is a vertex buffer a renderer binds),
    // `download` reads it back.
    let refiner = Refiner::new(topology.clone(), 2)?;
    let gpu_refiner = GpuRefiner::new(ctx, &refiner)?;
    for frame in 0..3 {
        let lift = 0.05 * frame as f32;
        let moved: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|p| [p[0], p[1], p[2] + lift * p[0]])
            .collect();
        gpu_refiner.update(ctx, &moved)?;
        let on_gpu = gpu_refiner.download(ctx)?;
        let e = max_diff(&on_gpu, &refiner.refine_positions(&moved));
        println!(
            "frame {frame}: {} refined vertices, GPU - CPU within {e:.1e}",
            on_gpu.len()
        );
        assert!(e < 1e-4, "frame {frame}: {e}");
    }

    // 2. The limit surface: the patch table is built on the CPU and uploaded; the GPU makes
    // the patch points from base positions and evaluates the samples of the CPU's watertight
    // tessellation (so both have the same index buffer).
    let table = PatchTable::build(
        &topology,
        &PatchOptions {
            isolation_level: 3,
            ..Default::default()
        },
    )?;
    let cpu = LimitSurface::new(table.clone(), &mesh.positions).tessellate(5)?;
    let mut limit = GpuLimit::new(ctx, &table)?;
    limit.update(ctx, &mesh.positions)?;
    let tess = limit.tessellation(ctx, &table, 5)?;
    limit.eval(ctx, &tess.samples)?;
    let on_gpu = tess.download(ctx)?;
    assert_eq!(on_gpu.quads, cpu.quads);
    let e = max_diff(&on_gpu.positions, &cpu.positions);
    println!(
        "limit surface: {} samples, GPU - CPU within {e:.1e}",
        cpu.positions.len()
    );
    assert!(e < 1e-4);

    // 3. The one-call surface API with the GPU behind it: the same call as with `Cpu`.
    let options = SurfaceOptions {
        method: Method::Refine {
            level: 2,
            limit: true,
        },
        ..Default::default()
    };
    let (a, b) = (build(&mesh, &options, &gpu)?, build(&mesh, &options, &Cpu)?);
    assert_eq!(a.triangles, b.triangles);
    let e = max_diff(&a.positions, &b.positions);
    println!(
        "surface::build: {} triangles on GPU and CPU, within {e:.1e}",
        a.triangles.len()
    );
    assert!(e < 1e-4);
    Ok(())
}
