//! Bytes a subsurf frame moves, against what `memcpy` moves per second on this machine.
//!
//! A frame (`Refiner::refine_positions_into`) reads, per step, the stored indices of every
//! row (the weights and row offsets only where its plan needs them: vertex rows' offsets and
//! the exceptions' weights, counted here as if every vertex row were smooth), each parent
//! value at least once, and writes each child value once. The count is a lower bound on the
//! traffic (a parent value read twice from memory counts once).

use std::time::Instant;
use subsurf::Refiner;

/// Bytes one frame of `N = 3` values reads and writes: `(plan, stored tables)` — with the
/// smooth plan, and applying every stored row with its weight and offsets.
pub fn frame_bytes(r: &Refiner) -> (usize, usize) {
    let (mut plan, mut tables) = (0, 0);
    for s in r.stencils() {
        let values = 12 * (s.num_parent_vertices() + s.num_rows());
        plan += values
            + 4 * (s.face().indices().len()
                + s.vertex().offsets().len()
                + s.vertex().indices().len())
            + 4 * s.edge().indices().len();
        tables += values + s.size_bytes();
    }
    (plan, tables)
}

/// `memcpy`'s bandwidth in GB/s (read plus write bytes per second, as the frame counts them),
/// the median of `runs` copies of a buffer of `bytes`.
pub fn memcpy_gbps(bytes: usize, runs: usize) -> f64 {
    let src = vec![1u8; bytes];
    let mut dst = vec![0u8; bytes];
    dst.copy_from_slice(&src);
    let mut t: Vec<f64> = (0..runs.max(1))
        .map(|_| {
            let t0 = Instant::now();
            dst.copy_from_slice(std::hint::black_box(&src));
            std::hint::black_box(&mut dst);
            t0.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(|a, b| a.total_cmp(b));
    2.0 * bytes as f64 / t[t.len() / 2] / 1e9
}

/// A frame through the stored rows only (every row's offsets, indices and weights, as
/// `LevelStencils::apply` reads them): the path `refine_positions_into` took before its smooth
/// plan, into the same kind of kept buffers, for an in-process comparison.
pub fn stored_rows_frame(
    r: &Refiner,
    base: &[[f32; 3]],
    out: &mut [[f32; 3]],
    scratch: &mut Vec<[f32; 3]>,
) {
    let steps = r.stencils().len();
    if steps >= 2 {
        scratch.resize(
            scratch.len().max(r.stencils()[steps - 2].num_rows()),
            [0.0; 3],
        );
    }
    for (i, s) in r.stencils().iter().enumerate() {
        let n = s.num_rows();
        let prev = if i == 0 {
            0
        } else {
            r.stencils()[i - 1].num_rows()
        };
        if (steps - i - 1) % 2 == 0 {
            let src: &[[f32; 3]] = if i == 0 { base } else { &scratch[..prev] };
            s.apply(src, &mut out[..n]);
        } else {
            let src: &[[f32; 3]] = if i == 0 { base } else { &out[..prev] };
            s.apply(src, &mut scratch[..n]);
        }
    }
}
