//! The patch map of triangular (Loop) faces: the same flat tree as [`PatchMap`], with the
//! four children of a triangle (OpenSubdiv's `Far::PatchMap` for triangles).
//!
//! Child `k` of a node is child face `k` of the refined triangle ([`super::loop_patches`]):
//! in the node's own `(s, t)` (`s + t ≤ 1`),
//!
//! ```text
//! child 0: s < ½, t < ½, s + t < ½   (s, t) → (2s, 2t)
//! child 1: s ≥ ½                      (s, t) → (2s − 1, 2t)
//! child 2: t ≥ ½                      (s, t) → (2s, 2t − 1)
//! child 3: the middle, turned by 180° (s, t) → (1 − 2s, 1 − 2t)
//! ```
//!
//! Each child's coordinates are its own, so the descent needs no orientation flag.

use super::patch_map::{PatchMap, EMPTY, LEAF};
use crate::real::Real;

impl PatchMap {
    /// The patch covering `(u, v)` of triangular base face `face` (`u, v ≥ 0`, `u + v ≤ 1`,
    /// clamped onto the triangle); `None` for a hole or an index out of range.
    pub fn find_triangle<R: Real>(&self, face: usize, u: R, v: R) -> Option<u32> {
        let mut h = *self.roots.get(face)?;
        let clamp = |x: R| if x < R::ZERO { R::ZERO } else { x };
        let (mut s, mut t) = (clamp(u), clamp(v));
        if s + t > R::ONE {
            let sum = s + t;
            s = s / sum;
            t = t / sum;
        }
        let (half, two) = (R::from_f64(0.5), R::from_f64(2.0));
        loop {
            if h == EMPTY {
                return None;
            }
            if h & LEAF != 0 {
                return Some(h & !LEAF);
            }
            let (k, ns, nt) = if s >= half {
                (1, two * s - R::ONE, two * t)
            } else if t >= half {
                (2, two * s, two * t - R::ONE)
            } else if s + t < half {
                (0, two * s, two * t)
            } else {
                (3, R::ONE - two * s, R::ONE - two * t)
            };
            s = ns;
            t = nt;
            h = self.nodes.get(h as usize)?[k];
        }
    }
}
