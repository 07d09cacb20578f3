//! Patch-level mathematics of limit-surface evaluation.
//!
//! A patch table (built elsewhere from a refined topology) stores, per patch, a list of
//! control-point indices, a packed [`PatchParam`] and, for single-crease patches, a
//! sharpness. This module evaluates one patch from its control points:
//!
//! | patch type | points | file |
//! |---|---|---|
//! | regular bicubic B-spline, with boundary/corner extrapolation | 16 | [`eval_bspline_patch`] |
//! | regular B-spline with one semi-sharp crease edge (Nießner, Loop & Greiner 2012) | 16 | [`eval_single_crease_patch`] |
//! | bicubic Bézier (used by the Gregory end cap) | 16 | [`eval_bezier_patch`] |
//! | 20-point Gregory basis end cap (Loop, Schaefer, Ni & Castaño 2009) | 20 | [`eval_gregory_patch`] |
//! | quartic box spline, the regular Loop triangle (Stam 1998), with boundary variants | 12 | [`eval_box_spline_patch`] |
//! | quartic Gregory triangle, the Loop end cap | 18 | [`eval_gregory_triangle`] |
//!
//! Triangular patches have their own parameterization and entry point ([`tri_patch_weights`]).
//!
//! # Conventions (OpenSubdiv 3.x `Far`)
//!
//! Patch parameters `(u, v)` run over `[0,1]²`. Corner `k` of the patch is corner `k` of the
//! refined face it stands for, counter-clockwise: corner 0 at `(0,0)`, 1 at `(1,0)`, 2 at
//! `(1,1)`, 3 at `(0,1)`. Edge `k` joins corner `k` and corner `k+1` ([`PatchEdge`]):
//!
//! ```text
//!   v
//!   1  3 ──── edge 2 (v=1) ──── 2
//!      │                        │
//!    edge 3 (u=0)          edge 1 (u=1)
//!      │                        │
//!   0  0 ──── edge 0 (v=0) ──── 1
//!      0                        1  u
//! ```
//!
//! A 16-point patch is a row-major 4×4 grid: point `(i, j)` (`i` along `u`, `j` along `v`)
//! has index `4*j + i`; the patch's own face is spanned by points 5, 6, 10, 9:
//!
//! ```text
//!   12 ── 13 ── 14 ── 15
//!    │     │     │     │
//!    8 ──  9 ── 10 ── 11
//!    │     │ face│     │
//!    4 ──  5 ──  6 ──  7
//!    │     │     │     │
//!    0 ──  1 ──  2 ──  3      (u → along a row, v ↑ across rows)
//! ```
//!
//! Bit `k` of a boundary mask (and of a transition mask) stands for edge `k`.
//!
//! [`patch_weights`] is the single entry point for a patch of any [`PatchKind`] at base-face
//! coordinates.
//!
//! Every basis function returns a [`PatchWeights`]: one weight per control point for the
//! position and for the first and second partial derivatives, in the patch's own `(u, v)`.
//! [`PatchParam::deriv_scale`] converts derivatives to the base face's parameterization.

pub(crate) mod basis;
pub(crate) mod bezier;
pub(crate) mod box_spline;
pub(crate) mod bspline;
pub(crate) mod gregory;
pub(crate) mod gregory_tri;
pub(crate) mod param;
pub(crate) mod single_crease;
pub(crate) mod tri_basis;
pub(crate) mod weights;

pub(crate) use crate::real::Real;
pub use basis::{
    patch_first_weights, patch_position_weights, patch_weights, patch_weights_normalized,
    AnyPatchWeights, PatchKind,
};
pub use bezier::{bezier_curve, bezier_patch_weights, eval_bezier_patch, BSPLINE_TO_BEZIER};
pub use box_spline::{
    box_spline_patch_weights, eval_box_spline_patch, BOX_SPLINE_COEFFS, BOX_SPLINE_MONOMIALS,
    BOX_SPLINE_ROTATE,
};
pub use bspline::{
    bspline_curve, bspline_patch_weights, eval_bspline_patch, BOUNDARY_U0, BOUNDARY_U1,
    BOUNDARY_V0, BOUNDARY_V1,
};
pub use gregory::{
    eval_gregory_patch, gregory_patch_weights, GregoryDerivatives, GREGORY_BOUNDARY,
    GREGORY_INTERIOR,
};
pub use gregory_tri::{bezier_triangle_weights, eval_gregory_triangle, gregory_triangle_weights};
pub use param::{PatchParam, PatchParamError, PatchParamFields, SharpnessTable, NO_SHARPNESS};
pub use single_crease::{crease_curve, eval_single_crease_patch, single_crease_patch_weights};
pub use tri_basis::{
    tri_patch_weights, tri_patch_weights_normalized, AnyTriPatchWeights, TriPatchKind,
};
pub use weights::{CurveWeights, PatchEval, PatchWeights};

/// An edge of a quad patch: edge `k` joins corner `k` and corner `k + 1` (see the module
/// documentation). The discriminant is the bit index used in boundary and transition masks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PatchEdge {
    /// Edge 0, `v = 0`, from corner 0 to corner 1.
    V0 = 0,
    /// Edge 1, `u = 1`, from corner 1 to corner 2.
    U1 = 1,
    /// Edge 2, `v = 1`, from corner 2 to corner 3.
    V1 = 2,
    /// Edge 3, `u = 0`, from corner 3 to corner 0.
    U0 = 3,
}

impl PatchEdge {
    /// All four edges in order.
    pub const ALL: [PatchEdge; 4] = [PatchEdge::V0, PatchEdge::U1, PatchEdge::V1, PatchEdge::U0];

    /// Edge `k` of the face (`k` in `0..4`), or `None` for any other value.
    pub fn from_index(k: u32) -> Option<PatchEdge> {
        Self::ALL.get(k as usize).copied()
    }

    /// The edge's index `k` in `0..4`.
    pub fn index(self) -> u32 {
        self as u32
    }

    /// The edge's bit in a boundary or transition mask, `1 << k`.
    pub fn mask(self) -> u8 {
        1 << (self as u8)
    }
}
