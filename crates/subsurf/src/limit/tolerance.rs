//! The isolation level chosen per region for a tolerance: deep enough near each
//! extraordinary vertex that its end caps are within the tolerance of the true limit surface,
//! no deeper elsewhere.
//!
//! A Gregory end cap only approximates the limit surface around an extraordinary vertex (or
//! another irregular feature left at the isolation level). So do the regular and
//! single-crease patches of faces at an interior infinitely sharp corner or crease vertex and
//! along semi-sharp creases under Chaikin's rule (measured against
//! isolation 10: `catmark_inf_crease0` 1.1e-2 of the diagonal off at isolation 4,
//! `catmark_fvar_project0` 9.5e-3, `catmark_chaikin1` 3.6e-3). All patches of those faces
//! are measured below with the end caps ("end caps" for short).
//!
//! Each level of isolation shrinks the end caps' region by the vertex's subdominant
//! eigenvalue `λ` (Catmull-Clark: 0.41 at valence 3, 0.55 at 5, towards 0.65 at high
//! valence), and their distance to the limit surface falls by about that ratio: measured here
//! against an isolation-9 reference, 0.49–0.57 per level on the car's valence-3 and -5 vertices
//! and 0.63–0.64 on the pawn's pole, from level 1 to 8.
//!
//! So the distance is estimated per base face from three tables, at the table's isolation `L`
//! and at `L + 1`, `L + 2`: `d₀` the largest distance between the level-`L` and level-`L + 1`
//! surfaces at a 5 × 5 grid of every level-`L` end cap of the face, `d₁` the same one level
//! down, `r = d₁ / d₀` (kept within [0.5, 0.8]: the ratio of a regular vertex at least, as a
//! single level's ratio can dip below the trend) the face's ratio per level. With the
//! differences falling by `r` per level, the level-`(L + k)` end caps are within
//!
//! ```text
//! e(k) = d₀ · rᵏ / (1 − r)
//! ```
//!
//! of the limit (the sum of the remaining differences), and the face takes the least `k` with
//! `e(k)` within the budget (up to [`MAX_ISOLATION_LEVEL`]). Faces without end caps keep `L`.
//! The levels then go to [`PatchTable::build_face_levels`].

use super::eval::LimitSurface;
use super::table::{PatchOptions, PatchTable, PatchType, MAX_ISOLATION_LEVEL};
use crate::error::{Error, Result, TessError};
use crate::options::CreaseMethod;
use crate::real::Real;
use crate::topology::{tags, Topology};
use rayon::prelude::*;

/// The share of a `--tolerance` given to the end caps; the chords of the tessellation take
/// the rest ([`split_tolerance`]).
pub const END_CAP_SHARE: f32 = 0.25;

/// The most of a tolerance the end caps may take where the deepest isolation leaves them past
/// [`END_CAP_SHARE`] ([`table_for_tolerance`]).
pub const MAX_END_CAP_SHARE: f32 = 0.5;

/// The end caps' and the chords' parts of a total tolerance `e`: `(e/4, 3e/4)`.
pub fn split_tolerance(e: f32) -> (f32, f32) {
    (e * END_CAP_SHARE, e * (1.0 - END_CAP_SHARE))
}

/// Per-region isolation levels and what they are expected to give.
#[derive(Debug, Clone, PartialEq)]
pub struct IsolationChoice {
    /// Per base face, its isolation level.
    pub face_levels: Vec<u8>,
    /// Per base face, the estimated distance of its end caps to the limit surface at that
    /// level, as a fraction of the bounding-box diagonal (0 without end caps).
    pub deviation: Vec<f32>,
    /// Per base face, the measured ratio of the distance per level (1 without end caps).
    pub ratio: Vec<f32>,
}

/// Samples per end-cap side.
const GRID: usize = 5;
/// Bounds of the per-level ratio.
const RATIO: (f64, f64) = (0.5, 0.8);

