//! Packed per-patch parameterization, bit for bit OpenSubdiv 3.x's `Far::PatchParam`.
//!
//! Refinement splits a base face into a quadtree of sub-faces; a patch stands for one of
//! them. Its parameter records which base face, where in the face's `[0,1]²` the patch sits
//! and how deep, plus the flags an evaluator needs. Two `u32` words, `#[repr(C)]`, so a GPU
//! kernel reads the same layout (keep in sync with the shaders' copy of this struct).
//!
//! ```text
//! field0   bits   content
//!          0..28  face id      base (ptex) face the patch belongs to            (28 bits)
//!         28..32  transition   edges shared with a patch one level deeper       (4 bits)
//!
//! field1   bits   content
//!          0..4   depth        refinement level of the patch                    (4 bits)
//!          4      non-quad     the base face is not a quad                      (1 bit)
//!          5      regular      the patch is a regular B-spline patch            (1 bit)
//!          6      unused                                                        (1 bit)
//!          7..12  boundary     boundary edges (single-crease patches: the crease edge) (5 bits)
//!         12..22  v            v index of the patch origin at its level         (10 bits)
//!         22..32  u            u index of the patch origin at its level         (10 bits)
//! ```
//!
//! Masks use one bit per [`super::PatchEdge`] (`1 << k` for edge `k`).
//!
//! # Parameterization
//!
//! A quad base face's patches at depth `d` tile `[0,1]²` in squares of side `2^-d`. A base
//! face with `n ≠ 4` corners is split into `n` quads by the first refinement; each of them
//! is its own ptex face (with its own face id), so the side is `2^-(d-1)` there — the
//! *parameter fraction* `φ = 2^-(d - nonquad)`. With the origin `(U, V)`:
//!
//! ```text
//! normalize:    (u, v)_patch = (u / φ − U, v / φ − V)
//! unnormalize:  (u, v)_face  = ((u + U) φ, (v + V) φ)
//! ```
//!
//! By the chain rule, derivatives with respect to the face's `(u, v)` are the patch's
//! derivatives times `1/φ` (second derivatives `1/φ²`): [`PatchParam::deriv_scale`].
//! OpenSubdiv's `EvaluatePatchBasis` scales by `2^depth`, which is the same for patches of
//! quad faces and twice as large for patches of non-quad faces.

use thiserror::Error;

/// A packed patch parameter (see the module documentation for the bit layout).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PatchParam {
    /// Face id (bits 0..28) and transition mask (bits 28..32).
    pub field0: u32,
    /// Depth, flags, boundary mask and `(u, v)` origin.
    pub field1: u32,
}

/// The unpacked fields of a [`PatchParam`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct PatchParamFields {
    /// Base (ptex) face id, `< 2^28`.
    pub face_id: u32,
    /// `u` index of the patch origin at its level, `< 2^(depth − non_quad_root)` and `< 1024`.
    pub u: u16,
    /// `v` index of the patch origin at its level, same range as `u`.
    pub v: u16,
    /// Refinement level, `0..=15`; at least 1 for a non-quad root.
    pub depth: u8,
    /// The base face is not a quad.
    pub non_quad_root: bool,
    /// Boundary mask, 5 bits (quads use bits 0..4, one per edge).
    pub boundary: u8,
    /// Transition mask, 4 bits, one per edge.
    pub transition: u8,
    /// The patch is a regular B-spline patch.
    pub regular: bool,
}

/// A field value that does not fit its bits.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum PatchParamError {
    /// A field exceeds its range.
    #[error("patch parameter field `{field}` = {value} is out of range (maximum {max})")]
    OutOfRange {
        /// Field name.
        field: &'static str,
        /// The value given.
        value: u64,
        /// The largest value allowed.
        max: u64,
    },
    /// A patch of a non-quad base face must be at depth 1 or deeper.
    #[error("a patch of a non-quad base face must have depth >= 1")]
    NonQuadDepthZero,
}

impl From<PatchParamError> for crate::Error {
    fn from(e: PatchParamError) -> Self {
        crate::Error::Unsupported(e.to_string())
    }
}

const FACE_BITS: u32 = 28;
const UV_BITS: u32 = 10;

#[inline]
fn unpack(x: u32, width: u32, offset: u32) -> u32 {
    (x >> offset) & ((1u32 << width) - 1)
}

