//! A tolerance checked where its rate curves cannot see: at the corners of the end caps.
//!
//! The tolerance policy measures second differences along 17 samples of each rate curve
//! ([`super::curves`]). Around an extraordinary vertex the limit surface bends fastest at the
//! vertex itself (Catmull-Clark's curvature there is unbounded at high valence), within a
//! region smaller than the samples' spacing once the isolation is deep enough to follow it
//! ([`crate::limit::tolerance`]): on the pawn's pole, chords of rates chosen for `7.5e-4`
//! were `1.03e-3` off at the pole. (At the default isolation 4 an end cap spans 1/16 of its
//! face, one sample spacing of the rate curves, which see its bending.) So in base faces
//! isolated deeper than the table's least level, the triangles that touch a ptex-face corner
//! lying in an end cap are measured after the tessellation (the midpoints of their edges at
//! that corner and their centroid against the surface), and the
//! rates of every base face where one misses are raised by the square root of the excess
//! (chord error falling as the square of the spacing) and tessellated again, until none
//! misses or the rates reach [`MAX_RATE`].

use super::mesh::{plan, AdaptiveTessellation, EdgeRates, MAX_RATE};
use crate::error::Result;
use crate::limit::{LimitSurface, PatchType};
use rayon::prelude::*;

/// At most this many plans.
const ROUNDS: usize = 6;

