//! A step's per-frame plan made from the topology, without the step's stencil tables: the
//! smooth rows' inputs as gather offsets (`OwnRows`; no weights) and the exceptions' rows, as
//! the stored tables would hold them.
//!
//! A vertex row follows the smooth rule when its parent vertex's rule is smooth (or a dart)
//! and its rings close (as many faces as edges), at a valence of at most 32; an edge row when
//! the edge is smooth (sharpness `<= 0`) with two faces, neither a triangle under the smooth
//! triangle rule. Those are exactly the rows [`super::masks::LevelRows`] forms with the smooth
//! weights (the plan asks it, `LevelRows::smooth_valence` and `LevelRows::quarter_edge`, the
//! tests the masks themselves take); every other row is formed by `LevelRows` itself and kept
//! whole. So applying the
//! plan gives the stored tables' bits (the smooth-plan tests in `smooth_frame.rs` and
//! `tests/refine_positions_into.rs` on every shape).
//!
//! The `Refiner` builds these plans as it refines (the tables a frame reads) and its stencil
//! tables only on first use, from the plans ([`StepPlan::stencils`]; `tests/refine_stencils.rs`
//! checks them against the masks' tables): a plan holds no weights and no copy of the face
//! lists, which the stencils do.

use super::alloc::{put, unwritten, written};
use super::loop_masks::write_rows;
use super::masks::{face_table, LevelRows, LevelStencils, Scratch};
use super::smooth_frame::{input_at, OwnRows, StepPlan, MAX_VALENCE, OFFSET_MAX};
use super::stencil::StencilTable;
use crate::options::Scheme;
use crate::topology::Topology;
use crate::util::par;
use rayon::prelude::*;

/// One chunk's rows kept whole: their row numbers, entry counts and entries, and its smooth
/// vertex rows of a valence other than 4.
#[derive(Default)]
struct Kept {
    rows: Vec<u32>,
    counts: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f32>,
    odd: Vec<u32>,
}

impl Kept {
    /// Row `r`, formed by `form`, kept whole.
    fn push(&mut self, r: usize, form: impl FnOnce(&mut dyn FnMut(u32, f32))) {
        let before = self.indices.len();
        let (idx, wts) = (&mut self.indices, &mut self.weights);
        form(&mut |x, w| {
            idx.push(x);
            wts.push(w);
        });
        self.rows.push(r as u32);
        self.counts.push((self.indices.len() - before) as u32);
    }
}

/// The chunks' kept rows joined: the rows in order, their table, and the odd rows.
fn join_kept(parts: Vec<Kept>, inputs: usize) -> (Vec<u32>, StencilTable, Vec<u32>) {
    let mut ex = StencilTable {
        offsets: vec![0],
        num_inputs: inputs,
        ..Default::default()
    };
    let (mut rows, mut odd) = (Vec::new(), Vec::new());
    let mut acc = 0u32;
    for p in parts {
        for c in p.counts {
            acc += c;
            ex.offsets.push(acc);
        }
        ex.indices.extend_from_slice(&p.indices);
        ex.weights.extend_from_slice(&p.weights);
        rows.extend_from_slice(&p.rows);
        odd.extend_from_slice(&p.odd);
    }
    (rows, ex, odd)
}

