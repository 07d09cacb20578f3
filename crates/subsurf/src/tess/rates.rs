//! Rate policies: how the per-edge rates of a [`super::mesh::plan`] are chosen.
//!
//! - [`RatePolicy::Uniform`]: one rate everywhere (`--tess N` is rate `N − 1`);
//! - [`RatePolicy::MaxEdgeLength`]: no output edge longer than `L` world units along the
//!   limit surface;
//! - [`RatePolicy::Tolerance`]: chordal error — every output triangle, measured across along
//!   its normal, within `E ×` the bounding-box diagonal of the limit surface;
//! - [`RatePolicy::Screen`]: no edge longer than `P` pixels under a camera's
//!   world-to-clip matrix;
//! - [`RatePolicy::Explicit`]: rates given directly (see [`parse_edge_rates`]).
//!
//! Lengths and curvatures are measured on the limit surface itself, along the rate curves of
//! [`super::curves`]: each base edge's limit curve and each ptex face's isolines, evaluated
//! at [`CURVE_SAMPLES`]` + 1` points (on the CPU in parallel, rayon, or on the GPU through
//! `subsurf-gpu`'s `GpuRates`; both end in [`RatePolicy::rates_from_measures`]). A chord of
//! parameter length `h` over a curve with second derivative `p''` deviates from it by about
//! `|p''| h² / 8`, so the tolerance policy takes
//! `R = ⌈√(max |p''| / (8 E'))⌉` with `E'` the tolerance in world units (no safety factor:
//! the triangles are checked afterwards, [`super::tessellate_within_tolerance`]); the length policies take the fastest stretch of the curve (length per unit
//! parameter) over the length allowed, `/√2` for diagonals. A face's interior rate is chosen
//! the same way from its isolines, and raises its edges to at least `1/GRADING` of it.

