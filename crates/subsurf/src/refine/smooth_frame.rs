//! The per-frame evaluation of one refinement step with fewer bytes read per child vertex.
//!
//! Most rows of a step's [`LevelStencils`] follow the smooth Catmull-Clark rules (Catmull &
//! Clark 1978), whose weights are known from the row's class alone:
//!
//! - a face point of a quad: its four vertices (the parent's face-vertex list), `1/4` each;
//! - a smooth edge point: its two faces' points, then its two ends, `1/4` each;
//! - a smooth vertex of valence `n`: its `n` faces' points, its `n` neighbours (the parent's
//!   vertex-face and vertex-edge rings), `1/n²` each, then itself, `(n - 2)/n`.
//!
//! A [`StepPlan`] finds those rows once, by reading the stored rows themselves (so it knows
//! nothing of rules or topology: a row is smooth when its entries have exactly the smooth
//! pattern and weights, bit for bit), and keeps the rows where the rules differ (creases,
//! boundaries, corners, irregular faces or rules) as a sorted list of exceptions. Applying
//! the plan then reads, per smooth row, only its input indices: no weight, and for face and
//! edge points no row offset either (their length is known). Exceptions are evaluated from
//! their stored rows. Every row is summed in the stored entry order with the stored weights,
//! so the result is bit-identical to [`LevelStencils::apply`].

use super::masks::LevelStencils;
use super::stencil::StencilTable;
use rayon::prelude::*;

/// Rows per parallel chunk.
const CHUNK: usize = 4096;

/// The smooth rows and the exceptions of one step's tables (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct StepPlan {
    /// Whether most rows are exceptions (a bilinear step, say): the stored tables are then
    /// applied as they are.
    stencils_only: bool,
    /// Whether every face row has four entries of weight `1/4` (an all-quad parent).
    quad_faces: bool,
    /// Vertex rows that are not the smooth rule, ascending.
    vertex_special: Vec<u32>,
    /// Edge rows that are not the smooth two-face rule, ascending.
    edge_special: Vec<u32>,
    /// `(1/n², (n - 2)/n)` of a smooth vertex of valence `n`, as the tables store them.
    valence_weights: Vec<[f32; 2]>,
}

/// Weights of the smooth vertex rule at valence `n`, computed as the tables compute them.
fn smooth_vertex_weights(n: usize) -> [f32; 2] {
    [1.0 / (n * n) as f32, (n as f32 - 2.0) / n as f32]
}

/// Largest valence with a precomputed weight pair; higher valences are exceptions.
const MAX_VALENCE: usize = 32;

impl StepPlan {
    /// Classifies the rows of `s`.
    pub(crate) fn new(s: &LevelStencils) -> StepPlan {
        let p = s.num_parent_vertices as u32;
        let quarter = 0.25f32.to_bits();
        let f = &s.face;
        let quad_faces = f
            .offsets
            .iter()
            .enumerate()
            .all(|(i, &o)| o as usize == 4 * i)
            && f.weights.iter().all(|w| w.to_bits() == quarter);
        let valence_weights: Vec<[f32; 2]> = (0..=MAX_VALENCE)
            .map(|n| {
                if n == 0 {
                    [0.0; 2]
                } else {
                    smooth_vertex_weights(n)
                }
            })
            .collect();
        let vw = &valence_weights;
        let vertex_special = specials(&s.vertex, |idx, w| {
            let len = idx.len();
            if len % 2 == 0 || !(3..=2 * MAX_VALENCE + 1).contains(&len) {
                return false;
            }
            let n = len / 2;
            let [a, b] = vw[n].map(f32::to_bits);
            idx[..n].iter().all(|&k| k >= p)
                && idx[n..].iter().all(|&k| k < p)
                && w[..2 * n].iter().all(|x| x.to_bits() == a)
                && w[2 * n].to_bits() == b
        });
        let edge_special = specials(&s.edge, |idx, w| {
            idx.len() == 4
                && idx[0] >= p
                && idx[1] >= p
                && idx[2] < p
                && idx[3] < p
                && w.iter().all(|x| x.to_bits() == quarter)
        });
        let exceptions = vertex_special.len() + edge_special.len();
        StepPlan {
            stencils_only: 2 * exceptions > s.vertex.num_rows() + s.edge.num_rows(),
            quad_faces,
            vertex_special,
            edge_special,
            valence_weights,
        }
    }

    /// Number of rows evaluated from their stored rows (vertex and edge exceptions).
    #[cfg(test)]
    pub(crate) fn num_exceptions(&self) -> usize {
        self.vertex_special.len() + self.edge_special.len()
    }

