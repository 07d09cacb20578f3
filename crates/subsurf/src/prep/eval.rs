//! Evaluation of the p-rep surface (Myles, Yeo & Peters 2008, §4 "pass 2"; spec §1):
//!
//! ```text
//! x(u,v) = Σ_{i,j=0..3} g_ij B³_i(u) B³_j(v) + Σ_{i,j=0..5} h_ij B⁵_i(u) B⁵_j(v),
//! B^d_i(t) = C(d,i) (1−t)^(d−i) t^i
//! ```
//!
//! evaluated in p-rep form (not through the bi-5 conversion) so that a shared boundary is
//! never re-rounded. [`PrepPatches::tessellate`] builds a watertight triangle mesh: a sample
//! on a shared edge is computed once, from the edge curve `Σ g_i0 B³_i + h20 B⁵_2 + h30 B⁵_3`
//! in the edge's canonical direction (lower vertex index first), and both faces reference it
//! by index; each corner is the vertex's limit point `g00`, with normal `e1 × e2`.

use rayon::prelude::*;

use super::grid::{uniform_params, GridBasis};
use super::patch_pass::{corner_index, H_SLOTS};
use super::PrepPatches;
use crate::real::Real;
use crate::util::vec3::{add, cross, normalize, scale, sub, zero3, V3};

/// Bernstein values and derivatives of degree 3 and 5 at one parameter.
#[derive(Debug, Clone, Copy)]
pub struct Basis<T> {
    b3: [T; 4],
    d3: [T; 4],
    b5: [T; 6],
    d5: [T; 6],
}

impl<T: Real> Basis<T> {
    /// Basis at `t`.
    pub fn new(t: T) -> Self {
        let s = T::one() - t;
        let (three, five, ten) = (T::from_f64(3.0), T::from_f64(5.0), T::from_f64(10.0));
        let b3 = [s * s * s, three * s * s * t, three * s * t * t, t * t * t];
        let q = [s * s, T::from_f64(2.0) * s * t, t * t]; // B²
        let d3 = [
            -three * q[0],
            three * (q[0] - q[1]),
            three * (q[1] - q[2]),
            three * q[2],
        ];
        let (s2, t2) = (s * s, t * t);
        let b5 = [
            s2 * s2 * s,
            five * s2 * s2 * t,
            ten * s2 * s * t2,
            ten * s2 * t2 * t,
            five * s * t2 * t2,
            t2 * t2 * t,
        ];
        let four = T::from_f64(4.0);
        let six = T::from_f64(6.0);
        let c = [
            s2 * s2,
            four * s2 * s * t,
            six * s2 * t2,
            four * s * t2 * t,
            t2 * t2,
        ]; // B⁴
        let d5 = [
            -five * c[0],
            five * (c[0] - c[1]),
            five * (c[1] - c[2]),
            five * (c[2] - c[3]),
            five * (c[3] - c[4]),
            five * c[4],
        ];
        Basis { b3, d3, b5, d5 }
    }
}

/// Position and partial derivatives at one point of a patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<T> {
    /// `x(u, v)`.
    pub position: V3<T>,
    /// `∂x/∂u`.
    pub du: V3<T>,
    /// `∂x/∂v`.
    pub dv: V3<T>,
}

impl<T: Real> Sample<T> {
    /// Unit normal `du × dv / |du × dv|` (outward for ccw faces).
    pub fn normal(&self) -> V3<T> {
        normalize(cross(self.du, self.dv))
    }
}

/// Evaluates one patch (`g` 16 row-major, compact `h` or `None`) with precomputed bases.
#[inline]
pub fn eval_patch<T: Real>(
    g: &[V3<T>],
    h: Option<&[V3<T>]>,
    bu: &Basis<T>,
    bv: &Basis<T>,
) -> Sample<T> {
    let (mut p, mut du, mut dv) = (zero3::<T>(), zero3::<T>(), zero3::<T>());
    // The bi-3 part relative to g00: its weights sum to 1 (derivatives: 0), so the rounding
    // is of the patch's size, not of its distance from the origin; h is a perturbation.
    let x0 = g[0];
    for i in 0..4 {
        for j in 0..4 {
            let x = sub(g[4 * i + j], x0);
            let (w, wu, wv) = (
                bu.b3[i] * bv.b3[j],
                bu.d3[i] * bv.b3[j],
                bu.b3[i] * bv.d3[j],
            );
            for k in 0..3 {
                p[k] += w * x[k];
                du[k] += wu * x[k];
                dv[k] += wv * x[k];
            }
        }
    }
    if let Some(h) = h {
        for (s, &(i, j)) in H_SLOTS.iter().enumerate() {
            let x = h[s];
            let (w, wu, wv) = (
                bu.b5[i] * bv.b5[j],
                bu.d5[i] * bv.b5[j],
                bu.b5[i] * bv.d5[j],
            );
            for k in 0..3 {
                p[k] += w * x[k];
                du[k] += wu * x[k];
                dv[k] += wv * x[k];
            }
        }
    }
    Sample {
        position: add(p, x0),
        du,
        dv,
    }
}

