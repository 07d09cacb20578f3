//! Face-varying (UV) refinement on catmark_car (which has UV seams): building the value
//! topology and stencils (`Refiner::fvar_refinement`) and applying them
//! (`FVarRefinement::refine`), for the smooth `CornersOnly` mode and the linear `All` mode,
//! next to the vertex refinement it runs on (`Refiner::new`).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::path::Path;
use subsurf::{FVarLinearInterpolation as Mode, Mesh, Refiner, Topology};

fn car() -> Mesh {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes/catmark_car.obj");
    subsurf::io::read_path(path).expect("catmark_car")
}

fn fvar(c: &mut Criterion) {
    let mesh = car();
    let uvs = mesh.uvs.clone().expect("catmark_car has UVs");
    let base = Topology::new(&mesh).unwrap();
    let mut g = c.benchmark_group("fvar/catmark_car");
    g.sample_size(10);
    for level in [3usize, 4] {
        let r = Refiner::new(base.clone(), level).unwrap();
        g.bench_with_input(
            BenchmarkId::new("vertex topology+plans", level),
            &level,
            |b, &l| b.iter(|| Refiner::new(base.clone(), l).unwrap()),
        );
        for (name, mode) in [("corners-only", Mode::CornersOnly), ("linear", Mode::All)] {
            g.bench_with_input(
                BenchmarkId::new(format!("{name} topology+stencils"), level),
                &level,
                |b, _| {
                    b.iter(|| {
                        r.fvar_refinement(&uvs.indices, uvs.values.len(), mode)
                            .unwrap()
                    })
                },
            );
            let f = r
                .fvar_refinement(&uvs.indices, uvs.values.len(), mode)
                .unwrap();
            g.bench_with_input(
                BenchmarkId::new(format!("{name} values"), level),
                &level,
                |b, _| b.iter(|| f.refine(&uvs.values).unwrap()),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, fvar);
criterion_main!(benches);
