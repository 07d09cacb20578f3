//! A tolerance checked on every triangle of the tessellation, where the rate curves cannot see.
//!
//! The tolerance policy estimates each curve's second derivative from second differences of
//! 17 samples ([`super::curves`]), which misses bending confined to less than a sample
//! spacing: across a semi-sharp crease (the surface turns within a band about `2^-s` of the
//! face wide), at the ends of creases and at corners (valence-one corners of the car, chords
//! 1.47x over their budget at `3e-4`), and around extraordinary vertices (on the pawn's pole,
//! chords of rates chosen for `7.5e-4` were `1.03e-3` off). With the rate curves alone, 30 of
//! the 64 `catmark_*` regression shapes had edge midpoints or centroids past a tolerance of
//! `1e-3` or `1e-2` (up to 3x).
//!
//! So after planning, before anything is evaluated for output, every triangle is measured:
//! its distance across from the surface it spans, along its unit normal (a drift of the
//! parametrization along the surface is no error a renderer or a distance check sees). The
//! surface at the midpoints of its edges, less the chords' midpoints, gives the second
//! derivative across each edge, `n·D²S[eᵢⱼ, eᵢⱼ]` for the edge `eᵢⱼ` in ptex parameters (the
//! twist included where an edge runs across both parameters), and the distance to second
//! order is the largest of `½ Σ λᵢλⱼ |n·D²S[eᵢⱼ, eᵢⱼ]|` over the triangle; the centroid is
//! measured along the normal too. Along the surface's boundary, where no neighbouring
//! triangle covers what a chord cuts off inside the tangent plane, the surface's whole
//! offset across the chord at its midpoint counts. The rates of every base face where one misses are raised (every edge and the
//! interior, by the square root of the excess — chord error falls as the square of the
//! spacing — at least 1.25x; by the excess itself when the face misses again, as across a
//! bend narrower than its triangles the error falls only linearly) and the faces whose
//! samples changed planned and measured again, until none misses or the rates reach
//! [`MAX_RATE`], at most [`ROUNDS`] plans. A miss that a raise does not cut lies in a bend
//! narrower than the triangles (within `2^-s` of a semi-sharp corner), which finer rates
//! resolve once they pass its width: such a face's rates are doubled, up to 8x those of its
//! first miss, and then left (no chord error there: the surface is not continuous at that
//! scale). In the first round, faces measured well inside the tolerance have their rates
//! lowered ([`relax`]): the rate curves overestimate where the surface bends in a direction
//! no chord of the triangles crosses. Each plan's output is evaluated before its check, whose corner positions it gives;
//! the last plan's is the tessellation.

use super::mesh::{plan, AdaptivePlan, AdaptiveTessellation, EdgeRates, MAX_RATE};
use crate::error::Result;
use crate::limit::curve_eval::CurveCache;
use crate::limit::LimitSurface;
use rayon::prelude::*;

/// Queries or triangles per parallel chunk.
const CHUNK: usize = 512;

/// Slots of the memo of samples evaluated again from another ptex face.
const SEEN: usize = 64;

/// At most this many plans.
pub const ROUNDS: usize = 8;

/// Which sides of its ptex face a `(u, v)` lies on: bit 0 `v = 0`, 1 `u = 1`, 2 `v = 1`,
/// 3 `u = 0`.
fn sides(c: [f32; 2]) -> u8 {
    u8::from(c[1] == 0.0)
        | u8::from(c[0] == 1.0) << 1
        | u8::from(c[1] == 1.0) << 2
        | u8::from(c[0] == 0.0) << 3
}

/// Per ptex face, its sides (bits as [`sides`]) on the boundary of the surface: on a base
/// edge whose other faces are holes, or that has none. A quad's side `k` is its edge `k`; a
/// sub-face `k` of an n-gon has half of the face's edge `k` at `v = 0` and half of edge
/// `k − 1` at `u = 0`.
fn open_sides(surface: &LimitSurface) -> Vec<u8> {
    let table = &surface.table;
    let t = &table.base;
    let mut out = vec![0u8; table.num_ptex_faces()];
    for f in 0..t.num_faces() {
        if t.face_is_hole[f] {
            continue;
        }
        let open = |e: u32| {
            t.edge_faces(e as usize)
                .iter()
                .all(|&g| g as usize == f || t.face_is_hole[g as usize])
        };
        let fe = t.face_edges(f);
        let first = table.ptex_offsets[f] as usize;
        if fe.len() == 4 {
            out[first] = (0..4).fold(0, |m, k| m | u8::from(open(fe[k])) << k);
        } else {
            let n = fe.len();
            for k in 0..n {
                let prev = fe[(k + n - 1) % n];
                out[first + k] = u8::from(open(fe[k])) | u8::from(open(prev)) << 3;
            }
        }
    }
    out
}

