//! The rate curves of a limit surface: where the rate policies of [`super::rates`] measure it.
//!
//! A policy looks at curves on the limit surface, each sampled at [`CURVE_POINTS`] evenly
//! spaced parameters: the limit curve of every base edge (seen from its first face that is
//! not a hole), then, face by face, the isolines through every ptex face of the face at
//! `u = ¼, ½, ¾` and `v = ¼, ½, ¾` ([`ISOLINES`]). [`RateCurves`] lays those samples out
//! as one flat list of `(ptex, u, v)` queries, [`CURVE_POINTS`] per curve, so that any
//! evaluator can measure them: [`RateCurves::measure`] on the CPU, or the GPU's limit
//! evaluation followed by its `rate_measure` kernel (`subsurf-gpu`). Each curve is reduced to
//! one number, its [`CurveMeasure`]; [`super::RatePolicy::rates_from_measures`] turns the
//! numbers into rates.

use rayon::prelude::*;

use super::rates::ScreenCamera;
use crate::limit::curve_eval::CurveCache;
pub use crate::limit::rate_curves::{
    RateCurves, CURVE_POINTS, CURVE_SAMPLES, ISOLINES, ISOLINES_PER_PTEX,
};
use crate::limit::LimitSurface;

/// What a curve's samples are reduced to (the largest over its segments).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CurveMeasure {
    /// Second derivative per unit parameter squared, from second differences (chordal
    /// tolerance).
    SecondDerivative,
    /// Length per unit parameter, from chords (maximum edge length).
    Speed,
    /// Length per unit parameter in pixels under a camera; a chord with an end behind the
    /// eye counts zero (screen space).
    ScreenSpeed(ScreenCamera),
}

impl RateCurves {
    /// Every curve measured on the CPU, from `surface`'s positions (in parallel, rayon, in
    /// chunks of curves walked by plain loops).
    pub fn measure(&self, surface: &LimitSurface, m: &CurveMeasure) -> Vec<f64> {
        /// Curves per parallel chunk.
        const CHUNK: usize = 64;
        let mut out = vec![0.0; self.num_curves()];
        out.par_chunks_mut(CHUNK)
            .zip(self.queries.par_chunks(CHUNK * CURVE_POINTS))
            .zip(self.live.par_chunks(CHUNK))
            .for_each(|((out, q), live)| {
                let mut cache = CurveCache::new();
                for ((out, q), &live) in out.iter_mut().zip(q.chunks_exact(CURVE_POINTS)).zip(live)
                {
                    if !live {
                        continue;
                    }
                    // As fresh for each curve: its samples mostly share patches.
                    cache.reset();
                    let points = q
                        .iter()
                        .filter_map(|&(p, u, v)| cache.position(surface, p as usize, u, v));
                    *out = measure_stream(points, m);
                }
            });
        out
    }
}

/// One curve's measure (the CPU's, in `f64`): the largest over its segments or second
/// differences; zero for fewer than two (three) points.
pub fn measure(points: &[[f32; 3]], m: &CurveMeasure) -> f64 {
    measure_stream(points.iter().copied(), m)
}

/// [`measure`] of points as they are evaluated (no list).
fn measure_stream(points: impl IntoIterator<Item = [f32; 3]>, m: &CurveMeasure) -> f64 {
    match m {
        CurveMeasure::SecondDerivative => max_second_derivative(points),
        CurveMeasure::Speed => max_speed(points, Some),
        CurveMeasure::ScreenSpeed(camera) => {
            max_speed(points, |p| camera.project(p).map(|q| [q[0], q[1], 0.0]))
        }
    }
}

/// The largest length per unit parameter of the curve's segments, after `map` (a segment with
/// an end mapped to `None` counts zero). The square roots are taken once, of the largest
/// squared length: `sqrt` is correctly rounded and monotonic, so the result is the largest of
/// the segments' rounded lengths, bit for bit.
fn max_speed(
    points: impl IntoIterator<Item = [f32; 3]>,
    map: impl Fn([f32; 3]) -> Option<[f32; 3]>,
) -> f64 {
    let mut n = 0usize;
    let mut prev: Option<[f32; 3]> = None;
    let mut best = 0.0f64;
    for p in points {
        n += 1;
        let m = map(p);
        if let (Some(a), Some(b)) = (prev, m) {
            let sq = (0..3).map(|k| f64::from(b[k] - a[k]).powi(2)).sum::<f64>();
            best = best.max(sq);
        }
        prev = m;
    }
    let steps = (n.max(2) - 1) as f64;
    best.sqrt() * steps
}

