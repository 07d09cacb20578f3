//! OpenSubdiv's limit surface in double precision: the reference for measuring the `f32`
//! rounding of subsurf's evaluation (normals of small or thin faces, surfaces far from the
//! origin), which a single-precision reference shares in part.

use crate::adaptive::{patch_stats, PatchOptions};
use crate::ffi;
use crate::mesh::{Desc, OsdMesh};
use crate::{unavailable_or_osd, Error, Result};

/// One limit-surface sample in double precision (see [`crate::LimitSample`]): the mesh's
/// `f64` positions ([`crate::OsdMesh::positions_f64`], else its `f32` ones widened) refined,
/// turned into end-cap points and evaluated in `f64`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LimitSampleF64 {
    /// Ptex face index.
    pub face: u32,
    /// Ptex coordinate along the face's first edge (the `f32` value subsurf evaluates at).
    pub u: f32,
    /// Ptex coordinate along the face's last edge.
    pub v: f32,
    /// Limit position.
    pub p: [f64; 3],
    /// ∂p/∂u.
    pub du: [f64; 3],
    /// ∂p/∂v.
    pub dv: [f64; 3],
}

/// [`crate::eval_limit_grid_with`] in double precision throughout (OpenSubdiv's
/// `PrimvarRefinerReal<double>`, `SetPatchPrecision<double>` and `EvaluateBasis<double>`):
/// the same samples, in the same order.
pub fn eval_limit_grid_f64(
    mesh: &OsdMesh,
    samples_per_side: usize,
    o: &PatchOptions,
) -> Result<Vec<LimitSampleF64>> {
    let n = samples_per_side;
    if !(2..=4096).contains(&n) {
        return Err(Error::Invalid(format!(
            "samples per side {n} not in 2..=4096"
        )));
    }
    // Also rejects isolation levels above 10 before the double-precision build.
    let cap = patch_stats(mesh, o)?.num_ptex_faces * n * n;
    let desc = Desc::new(mesh)?;
    let raw_desc = desc.raw();
    let mut out = vec![LimitSampleF64::default(); cap];
    // SAFETY: `raw_desc` points into validated data alive for the call; `out` has room for
    // `cap` samples and `LimitSampleF64` is `repr(C)` with the layout of
    // `osd_limit_sample_f64`.
    let count = unsafe {
        ffi::osd_adaptive_eval_grid_f64(
            &raw_desc,
            o.isolation_level as i32,
            o.use_single_crease as i32,
            o.use_inf_sharp as i32,
            o.end_cap.raw(),
            n as i32,
            out.as_mut_ptr(),
            cap,
        )
    };
    if count < 0 {
        return Err(unavailable_or_osd());
    }
    out.truncate(count as usize);
    Ok(out)
}
