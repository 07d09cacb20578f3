//! Positions of many nearby points of a limit surface, for the tessellation's rate curves and
//! chord checks: a tensor-product patch is collapsed once along the parameter its queries
//! share, and each query then sums four points, or evaluates one cubic.
//!
//! A regular or single-crease patch is `P(s, t) = x₀ + Σ_j Σ_i a_i(s) b_j(t) d_{ji}` with
//! `d = x − x₀` ([`super::eval`]) and curves `a`, `b` that each depend on one parameter
//! ([`crate::patch::basis::patch_curve`]). For a fixed `t` its rows collapse to four points
//! `r_i = Σ_j b_j(t) d_{ji}` (48 products), and `P = x₀ + Σ_i a_i(s) r_i`. Where the curve
//! along `s` is a B-spline ([`crate::patch::basis::CurveShape::BSpline`]: regular patches, and
//! single-crease ones along their crease), its boundary phantoms are folded into the four
//! points and they become the cubic's coefficients in the power basis, so a query is a Horner
//! sum (9 products) instead of the 16 tensor weights and 48 products of
//! [`super::LimitSurface::eval_position`]. Along an isoline of constant `v` every query after
//! the first in a patch reuses the rows; a query with the previous one's `u` collapses the
//! columns `c_j = Σ_i a_i(s) d_{ji}` instead, which the next ones along `v` reuse. The square
//! of the patch map's last leaf ([`super::patch_map::Cell`]) is tested before walking the
//! tree again, and the points of the last patches loaded stay in eight slots, so a query
//! that returns to one skips the gather. Across a semi-sharp crease the curve's weights are
//! formed per query; Gregory patches are summed whole. Points are [`Real::V3`] values (one
//! SSE register for `f32`), summed lane by lane.
//!
//! The sums run in another order than [`super::LimitSurface::eval_position`]'s, so positions
//! agree with it to rounding (a few units in the last place of the patch's extent), not bit
//! for bit; the rate curves and the chord check only compare distances far above that.

use super::eval::LastPatch;
use super::patch_map::{clamp01, square_local, Cell};
use super::LimitSurface;
use crate::patch::basis::{
    patch_curve, patch_curve_shape, patch_position_weights, CurveShape, PatchKind,
};
use crate::real::{Real, Vec3};

/// A collapsed patch: four points along the free parameter, for one value of the fixed one;
/// where the free curve is one cubic (a B-spline, its boundary phantoms folded into the
/// points), its power-basis coefficients instead, so that a query is a Horner sum.
#[derive(Debug, Clone, Copy)]
struct Collapsed<R: Real> {
    /// The fixed parameter's value (the patch's own `t` for rows, `s` for columns).
    at: R,
    /// The four points, relative to the patch's first control point, or the coefficients of
    /// `1, x, x², x³`.
    points: [R::V3; 4],
    /// Whether `points` are coefficients.
    cubic: bool,
}

impl<R: Real> Collapsed<R> {
    /// No collapse (NaN equals no parameter).
    fn none() -> Self {
        Collapsed {
            at: R::from_f64(f64::NAN),
            points: [R::V3::zero(); 4],
            cubic: false,
        }
    }

    /// The collapse at `at` of the points `Σ_m w d` over the terms `term(k, m) = (w, d)`,
    /// `k` the point, `m = 0..4` the fixed direction's index; `shape` is the free curve's.
    #[inline(always)]
    fn new(at: R, shape: CurveShape, term: impl Fn(usize, usize) -> (R, R::V3)) -> Self {
        let mut p = [R::V3::zero(); 4];
        for (k, q) in p.iter_mut().enumerate() {
            for m in 0..4 {
                let (w, d) = term(k, m);
                *q = q.mul_add(w, d);
            }
        }
        let CurveShape::BSpline { low, high } = shape else {
            return Collapsed {
                at,
                points: p,
                cubic: false,
            };
        };
        Collapsed {
            at,
            points: power_basis::<R>(folded::<R>(p, low, high)),
            cubic: true,
        }
    }

    /// The cubic at `x` (a collapse with `cubic` set), relative to the patch's first point.
    #[inline(always)]
    fn cubic_at(&self, x: R) -> R::V3 {
        let [k0, k1, k2, k3] = self.points;
        // `k0 + x (k1 + x (k2 + x k3))`
        k3.scale(x).add(k2).scale(x).add(k1).scale(x).add(k0)
    }

    /// The point at `x` along the free parameter; `weights` gives the free curve's weights
    /// when the collapse is not a cubic.
    #[inline(always)]
    fn along(&self, x: R, weights: impl FnOnce() -> [R; 4]) -> R::V3 {
        if self.cubic {
            self.cubic_at(x)
        } else {
            sum4::<R>(&weights(), &self.points)
        }
    }
}

