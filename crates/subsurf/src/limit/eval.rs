//! Evaluation of the limit surface at any `(ptex face, u, v)`: the patch map finds the patch,
//! [`crate::patch::patch_weights`] gives its basis weights (derivatives already with respect
//! to the ptex face's own `(u, v)`), and the weights are applied to the patch's control points.
//! Weights and sums are `R`: `f32` as on a GPU, or `f64` on a table built with
//! [`PatchTable::build_real`].
//!
//! The weights are applied to the control points relative to the patch's first one,
//!
//! ```text
//! P = x_0 + Σ_k w_k (x_k − x_0),    ∂P/∂u = Σ_k ∂w_k/∂u (x_k − x_0)    (likewise ∂P/∂v),
//! ```
//!
//! which is exact because the position weights sum to 1 and the derivative weights to 0.
//! Weighting `x_k` itself, each `f32` product is rounded by `ε |x_k|` while the derivative is
//! of the patch's size, so a small patch far from the origin loses most of its derivative's
//! digits (normal errors of 3·10⁻³ rad on faces 10⁻³ of their distance from the origin
//! whose edges are 4° apart); with `x_k − x_0` (exact in `f32` for nearby points, Sterbenz
//! 1974) the rounding is relative to the patch.
//!
//! # Local origin
//!
//! A mesh far from the origin relative to its size (georeferenced or architectural
//! coordinates: a car 10⁶ units out) loses its shape when its positions are rounded to `f32`
//! (a 4-unit car moves by up to 3·10⁻² there). The surface then keeps its points relative to
//! a local origin ([`LimitSurface::origin`]: the bounding-box centre, rounded to `R`), formed
//! from the positions as given (`f64` when held so, [`crate::mesh::Positions`]) minus the
//! origin before any rounding, so its derivatives and normals keep the accuracy of a mesh at
//! the origin; evaluated positions are the origin plus the patch's sum, rounded once. A mesh
//! within 1024 bounding-box diagonals of the origin ([`FAR`]), where rounding its positions
//! to `f32` moves them by less than 6·10⁻⁵ of its size, keeps the origin `0` and its points
//! as given (so do the GPU uploads, which read the base positions: a far mesh evaluated on
//! the GPU has the accuracy of its `f32` world coordinates).

use rayon::prelude::*;

use super::patch_map::clamp01;
use super::table::PatchTable;
use crate::patch::{patch_first_weights, patch_position_weights};
use crate::real::{Real, Vec3, VertexData};

/// A point of the limit surface.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LimitPoint<R = f32> {
    /// Position.
    pub p: [R; 3],
    /// `∂P/∂u` (ptex face parameter).
    pub du: [R; 3],
    /// `∂P/∂v`.
    pub dv: [R; 3],
    /// Unit normal `du × dv / |du × dv|`; where that vanishes (a degenerate corner), the
    /// normal a little inside the face; `[0, 0, 0]` if that fails too.
    pub n: [R; 3],
}

/// A patch table with the point array of one set of base positions (`R`: see
/// [`PatchTable`]).
#[derive(Debug, Clone)]
pub struct LimitSurface<R = f32> {
    /// The patches.
    pub(crate) table: PatchTable<R>,
    /// The flat point array ([`PatchTable::points`]), relative to `origin`.
    pub(crate) points: Vec<[R; 3]>,
    /// The local origin (see the module documentation), exactly an `R` value.
    pub(crate) origin: [f64; 3],
    /// The origin in `R` where it is not zero: what each patch load adds to its first point.
    pub(crate) shift: Option<[R; 3]>,
}

impl<R> LimitSurface<R> {
    /// The patches.
    pub fn table(&self) -> &PatchTable<R> {
        &self.table
    }

    /// The flat point array ([`PatchTable::points`]), relative to [`LimitSurface::origin`].
    pub fn points(&self) -> &[[R; 3]] {
        &self.points
    }

