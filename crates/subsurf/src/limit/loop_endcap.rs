//! Gregory-triangle end caps of the Loop scheme: the 18 points of a quartic Gregory triangle
//! ([`crate::patch::gregory_tri`]) for an irregular triangle of the isolation level, each as
//! a stencil over the level's vertices. The construction follows OpenSubdiv 3.5's
//! `GregoryTriConverter` (`Far::LoopPatchBuilder`, end cap `GREGORY_BASIS`) so that the end
//! caps agree with OpenSubdiv's to rounding.
//!
//! The patch is first built as a cubic/quartic hybrid (Loop, Schaefer, Ni & Castaño 2009,
//! written there for quads): per corner `k` (vertex `v`, ring `e_0 … e_{n−1}` of its edges'
//! far ends, the patch face between ring edges `r` and `r + 1`):
//!
//! - `P` is the Loop limit position, `E+`/`E−` the limit point plus a scaled limit tangent
//!   along the edge towards corner `k + 1` / `k − 1` (cubic placement). Interior corners use
//!   Loop's limit masks with the tangent scale `(3 + 2 cos θ) / (6 n)`; boundary corners the
//!   boundary B-spline `(e_0 + 4 v + e_n) / 6` and its interior tangent turned towards the
//!   edge; a sharp corner interpolates `v`; regular corners have fixed masks.
//! - Face points `F+`/`F−`: fixed masks next to regular corners, otherwise
//!
//! ```text
//! F = (cos θ_far P + (4 − 2 cos θ_near − cos θ_far) E_near + 2 cos θ_near E_far) / 4
//!     ± 7/72 (e_{i+1} − e_{i−1})
//! ```
//!
//!   with `i` the ring edge along `E_near`; a face point next to a boundary edge copies
//!   its twin.
//! - Mid-edge points `M`: the regular quartic point `(v_0 + v_1) / 3 + (v_2 + opposite) / 6`
//!   (or the midpoint of a boundary edge), else the midpoint of the two cubic edge points.
//!
//! Finally every cubic edge point is raised to quartic, `E ← P / 4 + 3 E / 4` (sharp corners
//! included: there `E = (3 v + v_next) / 4`).
//!
//! Points are stored per corner as `P, E+, E−, F+, F−` (index `5 k + …`), then `M` of
//! edges 0, 1, 2 (15, 16, 17).

use super::features::is_smooth_corner;
use super::gather::ring_position;
use super::span::{neighbours, span};
use crate::topology::tags;
use crate::topology::Topology;
use std::f64::consts::PI;

pub use super::endcap::Row;
use super::endcap::{push, row};

/// `Σ s · row` over the terms.
fn lin(terms: &[(&Row, f64)]) -> Row {
    let mut r = Row::new();
    for (src, s) in terms {
        for &(i, w) in src.iter() {
            push(&mut r, i, w * s);
        }
    }
    r
}

#[derive(Debug, Clone, Default)]
struct Corner {
    v: u32,
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

fn corner_topology(t: &Topology, f: usize, k: usize) -> Corner {
    let v = t.face_vertices(f)[k] as usize;
    let vt = t.vert_tags[v];
    let mut ring = Vec::new();
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
            ring.push(neighbours(t, g as usize, c as usize).0);
        }
        if boundary {
            let (g, c) = sp.faces[nf - 1];
            ring.push(neighbours(t, g as usize, c as usize).1);
        }
    } else {
        let edges = t.vertex_edges(v);
        boundary = vt & tags::V_BOUNDARY != 0;
        sharp = vt & tags::V_CORNER != 0 || is_smooth_corner(t, v);
        nf = t.vertex_faces(v).len();
        r = ring_position(t, v, f, k).unwrap_or(0);
        for &e in edges.iter().take(nf + boundary as usize) {
            ring.push(t.other_vertex(e as usize, v as u32));
        }
    }
    let regular = (nf << boundary as usize) == 6 && !sharp;
    let cos = if regular {
        0.5
    } else if boundary {
        (PI / nf as f64).cos()
    } else {
        (2.0 * PI / nf as f64).cos()
    };
    Corner {
        v: v as u32,
        boundary,
        sharp,
        regular,
        num_faces: nf,
        valence: nf + boundary as usize,
        face_in_ring: r,
        cos,
        ring,
        ..Default::default()
    }
}

