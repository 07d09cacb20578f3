//! The rate curves of a limit surface: the curves on it that the rate policies of
//! `crate::tess` measure, laid out once per table ([`crate::limit::PatchTable::rate_curves`]).
//!
//! Each curve is sampled at [`CURVE_POINTS`] evenly spaced parameters: the limit curve of every
//! base edge (seen from its first face that is not a hole), then, face by face, the isolines
//! through every ptex face of the face at `u = ¼, ½, ¾` and `v = ¼, ½, ¾` ([`ISOLINES`]).
//! [`RateCurves`] lays those samples out as one flat list of `(ptex, u, v)` queries,
//! [`CURVE_POINTS`] per curve, so that any evaluator can measure them.

use rayon::prelude::*;

use super::patch_map::EMPTY;
use super::PatchTable;
use crate::topology::Topology;

/// Intervals per rate curve (its samples are `i / CURVE_SAMPLES`, `i = 0..=CURVE_SAMPLES`).
pub const CURVE_SAMPLES: usize = 16;

/// Samples per rate curve.
pub const CURVE_POINTS: usize = CURVE_SAMPLES + 1;

/// The constant parameter of a ptex face's isolines, in each direction.
pub const ISOLINES: [f32; 3] = [0.25, 0.5, 0.75];

/// Isolines per ptex face: [`ISOLINES`] along `u` (constant `v`), then along `v`.
pub const ISOLINES_PER_PTEX: usize = 2 * ISOLINES.len();

/// The sample layout of a surface's rate curves (module documentation).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RateCurves {
    /// `(ptex face, u, v)` of every sample, [`CURVE_POINTS`] per curve, curve after curve.
    pub(crate) queries: Vec<(u32, f32, f32)>,
    /// Per curve: whether it lies on the surface. A dead curve (the edge of holes only, or
    /// a ptex face without patches) measures zero; its queries name ptex face `u32::MAX`.
    pub(crate) live: Vec<bool>,
    /// Number of base edges: curve `e < num_edges` is base edge `e`'s.
    pub(crate) num_edges: usize,
    /// Per base face, the first of its isolines (curves `face_curves[f]..face_curves[f + 1]`,
    /// [`ISOLINES_PER_PTEX`] per ptex face; none for holes); `num_faces + 1` entries.
    pub(crate) face_curves: Vec<u32>,
}

impl RateCurves {
    /// `(ptex face, u, v)` of every sample, [`CURVE_POINTS`] per curve, curve after curve.
    #[inline]
    pub fn queries(&self) -> &[(u32, f32, f32)] {
        &self.queries
    }

    /// Per curve: whether it lies on the surface. A dead curve (the edge of holes only, or
    /// a ptex face without patches) measures zero; its queries name ptex face `u32::MAX`.
    #[inline]
    pub fn live(&self) -> &[bool] {
        &self.live
    }

    /// Number of base edges: curve `e < num_edges` is base edge `e`'s.
    #[inline]
    pub fn num_edges(&self) -> usize {
        self.num_edges
    }

    /// Per base face, the first of its isolines (curves `face_curves[f]..face_curves[f + 1]`,
    /// [`ISOLINES_PER_PTEX`] per ptex face; none for holes); `num_faces + 1` entries.
    #[inline]
    pub fn face_curves(&self) -> &[u32] {
        &self.face_curves
    }
}

/// Parameter of sample `i` of a curve.
fn at(i: usize) -> f32 {
    i as f32 / CURVE_SAMPLES as f32
}

/// The query of a dead curve's samples (a ptex face out of range: evaluators write zeros).
const DEAD: (u32, f32, f32) = (u32::MAX, 0.0, 0.0);