impl StepPlan {
    /// The plan of the step from `p` whose rows are `rows` (see the module documentation).
    /// Bilinear steps and steps where most rows are exceptions take their stencil tables
    /// whole (as [`StepPlan::new`] applies them), so this returns `None` for them.
    #[allow(unsafe_code)]
    pub(crate) fn from_topology(p: &Topology, rows: LevelRows<'_>) -> Option<StepPlan> {
        if p.options.scheme != Scheme::Catmark {
            return None;
        }
        let (nv, nf, ne) = (p.num_vertices(), p.num_faces(), p.num_edges());
        let inputs = nv + nf;
        if inputs > OFFSET_MAX {
            return None;
        }
        let quad_faces = (0..nf).all(|f| p.face_size(f) == 4);
        // Gather offsets (`OwnRows`): face point `f` at `3 f`, parent vertex `k` at `3 k`.
        let at = |k: u32| 3 * k;
        // Vertex rows: a smooth row of valence n (1..=MAX_VALENCE: the plan's weight table)
        // has 2n + 1 entries, a kept one none here.
        let smooth_valence = |v: usize| {
            rows.smooth_valence(v)
                .filter(|n| (1..=MAX_VALENCE).contains(n))
        };
        let vb = par::bounds(nv);
        let mut voffsets = unwritten(nv + 1, u32::MAX);
        voffsets[0].write(0);
        par::ranges(&vb)
            .into_par_iter()
            .zip(par::split_exact(&mut voffsets[1..], &vb, |v| v))
            .for_each(|(r, out)| {
                let base = r.start;
                for v in r {
                    out[v - base].write(smooth_valence(v).map_or(0, |n| 2 * n as u32 + 1));
                }
            });
        // SAFETY: the first value and every vertex's (the chunks cover the rest) written.
        let mut voffsets = unsafe { written(voffsets) };
        let mut acc = 0u32;
        for o in &mut voffsets[1..] {
            acc += *o;
            *o = acc;
        }
        let mut vindices = unwritten(acc as usize, u32::MAX);
        let vstart = |v: usize| voffsets[v] as usize;
        let vparts: Vec<Kept> = par::ranges(&vb)
            .into_par_iter()
            .zip(par::split_exact(&mut vindices, &vb, vstart))
            .map(|(r, out)| {
                let mut kept = Kept::default();
                let mut scratch = Scratch::<f32>::default();
                let base = vstart(r.start);
                for v in r {
                    // The class found by the sizing pass: a smooth row has 2n + 1 entries.
                    let len = vstart(v + 1) - vstart(v);
                    if len == 0 {
                        kept.push(v, |add| rows.vertex(v, &mut scratch, &mut |x, w| add(x, w)));
                        continue;
                    }
                    let n = len / 2;
                    let o = &mut out[vstart(v) - base..vstart(v + 1) - base];
                    // `n` faces and `n` edges (`smooth_valence`), then the vertex.
                    let (faces, edges) = (p.vertex_faces(v), p.vertex_edges(v));
                    assert!(faces.len() == n && edges.len() == n);
                    for (o, &f) in o.iter_mut().zip(faces) {
                        o.write(at(f));
                    }
                    for (o, &e) in o[n..].iter_mut().zip(edges) {
                        o.write(at(p.other_vertex(e as usize, v as u32)));
                    }
                    o[2 * n].write(at(v as u32));
                    if n != 4 {
                        kept.odd.push(v as u32);
                    }
                }
                kept
            })
            .collect();
        // Edge rows: four entries each (zero where kept whole).
        let eb = par::bounds(ne);
        let mut eindices = unwritten(4 * ne, u32::MAX);
        let eparts: Vec<Kept> = par::ranges(&eb)
            .into_par_iter()
            .zip(par::split_exact(&mut eindices, &eb, |e| 4 * e))
            .map(|(r, out)| {
                let mut kept = Kept::default();
                let base = 4 * r.start;
                for e in r {
                    let o = &mut out[4 * e - base..4 * e - base + 4];
                    if rows.quarter_edge(e) {
                        let (faces, ev) = (p.edge_faces(e), p.edge_verts[e]);
                        put(o, &[at(faces[0]), at(faces[1]), at(ev[0]), at(ev[1])]);
                    } else {
                        put(o, &[0; 4]);
                        kept.push(e, |add| rows.edge(e, &mut |x, w| add(x, w)));
                    }
                }
                kept
            })
            .collect();
        // SAFETY: the chunks cover both tables; a smooth vertex row writes its `2n + 1` values
        // (a kept one has none), every edge row its four.
        let (vindices, eindices) = unsafe { (written(vindices), written(eindices)) };
        let (vertex_special, vex, vertex_odd) = join_kept(vparts, inputs);
        let (edge_special, eex, _) = join_kept(eparts, inputs);
        if 2 * (vertex_special.len() + edge_special.len()) > nv + ne {
            return None;
        }
        let vertex = StencilTable {
            offsets: voffsets,
            indices: vindices,
            weights: Vec::new(),
            num_inputs: inputs,
        };
        let edge = StencilTable {
            offsets: super::level::iota(ne + 1, |e| 4 * e as u32),
            indices: eindices,
            weights: Vec::new(),
            num_inputs: inputs,
        };
        Some(StepPlan {
            stencils_only: false,
            quad_faces,
            vertex_special,
            vertex_odd,
            edge_special,
            valence_weights: StepPlan::valence_table(),
            exceptions: [vex, eex],
            own: Some(OwnRows {
                face: (!quad_faces).then(|| face_table(p)),
                vertex,
                edge,
            }),
            loop_plan: None,
        })
    }
}

