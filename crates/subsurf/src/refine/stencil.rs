//! Sparse stencil tables: each row gives one output vertex as a weighted sum of input vertices.
//!
//! Layout (uploaded as is by the GPU backend): `offsets` has `rows + 1` entries; row `i` uses
//! `indices[offsets[i]..offsets[i + 1]]` and the matching `weights`. Applying a table computes
//! `dst[i] = Σ_j weights[j] · src[indices[j]]`, accumulated in `f32` in index order.

use super::smooth_frame::{split_row, Acc};
use crate::real::Real;
use rayon::prelude::*;

/// A sparse row-major matrix from input vertices to output vertices.
///
/// # Example
///
/// The composed table of a two-level refinement maps base positions straight to level 2,
/// as the per-level tables do one after the other; every row is an affine combination:
///
/// ```
/// use subsurf::{shapes, Refiner, StencilTable, Topology};
///
/// let torus = shapes::torus(6, 4, 2.0, 0.5);
/// let refiner = Refiner::new(Topology::new(&torus)?, 2)?;
/// let table: StencilTable = refiner.stencil_table();
/// assert_eq!(table.num_inputs(), torus.num_vertices());
/// assert_eq!(table.num_rows(), refiner.last().num_vertices());
/// assert_eq!(table.offsets().len(), table.num_rows() + 1);
///
/// let mut direct = vec![[0.0f32; 3]; table.num_rows()];
/// table.apply(&torus.positions, &mut direct);
/// let stepwise = refiner.refine_positions(&torus.positions);
/// for (a, b) in direct.iter().zip(&stepwise) {
///     assert!((0..3).all(|c| (a[c] - b[c]).abs() < 1e-5));
/// }
/// for r in 0..table.num_rows() {
///     let (lo, hi) = (table.offsets()[r] as usize, table.offsets()[r + 1] as usize);
///     let sum: f32 = table.weights()[lo..hi].iter().sum();
///     assert!((sum - 1.0).abs() < 1e-5);
/// }
/// # Ok::<(), subsurf::Error>(())
/// ```
///
/// Weights are `W`: `f32` (the default, what the GPU reads), or `f64` for double-precision
/// tables ([`crate::limit::PatchTable::build_real`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StencilTable<W = f32> {
    /// `rows + 1` offsets into `indices` / `weights`.
    pub(crate) offsets: Vec<u32>,
    /// Input vertex of each entry.
    pub(crate) indices: Vec<u32>,
    /// Weight of each entry.
    pub(crate) weights: Vec<W>,
    /// Number of input vertices the indices refer to.
    pub(crate) num_inputs: usize,
}

impl<W> StencilTable<W> {
    /// The same rows with every weight replaced by `f(weight)` (for instance `|w|` for a
    /// rounding bound).
    pub fn map_weights<V>(&self, f: impl Fn(&W) -> V) -> StencilTable<V> {
        StencilTable {
            offsets: self.offsets.clone(),
            indices: self.indices.clone(),
            weights: self.weights.iter().map(f).collect(),
            num_inputs: self.num_inputs,
        }
    }

    /// `rows + 1` offsets into `indices` / `weights`.
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// Input vertex of each entry.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// Weight of each entry.
    pub fn weights(&self) -> &[W] {
        &self.weights
    }

    /// Number of input vertices the indices refer to.
    pub fn num_inputs(&self) -> usize {
        self.num_inputs
    }
}

impl<W> StencilTable<W> {
    /// Number of output vertices.
    pub fn num_rows(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Number of non-zero entries.
    pub fn num_entries(&self) -> usize {
        self.indices.len()
    }

    /// Bytes held by the three arrays.
    pub fn size_bytes(&self) -> usize {
        4 * (self.offsets.len() + self.indices.len())
            + std::mem::size_of::<W>() * self.weights.len()
    }
}

impl StencilTable {
    /// Applies the table to `N`-component values (positions: `N = 3`, UVs: `N = 2`),
    /// in parallel over rows.
    pub fn apply<const N: usize>(&self, src: &[[f32; N]], dst: &mut [[f32; N]]) {
        assert!(src.len() >= self.num_inputs, "source length");
        self.apply_split(src, &[], src.len(), dst, true);
    }

    /// Applies the table on the calling thread only.
    pub fn apply_serial<const N: usize>(&self, src: &[[f32; N]], dst: &mut [[f32; N]]) {
        self.apply_split(src, &[], src.len(), dst, false);
    }

    /// Applies the table to inputs held in two slices: input `k` is `src[k]` below `p`, else
    /// `fd[k - p]` (a refinement step's parent vertices and face points), in parallel chunks
    /// of rows or on the calling thread. Each row is `Σ w · x(k)` accumulated in `f32` in entry
    /// order; three-component values are summed in one SSE register on x86-64
    /// (`super::lanes`: the same products and sums, bit for bit).
    pub(crate) fn apply_split<const N: usize>(
        &self,
        src: &[[f32; N]],
        fd: &[[f32; N]],
        p: usize,
        dst: &mut [[f32; N]],
        parallel: bool,
    ) {
        assert_eq!(dst.len(), self.num_rows(), "destination length");
        #[cfg(target_arch = "x86_64")]
        if let (Some(src), Some(fd), Some(dst)) = (
            super::lanes::as3(src),
            super::lanes::as3(fd),
            super::lanes::as3_mut(dst),
        ) {
            return self.apply_acc::<3, super::lanes::Lanes3>(src, fd, p, dst, parallel);
        }
        self.apply_acc::<N, [f32; N]>(src, fd, p, dst, parallel);
    }