    /// The local origin the points are relative to: `[0, 0, 0]` for a mesh within 1024 of
    /// its bounding-box diagonals of the origin, else its bounding-box centre rounded to `R`
    /// (see the module documentation).
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }
}

/// Base positions minus a local origin, in `f64` before the one rounding to `R`.
struct Shifted<'a, V: ?Sized> {
    base: &'a V,
    origin: [f64; 3],
}

impl<V: VertexData<3> + ?Sized> VertexData<3> for Shifted<'_, V> {
    fn num_vertices(&self) -> usize {
        self.base.num_vertices()
    }
    fn vertex<R: Real>(&self, i: usize) -> [R; 3] {
        let x = self.base.vertex_f64(i);
        std::array::from_fn(|c| R::from_f64(x[c] - self.origin[c]))
    }
}

/// Distance from the origin, in bounding-box diagonals, past which a surface takes a local
/// origin (see the module documentation).
pub(crate) const FAR: f64 = 1024.0;

/// The local origin of `positions` for points in `R`: zero within [`FAR`] bounding-box
/// diagonals of the origin (or for no finite positions), else the bounding-box centre
/// rounded to `R`.
fn local_origin<R: Real>(positions: &(impl VertexData<3> + ?Sized)) -> [f64; 3] {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for i in 0..positions.num_vertices() {
        let x = positions.vertex_f64(i);
        if x.iter().all(|c| c.is_finite()) {
            for c in 0..3 {
                lo[c] = lo[c].min(x[c]);
                hi[c] = hi[c].max(x[c]);
            }
        }
    }
    if lo[0] > hi[0] {
        return [0.0; 3];
    }
    let centre: [f64; 3] = std::array::from_fn(|c| 0.5 * (lo[c] + hi[c]));
    let diag = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
    if centre.iter().all(|c| c.abs() <= FAR * diag) {
        return [0.0; 3];
    }
    centre.map(|c| R::from_f64(c).to_f64())
}

use crate::util::vec3::cross;

fn unit<R: Real>(a: [R; 3]) -> Option<[R; 3]> {
    crate::util::vec3::unit(a, R::from_f64(1e-30))
}

impl<R: Real> LimitSurface<R> {
    /// Builds the points of `table` for base positions `positions` (`f32` or `f64` values,
    /// or a mesh's [`crate::mesh::Positions`], read at the precision they were given).
    /// A mesh far from the origin gets a local origin ([`LimitSurface::origin`]).
    pub fn new(table: PatchTable<R>, positions: &(impl VertexData<3> + ?Sized)) -> LimitSurface<R> {
        let origin = local_origin::<R>(positions);
        let shift = (origin != [0.0; 3]).then(|| origin.map(R::from_f64));
        let mut s = LimitSurface {
            table,
            points: Vec::new(),
            origin,
            shift,
        };
        s.set_positions(positions);
        s
    }

    /// Moves the base vertices: the patch points are formed again from `positions` (one per
    /// base vertex), relative to the surface's origin (kept); the table is kept.
    pub fn set_positions(&mut self, positions: &(impl VertexData<3> + ?Sized)) {
        self.points = if self.shift.is_none() {
            self.table.points(positions)
        } else {
            self.table.points(&Shifted {
                base: positions,
                origin: self.origin,
            })
        };
    }

    /// Edits creases ([`PatchTable::apply_sharpness`]) and, where the table changed, forms
    /// the points again from the base `positions`.
    pub fn apply_sharpness(
        &mut self,
        edits: &[super::SharpnessEdit],
        positions: &(impl VertexData<3> + ?Sized),
    ) -> crate::Result<super::EditOutcome> {
        let outcome = self.table.apply_sharpness(edits)?;
        if outcome != super::EditOutcome::Unchanged {
            self.set_positions(positions);
        }
        Ok(outcome)
    }