/// Whether base face `f` touches a vertex where regular patches at the isolation level may
/// still approximate: an interior infinitely sharp corner or crease vertex, or (under
/// Chaikin's rule, whose sharpness varies along a crease) one on a semi-sharp crease, or an
/// extraordinary boundary vertex that is not a corner (a smooth corner of one face under
/// edge-only boundaries: `catmark_edgeonly`'s corners were 1.0e-3 of the diagonal off the
/// limit surface at isolation 4, along the surface). (Other boundary vertices, whose edges
/// are infinitely sharp too, are left out: their boundary patches are exact. Non-manifold
/// vertices are left out too: measuring them changed nothing on `catmark_nonman_verts` or
/// `catmark_val2_nonman`, whose misses were narrow bends that the tessellation's check
/// resolves, not levels.)
fn sharp_feature_face(base: &Topology, f: usize) -> bool {
    let chaikin = base.options.crease_method == CreaseMethod::Chaikin;
    base.face_vertices(f).iter().any(|&v| {
        let tag = base.vert_tags[v as usize];
        let interior = tag & (tags::V_BOUNDARY | tags::V_NON_MANIFOLD) == 0;
        let smooth_boundary_corner = tag & tags::V_BOUNDARY != 0
            && tag & tags::V_XORDINARY != 0
            && tag & (tags::V_CORNER | tags::V_INF_SHARP | tags::V_NON_MANIFOLD) == 0;
        (interior && tag & (tags::V_INF_SHARP | tags::V_INF_SHARP_EDGES) != 0)
            || (chaikin && tag & tags::V_SEMI_SHARP_EDGES != 0)
            || smooth_boundary_corner
    })
}

/// Per base face: the largest distance between `a` and `b` at `a`'s patches that may only
/// approximate the limit surface in that face (module documentation): its end caps, and all
/// its patches where `feature` flags it ([`sharp_feature_face`]).
fn end_cap_differences<R: Real>(
    a: &LimitSurface<R>,
    b: &LimitSurface<R>,
    feature: &[bool],
) -> Vec<f64> {
    let t = &a.table;
    let nf = t.base.num_faces();
    let face_of_ptex = t.ptex_base_faces();
    let per_patch: Vec<(u32, f64)> = (0..t.num_patches())
        .into_par_iter()
        .filter(|&p| {
            t.patch_type(p) == PatchType::Gregory
                || feature[face_of_ptex[t.params[p].face_id() as usize] as usize]
        })
        .map(|p| {
            let pp = t.params[p];
            let ptex = pp.face_id() as usize;
            let mut worst = 0.0f64;
            for i in 0..GRID {
                for j in 0..GRID {
                    let s = R::from_f64(i as f64 / (GRID - 1) as f64);
                    let q = R::from_f64(j as f64 / (GRID - 1) as f64);
                    let (u, v) = pp.unnormalize(s, q);
                    if let (Some(x), Some(y)) =
                        (a.eval_position(ptex, u, v), b.eval_position(ptex, u, v))
                    {
                        let d2: f64 = (0..3).map(|k| (x[k] - y[k]).to_f64().powi(2)).sum();
                        worst = worst.max(d2.sqrt());
                    }
                }
            }
            (face_of_ptex[ptex], worst)
        })
        .collect();
    let mut out = vec![0.0f64; nf];
    for (f, d) in per_patch {
        out[f as usize] = out[f as usize].max(d);
    }
    out
}

/// Refuses an end-cap budget that is not a positive finite number.
fn check_budget(budget: f32) -> Result<()> {
    if budget.is_finite() && budget > 0.0 {
        Ok(())
    } else {
        Err(Error::Unsupported(format!(
            "end-cap tolerance {budget} is not a positive finite number"
        )))
    }
}

/// The limit surface of `base` isolated to level `l` everywhere.
fn surface_at<R: Real>(
    base: &Topology,
    options: &PatchOptions,
    positions: &[[f32; 3]],
    l: u32,
) -> Result<LimitSurface<R>> {
    let o = PatchOptions {
        isolation_level: l,
        ..*options
    };
    Ok(LimitSurface::new(
        PatchTable::build_real(base, &o)?,
        positions,
    ))
}

/// The isolation level of each base face of `base` (positions `positions`) that keeps its end
/// caps within `budget` × the bounding-box diagonal of the limit surface (module
/// documentation), starting from `options.isolation_level`. A budget that is not a positive
/// finite number is refused with [`Error::Unsupported`] before any work.
pub fn choose_isolation<R: Real>(
    base: &Topology,
    options: &PatchOptions,
    positions: &[[f32; 3]],
    budget: f32,
) -> Result<IsolationChoice> {
    check_budget(budget)?;
    let s0 = surface_at::<R>(base, options, positions, options.level_for(base))?;
    choose_from(base, options, positions, budget, &s0)
}