/// The control points of the last patch found and its last collapses (module documentation).
/// One cache serves one surface.
#[derive(Debug, Clone)]
pub struct CurveCache<R: Real> {
    /// The ptex face of the leaf last found (its patch's data below; `usize::MAX`: none).
    ptex: usize,
    /// Its square as in [`Cell::local`]: `2^level`, `iu`, `iv`.
    square: [R; 3],
    /// Whether the leaf's square is the patch's own (`PatchParam::normalize` then equals
    /// [`Cell::local`], the same operations); else queries are normalized.
    own_square: bool,
    patch: usize,
    x0: R::V3,
    /// The slot of `loaded` holding the patch's points.
    slot: usize,
    /// Points of the patches last loaded, by [`slot_of`] their index: a query that returns
    /// to a patch (the check's samples alternate between the few large patches of a ptex
    /// face; a face's isolines cross the same ones) skips the gather.
    loaded: [LastPatch<R>; SLOTS],
    /// Rows collapsed at a `t` (along `s`); at NaN when none.
    rows: Collapsed<R>,
    /// Columns collapsed at an `s` (along `t`); at NaN when none.
    cols: Collapsed<R>,
    /// The previous query's ptex face and `u` (clamped; NaN: none), in any patch.
    last: (usize, R),
}

/// Patches whose points a cache keeps (a power of two).
const SLOTS: usize = 8;
const _: () = assert!(SLOTS.is_power_of_two() && SLOTS > 1);

/// The slot of patch `p`: the top bits of a multiplicative hash (a ptex face's patches need
/// not be consecutive in the table).
#[inline(always)]
fn slot_of(p: usize) -> usize {
    ((p as u32).wrapping_mul(0x9E37_79B1) >> (32 - SLOTS.trailing_zeros())) as usize
}

impl<R: Real> Default for CurveCache<R> {
    fn default() -> Self {
        Self::new()
    }
}

/// The four points of a uniform cubic B-spline segment with its first (`low`) or last
/// (`high`) point replaced by the phantom `2 P1 − P2` (`2 P2 − P1`), as
/// `fold_phantom_low` and `fold_phantom_high` fold them into the weights.
#[inline(always)]
fn folded<R: Real>(mut p: [R::V3; 4], low: bool, high: bool) -> [R::V3; 4] {
    let two = R::from_f64(2.0);
    let (p1, p2) = (p[1], p[2]);
    if low {
        p[0] = p1.scale(two).sub(p2);
    }
    if high {
        p[3] = p2.scale(two).sub(p1);
    }
    p
}

/// The coefficients of `1, x, x², x³` of the uniform cubic B-spline segment with points `p`.
#[inline(always)]
fn power_basis<R: Real>(p: [R::V3; 4]) -> [R::V3; 4] {
    let [a, b, d, e] = p;
    let (two, half, sixth) = (R::from_f64(2.0), R::from_f64(0.5), R::from_f64(1.0 / 6.0));
    let (three, four) = (R::from_f64(3.0), R::from_f64(4.0));
    [
        // sixth (a + 4 b + d), half (d − a), half (a − 2 b + d), sixth (e − a + 3 (b − d))
        a.add(b.scale(four)).add(d).scale(sixth),
        d.sub(a).scale(half),
        a.sub(b.scale(two)).add(d).scale(half),
        e.sub(a).add(b.sub(d).scale(three)).scale(sixth),
    ]
}

/// `Σ_k w_k p_k` over four points, in order.
#[inline(always)]
fn sum4<R: Real>(w: &[R; 4], p: &[R::V3; 4]) -> R::V3 {
    let mut r = R::V3::zero();
    for (&w, &p) in w.iter().zip(p) {
        r = r.mul_add(w, p);
    }
    r
}

impl<R: Real> CurveCache<R> {
    /// An empty cache.
    pub fn new() -> Self {
        CurveCache {
            ptex: usize::MAX,
            square: [R::ZERO; 3],
            own_square: false,
            patch: usize::MAX,
            x0: R::V3::zero(),
            slot: 0,
            loaded: [LastPatch::new(); SLOTS],
            rows: Collapsed::none(),
            cols: Collapsed::none(),
            last: (usize::MAX, R::from_f64(f64::NAN)),
        }
    }

    /// Forgets the patch and the previous query: the next queries give what they give
    /// through a new cache.
    pub fn reset(&mut self) {
        self.ptex = usize::MAX;
        self.last = (usize::MAX, R::from_f64(f64::NAN));
    }

