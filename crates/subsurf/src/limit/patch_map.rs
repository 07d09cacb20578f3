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
    pub(crate) roots: Vec<u32>,
    /// Four child handles per inner node.
    pub(crate) nodes: Vec<[u32; 4]>,
}

impl PatchMap {
    /// One handle per ptex face.
    #[inline]
    pub fn roots(&self) -> &[u32] {
        &self.roots
    }

    /// Four child handles per inner node.
    #[inline]
    pub fn nodes(&self) -> &[[u32; 4]] {
        &self.nodes
    }
}

/// A leaf of a ptex face's quadtree and its square: `[iu, iu + 1) × [iv, iv + 1)` scaled by
/// `2^-level` (closed at `u, v = 1`), the `(u, v)` that [`PatchMap::find`] sends to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cell {
    /// The patch.
    pub patch: u32,
    /// The ptex face.
    pub ptex: u32,
    /// Depth of the leaf in the tree.
    pub level: u32,
    /// Column of the square at that depth.
    pub iu: u32,
    /// Row of the square at that depth.
    pub iv: u32,
}

impl Cell {
    /// Whether [`PatchMap::find`] sends `(u, v)` of ptex face `ptex` here (after clamping).
    #[inline]
    pub fn contains<R: Real>(&self, ptex: usize, u: R, v: R) -> bool {
        self.local(ptex, clamp01(u), clamp01(v)).is_some()
    }

    /// `(u, v)` (in `[0, 1]`) in the square's own coordinates, `u 2^level − iu` and
    /// `v 2^level − iv`, when [`PatchMap::find`] sends it here; `None` otherwise. The walk
    /// compares `u` with dyadic fractions (its doublings and subtractions are exact), so it
    /// ends in the square with `iu ≤ u 2^level < iu + 1`, or the last one at `u = 1`; the
    /// local coordinate is exact in that range and rounds monotonically outside it, so the
    /// comparisons below decide the same.
    #[inline]
    pub fn local<R: Real>(&self, ptex: usize, u: R, v: R) -> Option<(R, R)> {
        if ptex != self.ptex as usize {
            return None;
        }
        let scale = R::pow2(self.level as i32);
        let at = |i: u32| R::from_f64(f64::from(i));
        Some((
            square_local(u, scale, at(self.iu))?,
            square_local(v, scale, at(self.iv))?,
        ))
    }
}

/// `x` (in `[0, 1]`) in the coordinate of the squares of side `1 / scale` whose `i`-th it
/// falls in, as [`PatchMap::find`] assigns it ([`Cell::local`]); `None` outside that square.
#[inline(always)]
pub(crate) fn square_local<R: Real>(x: R, scale: R, i: R) -> Option<R> {
    let a = x * scale - i;
    (a >= R::ZERO && (a < R::ONE || (a == R::ONE && x == R::ONE))).then_some(a)
}

/// `(du, dv)` offset of quadrant `q`.
pub const QUADRANT: [(u32, u32); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];

impl PatchMap {
    /// Number of ptex faces.
    #[inline]
    pub fn num_ptex(&self) -> usize {
        self.roots.len()
    }

    /// Whether ptex face `ptex` has patches (is in range and not a hole).
    #[inline]
    pub fn has_patches(&self, ptex: usize) -> bool {
        self.roots.get(ptex).is_some_and(|&h| h != EMPTY)
    }

    /// The patch covering `(u, v)` of ptex face `ptex`; `None` for a hole or an index out of
    /// range. `u` and `v` are clamped to `[0, 1]`.
    pub fn find<R: Real>(&self, ptex: usize, u: R, v: R) -> Option<u32> {
        self.find_cell(ptex, u, v).map(|c| c.patch)
    }

