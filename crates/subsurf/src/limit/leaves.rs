//! The patch of every leaf face of one level: the faces the quadtree walk reaches and does
//! not refine further. They are computed level by level, while the level is being built and
//! its tables are still in cache, and the walk of [`super::table`] then only places them in
//! quadtree order.
//!
//! A leaf becomes:
//! - a regular bicubic B-spline patch when [`is_patch_regular`]: its 16 points
//!   ([`super::gather::regular_points`]) and boundary mask ([`boundary_mask`]);
//! - a single-crease patch when, in addition, it is interior and [`single_crease`]: the
//!   crease edge `k` as the boundary bit `1 << k`, and the level's sharpness (with
//!   `cap_crease_sharpness`, OpenSubdiv's `min(s, L − d)`, and none at level `L`);
//! - a Gregory end cap otherwise: its 20 points as stencils over the level vertices
//!   ([`gregory_points`]).
//!
//! Every point a patch reads is checked to be exact ([`super::sparse`]).

use super::endcap::gregory_points;
use super::features::{boundary_mask, is_patch_regular, single_crease};
use super::patch_map::{EMPTY, LEAF};
use super::sparse::Level;
use super::table::PatchType;
use crate::error::{Error, Result};
use crate::real::Real;
use rayon::prelude::*;

/// How leaves become patches.
#[derive(Debug, Clone, Copy)]
pub struct LeafOptions {
    /// Single-crease patches are made.
    pub single_crease: bool,
    /// Crease sharpness is capped at `L − d` (and level `L` makes none).
    pub cap: bool,
    /// The isolation level `L`.
    pub max_level: usize,
}

impl LeafOptions {
    /// The leaves of a table built with `options` to isolation level `max_level`.
    pub fn new(options: &super::table::PatchOptions, max_level: usize) -> LeafOptions {
        LeafOptions {
            single_crease: options.single_crease,
            cap: options.cap_crease_sharpness,
            max_level,
        }
    }
}

/// The patch of one leaf.
#[derive(Debug, Clone, Copy)]
pub struct Leaf {
    /// Its basis.
    pub kind: PatchType,
    /// Boundary mask, or the crease edge's bit of a single-crease patch.
    pub boundary: u8,
    /// Regular (B-spline or single-crease) patch.
    pub regular: bool,
    /// Crease sharpness (0 unless single-crease).
    pub sharpness: f32,
    /// First of its 16 points in [`Part::cvs`] (regular) or its 20 rows in
    /// [`Part::local_offsets`] (end cap).
    pub first: u32,
}

/// The patches of the leaves of one level.
#[derive(Debug, Clone, Default)]
pub struct LevelPatches<W = f32> {
    /// Per face of the level, what the walk finds there: `LEAF | leaf` for a leaf, its first
    /// child face for a refined face, [`EMPTY`] for a hole and [`UNWALKED`] for a face the
    /// walk does not reach (one array, so that the walk reads one word per face and level).
    pub slot: Vec<u32>,
    /// The leaves in chunks of 512 (the last one shorter), as they were computed.
    pub parts: Vec<Part<W>>,
}

impl<W> LevelPatches<W> {
    /// Leaf `i` and the part holding its points.
    pub fn leaf(&self, i: u32) -> (&Part<W>, &Leaf) {
        let p = &self.parts[i as usize / CHUNK];
        (p, &p.leaves[i as usize % CHUNK])
    }
}

/// The points of a leaf made before, given to [`LevelPatches::push`].
#[derive(Debug, Clone, Copy)]
pub enum LeafPoints<'a, W> {
    /// A regular leaf's 16 flat point indices.
    Regular(&'a [u32]),
    /// An end cap's 20 rows: their 21 offsets into `indices` and `weights`.
    EndCap {
        /// The offsets.
        offsets: &'a [u32],
        /// Flat point index of each row entry.
        indices: &'a [u32],
        /// Weight of each row entry.
        weights: &'a [W],
    },
}

impl<W: Copy + Default> LevelPatches<W> {
    /// Appends a leaf made before (the leaves of the levels a crease edit keeps,
    /// [`super::edit_rebuild`]) as the next leaf of the level, in the chunks a construction
    /// makes; `leaf.first` is set here.
    pub fn push(&mut self, mut leaf: Leaf, points: LeafPoints<'_, W>) {
        if self.parts.last().is_none_or(|p| p.leaves.len() == CHUNK) {
            self.parts.push(Part {
                local_offsets: vec![0],
                ..Default::default()
            });
        }
        let last = self.parts.len() - 1;
        let part = &mut self.parts[last];
        match points {
            LeafPoints::Regular(cvs) => {
                leaf.first = part.cvs.len() as u32;
                part.cvs.extend_from_slice(cvs);
            }
            LeafPoints::EndCap {
                offsets,
                indices,
                weights,
            } => {
                leaf.first = (part.local_offsets.len() - 1) as u32;
                let (a, z) = (offsets[0] as usize, offsets[offsets.len() - 1] as usize);
                let to = part.local_indices.len() as u32;
                part.local_indices.extend_from_slice(&indices[a..z]);
                part.local_weights.extend_from_slice(&weights[a..z]);
                (part.local_offsets).extend(offsets[1..].iter().map(|&o| o - offsets[0] + to));
            }
        }
        part.leaves.push(leaf);
    }
}

