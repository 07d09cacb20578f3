//! [`Refiner::refine_positions_into`]: the per-frame evaluation of [`Refiner::refine_positions`]
//! into buffers the caller keeps, so that an animated mesh allocates nothing per frame.

use super::smooth_frame::StepPlan;
use super::Refiner;
use crate::error::{MeshError, Result};

impl Refiner {
    /// Vertex data of the last level written into `out`, bit-identical to
    /// [`Refiner::refine_positions`], allocating nothing once `scratch` has grown to one
    /// value more than the second-to-last level (on the first call).
    ///
    /// Levels alternate between `out` and `scratch` from the last one down: level `L` fills
    /// `out`, level `L - 1` the front of `scratch`, level `L - 2` the front of `out`, and so on,
    /// so the one scratch buffer holds at most the second-to-last level.
    ///
    /// Rows that follow the smooth rules (most of them) are evaluated from their input indices
    /// alone, their weights known from their class; only the other rows read their stored
    /// weights. The per-step plans saying which is which are found on the first call and kept.
    ///
    /// Errors with [`MeshError::LengthMismatch`] when `base` does not hold one value per base
    /// vertex or `out` one value per last-level vertex.
    ///
    /// ```
    /// use subsurf::{shapes, Refiner, Topology};
    ///
    /// let cube = shapes::cube();
    /// let r = Refiner::new(Topology::new(&cube)?, 2)?;
    /// let mut out = vec![[0.0f32; 3]; r.last().num_vertices()];
    /// let mut scratch = Vec::new();
    /// r.refine_positions_into(&cube.positions, &mut out, &mut scratch)?;
    /// assert_eq!(out, r.refine_positions(&cube.positions));
    /// # Ok::<(), subsurf::Error>(())
    /// ```
    pub fn refine_positions_into<const N: usize>(
        &self,
        base: &[[f32; N]],
        out: &mut [[f32; N]],
        scratch: &mut Vec<[f32; N]>,
    ) -> Result<()> {
        let inputs = self.levels[0].num_vertices();
        if base.len() != inputs {
            return Err(MeshError::LengthMismatch {
                what: "base vertex data",
                expected: inputs,
                found: base.len(),
            }
            .into());
        }
        let steps = self.max_level();
        let rows = self.levels[steps].num_vertices();
        if out.len() != rows {
            return Err(MeshError::LengthMismatch {
                what: "last-level output",
                expected: rows,
                found: out.len(),
            }
            .into());
        }
        if steps == 0 {
            out.copy_from_slice(base);
            return Ok(());
        }
        if steps >= 2 {
            let need = self.levels[steps - 1].num_vertices();
            // One value more than the level: a step reads its source one value past its
            // rows (`StepPlan::apply`'s padded sources).
            if scratch.len() <= need {
                scratch.resize(need + 1, [0.0; N]);
            }
        }
        let plans = self
            .frame_plans
            .get_or_init(|| self.stencils().iter().map(StepPlan::new).collect());
        // Level k (1-based) goes to `out` when `steps - k` is even, else to `scratch`.
        for (i, plan) in plans.iter().enumerate() {
            let k = i + 1;
            let (p, n, prev) = (
                &self.levels[i],
                self.levels[k].num_vertices(),
                self.levels[i].num_vertices(),
            );
            let s = || self.stencils().get(i);
            if (steps - k) % 2 == 0 {
                let src: &[[f32; N]] = if i == 0 { base } else { padded(scratch, prev) };
                plan.apply(p, s, src, &mut out[..n]);
            } else {
                let src: &[[f32; N]] = if i == 0 { base } else { padded(out, prev) };
                plan.apply(p, s, src, &mut scratch[..n]);
            }
        }
        Ok(())
    }
}

/// The first `prev` values of `v` (the level before), with the value after them where `v` has
/// one: `StepPlan::apply` then reads them padded.
fn padded<T>(v: &[T], prev: usize) -> &[T] {
    &v[..(prev + 1).min(v.len())]
}