/// A tessellated surface: shared vertices, per-vertex normals, ccw triangles.
#[derive(Debug, Clone, Default)]
pub struct Tessellation<T> {
    /// Vertex positions.
    pub positions: Vec<V3<T>>,
    /// Unit normals, one per vertex.
    pub normals: Vec<V3<T>>,
    /// Triangles (ccw seen from outside).
    pub triangles: Vec<[u32; 3]>,
}

/// `n×n` samples per face, not shared: entry `f n² + j n + i` is at `(u, v) = (i, j)/(n−1)`.
#[derive(Debug, Clone, Default)]
pub struct Grid<T> {
    /// Samples per side.
    pub n: usize,
    /// Positions.
    pub positions: Vec<V3<T>>,
    /// Unit normals.
    pub normals: Vec<V3<T>>,
}

fn params<T: Real>(n: usize) -> Vec<Basis<T>> {
    let d = T::from_f64((n - 1) as f64);
    (0..n)
        .map(|i| Basis::new(T::from_f64(i as f64) / d))
        .collect()
}

impl<T: Real> PrepPatches<T> {
    /// The 16 coefficients `g` of `face`.
    pub fn face_g(&self, face: usize) -> &[V3<T>] {
        &self.g[16 * face..16 * face + 16]
    }

    /// The 16 non-zero `h` of `face` in [`H_SLOTS`] order, `None` for a B-quad.
    pub fn face_h(&self, face: usize) -> Option<&[V3<T>]> {
        let i = self.h_index[face];
        (i != u32::MAX).then(|| &self.h[16 * i as usize..16 * i as usize + 16])
    }

    /// Position and derivatives at `(face, u, v)`, `u` along `v0 → v1`, `v` along `v0 → v3`.
    pub fn eval(&self, face: usize, u: T, v: T) -> Sample<T> {
        eval_patch(
            self.face_g(face),
            self.face_h(face),
            &Basis::new(u),
            &Basis::new(v),
        )
    }

    /// Positions and normals on an `n×n` grid of every face (`n >= 2`), in parallel.
    pub fn eval_grid(&self, n: usize) -> Grid<T> {
        let mut grid = Grid::default();
        self.eval_grid_into(n, &mut grid);
        grid
    }

    /// [`Self::eval_grid`] into existing buffers (reused from frame to frame).
    pub fn eval_grid_into(&self, n: usize, grid: &mut Grid<T>) {
        let n = n.max(2);
        self.eval_grid_with(&GridBasis::uniform(n), grid);
        grid.n = n;
    }

    /// Evaluates every face on the grid tabulated in `basis` (see `GridBasis`) into
    /// `grid` (`grid.n` is left to the caller), in parallel over faces.
    pub fn eval_grid_with(&self, basis: &GridBasis<T>, grid: &mut Grid<T>) {
        let per = basis.len();
        let len = self.num_faces() * per;
        grid.positions.resize(len, zero3());
        grid.normals.resize(len, zero3());
        if per == 0 {
            return;
        }
        grid.positions
            .par_chunks_mut(per)
            .zip(grid.normals.par_chunks_mut(per))
            .enumerate()
            .for_each(|(f, (p, nr))| basis.eval_patch(self.face_g(f), self.face_h(f), p, nr));
    }

    /// Point of the edge curve leaving corner `c` of `face` at local parameter `t`: the
    /// boundary `Σ g_i0 B³_i(t) + h20 B⁵_2(t) + h30 B⁵_3(t)` in the corner's frame.
    fn edge_point(&self, face: usize, c: usize, b: &Basis<T>) -> V3<T> {
        let g = self.face_g(face);
        let mut p = zero3::<T>();
        for i in 0..4 {
            let (a, bb) = corner_index(c, i, 0, 3);
            p = add(p, scale(b.b3[i], g[4 * a + bb]));
        }
        if let Some(h) = self.face_h(face) {
            p = add(p, scale(b.b5[2], h[4 * c]));
            p = add(p, scale(b.b5[3], h[4 * c + 1]));
        }
        p
    }

