//! Building the topology tables of a 1,000 × 1,000 quad torus (1 M quads, 2 M edges).

use criterion::{criterion_group, criterion_main, Criterion};
use subsurf::{shapes, Topology};

fn topology(c: &mut Criterion) {
    let mesh = shapes::torus(1000, 1000, 2.0, 0.5);
    let mut g = c.benchmark_group("topology");
    g.sample_size(10);
    g.bench_function("torus_1M_quads", |b| {
        b.iter(|| Topology::new(&mesh).unwrap())
    });
    g.finish();
}

criterion_group!(benches, topology);
criterion_main!(benches);
