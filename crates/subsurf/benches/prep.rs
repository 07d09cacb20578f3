//! p-rep construction and N×N evaluation per patch (Myles, Yeo & Peters 2008, Table 1:
//! frames per second of construction + evaluation on an NVidia 8800 GTX; their Frog has
//! 1,292 faces, 40.9% of them B-quads).
//!
//! Mesh: three disjoint copies of `catmark_lefthanded` (OpenSubdiv regression shape, closed
//! quad mesh, valences 3–5): 1,302 faces, 47.9% B-quads, close to the Frog. f32, rayon on all
//! cores. One "frame" = recompute all coefficients for the current positions (vertex + patch
//! pass) + evaluate positions and unit normals on an N×N grid of every patch into buffers
//! reused from frame to frame; frames per second = 1 / median.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use subsurf::prep::{Grid, PrepPatches};
use subsurf::{Mesh, Topology};

/// `copies` disjoint translated copies of `catmark_lefthanded`.
fn bench_mesh(copies: usize) -> Mesh {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/prep/catmark_lefthanded.obj"
    );
    let base = subsurf::io::read_path(path).expect("bench mesh");
    let nv = base.positions.len() as u32;
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for c in 0..copies {
        let dx = c as f32; // the shape is 0.69 wide in x
        positions.extend(base.positions.iter().map(|p| [p[0] + dx, p[1], p[2]]));
        let mut start = 0usize;
        for &n in &base.face_counts {
            let f = &base.face_indices[start..start + n as usize];
            faces.push(f.iter().map(|&v| v + c as u32 * nv).collect());
            start += n as usize;
        }
    }
    Mesh::from_faces(positions, &faces)
}

fn prep(c: &mut Criterion) {
    let mesh = bench_mesh(3);
    let topo = Topology::new(&mesh).unwrap();
    let mut p = PrepPatches::<f32>::from_topology(&topo, &mesh.positions).unwrap();
    let nf = p.num_faces();
    let bq = nf - p.topology().perturbed_faces().len();
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
    let mut grid = Grid::default();
    for n in [5usize, 9, 17, 33] {
        g.bench_with_input(BenchmarkId::new("eval grid", n), &n, |b, &n| {
            b.iter(|| p.eval_grid_into(n, &mut grid))
        });
        g.bench_with_input(
            BenchmarkId::new("frame: update + eval grid", n),
            &n,
            |b, &n| {
                b.iter(|| {
                    p.update(&mesh.positions).unwrap();
                    p.eval_grid_into(n, &mut grid)
                })
            },
        );
    }
    g.bench_function("tessellate 9", |b| b.iter(|| p.tessellate(9)));
    g.finish();
}

criterion_group!(benches, prep);
criterion_main!(benches);