/// The offset `off` of the surface from the chord `a b`'s midpoint, less its part along the
/// chord: how far the surface lies across it.
fn sag(a: [f32; 3], b: [f32; 3], off: [f64; 3]) -> f64 {
    let d = sub(b.map(f64::from), a.map(f64::from));
    let len2 = dot(d, d);
    let along = if len2 > 0.0 { dot(off, d) / len2 } else { 0.0 };
    let r = [0, 1, 2].map(|k| off[k] - along * d[k]);
    dot(r, r).sqrt()
}

/// The distance across a flat triangle `x` (its corners' surface normals `nrm`) from the
/// surface it spans, along the surface's unit normal, to second order: with `eᵢⱼ` its edges in
/// ptex parameters, `S − L ≈ −½ Σᵢ<ⱼ λᵢλⱼ D²S[eᵢⱼ, eᵢⱼ]` over the barycentric `λ` (exact for a
/// quadratic surface, the twist `S_uv` included along the edges that run across both
/// parameters), so the distance is at most `½ Σᵢ<ⱼ λᵢλⱼ aᵢⱼ` with `aᵢⱼ = |n·D²S[eᵢⱼ, eᵢⱼ]|`,
/// whose largest value over the triangle this returns. `aᵢⱼ` is read from `off[i]`, the
/// surface at edge `i → i + 1`'s midpoint less the chord's midpoint: `n·off = −aᵢⱼ/8` to
/// second order, with `n` the normal there (the mean of the edge's corner normals; the
/// triangle's where they cancel). The surface at the centroid less the triangle's
/// (`centroid`, where evaluated) is measured along the normal there as well, for bending
/// past second order. Along the surface's normal, not the triangle's: a drift of the
/// parametrization along a surface that a coarse triangle tilts against is no distance. A
/// degenerate triangle (no normal) counts the full distances.
fn across(
    x: [[f32; 3]; 3],
    nrm: [[f32; 3]; 3],
    off: [[f64; 3]; 3],
    centroid: Option<[f64; 3]>,
) -> f64 {
    let wide = |p: [f32; 3]| p.map(f64::from);
    let (a, b, c) = (wide(x[0]), wide(x[1]), wide(x[2]));
    let (u, v) = (sub(b, a), sub(c, a));
    let flat = unit([
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]);
    let Some(flat) = flat else {
        let norm = |d: [f64; 3]| dot(d, d).sqrt();
        let edges = off.iter().map(|&d| norm(d)).fold(0.0, f64::max);
        return edges.max(centroid.map_or(0.0, norm));
    };
    let n = nrm.map(wide);
    let mean = |ks: &[usize]| {
        let s = ks
            .iter()
            .fold([0.0; 3], |s, &k| [0, 1, 2].map(|q| s[q] + n[k][q]));
        unit(s).unwrap_or(flat)
    };
    let [p, q, r] = [0, 1, 2].map(|i| 8.0 * dot(mean(&[i, (i + 1) % 3]), off[i]).abs());
    let at_centroid = centroid.map_or(0.0, |d| dot(mean(&[0, 1, 2]), d).abs());
    at_centroid.max(largest_bending(p, q, r))
}

/// `d` over its length; `None` for a zero or non-finite length.
fn unit(d: [f64; 3]) -> Option<[f64; 3]> {
    let len = dot(d, d).sqrt();
    (len > 0.0 && len.is_finite()).then(|| d.map(|k| k / len))
}

