//! The tessellation pattern of one quad (ptex) face for four outer rates and two inner rates:
//! the sample set and facet count of OpenSubdiv 3.5's `Bfr::Tessellation` (quad
//! parameterization, triangles).
//!
//! # Samples
//!
//! Boundary first, edge by edge from corner 0, counter-clockwise: edge 0 `(i/R₀, 0)`, edge 1
//! `(1, i/R₁)`, edge 2 `(1 − i/R₂, 1)`, edge 3 `(0, 1 − i/R₃)`, `i = 0..R` (the next corner
//! starts the next edge). Then the interior:
//!
//! - inner rates `(U, V)` both above 1: the grid `(i/U, j/V)`, `0 < i < U`, `0 < j < V`;
//! - one inner rate 1 and every outer rate equal to the inner rate of its direction (a
//!   `1 × M` strip): no interior sample;
//! - otherwise (an inner rate of 1 against finer edges): the centre `(½, ½)` alone.
//!
//! Inner rates default to the means of opposite outer rates, `(⌊(R₀+R₂)/2⌋, ⌊(R₁+R₃)/2⌋)`.
//!
//! # Facets
//!
//! The interior grid's cells are split along their `(i, j)–(i+1, j+1)` diagonal. Each outer
//! edge is joined to the matching side of the grid's outermost ring by a strip of transition
//! triangles, walking both rows by their parameter along the edge and always closing the
//! triangle whose new edge spans the shorter interval (ties broken by the side of the edge's
//! midpoint, so the strip is symmetric); strips meet at the diagonals from outer to inner
//! corners. Every triangle is counter-clockwise in `(u, v)`. Since every sample is used and
//! the pattern triangulates the square, Euler's formula fixes the count at
//! `B + 2 I − 2` triangles (`B` boundary, `I` interior samples) — Bfr's count. The facets
//! themselves differ from Bfr's where Bfr keeps its own corner and middle-triangle choices.

/// One face's pattern in its own `(u, v)`: boundary samples first (see the module
/// documentation), then interior samples; triangles of sample indices.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct QuadPattern {
    /// The outer rates used, edge `k` from corner `k` to corner `k + 1`.
    pub outer: [u32; 4],
    /// The inner rates used `(U, V)`.
    pub inner: [u32; 2],
    /// The `(u, v)` samples.
    pub coords: Vec<[f32; 2]>,
    /// How many of `coords` are on the boundary (the sum of the outer rates).
    pub num_boundary: usize,
    /// Counter-clockwise triangles.
    pub triangles: Vec<[u32; 3]>,
}

/// Bfr's default inner rates of a quad: the means of opposite outer rates.
pub fn default_inner(outer: [u32; 4]) -> [u32; 2] {
    [
        ((outer[0] + outer[2]) / 2).max(1),
        ((outer[1] + outer[3]) / 2).max(1),
    ]
}

impl QuadPattern {
    /// The pattern for `outer` rates (each at least 1) and `inner` rates (default
    /// [`default_inner`]).
    pub fn new(outer: [u32; 4], inner: Option<[u32; 2]>) -> QuadPattern {
        let inner = inner.unwrap_or_else(|| default_inner(outer));
        let [ru, rv] = inner.map(|r| r.max(1) as usize);
        let r = outer.map(|r| r.max(1) as usize);
        let mut p = QuadPattern {
            outer: r.map(|x| x as u32),
            inner: [ru as u32, rv as u32],
            ..Default::default()
        };
        let mut off = [0usize; 5];
        for k in 0..4 {
            off[k + 1] = off[k] + r[k];
        }
        let nb = off[4];
        p.num_boundary = nb;
        for (k, &rk) in r.iter().enumerate() {
            for i in 0..rk {
                let t = i as f32 / rk as f32;
                p.coords.push(match k {
                    0 => [t, 0.0],
                    1 => [1.0, t],
                    2 => [1.0 - t, 1.0],
                    _ => [0.0, 1.0 - t],
                });
            }
        }
        // Boundary sample `i` of edge `k` (`i = r[k]` is the next corner).
        let b = |k: usize, i: usize| ((off[k] + i) % nb) as u32;
        if ru > 1 && rv > 1 {
            p.grid(ru, rv, &r, &b);
        } else if r == [ru, rv, ru, rv] {
            // A 1 × M strip: a ladder between the two long edges.
            let (long, m) = if ru == 1 { (1, rv) } else { (0, ru) };
            for j in 0..m {
                let (a0, a1) = (b(long, j), b(long, j + 1));
                let (c0, c1) = (b(long + 2, m - j), b(long + 2, m - j - 1));
                p.triangles.push([c0, a0, a1]);
                p.triangles.push([a1, c1, c0]);
            }
        } else {
            p.coords.push([0.5, 0.5]);
            let c = nb as u32;
            for i in 0..nb {
                p.triangles.push([i as u32, ((i + 1) % nb) as u32, c]);
            }
        }
        p
    }

