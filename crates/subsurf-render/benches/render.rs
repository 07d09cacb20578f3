//! Time of one headless render (upload, draw with 4x MSAA, read back; no PNG encoding) of a
//! UV sphere with 2·n·n/2 triangles at 800x600, on the adapter `subsurf_render::open` picks.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::f32::consts::PI;
use subsurf_render::{render_with, RenderMesh, RenderOptions};

fn sphere(n: usize) -> RenderMesh {
    let m = n / 2;
    let mut positions = vec![];
    for i in 0..=m {
        let th = PI * i as f32 / m as f32;
        for j in 0..n {
            let ph = 2.0 * PI * j as f32 / n as f32;
            positions.push([th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()]);
        }
    }
    let mut indices = vec![];
    for i in 0..m {
        for j in 0..n {
            let a = (i * n + j) as u32;
            let b = (i * n + (j + 1) % n) as u32;
            let (c, d) = (a + n as u32, b + n as u32);
            indices.extend_from_slice(&[a, b, c, b, d, c]);
        }
    }
    RenderMesh {
        normals: positions.clone(),
        positions,
        indices,
        ..Default::default()
    }
}

fn bench(c: &mut Criterion) {
    let gpu = match subsurf_render::open() {
        Ok(g) => g,
        Err(e) => {
            eprintln!("*** SKIPPED render bench: {e} ***");
            return;
        }
    };
    let mut g = c.benchmark_group("render_800x600");
    g.sample_size(10);
    let o = RenderOptions::default();
    for n in [64usize, 256, 1024] {
        let mesh = sphere(n);
        g.throughput(Throughput::Elements(mesh.num_triangles() as u64));
        g.bench_with_input(
            BenchmarkId::from_parameter(mesh.num_triangles()),
            &mesh,
            |b, m| b.iter(|| render_with(&gpu, m, &o).unwrap()),
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
