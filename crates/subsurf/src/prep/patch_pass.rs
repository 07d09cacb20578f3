//! Patch pass of the p-rep (Myles, Yeo & Peters 2008, §4 "geometry shader"; spec §4, §5).
//!
//! Per face `(v0, v1, v2, v3)` with sector numbers `k_c`:
//!
//! * the 16 bi-3 coefficients `g`, assembled from vertex data only (spec §4): at corner `c`
//!   the local coefficients are `g00 = L(v_c)`, `g10 = T(v_c, k_c)`, `g01 = T(v_c, k_c+1)`,
//!   `g11 = I(v_c, k_c)`, stored through the corner frame map
//!   `c=0: (i,j)  c=1: (d-j,i)  c=2: (d-i,d-j)  c=3: (j,d-i)` with `d = 3`;
//! * unless all four vertices have valence 4 (a B-quad), the 16 non-zero coefficients of
//!   the bi-5 perturbation `h`: per corner `c`, `h20, h30, h21, h31` of the edge
//!   `v_c → v_{c+1}` in the local frame of corner `c` (equations (8), (9); spec §5), stored
//!   through the same map with `d = 5`.
//!
//! The perturbation reads only vertex data of the edge's two end vertices (spec §5.1), so
//! both faces along an edge compute `h20`/`h30` from the same array elements with the same
//! expressions: the mirrored end is evaluated by the *same function* with swapped arguments
//! (`S0 + S1` sums commute exactly), which makes the shared boundary bit-identical.
//! Case 2/3 use the symmetric `h31`/`h21` derived from eq. (15) (spec §5.5), on every face.

use rayon::prelude::*;

use super::constants::ValenceTable;
use super::ring::PrepTopology;
use super::vertex_pass::VertexData;
use crate::real::Real;
use crate::util::vec3::{add, V3};

/// Face index `(i, j)` of local index `(i, j)` at corner `c` for a `(d+1)×(d+1)` array.
#[inline(always)]
pub const fn corner_index(c: usize, i: usize, j: usize, d: usize) -> (usize, usize) {
    match c {
        0 => (i, j),
        1 => (d - j, i),
        2 => (d - i, d - j),
        _ => (j, d - i),
    }
}

/// Face indices `(i, j)` of the compact `h` block: entry `4 c + m` holds local
/// `[h20, h30, h21, h31][m]` of corner `c` (spec §5 table).
pub const H_SLOTS: [(usize, usize); 16] = {
    let local = [(2, 0), (3, 0), (2, 1), (3, 1)];
    let mut out = [(0, 0); 16];
    let mut k = 0;
    while k < 16 {
        let (i, j) = local[k % 4];
        out[k] = corner_index(k / 4, i, j, 5);
        k += 1;
    }
    out
};

/// The twelve inputs of one edge's perturbation in the local frame of its first corner
/// (spec §5.1); `gs*` are the starred coefficients of the neighbouring patch `k-1`.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct EdgeInputs<T> {
    pub g00: V3<T>,
    pub g10: V3<T>,
    pub g20: V3<T>,
    pub g30: V3<T>,
    pub g01: V3<T>,
    pub g11: V3<T>,
    pub g21: V3<T>,
    pub g31: V3<T>,
    pub gs10: V3<T>,
    pub gs11: V3<T>,
    pub gs12: V3<T>,
    pub gs13: V3<T>,
}

#[inline(always)]
fn f<T: Real>(x: f64) -> T {
    T::from_f64(x)
}

#[inline(always)]
fn lin<T: Real, const N: usize>(terms: [(T, V3<T>); N]) -> V3<T> {
    let mut acc = [T::zero(); 3];
    for (w, p) in terms {
        for k in 0..3 {
            acc[k] += w * p[k];
        }
    }
    acc
}

/// Case 2 end coefficient `h20 = h30` (eq. 8), seen from the extraordinary end `a`:
/// `3/40 (−2 p0 + (6 − 6/c) p1 − 4 p2 + (3/c) S)`.
#[inline]
fn case2_end<T: Real>(c: T, p0: V3<T>, p1: V3<T>, p2: V3<T>, s: V3<T>) -> V3<T> {
    let k = f::<T>(3.0 / 40.0);
    let six = f::<T>(6.0);
    lin([
        (k * f(-2.0), p0),
        (k * (six - six / c), p1),
        (k * f(-4.0), p2),
        (k * (f::<T>(3.0) / c), s),
    ])
}