    /// Position and first derivatives at `(u, v)` of ptex face `ptex`, without the normal;
    /// `None` in a hole, for a ptex index out of range or a non-finite parameter. `u` and `v`
    /// are clamped to `[0, 1]`.
    pub fn eval_raw(&self, ptex: usize, u: R, v: R) -> Option<LimitPoint<R>> {
        self.eval_raw_in(&mut LastPatch::new(), (ptex, u, v))
    }

    /// [`Self::eval_raw`] through `last`: a query in the patch `last` holds skips the gather
    /// (the same points, the same sums, bit for bit).
    pub(crate) fn eval_raw_in(
        &self,
        last: &mut LastPatch<R>,
        q: (usize, R, R),
    ) -> Option<LimitPoint<R>> {
        let (p, u, v) = self.locate(q)?;
        last.load(self, p);
        let t = &self.table;
        let kind = t.patch_type(p).kind();
        let [wp, wu, wv] =
            patch_first_weights(kind, &t.params[p], R::from_f32(t.sharpness[p]), u, v);
        // Relative to the first control point (see the module documentation).
        let [mut p, mut du, mut dv] = [R::V3::zero(); 3];
        for (k, &d) in last.points().iter().enumerate() {
            p = p.mul_add(wp[k], d);
            du = du.mul_add(wu[k], d);
            dv = dv.mul_add(wv[k], d);
        }
        Some(LimitPoint {
            p: p.add(last.x0()).to_array(),
            du: du.to_array(),
            dv: dv.to_array(),
            n: [R::ZERO; 3],
        })
    }

    /// The position of [`LimitSurface::eval_raw`] alone (the same sums, bit for bit), for
    /// callers that need no derivatives.
    pub fn eval_position(&self, ptex: usize, u: R, v: R) -> Option<[R; 3]> {
        let (p, u, v) = self.locate((ptex, u, v))?;
        let mut last = LastPatch::new();
        last.load(self, p);
        let t = &self.table;
        let kind = t.patch_type(p).kind();
        let w = patch_position_weights(kind, &t.params[p], R::from_f32(t.sharpness[p]), u, v);
        Some(last.sum(&w).to_array())
    }

    /// The patch of query `(ptex, u, v)` and its parameters clamped to `[0, 1]`; `None` in
    /// a hole, for a ptex index out of range or a non-finite parameter.
    #[inline]
    fn locate(&self, (ptex, u, v): (usize, R, R)) -> Option<(usize, R, R)> {
        if !(u.is_finite() && v.is_finite()) {
            return None;
        }
        let (u, v) = (clamp01(u), clamp01(v));
        let p = self.table.patch_map.find(ptex, u, v)? as usize;
        Some((p, u, v))
    }

    /// Position, derivatives and normal at `(u, v)` of ptex face `ptex`.
    pub fn eval(&self, ptex: usize, u: R, v: R) -> Option<LimitPoint<R>> {
        self.eval_in(&mut LastPatch::new(), (ptex, u, v))
    }

    /// [`Self::eval`] through `last` ([`Self::eval_raw_in`]).
    fn eval_in(&self, last: &mut LastPatch<R>, q: (usize, R, R)) -> Option<LimitPoint<R>> {
        let (ptex, u, v) = q;
        let mut r = self.eval_raw_in(last, q)?;
        let (u, v) = (clamp01(u), clamp01(v));
        let mut fallback = || {
            // Step a little towards the face centre, where the tangent plane is regular.
            let (h, s) = (R::from_f64(0.5), R::from_f64(1e-3));
            let (a, b) = (u + (h - u) * s, v + (h - v) * s);
            let q = self.eval_raw_in(last, (ptex, a, b))?;
            unit(cross(q.du, q.dv))
        };
        r.n = match unit(cross(r.du, r.dv)) {
            Some(n) => n,
            None => fallback().unwrap_or([R::ZERO; 3]),
        };
        Some(r)
    }