/// The flags that depend on the neighbouring corners (OpenSubdiv's second pass).
fn classify(c: &mut [Corner; 3]) {
    for k in 0..3 {
        let next_regular = c[(k + 1) % 3].regular;
        let prev_regular = c[(k + 2) % 3].regular;
        let x = &mut c[k];
        x.fp_regular = x.regular && next_regular;
        x.fm_regular = x.regular && prev_regular;
        if x.boundary {
            x.ep_on_boundary = x.face_in_ring == 0;
            x.em_on_boundary = x.face_in_ring == x.num_faces - 1;
            if x.num_faces > 1 {
                if x.ep_on_boundary {
                    x.fp_regular = x.fm_regular;
                    x.fp_copied = !x.fp_regular;
                }
                if x.em_on_boundary {
                    x.fm_regular = x.fp_regular;
                    x.fm_copied = !x.fm_regular;
                }
            } else {
                x.fp_regular = true;
                x.fm_regular = true;
            }
        }
    }
}

/// Loop's smooth limit position mask: vertex weight, edge weight.
fn smooth_limit(n: usize) -> (f64, f64) {
    if n == 6 {
        return (0.5, 1.0 / 12.0);
    }
    let nd = n as f64;
    let beta = 0.25 * (2.0 * PI / nd).cos() + 0.375;
    let gamma = (0.625 - beta * beta) / nd;
    let e = 1.0 / (nd + 3.0 / (8.0 * gamma));
    (1.0 - e * nd, e)
}

/// `P`, cubic `E+`, `E−` of corner `c` (corner vertices `next`, `prev`).
fn edge_points(c: &Corner, next: u32, prev: u32) -> (Row, Row, Row) {
    let v = c.v;
    let ring = &c.ring;
    let r = c.face_in_ring;
    if c.regular {
        if !c.boundary {
            let mut p = row(&[(v, 0.5)]);
            for &x in ring.iter().take(6) {
                push(&mut p, x, 1.0 / 12.0);
            }
            const W: [f64; 6] = [7.0, 5.0, 1.0, -1.0, 1.0, 5.0];
            let e = |i0: usize| {
                let mut e = row(&[(v, 0.5)]);
                for (j, w) in W.iter().enumerate() {
                    push(&mut e, ring[(i0 + j) % 6], w / 36.0);
                }
                e
            };
            return (p, e(r), e((r + 1) % 6));
        }
        let p = row(&[(v, 2.0 / 3.0), (ring[0], 1.0 / 6.0), (ring[3], 1.0 / 6.0)]);
        let ep = if c.ep_on_boundary {
            row(&[(v, 2.0 / 3.0), (ring[0], 1.0 / 3.0)])
        } else {
            let o = if c.em_on_boundary { ring[3] } else { ring[0] };
            row(&[
                (v, 0.5),
                (ring[1], 1.0 / 6.0),
                (ring[2], 1.0 / 6.0),
                (o, 1.0 / 6.0),
            ])
        };
        let em = if c.em_on_boundary {
            row(&[(v, 2.0 / 3.0), (ring[3], 1.0 / 3.0)])
        } else {
            let o = if c.ep_on_boundary { ring[0] } else { ring[3] };
            row(&[
                (v, 0.5),
                (ring[1], 1.0 / 6.0),
                (ring[2], 1.0 / 6.0),
                (o, 1.0 / 6.0),
            ])
        };
        return (p, ep, em);
    }
    if c.sharp {
        return (
            row(&[(v, 1.0)]),
            row(&[(v, 2.0 / 3.0), (next, 1.0 / 3.0)]),
            row(&[(v, 2.0 / 3.0), (prev, 1.0 / 3.0)]),
        );
    }
    if !c.boundary {
        let n = c.valence;
        let (pv, pe) = smooth_limit(n);
        let theta = 2.0 * PI / n as f64;
        let scale = (3.0 + 2.0 * theta.cos()) / (6.0 * n as f64);
        let mut p = row(&[(v, pv)]);
        for &x in ring.iter().take(n) {
            push(&mut p, x, pe);
        }
        // The point along edge `i0`: the tangent mask `cos(i θ)` turned to start there.
        let e = |i0: usize| {
            let mut e = row(&[(v, pv)]);
            for j in 0..n {
                let w = pe + scale * (theta * j as f64).cos();
                push(&mut e, ring[(i0 + j) % n], w);
            }
            e
        };
        return (p, e(r), e((r + 1) % n));
    }
    if c.num_faces == 1 {
        return (
            row(&[(v, 4.0 / 6.0), (next, 1.0 / 6.0), (prev, 1.0 / 6.0)]),
            row(&[(v, 2.0 / 3.0), (next, 1.0 / 3.0)]),
            row(&[(v, 2.0 / 3.0), (prev, 1.0 / 3.0)]),
        );
    }
    // Boundary corner with two or more faces: ring edges 0 ..= last, last = number of faces.
    let nf = c.num_faces;
    let last = nf;
    let p = row(&[
        (v, 4.0 / 6.0),
        (ring[0], 1.0 / 6.0),
        (ring[last], 1.0 / 6.0),
    ]);
    // Loop's crease tangent across the interior (vertex weight, edge weights).
    let m = nf - 1;
    let mut t2 = vec![0.0; last + 1];
    let t2v;
    if m == 1 {
        t2v = -3.0;
        t2[1] = 3.0;
    } else if m == 2 {
        let r3 = 3.0f64.sqrt();
        t2v = -r3;
        t2[0] = -r3 / 2.0;
        t2[last] = -r3 / 2.0;
        t2[1] = r3;
        t2[2] = r3;
    } else {
        let th = PI / (m + 1) as f64;
        t2v = 0.0;
        t2[0] = -3.0 * th.sin();
        t2[last] = t2[0];
        let ec = -6.0 * (th.cos() - 1.0);
        for (i, w) in t2.iter_mut().enumerate().take(m + 1).skip(1) {
            *w = ec * (i as f64 * th).sin();
        }
    }
    let along = |edge: usize| {
        let a = PI / nf as f64 * edge as f64;
        let (s, co) = (a.sin() / 24.0, a.cos());
        let mut e = row(&[(v, 4.0 / 6.0 + t2v * s)]);
        for (i, w) in t2.iter().enumerate() {
            let mut w = w * s;
            if i == 0 {
                w += 1.0 / 6.0 + co / 6.0;
            } else if i == last {
                w += 1.0 / 6.0 - co / 6.0;
            }
            push(&mut e, ring[i], w);
        }
        e
    };
    let ep = if c.ep_on_boundary {
        row(&[(v, 2.0 / 3.0), (ring[0], 1.0 / 3.0)])
    } else {
        along(r)
    };
    let em = if c.em_on_boundary {
        row(&[(v, 2.0 / 3.0), (ring[last], 1.0 / 3.0)])
    } else {
        along(r + 1)
    };
    (p, ep, em)
}