/// Case 2 `h21` (eq. 8), near the extraordinary end:
/// `(1 − 2c/5) h + 3/100 (2c p0 + (12 − 6c) p1 + (6 + 2c) p2 + 2c p3 − 6 Sa − 3 Sb)`.
#[inline]
fn case2_near<T: Real>(c: T, h: V3<T>, p: [V3<T>; 4], sa: V3<T>, sb: V3<T>) -> V3<T> {
    let k = f::<T>(3.0 / 100.0);
    let two_c = f::<T>(2.0) * c;
    lin([
        (T::one() - two_c / f(5.0), h),
        (k * two_c, p[0]),
        (k * (f::<T>(12.0) - f::<T>(6.0) * c), p[1]),
        (k * (f::<T>(6.0) + two_c), p[2]),
        (k * two_c, p[3]),
        (k * f(-6.0), sa),
        (k * f(-3.0), sb),
    ])
}

/// Case 2 symmetric `h31` (from eq. 15, spec §5.3), near the valence-4 end:
/// `h + 3/100 (6 p1 + (12 − 2c) p2 + (2 + 2c) p3 − 3 Sa − 6 Sb − Tb)`.
#[inline]
fn case2_far<T: Real>(c: T, h: V3<T>, p: [V3<T>; 4], sa: V3<T>, sb: V3<T>, tb: V3<T>) -> V3<T> {
    let k = f::<T>(3.0 / 100.0);
    let two_c = f::<T>(2.0) * c;
    lin([
        (T::one(), h),
        (k * f(6.0), p[1]),
        (k * (f::<T>(12.0) - two_c), p[2]),
        (k * (f::<T>(2.0) + two_c), p[3]),
        (k * f(-3.0), sa),
        (k * f(-6.0), sb),
        (-k, tb),
    ])
}

/// Case 4 end coefficient (eq. 9, `h20` with the spurious fifth weight dropped, spec §9.10):
/// `3/40 (−(2cb/ca) p0 + (4 + (2cb − 6)/ca) p1 − 4 p2 + (3/ca) S)`.
#[inline]
fn case4_end<T: Real>(ca: T, cb: T, p0: V3<T>, p1: V3<T>, p2: V3<T>, s: V3<T>) -> V3<T> {
    let k = f::<T>(3.0 / 40.0);
    let two_cb = f::<T>(2.0) * cb;
    lin([
        (k * (-(two_cb / ca)), p0),
        (k * (f::<T>(4.0) + (two_cb - f(6.0)) / ca), p1),
        (k * f(-4.0), p2),
        (k * (f::<T>(3.0) / ca), s),
    ])
}

/// Case 4 `h21` (eq. 9): `(1 − 3ca/5 − 2cb/5) ha + (3ca/5) hb + 3/100 (4cb p0 + (12 − 8ca) p1
/// + (6 + 6ca − 4cb) p2 + 2ca p3 − 6 Sa − 3 Sb)`.
#[inline]
fn case4_inner<T: Real>(
    ca: T,
    cb: T,
    ha: V3<T>,
    hb: V3<T>,
    p: [V3<T>; 4],
    sa: V3<T>,
    sb: V3<T>,
) -> V3<T> {
    let k = f::<T>(3.0 / 100.0);
    let (three, four, five) = (f::<T>(3.0), f::<T>(4.0), f::<T>(5.0));
    lin([
        (T::one() - three * ca / five - f::<T>(2.0) * cb / five, ha),
        (three * ca / five, hb),
        (k * (four * cb), p[0]),
        (k * (f::<T>(12.0) - f::<T>(8.0) * ca), p[1]),
        (k * (f::<T>(6.0) + f::<T>(6.0) * ca - four * cb), p[2]),
        (k * (f::<T>(2.0) * ca), p[3]),
        (k * f(-6.0), sa),
        (k * f(-3.0), sb),
    ])
}

/// `[h20, h30, h21, h31]` of one edge with end valences `n0`, `n1` (`c0`, `c1` = `c_n`, 0 for
/// valence 4). Cases 1–4 of spec §5; the Case-3 expressions are the Case-2 functions called
/// with the ends swapped, and Case 4's `h30`, `h31` are its `h20`, `h21` functions mirrored.
pub fn edge_h<T: Real>(e: &EdgeInputs<T>, n0: usize, n1: usize, c0: T, c1: T) -> [V3<T>; 4] {
    let s0 = add(e.g11, e.gs11);
    let s1 = add(e.g21, e.gs12);
    let fwd = [e.g00, e.g10, e.g20, e.g30];
    let rev = [e.g30, e.g20, e.g10, e.g00];
    match (n0 == 4, n1 == 4) {
        (true, true) => [[T::zero(); 3]; 4],
        (false, true) => {
            let h = case2_end(c0, e.g00, e.g10, e.g20, s0);
            let t1 = add(e.g31, e.gs13);
            let h21 = case2_near(c0, h, fwd, s0, s1);
            let h31 = case2_far(c0, h, fwd, s0, s1, t1);
            [h, h, h21, h31]
        }
        (true, false) => {
            let h = case2_end(c1, e.g30, e.g20, e.g10, s1);
            let t0 = add(e.g01, e.gs10);
            let h31 = case2_near(c1, h, rev, s1, s0);
            let h21 = case2_far(c1, h, rev, s1, s0, t0);
            [h, h, h21, h31]
        }
        (false, false) => {
            let h20 = case4_end(c0, c1, e.g00, e.g10, e.g20, s0);
            let h30 = case4_end(c1, c0, e.g30, e.g20, e.g10, s1);
            let h21 = case4_inner(c0, c1, h20, h30, fwd, s0, s1);
            let h31 = case4_inner(c1, c0, h30, h20, rev, s1, s0);
            [h20, h30, h21, h31]
        }
    }
}

