//! Stencil tables as produced by the refinement module.
//!
//! Row `i` of a table (one destination vertex) is the weighted sum of the source vertices
//! `indices[offsets[i]..offsets[i+1]]` with weights `weights[offsets[i]..offsets[i+1]]`
//! (OpenSubdiv `Far::StencilTable`: sizes/offsets, indices, weights, flattened into a CSR
//! layout).

use crate::error::{GpuError, Result};

/// A validated, borrowed stencil table in CSR layout.
#[derive(Clone, Copy, Debug)]
pub struct StencilTable<'a> {
    offsets: &'a [u32],
    indices: &'a [u32],
    weights: &'a [f32],
    /// One past the largest source index referenced (0 for a table with no entries).
    min_source_vertices: usize,
}

impl<'a> StencilTable<'a> {
    /// Checks the CSR invariants: `offsets` has `rows + 1` entries, starts at 0, never
    /// decreases and ends at `indices.len() == weights.len()`; weights are finite.
    pub fn new(offsets: &'a [u32], indices: &'a [u32], weights: &'a [f32]) -> Result<Self> {
        let bad = |msg: String| Err(GpuError::InvalidStencil(msg));
        if offsets.is_empty() {
            return bad("offsets must hold rows + 1 entries, got none".into());
        }
        if offsets[0] != 0 {
            return bad(format!("offsets[0] must be 0, got {}", offsets[0]));
        }
        if indices.len() != weights.len() {
            return bad(format!(
                "{} indices but {} weights",
                indices.len(),
                weights.len()
            ));
        }
        if let Some(i) = offsets.windows(2).position(|w| w[1] < w[0]) {
            return bad(format!(
                "offsets decrease at row {i}: {} > {}",
                offsets[i],
                offsets[i + 1]
            ));
        }
        let last = *offsets.last().unwrap_or(&0) as usize;
        if last != indices.len() {
            return bad(format!(
                "offsets end at {last} but there are {} entries",
                indices.len()
            ));
        }
        if let Some(j) = weights.iter().position(|w| !w.is_finite()) {
            return bad(format!("weight {j} is not finite ({})", weights[j]));
        }
        let min_source_vertices = indices.iter().map(|&i| i as usize + 1).max().unwrap_or(0);
        Ok(Self {
            offsets,
            indices,
            weights,
            min_source_vertices,
        })
    }

    /// Number of rows (destination vertices).
    pub fn rows(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of (index, weight) entries.
    pub fn entries(&self) -> usize {
        self.indices.len()
    }

    /// Row offsets (`rows + 1`).
    pub fn offsets(&self) -> &'a [u32] {
        self.offsets
    }

    /// Source vertex of each entry.
    pub fn indices(&self) -> &'a [u32] {
        self.indices
    }

    /// Weight of each entry.
    pub fn weights(&self) -> &'a [f32] {
        self.weights
    }

    /// The smallest source vertex count the table can be applied to.
    pub fn min_source_vertices(&self) -> usize {
        self.min_source_vertices
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_valid_and_empty_tables() {
        let t = StencilTable::new(&[0, 2, 3], &[4, 1, 0], &[0.5, 0.5, 1.0]).unwrap();
        assert_eq!((t.rows(), t.entries(), t.min_source_vertices()), (2, 3, 5));
        let e = StencilTable::new(&[0], &[], &[]).unwrap();
        assert_eq!((e.rows(), e.min_source_vertices()), (0, 0));
    }

    #[test]
    fn rejects_malformed_tables() {
        let cases: [(&[u32], &[u32], &[f32]); 6] = [
            (&[], &[], &[]),
            (&[1, 1], &[0], &[1.0]),
            (&[0, 2, 1], &[0, 0], &[1.0, 1.0]),
            (&[0, 1], &[0, 1], &[1.0, 1.0]),
            (&[0, 2], &[0, 1], &[1.0]),
            (&[0, 1], &[0], &[f32::NAN]),
        ];
        for (o, i, w) in cases {
            assert!(
                matches!(StencilTable::new(o, i, w), Err(GpuError::InvalidStencil(_))),
                "accepted offsets {o:?} indices {i:?} weights {w:?}"
            );
        }
    }
}
