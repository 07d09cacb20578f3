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
//! A [`StepPlan`] finds those rows once and keeps the rows where the rules differ (creases,
//! boundaries, corners, irregular faces or rules) as a sorted list of exceptions with their
//! rows. A Catmull-Clark `Refiner` makes its plans from the topology as it refines
//! ([`StepPlan::from_topology`], `frame_plan.rs`: the smooth rows' inputs and the
//! exceptions' rows, no stencil table at all); otherwise a plan is found from a step's stored
//! tables ([`StepPlan::new`]: a row is smooth when its entries have exactly the smooth
//! pattern and weights, bit for bit; its inputs are then copied as gather offsets). Applying the plan then reads, per smooth row, only its
//! input indices: no weight, and for face points (the parent's face lists), edge points and
//! vertices of valence 4 no row offset either (their length is known; the plan also lists the
//! smooth vertices of other valences, which read their offsets). The smooth rows' inputs are
//! kept as gather offsets ([`OwnRows`]: `3 k`, face points counted from the first), and where
//! a step's sources hold one value past the ones it sums (`Refiner::refine_positions_into`
//! arranges it) each gather is one bounds test and one 16-byte load ([`Padded`]). Every row is
//! summed in the stored entry order with the stored weights, so the result is bit-identical to
//! [`LevelStencils::apply`].

#[cfg(target_arch = "x86_64")]
use super::lanes;
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
    pub(super) stencils_only: bool,
    /// Whether every face row has four entries of weight `1/4` (an all-quad parent).
    pub(super) quad_faces: bool,
    /// Vertex rows that are not the smooth rule, ascending.
    pub(super) vertex_special: Vec<u32>,
    /// Smooth vertex rows of a valence other than 4, ascending: between these and the
    /// exceptions, vertex rows have 9 entries each, read without their offsets.
    pub(super) vertex_odd: Vec<u32>,
    /// Edge rows that are not the smooth two-face rule, ascending.
    pub(super) edge_special: Vec<u32>,
    /// `(1/n², (n - 2)/n)` of a smooth vertex of valence `n`, as the tables store them.
    pub(super) valence_weights: Vec<[f32; 2]>,
    /// The exceptions' rows, in the order of `vertex_special` and of `edge_special`.
    pub(super) exceptions: [StencilTable; 2],
    /// The smooth rows' gather offsets ([`OwnRows`]); `None` where the plan applies the
    /// stored tables whole (`stencils_only`).
    pub(super) own: Option<OwnRows>,
    /// A Loop step's plan, made from the topology; the fields above are then unused.
    pub(super) loop_plan: Option<super::loop_frame::LoopPlan>,
}

/// A plan's own tables: the smooth rows' inputs (an exception's row is empty, or four zeros
/// for an edge; no weights), and the face rows where the parent has faces other than quads.
///
/// An input is stored as its gather offset, `3 k` for value `k` of its source: a parent
/// vertex `k`, or face point `k` of the step (counted from the first face point, not from the
/// parent's vertex count as the stored tables number it). A three-component gather then
/// needs neither the subtraction nor the scaling of the index (`Acc::add_at`); an offset
/// table holds at most `u32::MAX / 3` values' offsets, so larger steps keep their stored
/// tables.
#[derive(Debug, Clone, Default)]
pub(crate) struct OwnRows {
    pub(super) face: Option<StencilTable>,
    pub(super) vertex: StencilTable,
    pub(super) edge: StencilTable,
}

/// The rows `rows` (ascending) of `t`, as a table of their own.
pub(super) fn pick_rows(t: &StencilTable, rows: &[u32]) -> StencilTable {
    let mut out = StencilTable {
        offsets: Vec::with_capacity(rows.len() + 1),
        num_inputs: t.num_inputs,
        ..Default::default()
    };
    out.offsets.push(0);
    for &r in rows {
        let (lo, hi) = (
            t.offsets[r as usize] as usize,
            t.offsets[r as usize + 1] as usize,
        );
        out.indices.extend_from_slice(&t.indices[lo..hi]);
        out.weights.extend_from_slice(&t.weights[lo..hi]);
        out.offsets.push(out.indices.len() as u32);
    }
    out
}

/// Weights of the smooth vertex rule at valence `n`, computed as the tables compute them.
fn smooth_vertex_weights(n: usize) -> [f32; 2] {
    [1.0 / (n * n) as f32, (n as f32 - 2.0) / n as f32]
}