    /// Watertight triangle mesh with `n` samples per patch side (`n >= 2`).
    ///
    /// Vertex layout: one vertex per mesh vertex (the limit point), then `n − 2` per edge in
    /// canonical direction, then `(n − 2)²` per face.
    pub fn tessellate(&self, n: usize) -> Tessellation<T> {
        let n = n.max(2);
        let m = n - 2;
        let topo = &self.topology;
        let (nv, ne, nf) = (topo.num_vertices, topo.num_edges(), self.num_faces());
        let b = params::<T>(n);
        let total = nv + ne * m + nf * m * m;
        let mut positions = vec![zero3(); total];
        let mut normals = vec![zero3(); total];
        let (pc, rest) = positions.split_at_mut(nv);
        let (pe, pf) = rest.split_at_mut(ne * m);
        let (nc, rest) = normals.split_at_mut(nv);
        let (ne_, nf_) = rest.split_at_mut(ne * m);
        let vd = &self.vertex;
        pc.par_iter_mut()
            .zip(nc.par_iter_mut())
            .enumerate()
            .for_each(|(v, (p, nr))| {
                *p = vd.limit[v];
                *nr = normalize(cross(vd.e1[v], vd.e2[v]));
            });
        if m > 0 {
            pe.par_chunks_mut(m)
                .zip(ne_.par_chunks_mut(m))
                .enumerate()
                .for_each(|(e, (p, nr))| {
                    let corner = topo.edge_corner[e] as usize;
                    let (f, c) = (corner / 4, corner % 4);
                    for s in 1..=m {
                        p[s - 1] = self.edge_point(f, c, &b[s]);
                        let (u, v) = corner_index(c, s, 0, n - 1);
                        nr[s - 1] =
                            eval_patch(self.face_g(f), self.face_h(f), &b[u], &b[v]).normal();
                    }
                });
            let inner = &uniform_params::<T>(n)[1..=m];
            let basis = GridBasis::new(inner, inner);
            pf.par_chunks_mut(m * m)
                .zip(nf_.par_chunks_mut(m * m))
                .enumerate()
                .for_each(|(f, (p, nr))| basis.eval_patch(self.face_g(f), self.face_h(f), p, nr));
        }
        let mut triangles = vec![[0u32; 3]; 2 * nf * (n - 1) * (n - 1)];
        triangles
            .par_chunks_mut(2 * (n - 1) * (n - 1))
            .enumerate()
            .for_each(|(f, tri)| {
                let idx = |i: usize, j: usize| self.grid_vertex(f, i, j, n) as u32;
                let mut t = 0;
                for j in 0..n - 1 {
                    for i in 0..n - 1 {
                        let (a, b, c, d) =
                            (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
                        tri[t] = [a, b, c];
                        tri[t + 1] = [a, c, d];
                        t += 2;
                    }
                }
            });
        Tessellation {
            positions,
            normals,
            triangles,
        }
    }

    /// Index in [`Self::tessellate`]'s vertex array of grid sample `(i, j)` of `face`.
    fn grid_vertex(&self, face: usize, i: usize, j: usize, n: usize) -> usize {
        let topo = &self.topology;
        let (last, m) = (n - 1, n - 2);
        let corner = match (i, j) {
            (0, 0) => Some(0),
            (x, 0) if x == last => Some(1),
            (x, y) if x == last && y == last => Some(2),
            (0, y) if y == last => Some(3),
            _ => None,
        };
        if let Some(c) = corner {
            return topo.face_verts[4 * face + c] as usize;
        }
        let edge = if j == 0 {
            Some((0, i))
        } else if i == last {
            Some((1, j))
        } else if j == last {
            Some((2, last - i))
        } else if i == 0 {
            Some((3, last - j))
        } else {
            None
        };
        if let Some((c, s)) = edge {
            let e = topo.face_edges[4 * face + c] as usize;
            let forward = topo.face_verts[4 * face + c] < topo.face_verts[4 * face + (c + 1) % 4];
            let k = if forward { s - 1 } else { m - s };
            return topo.num_vertices + e * m + k;
        }
        topo.num_vertices + topo.num_edges() * m + face * m * m + (j - 1) * m + (i - 1)
    }
}