    /// [`LimitSurface::eval`] for many `(ptex, u, v)` in parallel (rayon), in chunks that
    /// each keep the patch they last evaluated (neighbouring queries mostly share patches).
    pub fn eval_batch(&self, queries: &[(u32, R, R)]) -> Vec<Option<LimitPoint<R>>> {
        let mut out = vec![None; queries.len()];
        out.par_chunks_mut(BATCH)
            .zip(queries.par_chunks(BATCH))
            .for_each(|(out, q)| self.eval_chunk(q, |i, e| out[i] = Some(e)));
        out
    }

    /// Each query of `queries` (one chunk of a batch of [`BATCH`]) evaluated as
    /// [`LimitSurface::eval`], in order, keeping the patch last evaluated: `put(i, point)` for
    /// query `i`, unless it is in a hole.
    pub(crate) fn eval_chunk(
        &self,
        queries: &[(u32, R, R)],
        mut put: impl FnMut(usize, LimitPoint<R>),
    ) {
        let mut last = LastPatch::new();
        for (i, &(f, u, v)) in queries.iter().enumerate() {
            if let Some(e) = self.eval_in(&mut last, (f as usize, u, v)) {
                put(i, e);
            }
        }
    }
}

/// Queries per chunk of a batch evaluation ([`LimitSurface::eval_chunk`]).
pub(crate) const BATCH: usize = 512;

/// The points of the patch a walk last evaluated, relative to its first ([`LastPatch::load`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LastPatch<R: Real> {
    /// The patch (`usize::MAX`: none).
    patch: usize,
    x0: R::V3,
    d: [R::V3; 20],
    n: usize,
}

impl<R: Real> LastPatch<R> {
    pub(crate) fn new() -> Self {
        LastPatch {
            patch: usize::MAX,
            x0: R::V3::zero(),
            d: [R::V3::zero(); 20],
            n: 0,
        }
    }

    /// Holds patch `p` of `surface`: unless it is the one held, its control points are
    /// gathered relative to its first (`x − x₀`, as [`LimitSurface::eval_raw`] sums them).
    #[inline(always)]
    pub(crate) fn load(&mut self, surface: &LimitSurface<R>, p: usize) {
        if self.patch == p {
            return;
        }
        let cvs = surface.table.patch_cvs(p);
        assert!(
            cvs.len() <= self.d.len(),
            "patch {p} has {} points",
            cvs.len()
        );
        let x0 = R::V3::load(&surface.points, cvs[0] as usize);
        for (d, &cv) in self.d.iter_mut().zip(cvs) {
            *d = R::V3::load(&surface.points, cv as usize).sub(x0);
        }
        // The first point in the surface's coordinates: the origin added once, here.
        let x0 = match &surface.shift {
            None => x0,
            Some(o) => x0.add(R::V3::load(std::slice::from_ref(o), 0)),
        };
        (self.patch, self.x0, self.n) = (p, x0, cvs.len());
    }

    /// The held patch's first point (in the surface's coordinates, the origin added).
    #[inline(always)]
    pub(crate) fn x0(&self) -> R::V3 {
        self.x0
    }

    /// The held patch's points relative to its first.
    #[inline(always)]
    pub(crate) fn points(&self) -> &[R::V3] {
        &self.d[..self.n]
    }

    /// Point `k` of the held patch relative to its first (`k` below its point count).
    #[inline(always)]
    pub(crate) fn point(&self, k: usize) -> R::V3 {
        self.d[k]
    }

