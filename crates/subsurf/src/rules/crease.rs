//! Semi-sharp creases (DeRose, Kass & Truong 1998), as OpenSubdiv's `Sdc::Crease`.
//!
//! Sharpness `s <= 0` is smooth, `s >= 10` infinitely sharp, anything between semi-sharp. Each
//! level a semi-sharp value decays: by one (uniform) or, with Chaikin's rule, to
//! `0.75 s + 0.25 avg(other semi-sharp edges at the vertex) − 1`.

use crate::options::CreaseMethod;
use crate::SHARPNESS_INFINITE;

/// `s > 0`.
#[inline]
pub fn is_sharp(s: f32) -> bool {
    s > 0.0
}
/// `s >= 10`.
#[inline]
pub fn is_infinite(s: f32) -> bool {
    s >= SHARPNESS_INFINITE
}
/// `0 < s < 10`.
#[inline]
pub fn is_semi_sharp(s: f32) -> bool {
    s > 0.0 && s < SHARPNESS_INFINITE
}

/// One level of uniform decay: `s − 1`, infinite stays infinite, values `<= 1` become 0.
#[inline]
pub fn decrement(s: f32) -> f32 {
    if s <= 0.0 {
        0.0
    } else if is_infinite(s) {
        SHARPNESS_INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// Sharpness of the child of an edge of sharpness `s` at a vertex whose incident edges have
/// sharpness `around` (the edge itself included). Chaikin's rule averages with the other
/// semi-sharp edges at that vertex.
pub fn subdivide_edge_sharpness_at_vertex(method: CreaseMethod, s: f32, around: &[f32]) -> f32 {
    if method == CreaseMethod::Uniform || around.len() < 2 {
        return decrement(s);
    }
    if s <= 0.0 {
        return 0.0;
    }
    if is_infinite(s) {
        return SHARPNESS_INFINITE;
    }
    let (mut sum, mut count) = (0.0f32, 0usize);
    for &x in around {
        if is_semi_sharp(x) {
            sum += x;
            count += 1;
        }
    }
    let mut e = s;
    if count > 1 {
        let avg = (sum - s) / (count - 1) as f32;
        e = 0.75 * s + 0.25 * avg;
    }
    e -= 1.0;
    if e > 0.0 {
        e
    } else {
        0.0
    }
}

/// Child sharpness of every edge around one vertex at once (`parent` → `child`, same order).
#[cfg(test)]
pub fn subdivide_edge_sharpness_around_vertex(
    method: CreaseMethod,
    parent: &[f32],
    child: &mut [f32],
) {
    if method == CreaseMethod::Uniform || parent.len() < 2 {
        for (c, &p) in child.iter_mut().zip(parent) {
            *c = decrement(p);
        }
        return;
    }
    let (mut sum, mut count) = (0.0f32, 0usize);
    for &x in parent {
        if is_semi_sharp(x) {
            sum += x;
            count += 1;
        }
    }
    if count == 0 {
        child.copy_from_slice(parent);
        return;
    }
    for (c, &p) in child.iter_mut().zip(parent) {
        *c = if p <= 0.0 {
            0.0
        } else if is_infinite(p) {
            SHARPNESS_INFINITE
        } else if count == 1 {
            decrement(p)
        } else {
            let avg = (sum - p) / (count - 1) as f32;
            let s = 0.75 * p + 0.25 * avg - 1.0;
            if s > 0.0 {
                s
            } else {
                0.0
            }
        };
    }
}

/// The weight of the parent rule when a vertex changes rule between levels: the average
/// sharpness of the features that decay to smooth, clamped to 1 (OpenSubdiv
/// `Crease::ComputeFractionalWeightAtVertex`).
pub fn fractional_weight_at_vertex(
    method: CreaseMethod,
    parent_vertex: f32,
    child_vertex: f32,
    parent_edges: &[f32],
    child_edges: &[f32],
) -> f32 {
    let (mut count, mut sum) = (0usize, 0.0f32);
    if is_sharp(parent_vertex) && !is_sharp(child_vertex) {
        count = 1;
        sum = parent_vertex;
    }
    if method == CreaseMethod::Uniform {
        for &p in parent_edges {
            if is_sharp(p) && p <= 1.0 {
                sum += p;
                count += 1;
            }
        }
    } else {
        for (&p, &c) in parent_edges.iter().zip(child_edges) {
            if is_sharp(p) && !is_sharp(c) {
                sum += p;
                count += 1;
            }
        }
    }
    if count == 0 {
        return 0.0;
    }
    (sum / count as f32).min(1.0)
}

/// Indices of the first two sharp edges (the crease's ends).
pub fn sharp_edge_pair(edges: &[f32]) -> [usize; 2] {
    let mut pair = [0usize; 2];
    let mut n = 0;
    for (i, &s) in edges.iter().enumerate() {
        if is_sharp(s) {
            pair[n] = i;
            n += 1;
            if n == 2 {
                break;
            }
        }
    }
    pair
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decay_is_rendermans() {
        assert_eq!(decrement(2.5), 1.5);
        assert_eq!(decrement(1.0), 0.0);
        assert_eq!(decrement(0.3), 0.0);
        assert_eq!(decrement(10.0), 10.0);
        assert_eq!(decrement(-1.0), 0.0);
    }

    #[test]
    fn chaikin_averages_neighbours() {
        let around = [3.0, 1.0, 0.0, 10.0];
        // 0.75*3 + 0.25*1 - 1 = 1.5
        assert_eq!(
            subdivide_edge_sharpness_at_vertex(CreaseMethod::Chaikin, 3.0, &around),
            1.5
        );
        let mut child = [0.0; 4];
        subdivide_edge_sharpness_around_vertex(CreaseMethod::Chaikin, &around, &mut child);
        assert_eq!(child, [1.5, 0.5, 0.0, 10.0]);
        subdivide_edge_sharpness_around_vertex(CreaseMethod::Uniform, &around, &mut child);
        assert_eq!(child, [2.0, 0.0, 0.0, 10.0]);
    }

    #[test]
    fn fractional_weight_is_mean_of_decaying_features() {
        let w = fractional_weight_at_vertex(
            CreaseMethod::Uniform,
            0.0,
            0.0,
            &[0.5, 0.7, 0.0, 3.0],
            &[],
        );
        assert!((w - 0.6).abs() < 1e-7);
        assert_eq!(
            fractional_weight_at_vertex(CreaseMethod::Uniform, 0.0, 0.0, &[2.0, 0.0], &[]),
            0.0
        );
        assert_eq!(sharp_edge_pair(&[0.0, 1.0, 0.0, 2.0, 5.0]), [1, 3]);
    }
}
