//! The per-frame plan of a Loop step from a manifold triangle level, made from the topology:
//! no stencil table is built during setup.
//!
//! Most rows of a Loop step follow the smooth rules, whose weights depend on a class alone: a
//! child of a smooth vertex of valence `n` is its `n` neighbours, `(5/8 - beta^2) / n` each,
//! and itself, `1 - n` times that ([`crate::rules::r#loop::smooth_weights`]); the edge point
//! of a smooth two-face edge is its two ends, `3/8` each, and the two opposite vertices, `1/8`
//! each (one vertex, `1/4`, where they coincide). The plan keeps those rows' input indices
//! only, read once from the parent's vertex-edge, edge-vertex and edge-face lists in the order
//! the stencil rows store them ([`super::loop_masks::manifold_tables`]), and the other rows
//! (creases, corners, boundaries, isolated vertices) whole, formed once by the masks. A frame
//! weighs the indices by class. Every row is summed in the stored entry order from zero, so a
//! frame is bit-identical to applying the step's stencil table (tested for every `loop_*`
//! shape in `tests/refine_positions_into.rs`); [`super::Refiner::stencils`] builds that table
//! on first use.

use super::alloc::{unwritten, written, Slot};
#[cfg(target_arch = "x86_64")]
use super::lanes;
use super::last_level::ChildSharpness;
use super::loop_masks::{manifold_tables, opposite, smooth_edge, smooth_vertex};
use super::loop_rings::is_manifold;
#[cfg(target_arch = "x86_64")]
use super::smooth_frame::Padded;
use super::smooth_frame::{runs_between, Acc};
use super::stencil::StencilTable;
use crate::rules::r#loop::{edge_mask, smooth_weights};
use crate::topology::tags::rule;
use crate::topology::Topology;
use crate::util::par;
use rayon::prelude::*;

/// Rows per parallel chunk.
const CHUNK: usize = 4096;

/// A Loop step's per-frame plan (see the module documentation).
#[derive(Debug, Clone, Default)]
pub(crate) struct LoopPlan {
    /// Vertex rows that are not the smooth rule, ascending.
    vertex_special: Vec<u32>,
    /// Edge rows that are not the smooth two-face rule, ascending.
    edge_special: Vec<u32>,
    /// The exceptions' rows, in the order of `vertex_special` and of `edge_special`.
    exceptions: [StencilTable; 2],
    /// Per vertex `v` of valence `n`, from `vert_edge_offsets[v] + v`: its `n` neighbours and
    /// itself (zeros for an exception).
    vertex_inputs: Vec<u32>,
    /// Per edge, four values: its two ends and its two opposite vertices (the second
    /// `u32::MAX` where they coincide; zeros for an exception).
    edge_inputs: Vec<[u32; 4]>,
    /// `[itself, each neighbour]` weights of a smooth vertex of valence `n`, up to the level's
    /// largest valence.
    vertex_weights: Vec<[f32; 2]>,
    /// A smooth edge's weights: each end, each opposite vertex, the one merged opposite vertex.
    edge_weights: [f32; 3],
}

impl LoopPlan {
    /// The plan of the Loop step from `p` to a child with sharpness and rules `c`; `None` where
    /// `p` is not manifold (its rows can meet a vertex twice: the stored tables merge those).
    /// A step of mostly exceptions (a small creased or open base) keeps a plan too: its
    /// exceptions' rows are then most of a stencil table.
    pub(crate) fn from_topology(p: &Topology, c: ChildSharpness<'_>) -> Option<LoopPlan> {
        if !is_manifold(p) {
            return None;
        }
        let ((vertex_inputs, vertex_special, max_valence), (edge_inputs, edge_special)) =
            rayon::join(|| vertex_inputs(p), || edge_inputs(p));
        let (vex, eex) = manifold_tables(p, c, Some((&vertex_special, &edge_special)));
        let vertex_weights = (0..=max_valence)
            .map(|n| {
                if n == 0 {
                    [0.0; 2]
                } else {
                    let (vw, ew) = smooth_weights(n);
                    [vw, ew]
                }
            })
            .collect();
        let m = edge_mask(0.0, rule::SMOOTH, 2);
        let merged = (m.opposite as f64 + m.opposite as f64) as f32;
        Some(LoopPlan {
            vertex_special,
            edge_special,
            exceptions: [vex, eex],
            vertex_inputs,
            edge_inputs,
            vertex_weights,
            edge_weights: [m.vertex, m.opposite, merged],
        })
    }