/// [`choose_isolation`] given the surface at the table's own level `s0` (which
/// [`build_for_tolerance`] keeps when no face needs more).
fn choose_from<R: Real>(
    base: &Topology,
    options: &PatchOptions,
    positions: &[[f32; 3]],
    budget: f32,
    s0: &LimitSurface<R>,
) -> Result<IsolationChoice> {
    let nf = base.num_faces();
    let l0 = options.level_for(base);
    let keep = |l: u32| IsolationChoice {
        face_levels: vec![l.min(MAX_ISOLATION_LEVEL) as u8; nf],
        deviation: vec![0.0; nf],
        ratio: vec![1.0; nf],
    };
    let feature: Vec<bool> = (0..nf).map(|f| sharp_feature_face(base, f)).collect();
    let plain = s0.table.counts().gregory == 0 && !feature.contains(&true);
    if l0 >= MAX_ISOLATION_LEVEL || plain {
        return Ok(keep(l0));
    }
    let diag = f64::from(crate::mesh::bbox_diagonal(positions));
    let bound = f64::from(budget) * diag;
    let surface = |l: u32| surface_at::<R>(base, options, positions, l);
    let (s1, s2) = rayon::join(
        || surface(l0 + 1),
        || (l0 + 2 <= MAX_ISOLATION_LEVEL).then(|| surface(l0 + 2)),
    );
    let s1 = s1?;
    let (d0, d1) = match s2 {
        Some(s2) => {
            let s2 = s2?;
            rayon::join(
                || end_cap_differences(s0, &s1, &feature),
                || end_cap_differences(&s1, &s2, &feature),
            )
        }
        None => (end_cap_differences(s0, &s1, &feature), vec![f64::NAN; nf]),
    };
    let mut out = keep(l0);
    for f in 0..nf {
        if d0[f] == 0.0 {
            continue;
        }
        let r = if d1[f].is_nan() {
            RATIO.1
        } else {
            (d1[f] / d0[f]).clamp(RATIO.0, RATIO.1)
        };
        let mut k = 0u32;
        let mut e = d0[f] / (1.0 - r);
        while e > bound && l0 + k < MAX_ISOLATION_LEVEL {
            k += 1;
            e *= r;
        }
        out.face_levels[f] = (l0 + k) as u8;
        out.deviation[f] = if diag > 0.0 { (e / diag) as f32 } else { 0.0 };
        out.ratio[f] = r as f32;
    }
    Ok(out)
}

/// The patch table of `base` with its isolation chosen per region so that the end caps are
/// within `budget` × the bounding-box diagonal of the limit surface ([`choose_isolation`]),
/// and the choice. Where no face needs more than `options.isolation_level`, the table is
/// [`PatchTable::build_real`]'s.
pub fn build_for_tolerance<R: Real>(
    base: &Topology,
    options: &PatchOptions,
    positions: &[[f32; 3]],
    budget: f32,
) -> Result<(PatchTable<R>, IsolationChoice)> {
    check_budget(budget)?;
    let l0 = options.level_for(base);
    let s0 = surface_at::<R>(base, options, positions, l0)?;
    let choice = choose_from(base, options, positions, budget, &s0)?;
    let table = if choice.face_levels.iter().all(|&l| u32::from(l) <= l0) {
        s0.table
    } else {
        PatchTable::build_face_levels(base, options, &choice.face_levels)?
    };
    Ok((table, choice))
}

/// The table a total tolerance `e` tessellates and the tolerance left to its chords: end
/// caps within `e/4` ([`split_tolerance`], [`build_for_tolerance`]) and the chords within
/// `3e/4`; where even the deepest isolation leaves an end cap past `e/4`, the end caps take
/// their estimate, up to [`MAX_END_CAP_SHARE`] of `e`, and the chords the rest. Beyond that,
/// [`TessError::ToleranceUnreachable`] naming `origin`, the base face, its estimate and level.
pub fn table_for_tolerance<R: Real>(
    base: &Topology,
    options: &PatchOptions,
    positions: &[[f32; 3]],
    e: f32,
    origin: &str,
) -> Result<(PatchTable<R>, f32)> {
    let (caps, chords) = split_tolerance(e);
    let (table, choice) = build_for_tolerance(base, options, positions, caps)?;
    let worst = choice.deviation.iter().copied().fold(0.0f32, f32::max);
    if worst > e * MAX_END_CAP_SHARE {
        let face = choice
            .deviation
            .iter()
            .position(|&d| d == worst)
            .unwrap_or(0);
        return Err(TessError::ToleranceUnreachable {
            origin: origin.to_string(),
            tolerance: e,
            budget: e * MAX_END_CAP_SHARE,
            face,
            estimate: worst,
            level: u32::from(choice.face_levels[face]),
        }
        .into());
    }
    Ok((table, if worst > caps { e - worst } else { chords }))
}