/// Largest valence with a precomputed weight pair; higher valences are exceptions.
pub(super) const MAX_VALENCE: usize = 32;

impl StepPlan {
    /// `(1/n², (n - 2)/n)` for valences `0..=MAX_VALENCE` (zero at 0).
    pub(super) fn valence_table() -> Vec<[f32; 2]> {
        (0..=MAX_VALENCE)
            .map(|n| {
                if n == 0 {
                    [0.0; 2]
                } else {
                    smooth_vertex_weights(n)
                }
            })
            .collect()
    }

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
        let valence_weights = StepPlan::valence_table();
        let vw = &valence_weights;
        // Per vertex row: `None` for a smooth row of valence 4, `Some(0)` for an exception,
        // `Some(1)` for a smooth row of another valence.
        let vertex_class = |idx: &[u32], w: &[f32]| {
            let len = idx.len();
            if len % 2 == 0 || !(3..=2 * MAX_VALENCE + 1).contains(&len) {
                return Some(0);
            }
            let n = len / 2;
            let [a, b] = vw[n].map(f32::to_bits);
            let smooth = idx[..n].iter().all(|&k| k >= p)
                && idx[n..].iter().all(|&k| k < p)
                && w[..2 * n].iter().all(|x| x.to_bits() == a)
                && w[2 * n].to_bits() == b;
            match (smooth, n) {
                (false, _) => Some(0),
                (true, 4) => None,
                (true, _) => Some(1),
            }
        };
        let [vertex_special, vertex_odd] = rows_by_class(&s.vertex, vertex_class);
        let edge_special = rows_where(&s.edge, |idx, w| {
            !(idx.len() == 4
                && idx[0] >= p
                && idx[1] >= p
                && idx[2] < p
                && idx[3] < p
                && w.iter().all(|x| x.to_bits() == quarter))
        });
        let exceptions = vertex_special.len() + edge_special.len();
        let stencils_only = 2 * exceptions > s.vertex.num_rows() + s.edge.num_rows()
            || s.vertex.num_inputs > OFFSET_MAX;
        let (exceptions, own) = if stencils_only {
            Default::default()
        } else {
            let (p, face) = (s.num_parent_vertices as u32, &s.face);
            (
                [
                    pick_rows(&s.vertex, &vertex_special),
                    pick_rows(&s.edge, &edge_special),
                ],
                Some(OwnRows {
                    face: (!quad_faces).then(|| face.clone()),
                    vertex: offset_rows(&s.vertex, &vertex_special, p, None),
                    edge: offset_rows(&s.edge, &edge_special, p, Some(4)),
                }),
            )
        };
        StepPlan {
            stencils_only,
            quad_faces,
            vertex_special,
            vertex_odd,
            edge_special,
            valence_weights,
            exceptions,
            own,
            loop_plan: None,
        }
    }

    /// Number of rows evaluated from their stored rows (vertex and edge exceptions).
    #[cfg(test)]
    pub(crate) fn num_exceptions(&self) -> usize {
        self.vertex_special.len() + self.edge_special.len()
    }

    /// One step of `N`-component values from parent `p`, bit-identical to
    /// [`LevelStencils::apply`] of the step's stencils `s`, in parallel chunks of rows. `s`
    /// is read only by a plan that applies the stored tables whole (`stencils_only`); the
    /// others read their own rows and `p`'s face lists.
    pub(crate) fn apply<'s, const N: usize>(
        &self,
        p: &super::Topology,
        s: impl FnOnce() -> Option<&'s LevelStencils>,
        src: &[[f32; N]],
        dst: &mut [[f32; N]],
    ) {
        if let Some(lp) = &self.loop_plan {
            lp.apply(p, src, dst);
            return;
        }
        let own = match &self.own {
            Some(own) if !self.stencils_only => own,
            _ => {
                s().expect("a plan without rows of its own applies the stored tables")
                    .apply(src, dst);
                return;
            }
        };
        let t = Tables {
            face: own.face.as_ref(),
            quads: &p.face_verts,
            vertex: &own.vertex,
            edge: &own.edge,
        };
        let np = p.num_vertices();
        let rows = np + p.num_faces() + p.num_edges();
        assert_eq!(dst.len(), rows, "destination length");
        assert!(src.len() >= np, "source length");
        // Padded sources: `src` holds a value past the parent's, and the face points are
        // followed by the first edge point (there is one).
        let padded = src.len() > np && t.edge.num_rows() > 0;
        #[cfg(target_arch = "x86_64")]
        if let (Some(src), Some(dst)) = (lanes::as3(src), lanes::as3_mut(dst)) {
            return if padded {
                self.apply_with::<3, Padded<lanes::Lanes3>>(&t, np, src, dst, true)
            } else {
                self.apply_with::<3, lanes::Lanes3>(&t, np, src, dst, false)
            };
        }
        self.apply_with::<N, [f32; N]>(&t, np, src, dst, false);
    }

    /// [`StepPlan::apply`] summing each row in accumulators of type `A` (the same products
    /// and sums in the same order, whatever `A`). With `padded` (`A` then a [`Padded`]
    /// accumulator) the rows read sources one value longer than the values they sum:
    /// `src[..p + 1]`, and the face points with the first edge point after them, which is
    /// therefore formed first, alone, before the other edge points are formed in parallel
    /// (no value is read while another thread writes it).
    fn apply_with<const N: usize, A: Acc<N>>(
        &self,
        t: &Tables<'_>,
        p: usize,
        src: &[[f32; N]],
        dst: &mut [[f32; N]],
        padded: bool,
    ) {
        let (nv, ne) = (t.vertex.num_rows(), t.edge.num_rows());
        let nf = dst.len() - nv - ne;
        let pad = usize::from(padded);
        let src = &src[..p + pad];
        let (vd, rest) = dst.split_at_mut(nv);
        let fd = &mut rest[..nf];
        match t.face {
            Some(face) if !self.quad_faces => face.apply(&src[..p], fd),
            _ => fd
                .par_chunks_mut(CHUNK)
                .zip(t.quads[..4 * nf].par_chunks(4 * CHUNK))
                .for_each(|(out, q)| quad_rows::<N, A>(q, src, out)),
        }
        let [vex, eex] = &self.exceptions;
        {
            let fd = &rest[..nf + pad];
            vd.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
                self.vertex_rows::<N, A>(t.vertex, vex, p, c * CHUNK, out, src, fd);
            });
        }
        let special = &self.edge_special;
        if padded {
            let mut first = [[0.0; N]];
            edge_rows::<N, A>(t.edge, eex, special, p, 0, &mut first, src, &rest[..nf + 1]);
            rest[nf] = first[0];
        }
        let (fd, ed) = rest.split_at_mut(nf + pad);
        let fd: &[[f32; N]] = fd;
        ed.par_chunks_mut(CHUNK).enumerate().for_each(|(c, out)| {
            edge_rows::<N, A>(t.edge, eex, special, p, pad + c * CHUNK, out, src, fd);
        });
    }

    /// Vertex rows `first..first + out.len()`: the runs of smooth valence-4 rows (9 entries
    /// each, contiguous from the run's first offset) between the other rows, each of those
    /// from its offsets (an exception from its stored row).
    #[allow(clippy::too_many_arguments)]
    fn vertex_rows<const N: usize, A: Acc<N>>(
        &self,
        t: &StencilTable,
        ex: &StencilTable,
        p: usize,
        first: usize,
        out: &mut [[f32; N]],
        src: &[[f32; N]],
        fd: &[[f32; N]],
    ) {
        let end = first + out.len();
        let mut q = self
            .vertex_special
            .partition_point(|&r| (r as usize) < first);
        let mut special = in_range(&self.vertex_special, first, out.len()).iter();
        let mut odd = in_range(&self.vertex_odd, first, out.len()).iter();
        let row = |r: Option<&u32>| r.map_or(end, |&r| r as usize);
        let (mut next_special, mut next_odd) = (row(special.next()), row(odd.next()));
        let mut out = out;
        let mut r = first;
        let mut j = t.offsets[first] as usize;
        loop {
            let e = next_special.min(next_odd);
            let (run, rest) = std::mem::take(&mut out).split_at_mut(e - r);
            vertex4_run::<N, A>(&t.indices[j..j + 9 * run.len()], run, src, fd);
            let Some((o, rest)) = rest.split_first_mut() else {
                break;
            };
            let (lo, hi) = (j + 9 * run.len(), t.offsets[e + 1] as usize);
            let idx = &t.indices[lo..hi];
            if e == next_special {
                *o = exception_row::<N, A>(ex, q, p, src, fd);
                q += 1;
                next_special = row(special.next());
            } else {
                let n = idx.len() / 2;
                let [w, wv] = self.valence_weights[n];
                let mut acc = A::zero();
                for &k in &idx[..n] {
                    acc.add_at(w, fd, k as usize);
                }
                for &k in &idx[n..2 * n] {
                    acc.add_at(w, src, k as usize);
                }
                acc.add_at(wv, src, idx[2 * n] as usize);
                *o = acc.get();
                next_odd = row(odd.next());
            }
            out = rest;
            j = hi;
            r = e + 1;
        }
    }
}

