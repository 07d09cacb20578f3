//! OpenSubdiv's patch basis functions (`Far::internal::EvaluatePatchBasis`) for one patch
//! type at one `(u, v)`, with the packed `PatchParam` words given directly.

use std::os::raw::c_int;

use crate::{Error, Result};

/// Patch types of [`patch_basis`] (`Far::PatchDescriptor::Type`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OsdPatchType {
    /// `REGULAR`: bicubic B-spline, 16 points.
    Regular,
    /// `LOOP`: quartic box spline, 12 points.
    Loop,
    /// `GREGORY_BASIS`: 20 points.
    GregoryBasis,
    /// `GREGORY_TRIANGLE`: 18 points.
    GregoryTriangle,
}

/// Basis weights: `n` points, each array holds 20 entries of which the first `n` are used.
#[derive(Debug, Clone, PartialEq)]
pub struct OsdBasis {
    /// Number of points of the patch type.
    pub n: usize,
    /// Position, ∂/∂u, ∂/∂v, ∂²/∂u², ∂²/∂u∂v, ∂²/∂v² weights.
    pub w: [[f64; 20]; 6],
}

#[cfg(not(osd_missing))]
extern "C" {
    fn osd_patch_basis(ty: c_int, field0: u32, field1: u32, u: f64, v: f64, out: *mut f64)
        -> c_int;
}

#[cfg(osd_missing)]
unsafe fn osd_patch_basis(_: c_int, _: u32, _: u32, _: f64, _: f64, _: *mut f64) -> c_int {
    -2
}

/// `EvaluatePatchBasis<double>` of a patch of type `ty` with `PatchParam` words
/// `(field0, field1)` at the base-face `(u, v)`: normalizes with the param (the triangle
/// normalization for triangular types), evaluates, applies the boundary mask and scales
/// the derivatives to the base face.
pub fn patch_basis(ty: OsdPatchType, field0: u32, field1: u32, u: f64, v: f64) -> Result<OsdBasis> {
    let code = match ty {
        OsdPatchType::Regular => 0,
        OsdPatchType::Loop => 1,
        OsdPatchType::GregoryBasis => 2,
        OsdPatchType::GregoryTriangle => 3,
    };
    let mut out = [0.0f64; 120];
    // SAFETY: `out` has the 6 × 20 slots the shim writes.
    let n = unsafe { osd_patch_basis(code, field0, field1, u, v, out.as_mut_ptr()) };
    match n {
        -2 => return Err(Error::Unavailable),
        n if n < 0 => return Err(Error::Osd(format!("patch type {ty:?} rejected"))),
        _ => {}
    }
    let mut w = [[0.0; 20]; 6];
    for (k, row) in w.iter_mut().enumerate() {
        row.copy_from_slice(&out[20 * k..20 * k + 20]);
    }
    Ok(OsdBasis { n: n as usize, w })
}
