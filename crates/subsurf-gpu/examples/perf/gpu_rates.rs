//! Screen-space tessellation rates chosen again every frame of a camera orbit, on the GPU
//! (`GpuRates`: the rate curves evaluated by `limit_eval`, measured by `rate_measure`, the
//! rates formed on the CPU from one float per curve) and on the CPU (`RatePolicy::rates`), with
//! the share of edges where the two differ. Prints the median time per frame of each.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p subsurf-gpu --example gpu_rates [-- FILE FRAMES
//! PIXELS]` (default `testdata/shapes/catmark_car.obj`, 24 frames, 4 pixels per edge).

mod common;
use std::time::Instant;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::tess::{RatePolicy, ScreenCamera};
use subsurf::Topology;
use subsurf_gpu::{GpuContext, GpuLimit, GpuRates};

/// A perspective camera (60 degrees, 4:3) at angle `a` around the box centre `c`, `r` away.
fn orbit(c: [f32; 3], r: f32, a: f32) -> ScreenCamera {
    let eye = [c[0] + r * a.sin(), c[1] + 0.3 * r, c[2] + r * a.cos()];
    let f: [f32; 3] = std::array::from_fn(|k| c[k] - eye[k]);
    let norm = |v: [f32; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|x| x / l)
    };
    let cross = |a: [f32; 3], b: [f32; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let f = norm(f);
    let s = norm(cross(f, [0.0, 1.0, 0.0]));
    let u = cross(s, f);
    let (t, aspect, near, far) = (
        1.0 / 30f32.to_radians().tan(),
        4.0 / 3.0,
        0.01 * r,
        10.0 * r,
    );
    let (pa, pb) = ((far + near) / (near - far), 2.0 * far * near / (near - far));
    // Projection times view, column-major.
    let view = |row: [f32; 3], k: usize| if k < 3 { row[k] } else { -dot(row, eye) };
    let col = |k: usize| {
        [
            t / aspect * view(s, k),
            t * view(u, k),
            -pa * view(f, k) + if k == 3 { pb } else { 0.0 },
            view(f, k),
        ]
    };
    ScreenCamera {
        view_proj: [col(0), col(1), col(2), col(3)],
        width: 800,
        height: 600,
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let frames: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(24);
    let pixels: f32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(4.0);
    let mesh = subsurf::io::read_path(path)?;
    let table = PatchTable::build(&Topology::new(&mesh)?, &PatchOptions::default())?;
    let surface = LimitSurface::new(table.clone(), &mesh.positions);
    let ctx = GpuContext::new()?;
    println!("{}: {}", path, ctx.gpu_info());
    let mut limit = GpuLimit::new(&ctx, &table)?;
    limit.update(&ctx, &mesh.positions)?;
    let rates = GpuRates::new(&ctx, &limit, &table)?;
    let diagonal = subsurf::mesh::bbox_diagonal(&mesh.positions);
    let (lo, hi) = subsurf::mesh::bounding_box(&mesh.positions).ok_or("empty mesh")?;
    let centre: [f32; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let (mut gpu_ms, mut cpu_ms, mut differ, mut edges) = (Vec::new(), Vec::new(), 0, 0);
    for i in 0..=frames {
        let camera = orbit(centre, 1.2 * diagonal, i as f32 * 0.26);
        let policy = RatePolicy::Screen { camera, pixels };
        let t = Instant::now();
        let gpu = rates.rates(&ctx, &limit, &table, &policy, diagonal, "--pixels")?;
        let g = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let cpu = policy.rates(&surface, "--pixels")?;
        let c = t.elapsed().as_secs_f64() * 1e3;
        if i > 0 {
            // Frame 0 warms the pipelines up.
            gpu_ms.push(g);
            cpu_ms.push(c);
        }
        differ += gpu
            .edges
            .iter()
            .zip(&cpu.edges)
            .filter(|(a, b)| a != b)
            .count();
        edges += cpu.edges.len();
        if i % 6 == 0 {
            println!(
                "frame {i}: edge rates {}..={}",
                cpu.edges.iter().min().unwrap_or(&0),
                cpu.edges.iter().max().unwrap_or(&0)
            );
        }
    }
    println!(
        "{} rate curves; per frame (median of {frames}): GPU rates {:.2} ms, CPU rates {:.2} ms; \
         edges where they differ: {differ} of {edges}",
        rates.curves().num_curves(),
        common::median(&mut gpu_ms),
        common::median(&mut cpu_ms),
    );
    Ok(())
}