impl RateCurves {
    /// The rate curves of `table`'s surface.
    pub fn new<R>(table: &PatchTable<R>) -> RateCurves {
        // Only the topology, ptex offsets and patch map are read.
        let t = &table.base;
        let num_edges = t.num_edges();
        let mut face_curves = Vec::with_capacity(t.num_faces() + 1);
        let mut curves = num_edges as u32;
        face_curves.push(curves);
        for f in 0..t.num_faces() {
            if !t.face_is_hole[f] {
                let ptex = table.ptex_offsets[f + 1] - table.ptex_offsets[f];
                curves += ptex * ISOLINES_PER_PTEX as u32;
            }
            face_curves.push(curves);
        }
        let total = curves as usize;
        let mut queries = vec![DEAD; total * CURVE_POINTS];
        let mut live = vec![false; total];
        let (edge_q, face_q) = queries.split_at_mut(num_edges * CURVE_POINTS);
        let (edge_live, face_live) = live.split_at_mut(num_edges);
        let (roots, ptex_offsets) = (&table.patch_map.roots[..], &table.ptex_offsets[..]);
        edge_q
            .par_chunks_mut(CURVE_POINTS)
            .zip(edge_live.par_iter_mut())
            .enumerate()
            .for_each(|(e, (q, live))| {
                // The face the edge is seen from, found once for its samples.
                let Some(side) = EdgeSide::of(t, ptex_offsets, e) else {
                    return; // its queries stay dead
                };
                for (i, q) in q.iter_mut().enumerate() {
                    if let Some((ptex, u, v)) = side.point(at(i), roots) {
                        *q = (ptex as u32, u, v);
                        *live = true;
                    }
                }
            });
        // The ptex faces of faces that are not holes, in curve order: six curves each.
        let live_ptex: Vec<u32> = (0..t.num_faces())
            .filter(|&f| !t.face_is_hole[f])
            .flat_map(|f| table.ptex_offsets[f]..table.ptex_offsets[f + 1])
            .collect();
        face_q
            .par_chunks_mut(ISOLINES_PER_PTEX * CURVE_POINTS)
            .zip(face_live.par_chunks_mut(ISOLINES_PER_PTEX))
            .zip(live_ptex.par_iter())
            .for_each(|((q, l), &ptex)| {
                let ptex_live = roots[ptex as usize] != EMPTY;
                for (line, (q, l)) in q.chunks_exact_mut(CURVE_POINTS).zip(l).enumerate() {
                    let c = ISOLINES[line % ISOLINES.len()];
                    *l = ptex_live;
                    for (i, q) in q.iter_mut().enumerate() {
                        let a = at(i);
                        let (u, v) = if line < ISOLINES.len() {
                            (a, c)
                        } else {
                            (c, a)
                        };
                        *q = if ptex_live { (ptex, u, v) } else { DEAD };
                    }
                }
            });
        RateCurves {
            queries,
            live,
            num_edges,
            face_curves,
        }
    }

    /// Number of curves.
    pub fn num_curves(&self) -> usize {
        self.live.len()
    }
}

/// A base edge as seen from its first face that is not a hole: the face's ptex faces and
/// the edge's place in it.
struct EdgeSide {
    /// The face's first ptex face.
    first: usize,
    /// The face's size.
    n: usize,
    /// The edge's local index in the face.
    k: usize,
    /// Whether the edge runs from the face's corner `k` (else towards it).
    forward: bool,
}

impl EdgeSide {
    /// Edge `e`'s side; `None` when all its faces are holes.
    fn of(topo: &Topology, ptex_offsets: &[u32], e: usize) -> Option<EdgeSide> {
        let (faces, locals) = (topo.edge_faces(e), topo.edge_faces_local(e));
        let (f, k) = faces
            .iter()
            .zip(locals)
            .map(|(&f, &k)| (f as usize, k as usize))
            .find(|&(f, _)| !topo.face_is_hole[f])?;
        Some(EdgeSide {
            first: ptex_offsets[f] as usize,
            n: topo.face_size(f),
            k,
            forward: topo.edge_verts[e][0] == topo.face_vertices(f)[k],
        })
    }

    /// The `(ptex, u, v)` of the point at `t` along the edge, from its first vertex; `None`
    /// when that ptex face has no patches (`roots`: the patch map's).
    fn point(&self, t: f32, roots: &[u32]) -> Option<(usize, f32, f32)> {
        let (first, n, k) = (self.first, self.n, self.k);
        // Along the face's edge k, from its corner k.
        let t = if self.forward { t } else { 1.0 - t };
        let (ptex, u, v) = if n == 4 {
            let (u, v) = match k {
                0 => (t, 0.0),
                1 => (1.0, t),
                2 => (1.0 - t, 1.0),
                _ => (0.0, 1.0 - t),
            };
            (first, u, v)
        } else if t <= 0.5 {
            (first + k, 2.0 * t, 0.0)
        } else {
            (first + (k + 1) % n, 0.0, 2.0 - 2.0 * t)
        };
        (roots[ptex] != EMPTY).then_some((ptex, u, v))
    }
}
