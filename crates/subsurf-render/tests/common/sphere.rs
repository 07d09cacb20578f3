//! A UV sphere for the renderer's tests and benches.

use std::f32::consts::PI;
use subsurf_render::RenderMesh;

/// UV sphere of radius 1 at the origin, poles on Y; `n` segments around (even).
pub fn sphere(n: usize) -> RenderMesh {
    let m = n / 2;
    let mut positions = vec![];
    for i in 0..=m {
        let th = PI * i as f32 / m as f32;
        for j in 0..n {
            let ph = 2.0 * PI * j as f32 / n as f32;
            positions.push([th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()]);
        }
    }
    let mut indices = vec![];
    for i in 0..m {
        for j in 0..n {
            let a = (i * n + j) as u32;
            let b = (i * n + (j + 1) % n) as u32;
            let (c, d) = (a + n as u32, b + n as u32);
            // Counter-clockwise seen from outside.
            indices.extend_from_slice(&[a, b, c, b, d, c]);
        }
    }
    RenderMesh {
        normals: positions.clone(),
        positions,
        indices,
        ..Default::default()
    }
}
