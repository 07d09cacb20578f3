//! `subsurf::patch` bases against OpenSubdiv's own limit evaluation (`Far::PatchTable`
//! after feature-adaptive refinement):
//!
//! - regular interior, boundary and corner patches of a quad grid: OpenSubdiv evaluates them
//!   with its phantom-point boundary weights, ours must give the same surface;
//! - a semi-sharp crease line (integer and fractional sharpness): OpenSubdiv, without single-
//!   crease patches, isolates the crease until its sharpness has decayed, so its patches are
//!   exact; the direct single-crease evaluation (Nießner, Loop & Greiner 2012) must match.

#[macro_use]
mod common;

use osd_ref::{eval_limit_grid_with, EndCap, LimitSample, OsdBoundary, OsdMesh, PatchOptions};
use subsurf::patch::{
    eval_bspline_patch, eval_single_crease_patch, PatchEdge, BOUNDARY_U0, BOUNDARY_U1, BOUNDARY_V0,
    BOUNDARY_V1,
};

/// A jittered `n × n` quad grid: vertex `(x, y)` has index `y (n+1) + x`, face `(x, y)` has
/// index `y n + x` and corners `(x,y), (x+1,y), (x+1,y+1), (x,y+1)` (so the ptex `u` runs
/// along `x` and `v` along `y`).
struct Grid {
    n: usize,
    pos: Vec<[f32; 3]>,
    counts: Vec<u32>,
    indices: Vec<u32>,
}

fn grid(n: usize, seed: u64) -> Grid {
    let mut state = seed;
    let mut rnd = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as f64 / (1u64 << 31) as f64 - 0.5) as f32
    };
    let mut pos = Vec::new();
    for y in 0..=n {
        for x in 0..=n {
            pos.push([x as f32 + 0.3 * rnd(), y as f32 + 0.3 * rnd(), rnd()]);
        }
    }
    let w = (n + 1) as u32;
    let mut indices = Vec::new();
    for y in 0..n as u32 {
        for x in 0..n as u32 {
            indices.extend([
                y * w + x,
                y * w + x + 1,
                (y + 1) * w + x + 1,
                (y + 1) * w + x,
            ]);
        }
    }
    Grid {
        n,
        pos,
        counts: vec![4; n * n],
        indices,
    }
}

impl Grid {
    fn vertex(&self, x: i64, y: i64) -> u32 {
        let c = |a: i64| a.clamp(0, self.n as i64) as u32;
        c(y) * (self.n as u32 + 1) + c(x)
    }

    /// The 16 patch points of face `(fx, fy)` in subsurf's order (index `4 j + i`, `i`
    /// along `u`); points beyond the grid are clamped (they are phantom points whose value
    /// the boundary weights ignore).
    fn patch_points(&self, fx: usize, fy: usize) -> [[f64; 3]; 16] {
        std::array::from_fn(|k| {
            let (i, j) = ((k % 4) as i64, (k / 4) as i64);
            let p = self.pos[self.vertex(fx as i64 - 1 + i, fy as i64 - 1 + j) as usize];
            [p[0] as f64, p[1] as f64, p[2] as f64]
        })
    }

    fn boundary_mask(&self, fx: usize, fy: usize) -> u8 {
        let mut m = 0;
        if fy == 0 {
            m |= BOUNDARY_V0;
        }
        if fx == self.n - 1 {
            m |= BOUNDARY_U1;
        }
        if fy == self.n - 1 {
            m |= BOUNDARY_V1;
        }
        if fx == 0 {
            m |= BOUNDARY_U0;
        }
        m
    }
}

