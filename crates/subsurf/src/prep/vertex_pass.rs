//! Vertex pass of the p-rep (Myles, Yeo & Peters 2008, §4 "vertex shader"; spec §3).
//!
//! Per vertex `p0` of valence `n`, with its ring `p1 … p2n` (odd = edge neighbours,
//! even = diagonal neighbours):
//!
//! ```text
//! (2)  g00  = (n² p0 + 4 Σ_l p_{2l-1} + Σ_l p_{2l}) / (n (n+5))          Catmull-Clark limit point
//! (3)  e_i  = σ_n / (3 (2 + w_n)) Σ_{j=1..n} (α_i p_{2j-1} + β_i p_{2j})
//!      α_1 = w_n c^{j-1},  β_1 = c^{j-1} + c^j,   α_2 = w_n s^{j-1},  β_2 = s^{j-1} + s^j
//!      T(k) = g^k_10 = g00 + c^k e1 + s^k e2                               tangent coefficient, along p0 → p_{2k+1}
//! (4)  I(k) = g^k_11 = (4 p0 + 2 (p_{2k+1} + p_{2k+3}) + p_{2k+2}) / 9    interior coefficient
//! ```
//!
//! The outputs are flat arrays: `limit`, `e1`, `e2` per vertex and `tangent`, `interior`
//! per sector (sector `k` of vertex `v` is entry `ring_offsets[v]/2 + k`). Each entry is a
//! pure function of the input positions, so the parallel pass ([`vertex_pass`]) and the
//! sequential reference ([`vertex_pass_seq`]) give identical bits.

use crate::real::VertexData as Values;
use rayon::prelude::*;

use super::constants::{Valence, ValenceTable};
use super::ring::PrepTopology;
use crate::real::Real;
use crate::util::vec3::{add, axpy, scale, zero3, V3};

/// Per-vertex `(limit, e1, e2)` arrays, read by the sector step.
pub type Frames<'a, T> = (&'a [V3<T>], &'a [V3<T>], &'a [V3<T>]);

/// Elements per parallel work item.
pub const CHUNK: usize = 256;

/// Outputs of the vertex pass.
#[derive(Debug, Clone, Default)]
pub struct VertexData<T> {
    /// Limit point `g00` of each vertex (count: V).
    pub limit: Vec<V3<T>>,
    /// Tangent vector `e1` of each vertex (count: V).
    pub e1: Vec<V3<T>>,
    /// Tangent vector `e2` of each vertex (count: V).
    pub e2: Vec<V3<T>>,
    /// `T(k) = g^k_10` of each sector (count: S).
    pub tangent: Vec<V3<T>>,
    /// `I(k) = g^k_11` of each sector (count: S).
    pub interior: Vec<V3<T>>,
}

impl<T: Real> VertexData<T> {
    /// Zeroed arrays sized for `topo`.
    pub fn new(topo: &PrepTopology) -> Self {
        let (v, s) = (topo.num_vertices, topo.sector_vertex.len());
        VertexData {
            limit: vec![zero3(); v],
            e1: vec![zero3(); v],
            e2: vec![zero3(); v],
            tangent: vec![zero3(); s],
            interior: vec![zero3(); s],
        }
    }
}

#[inline(always)]
fn pos<T: Real>(p: &(impl Values<3> + ?Sized), i: u32) -> V3<T> {
    p.vertex::<T>(i as usize)
}

/// `(g00, e1, e2)` from `p0` and its ring (equations (2) and (3)): `ring(j)` returns
/// `(p_{2j+1}, p_{2j+2})`, the edge and diagonal neighbour of sector `j`, for `j = 0..n-1`.
#[inline]
pub fn frame_from_ring<T: Real>(
    c: &Valence<T>,
    p0: V3<T>,
    ring: impl Fn(usize) -> (V3<T>, V3<T>),
) -> (V3<T>, V3<T>, V3<T>) {
    let (mut se, mut sd) = (zero3::<T>(), zero3::<T>());
    let (mut e1, mut e2) = (zero3::<T>(), zero3::<T>());
    for j in 0..c.n {
        let (pe, pd) = ring(j);
        se = add(se, pe);
        sd = add(sd, pd);
        e1 = axpy(axpy(e1, c.e1[j][0], pe), c.e1[j][1], pd);
        e2 = axpy(axpy(e2, c.e2[j][0], pe), c.e2[j][1], pd);
    }
    let g00 = axpy(axpy(scale(c.limit[0], p0), c.limit[1], se), c.limit[2], sd);
    (g00, e1, e2)
}

