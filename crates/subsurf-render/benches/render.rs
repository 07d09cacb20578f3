//! Time of one headless render (upload, draw with 4x MSAA, read back; no PNG encoding) of a
//! UV sphere of n·n triangles (n = 64, 256, 1024) at 800x600, on the adapter that
//! `subsurf_render::open` picks.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
#[path = "../tests/common/sphere.rs"]
mod sphere;
use sphere::sphere;
use subsurf_render::{render_with, RenderOptions};

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
