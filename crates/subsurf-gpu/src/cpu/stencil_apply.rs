//! CPU twin of `shaders/stencil_apply.wgsl`.
//!
//! For destination vertex `i` and component `k < stride`:
//!
//! ```text
//! dst[i*stride + k] = Σ_{j = offsets[i]}^{offsets[i+1]-1} weights[j] · src[indices[j]*stride + k]
//! ```
//!
//! accumulated in f32, in increasing `j`, with components processed in blocks of
//! [`BLOCK`] — the loop structure of the shader. The GPU may contract `acc + w·s` into a
//! fused multiply-add, so the two results agree to within the f32 summation error bound
//! `|error| ≤ γ_n Σ_j |w_j s_jk|`, `γ_n = n u / (1 - n u)` with `u = 2^-24` (Higham 2002,
//! "Accuracy and Stability of Numerical Algorithms", §4.2), not bit for bit.

use crate::error::{GpuError, Result};
use crate::shared::StencilConfig;
use crate::table::StencilTable;

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;
/// Components accumulated together (same as the shader's `BLOCK`).
pub const BLOCK: u32 = 4;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::STENCIL_APPLY_WORKGROUP_SIZE);

/// One invocation of the shader: computes destination row `row` of the dispatch.
///
/// Arguments follow the shader's bindings 0..=5. Panics if the slices are inconsistent with
/// `config` (callers go through [`apply_stencil_table`], which validates).
pub fn stencil_apply_invocation(
    row: u32,
    config: &StencilConfig,
    offsets: &[u32],
    indices: &[u32],
    weights: &[f32],
    src: &[f32],
    dst: &mut [f32],
) {
    if row >= config.row_count {
        return;
    }
    let row = row as usize;
    let begin = offsets[row] as usize;
    let end = offsets[row + 1] as usize;
    let stride = config.stride as usize;
    let block = BLOCK as usize;
    let mut k0 = 0;
    while k0 < stride {
        let width = block.min(stride - k0);
        let mut acc = [0.0f32; 4];
        // Relative rows: x0 + Σ w (x − x0) (x0 = 0 otherwise: exactly Σ w x).
        let mut x0 = [0.0f32; 4];
        if config.relative != 0 && begin < end {
            let base0 = indices[begin] as usize * stride + k0;
            x0[..width].copy_from_slice(&src[base0..base0 + width]);
        }
        for j in begin..end {
            let w = weights[j];
            let base = indices[j] as usize * stride + k0;
            for c in 0..width {
                acc[c] += w * (src[base + c] - x0[c]);
            }
        }
        let out = row * stride + k0;
        for c in 0..width {
            dst[out + c] = if config.relative != 0 {
                acc[c] + x0[c]
            } else {
                acc[c]
            };
        }
        k0 += block;
    }
}

/// Runs every invocation of one dispatch of `config.row_count` rows (the bindings of one
/// chunk: chunk-local `offsets`, `dst` starting at the chunk's first row).
pub fn stencil_apply(
    config: &StencilConfig,
    offsets: &[u32],
    indices: &[u32],
    weights: &[f32],
    src: &[f32],
    dst: &mut [f32],
) {
    for row in 0..config.row_count {
        stencil_apply_invocation(row, config, offsets, indices, weights, src, dst);
    }
}

/// Applies a whole table to `src` (`stride` floats per vertex); returns `rows * stride`
/// floats. Checks that `src` holds whole vertices and every vertex the table references.
pub fn apply_stencil_table(
    table: &StencilTable<'_>,
    src: &[f32],
    stride: usize,
) -> Result<Vec<f32>> {
    if stride == 0 || !src.len().is_multiple_of(stride) {
        return Err(GpuError::BufferMismatch(format!(
            "source of {} floats is not a whole number of vertices of stride {stride}",
            src.len()
        )));
    }
    if src.len() / stride < table.min_source_vertices() {
        return Err(GpuError::BufferMismatch(format!(
            "table references {} source vertices but the source holds {}",
            table.min_source_vertices(),
            src.len() / stride
        )));
    }
    let rows = u32::try_from(table.rows())
        .map_err(|_| GpuError::InvalidStencil("more than 2^32 - 1 rows".into()))?;
    let config = StencilConfig {
        row_count: rows,
        stride: stride as u32,
        grid_width: rows,
        relative: 0,
    };
    let mut dst = vec![0.0; table.rows() * stride];
    stencil_apply(
        &config,
        table.offsets(),
        table.indices(),
        table.weights(),
        src,
        &mut dst,
    );
    Ok(dst)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn computes_weighted_sums() {
        // Row 0: midpoint of vertices 0 and 2; row 1: copy of vertex 1; row 2: empty.
        let table = StencilTable::new(&[0, 2, 3, 3], &[0, 2, 1], &[0.5, 0.5, 1.0]).unwrap();
        let src = [1.0, 2.0, 3.0, 7.0, 8.0, 9.0, 5.0, 6.0, -3.0];
        let dst = apply_stencil_table(&table, &src, 3).unwrap();
        assert_eq!(dst, vec![3.0, 4.0, 0.0, 7.0, 8.0, 9.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn strides_above_block_use_every_component() {
        // Stride 6 takes two blocks (4 + 2 components).
        let table = StencilTable::new(&[0, 2], &[1, 0], &[2.0, -1.0]).unwrap();
        let src: Vec<f32> = (0..12).map(|x| x as f32).collect();
        let dst = apply_stencil_table(&table, &src, 6).unwrap();
        let want: Vec<f32> = (0..6).map(|k| 2.0 * (6 + k) as f32 - k as f32).collect();
        assert_eq!(dst, want);
    }

    #[test]
    fn rejects_short_source() {
        let table = StencilTable::new(&[0, 1], &[3], &[1.0]).unwrap();
        assert!(matches!(
            apply_stencil_table(&table, &[0.0; 9], 3),
            Err(GpuError::BufferMismatch(_))
        ));
        assert!(matches!(
            apply_stencil_table(&table, &[0.0; 13], 3),
            Err(GpuError::BufferMismatch(_))
        ));
    }
}