    /// One step of `N`-component values from parent `p` (children of vertices, then edge
    /// points into `dst`), bit-identical to applying the step's stencil table. `src` holds
    /// the parent's values, and may hold more: with one value past them the rows read it
    /// padded ([`Padded`]).
    pub(crate) fn apply<const N: usize>(
        &self,
        p: &Topology,
        src: &[[f32; N]],
        dst: &mut [[f32; N]],
    ) {
        let np = p.num_vertices();
        assert_eq!(dst.len(), np + p.num_edges(), "destination length");
        assert!(src.len() >= np, "source length");
        #[cfg(target_arch = "x86_64")]
        if let (Some(src), Some(dst)) = (lanes::as3(src), lanes::as3_mut(dst)) {
            return if src.len() > np {
                self.apply_acc::<3, Padded<lanes::Lanes3>>(p, &src[..np + 1], dst)
            } else {
                self.apply_acc::<3, lanes::Lanes3>(p, src, dst)
            };
        }
        self.apply_acc::<N, [f32; N]>(p, &src[..np], dst);
    }

    /// [`LoopPlan::apply`], each row summed in an `A` (`src` one value longer than the
    /// parent's values where `A` reads padded sources).
    fn apply_acc<const N: usize, A: Acc<N>>(
        &self,
        p: &Topology,
        src: &[[f32; N]],
        dst: &mut [[f32; N]],
    ) {
        let (dv, de) = dst.split_at_mut(p.num_vertices());
        let (vw, vi, veo) = (
            &self.vertex_weights,
            &self.vertex_inputs,
            &p.vert_edge_offsets,
        );
        // Valence 6 (the regular vertex) with its length known, so the row unrolls.
        let row_sum = |row: &[u32], [wv, we]: [f32; 2]| {
            let (last, nb) = row.split_last().expect("n + 1 inputs");
            let mut acc = A::zero();
            for &x in nb {
                acc.add(we, src, x as usize);
            }
            acc.add(wv, src, *last as usize);
            acc.get()
        };
        let w6 = vw.get(6).copied().unwrap_or_default();
        let np = p.num_vertices();
        chunks::<N, A>(
            dv,
            &self.vertex_special,
            &self.exceptions[0],
            np,
            src,
            |v| {
                let (a, b) = (veo[v] as usize, veo[v + 1] as usize);
                if b - a == 6 {
                    row_sum(&vi[a + v..a + v + 7], w6)
                } else {
                    row_sum(&vi[a + v..b + v + 1], vw[b - a])
                }
            },
        );
        let [wv, wo, wm] = self.edge_weights;
        let ei = &self.edge_inputs;
        chunks::<N, A>(de, &self.edge_special, &self.exceptions[1], np, src, |e| {
            let [e0, e1, o0, o1] = ei[e];
            let mut acc = A::zero();
            acc.add(wv, src, e0 as usize);
            acc.add(wv, src, e1 as usize);
            if o1 != u32::MAX {
                acc.add(wo, src, o0 as usize);
                acc.add(wo, src, o1 as usize);
            } else {
                acc.add(wm, src, o0 as usize);
            }
            acc.get()
        });
    }
}

/// The smooth vertex rows' inputs of [`LoopPlan`] (`vertex_inputs`), the other vertex rows
/// (`vertex_special`, ascending) and the largest valence, in one pass of parallel chunks
/// (each chunk's exceptions listed in a vector of its own, joined in order: rayon's per-item
/// `filter`/`collect` of the two lists took 0.9 ms at `loop_pole64` level 5, this whole pass
/// 0.4 ms).
#[allow(unsafe_code)]
fn vertex_inputs(p: &Topology) -> (Vec<u32>, Vec<u32>, usize) {
    let nv = p.num_vertices();
    let veo = &p.vert_edge_offsets;
    let mut out = unwritten(veo[nv] as usize + nv, u32::MAX);
    let b = par::bounds(nv);
    let parts: Vec<(Vec<u32>, usize)> = par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut out, &b, |v| veo[v] as usize + v))
        .map(|(r, out)| {
            let (mut special, mut max_valence) = (Vec::new(), 0);
            let base = veo[r.start] as usize + r.start;
            for v in r {
                let o = &mut out[veo[v] as usize + v - base..veo[v + 1] as usize + v + 1 - base];
                let n = o.len() - 1;
                max_valence = max_valence.max(n);
                if n > 0 && smooth_vertex(p, v) {
                    let (last, nb) = o.split_last_mut().expect("n + 1 values");
                    for (o, &e) in nb.iter_mut().zip(p.vertex_edges(v)) {
                        o.set(p.other_vertex(e as usize, v as u32));
                    }
                    last.set(v as u32);
                } else {
                    special.push(v as u32);
                    for o in o {
                        o.set(0);
                    }
                }
            }
            (special, max_valence)
        })
        .collect();
    // SAFETY: the chunks cover the table, each vertex writing its `n + 1` values (its `n`
    // edges give its `n` neighbours).
    let out = unsafe { written(out) };
    let max_valence = parts.iter().map(|(_, n)| *n).max().unwrap_or(0);
    let special = parts.into_iter().flat_map(|(s, _)| s).collect();
    (out, special, max_valence)
}