    /// The position of `surface` at `(u, v)` of ptex face `ptex` (clamped to `[0, 1]`);
    /// `None` in a hole, for a ptex index out of range or a non-finite parameter, as
    /// [`LimitSurface::eval_position`], which it equals to rounding.
    #[inline]
    pub fn position(
        &mut self,
        surface: &LimitSurface<R>,
        ptex: usize,
        u: R,
        v: R,
    ) -> Option<[R; 3]> {
        if !(u.is_finite() && v.is_finite()) {
            return None;
        }
        let (u, v) = (clamp01(u), clamp01(v));
        // The last leaf's square first: nearby queries skip the walk down the tree, and a
        // row or column of a cubic already collapsed is a Horner sum.
        let local = self.local(ptex, u, v);
        if let (Some((s, t)), true) = (local, self.own_square) {
            if self.rows.cubic && self.rows.at == t {
                self.last = (ptex, u);
                return Some(self.x0.add(self.rows.cubic_at(s)).to_array());
            }
            if self.cols.cubic && self.cols.at == s {
                self.last = (ptex, u);
                return Some(self.x0.add(self.cols.cubic_at(t)).to_array());
            }
        }
        self.miss(surface, ptex, u, v, local)
    }

    /// [`Self::position`] past the cached collapses (`local`: the query in the cached leaf's
    /// square, if it lies there): finds and loads the patch if needed, then collapses it.
    #[inline(never)]
    fn miss(
        &mut self,
        surface: &LimitSurface<R>,
        ptex: usize,
        u: R,
        v: R,
        local: Option<(R, R)>,
    ) -> Option<[R; 3]> {
        let local = match local {
            Some(st) => st,
            None => {
                let c = surface.table.patch_map.find_cell(ptex, u, v)?;
                self.load(surface, c);
                self.local(ptex, u, v)?
            }
        };
        // The patch's own parameters: the square's when it is the patch's.
        let param = &surface.table.params[self.patch];
        let (s, t) = if self.own_square {
            local
        } else {
            param.normalize(u, v)
        };
        // A query with the previous one's `u` walks along `v`: columns.
        let walking_v = self.last == (ptex, u);
        self.last = (ptex, u);
        Some(self.collapse(surface, u, v, (s, t), walking_v))
    }

    /// [`Cell::local`] of the cached leaf, from its scale and corner kept as `R`.
    #[inline(always)]
    fn local(&self, ptex: usize, u: R, v: R) -> Option<(R, R)> {
        if ptex != self.ptex {
            return None;
        }
        let [scale, iu, iv] = self.square;
        Some((square_local(u, scale, iu)?, square_local(v, scale, iv)?))
    }

    /// Makes the patch of leaf `c` the cached one, its points gathered relative to its first
    /// unless a slot holds them.
    fn load(&mut self, surface: &LimitSurface<R>, c: Cell) {
        let t = &surface.table;
        let p = c.patch as usize;
        let slot = slot_of(p);
        self.loaded[slot].load(surface, p);
        let x0 = self.loaded[slot].x0();
        let param = &t.params[p];
        self.own_square = param.square() == (c.level, c.iu, c.iv);
        self.square = [
            R::pow2(c.level as i32),
            R::from_f64(f64::from(c.iu)),
            R::from_f64(f64::from(c.iv)),
        ];
        (self.ptex, self.patch, self.x0, self.slot) = (c.ptex as usize, p, x0, slot);
        (self.rows, self.cols) = (Collapsed::none(), Collapsed::none());
    }

