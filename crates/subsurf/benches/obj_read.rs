//! OBJ reading speed on the largest regression shape with tags and UVs (catmark_car:
//! 1642 vertices, 1575 quads, 314 creases, face-varying UVs), plus writing it back.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use subsurf::io::obj;

fn car_text() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../testdata/shapes/catmark_car.obj"
    );
    std::fs::read_to_string(path).expect("testdata/shapes/catmark_car.obj")
}

fn bench_obj(c: &mut Criterion) {
    let text = car_text();
    let mut g = c.benchmark_group("obj");
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.bench_function("read catmark_car", |b| {
        b.iter(|| obj::read(black_box(&text)).unwrap())
    });
    let mesh = obj::read(&text).unwrap();
    g.bench_function("write catmark_car", |b| {
        b.iter(|| {
            let mut out = Vec::with_capacity(text.len());
            obj::write(black_box(&mesh), &mut out).unwrap();
            out
        })
    });
    g.finish();
}

criterion_group!(benches, bench_obj);
criterion_main!(benches);