    /// One step of `N`-component values, bit-identical to [`LevelStencils::apply`] (`s` is the
    /// step this plan was made from), in parallel chunks of rows.
    pub(crate) fn apply<const N: usize>(
        &self,
        s: &LevelStencils,
        src: &[[f32; N]],
        dst: &mut [[f32; N]],
    ) {
        assert_eq!(dst.len(), s.num_rows(), "destination length");
        assert!(src.len() >= s.num_parent_vertices, "source length");
        if self.stencils_only {
            s.apply(src, dst);
            return;
        }
        let (nv, nf) = (s.vertex.num_rows(), s.face.num_rows());
        let (vd, rest) = dst.split_at_mut(nv);
        let (fd, ed) = rest.split_at_mut(nf);
        if self.quad_faces {
            let idx = &s.face.indices;
            fd.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
                let q = &idx[4 * c * CHUNK..4 * (c * CHUNK + out.len())];
                for (o, q) in out.iter_mut().zip(q.chunks_exact(4)) {
                    let mut acc = [0.0f32; N];
                    for &k in q {
                        let v = &src[k as usize];
                        for (a, x) in acc.iter_mut().zip(v) {
                            *a += 0.25 * x;
                        }
                    }
                    *o = acc;
                }
            });
        } else {
            s.face.apply(src, fd);
        }
        let fd: &[[f32; N]] = fd;
        let p = s.num_parent_vertices;
        vd.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
            self.vertex_rows(&s.vertex, p, c * CHUNK, out, src, fd);
        });
        ed.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
            edge_rows(&s.edge, &self.edge_special, p, c * CHUNK, out, src, fd);
        });
    }

    /// Vertex rows `first..first + out.len()`.
    fn vertex_rows<const N: usize>(
        &self,
        t: &StencilTable,
        p: usize,
        first: usize,
        out: &mut [[f32; N]],
        src: &[[f32; N]],
        fd: &[[f32; N]],
    ) {
        let mut special = in_range(&self.vertex_special, first, out.len()).iter();
        let mut next = special.next().map_or(usize::MAX, |&r| r as usize);
        let offs = &t.offsets[first..=first + out.len()];
        for (i, (o, w2)) in out.iter_mut().zip(offs.windows(2)).enumerate() {
            let (lo, hi) = (w2[0] as usize, w2[1] as usize);
            let idx = &t.indices[lo..hi];
            if first + i == next {
                *o = general_row(idx, &t.weights[lo..hi], p, src, fd);
                next = special.next().map_or(usize::MAX, |&r| r as usize);
                continue;
            }
            let n = idx.len() / 2;
            let [w, wv] = self.valence_weights[n];
            *o = if n == 4 {
                smooth_vertex4(idx[..9].try_into().expect("9 entries"), w, wv, p, src, fd)
            } else {
                let mut acc = [0.0f32; N];
                for &k in &idx[..n] {
                    add(&mut acc, w, &fd[k as usize - p]);
                }
                for &k in &idx[n..2 * n] {
                    add(&mut acc, w, &src[k as usize]);
                }
                add(&mut acc, wv, &src[idx[2 * n] as usize]);
                acc
            };
        }
    }
}

/// `acc += w · v`, component by component (the tables' accumulation).
#[inline(always)]
fn add<const N: usize>(acc: &mut [f32; N], w: f32, v: &[f32; N]) {
    for (a, x) in acc.iter_mut().zip(v) {
        *a += w * x;
    }
}

/// A smooth vertex row of valence 4 (9 entries), unrolled.
#[inline(always)]
fn smooth_vertex4<const N: usize>(
    idx: &[u32; 9],
    w: f32,
    wv: f32,
    p: usize,
    src: &[[f32; N]],
    fd: &[[f32; N]],
) -> [f32; N] {
    let mut acc = [0.0f32; N];
    for &k in &idx[..4] {
        add(&mut acc, w, &fd[k as usize - p]);
    }
    for &k in &idx[4..8] {
        add(&mut acc, w, &src[k as usize]);
    }
    add(&mut acc, wv, &src[idx[8] as usize]);
    acc
}

/// Edge rows `first..first + out.len()`: smooth rows are four indices at a known stride from
/// the chunk's first offset; only exceptions read their offsets and weights.
fn edge_rows<const N: usize>(
    t: &StencilTable,
    special: &[u32],
    p: usize,
    first: usize,
    out: &mut [[f32; N]],
    src: &[[f32; N]],
    fd: &[[f32; N]],
) {
    let mut special = in_range(special, first, out.len()).iter();
    let mut next = special.next().map_or(usize::MAX, |&r| r as usize);
    let mut j = t.offsets[first] as usize;
    for (i, o) in out.iter_mut().enumerate() {
        let r = first + i;
        if r == next {
            let hi = t.offsets[r + 1] as usize;
            *o = general_row(&t.indices[j..hi], &t.weights[j..hi], p, src, fd);
            j = hi;
            next = special.next().map_or(usize::MAX, |&r| r as usize);
            continue;
        }
        let q = &t.indices[j..j + 4];
        let mut acc = [0.0f32; N];
        add(&mut acc, 0.25, &fd[q[0] as usize - p]);
        add(&mut acc, 0.25, &fd[q[1] as usize - p]);
        add(&mut acc, 0.25, &src[q[2] as usize]);
        add(&mut acc, 0.25, &src[q[3] as usize]);
        *o = acc;
        j += 4;
    }
}

