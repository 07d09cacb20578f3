//! Adaptive tessellation of the limit surface: one integer rate per base edge (and an
//! interior rate per face), every edge sampled once and shared by index by its faces, so the
//! mesh is watertight with any mix of rates.
//!
//! ```text
//! RatePolicy ──rates──▶ EdgeRates ──mesh::plan──▶ AdaptivePlan ──eval──▶ triangles
//! ```
//!
//! The parts: the pattern of one quad ptex face ([`QuadPattern`], the sample set and facet
//! count of OpenSubdiv's `Bfr::Tessellation`, with its transition strips); the ptex faces'
//! patterns joined through shared edge samples ([`plan`], [`AdaptiveTessellation`]); policies
//! (uniform, maximum edge length, chordal tolerance, screen space, explicit rates) turned
//! into per-edge rates ([`RatePolicy`], [`EdgeRates`]); a tolerance checked on every planned
//! triangle, where the rate curves cannot see ([`tessellate_within_tolerance`]); and the
//! curves on the limit surface that the policies measure, as a flat list of samples any
//! evaluator (the CPU's, a GPU's) can measure ([`RateCurves`]).

pub(crate) mod check;
pub(crate) mod curves;
pub(crate) mod deviation;
pub(crate) mod mesh;
pub(crate) mod pattern;
pub(crate) mod rates;

pub use check::{chord_errors, tessellate_within_tolerance};
pub use curves::{
    measure, CurveMeasure, RateCurves, CURVE_POINTS, CURVE_SAMPLES, ISOLINES, ISOLINES_PER_PTEX,
};
pub use deviation::{
    deviation, Deviation, DeviationOptions, DeviationReference, TriangleParameters, SEEDS,
};
pub use mesh::{plan, plan_without_uv, AdaptivePlan, AdaptiveTessellation, EdgeRates, MAX_RATE};
pub use pattern::{default_inner, QuadPattern};
pub use rates::{parse_edge_rates, set_edge_rate, RatePolicy, ScreenCamera};