use super::curves::{CurveMeasure, RateCurves};
use super::mesh::{check_samples, graded, EdgeRates, GRADING, MAX_RATE};
use crate::error::{Result, TessError};
use crate::limit::{LimitSurface, PatchTable};
use crate::topology::Topology;

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
    #[inline]
    pub fn project(&self, p: [f32; 3]) -> Option<[f32; 2]> {
        let m = &self.view_proj;
        // Row `r` of the clip coordinates, `m[0][r] p0 + m[1][r] p1 + m[2][r] p2 + m[3][r]`
        // (written out: the array adaptor was not inlined in the measure's loop).
        let row = |r: usize| m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r];
        let w = row(3);
        if w <= 1e-12 {
            return None;
        }
        let (x, y) = (row(0) / w, row(1) / w);
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

    /// What this policy measures its rate curves for; `None` for rates that need no
    /// measurement (uniform, explicit).
    pub fn measure(&self) -> Option<CurveMeasure> {
        match self {
            RatePolicy::Uniform(_) | RatePolicy::Explicit(_) => None,
            RatePolicy::MaxEdgeLength(_) => Some(CurveMeasure::Speed),
            RatePolicy::Tolerance(_) => Some(CurveMeasure::SecondDerivative),
            RatePolicy::Screen { camera, .. } => Some(CurveMeasure::ScreenSpeed(*camera)),
        }
    }

    /// The rates of `surface` under this policy (checked first, see [`Self::validate`]), its
    /// rate curves measured on the CPU.
    pub fn rates(&self, surface: &LimitSurface, origin: &str) -> Result<EdgeRates> {
        self.validate(&surface.table.base, origin)?;
        let none = RateCurves::default();
        let (curves, measures) = match self.measure() {
            Some(m) => {
                // Laid out once per table and kept with it.
                let curves: &RateCurves = surface.table.rate_curves();
                (curves, curves.measure(surface, &m))
            }
            None => (&none, Vec::new()),
        };
        let diagonal = crate::mesh::bbox_diagonal(&surface.points);
        self.rates_from_measures(&surface.table, diagonal, curves, &measures, origin)
    }

    /// The rates of a surface whose rate curves `curves` ([`RateCurves::new`] of `table`)
    /// measured `measures` under [`Self::measure`] (on the CPU, [`RateCurves::measure`], or on
    /// a GPU); `diagonal` is the bounding-box diagonal of its points, which a tolerance is
    /// relative to. Checked first ([`Self::validate`]); uniform and explicit rates ignore the
    /// curves. Refuses a measure list of the wrong length, and rates past [`MAX_RATE`] or a
    /// tessellation past the memory limit, naming `origin`.
    pub fn rates_from_measures(
        &self,
        table: &PatchTable,
        diagonal: f32,
        curves: &RateCurves,
        measures: &[f64],
        origin: &str,
    ) -> Result<EdgeRates> {
        let t = &table.base;
        self.validate(t, origin)?;
        // A curve's need from its measure and the policy's scale.
        let (need_of, scale): (fn(f64, f64) -> f64, f64) = match self {
            RatePolicy::Uniform(r) => return Ok(EdgeRates::uniform(t, *r)),
            RatePolicy::Explicit(r) => return Ok(r.clone()),
            // Parameter-uniform samples: the fastest stretch of a curve sets its rate;
            // diagonals and transition edges are up to √2 longer than the grid's.
            RatePolicy::MaxEdgeLength(l) => (
                |speed, l| (speed / l).ceil(),
                f64::from(*l) / std::f64::consts::SQRT_2,
            ),
            // Close-ups past the highest rate are held at it.
            RatePolicy::Screen { pixels, .. } => (
                |speed, px| (speed / px).ceil().min(f64::from(MAX_RATE)),
                f64::from(*pixels) / std::f64::consts::SQRT_2,
            ),
            RatePolicy::Tolerance(e) => (chord_rate, f64::from(*e) * f64::from(diagonal)),
        };
        if curves.num_curves() != measures.len()
            || curves.num_edges != t.num_edges()
            || curves.face_curves.len() != t.num_faces() + 1
        {
            return Err(TessError::MeasureMismatch {
                origin: origin.to_string(),
                expected: curves.num_curves(),
                found: measures.len(),
            }
            .into());
        }
        // Each curve's need (dead curves measure zero).
        let needs: Vec<f64> = measures
            .iter()
            .zip(&curves.live)
            .map(|(&m, &live)| need_of(if live { m } else { 0.0 }, scale))
            .collect();
        let mut r = curve_rates(table, curves, &needs, origin)?;
        if matches!(self, RatePolicy::Screen { .. }) {
            r.faces.iter_mut().for_each(|f| *f = (*f).min(MAX_RATE));
        }
        Ok(r)
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

/// The rate whose chords of a curve with second derivative `d2` stay within `tol`.
fn chord_rate(d2: f64, tol: f64) -> f64 {
    (d2 / (8.0 * tol)).sqrt().ceil()
}

/// Rates from the rate need of each curve: edges from their curves, faces from their isolines
/// at `u, v = ¼, ½, ¾`, and every edge at least `1/GRADING` of its faces' interior rate so
/// that the graded interior reaches it.
fn curve_rates(
    table: &PatchTable,
    curves: &RateCurves,
    needs: &[f64],
    origin: &str,
) -> Result<EdgeRates> {
    let t = &table.base;
    let mut need: Vec<f64> = needs[..t.num_edges()].to_vec();
    // Interiors: the largest need of a face's isolines, both directions.
    let face_need: Vec<f64> = (0..t.num_faces())
        .map(|f| {
            if t.face_is_hole[f] {
                return 0.0;
            }
            let lines = curves.face_curves[f] as usize..curves.face_curves[f + 1] as usize;
            let worst = needs[lines].iter().fold(0.0f64, |a, &b| a.max(b));
            // A sub-face spans half the face: its rate counts for half as many samples.
            let ptex = table.ptex_offsets[f + 1] - table.ptex_offsets[f];
            let scale = if ptex == 1 { 1.0 } else { 0.5 };
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
    check_samples(estimate(t, &need, &face_need))?;
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
fn estimate(t: &Topology, need: &[f64], face_need: &[f64]) -> f64 {
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
    samples
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
