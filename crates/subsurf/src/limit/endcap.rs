//! Gregory-basis end caps: the 20 control points of a Gregory patch (Loop, Schaefer, Ni &
//! Castaño 2009) for an irregular face at the isolation level, each as a stencil over the
//! level's vertices. The construction follows OpenSubdiv 3.5's `GregoryConverter`
//! (`Far::CatmarkPatchBuilder`, its `ENDCAP_GREGORY_BASIS`) so that end caps agree with
//! OpenSubdiv's to rounding.
//!
//! Per corner `k` (vertex `v`, `n` incident faces, the patch face at ring position `r`):
//!
//! - `P` is the limit position, `E+`/`E−` are `P` plus a third of the limit tangent along the
//!   edge towards corner `k + 1` / `k − 1`. Regular corners use the B-spline masks (interior:
//!   `P = (16 v + 4 Σ e_i + Σ d_i) / 36`); extraordinary interior corners the eigen-analysis
//!   masks with OpenSubdiv's tangent scale `λ`-table; boundary corners the boundary limit
//!   curve `(e_0 + 4 v + e_n) / 6` and its interior tangent; a sharp corner (and, as
//!   OpenSubdiv's default legacy option has it, a smooth one-face corner) interpolates `v`.
//! - Face points `F+`/`F−`: at a corner whose neighbour along the edge is regular too,
//!   the bicubic point `(4 v + 2 c_{k−1} + 2 c_{k+1} + c_{k+2}) / 9`; otherwise
//!
//! ```text
//! F = cos θ_far / 3 · P + (3 − 2 cos θ_near − cos θ_far) / 3 · E_near + 2 cos θ_near / 3 · E_far
//!     ± (−e_{i−1}/9 − d_{i−1}/18 + d_i/18 + e_{i+1}/9)
//! ```
//!
//! with `θ = 2π/n` (interior) or `π/n` (boundary), `π/2` at regular corners, `e_i`/`d_i` the
//! ring's edge and diagonal points and `i` the ring edge along which `E_near` lies. On a
//! boundary corner the face point next to the boundary edge copies its twin.
//!
//! Points are stored per corner as `P, E+, E−, F+, F−` (index `5 k + …`), the layout of
//! [`crate::patch::gregory`].

use super::features::is_smooth_corner;
use super::gather::ring_position;
use super::span::{neighbours, span};
use crate::topology::tags;
use crate::topology::Topology;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::hash::{BuildHasherDefault, Hasher};

/// A sparse combination of level vertices.
pub type Row = Vec<(u32, f64)>;

/// `dst += s · src`. Every row holds each vertex once, so into an empty row this is a copy.
fn add(dst: &mut Row, src: &Row, s: f64) {
    if dst.is_empty() {
        dst.extend(src.iter().map(|&(i, w)| (i, w * s)));
        return;
    }
    extend(dst, src.iter().map(|&(i, w)| (i, w * s)));
}

pub(crate) fn push(dst: &mut Row, i: u32, w: f64) {
    match dst.iter_mut().find(|(j, _)| *j == i) {
        Some(e) => e.1 += w,
        None => dst.push((i, w)),
    }
}

/// Multiplicative hash of a vertex index (Knuth 1973, "Sorting and Searching", 6.4).
#[derive(Default)]
struct IndexHasher(u64);

