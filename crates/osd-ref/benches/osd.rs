//! OpenSubdiv's own timings on the regression shapes, as the baseline for subsurf's benches:
//! topology (build + uniform refinement), positions (PrimvarRefiner over every level),
//! stencils (factorized StencilTable update) and limit evaluation through the patch table.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use osd_ref::{eval_limit_grid, EndCap, OsdMesh, OsdRefiner, OsdStencils};

#[path = "../tests/common/mod.rs"]
mod common;

const SHAPES: [&str; 2] = ["catmark_car", "catmark_pawn"];
const LEVEL: usize = 3;

fn uniform(c: &mut Criterion) {
    if !osd_ref::available() {
        eprintln!("!!!!! OpenSubdiv not installed: osd-ref benches SKIPPED !!!!!");
        return;
    }
    let mut g = c.benchmark_group("osd_uniform");
    for name in SHAPES {
        let mesh = common::load_shape(name);
        let osd = OsdMesh::from(&mesh);
        let id = format!("{name}/L{LEVEL}");
        g.bench_function(BenchmarkId::new("topology", &id), |b| {
            b.iter(|| OsdRefiner::new(&osd, LEVEL).unwrap())
        });
        let refiner = OsdRefiner::new(&osd, LEVEL).unwrap();
        let mut out = vec![[0.0f32; 3]; refiner.num_vertices(LEVEL)];
        g.bench_function(BenchmarkId::new("positions", &id), |b| {
            b.iter(|| refiner.interpolate_into(&mesh.positions, &mut out).unwrap())
        });
        let stencils = OsdStencils::new(&refiner).unwrap();
        g.bench_function(BenchmarkId::new("stencils", &id), |b| {
            b.iter(|| stencils.update_into(&mesh.positions, &mut out).unwrap())
        });
    }
    g.finish();
}

fn limit(c: &mut Criterion) {
    if !osd_ref::available() {
        return;
    }
    let mut g = c.benchmark_group("osd_limit");
    g.sample_size(10);
    for name in SHAPES {
        let mesh = common::load_shape(name);
        let osd = OsdMesh::from(&mesh);
        // Build + evaluate: adaptive refinement, patch table, 8x8 samples per ptex face.
        g.bench_function(BenchmarkId::new("grid8_iso4", name), |b| {
            b.iter(|| eval_limit_grid(&osd, 8, 4, false, EndCap::Gregory).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, uniform, limit);
criterion_main!(benches);