    /// [`StencilTable::apply_split`], each row summed in an `A`.
    fn apply_acc<const N: usize, A: Acc<N>>(
        &self,
        src: &[[f32; N]],
        fd: &[[f32; N]],
        p: usize,
        dst: &mut [[f32; N]],
        parallel: bool,
    ) {
        const CHUNK: usize = 4096;
        // Without face points every input is in `src`: no test of which slice per entry.
        let rows = |first: usize, out: &mut [[f32; N]]| {
            if fd.is_empty() {
                self.walk_rows(first, out, |ri, rw| {
                    split_row::<N, A>(ri, rw, usize::MAX, src, fd)
                });
            } else {
                self.walk_rows(first, out, |ri, rw| split_row::<N, A>(ri, rw, p, src, fd));
            }
        };
        if parallel {
            dst.par_chunks_mut(CHUNK)
                .enumerate()
                .for_each(|(c, out)| rows(c * CHUNK, out));
        } else {
            rows(0, dst);
        }
    }

    /// Rows `first..first + out.len()` into `out`, each `row(indices, weights)`. The rows'
    /// entries are contiguous, so they are walked once; rows of 4, 7 and 9 entries (a smooth
    /// edge point, a smooth Loop vertex of valence 6, a smooth valence-4 vertex) are handed
    /// over as slices of known length, so `row` unrolls for them.
    #[inline(always)]
    fn walk_rows<const N: usize>(
        &self,
        first: usize,
        out: &mut [[f32; N]],
        row: impl Fn(&[u32], &[f32]) -> [f32; N],
    ) {
        let offs = &self.offsets[first..=first + out.len()];
        let (lo, hi) = (offs[0] as usize, offs[out.len()] as usize);
        let (idx, wts) = (&self.indices[lo..hi], &self.weights[lo..hi]);
        let mut j = 0;
        for (o, w2) in out.iter_mut().zip(offs.windows(2)) {
            let n = (w2[1] - w2[0]) as usize;
            let (ri, rw) = (&idx[j..j + n], &wts[j..j + n]);
            j += n;
            *o = match n {
                4 => row(&ri[..4], &rw[..4]),
                7 => row(&ri[..7], &rw[..7]),
                9 => row(&ri[..9], &rw[..9]),
                _ => row(ri, rw),
            };
        }
    }

    /// Composes two tables: `(other ∘ self)`, i.e. first `self` then `other`.
    /// Rows of the result are `other`'s rows expressed in `self`'s inputs.
    pub fn then(&self, other: &StencilTable) -> StencilTable {
        let rows = other.num_rows();
        let chunk = 8192;
        let parts: Vec<(Vec<u32>, Vec<u32>, Vec<f32>)> = (0..rows.div_ceil(chunk))
            .into_par_iter()
            .map(|c| {
                let mut builder = RowBuilder::new(self.num_inputs);
                let (mut counts, mut idx, mut wts) = (Vec::new(), Vec::new(), Vec::new());
                for r in c * chunk..((c + 1) * chunk).min(rows) {
                    let (s, e) = (other.offsets[r] as usize, other.offsets[r + 1] as usize);
                    for j in s..e {
                        let (m, w) = (other.indices[j] as usize, other.weights[j]);
                        let (ms, me) = (self.offsets[m] as usize, self.offsets[m + 1] as usize);
                        for q in ms..me {
                            builder.add_f64(self.indices[q], w as f64 * self.weights[q] as f64);
                        }
                    }
                    counts.push(builder.len() as u32);
                    builder.drain_into(&mut idx, &mut wts);
                }
                (counts, idx, wts)
            })
            .collect();
        let mut out = StencilTable {
            offsets: vec![0],
            num_inputs: self.num_inputs,
            ..Default::default()
        };
        for (counts, idx, wts) in parts {
            for c in counts {
                let last = *out.offsets.last().unwrap_or(&0);
                out.offsets.push(last + c);
            }
            out.indices.extend(idx);
            out.weights.extend(wts);
        }
        out
    }
}

/// Accumulates one row, merging repeated inputs. Short rows merge by linear search; long rows
/// use a marker array sized to the number of inputs.
#[derive(Debug)]
pub(crate) struct RowBuilder {
    idx: Vec<u32>,
    wts: Vec<f64>,
    marker: Vec<u32>,
}

impl RowBuilder {
    pub(crate) fn new(num_inputs: usize) -> Self {
        RowBuilder {
            idx: Vec::with_capacity(64),
            wts: Vec::with_capacity(64),
            marker: vec![u32::MAX; num_inputs],
        }
    }
    #[inline]
    pub(crate) fn add<W: Real>(&mut self, i: u32, w: W) {
        self.add_f64(i, w.to_f64());
    }
    /// Adds with a weight kept in double precision until the row is drained.
    #[inline]
    pub(crate) fn add_f64(&mut self, i: u32, w: f64) {
        let m = self.marker[i as usize];
        if m != u32::MAX {
            self.wts[m as usize] += w;
        } else {
            self.marker[i as usize] = self.idx.len() as u32;
            self.idx.push(i);
            self.wts.push(w);
        }
    }
    pub(crate) fn len(&self) -> usize {
        self.idx.len()
    }
    pub(crate) fn drain_into<W: Real>(&mut self, idx: &mut Vec<u32>, wts: &mut Vec<W>) {
        for &i in &self.idx {
            self.marker[i as usize] = u32::MAX;
        }
        idx.extend_from_slice(&self.idx);
        wts.extend(self.wts.iter().map(|&w| W::from_f64(w)));
        self.idx.clear();
        self.wts.clear();
    }
}