/// The smooth edge rows' inputs of [`LoopPlan`] (`edge_inputs`) and the other edge rows
/// (`edge_special`, ascending), as [`vertex_inputs`] finds them.
#[allow(unsafe_code)]
fn edge_inputs(p: &Topology) -> (Vec<[u32; 4]>, Vec<u32>) {
    let ne = p.num_edges();
    let mut out = unwritten(ne, [u32::MAX; 4]);
    let b = par::bounds(ne);
    let parts: Vec<Vec<u32>> = par::ranges(&b)
        .into_par_iter()
        .zip(par::split_exact(&mut out, &b, |e| e))
        .map(|(r, out)| {
            let mut special = Vec::new();
            let base = r.start;
            for e in r {
                out[e - base].set(if smooth_edge(p, e) {
                    let ev = p.edge_verts[e];
                    let (o0, o1) = (opposite(p, e, 0), opposite(p, e, 1));
                    [ev[0], ev[1], o0, if o1 != o0 { o1 } else { u32::MAX }]
                } else {
                    special.push(e as u32);
                    [0; 4]
                });
            }
            special
        })
        .collect();
    // SAFETY: the chunks cover the table, each edge writing its four values.
    (unsafe { written(out) }, parts.concat())
}

/// Fills `out` (one value per row) in parallel chunks: row `r` is `smooth(r)` unless it is in
/// `special` (ascending), whose `k`-th row is row `k` of `rows` (over the `np` parent
/// vertices only).
fn chunks<const N: usize, A: Acc<N>>(
    out: &mut [[f32; N]],
    special: &[u32],
    rows: &StencilTable,
    np: usize,
    src: &[[f32; N]],
    smooth: impl Fn(usize) -> [f32; N] + Sync,
) {
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(c, out): (usize, &mut [[f32; N]])| {
            runs_between::<N, A>(special, rows, np, src, &[], c * CHUNK, out, |r, run| {
                for (o, q) in run.iter_mut().zip(r..) {
                    *o = smooth(q);
                }
            });
        });
}

#[cfg(test)]
mod tests {
    use crate::refine::loop_rings::is_manifold;
    use crate::{shapes, RefineOptions, Refiner, Topology};

    /// Every manifold `loop_*` shape (open and creased ones too), full and lean: each step
    /// keeps a plan made from the topology, and applying it to arbitrary data gives the bits
    /// of the step's stencil table (built on first use) applied to the same data.
    #[test]
    fn plans_give_the_tables_bits_step_by_step() {
        let dir =
            std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
        let mut planned = 0;
        for path in shapes::regression_shapes(&dir, &["loop_"]).unwrap() {
            let m = crate::io::read_path(&path).unwrap();
            for options in [RefineOptions::default(), RefineOptions::lean()] {
                let r = Refiner::with_options(Topology::new(&m).unwrap(), 3, options).unwrap();
                let plans = r.frame_plans.get();
                if !(0..3).all(|k| is_manifold(&r.levels[k])) {
                    continue;
                }
                let plans = plans.expect("plans made during setup");
                assert!(r.stencils.get().is_none(), "no table built during setup");
                for (k, plan) in plans.iter().enumerate() {
                    let lp = plan.loop_plan.as_ref().expect("a Loop plan");
                    let p = &r.levels[k];
                    let src: Vec<[f32; 3]> = (0..p.num_vertices())
                        .map(|v| {
                            let t = v as f32 * 0.731 - 3.0;
                            [t.sin() * 7.0, t.cos() * 1e-2, t * t - 1.0]
                        })
                        .collect();
                    let mut got = vec![[f32::NAN; 3]; r.levels[k + 1].num_vertices()];
                    lp.apply(p, &src, &mut got);
                    let mut want = vec![[f32::NAN; 3]; got.len()];
                    r.stencils()[k].apply(&src, &mut want);
                    let bits = |v: &[[f32; 3]]| -> Vec<[u32; 3]> {
                        v.iter().map(|x| x.map(f32::to_bits)).collect()
                    };
                    assert_eq!(bits(&got), bits(&want), "{} step {k}", path.display());
                    // With a value past the parent's (read padded): the same bits.
                    let mut padded = src.clone();
                    padded.push([f32::NAN, 3.0, -2.0]);
                    lp.apply(p, &padded, &mut got);
                    assert_eq!(bits(&got), bits(&want), "{} step {k}", path.display());
                    planned += 1;
                }
            }
        }
        assert!(planned > 100, "{planned} steps planned");
    }
}