    fn grid(&mut self, ru: usize, rv: usize, r: &[usize; 4], b: &dyn Fn(usize, usize) -> u32) {
        let nb = self.num_boundary as u32;
        let (nu, nv) = (ru - 1, rv - 1); // interior samples per row / column
        for j in 1..rv {
            for i in 1..ru {
                self.coords
                    .push([i as f32 / ru as f32, j as f32 / rv as f32]);
            }
        }
        let g = |i: usize, j: usize| nb + ((j - 1) * nu + (i - 1)) as u32;
        for j in 1..rv - 1 {
            for i in 1..ru - 1 {
                let (a, c) = (g(i, j), g(i + 1, j + 1));
                self.triangles.push([a, g(i + 1, j), c]);
                self.triangles.push([a, c, g(i, j + 1)]);
            }
        }
        // The inner row of each edge, in the edge's direction, with parameters along it.
        for k in 0..4 {
            let inner: Vec<(u32, f64)> = match k {
                0 => (1..ru).map(|i| (g(i, 1), i as f64 / ru as f64)).collect(),
                1 => (1..rv).map(|j| (g(nu, j), j as f64 / rv as f64)).collect(),
                2 => (1..ru)
                    .rev()
                    .map(|i| (g(i, nv), 1.0 - i as f64 / ru as f64))
                    .collect(),
                _ => (1..rv)
                    .rev()
                    .map(|j| (g(1, j), 1.0 - j as f64 / rv as f64))
                    .collect(),
            };
            let outer: Vec<(u32, f64)> = (0..=r[k])
                .map(|i| (b(k, i), i as f64 / r[k] as f64))
                .collect();
            stitch(&outer, &inner, &mut self.triangles);
        }
    }
}

/// Joins an outer row and an inner row (both in the same direction, the inner row to the
/// left of the outer one) by `(outer − 1) + (inner − 1)` counter-clockwise triangles.
pub(crate) fn stitch(outer: &[(u32, f64)], inner: &[(u32, f64)], out: &mut Vec<[u32; 3]>) {
    let (no, ni) = (outer.len() - 1, inner.len() - 1);
    let (mut o, mut q) = (0, 0);
    while o < no || q < ni {
        let advance_outer = if q == ni {
            true
        } else if o == no {
            false
        } else {
            let to_outer = outer[o + 1].1 - inner[q].1;
            let to_inner = inner[q + 1].1 - outer[o].1;
            if (to_outer - to_inner).abs() < 1e-12 {
                outer[o + 1].1 <= 0.5
            } else {
                to_outer < to_inner
            }
        };
        if advance_outer {
            out.push([outer[o].0, outer[o + 1].0, inner[q].0]);
            o += 1;
        } else {
            out.push([inner[q + 1].0, inner[q].0, outer[o].0]);
            q += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn signed_area(p: &QuadPattern, t: [u32; 3]) -> f64 {
        let [a, b, c] = t.map(|i| p.coords[i as usize].map(f64::from));
        0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    }

    /// Every pattern tiles the unit square: counter-clockwise triangles whose areas add up
    /// to 1, each sample used, the count of Euler's formula.
    #[test]
    fn patterns_tile_the_square() {
        let rates = [1u32, 2, 3, 4, 7, 16, 64];
        for &a in &rates {
            for &b in &rates {
                for &c in &[1u32, 5, 64] {
                    for inner in [None, Some([1, 1]), Some([3, 9]), Some([2, 2])] {
                        let p = QuadPattern::new([a, b, c, a.max(2)], inner);
                        let area: f64 = p.triangles.iter().map(|&t| signed_area(&p, t)).sum();
                        assert!(
                            (area - 1.0).abs() < 1e-9,
                            "{:?} {inner:?}: area {area}",
                            p.outer
                        );
                        assert!(p.triangles.iter().all(|&t| signed_area(&p, t) > 0.0));
                        let mut used = vec![false; p.coords.len()];
                        p.triangles
                            .iter()
                            .flatten()
                            .for_each(|&i| used[i as usize] = true);
                        assert!(used.iter().all(|&u| u), "{:?}: unused sample", p.outer);
                        let i = p.coords.len() - p.num_boundary;
                        assert_eq!(p.triangles.len(), p.num_boundary + 2 * i - 2);
                    }
                }
            }
        }
    }
}