impl StepPlan {
    /// The step's stencil tables from a plan made by [`StepPlan::from_topology`] from `p`
    /// (`None` for a plan made from stored tables): the smooth rows' indices with their
    /// class's weights, the exceptions' rows as kept. The same tables as
    /// [`super::level_stencils`] forms from the masks (tested).
    pub(crate) fn stencils(&self, p: &Topology) -> Option<LevelStencils> {
        let own = self.own.as_ref()?;
        let [vex, eex] = &self.exceptions;
        let vw = &self.valence_weights;
        let np = p.num_vertices() as u32;
        // A smooth vertex row's `n` face points come first, an edge row's two.
        let vertex = expand(&own.vertex, vex, &self.vertex_special, np, |len| {
            let n = (len - 1) / 2;
            let [w, wv] = vw[n];
            (n, move |i| if i < 2 * n { w } else { wv })
        });
        let edge = expand(&own.edge, eex, &self.edge_special, np, |_| (2, |_| 0.25f32));
        Some(LevelStencils {
            num_parent_vertices: p.num_vertices(),
            face: own.face.clone().unwrap_or_else(|| face_table(p)),
            vertex,
            edge,
        })
    }
}

/// The full table of a plan's rows: row `r` is exception `q` of `ex` where `special[q] == r`,
/// else the smooth row `r` of `t` (gather offsets over `np` parent vertices, its first
/// `faces` entries face points) with weights `weight(entry)`, where `class(row length)` is
/// `(faces, weight)`.
fn expand<F: Fn(usize) -> f32>(
    t: &StencilTable,
    ex: &StencilTable,
    special: &[u32],
    np: u32,
    class: impl Fn(usize) -> (usize, F) + Sync,
) -> StencilTable {
    // Each pass walks its rows in order with a cursor on the next kept row.
    let kept = |r: usize, q: &mut usize| -> Option<usize> {
        let k = *q;
        (special.get(k) == Some(&(r as u32))).then(|| {
            *q += 1;
            k
        })
    };
    let span = |t: &StencilTable, r: usize| t.offsets[r] as usize..t.offsets[r + 1] as usize;
    write_rows(
        t.num_rows(),
        t.num_inputs,
        |first| special.partition_point(|&s| (s as usize) < first),
        |r, q| kept(r, q).map_or_else(|| span(t, r), |k| span(ex, k)).len(),
        |r, q, io, wo| match kept(r, q) {
            Some(k) => {
                io.copy_from_slice(&ex.indices[span(ex, k)]);
                wo.copy_from_slice(&ex.weights[span(ex, k)]);
            }
            None => {
                let (faces, w) = class(io.len());
                for (i, (x, &off)) in io.iter_mut().zip(&t.indices[span(t, r)]).enumerate() {
                    *x = input_at(off, i < faces, np);
                }
                for (i, x) in wo.iter_mut().enumerate() {
                    *x = w(i);
                }
            }
        },
    )
}