/// The smooth vertex weights at valence 4, `(1/16, 1/2)` (equal to
/// `smooth_vertex_weights(4)`, tested).
const VALENCE4: [f32; 2] = [0.0625, 0.5];

/// Face points of quads whose vertices are `idx` (four per row of `out`), `1/4` each.
fn quad_rows<const N: usize, A: Acc<N>>(idx: &[u32], src: &[[f32; N]], out: &mut [[f32; N]]) {
    for (o, q) in out.iter_mut().zip(idx.chunks_exact(4)) {
        let &[a, b, c, d] = q else {
            unreachable!("chunks of 4")
        };
        let mut acc = A::zero();
        acc.add(0.25, src, a as usize);
        acc.add(0.25, src, b as usize);
        acc.add(0.25, src, c as usize);
        acc.add(0.25, src, d as usize);
        *o = acc.get();
    }
}

/// A row's running sum: `add` does `acc += w · v` component by component (the tables'
/// accumulation), whatever the representation.
pub(crate) trait Acc<const N: usize>: Copy {
    /// All components zero.
    fn zero() -> Self;
    /// `self += w · v[k]`.
    fn add(&mut self, w: f32, v: &[[f32; N]], k: usize);
    /// `self += w · v[k]` where `v` holds one value past the values summed: `k < v.len() - 1`
    /// (checked), so a representation may load `v[k]` with what follows it.
    #[inline(always)]
    fn add_padded(&mut self, w: f32, v: &[[f32; N]], k: usize) {
        if k >= v.len().saturating_sub(1) {
            past_the_values(k, v.len());
        }
        self.add(w, v, k);
    }
    /// `self += w · v[off / 3]`: the gather offset of an [`OwnRows`] input.
    #[inline(always)]
    fn add_at(&mut self, w: f32, v: &[[f32; N]], off: usize) {
        self.add(w, v, off / 3);
    }
    /// [`Acc::add_at`] from a padded source ([`Acc::add_padded`]).
    #[inline(always)]
    fn add_at_padded(&mut self, w: f32, v: &[[f32; N]], off: usize) {
        self.add_padded(w, v, off / 3);
    }
    /// The components.
    fn get(self) -> [f32; N];
}

