//! Limit surface of `catmark_car`: patch table construction (sparse feature-adaptive
//! refinement to the isolation level), evaluation of 10⁴ scattered samples in
//! parallel, and watertight tessellation with 9 samples per ptex side.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::Topology;

fn car() -> subsurf::Mesh {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../testdata/shapes/catmark_car.obj"
    );
    subsurf::io::read_path(path).expect("catmark_car")
}

fn bench(c: &mut Criterion) {
    let mesh = car();
    let topo = Topology::new(&mesh).unwrap();
    let mut g = c.benchmark_group("limit_car");
    g.sample_size(10);
    g.bench_function("build_table_iso4", |b| {
        b.iter(|| PatchTable::build(black_box(&topo), &PatchOptions::default()).unwrap())
    });
    let iso10 = PatchOptions {
        isolation_level: 10,
        ..Default::default()
    };
    g.bench_function("build_table_iso10", |b| {
        b.iter(|| PatchTable::build(black_box(&topo), &iso10).unwrap())
    });
    let table = PatchTable::build(&topo, &PatchOptions::default()).unwrap();
    g.bench_function("points", |b| {
        b.iter(|| table.points(black_box(&mesh.positions)))
    });
    let s = LimitSurface::new(table, &mesh.positions);
    let n = s.table().num_ptex_faces() as u32;
    let queries: Vec<(u32, f32, f32)> = (0..10_000u32)
        .map(|k| {
            let h = k.wrapping_mul(2654435761);
            (
                h % n,
                (h >> 8 & 1023) as f32 / 1023.0,
                (h >> 18 & 1023) as f32 / 1023.0,
            )
        })
        .collect();
    g.throughput(Throughput::Elements(queries.len() as u64));
    g.bench_function("eval_batch_10k", |b| {
        b.iter(|| s.eval_batch(black_box(&queries)))
    });
    g.throughput(Throughput::Elements(s.table().num_ptex_faces() as u64 * 81));
    g.bench_function("tessellate_9", |b| {
        b.iter(|| s.tessellate(black_box(9)).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
