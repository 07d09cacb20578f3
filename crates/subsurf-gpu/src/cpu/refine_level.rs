//! CPU twin of `shaders/refine_level.wgsl`: one uniform refinement step from the per-level
//! stencils of [`subsurf::refine::LevelStencils`].
//!
//! A level is three dispatches over the child buffer, laid out
//! `[vertex rows | face rows | edge rows]` (OpenSubdiv's order):
//!
//! 1. the face table (rows over parent vertices) writes child vertices `P .. P + F`;
//! 2. the vertex table writes child vertices `0 .. P`;
//! 3. the edge table writes child vertices `P + F ..`.
//!
//! Rows of the vertex and edge tables refer to inputs `k < P` (parent vertex `k`) and
//! `k >= P` (face point `k - P`, i.e. child vertex `k`, since the vertex rows come first and
//! there is one per parent vertex). Each row is `Σ_j w_j · src(k_j)` accumulated in f32 in
//! index order starting from zero — the loop of `LevelStencils::apply`, so the twin
//! reproduces the CPU refiner bit for bit.

use crate::error::{GpuError, Result};
use crate::shared::RefineConfig;
use subsurf::refine::{LevelStencils, Refiner, StencilTable};

/// Invocations per workgroup (same as the shader's `WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;

const _: () = assert!(WORKGROUP_SIZE == crate::shader_consts::REFINE_LEVEL_WORKGROUP_SIZE);

/// One invocation of the shader (bindings 0..=5 in order).
pub fn refine_level_invocation(
    row: u32,
    config: &RefineConfig,
    offsets: &[u32],
    indices: &[u32],
    weights: &[f32],
    parent: &[f32],
    child: &mut [f32],
) {
    if row >= config.row_count {
        return;
    }
    let (begin, end) = (
        offsets[row as usize] as usize,
        offsets[row as usize + 1] as usize,
    );
    let stride = config.stride as usize;
    let np = config.num_parent;
    let mut acc = [0.0f32; 4];
    for j in begin..end {
        let w = weights[j];
        let k = indices[j];
        let base = k as usize * stride;
        let src: &[f32] = if k < np { parent } else { child };
        for c in 0..stride {
            acc[c] += w * src[base + c];
        }
    }
    let out = (config.first_row + row) as usize * stride;
    child[out..out + stride].copy_from_slice(&acc[..stride]);
}

/// Runs every invocation of one dispatch.
pub fn refine_level(
    config: &RefineConfig,
    offsets: &[u32],
    indices: &[u32],
    weights: &[f32],
    parent: &[f32],
    child: &mut [f32],
) {
    for row in 0..config.row_count {
        refine_level_invocation(row, config, offsets, indices, weights, parent, child);
    }
}

/// The three dispatches of one level, as `(table, first child row)` in dispatch order.
pub fn level_dispatches(s: &LevelStencils) -> [(&StencilTable, usize); 3] {
    let p = s.num_parent_vertices();
    let f = s.face().num_rows();
    [(s.face(), p), (s.vertex(), 0), (s.edge(), p + f)]
}

/// One refinement step of `parent` (`stride` floats per vertex, 1..=4).
pub fn refine_level_step(s: &LevelStencils, parent: &[f32], stride: usize) -> Result<Vec<f32>> {
    if !(1..=4).contains(&stride) || parent.len() != s.num_parent_vertices() * stride {
        return Err(GpuError::BufferMismatch(format!(
            "{} floats of stride {stride} for {} parent vertices (stride must be 1..=4)",
            parent.len(),
            s.num_parent_vertices()
        )));
    }
    let mut child = vec![0.0f32; s.num_rows() * stride];
    for (table, first_row) in level_dispatches(s) {
        let config = RefineConfig {
            row_count: table.num_rows() as u32,
            stride: stride as u32,
            grid_width: table.num_rows() as u32,
            first_row: first_row as u32,
            num_parent: s.num_parent_vertices() as u32,
            _pad: [0; 3],
        };
        refine_level(
            &config,
            table.offsets(),
            table.indices(),
            table.weights(),
            parent,
            &mut child,
        );
    }
    Ok(child)
}

/// All levels of `refiner` applied to `base` positions; returns the last level.
pub fn refine_positions(refiner: &Refiner, base: &[[f32; 3]]) -> Result<Vec<[f32; 3]>> {
    let mut cur: Vec<f32> = base.iter().flatten().copied().collect();
    for s in refiner.stencils() {
        cur = refine_level_step(s, &cur, 3)?;
    }
    Ok(cur.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use subsurf::{shapes, Topology};

    /// The twin is the CPU refiner's loop: bit-identical results on a cube and a pole.
    #[test]
    fn twin_matches_cpu_refiner_bit_for_bit() {
        for mesh in [shapes::cube(), shapes::pole(5)] {
            let r = Refiner::new(Topology::new(&mesh).unwrap(), 3).unwrap();
            let want = r.refine_positions(&mesh.positions);
            let got = refine_positions(&r, &mesh.positions).unwrap();
            assert_eq!(want.len(), got.len());
            for (i, (a, b)) in want.iter().zip(&got).enumerate() {
                assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits), "vertex {i}");
            }
        }
    }

    #[test]
    fn rejects_bad_strides_and_lengths() {
        let mesh = shapes::cube();
        let r = Refiner::new(Topology::new(&mesh).unwrap(), 1).unwrap();
        assert!(refine_level_step(&r.stencils()[0], &[0.0; 8 * 5], 5).is_err());
        assert!(refine_level_step(&r.stencils()[0], &[0.0; 7 * 3], 3).is_err());
    }
}