/// The panic of [`Acc::add_padded`], out of the loops' way.
#[cold]
#[inline(never)]
pub(crate) fn past_the_values(k: usize, len: usize) -> ! {
    panic!("value {k} read from a padded source of {len} values (one past the last summed)")
}

/// An accumulator summing from padded sources ([`Acc::add_padded`]) through `add`, so the
/// same kernels serve both: the sources handed to them then hold one value past their rows.
#[derive(Clone, Copy)]
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
pub(crate) struct Padded<A>(A);

impl<const N: usize, A: Acc<N>> Acc<N> for Padded<A> {
    #[inline(always)]
    fn zero() -> Self {
        Padded(A::zero())
    }
    #[inline(always)]
    fn add(&mut self, w: f32, v: &[[f32; N]], k: usize) {
        self.0.add_padded(w, v, k);
    }
    #[inline(always)]
    fn add_at(&mut self, w: f32, v: &[[f32; N]], off: usize) {
        self.0.add_at_padded(w, v, off);
    }
    #[inline(always)]
    fn get(self) -> [f32; N] {
        self.0.get()
    }
}

impl<const N: usize> Acc<N> for [f32; N] {
    #[inline(always)]
    fn zero() -> Self {
        [0.0; N]
    }
    #[inline(always)]
    fn add(&mut self, w: f32, v: &[[f32; N]], k: usize) {
        for (a, x) in self.iter_mut().zip(&v[k]) {
            *a += w * x;
        }
    }
    #[inline(always)]
    fn get(self) -> [f32; N] {
        self
    }
}

