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

use super::loop_patches::LoopLeaf;
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

    /// The map of `num_faces` triangular base faces over `leaves` (patch `i` is leaf `i`;
    /// child `k` of a level face `f` is face `4 f + k` of the next level).
    pub fn of_triangles(num_faces: usize, leaves: &[LoopLeaf]) -> PatchMap {
        let mut map = PatchMap {
            roots: vec![EMPTY; num_faces],
            nodes: Vec::new(),
        };
        for (i, leaf) in leaves.iter().enumerate() {
            // The child index at each depth, from the top.
            let mut path = Vec::with_capacity(leaf.depth);
            let mut f = leaf.face as usize;
            for _ in 0..leaf.depth {
                path.push(f & 3);
                f >>= 2;
            }
            let mut handle = map.roots[leaf.base_face as usize];
            let mut parent: Option<(usize, usize)> = None;
            for &k in path.iter().rev() {
                if handle == EMPTY {
                    let n = map.nodes.len() as u32;
                    map.nodes.push([EMPTY; 4]);
                    match parent {
                        None => map.roots[leaf.base_face as usize] = n,
                        Some((p, j)) => map.nodes[p][j] = n,
                    }
                    handle = n;
                }
                parent = Some((handle as usize, k));
                handle = map.nodes[handle as usize][k];
            }
            let h = LEAF | i as u32;
            match parent {
                None => map.roots[leaf.base_face as usize] = h,
                Some((p, j)) => map.nodes[p][j] = h,
            }
        }
        map
    }
}
