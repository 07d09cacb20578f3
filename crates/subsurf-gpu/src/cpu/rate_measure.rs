//! CPU twin of `shaders/rate_measure.wgsl`: one number per rate curve
//! ([`subsurf::tess::RateCurves`]), the largest over the curve's segments of its second difference
//! times `s²` (kind 0), its chord length times `s` (kind 1) or its chord length in pixels under
//! `view_proj` times `s` (kind 2; a chord with an end behind the eye counts zero), with
//! `s = points_per_curve − 1`. All in `f32`, in the shader's order; the GPU may contract
//! products and sums and round `sqrt` and `/` differently, so the two agree to a few units in
//! the last place, not bit for bit.

use crate::shared::RateConfig;

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::RATE_MEASURE_WORKGROUP_SIZE);

fn position(cfg: &RateConfig, samples: &[f32], c: u32, i: u32) -> [f32; 3] {
    let b = ((c * cfg.points_per_curve + i) * cfg.sample_stride) as usize;
    [samples[b], samples[b + 1], samples[b + 2]]
}

/// Pixel position of `p` and `1.0`, or zeros behind the eye (the shader's `pixel`).
fn pixel(cfg: &RateConfig, p: [f32; 3]) -> [f32; 3] {
    let m = &cfg.view_proj;
    let c: [f32; 4] =
        std::array::from_fn(|r| m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r]);
    if c[3] <= 1e-12 {
        return [0.0; 3];
    }
    let (x, y) = (c[0] / c[3], c[1] / c[3]);
    [
        (x * 0.5 + 0.5) * cfg.width,
        (0.5 - y * 0.5) * cfg.height,
        1.0,
    ]
}

fn length(d: [f32; 3]) -> f32 {
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

/// One invocation: the measure of curve `c` of the dispatch (bindings 0..=2).
pub fn rate_measure_invocation(c: u32, cfg: &RateConfig, samples: &[f32], measures: &mut [f32]) {
    if c >= cfg.curve_count {
        return;
    }
    let n = cfg.points_per_curve;
    let s = (n.max(2) - 1) as f32;
    let mut best = 0.0f32;
    if cfg.kind == 0 {
        let mut i = 0;
        while i + 2 < n {
            let (a, b, e) = (
                position(cfg, samples, c, i),
                position(cfg, samples, c, i + 1),
                position(cfg, samples, c, i + 2),
            );
            let d: [f32; 3] = std::array::from_fn(|k| a[k] - 2.0 * b[k] + e[k]);
            best = best.max(length(d) * (s * s));
            i += 1;
        }
    } else {
        let mut i = 0;
        while i + 1 < n {
            let (mut a, mut b) = (
                position(cfg, samples, c, i),
                position(cfg, samples, c, i + 1),
            );
            i += 1;
            if cfg.kind == 2 {
                a = pixel(cfg, a);
                b = pixel(cfg, b);
                if a[2] == 0.0 || b[2] == 0.0 {
                    continue;
                }
            }
            best = best.max(length(std::array::from_fn(|k| b[k] - a[k])) * s);
        }
    }
    measures[c as usize] = best;
}

/// The whole dispatch: every curve of `cfg.curve_count`.
pub fn rate_measure(cfg: &RateConfig, samples: &[f32], measures: &mut [f32]) {
    for c in 0..cfg.curve_count {
        rate_measure_invocation(c, cfg, samples, measures);
    }
}
