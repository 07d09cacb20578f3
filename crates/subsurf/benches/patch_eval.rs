//! Evaluations per second of the regular B-spline patch and of the single-crease patch at
//! sharpness 1..=10 (and fractional values): the crease evaluation's cost does not grow with
//! the sharpness (closed-form `Rp^s`, no per-level loop).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use subsurf::patch::{
    eval_bspline_patch, eval_gregory_patch, eval_single_crease_patch, GregoryDerivatives, PatchEdge,
};

const SAMPLES: usize = 32;

fn grid() -> [[f32; 3]; 16] {
    std::array::from_fn(|k| {
        let (i, j) = ((k % 4) as f32, (k / 4) as f32);
        [i, j, (0.7 * i).sin() * (1.3 * j).cos()]
    })
}

/// A uniform tessellation pattern over the patch.
fn params() -> Vec<(f32, f32)> {
    (0..SAMPLES * SAMPLES)
        .map(|k| {
            let a = (k % SAMPLES) as f32 / (SAMPLES - 1) as f32;
            let b = (k / SAMPLES) as f32 / (SAMPLES - 1) as f32;
            (a, b)
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let pts = grid();
    let uv = params();
    let mut g = c.benchmark_group("patch_eval");
    g.throughput(Throughput::Elements(uv.len() as u64));
    g.bench_function("bspline", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for &(u, v) in &uv {
                let e = eval_bspline_patch(black_box(&pts), u, v, 0);
                acc += e.p[2] + e.du[2];
            }
            acc
        })
    });
    // Uniform samples over the patch: the share of samples in the transition parts
    // shrinks like 2^-s, so this is the average cost of a tessellated patch.
    for s in [1.0f32, 2.0, 4.0, 6.0, 8.0, 10.0] {
        g.bench_with_input(BenchmarkId::new("single_crease_uniform", s), &s, |b, &s| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for &(u, v) in &uv {
                    let e = eval_single_crease_patch(black_box(&pts), u, v, PatchEdge::U1, s);
                    acc += e.p[2] + e.du[2];
                }
                acc
            })
        });
    }
    // Every sample inside the transition parts u > 1 - 2^-floor(s): the worst case, which
    // would grow with s if the cost depended on the number of crease levels.
    for s in [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 9.5] {
        let near: Vec<(f32, f32)> = uv
            .iter()
            .map(|&(u, v)| (1.0 - (1.0 - u) * (s.floor()).exp2().recip(), v))
            .collect();
        g.bench_with_input(
            BenchmarkId::new("single_crease_transition", s),
            &s,
            |b, &s| {
                b.iter(|| {
                    let mut acc = 0.0f32;
                    for &(u, v) in &near {
                        let e = eval_single_crease_patch(black_box(&pts), u, v, PatchEdge::U1, s);
                        acc += e.p[2] + e.du[2];
                    }
                    acc
                })
            },
        );
    }
    let greg: [[f32; 3]; 20] = std::array::from_fn(|k| [k as f32, (k * k) as f32, 1.0]);
    g.bench_function("gregory", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for &(u, v) in &uv {
                let e = eval_gregory_patch(black_box(&greg), u, v, GregoryDerivatives::Exact);
                acc += e.p[2] + e.du[2];
            }
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