/// Tangent coefficient `T(k) = g00 + c^k e1 + s^k e2` (3).
#[inline]
pub fn tangent_coeff<T: Real>(c: &Valence<T>, k: usize, g00: V3<T>, e1: V3<T>, e2: V3<T>) -> V3<T> {
    axpy(axpy(g00, c.cos[k], e1), c.sin[k], e2)
}

/// Interior coefficient `I(k) = (4 p0 + 2 (p_{2k+1} + p_{2k+3}) + p_{2k+2}) / 9` (4).
#[inline]
pub fn interior_coeff<T: Real>(p0: V3<T>, p1: V3<T>, p2: V3<T>, p3: V3<T>) -> V3<T> {
    let sum = add(
        add(
            scale(T::from_f64(4.0), p0),
            scale(T::from_f64(2.0), add(p1, p3)),
        ),
        p2,
    );
    scale(T::from_f64(1.0 / 9.0), sum)
}

/// `(g00, e1, e2)` of vertex `v`: equations (2) and (3).
#[inline]
pub fn vertex_frame<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    positions: &(impl Values<3> + Sync + ?Sized),
    v: usize,
) -> (V3<T>, V3<T>, V3<T>) {
    let p0 = pos::<T>(positions, v as u32);
    let ring = topo.ring(v);
    let n = ring.len() / 2;
    if n == 0 {
        return (p0, zero3(), zero3());
    }
    frame_from_ring(consts.get(n), p0, |j| {
        (pos(positions, ring[2 * j]), pos(positions, ring[2 * j + 1]))
    })
}

/// `(T(k), I(k))` of sector `s` (global sector index): equations (3) and (4).
#[inline]
pub fn sector_coeffs<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    positions: &(impl Values<3> + Sync + ?Sized),
    frame: Frames<'_, T>,
    s: usize,
) -> (V3<T>, V3<T>) {
    let v = topo.sector_vertex[s] as usize;
    let ring = topo.ring(v);
    let n = ring.len() / 2;
    let k = s - topo.sector_base(v);
    let t = tangent_coeff(consts.get(n), k, frame.0[v], frame.1[v], frame.2[v]);
    let i = interior_coeff(
        pos(positions, v as u32),
        pos(positions, ring[2 * k]),
        pos(positions, ring[2 * k + 1]),
        pos(positions, ring[(2 * k + 2) % (2 * n)]),
    );
    (t, i)
}

/// Parallel vertex pass (rayon, chunks of [`CHUNK`] elements).
pub fn vertex_pass<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    positions: &(impl Values<3> + Sync + ?Sized),
    out: &mut VertexData<T>,
) {
    out.limit
        .par_chunks_mut(CHUNK)
        .zip(out.e1.par_chunks_mut(CHUNK))
        .zip(out.e2.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(ci, ((l, a), b))| {
            for i in 0..l.len() {
                (l[i], a[i], b[i]) = vertex_frame(topo, consts, positions, ci * CHUNK + i);
            }
        });
    let frame = (&out.limit[..], &out.e1[..], &out.e2[..]);
    out.tangent
        .par_chunks_mut(CHUNK)
        .zip(out.interior.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(ci, (t, m))| {
            for i in 0..t.len() {
                (t[i], m[i]) = sector_coeffs(topo, consts, positions, frame, ci * CHUNK + i);
            }
        });
}

/// Sequential reference of [`vertex_pass`].
pub fn vertex_pass_seq<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    positions: &(impl Values<3> + Sync + ?Sized),
    out: &mut VertexData<T>,
) {
    for v in 0..topo.num_vertices {
        (out.limit[v], out.e1[v], out.e2[v]) = vertex_frame(topo, consts, positions, v);
    }
    let frame = (&out.limit[..], &out.e1[..], &out.e2[..]);
    for s in 0..out.tangent.len() {
        (out.tangent[s], out.interior[s]) = sector_coeffs(topo, consts, positions, frame, s);
    }
}