/// The largest of `½ (λ₀λ₁ p + λ₁λ₂ q + λ₂λ₀ r)` over the barycentric `λ` (`p, q, r ≥ 0`, the
/// edges 0–1, 1–2, 2–0): on an edge `max / 8` at its midpoint; inside, where the gradient is
/// normal to the simplex, `λ ∝ y` with `y₀ = (p + r − q) / 2pr` (and its rotations),
/// `1 / (4 Σ y)`, when every `y` is positive.
fn largest_bending(p: f64, q: f64, r: f64) -> f64 {
    let edge = p.max(q).max(r) / 8.0;
    if !(p > 0.0 && q > 0.0 && r > 0.0) {
        return edge;
    }
    let y = [
        (p + r - q) / (2.0 * p * r),
        (p + q - r) / (2.0 * p * q),
        (q + r - p) / (2.0 * q * r),
    ];
    if y.iter().all(|&y| y > 0.0) {
        edge.max(1.0 / (4.0 * (y[0] + y[1] + y[2])))
    } else {
        edge
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Per base face, the largest distance (world units) across its flat triangles of `p` from
/// the surface, along each triangle's unit normal (module documentation: second order from
/// the edge midpoints, and the centroid), over the faces flagged in `only` (all when `None`;
/// the others read zero).
pub fn chord_errors(
    surface: &LimitSurface,
    p: &AdaptivePlan,
    face_of_ptex: &[u32],
    only: Option<&[bool]>,
) -> Vec<f64> {
    chord_errors_at(surface, p, face_of_ptex, only, None)
}

/// A plan's sample positions and normals, one each per query.
type Samples<'a> = (&'a [[f32; 3]], &'a [[f32; 3]]);

/// [`chord_errors`], the samples' positions and normals given (`known`: the output's, one
/// per query of `p`) or evaluated here.
fn chord_errors_at(
    surface: &LimitSurface,
    p: &AdaptivePlan,
    face_of_ptex: &[u32],
    only: Option<&[bool]>,
    known: Option<Samples<'_>>,
) -> Vec<f64> {
    let nf = surface.table.base.num_faces();
    let measured = |ptex: u32| only.is_none_or(|o| o[face_of_ptex[ptex as usize] as usize]);
    // The positions and normals of the samples, as the output will have them (a sample
    // shared by two ptex faces is evaluated from the first, as `eval_plan`).
    let evaluated;
    let (positions, normals) = match known {
        Some(known) => known,
        None => {
            evaluated = surface.eval_queries(&p.queries);
            (&evaluated.0[..], &evaluated.1[..])
        }
    };
    let open = open_sides(surface);
    let found: Vec<(u32, f64)> = p
        .triangles
        .par_chunks(CHUNK)
        .zip(p.triangle_uv.par_chunks(CHUNK))
        .flat_map_iter(|(tris, uvs)| {
            let mut cache = CurveCache::new();
            let mut found = Vec::new();
            // Samples of other ptex faces evaluated from this one, by sample index (direct
            // mapped: a sample joins several triangles of the face).
            let mut seen = [(u32::MAX, [0.0f32; 3]); SEEN];
            let mut seen_ptex = u32::MAX;
            for (tri, &(ptex, c)) in tris.iter().zip(uvs) {
                if !measured(ptex) {
                    continue;
                }
                if ptex != seen_ptex {
                    seen.iter_mut().for_each(|e| e.0 = u32::MAX);
                    seen_ptex = ptex;
                }
                let mut at = |u: f32, v: f32| cache.position(surface, ptex as usize, u, v);
                // A sample another ptex face evaluates is taken again from this one: the
                // chords are this face's (a table whose neighbouring patches part by more
                // than the tolerance is not mended by finer rates).
                let mut corner = |k: usize| {
                    let i = tri[k] as usize;
                    if p.queries[i].0 == ptex {
                        return positions[i];
                    }
                    let e = &mut seen[i % SEEN];
                    if e.0 != tri[k] {
                        *e = (tri[k], at(c[k][0], c[k][1]).unwrap_or(positions[i]));
                    }
                    e.1
                };
                // Written out: the array adaptor was not always inlined around this closure.
                let x = [corner(0), corner(1), corner(2)];
                // Per edge `i → i + 1`: the surface at its midpoint against the chord's
                // midpoint.
                let mut off = [[0.0f64; 3]; 3];
                for (i, off) in off.iter_mut().enumerate() {
                    let j = (i + 1) % 3;
                    if let Some(m) = at(0.5 * (c[i][0] + c[j][0]), 0.5 * (c[i][1] + c[j][1])) {
                        *off = [0, 1, 2].map(|q| {
                            f64::from(m[q]) - 0.5 * (f64::from(x[i][q]) + f64::from(x[j][q]))
                        });
                    }
                }
                let g = at(
                    (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                    (c[0][1] + c[1][1] + c[2][1]) / 3.0,
                );
                let centroid = g.map(|g| {
                    [0, 1, 2].map(|q| {
                        f64::from(g[q])
                            - (f64::from(x[0][q]) + f64::from(x[1][q]) + f64::from(x[2][q])) / 3.0
                    })
                });
                let nrm = [0, 1, 2].map(|k| normals[tri[k] as usize]);
                let mut w = across(x, nrm, off, centroid);
                // Along the surface's boundary no neighbour covers what a chord cuts off
                // inside the tangent plane: there the whole offset across the chord counts.
                let open = open[ptex as usize];
                if open != 0 {
                    for i in 0..3 {
                        let j = (i + 1) % 3;
                        if sides(c[i]) & sides(c[j]) & open != 0 {
                            w = w.max(sag(x[i], x[j], off[i]));
                        }
                    }
                }
                found.push((face_of_ptex[ptex as usize], w));
            }
            found
        })
        .collect();
    let mut out = vec![0.0f64; nf];
    for (f, w) in found {
        out[f as usize] = out[f as usize].max(w);
    }
    out
}

/// A tessellation of `surface` at `rates`, with the rates of base faces whose triangles miss
/// `tolerance` (a fraction of the points' bounding-box diagonal) across a triangle
/// ([`chord_errors`]) raised until they meet it (module documentation): the rates used, the
/// tessellation and, per triangle, its ptex face and corners' `(u, v)`. Refuses what [`plan`]
/// refuses, naming `origin`.
pub fn tessellate_within_tolerance(
    surface: &LimitSurface,
    mut rates: EdgeRates,
    tolerance: f32,
    origin: &str,
) -> Result<Tessellated> {
    let table = &surface.table;
    let t = &table.base;
    let bound = f64::from(tolerance) * f64::from(crate::mesh::bbox_diagonal(&surface.points));
    let face_of_ptex = table.ptex_base_faces();
    let mut p = plan(table, &rates, origin)?;
    // After the first round only the faces whose samples changed are measured again.
    let mut only: Option<Vec<bool>> = None;
    // Per face: its interior rate at its first miss (0: none yet), its last miss, and
    // whether it is left.
    let mut first = vec![0u32; t.num_faces()];
    let mut last = vec![0.0f64; t.num_faces()];
    let mut stuck = vec![false; t.num_faces()];
    // Each plan's output is evaluated first: its positions are the check's, and the last
    // plan's is the tessellation (every plan is evaluated once).
    let mut output = surface.eval_queries(&p.queries);
    for _ in 1..ROUNDS {
        let known = Some((&output.0[..], &output.1[..]));
        let errors = chord_errors_at(surface, &p, &face_of_ptex, only.as_deref(), known);
        if rates.faces.is_empty() {
            rates.faces = vec![0; t.num_faces()];
        }
        let old = rates.edges.clone();
        let mut again = vec![false; t.num_faces()];
        let mut raised = false;
        for (f, &w) in errors.iter().enumerate() {
            if w.is_nan() || w <= bound || stuck[f] {
                continue;
            }
            // A miss that a raise did not cut by a hundredth lies in a bend narrower than the
            // triangles (a semi-sharp corner: the surface turns within `2^-s` of the vertex),
            // which finer rates resolve only once they pass its width, or is no chord error
            // at all (the surface is not continuous there): the face's rates are doubled
            // until they are 8x those of its first miss, then left.
            let missed = first[f] > 0;
            let flat = missed && w > 0.99 * last[f];
            let inner = if rates.faces[f] > 0 {
                rates.faces[f]
            } else {
                t.face_edges(f)
                    .iter()
                    .map(|&e| old[e as usize])
                    .max()
                    .unwrap_or(1)
            };
            if !missed {
                first[f] = inner;
            }
            if flat && inner >= 8 * first[f] {
                stuck[f] = true;
                continue;
            }
            last[f] = w;
            // Chord error falls as the square of the spacing where the surface is smooth at
            // the scale of the triangles, but only linearly across a bend narrower than them
            // (a crease of high sharpness): a face that misses again is raised by the
            // excess itself.
            let excess = w / bound;
            let k = if flat {
                2.0
            } else if missed {
                excess.max(1.25) * 1.05
            } else {
                excess.sqrt().max(1.25) * 1.05
            };
            let up = |r: u32| ((f64::from(r) * k).ceil() as u32).min(MAX_RATE);
            for &e in t.face_edges(f) {
                let e = e as usize;
                let r = up(old[e]).max(rates.edges[e]);
                if r != rates.edges[e] {
                    rates.edges[e] = r;
                    // Both sides of the edge change.
                    for &g in t.edge_faces(e) {
                        again[g as usize] = true;
                    }
                }
            }
            let r = up(inner);
            if r != rates.faces[f] {
                rates.faces[f] = r;
                again[f] = true;
            }
            raised |= again[f];
        }
        if only.is_none() {
            raised |= relax(t, &mut rates, &old, &errors, bound, &mut again);
        }
        if !raised {
            break;
        }
        p = plan(table, &rates, origin)?;
        only = Some(again);
        output = surface.eval_queries(&p.queries);
    }
    let uv = std::mem::take(&mut p.triangle_uv);
    let (positions, normals) = output;
    let tessellation = AdaptiveTessellation {
        positions,
        normals,
        triangles: p.triangles,
        edge_rates: p.edge_rates,
    };
    Ok((rates, tessellation, uv))
}

/// Below this share of the tolerance a face's first measure lowers its rates.
const SLACK: f64 = 0.5;

/// The share of the tolerance lowered rates aim at.
const AIM: f64 = 0.8;

/// The first round's lowering: the rate curves see bending along and across each edge from
/// second differences, which overestimates where the surface bends in a direction no chord
/// of the triangles crosses (a thin rim: the curves across it are bent, the triangles' chords
/// along it are not). A face whose triangles are measured within [`SLACK`] of the tolerance
/// has its interior rate, and every edge whose faces all are such, scaled by
/// `√(error / (AIM × tolerance))` (chord error falls as the square of the spacing), at least
/// 1; the faces that miss after it are raised as any miss is. Returns whether a rate changed.
fn relax(
    t: &crate::topology::Topology,
    rates: &mut EdgeRates,
    old: &[u32],
    errors: &[f64],
    bound: f64,
    again: &mut [bool],
) -> bool {
    // Per face its scale (1: kept).
    let scale: Vec<f64> = errors
        .iter()
        .map(|&w| {
            if w.is_nan() || w >= SLACK * bound {
                1.0
            } else {
                (w.max(0.0) / (AIM * bound)).sqrt()
            }
        })
        .collect();
    let down = |r: u32, k: f64| ((f64::from(r) * k).ceil() as u32).clamp(1, r);
    let mut changed = false;
    for (e, &r) in old.iter().enumerate() {
        if rates.edges[e] != r {
            continue; // raised by a miss beside it
        }
        let k = t
            .edge_faces(e)
            .iter()
            .map(|&g| scale[g as usize])
            .fold(0.0f64, f64::max);
        let lowered = down(r, k);
        if lowered < r {
            rates.edges[e] = lowered;
            changed = true;
            for &g in t.edge_faces(e) {
                again[g as usize] = true;
            }
        }
    }
    for f in 0..t.num_faces() {
        if scale[f] >= 1.0 || t.face_is_hole[f] {
            continue;
        }
        let inner = if rates.faces[f] > 0 {
            rates.faces[f]
        } else {
            t.face_edges(f)
                .iter()
                .map(|&e| old[e as usize])
                .max()
                .unwrap_or(1)
        };
        let lowered = down(inner, scale[f]);
        if lowered < inner {
            rates.faces[f] = lowered;
            changed = true;
            again[f] = true;
        }
    }
    changed
}

/// What [`tessellate_within_tolerance`] gives: the rates used, the tessellation, and per
/// triangle its ptex face and corners' `(u, v)`.
pub type Tessellated = (EdgeRates, AdaptiveTessellation, Vec<TriangleUv>);

/// A triangle's ptex face and its corners' `(u, v)` there.
pub type TriangleUv = (u32, [[f32; 2]; 3]);

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form of the largest second-order distance over a triangle is the largest
    /// value on a fine barycentric grid, to the grid's resolution, for edge bendings of every
    /// mix (one edge alone, equal, one small, random).
    #[test]
    fn largest_bending_is_the_grids_largest() {
        const N: usize = 400;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut cases = vec![
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [1.0, 1.0, 0.01],
            [3.0, 1.0, 1.0],
        ];
        cases.extend((0..50).map(|_| [next(), next(), next()]));
        for [p, q, r] in cases {
            let mut grid = 0.0f64;
            for i in 0..=N {
                for j in 0..=N - i {
                    let l = [i, j, N - i - j].map(|k| k as f64 / N as f64);
                    grid = grid.max(0.5 * (l[0] * l[1] * p + l[1] * l[2] * q + l[2] * l[0] * r));
                }
            }
            let exact = largest_bending(p, q, r);
            assert!(
                exact >= grid * (1.0 - 1e-12),
                "{p} {q} {r}: {exact} < {grid}"
            );
            assert!(
                exact <= grid * (1.0 + 1e-4),
                "{p} {q} {r}: {exact} > {grid}"
            );
        }
    }
}
