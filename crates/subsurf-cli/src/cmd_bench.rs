//! `subsurf bench`: time the refinement stages on a mesh (medians of repeated runs), on the
//! CPU or on the GPU the machine has.

use crate::common::{gpu_context, option_parser, Backend, SchemeArgs};
use anyhow::Context as _;
use std::path::PathBuf;
use std::time::Instant;
use subsurf::{Refiner, Topology};

/// Time topology refinement, stencil application and the whole pipeline.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Input mesh: .obj (with OpenSubdiv's tags), .ply, .gltf or .glb; `-` reads OBJ, PLY or GLB
    /// from standard input.
    pub input: PathBuf,
    /// Refinement level.
    #[arg(short, long, default_value_t = 3)]
    pub level: usize,
    /// Repetitions (the median is printed).
    #[arg(short, long, default_value_t = 7)]
    pub runs: usize,
    #[command(flatten)]
    pub scheme: SchemeArgs,
    /// Where refinement runs: `gpu` times the upload of the stencil tables, refinement with
    /// the data resident on the GPU, and refinement plus read-back.
    #[arg(long, value_parser = option_parser::<Backend>(), default_value_t = Backend::Cpu)]
    pub backend: Backend,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

pub fn run(a: &BenchArgs) -> anyhow::Result<()> {
    let mesh = a.scheme.read(&a.input)?;
    let base = Topology::new(&mesh)?;
    let runs = a.runs.max(1);
    let mut topo = Vec::new();
    let mut refiner = None;
    for _ in 0..runs {
        let t = Instant::now();
        let r = Refiner::new(base.clone(), a.level)?;
        topo.push(t.elapsed().as_secs_f64() * 1e3);
        refiner = Some(r);
    }
    let refiner = refiner.ok_or_else(|| anyhow::anyhow!("no run"))?;
    if a.backend == Backend::Gpu {
        return run_gpu(a, &mesh.positions, &refiner, median(topo));
    }
    let mut pos = Vec::new();
    let mut verts = 0;
    for _ in 0..runs {
        let t = Instant::now();
        let p = refiner.refine_positions(&mesh.positions);
        pos.push(t.elapsed().as_secs_f64() * 1e3);
        verts = p.len();
    }
    println!(
        "{}: level {} -> {} vertices, {} threads: topology+plans {:.2} ms, positions {:.2} ms (medians of {runs})",
        a.input.display(),
        a.level,
        verts,
        rayon::current_num_threads(),
        median(topo),
        median(pos)
    );
    Ok(())
}

/// Median milliseconds of `runs` calls of `f`, after one warm-up call.
fn time_ms(runs: usize, mut f: impl FnMut() -> anyhow::Result<()>) -> anyhow::Result<f64> {
    f()?;
    let mut v = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t = Instant::now();
        f()?;
        v.push(t.elapsed().as_secs_f64() * 1e3);
    }
    Ok(median(v))
}

fn run_gpu(
    a: &BenchArgs,
    base: &[[f32; 3]],
    refiner: &Refiner,
    topo_ms: f64,
) -> anyhow::Result<()> {
    let ctx = gpu_context()?;
    let t = Instant::now();
    let gpu = subsurf_gpu::GpuRefiner::new(&ctx, refiner).context("--backend gpu: uploading")?;
    ctx.wait_idle()?;
    let upload = t.elapsed().as_secs_f64() * 1e3;
    let runs = a.runs.max(1);
    let resident = time_ms(runs, || {
        gpu.update(&ctx, base)?;
        Ok(ctx.wait_idle()?)
    })?;
    // A frame loop's read-back: into one kept buffer (the context keeps its staging buffer).
    let mut out = vec![[0.0f32; 3]; gpu.num_output_vertices()];
    let readback = time_ms(runs, || {
        gpu.update(&ctx, base)?;
        Ok(gpu.download_into(&ctx, &mut out)?)
    })?;
    let verts = gpu.num_output_vertices();
    println!(
        "{}: level {} -> {verts} vertices on {}: topology+plans (CPU) {topo_ms:.2} ms, stencils + upload {upload:.2} ms, \
         positions resident {resident:.3} ms ({:.1} M vertices/s), with read-back {readback:.3} ms (medians of {runs})",
        a.input.display(),
        a.level,
        ctx.adapter_info().name,
        verts as f64 / resident / 1e3
    );
    Ok(())
}
