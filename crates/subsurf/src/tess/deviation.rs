//! The geometric deviation of a triangle mesh from a limit surface: the two-sided Hausdorff
//! distance, Metro-style (Cignoni, Rocchini & Scopigno 1998), as a fraction of the surface's
//! bounding-box diagonal.
//!
//! - **Mesh to surface**: points sampled on every triangle (a barycentric grid, vertices and
//!   edges included) are projected onto the surface by Gauss-Newton steps on the limit
//!   surface (clamped to a ptex face) to their foot point; the distance to the foot point is
//!   the sample's deviation. A tessellation that knows where its triangles came from (their
//!   ptex face and corners' `(u, v)`, as [`super::AdaptivePlan::triangle_uv`]) starts each
//!   sample from its own parameters; only where that foot point would leave the ptex face,
//!   or a dense surface sample lies nearer than it, are the samples nearest to the point
//!   tried as well (the best of each ptex face among the [`SEEDS`] nearest). A triangle
//!   without parameters starts from those seeds alone.
//! - **Surface to mesh**: the same dense surface samples, each at its exact distance to the
//!   nearest triangle (a uniform grid of triangle bounding boxes, searched ring by ring until
//!   no nearer triangle can exist).
//!
//! The deviation is the largest over both sample sets: it sees where the mesh is far from the
//! surface *and* where the surface is far from the mesh (a hole, a missing region), wherever
//! the nearest point is — not the distance at the same `(u, v)`, which counts a tangential
//! drift of the parametrization as error.
//!
//! A [`DeviationReference`] keeps the surface samples and their grid, so that many
//! tessellations of one surface (candidates at several rates) are measured against one set;
//! [`deviation`] builds one for a single measurement.

use rayon::prelude::*;

use crate::limit::eval::LastPatch;
use crate::limit::LimitSurface;
use crate::real::Real;
use crate::util::vec3::{add, dot, scale, sub};

/// How densely [`deviation`] samples the two sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeviationOptions {
    /// Surface samples per side of every ptex face (`(n + 1)²` per ptex face).
    pub surface_samples: usize,
    /// Sample intervals per triangle edge (`(k + 1)(k + 2) / 2` points per triangle).
    pub triangle_samples: usize,
}

impl Default for DeviationOptions {
    fn default() -> Self {
        DeviationOptions {
            surface_samples: 16,
            triangle_samples: 4,
        }
    }
}

/// The two one-sided deviations and their maximum, as fractions of the surface's
/// bounding-box diagonal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deviation {
    /// Largest distance from a mesh sample to the surface.
    pub mesh_to_surface: f64,
    /// Largest distance from a surface sample to the mesh.
    pub surface_to_mesh: f64,
    /// Mean distance from the mesh samples to the surface.
    pub mean_mesh_to_surface: f64,
    /// The bounding-box diagonal of the surface samples (the unit of the other fields).
    pub diagonal: f64,
    /// The mesh sample furthest from the surface (world units; the origin without
    /// triangles).
    pub worst_mesh_point: [f64; 3],
    /// The surface sample furthest from the mesh (world units; the origin without surface
    /// samples).
    pub worst_surface_point: [f64; 3],
}

impl Deviation {
    /// The two-sided (Hausdorff) deviation: the larger one-sided one.
    pub fn hausdorff(&self) -> f64 {
        self.mesh_to_surface.max(self.surface_to_mesh)
    }
}

type P = [f64; 3];

/// Surface samples a mesh sample is projected from where its own parameters do not do (the
/// best of each ptex face among them).
pub const SEEDS: usize = 8;

/// Gauss-Newton steps at most per projection.
const STEPS: usize = 12;

/// How far (in ptex parameters) a foot point's next step may point past the face's side
/// before the point counts as leaving the face.
const OUTSIDE: f64 = 1e-6;

fn widen<R: Real>(p: [R; 3]) -> P {
    p.map(Real::to_f64)
}