/// Per ptex face: bit `k` set when its corner `k` (`(0,0)`, `(1,0)`, `(1,1)`, `(0,1)`) lies in
/// an end cap of a base face isolated deeper than the table's least level (where the surface
/// bends within less than the rate curves' sample spacing, module documentation).
fn end_cap_corners(surface: &LimitSurface) -> Vec<u8> {
    let t = &surface.table;
    let Some(levels) = &t.face_levels else {
        return Vec::new();
    };
    let least = levels.iter().copied().min().unwrap_or(0);
    let mut out = vec![0u8; t.num_ptex_faces()];
    for (f, _) in levels.iter().enumerate().filter(|(_, &l)| l > least) {
        for ptex in t.ptex_offsets[f] as usize..t.ptex_offsets[f + 1] as usize {
            out[ptex] = [(0.0f32, 0.0f32), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                .iter()
                .enumerate()
                .filter(|(_, &(u, v))| {
                    t.patch_map
                        .find(ptex, u, v)
                        .is_some_and(|p| t.patch_type(p as usize) == PatchType::Gregory)
                })
                .fold(0u8, |m, (k, _)| m | 1 << k);
        }
    }
    out
}

fn corner_bit(c: [f32; 2]) -> u8 {
    match (c[0], c[1]) {
        (0.0, 0.0) => 1,
        (1.0, 0.0) => 2,
        (1.0, 1.0) => 4,
        (0.0, 1.0) => 8,
        _ => 0,
    }
}

/// Per base face, the largest distance (world units) between the flat triangles of `out`
/// (per triangle its ptex face and corners' `(u, v)` in `uv`) at its end-cap corners and the
/// surface: their edge midpoints and centroids. Only the faces flagged in `only` (all when
/// empty) are measured.
fn corner_errors(
    surface: &LimitSurface,
    out: &AdaptiveTessellation,
    uv: &[TriangleUv],
    corners: &[u8],
    face_of_ptex: &[u32],
    only: &[bool],
) -> Vec<f64> {
    let nf = surface.table.base.num_faces();
    let found: Vec<(u32, f64)> = out
        .triangles
        .par_iter()
        .zip(uv)
        .filter(|(_, (ptex, c))| {
            let ptex = *ptex as usize;
            corners.get(ptex).is_some_and(|&m| m != 0)
                && (only.is_empty() || only[face_of_ptex[ptex] as usize])
                && c.iter().any(|&x| corner_bit(x) & corners[ptex] != 0)
        })
        .filter_map(|(tri, &(ptex, c))| {
            let at = |u: f32, v: f32| surface.eval_position(ptex as usize, u, v);
            let x = tri.map(|i| out.positions[i as usize]);
            let dist = |a: [f32; 3], b: [f32; 3]| -> f64 {
                (0..3)
                    .map(|k| f64::from(a[k] - b[k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            };
            // The two edges at the end-cap corner and the centroid: the far edge is the
            // flattest.
            let at_corner = |i: usize| corner_bit(c[i]) & corners[ptex as usize] != 0;
            let mut w = 0.0f64;
            for k in 0..3 {
                let (i, j) = (k, (k + 1) % 3);
                if !(at_corner(i) || at_corner(j)) {
                    continue;
                }
                let m = at(0.5 * (c[i][0] + c[j][0]), 0.5 * (c[i][1] + c[j][1]))?;
                w = w.max(dist([0, 1, 2].map(|q| 0.5 * (x[i][q] + x[j][q])), m));
            }
            let g = at(
                (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                (c[0][1] + c[1][1] + c[2][1]) / 3.0,
            )?;
            w = w.max(dist(
                [0, 1, 2].map(|q| (x[0][q] + x[1][q] + x[2][q]) / 3.0),
                g,
            ));
            Some((face_of_ptex[ptex as usize], w))
        })
        .collect();
    let mut out = vec![0.0f64; nf];
    for (f, w) in found {
        out[f as usize] = out[f as usize].max(w);
    }
    out
}

/// A tessellation of `surface` at `rates`, with the rates of base faces whose triangles at
/// end-cap corners miss `tolerance` (a fraction of the points' bounding-box diagonal) raised
/// until they meet it (module documentation): the rates used, the tessellation and, per
/// triangle, its ptex face and corners' `(u, v)`. Refuses what [`plan`] refuses, naming
/// `origin`.
pub fn tessellate_within_tolerance(
    surface: &LimitSurface,
    mut rates: EdgeRates,
    tolerance: f32,
    origin: &str,
) -> Result<Tessellated> {
    let table = &surface.table;
    let t = &table.base;
    let bound = f64::from(tolerance) * f64::from(crate::mesh::bbox_diagonal(&surface.points));
    let corners = end_cap_corners(surface);
    let run = |rates: &EdgeRates| -> Result<(AdaptiveTessellation, Vec<TriangleUv>)> {
        let mut p = plan(table, rates, origin)?;
        let uv = std::mem::take(&mut p.triangle_uv);
        Ok((surface.eval_plan(p), uv))
    };
    let (mut out, mut uv) = run(&rates)?;
    if corners.iter().all(|&c| c == 0) {
        return Ok((rates, out, uv));
    }
    let face_of_ptex = table.ptex_base_faces();
    // After the first round only the faces whose rates were raised are measured again.
    let mut only: Vec<bool> = Vec::new();
    for _ in 1..ROUNDS {
        let errors = corner_errors(surface, &out, &uv, &corners, &face_of_ptex, &only);
        if rates.faces.is_empty() {
            rates.faces = vec![0; t.num_faces()];
        }
        let old = rates.edges.clone();
        only = vec![false; t.num_faces()];
        let mut raised = false;
        for (f, &w) in errors.iter().enumerate() {
            if w.is_nan() || w <= bound {
                continue;
            }
            let k = (w / bound).sqrt().max(1.25) * 1.05;
            let up = |r: u32| ((f64::from(r) * k).ceil() as u32).min(MAX_RATE);
            let finest = t
                .face_edges(f)
                .iter()
                .map(|&e| old[e as usize])
                .max()
                .unwrap_or(1);
            let inner = if rates.faces[f] > 0 {
                rates.faces[f]
            } else {
                finest
            };
            let mut changed = false;
            for &e in t.face_edges(f) {
                let e = e as usize;
                let r = up(old[e]).max(rates.edges[e]);
                changed |= r != rates.edges[e];
                rates.edges[e] = r;
            }
            let r = up(inner);
            changed |= r != rates.faces[f];
            rates.faces[f] = r;
            only[f] = changed;
            raised |= changed;
        }
        if !raised {
            break;
        }
        (out, uv) = run(&rates)?;
    }
    Ok((rates, out, uv))
}

/// What [`tessellate_within_tolerance`] gives: the rates used, the tessellation, and per
/// triangle its ptex face and corners' `(u, v)`.
pub type Tessellated = (EdgeRates, AdaptiveTessellation, Vec<TriangleUv>);

/// A triangle's ptex face and its corners' `(u, v)` there.
pub type TriangleUv = (u32, [[f32; 2]; 3]);