/// A stored row over parent vertices (`k < p`) and face points (`fd[k - p]`).
#[inline]
fn general_row<const N: usize>(
    idx: &[u32],
    w: &[f32],
    p: usize,
    src: &[[f32; N]],
    fd: &[[f32; N]],
) -> [f32; N] {
    let mut acc = [0.0f32; N];
    for (&k, &w) in idx.iter().zip(w) {
        let k = k as usize;
        add(&mut acc, w, if k < p { &src[k] } else { &fd[k - p] });
    }
    acc
}

/// The entries of the ascending list `rows` that fall in `first..first + len`.
fn in_range(rows: &[u32], first: usize, len: usize) -> &[u32] {
    let lo = rows.partition_point(|&r| (r as usize) < first);
    let hi = rows.partition_point(|&r| (r as usize) < first + len);
    &rows[lo..hi]
}

/// The rows of `t` for which `smooth(indices, weights)` is false, ascending.
fn specials(t: &StencilTable, smooth: impl Fn(&[u32], &[f32]) -> bool + Sync) -> Vec<u32> {
    let rows = t.num_rows();
    let parts: Vec<Vec<u32>> = (0..rows.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            (c * CHUNK..((c + 1) * CHUNK).min(rows))
                .filter(|&r| {
                    let (lo, hi) = (t.offsets[r] as usize, t.offsets[r + 1] as usize);
                    !smooth(&t.indices[lo..hi], &t.weights[lo..hi])
                })
                .map(|r| r as u32)
                .collect()
        })
        .collect();
    parts.concat()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Scheme;
    use crate::refine::Refiner;
    use crate::shapes;
    use crate::topology::Topology;

    fn plans(m: &crate::mesh::Mesh, level: usize) -> (Refiner, Vec<StepPlan>) {
        let r = Refiner::new(Topology::new(m).unwrap(), level).unwrap();
        let p = r.stencils.iter().map(StepPlan::new).collect();
        (r, p)
    }

    #[test]
    fn a_closed_regular_mesh_has_no_exceptions() {
        // Every vertex of a torus grid has valence 4 and no crease: every row is smooth.
        let (_, p) = plans(&shapes::torus(6, 5, 2.0, 0.5), 3);
        for s in &p {
            assert!(s.quad_faces && !s.stencils_only);
            assert_eq!(s.num_exceptions(), 0);
        }
    }

    #[test]
    fn boundaries_and_high_valence_are_exceptions() {
        // A pole of valence 40 with a boundary ring: the pole (above the precomputed
        // valences) and the boundary rows are exceptions, their count growing like the
        // boundary (x2 per level) while the rows grow x4.
        let (r, p) = plans(&shapes::pole(40), 3);
        assert!(p[0].vertex_special.contains(&0));
        for k in 1..p.len() {
            let boundary = r.levels[k]
                .edge_faces
                .len()
                .abs_diff(2 * r.levels[k].num_edges());
            assert!(p[k].num_exceptions() >= boundary, "level {k}");
            assert!(p[k].num_exceptions() < 2 * p[k - 1].num_exceptions() + 8);
        }
        // Applying the plan gives the stored tables' bits.
        let mut src: Vec<[f32; 3]> = r.levels[0]
            .face_verts
            .iter()
            .take(r.levels[0].num_vertices())
            .map(|&v| [v as f32 * 0.37, 1.0 - v as f32, -0.5])
            .collect();
        src.resize(r.levels[0].num_vertices(), [0.1, 0.2, -0.3]);
        for (s, plan) in r.stencils.iter().zip(&p) {
            let mut want = vec![[0.0f32; 3]; s.num_rows()];
            let mut got = vec![[f32::NAN; 3]; s.num_rows()];
            s.apply(&src, &mut want);
            plan.apply(s, &src, &mut got);
            let bits = |v: &[[f32; 3]]| -> Vec<[u32; 3]> {
                v.iter().map(|x| x.map(f32::to_bits)).collect()
            };
            assert_eq!(bits(&got), bits(&want));
            src = want;
        }
    }

    #[test]
    fn a_bilinear_step_applies_its_tables() {
        let mut m = shapes::cube();
        m.options.scheme = Scheme::Bilinear;
        let (_, p) = plans(&m, 2);
        assert!(p.iter().all(|s| s.stencils_only));
    }
}
