//! Rate policies: how the per-edge rates of a [`super::mesh::plan`] are chosen.
//!
//! - [`RatePolicy::Uniform`]: one rate everywhere (`--tess N` is rate `N − 1`);
//! - [`RatePolicy::MaxEdgeLength`]: no output edge longer than `L` world units along the
//!   limit surface;
//! - [`RatePolicy::Tolerance`]: chordal error — every output edge's midpoint and facet's
//!   centroid within `E ×` the bounding-box diagonal of the limit surface;
//! - [`RatePolicy::Screen`]: no edge longer than `P` pixels under a camera's
//!   world-to-clip matrix;
//! - [`RatePolicy::Explicit`]: rates given directly (see [`parse_edge_rates`]).
//!
//! Lengths and curvatures are measured on the limit surface itself: each base edge's limit
//! curve is evaluated at [`CURVE_SAMPLES`]` + 1` points from one of its faces (in parallel,
//! rayon). A chord of parameter length `h` over a curve with second derivative `p''`
//! deviates from it by about `|p''| h² / 8`, so the tolerance policy takes
//! `R = ⌈√(max |p''| / (8 E'))⌉` with `E'` the tolerance in world units over a safety factor
//! of 2; the length policies take the fastest stretch of the curve (length per unit
//! parameter) over the length allowed, `/√2` for diagonals. A face's interior rate is chosen
//! the same way from its isolines, and raises its edges to at least `1/GRADING` of it.

use rayon::prelude::*;

use super::mesh::{check_samples, graded, EdgeRates, GRADING, MAX_RATE};
use crate::error::{Result, TessError};
use crate::limit::patch_map::EMPTY;
use crate::limit::LimitSurface;
use crate::topology::Topology;

/// Points per base edge (plus one) at which lengths and curvatures are measured.
pub const CURVE_SAMPLES: usize = 16;

/// A camera for [`RatePolicy::Screen`]: the world-to-clip matrix (column-major, as
/// `subsurf-render`'s `Camera::view_proj`) and the image size in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenCamera {
    /// World-to-clip matrix, column-major (`m[column][row]`).
    pub view_proj: [[f32; 4]; 4],
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl ScreenCamera {
    /// Pixel coordinates of `p`, or `None` behind the eye.
    pub fn project(&self, p: [f32; 3]) -> Option<[f32; 2]> {
        let m = &self.view_proj;
        let c: [f32; 4] =
            [0, 1, 2, 3].map(|r| m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r]);
        if c[3] <= 1e-12 {
            return None;
        }
        let (x, y) = (c[0] / c[3], c[1] / c[3]);
        Some([
            (x * 0.5 + 0.5) * self.width as f32,
            (0.5 - y * 0.5) * self.height as f32,
        ])
    }
}

/// How rates are chosen (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub enum RatePolicy {
    /// The same rate on every edge.
    Uniform(u32),
    /// Longest output edge, world units.
    MaxEdgeLength(f32),
    /// Chordal error as a fraction of the bounding-box diagonal.
    Tolerance(f32),
    /// Longest output edge in pixels under a camera.
    Screen {
        /// The camera.
        camera: ScreenCamera,
        /// Longest edge, pixels.
        pixels: f32,
    },
    /// Rates given directly.
    Explicit(EdgeRates),
}

fn positive(value: f32, what: &'static str, origin: &str) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(TessError::NotPositive {
            origin: origin.to_string(),
            what,
            value: value.into(),
        }
        .into())
    }
}

impl RatePolicy {
    /// The screen policy from optional flags: `--pixels` without a camera is refused.
    pub fn screen(camera: Option<ScreenCamera>, pixels: f32, origin: &str) -> Result<RatePolicy> {
        positive(pixels, "pixels", origin)?;
        let camera = camera.ok_or_else(|| TessError::NoCamera {
            origin: origin.to_string(),
        })?;
        Ok(RatePolicy::Screen { camera, pixels })
    }