/// The patches of a chunk of leaves.
#[derive(Debug, Clone, Default)]
pub struct Part<W = f32> {
    /// The leaves.
    pub leaves: Vec<Leaf>,
    /// 16 flat point indices per regular leaf.
    pub cvs: Vec<u32>,
    /// End-cap rows: `rows + 1` offsets into `local_indices` / `local_weights`.
    pub local_offsets: Vec<u32>,
    /// Flat point index of each end-cap row entry.
    pub local_indices: Vec<u32>,
    /// Weight of each end-cap row entry.
    pub local_weights: Vec<W>,
}

/// [`LevelPatches::slot`] of a face the walk does not reach (above every child index, which
/// [`super::sparse`] keeps below `2^31 − 1`).
pub const UNWALKED: u32 = LEAF - 1;

fn not_exact(what: &str, d: usize, f: usize) -> Error {
    Error::Internal(format!(
        "sparse refinement: {what} of face {f} at level {d} is not exact"
    ))
}

/// Leaves per parallel task and per [`Part`].
const CHUNK: usize = 512;

/// The patches of the leaf faces `faces` of level `d` (`lv`), whose vertices start at `off`
/// in the flat point array; chunks of faces in parallel, joined in order.
pub fn level_patches<W: Real>(
    lv: &Level,
    d: usize,
    off: u32,
    faces: &[u32],
    o: &LeafOptions,
) -> Result<LevelPatches<W>> {
    let t = &lv.topo;
    let slot = || -> Vec<u32> {
        (0..t.num_faces())
            .map(|f| {
                if t.face_is_hole[f] {
                    EMPTY
                } else if lv.refine[f] {
                    lv.child[f]
                } else {
                    UNWALKED
                }
            })
            .collect()
    };
    let (mut slot, parts) = rayon::join(slot, || {
        faces
            .par_chunks(CHUNK)
            .map(|c| chunk_patches(lv, d, off, c, o))
            .collect::<Result<Vec<Part<W>>>>()
    });
    for (i, &f) in faces.iter().enumerate() {
        slot[f as usize] = LEAF | i as u32;
    }
    Ok(LevelPatches {
        slot,
        parts: parts?,
    })
}

/// The patches of a chunk of leaf faces.
fn chunk_patches<W: Real>(
    lv: &Level,
    d: usize,
    off: u32,
    faces: &[u32],
    o: &LeafOptions,
) -> Result<Part<W>> {
    let (t, tags) = (&lv.topo, &lv.tags);
    let mut out = Part {
        leaves: Vec::with_capacity(faces.len()),
        cvs: Vec::with_capacity(16 * faces.len()),
        local_offsets: vec![0],
        ..Default::default()
    };
    for &f in faces {
        let f = f as usize;
        if t.face_vertices(f).iter().any(|&c| !lv.sound[c as usize]) {
            return Err(not_exact("a corner", d, f));
        }
        let local = LeafOptions {
            max_level: lv.level_of(f, o.max_level),
            ..*o
        };
        let (kind, boundary, regular, sharpness) = leaf_kind(t, tags, f, d, &local);
        let leaf = if regular {
            let pts = regular_points_checked(lv, d, f)?;
            let first = out.cvs.len() as u32;
            out.cvs.extend(pts.iter().map(|&p| off + p));
            Leaf {
                kind,
                boundary,
                regular,
                sharpness,
                first,
            }
        } else {
            if t.face_size(f) != 4 {
                return Err(Error::Internal(format!(
                    "irregular non-quad face {f} at level {d} cannot take an end cap"
                )));
            }
            let first = (out.local_offsets.len() - 1) as u32;
            for row in gregory_points(t, f) {
                for (x, w) in row {
                    if !lv.exact[x as usize] {
                        return Err(not_exact("an end-cap input", d, f));
                    }
                    out.local_indices.push(x + off);
                    out.local_weights.push(W::from_f64(w));
                }
                out.local_offsets.push(out.local_indices.len() as u32);
            }
            Leaf {
                kind: PatchType::Gregory,
                boundary: 0,
                regular,
                sharpness: 0.0,
                first,
            }
        };
        out.leaves.push(leaf);
    }
    Ok(out)
}

/// The basis of the patch of leaf face `f` of level `d`: its type, boundary mask (or crease
/// edge bit), whether it is regular, and its crease sharpness.
pub fn leaf_kind(
    t: &crate::topology::Topology,
    tags: &[super::features::VTag],
    f: usize,
    d: usize,
    o: &LeafOptions,
) -> (PatchType, u8, bool, f32) {
    if !is_patch_regular(t, tags, f) {
        return (PatchType::Gregory, 0, false, 0.0);
    }
    let bmask = boundary_mask(t, f);
    let crease = if o.single_crease && bmask == 0 && (d < o.max_level || !o.cap) {
        single_crease(t, tags, f)
    } else {
        None
    };
    match crease {
        Some((k, s)) => (
            PatchType::SingleCrease,
            1u8 << k,
            true,
            if o.cap {
                s.min((o.max_level - d) as f32)
            } else {
                s
            },
        ),
        None => (PatchType::Regular, bmask, true, 0.0),
    }
}

/// [`super::gather::regular_points`] of face `f`, each checked to be exact.
fn regular_points_checked(lv: &Level, d: usize, f: usize) -> Result<[u32; 16]> {
    let pts = super::gather::regular_points(&lv.topo, f);
    if pts.iter().any(|&p| !lv.exact[p as usize]) {
        return Err(not_exact("a control point", d, f));
    }
    Ok(pts)
}