/// Smooth vertex rows of valence 4, 9 gather offsets each in `idx` ([`OwnRows`]), into
/// `out`.
fn vertex4_run<const N: usize, A: Acc<N>>(
    idx: &[u32],
    out: &mut [[f32; N]],
    src: &[[f32; N]],
    fd: &[[f32; N]],
) {
    let [w, wv] = VALENCE4;
    for (o, q) in out.iter_mut().zip(idx.chunks_exact(9)) {
        let q: &[u32; 9] = q.try_into().expect("chunks of 9");
        let mut acc = A::zero();
        for &k in &q[..4] {
            acc.add_at(w, fd, k as usize);
        }
        for &k in &q[4..8] {
            acc.add_at(w, src, k as usize);
        }
        acc.add_at(wv, src, q[8] as usize);
        *o = acc.get();
    }
}

/// Edge rows `first..first + out.len()`: the runs of smooth rows between exceptions (four
/// indices each, contiguous from the run's first offset), then each exception from its
/// stored row.
#[allow(clippy::too_many_arguments)]
fn edge_rows<const N: usize, A: Acc<N>>(
    t: &StencilTable,
    ex: &StencilTable,
    special: &[u32],
    p: usize,
    first: usize,
    out: &mut [[f32; N]],
    src: &[[f32; N]],
    fd: &[[f32; N]],
) {
    runs_between::<N, A>(special, ex, p, src, fd, first, out, |r, run| {
        // An exception's row is empty here, so a run's indices start at its first offset.
        let j = t.offsets[r] as usize;
        edge_run::<N, A>(&t.indices[j..j + 4 * run.len()], run, src, fd);
    });
}

/// Rows `first..first + out.len()` of a table whose exceptions are the rows `special`
/// (ascending; exception `q` is row `q` of `ex`, over parent vertices below `p` and face points
/// `fd`): each run of rows between two exceptions handed to `run(its first row, its outputs)`,
/// each exception summed from its stored row.
#[allow(clippy::too_many_arguments)]
pub(super) fn runs_between<const N: usize, A: Acc<N>>(
    special: &[u32],
    ex: &StencilTable,
    p: usize,
    src: &[[f32; N]],
    fd: &[[f32; N]],
    first: usize,
    out: &mut [[f32; N]],
    mut run: impl FnMut(usize, &mut [[f32; N]]),
) {
    let end = first + out.len();
    // Exception `q` of the chunk is row `q0 + q` of `ex`.
    let q0 = special.partition_point(|&r| (r as usize) < first);
    let mut out = out;
    let mut r = first;
    for (q, e) in in_range(special, first, out.len())
        .iter()
        .map(|&e| e as usize)
        .chain([end])
        .enumerate()
    {
        let (rows, rest) = std::mem::take(&mut out).split_at_mut(e - r);
        run(r, rows);
        let Some((o, rest)) = rest.split_first_mut() else {
            break;
        };
        *o = exception_row::<N, A>(ex, q0 + q, p, src, fd);
        out = rest;
        r = e + 1;
    }
}

/// Smooth two-face edge rows, 4 gather offsets each in `idx` (two face points, two ends;
/// [`OwnRows`]), into `out`.
fn edge_run<const N: usize, A: Acc<N>>(
    idx: &[u32],
    out: &mut [[f32; N]],
    src: &[[f32; N]],
    fd: &[[f32; N]],
) {
    for (o, q) in out.iter_mut().zip(idx.chunks_exact(4)) {
        let &[a, b, c, d] = q else {
            unreachable!("chunks of 4")
        };
        let mut acc = A::zero();
        acc.add_at(0.25, fd, a as usize);
        acc.add_at(0.25, fd, b as usize);
        acc.add_at(0.25, src, c as usize);
        acc.add_at(0.25, src, d as usize);
        *o = acc.get();
    }
}

/// Row `q` of the exceptions' table `ex`.
#[inline]
fn exception_row<const N: usize, A: Acc<N>>(
    ex: &StencilTable,
    q: usize,
    p: usize,
    src: &[[f32; N]],
    fd: &[[f32; N]],
) -> [f32; N] {
    let (lo, hi) = (ex.offsets[q] as usize, ex.offsets[q + 1] as usize);
    split_row::<N, A>(&ex.indices[lo..hi], &ex.weights[lo..hi], p, src, fd)
}

/// The tables a plan reads: its own rows ([`OwnRows`]) and the parent's face lists.
struct Tables<'a> {
    /// The face rows, where not all quads.
    face: Option<&'a StencilTable>,
    /// Four vertices per face, where all quads.
    quads: &'a [u32],
    vertex: &'a StencilTable,
    edge: &'a StencilTable,
}