impl Hasher for IndexHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ b as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }
    fn write_u32(&mut self, i: u32) {
        self.0 = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// Rows longer than this merge through a hash map (rings of high-valence vertices).
const LINEAR_MERGE: usize = 32;

/// [`push`] of every item in turn (same entry order, same sums), in linear time for long
/// rows.
fn extend(dst: &mut Row, items: impl ExactSizeIterator<Item = (u32, f64)>) {
    if dst.len() + items.len() <= LINEAR_MERGE {
        for (i, w) in items {
            push(dst, i, w);
        }
        return;
    }
    let mut at: HashMap<u32, usize, BuildHasherDefault<IndexHasher>> =
        HashMap::with_capacity_and_hasher(dst.len() + items.len(), Default::default());
    at.extend(dst.iter().enumerate().map(|(k, &(i, _))| (i, k)));
    for (i, w) in items {
        match at.get(&i) {
            Some(&k) => dst[k].1 += w,
            None => {
                at.insert(i, dst.len());
                dst.push((i, w));
            }
        }
    }
}

pub(crate) fn row(entries: &[(u32, f64)]) -> Row {
    let mut r = Row::with_capacity(entries.len());
    for &(i, w) in entries {
        push(&mut r, i, w);
    }
    r
}

#[derive(Debug, Clone, Default)]
struct Corner {
    boundary: bool,
    sharp: bool,
    regular: bool,
    num_faces: usize,
    valence: usize,
    face_in_ring: usize,
    cos: f64,
    ring: Vec<u32>,
    ep_on_boundary: bool,
    em_on_boundary: bool,
    fp_regular: bool,
    fm_regular: bool,
    fp_copied: bool,
    fm_copied: bool,
}

/// Tangent scale of the interior limit masks, from the subdominant eigenvalue of the
/// Catmull-Clark subdivision matrix: `16 / (n ((c + 5) + √((c + 9)(c + 1))))`, `c = cos 2π/n`
/// (0 below valence 3, where OpenSubdiv uses no tangent).
fn tangent_coefficient(n: usize) -> f64 {
    if n < 3 {
        return 0.0;
    }
    let c = (2.0 * PI / n as f64).cos();
    16.0 / n as f64 / ((c + 5.0) + ((c + 9.0) * (c + 1.0)).sqrt())
}

/// Limit position and edge points of an extraordinary interior vertex, as weights of
/// `[v, ring…]` (width `1 + 2n`).
fn interior_weights(n: usize, r: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let w = 1 + 2 * n;
    let nf = n as f64;
    let p_coeff = 1.0 / nf / (nf + 5.0);
    let tan_coeff = tangent_coefficient(n) * 0.5 / (nf + 5.0);
    let angle = 2.0 * PI / nf;
    let mut p = vec![0.0; w];
    let mut tw = vec![0.0; w];
    p[0] = nf / (nf + 5.0);
    for i in 0..n {
        p[1 + 2 * i] = 4.0 * p_coeff;
        p[2 + 2 * i] = p_coeff;
        let (ip, inx) = ((i + n - 1) % n, (i + 1) % n);
        let c = tan_coeff * (angle * i as f64).cos();
        tw[1 + 2 * ip] += 2.0 * c;
        tw[2 + 2 * ip] += c;
        tw[1 + 2 * i] += 4.0 * c;
        tw[2 + 2 * i] += c;
        tw[1 + 2 * inx] += 2.0 * c;
    }
    let ep_off = 2 * ((n - r) % n);
    let em_off = 2 * ((2 * n - r - 1) % n);
    let mut ep = vec![0.0; w];
    let mut em = vec![0.0; w];
    ep[0] = p[0];
    em[0] = p[0];
    for i in 1..w {
        let mut a = i + ep_off;
        if a >= w {
            a -= w - 1;
        }
        let mut b = i + em_off;
        if b >= w {
            b -= w - 1;
        }
        ep[i] = p[i] + tw[a];
        em[i] = p[i] + tw[b];
    }
    (p, ep, em)
}

/// Limit position and edge points of an extraordinary boundary vertex with `nf` faces, as
/// weights of `[v, ring…]` (width `2 (nf + 1)`).
fn boundary_weights(nf: usize, r: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let valence = nf + 1;
    let w = 2 * valence;
    let last = w - 1;
    let theta = PI / nf as f64;
    let mut p = vec![0.0; w];
    p[0] = 4.0 / 6.0;
    p[1] = 1.0 / 6.0;
    p[last] = 1.0 / 6.0;
    let k = nf as f64;
    let (c, s) = (theta.cos(), theta.sin());
    let div3kc = 1.0 / (3.0 * k + c);
    let mut tw = vec![0.0; w];
    tw[0] = -4.0 * s * div3kc / 3.0;
    let alpha0 = -((1.0 + 2.0 * c) * (1.0 + c).sqrt()) * div3kc / (1.0 - c).sqrt();
    tw[1] = alpha0 / 3.0;
    tw[2] = s * div3kc / 3.0;
    tw[last] = alpha0 / 3.0;
    for i in 1..valence - 1 {
        let (si, si1) = ((theta * i as f64).sin(), (theta * (i + 1) as f64).sin());
        tw[1 + 2 * i] = 4.0 * si * div3kc / 3.0;
        tw[2 + 2 * i] = (si + si1) * div3kc / 3.0;
    }
    let along = |edge: usize| -> Vec<f64> {
        let a = theta * edge as f64;
        let mut e: Vec<f64> = tw.iter().map(|x| x * a.sin()).collect();
        e[0] += p[0];
        e[1] += p[1] + a.cos() / 6.0;
        e[last] += p[last] - a.cos() / 6.0;
        e
    };
    let ep = if r == 0 {
        let mut e = vec![0.0; w];
        e[0] = 2.0 / 3.0;
        e[1] = 1.0 / 3.0;
        e
    } else {
        along(r)
    };
    let em = if r == nf - 1 {
        let mut e = vec![0.0; w];
        e[0] = 2.0 / 3.0;
        e[last] = 1.0 / 3.0;
        e
    } else {
        along((r + 1) % valence)
    };
    (p, ep, em)
}

fn corner_topology(t: &Topology, f: usize, k: usize) -> Corner {
    let v = t.face_vertices(f)[k] as usize;
    let vt = t.vert_tags[v];
    let mut ring = Vec::with_capacity(2 * t.vertex_faces(t.face_vertices(f)[k] as usize).len() + 1);
    let (boundary, sharp, nf, r);
    if vt & tags::V_NON_MANIFOLD != 0 {
        // The manifold span around the corner stands for the vertex's ring.
        let sp = span(t, f, k);
        nf = sp.faces.len();
        boundary = !sp.cyclic;
        sharp = vt & tags::V_CORNER != 0 || t.vert_sharpness[v] >= crate::SHARPNESS_INFINITE;
        r = sp
            .faces
            .iter()
            .position(|&(g, c)| g as usize == f && c as usize == k)
            .unwrap_or(0);
        for &(g, c) in &sp.faces {
            let (next, _, opp) = neighbours(t, g as usize, c as usize);
            ring.push(next);
            ring.push(opp);
        }
        if boundary {
            let (g, c) = sp.faces[nf - 1];
            ring.push(neighbours(t, g as usize, c as usize).1);
        }
    } else {
        let faces = t.vertex_faces(v);
        let locals = t.vertex_faces_local(v);
        let edges = t.vertex_edges(v);
        boundary = vt & tags::V_BOUNDARY != 0;
        sharp = vt & tags::V_CORNER != 0 || is_smooth_corner(t, v);
        nf = faces.len();
        r = ring_position(t, v, f, k).unwrap_or(0);
        for i in 0..nf {
            let e = edges.get(i).copied().unwrap_or(edges[0]);
            ring.push(t.other_vertex(e as usize, v as u32));
            let g = faces[i] as usize;
            let fv = t.face_vertices(g);
            ring.push(fv[(locals[i] as usize + 2) % fv.len()]);
        }
        if boundary && edges.len() > nf {
            ring.push(t.other_vertex(edges[nf] as usize, v as u32));
        }
    }
    let regular = (nf << boundary as usize) == 4 && !sharp;
    let angle = if regular {
        PI / 2.0
    } else if boundary {
        PI / nf as f64
    } else {
        2.0 * PI / nf as f64
    };
    Corner {
        boundary,
        sharp,
        regular,
        num_faces: nf,
        valence: nf + boundary as usize,
        face_in_ring: r,
        cos: if regular { 0.0 } else { angle.cos() },
        ring,
        ..Default::default()
    }
}

/// The 20 Gregory points of face `f` (a quad) of level `t`, as stencils over `t`'s vertices.
pub fn gregory_points(t: &Topology, f: usize) -> [Row; 20] {
    let fv: Vec<u32> = t.face_vertices(f).to_vec();
    let mut cs: Vec<Corner> = (0..4).map(|k| corner_topology(t, f, k)).collect();
    for k in 0..4 {
        let (next, prev) = (cs[(k + 1) % 4].regular, cs[(k + 3) % 4].regular);
        let c = &mut cs[k];
        c.fp_regular = c.regular && next;
        c.fm_regular = c.regular && prev;
        if c.boundary {
            c.ep_on_boundary = c.face_in_ring == 0;
            c.em_on_boundary = c.face_in_ring + 1 == c.num_faces;
            if c.num_faces > 1 {
                if c.ep_on_boundary {
                    c.fp_regular = c.fm_regular;
                    c.fp_copied = !c.fp_regular;
                }
                if c.em_on_boundary {
                    c.fm_regular = c.fp_regular;
                    c.fm_copied = !c.fm_regular;
                }
            } else {
                c.fp_regular = true;
                c.fm_regular = true;
            }
        }
    }
    let mut pts: [Row; 20] = Default::default();
    for k in 0..4 {
        let (p, ep, em) = edge_points(&cs[k], fv[k], fv[(k + 1) % 4], fv[(k + 3) % 4]);
        pts[5 * k] = p;
        pts[5 * k + 1] = ep;
        pts[5 * k + 2] = em;
    }
    for k in 0..4 {
        let (next, opp, prev) = ((k + 1) % 4, (k + 2) % 4, (k + 3) % 4);
        let c = &cs[k];
        let regular_f = row(&[
            (fv[k], 4.0 / 9.0),
            (fv[prev], 2.0 / 9.0),
            (fv[next], 2.0 / 9.0),
            (fv[opp], 1.0 / 9.0),
        ]);
        if c.fp_regular {
            pts[5 * k + 3] = regular_f.clone();
        }
        if c.fm_regular {
            pts[5 * k + 4] = regular_f;
        }
        if !c.fp_regular && !c.fp_copied {
            pts[5 * k + 3] = face_point(
                c,
                &cs[next],
                c.face_in_ring,
                &pts[5 * k],
                &pts[5 * k + 1],
                &pts[5 * next + 2],
                1.0,
            );
        }
        if !c.fm_regular && !c.fm_copied {
            pts[5 * k + 4] = face_point(
                c,
                &cs[prev],
                (c.face_in_ring + 1) % c.valence.max(1),
                &pts[5 * k],
                &pts[5 * k + 2],
                &pts[5 * prev + 1],
                -1.0,
            );
        }
        if c.fp_copied {
            pts[5 * k + 3] = pts[5 * k + 4].clone();
        }
        if c.fm_copied {
            pts[5 * k + 4] = pts[5 * k + 3].clone();
        }
    }
    pts
}

fn edge_points(c: &Corner, v: u32, next: u32, prev: u32) -> (Row, Row, Row) {
    let ring = &c.ring;
    let g = |i: usize| ring.get(i).copied().unwrap_or(v);
    if c.regular && !c.boundary {
        let r = c.face_in_ring;
        let p = row(&[
            (v, 4.0 / 9.0),
            (g(0), 1.0 / 9.0),
            (g(2), 1.0 / 9.0),
            (g(4), 1.0 / 9.0),
            (g(6), 1.0 / 9.0),
            (g(1), 1.0 / 36.0),
            (g(3), 1.0 / 36.0),
            (g(5), 1.0 / 36.0),
            (g(7), 1.0 / 36.0),
        ]);
        let (iep, iem, iop, iom) = (
            2 * r,
            2 * ((r + 1) & 3),
            2 * ((r + 2) & 3),
            2 * ((r + 3) & 3),
        );
        let ep = row(&[
            (v, 4.0 / 9.0),
            (g(iep), 2.0 / 9.0),
            (g(iem), 1.0 / 9.0),
            (g(iom), 1.0 / 9.0),
            (g(iep + 1), 1.0 / 18.0),
            (g(iom + 1), 1.0 / 18.0),
        ]);
        let em = row(&[
            (v, 4.0 / 9.0),
            (g(iem), 2.0 / 9.0),
            (g(iep), 1.0 / 9.0),
            (g(iop), 1.0 / 9.0),
            (g(iep + 1), 1.0 / 18.0),
            (g(iem + 1), 1.0 / 18.0),
        ]);
        (p, ep, em)
    } else if c.regular {
        let p = row(&[(v, 2.0 / 3.0), (g(0), 1.0 / 6.0), (g(4), 1.0 / 6.0)]);
        let on_b = c.ep_on_boundary;
        let eb = row(&[(v, 2.0 / 3.0), (g(if on_b { 0 } else { 4 }), 1.0 / 3.0)]);
        let ei = row(&[
            (v, 4.0 / 9.0),
            (g(2), 2.0 / 9.0),
            (g(0), 1.0 / 9.0),
            (g(4), 1.0 / 9.0),
            (g(1), 1.0 / 18.0),
            (g(3), 1.0 / 18.0),
        ]);
        if on_b {
            (p, eb, ei)
        } else {
            (p, ei, eb)
        }
    } else if c.sharp {
        (
            row(&[(v, 1.0)]),
            row(&[(v, 2.0 / 3.0), (next, 1.0 / 3.0)]),
            row(&[(v, 2.0 / 3.0), (prev, 1.0 / 3.0)]),
        )
    } else if !c.boundary {
        let (pw, epw, emw) = interior_weights(c.valence, c.face_in_ring);
        let conv = |w: &[f64]| {
            let mut r = Row::with_capacity(w.len());
            r.push((v, w[0]));
            extend(&mut r, (1..w.len()).map(|i| (g(i - 1), w[i])));
            r
        };
        (conv(&pw), conv(&epw), conv(&emw))
    } else if c.num_faces > 1 {
        let (pw, epw, emw) = boundary_weights(c.num_faces, c.face_in_ring);
        let conv = |w: &[f64]| {
            let mut r = row(&[(v, w[0])]);
            let nz: Vec<(u32, f64)> = (1..w.len())
                .filter(|&i| w[i] != 0.0)
                .map(|i| (g(i - 1), w[i]))
                .collect();
            extend(&mut r, nz.into_iter());
            r
        };
        (conv(&pw), conv(&epw), conv(&emw))
    } else {
        (
            row(&[(v, 4.0 / 6.0), (next, 1.0 / 6.0), (prev, 1.0 / 6.0)]),
            row(&[(v, 2.0 / 3.0), (next, 1.0 / 3.0)]),
            row(&[(v, 2.0 / 3.0), (prev, 1.0 / 3.0)]),
        )
    }
}

fn face_point(
    near: &Corner,
    far: &Corner,
    edge: usize,
    p: &Row,
    e_near: &Row,
    e_far: &Row,
    sign: f64,
) -> Row {
    let mut f = Row::with_capacity(p.len() + e_near.len() + e_far.len() + 4);
    add(&mut f, p, far.cos / 3.0);
    add(&mut f, e_near, (3.0 - 2.0 * near.cos - far.cos) / 3.0);
    add(&mut f, e_far, 2.0 * near.cos / 3.0);
    let n = near.valence.max(1);
    let (prev, next) = ((edge + n - 1) % n, (edge + 1) % n);
    let ring = &near.ring;
    let mut put = |i: usize, w: f64| {
        if let Some(&x) = ring.get(i) {
            push(&mut f, x, w);
        }
    };
    put(2 * prev, -sign / 9.0);
    put(2 * prev + 1, -sign / 18.0);
    put(2 * edge + 1, sign / 18.0);
    put(2 * next, sign / 9.0);
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hashed_merge_equals_repeated_push() {
        // A ring of a valence-200 vertex with repeats, merged into a row that already has
        // entries: same entries, same order, bit-identical sums.
        let mut a: Row = vec![(7, 0.5), (3, 0.25)];
        let items: Vec<(u32, f64)> = (0..400u32)
            .map(|k| ((k * 37) % 251, 1.0 / (k as f64 + 3.0)))
            .collect();
        let mut b = a.clone();
        for &(i, w) in &items {
            push(&mut a, i, w);
        }
        extend(&mut b, items.iter().copied());
        assert!(b.len() > LINEAR_MERGE);
        assert_eq!(a, b);
    }
}