/// The regular face point of corner `c` (the same for `F+` and `F−`).
fn regular_face_point(c: &Corner, next: u32, prev: u32) -> Row {
    let (v, ring) = (c.v, &c.ring);
    if c.num_faces == 1 && c.boundary {
        row(&[(v, 0.5), (next, 0.25), (prev, 0.25)])
    } else if c.ep_on_boundary {
        let w = [11.0, 7.0, 5.0, 1.0].map(|x| x / 24.0);
        row(&[(v, w[0]), (ring[0], w[1]), (ring[1], w[2]), (ring[2], w[3])])
    } else if c.em_on_boundary {
        let w = [11.0, 7.0, 5.0, 1.0].map(|x| x / 24.0);
        row(&[(v, w[0]), (ring[3], w[1]), (ring[2], w[2]), (ring[1], w[3])])
    } else {
        let r = c.face_in_ring;
        let (e_next, e_prev) = if c.boundary {
            (0, 3)
        } else {
            ((r + 5) % 6, (r + 2) % 6)
        };
        row(&[
            (v, 10.0 / 24.0),
            (prev, 0.25),
            (next, 0.25),
            (ring[e_prev], 1.0 / 24.0),
            (ring[e_next], 1.0 / 24.0),
        ])
    }
}

/// The irregular face point of corner `near` next to ring edge `edge`, towards `far`.
fn irregular_face_point(
    near: &Corner,
    edge: usize,
    far: &Corner,
    p: &Row,
    e_near: &Row,
    e_far: &Row,
    sign: f64,
) -> Row {
    let (cn, cf) = (near.cos, far.cos);
    let mut f = lin(&[
        (p, cf / 4.0),
        (e_near, (4.0 - 2.0 * cn - cf) / 4.0),
        (e_far, 2.0 * cn / 4.0),
    ]);
    let n = near.valence;
    let s = 0.25 * (7.0 / 18.0);
    push(&mut f, near.ring[(edge + n - 1) % n], -sign * s);
    push(&mut f, near.ring[(edge + 1) % n], sign * s);
    f
}