impl PatchParam {
    /// Packs the fields, checking every range.
    pub fn new(f: PatchParamFields) -> Result<Self, PatchParamError> {
        let check = |field: &'static str, value: u64, max: u64| {
            if value > max {
                Err(PatchParamError::OutOfRange { field, value, max })
            } else {
                Ok(())
            }
        };
        check("face_id", f.face_id as u64, (1 << FACE_BITS) - 1)?;
        check("depth", f.depth as u64, 15)?;
        if f.non_quad_root && f.depth == 0 {
            return Err(PatchParamError::NonQuadDepthZero);
        }
        let level = f.depth as u32 - f.non_quad_root as u32;
        let uv_max = ((1u64 << level) - 1).min((1 << UV_BITS) - 1);
        check("u", f.u as u64, uv_max)?;
        check("v", f.v as u64, uv_max)?;
        check("boundary", f.boundary as u64, 31)?;
        check("transition", f.transition as u64, 15)?;
        Ok(Self::pack_unchecked(f))
    }

    fn pack_unchecked(f: PatchParamFields) -> Self {
        let field0 = f.face_id | ((f.transition as u32) << 28);
        let field1 = ((f.u as u32) << 22)
            | ((f.v as u32) << 12)
            | ((f.boundary as u32) << 7)
            | ((f.regular as u32) << 5)
            | ((f.non_quad_root as u32) << 4)
            | f.depth as u32;
        PatchParam { field0, field1 }
    }

    /// All fields.
    pub fn fields(&self) -> PatchParamFields {
        PatchParamFields {
            face_id: self.face_id(),
            u: self.u(),
            v: self.v(),
            depth: self.depth(),
            non_quad_root: self.non_quad_root(),
            boundary: self.boundary(),
            transition: self.transition(),
            regular: self.is_regular(),
        }
    }

    /// Base (ptex) face id.
    pub fn face_id(&self) -> u32 {
        unpack(self.field0, FACE_BITS, 0)
    }
    /// Transition mask (4 bits).
    pub fn transition(&self) -> u8 {
        unpack(self.field0, 4, 28) as u8
    }
    /// `u` index of the origin at the patch's level.
    pub fn u(&self) -> u16 {
        unpack(self.field1, UV_BITS, 22) as u16
    }
    /// `v` index of the origin at the patch's level.
    pub fn v(&self) -> u16 {
        unpack(self.field1, UV_BITS, 12) as u16
    }
    /// Boundary mask (5 bits). For a single-crease patch: the crease edge's bit.
    pub fn boundary(&self) -> u8 {
        unpack(self.field1, 5, 7) as u8
    }
    /// Whether the patch is a regular B-spline patch.
    pub fn is_regular(&self) -> bool {
        unpack(self.field1, 1, 5) != 0
    }
    /// Whether the base face is not a quad.
    pub fn non_quad_root(&self) -> bool {
        unpack(self.field1, 1, 4) != 0
    }
    /// Refinement level.
    pub fn depth(&self) -> u8 {
        unpack(self.field1, 4, 0) as u8
    }

    /// Level of the quadtree that holds the patch within its ptex face:
    /// `depth − non_quad_root`, never negative.
    fn ptex_level(&self) -> i32 {
        (self.depth() as i32 - self.non_quad_root() as i32).max(0)
    }

    /// The patch's square in its ptex face's quadtree: `(level, u, v)`, the square
    /// `[u, u + 1] × [v, v + 1]` scaled by `2^-level` (what [`Self::normalize`] maps to
    /// `[0, 1]²`).
    pub fn square(&self) -> (u32, u32, u32) {
        (self.ptex_level() as u32, self.u() as u32, self.v() as u32)
    }

    /// Side length `φ = 2^-(depth − nonquad)` of the patch's square in its ptex face.
    pub fn param_fraction(&self) -> f32 {
        1.0 / (1u32 << self.ptex_level()) as f32
    }

    /// Maps a ptex-face `(u, v)` to the patch's own `[0,1]²` (values outside the patch map
    /// outside `[0,1]²`; no clamping).
    pub fn normalize<T: super::Real>(&self, u: T, v: T) -> (T, T) {
        let inv = T::pow2(self.ptex_level());
        (
            u * inv - T::from_f64(self.u() as f64),
            v * inv - T::from_f64(self.v() as f64),
        )
    }

    /// Maps the patch's own `(u, v)` back to its ptex face.
    pub fn unnormalize<T: super::Real>(&self, u: T, v: T) -> (T, T) {
        let frac = T::pow2(-self.ptex_level());
        (
            (u + T::from_f64(self.u() as f64)) * frac,
            (v + T::from_f64(self.v() as f64)) * frac,
        )
    }

    /// Factor turning patch derivatives into ptex-face derivatives: `1/φ` for first
    /// derivatives (square it for second derivatives).
    pub fn deriv_scale<T: super::Real>(&self) -> T {
        T::pow2(self.ptex_level())
    }

    /// Whether the ptex-face point `(u, v)` lies in this patch's closed square.
    pub fn contains<T: super::Real>(&self, u: T, v: T) -> bool {
        let (s, t) = self.normalize(u, v);
        s >= T::ZERO && s <= T::ONE && t >= T::ZERO && t <= T::ONE
    }
}

