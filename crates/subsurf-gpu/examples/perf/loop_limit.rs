//! Loop limit-surface tessellation on the GPU against the CPU, as medians of repeated runs:
//! a `loop_*` shape (default `loop_pole360`, 1,080 triangles around a valence-360 vertex) at
//! an isolation level, the watertight tessellation of `segments` per base edge.
//!
//! CPU = `LoopLimit::tessellate` (f64); GPU = `GpuLoopLimit::tessellate` (plan, patch lookup
//! and query packing on the host, upload, `loop_eval`, read-back) and `eval` + read-back of
//! an uploaded sample set. Every line names the adapter.
//!
//! ```text
//! cargo run --release -p subsurf-gpu --example loop_limit [-- SHAPE ISOLATION SEGMENTS]
//! ```

use std::time::Instant;
use subsurf::limit::tri_tessellation_plan;
use subsurf::limit::LoopLimit;
use subsurf::Topology;
use subsurf_gpu::loop_limit::plan_queries;
use subsurf_gpu::{GpuContext, GpuLoopLimit};

fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shape = args.first().map_or("loop_pole360", String::as_str);
    let isolation: u32 = args.get(1).map_or(Ok(3), |s| s.parse())?;
    let segments: usize = args.get(2).map_or(Ok(16), |s| s.parse())?;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../testdata/shapes")
        .join(format!("{shape}.obj"));
    let mesh = subsurf::io::read_path(&path)?;
    let topo = Topology::new(&mesh)?;
    let limit = LoopLimit::new(&topo, &mesh.positions, isolation)?;
    let regular = limit.patches.iter().filter(|p| p.regular).count();
    let plan = tri_tessellation_plan(&topo, segments)?;
    let samples = plan.samples.iter().filter(|s| s.is_some()).count();
    println!(
        "{shape}: {} faces, isolation {isolation}: {regular} box-spline and {} end-cap patches; \
         {segments} segments per edge: {samples} samples",
        topo.num_faces(),
        limit.patches.len() - regular
    );
    let runs = 5;
    let cpu = median_ms(runs, || {
        std::hint::black_box(limit.tessellate(&topo, segments).unwrap());
    });
    println!("CPU LoopLimit::tessellate (f64): {cpu:.2} ms");
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(e) => {
            println!("no GPU: {e}");
            return Ok(());
        }
    };
    let adapter = ctx.adapter_info().name.clone();
    let start = Instant::now();
    let gpu = GpuLoopLimit::new(&ctx, &limit)?;
    println!(
        "[{adapter}] GpuLoopLimit::new (tables, pipeline): {:.2} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    let tess = median_ms(runs, || {
        std::hint::black_box(gpu.tessellate(&ctx, &limit, &topo, segments).unwrap());
    });
    println!("[{adapter}] GpuLoopLimit::tessellate (plan, upload, eval, read-back): {tess:.2} ms");
    let queries = plan_queries(&limit, &plan)?;
    let set = gpu.samples(&ctx, &queries, false)?;
    let eval = median_ms(runs, || {
        gpu.eval(&ctx, &set).unwrap();
        std::hint::black_box(set.download(&ctx).unwrap());
    });
    println!(
        "[{adapter}] eval + read-back: {eval:.2} ms ({:.1} M samples/s)",
        samples as f64 / eval / 1e3
    );
    Ok(())
}
