//! p-rep construction and N×N evaluation per patch (Myles, Yeo & Peters 2008, Table 1:
//! frames per second of construction + evaluation on an NVidia 8800 GTX).
//!
//! Mesh: `catmark_lefthanded` (OpenSubdiv regression shape, closed, valences 3–5) split once
//! into quads: 1,736 faces. f32, rayon on all cores. One "frame" = recompute all coefficients
//! for the current positions (vertex + patch pass) + evaluate positions and normals on an
//! N×N grid of every patch; frames per second = 1 / median.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use subsurf::prep::quadrangulate::quadrangulate;
use subsurf::prep::PrepPatches;
use subsurf::{Mesh, Topology};

fn bench_mesh() -> Mesh {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/prep/catmark_lefthanded.obj"
    );
    let base = subsurf::io::read_path(path).expect("bench mesh");
    quadrangulate(&base).expect("quadrangulate")
}

fn prep(c: &mut Criterion) {
    let mesh = bench_mesh();
    let topo = Topology::new(&mesh).unwrap();
    let mut p = PrepPatches::<f32>::from_topology(&topo, &mesh.positions).unwrap();
    let nf = p.num_faces();
    let bq = nf - p.topology.perturbed_faces.len();
    eprintln!(
        "bench mesh: {} vertices, {nf} faces, {:.1}% B-quads, {} threads",
        mesh.num_vertices(),
        100.0 * bq as f64 / nf as f64,
        rayon::current_num_threads()
    );
    let mut g = c.benchmark_group("prep");
    g.sample_size(20);
    g.measurement_time(std::time::Duration::from_secs(3));
    g.bench_function("construct (topology tables + passes)", |b| {
        b.iter(|| PrepPatches::<f32>::from_topology(&topo, &mesh.positions).unwrap())
    });
    g.bench_function("update (vertex + patch pass)", |b| {
        b.iter(|| p.update(&mesh.positions).unwrap())
    });
    for n in [5usize, 9, 17, 33] {
        g.bench_with_input(BenchmarkId::new("eval grid", n), &n, |b, &n| {
            b.iter(|| p.eval_grid(n))
        });
        g.bench_with_input(
            BenchmarkId::new("frame: update + eval grid", n),
            &n,
            |b, &n| {
                b.iter(|| {
                    p.update(&mesh.positions).unwrap();
                    p.eval_grid(n)
                })
            },
        );
    }
    g.bench_function("tessellate 9", |b| b.iter(|| p.tessellate(9)));
    g.finish();
}

criterion_group!(benches, prep);
criterion_main!(benches);
