// rate_measure: one number per rate curve of a limit surface (subsurf::tess::curves), the
// largest over its segments of
//   kind 0: |p[i] - 2 p[i+1] + p[i+2]| * s^2   (second derivative per unit parameter squared)
//   kind 1: |p[i+1] - p[i]| * s                (speed: length per unit parameter)
//   kind 2: kind 1 on pixel positions under view_proj; a segment with an end behind the eye
//           (clip w <= 1e-12) counts zero
// with s = points_per_curve - 1 intervals. Curve c's samples are the positions (first three
// floats) of samples c * points_per_curve .. (c + 1) * points_per_curve.
//
// Bindings: 0 config, 1 samples (read), 2 measures (one f32 per curve, written).
// CPU twin: src/cpu/rate_measure.rs.

@group(0) @binding(0) var<uniform> cfg: RateConfig;
@group(0) @binding(1) var<storage, read> samples: array<f32>;
@group(0) @binding(2) var<storage, read_write> measures: array<f32>;

const WORKGROUP_SIZE: u32 = 64u;

fn position(c: u32, i: u32) -> vec3<f32> {
    let b = (c * cfg.points_per_curve + i) * cfg.sample_stride;
    return vec3<f32>(samples[b], samples[b + 1u], samples[b + 2u]);
}

// Pixel position of p in .xy, .z = 1; all zero behind the eye.
fn pixel(p: vec3<f32>) -> vec3<f32> {
    let m = cfg.view_proj;
    let c = m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3];
    if (c.w <= 1e-12) {
        return vec3<f32>(0.0, 0.0, 0.0);
    }
    let x = c.x / c.w;
    let y = c.y / c.w;
    return vec3<f32>((x * 0.5 + 0.5) * cfg.width, (0.5 - y * 0.5) * cfg.height, 1.0);
}

@compute @workgroup_size(WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let c = gid.y * cfg.grid_width + gid.x;
    if (c >= cfg.curve_count) {
        return;
    }
    let n = cfg.points_per_curve;
    let s = f32(max(n, 2u) - 1u);
    var best = 0.0;
    if (cfg.kind == 0u) {
        for (var i = 0u; i + 2u < n; i = i + 1u) {
            let d = position(c, i) - 2.0 * position(c, i + 1u) + position(c, i + 2u);
            best = max(best, length(d) * (s * s));
        }
    } else {
        for (var i = 0u; i + 1u < n; i = i + 1u) {
            var a = position(c, i);
            var b = position(c, i + 1u);
            if (cfg.kind == 2u) {
                a = pixel(a);
                b = pixel(b);
                if (a.z == 0.0 || b.z == 0.0) {
                    continue;
                }
            }
            best = max(best, length(b - a) * s);
        }
    }
    measures[c] = best;
}