/// Most values an offset table ([`OwnRows`]) can address: `3 k` fits a `u32`.
pub(super) const OFFSET_MAX: usize = (u32::MAX / 3) as usize;

/// The gather offset of stored input `k` of a step from `p` parent vertices: `3 k` for a
/// parent vertex, `3 (k - p)` for a face point.
#[inline]
fn offset_of(k: u32, p: u32) -> u32 {
    3 * if k < p { k } else { k - p }
}

/// The stored input at gather offset `off`, the entry being a face point or not.
#[inline]
pub(super) fn input_at(off: u32, face_point: bool, p: u32) -> u32 {
    off / 3 + if face_point { p } else { 0 }
}

/// The smooth rows of stored table `t` (all but `special`, ascending) as gather offsets
/// ([`offset_of`]), each special row empty, or `stride` zeros where rows have a fixed length.
fn offset_rows(t: &StencilTable, special: &[u32], p: u32, stride: Option<usize>) -> StencilTable {
    let mut out = StencilTable {
        offsets: Vec::with_capacity(t.offsets.len()),
        indices: Vec::with_capacity(t.indices.len()),
        weights: Vec::new(),
        num_inputs: t.num_inputs,
    };
    out.offsets.push(0);
    let mut special = special.iter().peekable();
    for r in 0..t.num_rows() {
        if special.next_if_eq(&&(r as u32)).is_some() {
            out.indices
                .resize(out.indices.len() + stride.unwrap_or(0), 0);
        } else {
            let (lo, hi) = (t.offsets[r] as usize, t.offsets[r + 1] as usize);
            out.indices
                .extend(t.indices[lo..hi].iter().map(|&k| offset_of(k, p)));
        }
        out.offsets.push(out.indices.len() as u32);
    }
    out
}

/// A stored row over parent vertices (`k < p`) and face points (`fd[k - p]`).
#[inline(always)]
pub(super) fn split_row<const N: usize, A: Acc<N>>(
    idx: &[u32],
    w: &[f32],
    p: usize,
    src: &[[f32; N]],
    fd: &[[f32; N]],
) -> [f32; N] {
    let mut acc = A::zero();
    for (&k, &w) in idx.iter().zip(w) {
        let k = k as usize;
        if k < p {
            acc.add(w, src, k);
        } else {
            acc.add(w, fd, k - p);
        }
    }
    acc.get()
}

/// The entries of the ascending list `rows` that fall in `first..first + len`.
fn in_range(rows: &[u32], first: usize, len: usize) -> &[u32] {
    let lo = rows.partition_point(|&r| (r as usize) < first);
    let hi = rows.partition_point(|&r| (r as usize) < first + len);
    &rows[lo..hi]
}

/// The rows of `t` for which `keep(indices, weights)` is true, ascending.
fn rows_where(t: &StencilTable, keep: impl Fn(&[u32], &[f32]) -> bool + Sync) -> Vec<u32> {
    let [rows] = rows_by_class(t, |idx, w| keep(idx, w).then_some(0));
    rows
}