fn deviation(s: &LimitSample, p: [f64; 3], du: [f64; 3], dv: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| {
            (p[k] - s.p[k] as f64)
                .abs()
                .max((du[k] - s.du[k] as f64).abs())
                .max((dv[k] - s.dv[k] as f64).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn regular_boundary_and_corner_patches_match_opensubdiv() {
    require_osd!();
    let g = grid(3, 17);
    let mut mesh = OsdMesh::new(&g.pos, &g.counts, &g.indices);
    // Valence-2 corners are sharp corners, so the corner faces are regular corner patches.
    mesh.options.boundary = OsdBoundary::EdgeAndCorner;
    let o = PatchOptions {
        isolation_level: 3,
        ..Default::default()
    };
    let samples = eval_limit_grid_with(&mesh, 9, &o).unwrap();
    assert_eq!(samples.len(), 9 * 81);
    let mut worst = 0.0f64;
    for s in &samples {
        let (fx, fy) = (s.face as usize % 3, s.face as usize / 3);
        let e = eval_bspline_patch(
            &g.patch_points(fx, fy),
            s.u as f64,
            s.v as f64,
            g.boundary_mask(fx, fy),
        );
        worst = worst.max(deviation(s, e.p, e.du, e.dv));
    }
    assert!(worst < 1e-5, "largest deviation from OpenSubdiv: {worst}");
}

#[test]
fn single_crease_patches_match_opensubdiv_adaptive_refinement() {
    require_osd!();
    let g = grid(6, 29);
    let w = 7u32;
    for transposed in [false, true] {
        // A crease line through the whole grid at x = 3 (or y = 3).
        let line: Vec<(u32, u32)> = (0..6u32)
            .map(|t| {
                if transposed {
                    (3 * w + t, 3 * w + t + 1)
                } else {
                    (t * w + 3, (t + 1) * w + 3)
                }
            })
            .collect();
        for sharpness in [0.5f32, 1.0, 1.5, 2.0, 2.7, 3.25] {
            let creases: Vec<(u32, u32, f32)> =
                line.iter().map(|&(a, b)| (a, b, sharpness)).collect();
            let mut mesh = OsdMesh::new(&g.pos, &g.counts, &g.indices);
            mesh.creases = creases.into();
            let o = PatchOptions {
                isolation_level: sharpness.ceil() as u32 + 2,
                use_single_crease: false,
                ..Default::default()
            };
            let samples = eval_limit_grid_with(&mesh, 9, &o).unwrap();
            let mut worst = 0.0f64;
            let mut compared = 0;
            for s in &samples {
                let (fx, fy) = (s.face as usize % 6, s.face as usize / 6);
                // Faces beside the crease whose 4×4 points are all interior.
                let (across, along) = if transposed { (fy, fx) } else { (fx, fy) };
                if !(2..=3).contains(&across) || !(2..=3).contains(&along) {
                    continue;
                }
                let edge = match (transposed, across) {
                    (false, 2) => PatchEdge::U1,
                    (false, _) => PatchEdge::U0,
                    (true, 2) => PatchEdge::V1,
                    (true, _) => PatchEdge::V0,
                };
                let e = eval_single_crease_patch(
                    &g.patch_points(fx, fy),
                    s.u as f64,
                    s.v as f64,
                    edge,
                    sharpness as f64,
                );
                worst = worst.max(deviation(s, e.p, e.du, e.dv));
                compared += 1;
            }
            assert_eq!(compared, 4 * 81);
            assert!(
                worst < 2e-5,
                "sharpness {sharpness}, transposed {transposed}: deviation {worst}"
            );
        }
    }
}

/// The check has teeth: the smooth patch (sharpness ignored) is far from OpenSubdiv here.
#[test]
fn smooth_patch_differs_from_creased_opensubdiv() {
    require_osd!();
    let g = grid(6, 29);
    let creases: Vec<(u32, u32, f32)> = (0..6u32)
        .map(|t| (t * 7 + 3, (t + 1) * 7 + 3, 2.0))
        .collect();
    let mut mesh = OsdMesh::new(&g.pos, &g.counts, &g.indices);
    mesh.creases = creases.into();
    let o = PatchOptions {
        isolation_level: 4,
        end_cap: EndCap::Gregory,
        ..Default::default()
    };
    let samples = eval_limit_grid_with(&mesh, 9, &o).unwrap();
    let s = samples
        .iter()
        .find(|s| s.face == 2 * 6 + 2 && s.u == 1.0 && s.v == 0.5)
        .unwrap();
    let e = eval_bspline_patch(&g.patch_points(2, 2), 1.0, 0.5, 0);
    assert!(deviation(s, e.p, e.du, e.dv) > 1e-2);
}