    /// [`PatchMap::find`] with the leaf's square, so that nearby queries can test
    /// `Cell::contains` instead of walking the tree again.
    pub fn find_cell<R: Real>(&self, ptex: usize, u: R, v: R) -> Option<Cell> {
        let mut h = *self.roots.get(ptex)?;
        let (mut u, mut v) = (clamp01(u), clamp01(v));
        let (half, two) = (R::from_f64(0.5), R::from_f64(2.0));
        let mut cell = Cell {
            patch: 0,
            ptex: ptex as u32,
            level: 0,
            iu: 0,
            iv: 0,
        };
        loop {
            if h == EMPTY {
                return None;
            }
            if h & LEAF != 0 {
                cell.patch = h & !LEAF;
                return Some(cell);
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
            cell.level += 1;
            cell.iu = 2 * cell.iu + hi_u as u32;
            cell.iv = 2 * cell.iv + hi_v as u32;
            h = self.nodes.get(h as usize)?[q];
        }
    }

    /// Bytes of the two arrays.
    pub fn size_bytes(&self) -> usize {
        4 * self.roots.len() + 16 * self.nodes.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quadtree descends by quadrant: 0 (low u, low v), 1 (high u), 2 (both), 3 (high v).
    #[test]
    fn patch_map_quadrants() {
        let map = PatchMap {
            roots: vec![0, LEAF | 7, EMPTY],
            nodes: vec![
                [LEAF, LEAF | 1, 1, EMPTY],
                [LEAF | 2, LEAF | 3, LEAF | 4, LEAF | 5],
            ],
        };
        assert_eq!(map.find(0, 0.1, 0.2), Some(0));
        assert_eq!(map.find(0, 0.6, 0.2), Some(1));
        assert_eq!(map.find(0, 0.1, 0.9), None);
        assert_eq!(map.find(0, 0.6, 0.6), Some(2));
        assert_eq!(map.find(0, 0.8, 0.6), Some(3));
        assert_eq!(map.find(0, 0.8, 0.8), Some(4));
        assert_eq!(map.find(0, 0.6, 0.9), Some(5));
        assert_eq!(map.find(1, 0.3, 0.3), Some(7));
        assert_eq!(map.find(2, 0.3, 0.3), None);
        assert_eq!(map.find(3, 0.3, 0.3), None);
    }
    use crate::limit::{PatchOptions, PatchTable};

    /// On a grid of every ptex face of an isolated pole (with a hole), including the
    /// squares' edges and `u, v = 1`, a point lies in a found cell exactly when `find` sends
    /// it to that cell.
    #[test]
    fn cells_contain_what_find_sends_them() {
        let mut mesh = crate::shapes::pole(5);
        mesh.holes.push(1);
        let t = crate::Topology::new(&mesh).unwrap();
        let table = PatchTable::build(&t, &PatchOptions::default()).unwrap();
        let map = &table.patch_map;
        let n = 32;
        let mut deepest = 0;
        for ptex in 0..map.roots.len() {
            let points: Vec<(f32, f32)> = (0..=n)
                .flat_map(|i| (0..=n).map(move |j| (i as f32 / n as f32, j as f32 / n as f32)))
                .collect();
            let cells: Vec<Option<Cell>> = points
                .iter()
                .map(|&(u, v)| map.find_cell(ptex, u, v))
                .collect();
            let mut distinct: Vec<Cell> = cells.iter().flatten().copied().collect();
            distinct.sort_by_key(|c| (c.level, c.iu, c.iv));
            distinct.dedup();
            for c in &distinct {
                deepest = deepest.max(c.level);
                for (&(u, v), found) in points.iter().zip(&cells) {
                    assert_eq!(
                        c.contains(ptex, u, v),
                        *found == Some(*c),
                        "{c:?} ({u}, {v})"
                    );
                }
                assert!(!c.contains(ptex + 1, 0.5, 0.5) || c.ptex as usize == ptex + 1);
            }
            for (&(u, v), found) in points.iter().zip(&cells) {
                assert_eq!(found.map(|c| c.patch), map.find(ptex, u, v));
            }
        }
        assert!(deepest >= 3, "{deepest}");
    }
}