/// Per-patch sharpness, kept apart from [`PatchParam`] like OpenSubdiv's sharpness index
/// table: `indices[patch]` is [`NO_SHARPNESS`] or an index into `values`, where equal
/// sharpness values are stored once.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SharpnessTable {
    /// One entry per patch: an index into `values`, or [`NO_SHARPNESS`].
    pub indices: Vec<u32>,
    /// Distinct sharpness values.
    pub values: Vec<f32>,
}

/// The index of a patch without a crease.
pub const NO_SHARPNESS: u32 = u32::MAX;

impl SharpnessTable {
    /// Appends the next patch's sharpness (`None`, zero, negative or NaN: no crease) and
    /// returns its index.
    pub fn push(&mut self, sharpness: Option<f32>) -> u32 {
        let idx = match sharpness {
            Some(s) if s > 0.0 => match self.values.iter().position(|&x| x == s) {
                Some(i) => i as u32,
                None => {
                    self.values.push(s);
                    (self.values.len() - 1) as u32
                }
            },
            _ => NO_SHARPNESS,
        };
        self.indices.push(idx);
        idx
    }

    /// Sharpness of `patch`: `None` for a patch without a crease or out of range.
    pub fn get(&self, patch: usize) -> Option<f32> {
        let i = *self.indices.get(patch)?;
        self.values.get(i as usize).copied()
    }

    /// Number of patches recorded.
    pub fn len(&self) -> usize {
        self.indices.len()
    }

    /// Whether no patch is recorded.
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_is_two_words() {
        assert_eq!(std::mem::size_of::<PatchParam>(), 8);
        let p = PatchParam {
            field0: 7,
            field1: 9,
        };
        assert_eq!(bytemuck::cast::<PatchParam, [u32; 2]>(p), [7, 9]);
    }

    #[test]
    fn known_bit_positions() {
        let p = PatchParam::new(PatchParamFields {
            face_id: 5,
            u: 3,
            v: 1,
            depth: 2,
            non_quad_root: false,
            boundary: 0b1001,
            transition: 0b0110,
            regular: true,
        })
        .unwrap();
        assert_eq!(p.field0, 5 | (0b0110 << 28));
        assert_eq!(
            p.field1,
            (3 << 22) | (1 << 12) | (0b1001 << 7) | (1 << 5) | 2
        );
    }

    #[test]
    fn rejects_out_of_range() {
        let ok = PatchParamFields {
            depth: 3,
            ..Default::default()
        };
        assert!(PatchParam::new(ok).is_ok());
        for bad in [
            PatchParamFields {
                face_id: 1 << 28,
                ..ok
            },
            PatchParamFields { u: 8, ..ok },
            PatchParamFields { v: 8, ..ok },
            PatchParamFields { depth: 16, ..ok },
            PatchParamFields { boundary: 32, ..ok },
            PatchParamFields {
                transition: 16,
                ..ok
            },
            PatchParamFields {
                depth: 0,
                non_quad_root: true,
                ..ok
            },
            PatchParamFields {
                u: 4,
                non_quad_root: true,
                ..ok
            },
        ] {
            assert!(PatchParam::new(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn sharpness_table_shares_values() {
        let mut t = SharpnessTable::default();
        assert_eq!(t.push(Some(2.5)), 0);
        assert_eq!(t.push(None), NO_SHARPNESS);
        assert_eq!(t.push(Some(1.0)), 1);
        assert_eq!(t.push(Some(2.5)), 0);
        assert_eq!(t.push(Some(0.0)), NO_SHARPNESS);
        assert_eq!(t.push(Some(f32::NAN)), NO_SHARPNESS);
        assert_eq!(t.values, vec![2.5, 1.0]);
        assert_eq!(t.get(3), Some(2.5));
        assert_eq!(t.get(1), None);
        assert_eq!(t.get(99), None);
        assert_eq!(t.len(), 6);
    }
}