    /// Checks the policy's values before any work; `origin` names where they came from.
    pub fn validate(&self, t: &Topology, origin: &str) -> Result<()> {
        match self {
            RatePolicy::Uniform(r) => EdgeRates::uniform(t, *r).validate(t, origin),
            RatePolicy::MaxEdgeLength(l) => positive(*l, "maximum edge length", origin),
            RatePolicy::Tolerance(e) => positive(*e, "tolerance", origin),
            RatePolicy::Screen { pixels, .. } => positive(*pixels, "pixels", origin),
            RatePolicy::Explicit(r) => r.validate(t, origin),
        }
    }

    /// The rates of `surface` under this policy (checked first, see [`Self::validate`]).
    pub fn rates(&self, surface: &LimitSurface, origin: &str) -> Result<EdgeRates> {
        let t = &surface.table.base;
        self.validate(t, origin)?;
        let out = match self {
            RatePolicy::Uniform(r) => EdgeRates::uniform(t, *r),
            RatePolicy::Explicit(r) => r.clone(),
            RatePolicy::MaxEdgeLength(l) => {
                // Parameter-uniform samples: the fastest stretch of a curve sets its rate;
                // diagonals and transition edges are up to √2 longer than the grid's.
                let l = f64::from(*l) / std::f64::consts::SQRT_2;
                curve_rates(surface, origin, |c| (max_speed(c, Some) / l).ceil())?
            }
            RatePolicy::Screen { camera, pixels } => {
                let px = f64::from(*pixels) / std::f64::consts::SQRT_2;
                let project = |p| camera.project(p).map(|q| [q[0], q[1], 0.0]);
                // Close-ups past the highest rate are held at it.
                let mut r = curve_rates(surface, origin, |c| {
                    (max_speed(c, project) / px).ceil().min(f64::from(MAX_RATE))
                })?;
                r.faces.iter_mut().for_each(|f| *f = (*f).min(MAX_RATE));
                r
            }
            RatePolicy::Tolerance(e) => {
                let diag = f64::from(crate::mesh::bbox_diagonal(&surface.points));
                let tol = f64::from(*e) * diag / 2.0; // safety factor 2
                curve_rates(surface, origin, |c| {
                    chord_rate(max_second_derivative(c), tol)
                })?
            }
        };
        Ok(out)
    }
}

/// Rates from real-valued needs, refusing those above [`MAX_RATE`] (naming the edge).
fn to_rates(t: &Topology, need: &[f64], origin: &str) -> Result<Vec<u32>> {
    need.iter()
        .enumerate()
        .map(|(e, &n)| {
            if n > f64::from(MAX_RATE) {
                let [v0, v1] = t.edge_verts[e];
                Err(TessError::RateOutOfRange {
                    origin: origin.to_string(),
                    v0,
                    v1,
                    rate: n.min(u64::MAX as f64) as u64,
                }
                .into())
            } else {
                Ok(n.max(1.0) as u32)
            }
        })
        .collect()
}