/// The rows of `t` in each of `K` classes, ascending: row `r` is in class `c` when
/// `class(indices, weights)` is `Some(c)`, in none when it is `None`.
fn rows_by_class<const K: usize>(
    t: &StencilTable,
    class: impl Fn(&[u32], &[f32]) -> Option<usize> + Sync,
) -> [Vec<u32>; K] {
    let rows = t.num_rows();
    let parts: Vec<[Vec<u32>; K]> = (0..rows.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut part: [Vec<u32>; K] = std::array::from_fn(|_| Vec::new());
            for r in c * CHUNK..((c + 1) * CHUNK).min(rows) {
                let (lo, hi) = (t.offsets[r] as usize, t.offsets[r + 1] as usize);
                if let Some(k) = class(&t.indices[lo..hi], &t.weights[lo..hi]) {
                    part[k].push(r as u32);
                }
            }
            part
        })
        .collect();
    std::array::from_fn(|k| parts.iter().flat_map(|p| p[k].iter().copied()).collect())
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
        let p = r.stencils().iter().map(StepPlan::new).collect();
        (r, p)
    }

    #[test]
    fn a_closed_regular_mesh_has_no_exceptions() {
        // Every vertex of a torus grid has valence 4 and no crease: every row is smooth.
        let (r, p) = plans(&shapes::torus(6, 5, 2.0, 0.5), 3);
        // The refiner made its own plans from the topology, with the same classes.
        let own = r.frame_plans.get().expect("plans made from the topology");
        for o in own {
            assert!(o.own.is_some() && o.quad_faces && o.num_exceptions() == 0);
        }
        for s in &p {
            assert!(s.quad_faces && !s.stencils_only);
            assert_eq!(s.num_exceptions(), 0);
            assert!(s.vertex_odd.is_empty());
        }
    }

    #[test]
    fn other_valences_break_the_valence_4_runs() {
        // A cube's eight corners have valence 3 at every level, the face centres of the
        // first step valence 4: the corners are the only smooth rows of another valence,
        // and applying the plan gives the stored tables' bits.
        let m = shapes::cube();
        let (r, p) = plans(&m, 3);
        for plan in &p {
            assert_eq!(plan.num_exceptions(), 0);
            assert_eq!(plan.vertex_odd, (0..8).collect::<Vec<u32>>());
        }
        assert_plans_match_tables(&r, &p, m.positions.to_vec());
    }

    /// Applies every step's plan (those classified from the stored tables, `p`, and those
    /// the refiner made from the topology) and its stored tables from `src` on: the same
    /// bits.
    fn assert_plans_match_tables(r: &Refiner, p: &[StepPlan], mut src: Vec<[f32; 3]>) {
        let bits =
            |v: &[[f32; 3]]| -> Vec<[u32; 3]> { v.iter().map(|x| x.map(f32::to_bits)).collect() };
        // A refiner whose steps are mostly exceptions keeps stored tables and no own plans.
        let own = r.frame_plans.get();
        for (k, (s, plan)) in r.stencils().iter().zip(p).enumerate() {
            let mut want = vec![[0.0f32; 3]; s.num_rows()];
            s.apply(&src, &mut want);
            // Each plan from the source alone and from the source with a value after it
            // (the padded path, which reads one value past the rows).
            let mut padded = src.clone();
            padded.push([f32::NAN, 7.0, -1.0]);
            for plan in [Some(plan), own.map(|o| &o[k])].into_iter().flatten() {
                for src in [&src, &padded] {
                    let mut got = vec![[f32::NAN; 3]; s.num_rows()];
                    plan.apply(&r.levels[k], || Some(s), src, &mut got);
                    assert_eq!(bits(&got), bits(&want));
                }
            }
            src = want;
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
        assert_plans_match_tables(&r, &p, src);
    }

    #[test]
    fn a_one_thread_pool_gives_the_same_bits() {
        // On one thread every pass runs as one sequential loop (no chunks): the same bits
        // as the tables (`refine_all` applies the stored stencils) on every regression
        // shape, the car one level deeper.
        let dir =
            std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes");
        let mut cases: Vec<_> =
            shapes::regression_shapes(&dir, &["catmark_", "bilinear_", "loop_"])
                .unwrap()
                .into_iter()
                .map(|p| (p, 2))
                .collect();
        assert!(cases.len() > 50);
        cases.push((dir.join("catmark_car.obj"), 3));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        pool.install(|| {
            let mut scratch = Vec::new();
            for (path, level) in cases {
                let m = crate::io::read_path(&path).unwrap();
                let r = Refiner::new(Topology::new(&m).unwrap(), level).unwrap();
                let want = r.refine_all(&m.positions).pop().expect("levels");
                let mut out = vec![[f32::NAN; 3]; want.len()];
                r.refine_positions_into(&m.positions, &mut out, &mut scratch)
                    .unwrap();
                let bits = |v: &[[f32; 3]]| -> Vec<[u32; 3]> {
                    v.iter().map(|x| x.map(f32::to_bits)).collect()
                };
                assert_eq!(bits(&out), bits(&want), "{}", path.display());
            }
        });
    }

    #[test]
    fn valence4_weights_are_the_tables() {
        assert_eq!(
            VALENCE4.map(f32::to_bits),
            smooth_vertex_weights(4).map(f32::to_bits)
        );
    }

    #[test]
    fn a_bilinear_step_applies_its_tables() {
        let mut m = shapes::cube();
        m.options.scheme = Scheme::Bilinear;
        let (_, p) = plans(&m, 2);
        assert!(p.iter().all(|s| s.stencils_only));
    }
}