/// Largest second derivative (per unit parameter squared) along evenly spaced samples, from
/// second differences (the square root taken once, as in [`max_speed`]).
fn max_second_derivative(c: impl IntoIterator<Item = [f32; 3]>) -> f64 {
    let wide = |p: [f32; 3]| [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])];
    let mut best = 0.0f64;
    // Each sample widened once; the windows' sums as `(a − 2b + c)²` over x, y, z.
    let mut c = c.into_iter();
    let mut n = 0usize;
    if let (Some(first), Some(second)) = (c.next(), c.next()) {
        n = 2;
        let (mut a, mut b) = (wide(first), wide(second));
        for p in c {
            n += 1;
            let q = wide(p);
            let sq = (0..3)
                .map(|k| (a[k] - 2.0 * b[k] + q[k]).powi(2))
                .sum::<f64>();
            best = best.max(sq);
            (a, b) = (b, q);
        }
    }
    let h = 1.0 / (n.max(2) - 1) as f64;
    best.sqrt() / (h * h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limit::{PatchOptions, PatchTable};

    /// Measures through one curve cache per curve ([`CurveCache`]: collapsed patches) agree
    /// with those of the exact evaluation per sample to rounding (a few units in the last
    /// place of the surface's extent, over the sample spacing or its square); dead curves
    /// (holes) measure zero; the layout has one curve per edge and six per ptex face of every
    /// face that is not a hole.
    #[test]
    fn cached_curve_measures_agree_with_exact_evaluations() {
        let mut mesh = crate::shapes::pole(7);
        mesh.holes.push(2);
        let t = crate::Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let surface = LimitSurface::new(table, &mesh.positions);
        let curves = RateCurves::new(&surface.table);
        let ptex_live: u32 = (0..t.num_faces())
            .filter(|&f| !t.face_is_hole[f])
            .map(|f| surface.table.ptex_offsets[f + 1] - surface.table.ptex_offsets[f])
            .sum();
        assert_eq!(
            curves.num_curves(),
            t.num_edges() + ISOLINES_PER_PTEX * ptex_live as usize
        );
        assert!(curves.live.iter().any(|&l| l) && !curves.live.iter().all(|&l| l));
        let diag = crate::mesh::bbox_diagonal(&surface.points);
        let mut worst = 0.0f64;
        for m in [CurveMeasure::SecondDerivative, CurveMeasure::Speed] {
            let cached = curves.measure(&surface, &m);
            for (c, q) in curves.queries.chunks_exact(CURVE_POINTS).enumerate() {
                let fresh: Vec<[f32; 3]> = q
                    .iter()
                    .filter_map(|&(p, u, v)| surface.eval_position(p as usize, u, v))
                    .collect();
                let want = if curves.live[c] {
                    measure(&fresh, &m)
                } else {
                    0.0
                };
                // A cache reset between curves gives what a new one gives, bit for bit.
                if curves.live[c] {
                    let mut cache = CurveCache::new();
                    let own: Vec<[f32; 3]> = q
                        .iter()
                        .filter_map(|&(p, u, v)| cache.position(&surface, p as usize, u, v))
                        .collect();
                    assert_eq!(
                        cached[c].to_bits(),
                        measure(&own, &m).to_bits(),
                        "curve {c}"
                    );
                }
                let steps = CURVE_SAMPLES as f64;
                let spacing = match m {
                    CurveMeasure::SecondDerivative => steps * steps,
                    _ => steps,
                };
                let rounding = 16.0 * f64::from(f32::EPSILON) * f64::from(diag) * spacing;
                assert!(
                    (cached[c] - want).abs() <= rounding,
                    "curve {c}: {} vs {want}",
                    cached[c]
                );
                worst = worst.max((cached[c] - want).abs() / rounding);
                if !curves.live[c] {
                    assert_eq!(cached[c], 0.0, "dead curve {c}");
                }
            }
        }
        eprintln!("worst difference: {worst:.3} of the rounding allowed");
    }

    /// A table lays its rate curves out once and keeps them (a clone shares them); after
    /// crease edits, in place or rebuilt, the kept layout is the one a new layout gives.
    #[test]
    fn the_table_keeps_its_layout() {
        let mesh = crate::shapes::creased_pole(5);
        let t = crate::Topology::new(&mesh).unwrap();
        let mut table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let first: *const RateCurves = &**table.rate_curves();
        assert_eq!(**table.rate_curves(), RateCurves::new(&table));
        assert!(std::ptr::eq(first, &**table.rate_curves()));
        assert!(std::ptr::eq(first, &**table.clone().rate_curves()));
        let c = mesh.creases[0];
        let mut outcomes = Vec::new();
        for sharpness in [5.0, 6.0, 7.5, 1.0] {
            let edit = crate::limit::SharpnessEdit::Edge {
                v0: c.v0,
                v1: c.v1,
                sharpness,
            };
            outcomes.push(table.apply_sharpness(&[edit]).unwrap());
            assert_eq!(
                **table.rate_curves(),
                RateCurves::new(&table),
                "{sharpness}"
            );
        }
        assert!(
            outcomes.contains(&crate::limit::EditOutcome::Updated),
            "{outcomes:?}"
        );
    }

    /// Measures of another mesh's curves are refused, naming the policy; uniform rates need
    /// none.
    #[test]
    fn measures_of_other_curves_are_refused() {
        let mesh = crate::shapes::cube();
        let t = crate::Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let surface = LimitSurface::new(table, &mesh.positions);
        let curves = RateCurves::new(&surface.table);
        let policy = super::super::RatePolicy::Tolerance(1e-3);
        let short = vec![1.0; curves.num_curves() - 1];
        let err = policy
            .rates_from_measures(&surface.table, 1.0, &curves, &short, "--tolerance")
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("--tolerance:") && err.contains("curve measures"),
            "{err}"
        );
        let uniform = super::super::RatePolicy::Uniform(3);
        let r = uniform
            .rates_from_measures(&surface.table, 1.0, &RateCurves::default(), &[], "--tess")
            .unwrap();
        assert_eq!(r, uniform.rates(&surface, "--tess").unwrap());
    }
}
