//! A quadtree per ptex face that finds the patch covering any `(ptex face, u, v)`
//! (OpenSubdiv `Far::PatchMap`).
//!
//! Node children follow the child faces of a quad: quadrant 0 is `u < ½, v < ½`, 1 is
//! `u ≥ ½, v < ½`, 2 is `u ≥ ½, v ≥ ½`, 3 is `u < ½, v ≥ ½`. A handle is [`EMPTY`] (a hole:
//! no surface), a leaf (bit 31 set, the patch index below it) or a node index. Flat arrays,
//! so a GPU kernel can walk the same tree.

use crate::real::Real;

/// `x` clamped to `[0, 1]` (NaN stays NaN, as `f32::clamp`).
#[inline]
pub(crate) fn clamp01<R: Real>(x: R) -> R {
    if x < R::ZERO {
        R::ZERO
    } else if x > R::ONE {
        R::ONE
    } else {
        x
    }
}

/// Handle of a region without patches (a hole).
pub const EMPTY: u32 = u32::MAX;
/// Bit marking a leaf handle.
pub const LEAF: u32 = 1 << 31;

/// Quadtrees of all ptex faces.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PatchMap {
    /// One handle per ptex face.
    pub roots: Vec<u32>,
    /// Four child handles per inner node.
    pub nodes: Vec<[u32; 4]>,
}

/// `(du, dv)` offset of quadrant `q`.
pub const QUADRANT: [(u32, u32); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

impl PatchMap {
    /// The patch covering `(u, v)` of ptex face `ptex`; `None` for a hole or an index out of
    /// range. `u` and `v` are clamped to `[0, 1]`.
    pub fn find<R: Real>(&self, ptex: usize, u: R, v: R) -> Option<u32> {
        let mut h = *self.roots.get(ptex)?;
        let (mut u, mut v) = (clamp01(u), clamp01(v));
        let (half, two) = (R::from_f64(0.5), R::from_f64(2.0));
        loop {
            if h == EMPTY {
                return None;
            }
            if h & LEAF != 0 {
                return Some(h & !LEAF);
            }
            let hi_u = u >= half;
            let hi_v = v >= half;
            let q = match (hi_u, hi_v) {
                (false, false) => 0,
                (true, false) => 1,
                (true, true) => 2,
                (false, true) => 3,
            };
            u = two * u - R::from_f64(hi_u as u32 as f64);
            v = two * v - R::from_f64(hi_v as u32 as f64);
            h = self.nodes.get(h as usize)?[q];
        }
    }

    /// Bytes of the two arrays.
    pub fn size_bytes(&self) -> usize {
        4 * self.roots.len() + 16 * self.nodes.len()
    }
}