/// A uniform grid over a box, `dims` cells per axis, holding item indices per cell (CSR).
struct Grid {
    lo: P,
    cell: f64,
    dims: [usize; 3],
    offsets: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// A grid over `lo..hi` with about `target` cells, holding each item in the cells its
    /// box `boxes[i]` overlaps.
    fn new(lo: P, hi: P, target: usize, boxes: &[(P, P)]) -> Grid {
        let ext = sub(hi, lo);
        let vol = ext.iter().map(|e| e.max(1e-12)).product::<f64>();
        let cell = (vol / target.max(1) as f64).cbrt().max(1e-12);
        let dims = ext.map(|e| ((e / cell).ceil() as usize).clamp(1, 1024));
        let mut grid = Grid {
            lo,
            cell,
            dims,
            offsets: Vec::new(),
            items: Vec::new(),
        };
        let n = dims[0] * dims[1] * dims[2];
        let mut counts = vec![0u32; n + 1];
        let ranges: Vec<([usize; 3], [usize; 3])> = boxes
            .iter()
            .map(|(a, b)| (grid.coords(*a), grid.coords(*b)))
            .collect();
        for (a, b) in &ranges {
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        counts[grid.index([x, y, z]) + 1] += 1;
                    }
                }
            }
        }
        for i in 0..n {
            counts[i + 1] += counts[i];
        }
        let mut next = counts.clone();
        grid.items = vec![0; counts[n] as usize];
        for (item, (a, b)) in ranges.iter().enumerate() {
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        let c = grid.index([x, y, z]);
                        grid.items[next[c] as usize] = item as u32;
                        next[c] += 1;
                    }
                }
            }
        }
        grid.offsets = counts;
        grid
    }

    fn coords(&self, p: P) -> [usize; 3] {
        std::array::from_fn(|k| {
            let c = ((p[k] - self.lo[k]) / self.cell).floor();
            (c.max(0.0) as usize).min(self.dims[k] - 1)
        })
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// Whether an item lies within `r2` (a squared distance, by `dist`) of `p`: the cells
    /// that box overlaps are searched.
    fn any_within(&self, p: P, r2: f64, dist: impl Fn(u32) -> f64) -> bool {
        let r = r2.sqrt();
        let a = self.coords(sub(p, [r; 3]));
        let b = self.coords(add(p, [r; 3]));
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                for x in a[0]..=b[0] {
                    let cell = self.index([x, y, z]);
                    let (s, e) = (self.offsets[cell], self.offsets[cell + 1]);
                    if self.items[s as usize..e as usize]
                        .iter()
                        .any(|&i| dist(i) < r2)
                    {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// The item nearest to `p` by `dist` (a squared distance); `None` when the grid is
    /// empty.
    fn nearest(&self, p: P, dist: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        self.nearest_k(p, 1, dist).first().copied()
    }

    /// The `k` items nearest to `p` by `dist` (a squared distance), nearest first: the cells
    /// are searched ring by ring around `p`'s cell until no cell outside can hold a nearer
    /// item than the `k`-th (`p` is nearer to the searched box's walls than that item).
    fn nearest_k(&self, p: P, k: usize, dist: impl Fn(u32) -> f64) -> Vec<(u32, f64)> {
        let c = self.coords(p);
        let mut best: Vec<(u32, f64)> = Vec::with_capacity(k + 1);
        let max_ring = self.dims.iter().copied().max().unwrap_or(1);
        for ring in 0..=max_ring {
            let lo = c.map(|x| x.saturating_sub(ring));
            let hi: [usize; 3] = std::array::from_fn(|a| (c[a] + ring).min(self.dims[a] - 1));
            for z in lo[2]..=hi[2] {
                for y in lo[1]..=hi[1] {
                    for x in lo[0]..=hi[0] {
                        let on_ring = [x, y, z]
                            .iter()
                            .zip(&c)
                            .any(|(&a, &b)| a.abs_diff(b) == ring);
                        if !on_ring {
                            continue;
                        }
                        let cell = self.index([x, y, z]);
                        let (a, b) = (self.offsets[cell], self.offsets[cell + 1]);
                        for &item in &self.items[a as usize..b as usize] {
                            let d = dist(item);
                            if best.len() < k || d < best[best.len() - 1].1 {
                                let at = best.partition_point(|e| e.1 <= d);
                                best.insert(at, (item, d));
                                best.truncate(k);
                            }
                        }
                    }
                }
            }
            // Every cell outside the box searched lies beyond one of its walls (none beyond
            // the grid's own sides).
            let mut reach = f64::INFINITY;
            for a in 0..3 {
                if lo[a] > 0 {
                    reach = reach.min(p[a] - (self.lo[a] + lo[a] as f64 * self.cell));
                }
                if hi[a] + 1 < self.dims[a] {
                    reach = reach.min(self.lo[a] + (hi[a] + 1) as f64 * self.cell - p[a]);
                }
            }
            if reach == f64::INFINITY
                || (best.len() == k && best[k - 1].1 <= reach.max(0.0).powi(2))
            {
                break;
            }
        }
        best
    }
}

/// Squared distance from `p` to triangle `abc` (Ericson 2005, "Real-Time Collision
/// Detection", 5.1.5).
fn point_triangle_d2(p: P, a: P, b: P, c: P) -> f64 {
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let at = |q: P| dot(sub(p, q), sub(p, q));
    if d1 <= 0.0 && d2 <= 0.0 {
        return at(a);
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return at(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return at(add(a, scale(d1 / (d1 - d3), ab)));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return at(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return at(add(a, scale(d2 / (d2 - d6), ac)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return at(add(b, scale(w, sub(c, b))));
    }
    let denom = va + vb + vc;
    if denom.abs() < 1e-300 {
        // A degenerate (zero-area) triangle: its three edges.
        return [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(s, e)| {
                let d = sub(e, s);
                let t = (dot(sub(p, s), d) / dot(d, d).max(1e-300)).clamp(0.0, 1.0);
                at(add(s, scale(t, d)))
            })
            .fold(f64::INFINITY, f64::min);
    }
    let (v, w) = (vb / denom, vc / denom);
    at(add(a, add(scale(v, ab), scale(w, ac))))
}

/// A Gauss-Newton projection's end: the squared distance reached and whether the foot point
/// would leave the ptex face (its next step points past a side it is clamped to).
#[derive(Debug, Clone, Copy)]
struct Foot {
    d2: f64,
    leaves: bool,
}

/// The foot point of `q` on ptex face `ptex` of `surface`, from `(u, v)`: Gauss-Newton steps
/// on `|S(u, v) - q|²`, clamped to the face (through `last`, the patch last evaluated).
fn project<R: Real>(
    surface: &LimitSurface<R>,
    last: &mut LastPatch<R>,
    q: P,
    ptex: usize,
    mut u: f64,
    mut v: f64,
) -> Foot {
    let mut at = |u: f64, v: f64| surface.eval_raw_in(last, (ptex, R::from_f64(u), R::from_f64(v)));
    let Some(mut s) = at(u, v) else {
        return Foot {
            d2: f64::INFINITY,
            leaves: false,
        };
    };
    let mut best = {
        let d = sub(q, widen(s.p));
        dot(d, d)
    };
    for step in 0..=STEPS {
        let (p, du, dv) = (widen(s.p), widen(s.du), widen(s.dv));
        let r = sub(q, p);
        let (a, b, c) = (dot(du, du), dot(du, dv), dot(dv, dv));
        let (g0, g1) = (dot(du, r), dot(dv, r));
        let det = a * c - b * b;
        if det.abs() <= 1e-30 * (a * c).max(1e-300) {
            break;
        }
        let (mut su, mut sv) = ((c * g0 - b * g1) / det, (a * g1 - b * g0) / det);
        // The step from the point reached: past a side of the face, the foot point lies in
        // a neighbouring one.
        let outside = |x: f64| !(-OUTSIDE..=1.0 + OUTSIDE).contains(&x);
        let leaves = outside(u + su) || outside(v + sv);
        if step == STEPS {
            return Foot { d2: best, leaves };
        }
        let mut improved = false;
        // Halve the step until it does not move away.
        for _ in 0..8 {
            let (nu, nv) = ((u + su).clamp(0.0, 1.0), (v + sv).clamp(0.0, 1.0));
            if let Some(t) = at(nu, nv) {
                let d = sub(q, widen(t.p));
                let d2 = dot(d, d);
                if d2 < best {
                    (best, u, v, s, improved) = (d2, nu, nv, t, true);
                    break;
                }
            }
            su *= 0.5;
            sv *= 0.5;
        }
        if !improved {
            return Foot { d2: best, leaves };
        }
        if su * su + sv * sv < 1e-24 {
            // Converged: `leaves` of the point before this last, tiny step.
            return Foot { d2: best, leaves };
        }
    }
    Foot {
        d2: best,
        leaves: false,
    }
}

/// A triangle's ptex face and its corners' `(u, v)` there (as
/// [`super::AdaptivePlan::triangle_uv`]).
pub type TriangleParameters = (u32, [[f32; 2]; 3]);

/// The reference side of [`deviation`]: a limit surface with its dense samples and their
/// grid, built once and kept for every mesh measured against it (module documentation).
pub struct DeviationReference<'a, R: Real = f64> {
    surface: &'a LimitSurface<R>,
    options: DeviationOptions,
    /// The surface samples and their `(ptex, u, v)`.
    samples: Vec<P>,
    sample_q: Vec<(u32, f64, f64)>,
    /// The samples' bounding box and its diagonal.
    lo: P,
    hi: P,
    diagonal: f64,
    /// The samples by cell.
    grid: Grid,
}

impl<R: Real> std::fmt::Debug for DeviationReference<'_, R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DeviationReference")
            .field("options", &self.options)
            .field("samples", &self.samples.len())
            .field("diagonal", &self.diagonal)
            .finish_non_exhaustive()
    }
}

impl<'a, R: Real> DeviationReference<'a, R> {
    /// The samples of `surface` at `options.surface_samples` per ptex-face side, and their
    /// grid.
    pub fn new(surface: &'a LimitSurface<R>, options: &DeviationOptions) -> Self {
        let n = options.surface_samples.max(1);
        let map = surface.table().patch_map();
        let queries: Vec<(u32, R, R)> = (0..map.num_ptex())
            .filter(|&f| map.has_patches(f))
            .flat_map(|f| {
                (0..=n).flat_map(move |j| {
                    (0..=n).map(move |i| {
                        let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                        (f as u32, R::from_f64(u), R::from_f64(v))
                    })
                })
            })
            .collect();
        let evals = surface.eval_batch(&queries);
        let (samples, sample_q): (Vec<P>, Vec<(u32, f64, f64)>) = evals
            .iter()
            .zip(&queries)
            .filter_map(|(e, &(f, u, v))| e.map(|e| (widen(e.p), (f, u.to_f64(), v.to_f64()))))
            .unzip();
        let (lo, hi) = bounds(samples.iter().copied());
        let diagonal = if samples.is_empty() {
            0.0
        } else {
            dot(sub(hi, lo), sub(hi, lo)).sqrt()
        };
        let boxes: Vec<(P, P)> = samples.iter().map(|&p| (p, p)).collect();
        let grid = if samples.is_empty() {
            Grid::new([0.0; 3], [0.0; 3], 1, &[])
        } else {
            Grid::new(lo, hi, samples.len() / 4 + 1, &boxes)
        };
        DeviationReference {
            surface,
            options: *options,
            samples,
            sample_q,
            lo,
            hi,
            diagonal,
            grid,
        }
    }

    /// The surface measured against.
    pub fn surface(&self) -> &'a LimitSurface<R> {
        self.surface
    }

    /// The bounding-box diagonal of the surface samples (the unit of every [`Deviation`]).
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// Number of surface samples.
    pub fn num_samples(&self) -> usize {
        self.samples.len()
    }

    /// The deviation of the triangle mesh (`positions`, `triangles` in any orientation)
    /// from the surface (module documentation). `parameters`, one per triangle where given
    /// (its ptex face and corners' `(u, v)` on this surface's ptex faces), starts each
    /// triangle sample's projection from its own parameters. A mesh without triangles is
    /// infinitely far from every surface sample.
    ///
    /// # Panics
    /// When `parameters` is given with another length than `triangles`.
    pub fn measure(
        &self,
        positions: &[[f32; 3]],
        triangles: &[[u32; 3]],
        parameters: Option<&[TriangleParameters]>,
    ) -> Deviation {
        if let Some(p) = parameters {
            assert_eq!(
                p.len(),
                triangles.len(),
                "one parameter triple per triangle"
            );
        }
        let unit = if self.diagonal > 0.0 {
            1.0 / self.diagonal
        } else {
            1.0
        };
        let verts: Vec<P> = positions.iter().map(|&p| widen(p)).collect();
        let (vlo, vhi) = bounds(verts.iter().copied());
        let lo: P = std::array::from_fn(|k| self.lo[k].min(vlo[k]));
        let hi: P = std::array::from_fn(|k| self.hi[k].max(vhi[k]));

        // Surface to mesh: exact nearest-triangle distances.
        let tri_boxes: Vec<(P, P)> = triangles
            .iter()
            .map(|t| bounds(t.iter().map(|&i| verts[i as usize])))
            .collect();
        let tri_grid = Grid::new(lo, hi, triangles.len(), &tri_boxes);
        let tri_d2 = |p: P, t: u32| {
            let [a, b, c] = triangles[t as usize].map(|i| verts[i as usize]);
            point_triangle_d2(p, a, b, c)
        };
        let (surface_to_mesh, worst_surface_point) = self
            .samples
            .par_iter()
            .map(|&p| {
                let d = tri_grid
                    .nearest(p, |t| tri_d2(p, t))
                    .map_or(f64::INFINITY, |(_, d2)| d2.sqrt());
                (d, p)
            })
            .reduce(|| (0.0, [0.0; 3]), farther);

        // Mesh to surface: triangle samples projected onto the surface.
        let k = self.options.triangle_samples.max(1);
        let bary: Vec<(f64, f64)> = (0..=k)
            .flat_map(|i| (0..=k - i).map(move |j| (i as f64 / k as f64, j as f64 / k as f64)))
            .collect();
        let (sum, count, mesh_to_surface, worst_mesh_point) = triangles
            .par_iter()
            .enumerate()
            .map(|(n, t)| {
                let [a, b, c] = t.map(|i| verts[i as usize]);
                let own = parameters.map(|p| p[n]);
                let mut last = LastPatch::new();
                let (mut sum, mut worst) = (0.0, (0.0f64, [0.0; 3]));
                for &(s, r) in &bary {
                    let q = add(a, add(scale(s, sub(b, a)), scale(r, sub(c, a))));
                    let d = self.distance(q, own, s, r, &mut last).sqrt();
                    sum += d;
                    worst = farther(worst, (d, q));
                }
                (sum, bary.len(), worst.0, worst.1)
            })
            .reduce(
                || (0.0, 0, 0.0, [0.0; 3]),
                |x, y| {
                    let (d, p) = farther((x.2, x.3), (y.2, y.3));
                    (x.0 + y.0, x.1 + y.1, d, p)
                },
            );
        Deviation {
            mesh_to_surface: mesh_to_surface * unit,
            surface_to_mesh: surface_to_mesh * unit,
            mean_mesh_to_surface: if count > 0 {
                sum / count as f64 * unit
            } else {
                0.0
            },
            diagonal: self.diagonal,
            worst_mesh_point,
            worst_surface_point,
        }
    }

    /// The squared distance from mesh sample `q` (at barycentric `(s, r)` of a triangle with
    /// parameters `own`, where known) to the surface.
    fn distance(
        &self,
        q: P,
        own: Option<TriangleParameters>,
        s: f64,
        r: f64,
        last: &mut LastPatch<R>,
    ) -> f64 {
        let sample_d2 = |i: u32| {
            let d = sub(q, self.samples[i as usize]);
            dot(d, d)
        };
        let mut d2 = f64::INFINITY;
        if let Some((ptex, c)) = own {
            let w = [1.0 - s - r, s, r];
            let at = |k: usize| (0..3).map(|i| w[i] * f64::from(c[i][k])).sum::<f64>();
            let foot = project(self.surface, last, q, ptex as usize, at(0), at(1));
            if !foot.leaves && foot.d2.is_finite() && !self.grid.any_within(q, foot.d2, sample_d2) {
                return foot.d2;
            }
            d2 = foot.d2;
        }
        // The nearest samples, projected from the best one of each ptex face among them
        // (the sample's own face again too, from another start): at a vertex shared by
        // several ptex faces the foot point may lie in any of them.
        let near = self.grid.nearest_k(q, SEEDS, sample_d2);
        d2 = d2.min(near.first().map_or(f64::INFINITY, |e| e.1));
        let mut faces: Vec<u32> = Vec::with_capacity(SEEDS);
        for &(i, _) in &near {
            let (f, u, v) = self.sample_q[i as usize];
            if !faces.contains(&f) {
                faces.push(f);
                d2 = d2.min(project(self.surface, last, q, f as usize, u, v).d2);
            }
        }
        d2
    }
}

/// The farther of two `(distance, point)` pairs (the first on a tie, NaN counting farthest).
fn farther(a: (f64, P), b: (f64, P)) -> (f64, P) {
    if b.0 > a.0 || (b.0.is_nan() && !a.0.is_nan()) {
        b
    } else {
        a
    }
}

/// The bounding box of `points` (inverted for none).
fn bounds(points: impl Iterator<Item = P>) -> (P, P) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The deviation of the triangle mesh (`positions`, counter-clockwise or not, `triangles`)
/// from `surface` (module documentation), every triangle sample projected from the surface
/// samples nearest to it. A mesh without triangles is infinitely far from every surface
/// sample. To measure several meshes against one surface, keep a [`DeviationReference`].
pub fn deviation<R: Real>(
    surface: &LimitSurface<R>,
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    options: &DeviationOptions,
) -> Deviation {
    DeviationReference::new(surface, options).measure(positions, triangles, None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limit::{PatchOptions, PatchTable};
    use crate::Topology;

    fn surface(mesh: &crate::Mesh) -> LimitSurface<f64> {
        let t = Topology::new(mesh).unwrap();
        let table = PatchTable::build_real(&t, &PatchOptions::default()).unwrap();
        LimitSurface::new(table, &mesh.positions)
    }

    #[test]
    fn point_triangle_distance_in_every_region() {
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let d = |p: P| point_triangle_d2(p, a, b, c).sqrt();
        assert!((d([0.2, 0.2, 0.5]) - 0.5).abs() < 1e-15); // interior
        assert!((d([-1.0, -1.0, 0.0]) - 2f64.sqrt()).abs() < 1e-15); // vertex a
        assert!((d([0.5, -2.0, 0.0]) - 2.0).abs() < 1e-15); // edge ab
        assert!((d([1.0, 1.0, 0.0]) - 0.5f64.sqrt()).abs() < 1e-15); // edge bc
        assert!((d([3.0, 0.0, 4.0]) - (4.0f64 + 16.0).sqrt()).abs() < 1e-15); // vertex b
    }

    /// A uniform tessellation's deviation falls as the square of the rate (chord height),
    /// and both sides agree for a closed surface tessellated everywhere.
    #[test]
    fn uniform_tessellations_converge_quadratically() {
        let s = surface(&crate::shapes::cube());
        let dev = |n: usize| {
            let t = s.tessellate(n).unwrap();
            deviation(
                &s,
                &t.positions,
                &t.triangles(),
                &DeviationOptions::default(),
            )
        };
        let (coarse, fine) = (dev(4), dev(16));
        let ratio = coarse.hausdorff() / fine.hausdorff();
        assert!(
            (9.0..25.0).contains(&ratio),
            "{coarse:?} {fine:?} ratio {ratio}"
        );
        assert!(fine.hausdorff() < 2e-3, "{fine:?}");
    }

    /// A tessellation moved off the surface by `δ` along its normals is `δ` away on both
    /// sides; with a face of triangles removed, the surface side sees the hole and the mesh
    /// side does not.
    #[test]
    fn offsets_and_holes_are_measured_where_they_are() {
        let s = surface(&crate::shapes::cube());
        let t = s.tessellate(32).unwrap();
        let diag = deviation(
            &s,
            &t.positions,
            &t.triangles(),
            &DeviationOptions::default(),
        );
        let delta = 1e-2 * diag.diagonal;
        let moved: Vec<[f32; 3]> = t
            .positions
            .iter()
            .zip(&t.normals)
            .map(|(p, n)| std::array::from_fn(|k| p[k] + (delta * n[k] as f64) as f32))
            .collect();
        let d = deviation(&s, &moved, &t.triangles(), &DeviationOptions::default());
        for side in [d.mesh_to_surface, d.surface_to_mesh] {
            assert!((side / 1e-2 - 1.0).abs() < 0.05, "{d:?}");
        }
        let tris = t.triangles();
        let kept = &tris[tris.len() / 6..]; // the first ptex faces' triangles removed
        let holed = deviation(&s, &t.positions, kept, &DeviationOptions::default());
        assert!(holed.surface_to_mesh > 0.1, "{holed:?}");
        assert!(holed.mesh_to_surface < 1e-3, "{holed:?}");
    }

    /// Brute force: the distance from `p` to the nearest of `triangles`.
    fn nearest_triangle(p: P, positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> f64 {
        triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| widen(positions[i as usize]));
                point_triangle_d2(p, a, b, c)
            })
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// One reference measures every candidate as a fresh [`deviation`] does, and projecting
    /// each triangle sample from its own `(ptex, u, v)` finds the foot points the seed search
    /// finds (an adaptive tessellation of a shape with an extraordinary pole and
    /// boundaries, at two rates); the worst points are where the distances are.
    #[test]
    fn own_parameters_find_the_seed_search_foot_points() {
        let mesh = crate::shapes::pole(5);
        let s = surface(&mesh);
        let options = DeviationOptions::default();
        let reference = DeviationReference::new(&s, &options);
        let t = Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let plain = LimitSurface::new(table, &mesh.positions);
        for rate in [2, 5] {
            let rates = crate::tess::EdgeRates::uniform(&plain.table.base, rate);
            let p = crate::tess::plan(&plain.table, &rates, "").unwrap();
            let uv = p.triangle_uv.clone();
            let out = plain.eval_plan(p);
            let (positions, tris) = (out.positions, out.triangles);
            let own = reference.measure(&positions, &tris, Some(&uv));
            let seeds = reference.measure(&positions, &tris, None);
            let fresh = deviation(&s, &positions, &tris, &options);
            // The same maxima (the mean is summed in another order).
            assert_eq!(
                (seeds.mesh_to_surface, seeds.surface_to_mesh, seeds.diagonal),
                (fresh.mesh_to_surface, fresh.surface_to_mesh, fresh.diagonal),
                "rate {rate}"
            );
            assert!(
                (seeds.mean_mesh_to_surface - fresh.mean_mesh_to_surface).abs()
                    <= 1e-12 * fresh.mean_mesh_to_surface,
                "rate {rate}"
            );
            let scale = own.mesh_to_surface.max(seeds.mesh_to_surface);
            assert!(
                (own.mesh_to_surface - seeds.mesh_to_surface).abs() <= 1e-3 * scale,
                "rate {rate}: {own:?} {seeds:?}"
            );
            assert!(
                (own.mean_mesh_to_surface - seeds.mean_mesh_to_surface).abs()
                    <= 1e-3 * own.mean_mesh_to_surface,
                "rate {rate}: {own:?} {seeds:?}"
            );
            assert_eq!(own.surface_to_mesh, seeds.surface_to_mesh);
            assert!(own.hausdorff() > 0.0);
            // The worst surface sample is that far from the mesh.
            let d = nearest_triangle(own.worst_surface_point, &positions, &tris);
            assert!(
                (d / own.diagonal - own.surface_to_mesh).abs() <= 1e-12,
                "{d} {own:?}"
            );
            // The worst mesh sample lies on a triangle, that far from the surface samples'
            // projections (no surface sample nearer).
            let on_mesh = nearest_triangle(own.worst_mesh_point, &positions, &tris);
            assert!(on_mesh <= 1e-9 * own.diagonal, "{on_mesh}");
            let nearest_sample = reference
                .samples
                .iter()
                .map(|&q| dot(sub(q, own.worst_mesh_point), sub(q, own.worst_mesh_point)))
                .fold(f64::INFINITY, f64::min)
                .sqrt();
            assert!(
                nearest_sample >= own.mesh_to_surface * own.diagonal * (1.0 - 1e-9),
                "{nearest_sample} {own:?}"
            );
        }
    }
}
