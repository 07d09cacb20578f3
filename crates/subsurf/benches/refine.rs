//! Uniform refinement: topology + stencils (`Refiner::new`, and with a lean last level), one-shot
//! topology + positions (`refine_once`, lean last level) and positions only
//! (`refine_positions`), on catmark_car (levels 3–5) and a generated 512×512 torus (262k quads).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::path::Path;
use subsurf::refine::refine_once;
use subsurf::{shapes, Mesh, RefineOptions, Refiner, Topology};

fn car() -> Mesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes/catmark_car.obj");
    subsurf::io::read_path(path).expect("catmark_car")
}

fn bench_mesh(c: &mut Criterion, name: &str, mesh: &Mesh, levels: &[usize]) {
    let base = Topology::new(mesh).unwrap();
    let mut g = c.benchmark_group(format!("refine/{name}"));
    g.sample_size(10);
    for &level in levels {
        g.bench_with_input(
            BenchmarkId::new("topology+plans", level),
            &level,
            |b, &l| b.iter(|| Refiner::new(base.clone(), l).unwrap()),
        );
        g.bench_with_input(
            BenchmarkId::new("topology+plans lean", level),
            &level,
            |b, &l| {
                b.iter(|| Refiner::with_options(base.clone(), l, RefineOptions::lean()).unwrap())
            },
        );
        g.bench_with_input(BenchmarkId::new("once lean", level), &level, |b, &l| {
            b.iter(|| refine_once(base.clone(), l, &mesh.positions, RefineOptions::lean()).unwrap())
        });
        let r = Refiner::new(base.clone(), level).unwrap();
        g.bench_with_input(BenchmarkId::new("positions", level), &level, |b, _| {
            b.iter(|| r.refine_positions(&mesh.positions))
        });
    }
    g.finish();
}

fn refine(c: &mut Criterion) {
    bench_mesh(c, "catmark_car", &car(), &[3, 4, 5]);
    bench_mesh(c, "torus512", &shapes::torus(512, 512, 2.0, 0.5), &[1, 2]);
}

criterion_group!(benches, refine);
criterion_main!(benches);