/// The largest length per unit parameter of the curve's segments, after `map`.
fn max_speed(points: &[[f32; 3]], map: impl Fn([f32; 3]) -> Option<[f32; 3]>) -> f64 {
    let mapped: Vec<_> = points.iter().map(|&p| map(p)).collect();
    let steps = (points.len().max(2) - 1) as f64;
    mapped
        .windows(2)
        .map(|w| match (w[0], w[1]) {
            (Some(a), Some(b)) => {
                (0..3)
                    .map(|k| f64::from(b[k] - a[k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
                    * steps
            }
            _ => 0.0,
        })
        .fold(0.0, f64::max)
}

/// The `(ptex, u, v)` of the point at `t` (from the edge's first vertex) along base edge
/// `e`, seen from its first live face; `None` when all its faces are holes.
fn edge_point(s: &LimitSurface, e: usize, t: f32) -> Option<(usize, f32, f32)> {
    let topo = &s.table.base;
    let (faces, locals) = (topo.edge_faces(e), topo.edge_faces_local(e));
    let (f, k) = faces
        .iter()
        .zip(locals)
        .map(|(&f, &k)| (f as usize, k as usize))
        .find(|&(f, _)| !topo.face_is_hole[f])?;
    let n = topo.face_size(f);
    // Along the face's edge k, from its corner k.
    let forward = topo.edge_verts[e][0] == topo.face_vertices(f)[k];
    let t = if forward { t } else { 1.0 - t };
    let first = s.table.ptex_offsets[f] as usize;
    let (ptex, u, v) = if n == 4 {
        let (u, v) = match k {
            0 => (t, 0.0),
            1 => (1.0, t),
            2 => (1.0 - t, 1.0),
            _ => (0.0, 1.0 - t),
        };
        (first, u, v)
    } else if t <= 0.5 {
        (first + k, 2.0 * t, 0.0)
    } else {
        (first + (k + 1) % n, 0.0, 2.0 - 2.0 * t)
    };
    (s.table.patch_map.roots[ptex] != EMPTY).then_some((ptex, u, v))
}

/// Every base edge's limit curve at `CURVE_SAMPLES + 1` points (empty for edges of holes).
fn edge_curves(s: &LimitSurface) -> Vec<Vec<[f32; 3]>> {
    (0..s.table.base.num_edges())
        .into_par_iter()
        .map(|e| {
            (0..=CURVE_SAMPLES)
                .filter_map(|i| {
                    let (f, u, v) = edge_point(s, e, i as f32 / CURVE_SAMPLES as f32)?;
                    s.eval_position(f, u, v)
                })
                .collect()
        })
        .collect()
}

/// Largest second derivative (per unit parameter squared) along evenly spaced samples.
fn max_second_derivative(c: &[[f32; 3]]) -> f64 {
    let h = 1.0 / (c.len().max(2) - 1) as f64;
    c.windows(3)
        .map(|w| {
            (0..3)
                .map(|k| {
                    (f64::from(w[0][k]) - 2.0 * f64::from(w[1][k]) + f64::from(w[2][k])).powi(2)
                })
                .sum::<f64>()
                .sqrt()
                / (h * h)
        })
        .fold(0.0, f64::max)
}

/// The rate whose chords of a curve with second derivative `d2` stay within `tol`.
fn chord_rate(d2: f64, tol: f64) -> f64 {
    (d2 / (8.0 * tol)).sqrt().ceil()
}

/// Rates from the rate `need` of each curve (a base edge's limit curve, or an isoline of a
/// face): edges from their curves, faces from their isolines at `u, v = ¼, ½, ¾`, and every
/// edge at least `1/GRADING` of its faces' interior rate so that the graded interior reaches
/// it.
fn curve_rates(
    s: &LimitSurface,
    origin: &str,
    need_of: impl Fn(&[[f32; 3]]) -> f64 + Sync,
) -> Result<EdgeRates> {
    let t = &s.table.base;
    let curves = edge_curves(s);
    let mut need: Vec<f64> = curves.par_iter().map(|c| need_of(c)).collect();
    // Interiors: the isolines through the middle of every ptex face, both directions.
    let face_need: Vec<f64> = (0..t.num_faces())
        .into_par_iter()
        .map(|f| {
            if t.face_is_hole[f] {
                return 0.0;
            }
            let (first, last) = (
                s.table.ptex_offsets[f] as usize,
                s.table.ptex_offsets[f + 1] as usize,
            );
            let mut worst = 0.0f64; // the largest need of the face's isolines
            let mut line = Vec::with_capacity(CURVE_SAMPLES + 1);
            for ptex in first..last {
                for dir in 0..2 {
                    for &c in &[0.25f32, 0.5, 0.75] {
                        // One buffer per face, no allocation per line.
                        line.clear();
                        line.extend((0..=CURVE_SAMPLES).filter_map(|i| {
                            let a = i as f32 / CURVE_SAMPLES as f32;
                            let (u, v) = if dir == 0 { (a, c) } else { (c, a) };
                            s.eval_position(ptex, u, v)
                        }));
                        worst = worst.max(need_of(&line));
                    }
                }
            }
            // A sub-face spans half the face: its rate counts for half as many samples.
            let scale = if last - first == 1 { 1.0 } else { 0.5 };
            (worst * scale).ceil()
        })
        .collect();
    for f in 0..t.num_faces() {
        let n = t.face_size(f);
        let per_edge = face_need[f] * if n == 4 { 1.0 } else { 2.0 } / f64::from(GRADING);
        for &ed in t.face_edges(f) {
            need[ed as usize] = need[ed as usize].max(per_edge.ceil());
        }
    }
    check_samples(estimate(s, &need, &face_need))?;
    let edges = to_rates(t, &need, origin)?;
    let faces = (0..t.num_faces())
        .map(|f| {
            let fe = t.face_edges(f);
            let derived = if fe.len() == 4 {
                let least = fe.iter().map(|&e| edges[e as usize]).min().unwrap_or(1);
                let r = |i: usize| edges[fe[i] as usize];
                graded(r(0), r(2), least).min(graded(r(1), r(3), least))
            } else {
                1
            };
            // The interior is as fine as its finest need: its isolines' or (a derived rate
            // being a mean) its finest edge's.
            let finest_edge = fe.iter().map(|&e| edges[e as usize]).max().unwrap_or(1);
            let finest_edge = if fe.len() == 4 {
                finest_edge
            } else {
                finest_edge.div_ceil(2)
            };
            let want = (face_need[f].min(f64::from(MAX_RATE)) as u32).max(finest_edge);
            if want > derived {
                want
            } else {
                0
            }
        })
        .collect();
    Ok(EdgeRates { edges, faces })
}

/// The samples of a tessellation at the real-valued needs (before they are checked against
/// [`MAX_RATE`]): every edge's, and per ptex face the square of its finest need, so that a
/// policy asking for too much is refused with the estimate before anything is built.
fn estimate(s: &LimitSurface, need: &[f64], face_need: &[f64]) -> u64 {
    let t = &s.table.base;
    let mut samples: f64 = need.iter().sum();
    for f in 0..t.num_faces() {
        if t.face_is_hole[f] {
            continue;
        }
        let fe = t.face_edges(f);
        let finest = fe.iter().map(|&e| need[e as usize]).fold(0.0, f64::max);
        let (ptex, r) = if fe.len() == 4 {
            (1.0, finest.max(face_need[f]))
        } else {
            (fe.len() as f64, (finest / 2.0).max(face_need[f]))
        };
        samples += ptex * r * r;
    }
    samples.min(u64::MAX as f64) as u64
}

/// Reads `--edge-rates` text: one `v0 v1 rate` per line (0-based vertex indices of a base
/// edge; `#` starts a comment), unlisted edges taking `default`. `file` names the source in
/// errors, which carry the line.
pub fn parse_edge_rates(text: &str, file: &str, t: &Topology, default: u32) -> Result<EdgeRates> {
    let mut rates = EdgeRates::uniform(t, default);
    for (i, line) in text.lines().enumerate() {
        let origin = format!("{file}:{}", i + 1);
        let body = line.split('#').next().unwrap_or("").trim();
        if body.is_empty() {
            continue;
        }
        let fields: Vec<&str> = body.split_whitespace().collect();
        let bad = |reason: String| TessError::BadLine {
            origin: origin.clone(),
            reason,
        };
        if fields.len() != 3 {
            return Err(bad(format!("expected `v0 v1 rate`, found {body:?}")).into());
        }
        let num = |s: &str, what: &str| {
            s.parse::<u64>()
                .map_err(|_| bad(format!("{what} {s:?} is not a non-negative integer")))
        };
        let (v0, v1, rate) = (
            num(fields[0], "vertex")?,
            num(fields[1], "vertex")?,
            num(fields[2], "rate")?,
        );
        set_edge_rate(&mut rates, t, &origin, [v0, v1], rate)?;
    }
    Ok(rates)
}

/// Sets the rate of the base edge `v0–v1` of `t` (either direction) to `rate`; an edge that
/// does not exist or a rate outside `1..=4096` is an error naming `origin`.
pub fn set_edge_rate(
    rates: &mut EdgeRates,
    t: &Topology,
    origin: &str,
    [v0, v1]: [u64; 2],
    rate: u64,
) -> Result<()> {
    let edge = (v0 < t.num_vertices() as u64 && v1 < t.num_vertices() as u64)
        .then(|| t.find_edge(v0 as u32, v1 as u32))
        .flatten()
        .ok_or(TessError::NoSuchEdge {
            origin: origin.to_string(),
            v0,
            v1,
        })?;
    if !(1..=u64::from(MAX_RATE)).contains(&rate) {
        return Err(TessError::RateOutOfRange {
            origin: origin.to_string(),
            v0: v0 as u32,
            v1: v1 as u32,
            rate,
        }
        .into());
    }
    rates.edges[edge as usize] = rate as u32;
    Ok(())
}
