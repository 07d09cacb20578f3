//! Read-back throughput of a vertex buffer, as a frame loop sees it: the first read of a
//! session (a fresh staging buffer, a new output `Vec`: `release_staging` + `download`) against
//! the steady state (the context's kept staging buffer, one kept output buffer:
//! `download_into`). Medians of repeated reads, in GB/s, for buffers of 1, 16 and 128 MiB.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p subsurf-gpu --example readback [-- RUNS]`

use std::time::Instant;

use subsurf_gpu::{GpuContext, VertexBuffer};

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let runs: usize = std::env::args().nth(1).map_or(Ok(15), |s| s.parse())?;
    let ctx = GpuContext::new()?;
    println!("adapter: {}", ctx.adapter_info().name);
    for mib in [1usize, 16, 128] {
        let floats = (mib << 20) / 4;
        let data: Vec<f32> = (0..floats).map(|i| i as f32).collect();
        let buf = VertexBuffer::upload(&ctx, &data, 1)?;
        ctx.wait_idle()?;
        let (mut fresh, mut kept) = (Vec::new(), Vec::new());
        let mut out = vec![0.0f32; floats];
        for _ in 0..runs {
            ctx.release_staging();
            let t = Instant::now();
            let v = buf.download(&ctx)?;
            fresh.push(t.elapsed().as_secs_f64());
            assert_eq!(v[floats - 1], data[floats - 1]);
            let t = Instant::now();
            buf.download_into(&ctx, &mut out)?;
            kept.push(t.elapsed().as_secs_f64());
            assert_eq!(out[floats / 2], data[floats / 2]);
        }
        let gbs = |s: f64| (mib << 20) as f64 / s / 1e9;
        let (f, k) = (median(&mut fresh), median(&mut kept));
        println!(
            "{mib:4} MiB: fresh staging + new Vec {:8.3} ms ({:5.2} GB/s) | kept staging + kept buffer {:8.3} ms ({:5.2} GB/s) | {:.2}x",
            f * 1e3,
            gbs(f),
            k * 1e3,
            gbs(k),
            f / k
        );
    }
    Ok(())
}