/// The 18 Gregory-triangle points of face `f` (a triangle) of level `t`, as stencils over
/// `t`'s vertices, in the order of [`crate::patch::gregory_tri`].
pub fn gregory_tri_points(t: &Topology, f: usize) -> Vec<Row> {
    let mut c = [0, 1, 2].map(|k| corner_topology(t, f, k));
    classify(&mut c);
    let cv = [c[0].v, c[1].v, c[2].v];
    let mut pts: Vec<Row> = vec![Row::new(); 18];
    for k in 0..3 {
        let (p, ep, em) = edge_points(&c[k], cv[(k + 1) % 3], cv[(k + 2) % 3]);
        pts[5 * k] = p;
        pts[5 * k + 1] = ep;
        pts[5 * k + 2] = em;
    }
    for k in 0..3 {
        let (kn, kp) = ((k + 1) % 3, (k + 2) % 3);
        let x = &c[k];
        if x.fp_regular || x.fm_regular {
            let reg = regular_face_point(x, cv[kn], cv[kp]);
            if x.fp_regular {
                pts[5 * k + 3] = reg.clone();
            }
            if x.fm_regular {
                pts[5 * k + 4] = reg;
            }
        }
        if !x.fp_regular && !x.fp_copied {
            pts[5 * k + 3] = irregular_face_point(
                x,
                x.face_in_ring,
                &c[kn],
                &pts[5 * k],
                &pts[5 * k + 1],
                &pts[5 * kn + 2],
                1.0,
            );
        }
        if !x.fm_regular && !x.fm_copied {
            pts[5 * k + 4] = irregular_face_point(
                x,
                (x.face_in_ring + 1) % x.valence,
                &c[kp],
                &pts[5 * k],
                &pts[5 * k + 2],
                &pts[5 * kp + 1],
                -1.0,
            );
        }
        if x.fp_copied {
            pts[5 * k + 3] = pts[5 * k + 4].clone();
        }
        if x.fm_copied {
            pts[5 * k + 4] = pts[5 * k + 3].clone();
        }
    }
    for e in 0..3 {
        let (c0, c1) = (&c[e], &c[(e + 1) % 3]);
        let boundary_edge = c0.ep_on_boundary && c1.em_on_boundary;
        let dart_edge = c0.ep_on_boundary != c1.em_on_boundary;
        pts[15 + e] = if boundary_edge || (c0.regular && c1.regular && !dart_edge) {
            if c0.ep_on_boundary {
                row(&[(cv[e], 0.5), (cv[(e + 1) % 3], 0.5)])
            } else {
                let r = c0.face_in_ring;
                let o = if c0.boundary { r - 1 } else { (r + 5) % 6 };
                row(&[
                    (cv[e], 1.0 / 3.0),
                    (cv[(e + 1) % 3], 1.0 / 3.0),
                    (cv[(e + 2) % 3], 1.0 / 6.0),
                    (c0.ring[o], 1.0 / 6.0),
                ])
            }
        } else {
            lin(&[(&pts[5 * e + 1], 0.5), (&pts[5 * ((e + 1) % 3) + 2], 0.5)])
        };
    }
    for k in 0..3 {
        for j in [1, 2] {
            pts[5 * k + j] = lin(&[(&pts[5 * k], 0.25), (&pts[5 * k + j], 0.75)]);
        }
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_affine_on_a_fan() {
        // An interior valence-5 vertex (irregular) with its fan: every point's weights sum
        // to one, so the patch reproduces translations.
        let n = 5usize;
        let mut faces = Vec::new();
        for i in 0..n {
            faces.push([0u32, 1 + i as u32, 1 + ((i + 1) % n) as u32]);
        }
        let mut positions = vec![[0.0f32; 3]];
        for i in 0..n {
            let a = 2.0 * PI * i as f64 / n as f64;
            positions.push([a.cos() as f32, a.sin() as f32, 0.0]);
        }
        let mesh = crate::mesh::Mesh::from_faces(positions, &faces);
        let t = Topology::new(&mesh).unwrap();
        for f in 0..n {
            for r in gregory_tri_points(&t, f) {
                assert!(!r.is_empty());
                let s: f64 = r.iter().map(|x| x.1).sum();
                assert!((s - 1.0).abs() < 1e-12, "{s}");
            }
        }
    }
}