/// Writes the 16 coefficients `g` of face `face` (row-major `g[4 i + j]`).
#[inline]
pub fn face_g<T: Real>(topo: &PrepTopology, vd: &VertexData<T>, face: usize, g: &mut [V3<T>]) {
    for c in 0..4 {
        let v = topo.face_verts[4 * face + c] as usize;
        let k = topo.corner_sector[4 * face + c] as usize;
        let n = topo.valence[v] as usize;
        let base = topo.sector_base(v);
        let local = [
            ((0, 0), vd.limit[v]),
            ((1, 0), vd.tangent[base + k]),
            ((0, 1), vd.tangent[base + (k + 1) % n]),
            ((1, 1), vd.interior[base + k]),
        ];
        for ((i, j), x) in local {
            let (a, b) = corner_index(c, i, j, 3);
            g[4 * a + b] = x;
        }
    }
}

/// Writes the 16 non-zero `h` coefficients of face `face` in [`H_SLOTS`] order.
#[inline]
pub fn face_h<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    vd: &VertexData<T>,
    face: usize,
    h: &mut [V3<T>],
) {
    for c in 0..4 {
        let v0 = topo.face_verts[4 * face + c] as usize;
        let v1 = topo.face_verts[4 * face + (c + 1) % 4] as usize;
        let (n0, n1) = (topo.valence[v0] as usize, topo.valence[v1] as usize);
        let k = topo.corner_sector[4 * face + c] as usize;
        let m = topo.corner_sector[4 * face + (c + 1) % 4] as usize;
        let (b0, b1) = (topo.sector_base(v0), topo.sector_base(v1));
        let t0 = |x: usize| vd.tangent[b0 + x % n0];
        let t1 = |x: usize| vd.tangent[b1 + x % n1];
        let i0 = |x: usize| vd.interior[b0 + x % n0];
        let i1 = |x: usize| vd.interior[b1 + x % n1];
        let e = EdgeInputs {
            g00: vd.limit[v0],
            g10: t0(k),
            g20: t1(m + 1),
            g30: vd.limit[v1],
            g01: t0(k + 1),
            g11: i0(k),
            g21: i1(m),
            g31: t1(m),
            gs10: t0(k + n0 - 1),
            gs11: i0(k + n0 - 1),
            gs12: i1(m + 1),
            gs13: t1(m + 2),
        };
        let out = edge_h(&e, n0, n1, consts.get(n0).c, consts.get(n1).c);
        h[4 * c..4 * c + 4].copy_from_slice(&out);
    }
}

/// Parallel patch pass: `g` for every face (16 per face), `h` for every perturbed face
/// (16 per entry of `topo.perturbed_faces`).
pub fn patch_pass<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    vd: &VertexData<T>,
    g: &mut [V3<T>],
    h: &mut [V3<T>],
) {
    g.par_chunks_mut(16)
        .enumerate()
        .for_each(|(f, gf)| face_g(topo, vd, f, gf));
    h.par_chunks_mut(16)
        .zip(topo.perturbed_faces.par_iter())
        .for_each(|(hf, &f)| face_h(topo, consts, vd, f as usize, hf));
}

/// Sequential reference of [`patch_pass`].
pub fn patch_pass_seq<T: Real>(
    topo: &PrepTopology,
    consts: &ValenceTable<T>,
    vd: &VertexData<T>,
    g: &mut [V3<T>],
    h: &mut [V3<T>],
) {
    for (f, gf) in g.chunks_mut(16).enumerate() {
        face_g(topo, vd, f, gf);
    }
    for (hf, &f) in h.chunks_mut(16).zip(&topo.perturbed_faces) {
        face_h(topo, consts, vd, f as usize, hf);
    }
}