    /// The position at `(u, v)` (clamped, in the loaded patch; `(s, tt)` in the patch's own
    /// parameters) by a collapse (columns when `walking_v`, else rows) or, for a Gregory
    /// patch, its whole sum.
    fn collapse(
        &mut self,
        surface: &LimitSurface<R>,
        u: R,
        v: R,
        (s, tt): (R, R),
        walking_v: bool,
    ) -> [R; 3] {
        let t = &surface.table;
        let p = self.patch;
        let l = &self.loaded[self.slot];
        let kind = t.patch_type(p).kind();
        let param = &t.params[p];
        let sharpness = R::from_f32(t.sharpness[p]);
        if matches!(kind, PatchKind::GregoryBasis(_)) {
            // The tensor does not factor.
            let w = patch_position_weights(kind, param, sharpness, u, v);
            return l.sum(&w).to_array();
        }
        let curve = |dir: usize, x: R| {
            patch_curve(kind, param, sharpness, dir, x).map_or([R::ZERO; 4], |w| w.p)
        };
        let rel = if self.rows.at == tt {
            self.rows.along(s, || curve(0, s))
        } else if self.cols.at == s {
            self.cols.along(tt, || curve(1, tt))
        } else if walking_v {
            // Columns at this `s`: c_j = Σ_i a_i d_{ji}.
            let a = curve(0, s);
            let shape = patch_curve_shape(kind, param, sharpness, 1);
            self.cols = Collapsed::new(s, shape, |j, i| (a[i], l.point(4 * j + i)));
            self.cols.along(tt, || curve(1, tt))
        } else {
            // Rows at this `t`: r_i = Σ_j b_j d_{ji}.
            let b = curve(1, tt);
            let shape = patch_curve_shape(kind, param, sharpness, 0);
            self.rows = Collapsed::new(tt, shape, |i, j| (b[j], l.point(4 * j + i)));
            self.rows.along(s, || curve(0, s))
        };
        self.x0.add(rel).to_array()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limit::{PatchOptions, PatchTable};

    /// The largest coordinate difference between the cache's positions and the exact
    /// evaluation's along rows, columns and a scatter of every ptex face of `s` (each walk
    /// through one cache), with the number compared; holes and bad parameters must give
    /// `None` as the evaluation does.
    fn worst_difference<R: Real>(s: &LimitSurface<R>) -> (f64, usize) {
        let n = s.table.ptex_offsets.last().copied().unwrap() as usize;
        let (mut worst, mut compared) = (0.0f64, 0);
        let grid = |k: usize| k as f32 / 16.0;
        for ptex in 0..n {
            let walks: [Vec<(f32, f32)>; 3] = [
                (0..17 * 3)
                    .map(|k| (grid(k % 17), 0.25 * (1 + k / 17) as f32))
                    .collect(),
                (0..17 * 3)
                    .map(|k| (0.25 * (1 + k / 17) as f32, grid(k % 17)))
                    .collect(),
                (0..40)
                    .map(|k| (((k * 7) % 40) as f32 / 39.0, ((k * 13) % 40) as f32 / 39.0))
                    .collect(),
            ];
            for walk in walks {
                let mut cache = CurveCache::new();
                for (u, v) in walk {
                    let (u, v) = (R::from_f32(u), R::from_f32(v));
                    let want = s.eval_position(ptex, u, v);
                    let got = cache.position(s, ptex, u, v);
                    assert_eq!(want.is_some(), got.is_some(), "ptex {ptex} ({u:?}, {v:?})");
                    if let (Some(a), Some(b)) = (want, got) {
                        compared += 1;
                        for c in 0..3 {
                            worst = worst.max((a[c] - b[c]).to_f64().abs());
                        }
                    }
                }
            }
            let nan = R::from_f64(f64::NAN);
            assert_eq!(CurveCache::new().position(s, ptex, nan, R::ZERO), None);
        }
        let half = R::from_f64(0.5);
        assert!(CurveCache::new().position(s, n, half, half).is_none());
        (worst, compared)
    }

    /// Along rows, columns and scattered points of every patch kind (a pole of valence 7 with
    /// a crease, a hole and a boundary: regular patches with and without folded boundaries,
    /// single-crease and Gregory patches), positions agree with the exact evaluation to a few
    /// units in the last place of the surface's extent, in `f32` and in `f64`.
    #[test]
    fn positions_agree_with_the_evaluation() {
        let mesh = crate::shapes::creased_pole(7);
        let t = crate::Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let kinds: std::collections::HashSet<_> = (0..table.num_patches())
            .map(|p| {
                let kind = format!("{:?}", table.patch_type(p).kind());
                let folded = matches!(
                    patch_curve_shape(table.patch_type(p).kind(), &table.params[p], 0.0f32, 0),
                    CurveShape::BSpline { low: true, .. } | CurveShape::BSpline { high: true, .. }
                );
                (kind, folded)
            })
            .collect();
        assert!(kinds.len() >= 4, "{kinds:?}");
        let s = LimitSurface::new(table, &mesh.positions);
        let diag = f64::from(crate::mesh::bbox_diagonal(&s.points));
        let (worst, compared) = worst_difference(&s);
        assert!(compared > 500, "{compared}");
        assert!(
            worst <= 8.0 * f64::from(f32::EPSILON) * diag,
            "{worst:e} of {diag}"
        );
        let s64 = LimitSurface::<f64>::new(
            PatchTable::build_real(&t, &PatchOptions::default()).unwrap(),
            &mesh.positions,
        );
        let (worst, compared) = worst_difference(&s64);
        assert!(compared > 500, "{compared}");
        assert!(worst <= 8.0 * f64::EPSILON * diag, "{worst:e} of {diag}");
    }
}
