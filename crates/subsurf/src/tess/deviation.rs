//! The geometric deviation of a triangle mesh from a limit surface: the two-sided Hausdorff
//! distance, Metro-style (Cignoni, Rocchini & Scopigno 1998), as a fraction of the surface's
//! bounding-box diagonal.
//!
//! - **Mesh to surface**: points sampled on every triangle (a barycentric grid, vertices and
//!   edges included) are projected onto the surface: the nearest of a dense set of surface
//!   samples gives a `(ptex, u, v)`, which Gauss-Newton steps on the limit surface refine to
//!   the foot point (clamped to the ptex face). The distance to the foot point is the
//!   sample's deviation.
//! - **Surface to mesh**: the same dense surface samples, each at its exact distance to the
//!   nearest triangle (a uniform grid of triangle bounding boxes, searched ring by ring until
//!   no nearer triangle can exist).
//!
//! The deviation is the largest over both sample sets: it sees where the mesh is far from the
//! surface *and* where the surface is far from the mesh (a hole, a missing region), wherever
//! the nearest point is — not the distance at the same `(u, v)`, which counts a tangential
//! drift of the parametrization as error.

use rayon::prelude::*;

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
}

impl Deviation {
    /// The two-sided (Hausdorff) deviation: the larger one-sided one.
    pub fn hausdorff(&self) -> f64 {
        self.mesh_to_surface.max(self.surface_to_mesh)
    }
}

type P = [f64; 3];

/// Surface samples a mesh sample is projected from (the best of each ptex face among them).
const SEEDS: usize = 8;

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

    /// The item nearest to `p` by `dist` (a squared distance); `None` when the grid is
    /// empty.
    fn nearest(&self, p: P, dist: impl Fn(u32) -> f64) -> Option<(u32, f64)> {
        self.nearest_k(p, 1, dist).first().copied()
    }

    /// The `k` items nearest to `p` by `dist` (a squared distance), nearest first: the cells
    /// are searched ring by ring around `p`'s cell until no cell outside can hold a nearer
    /// item than the `k`-th.
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
            // Every cell outside the rings searched is at least `ring` cells away.
            if best.len() == k {
                let reach = ring as f64 * self.cell;
                if best[k - 1].1 <= reach * reach {
                    break;
                }
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

/// The foot point of `q` on ptex face `ptex` of `surface`, from `(u, v)`: Gauss-Newton steps
/// on `|S(u, v) - q|²`, clamped to the face; the squared distance reached.
fn project<R: Real>(surface: &LimitSurface<R>, q: P, ptex: usize, mut u: f64, mut v: f64) -> f64 {
    let at = |u: f64, v: f64| surface.eval(ptex, R::from_f64(u), R::from_f64(v));
    let Some(mut s) = at(u, v) else {
        return f64::INFINITY;
    };
    let mut best = {
        let d = sub(q, widen(s.p));
        dot(d, d)
    };
    for _ in 0..12 {
        let (p, du, dv) = (widen(s.p), widen(s.du), widen(s.dv));
        let r = sub(q, p);
        let (a, b, c) = (dot(du, du), dot(du, dv), dot(dv, dv));
        let (g0, g1) = (dot(du, r), dot(dv, r));
        let det = a * c - b * b;
        if det.abs() <= 1e-30 * (a * c).max(1e-300) {
            break;
        }
        let (mut su, mut sv) = ((c * g0 - b * g1) / det, (a * g1 - b * g0) / det);
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
        if !improved || (su * su + sv * sv) < 1e-24 {
            break;
        }
    }
    best
}

/// The deviation of the triangle mesh (`positions`, counter-clockwise or not, `triangles`)
/// from `surface` (module documentation). A mesh without triangles is infinitely far from
/// every surface sample.
pub fn deviation<R: Real>(
    surface: &LimitSurface<R>,
    positions: &[[f32; 3]],
    triangles: &[[u32; 3]],
    options: &DeviationOptions,
) -> Deviation {
    let n = options.surface_samples.max(1);
    let table = surface.table();
    let map = table.patch_map();
    // Dense surface samples with their (ptex, u, v).
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
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &samples {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let diagonal = if samples.is_empty() {
        0.0
    } else {
        dot(sub(hi, lo), sub(hi, lo)).sqrt()
    };
    let unit = if diagonal > 0.0 { 1.0 / diagonal } else { 1.0 };
    let verts: Vec<P> = positions.iter().map(|&p| widen(p)).collect();
    for p in &verts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }

    // Surface to mesh: exact nearest-triangle distances.
    let tri_boxes: Vec<(P, P)> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| verts[i as usize]);
            (
                std::array::from_fn(|k| a[k].min(b[k]).min(c[k])),
                std::array::from_fn(|k| a[k].max(b[k]).max(c[k])),
            )
        })
        .collect();
    let tri_grid = Grid::new(lo, hi, triangles.len(), &tri_boxes);
    let tri_d2 = |p: P, t: u32| {
        let [a, b, c] = triangles[t as usize].map(|i| verts[i as usize]);
        point_triangle_d2(p, a, b, c)
    };
    let surface_to_mesh = samples
        .par_iter()
        .map(|&p| {
            tri_grid
                .nearest(p, |t| tri_d2(p, t))
                .map_or(f64::INFINITY, |(_, d2)| d2.sqrt())
        })
        .reduce(|| 0.0, f64::max);

    // Mesh to surface: triangle samples projected from their nearest surface sample.
    let point_boxes: Vec<(P, P)> = samples.iter().map(|&p| (p, p)).collect();
    let point_grid = Grid::new(lo, hi, samples.len() / 4 + 1, &point_boxes);
    let k = options.triangle_samples.max(1);
    let bary: Vec<(f64, f64)> = (0..=k)
        .flat_map(|i| (0..=k - i).map(move |j| (i as f64 / k as f64, j as f64 / k as f64)))
        .collect();
    let (sum, count, mesh_to_surface) = triangles
        .par_iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| verts[i as usize]);
            let (mut sum, mut worst) = (0.0, 0.0f64);
            for &(s, r) in &bary {
                let q = add(a, add(scale(s, sub(b, a)), scale(r, sub(c, a))));
                // The nearest samples, projected from the best one of each ptex face
                // among them: at a vertex shared by several ptex faces the foot point may
                // lie in any of them.
                let near = point_grid.nearest_k(q, SEEDS, |i| {
                    let d = sub(q, samples[i as usize]);
                    dot(d, d)
                });
                let mut d2 = near.first().map_or(f64::INFINITY, |e| e.1);
                let mut tried: Vec<u32> = Vec::with_capacity(SEEDS);
                for &(i, _) in &near {
                    let (f, u, v) = sample_q[i as usize];
                    if !tried.contains(&f) {
                        tried.push(f);
                        d2 = d2.min(project(surface, q, f as usize, u, v));
                    }
                }
                let d = d2.sqrt();
                sum += d;
                worst = worst.max(d);
            }
            (sum, bary.len(), worst)
        })
        .reduce(
            || (0.0, 0, 0.0),
            |x, y| (x.0 + y.0, x.1 + y.1, x.2.max(y.2)),
        );
    Deviation {
        mesh_to_surface: mesh_to_surface * unit,
        surface_to_mesh: surface_to_mesh * unit,
        mean_mesh_to_surface: if count > 0 {
            sum / count as f64 * unit
        } else {
            0.0
        },
        diagonal,
    }
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
}