    /// `x₀ + Σ_k w_k d_k` over the held patch's points, in order (as
    /// [`LimitSurface::eval_raw`] sums positions).
    #[inline(always)]
    pub(crate) fn sum(&self, w: &[R]) -> R::V3 {
        let mut r = R::V3::zero();
        for (&w, &d) in w.iter().zip(self.points()) {
            r = r.mul_add(w, d);
        }
        r.add(self.x0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limit::PatchOptions;

    /// Positions and derivatives summed as [`Real::V3`] values (SSE lanes for `f32`) equal,
    /// bit for bit, the component loops `x₀ + Σ w (x − x₀)` in the same order, on every patch
    /// kind (a pole of valence 7 with a crease, a hole and a boundary) at a scatter of points
    /// including the ptex faces' corners and sides.
    #[test]
    fn lane_sums_equal_component_loops() {
        let mesh = crate::shapes::creased_pole(7);
        let t = crate::Topology::new(&mesh).unwrap();
        let s = LimitSurface::new(
            PatchTable::build(&t, &PatchOptions::default()).unwrap(),
            &mesh.positions,
        );
        let tab = &s.table;
        let bits = |a: [f32; 3]| a.map(f32::to_bits);
        let mut compared = 0;
        for ptex in 0..tab.num_ptex_faces() {
            for k in 0..49 {
                let (u, v) = ((k % 7) as f32 / 6.0, (k / 7) as f32 / 6.0);
                let Some(p) = tab.patch_map.find(ptex, u, v) else {
                    assert!(s.eval_position(ptex, u, v).is_none());
                    continue;
                };
                let p = p as usize;
                let kind = tab.patch_type(p).kind();
                let sharp = tab.sharpness[p];
                let [wp, wu, wv] = patch_first_weights(kind, &tab.params[p], sharp, u, v);
                let cvs = tab.patch_cvs(p);
                let x0 = s.points[cvs[0] as usize];
                let mut want = [[0.0f32; 3]; 3];
                for (k, &cv) in cvs.iter().enumerate() {
                    let x = s.points[cv as usize];
                    for c in 0..3 {
                        let d = x[c] - x0[c];
                        want[0][c] += wp[k] * d;
                        want[1][c] += wu[k] * d;
                        want[2][c] += wv[k] * d;
                    }
                }
                for c in 0..3 {
                    want[0][c] += x0[c];
                }
                let got = s.eval_raw(ptex, u, v).unwrap();
                assert_eq!(bits(got.p), bits(want[0]), "ptex {ptex} ({u}, {v})");
                assert_eq!(bits(got.du), bits(want[1]), "ptex {ptex} ({u}, {v})");
                assert_eq!(bits(got.dv), bits(want[2]), "ptex {ptex} ({u}, {v})");
                let pos = s.eval_position(ptex, u, v).unwrap();
                let w = patch_position_weights(kind, &tab.params[p], sharp, u, v);
                let mut only = [0.0f32; 3];
                for (k, &cv) in cvs.iter().enumerate() {
                    let x = s.points[cv as usize];
                    for c in 0..3 {
                        only[c] += w[k] * (x[c] - x0[c]);
                    }
                }
                for c in 0..3 {
                    only[c] += x0[c];
                }
                assert_eq!(bits(pos), bits(only), "ptex {ptex} ({u}, {v})");
                compared += 1;
            }
        }
        assert!(compared > 250, "{compared}");
        // A batch walks its chunks through one kept patch: the same bits as each query alone
        // (queries in order, so neighbours share patches, and scattered).
        let n = tab.num_ptex_faces() as u32;
        let queries: Vec<(u32, f32, f32)> = (0..n * 49)
            .map(|k| (k / 49, (k % 7) as f32 / 6.0, ((k / 7) % 7) as f32 / 6.0))
            .chain((0..200).map(|k| ((k * 7) % n, (k % 13) as f32 / 12.0, 0.3)))
            .collect();
        let batch = s.eval_batch(&queries);
        for (&(f, u, v), got) in queries.iter().zip(&batch) {
            let want = s.eval(f as usize, u, v);
            assert_eq!(want.is_some(), got.is_some());
            if let (Some(a), Some(b)) = (want, got) {
                for (x, y) in [(a.p, b.p), (a.du, b.du), (a.dv, b.dv), (a.n, b.n)] {
                    assert_eq!(bits(x), bits(y), "ptex {f} ({u}, {v})");
                }
            }
        }
    }
}
