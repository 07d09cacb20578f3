//! Throughput of `stencil_apply` (destination vertices per second): GPU kernel vs CPU twin.
//!
//! The table mimics one Catmull-Clark refinement level: 4 destination vertices per source
//! vertex, 4 to 9 entries per row referencing nearby source vertices. The GPU timing covers
//! the dispatch and waiting for it (data stays on the GPU, no read-back). `gathered source`
//! runs the same table with 256 KiB bindings, so that its source (750 KiB at 250,000 rows) is
//! gathered per chunk, window by window: the cost of a source past one binding.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use subsurf_gpu::cpu::stencil_apply::stencil_apply;
use subsurf_gpu::shared::StencilConfig;
use subsurf_gpu::{GpuContext, StencilKernel, VertexBuffer};

struct Table {
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f32>,
    sources: usize,
}

fn refinement_like_table(rows: usize) -> Table {
    let sources = rows.div_ceil(4);
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut offsets = vec![0u32];
    let (mut indices, mut weights) = (Vec::new(), Vec::new());
    for r in 0..rows {
        let len = 4 + (next() % 6) as usize;
        for _ in 0..len {
            let near = (r / 4) as i64 + (next() % 64) as i64 - 32;
            indices.push(near.rem_euclid(sources as i64) as u32);
            weights.push(1.0 / len as f32);
        }
        offsets.push(indices.len() as u32);
    }
    Table {
        offsets,
        indices,
        weights,
        sources,
    }
}

fn bench(c: &mut Criterion) {
    let ctx = match GpuContext::new() {
        Ok(ctx) => {
            println!("gpu_stencil: adapter = {}", ctx.adapter_info().name);
            Some(ctx)
        }
        Err(e) => {
            println!("gpu_stencil: SKIPPING GPU benches: {e}");
            None
        }
    };
    let stride = 3;
    let mut group = c.benchmark_group("stencil_apply");
    group.sample_size(20);
    for rows in [10_000usize, 250_000] {
        let t = refinement_like_table(rows);
        let src: Vec<f32> = (0..t.sources * stride).map(|i| (i % 97) as f32).collect();
        group.throughput(Throughput::Elements(rows as u64));
        let config = StencilConfig {
            row_count: rows as u32,
            stride: stride as u32,
            grid_width: rows as u32,
            relative: 0,
        };
        let mut dst = vec![0.0f32; rows * stride];
        group.bench_with_input(BenchmarkId::new("cpu_twin", rows), &rows, |b, _| {
            b.iter(|| stencil_apply(&config, &t.offsets, &t.indices, &t.weights, &src, &mut dst))
        });
        if let Some(ctx) = &ctx {
            let kernel =
                StencilKernel::new(ctx, &t.offsets, &t.indices, &t.weights).expect("table uploads");
            let src_buf = VertexBuffer::upload(ctx, &src, stride).expect("source uploads");
            let mut dst_buf = VertexBuffer::zeroed(ctx, rows, stride).expect("destination");
            let name = format!("gpu ({})", ctx.adapter_info().name);
            group.bench_with_input(BenchmarkId::new(name.clone(), rows), &rows, |b, _| {
                b.iter(|| {
                    kernel.apply(ctx, &src_buf, &mut dst_buf).expect("apply");
                    ctx.wait_idle().expect("wait");
                })
            });
            let table = subsurf_gpu::StencilTable::new(&t.offsets, &t.indices, &t.weights)
                .expect("valid table");
            let limits = subsurf_gpu::ChunkLimits {
                max_binding_bytes: 256 << 10,
                max_stride: stride,
                ..subsurf_gpu::ChunkLimits::from_context(ctx)
            };
            let split = StencilKernel::with_limits(ctx, &table, limits).expect("table uploads");
            if split.gathers_source() {
                let name = format!("{name}, gathered source");
                group.bench_with_input(BenchmarkId::new(name, rows), &rows, |b, _| {
                    b.iter(|| {
                        split.apply(ctx, &src_buf, &mut dst_buf).expect("apply");
                        ctx.wait_idle().expect("wait");
                    })
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
