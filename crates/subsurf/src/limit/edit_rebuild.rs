//! Crease edits that change the isolation structure: the levels above the change kept, the
//! construction resumed at it.
//!
//! The walk of [`super::edit_region`] goes down the kept levels from the base and has every
//! level's faces decided again. Where the first level whose decisions differ is `d > 0`
//! (a face refined that should be a leaf, a leaf that should be refined, a patch that
//! changes between B-spline and end cap), the levels `0..=d` keep their topology: only the
//! decisions at level `d` and everything below change. Those levels already carry the edit's
//! values (the walk wrote their sharpness, tags and rules), the steps between them have their
//! re-formed stencil rows and their leaves their new types, so the construction resumes at
//! level `d` ([`super::sparse::resume`]): the faces of level `d` are decided, the levels below
//! refined and their leaves made as a fresh build makes them, and every base face's quadtree
//! walked again to place the patches (`PatchTable::assemble`). The leaves of the kept levels
//! are taken from the table (their points unchanged, their types as the edit decided).
//!
//! The table is a fresh build's, bit for bit, as is every level kept for the next edit
//! (`tests/limit_edit.rs`). The saving is the construction of the kept levels: the sparser
//! levels near the base, so it grows with `d` (a crease moved across sharpness `k` changes
//! the decisions at level `k` or so).

use super::edit_region::{write_params, EditState, NewParams, CHOSEN, NONE};
use super::features::FeatureMask;
use super::leaves::{level_patches, Leaf, LeafOptions, LeafPoints, LevelPatches, UNWALKED};
use super::patch_map::{EMPTY, LEAF};
use super::sparse::{self, Hierarchy, Level, Selection, Start};
use super::table::{PatchTable, PatchType};
use crate::error::{Error, Result};
use crate::patch::PatchParam;
use crate::real::Real;
use crate::refine::Restenciled;
use crate::util::budget::Budget;

/// The type, crease sharpness and parameter of every patch.
type Leaves = (Vec<u8>, Vec<f32>, Vec<PatchParam>);

impl<R: Real> PatchTable<R> {
    /// The table rebuilt from level `d` down, the levels above kept (module documentation):
    /// `st` is the kept state the walk updated, `rows` the re-formed stencil rows of the
    /// steps it walked (those above `d` are applied), `params` the new type, sharpness and
    /// parameter of the leaves decided above `d`, `(mask, leaf_options)` the edit's feature
    /// rules; the table's base is the edited one. The table itself is only read.
    pub(crate) fn rebuilt_from(
        &self,
        d: usize,
        st: EditState,
        rows: Vec<(usize, Restenciled<R>)>,
        params: NewParams,
        (mask, leaf_options): (&FeatureMask, &LeafOptions),
    ) -> Result<PatchTable<R>> {
        if d == 0 || d >= st.trace.levels.len() || rows.iter().filter(|r| r.0 < d).count() != d {
            return Err(Error::Internal(format!(
                "crease edit: no kept levels above level {d}"
            )));
        }
        // The kept levels' new values.
        let mut stencils = self.level_stencils[..d].to_vec();
        for (k, rows) in rows {
            if k < d {
                rows.apply(&mut stencils[k]);
            }
        }
        let mut leaves = (
            self.kinds.clone(),
            self.sharpness.clone(),
            self.params.clone(),
        );
        write_params(params, (&mut leaves.0, &mut leaves.1, &mut leaves.2));
        let out = (0..d)
            .map(|k| self.kept_patches(k, &st, &leaves))
            .collect::<Result<Vec<_>>>()?;
        let EditState { mut trace, .. } = st;

        // Level `d`: its topology and flags as kept, the children of the faces refined above.
        let above = if d == 1 {
            &self.base
        } else {
            &trace.levels[d - 1]
        };
        let visited: Vec<u32> = (trace.chosen[d - 1].iter())
            .flat_map(|&f| {
                let first = trace.child[d - 1][f as usize];
                first..first + above.face_size(f as usize) as u32
            })
            .collect();
        let level = Level::resumed(
            std::mem::take(&mut trace.levels[d]),
            std::mem::take(&mut trace.flags[d]),
        );
        let inputs = self.level_inputs[..d].to_vec();
        let h = Hierarchy {
            num_vertices: (self.level_offsets.windows(2))
                .take(d + 1)
                .map(|w| (w[1] - w[0]) as usize)
                .collect(),
            stencils,
            inputs,
        };
        trace.truncate(d);
        let start = Start {
            d,
            level,
            visited,
            h,
            out,
        };
        let (h, patches) = sparse::resume(
            start,
            leaf_options.max_level,
            mask,
            Selection::Sparse,
            &mut Budget::of_available_memory(),
            &|lv, k, off, faces| level_patches(lv, k, off, faces, leaf_options),
            Some(&mut trace),
        )?;
        PatchTable::assemble(&self.base, &self.options, h, patches, Some(trace), None)
    }

    /// The patches of the leaves of kept level `k`, as its construction made them: points
    /// from the table, types, sharpness and parameters from `leaves` (the table's as the
    /// edit decided them).
    fn kept_patches(&self, k: usize, st: &EditState, leaves: &Leaves) -> Result<LevelPatches<R>> {
        let t = if k == 0 {
            &self.base
        } else {
            &st.trace.levels[k]
        };
        let (visit, child) = (&st.visit[k], &st.trace.child[k]);
        let slot = (0..t.num_faces())
            .map(|f| match visit[f] {
                _ if t.face_is_hole[f] => EMPTY,
                CHOSEN => child[f],
                NONE => UNWALKED,
                i => LEAF | i,
            })
            .collect();
        let mut out = LevelPatches {
            slot,
            parts: Vec::new(),
        };
        let num_level_points = *self.level_offsets.last().unwrap_or(&0);
        let lp = &self.local_points;
        for &p in &st.leaf_patch[k] {
            if p == NONE {
                return Err(Error::Internal(format!("a leaf of level {k} has no patch")));
            }
            let p = p as usize;
            let (kind, fields) = (PatchType::from_u8(leaves.0[p]), leaves.2[p].fields());
            let cvs = self.patch_cvs(p);
            let leaf = Leaf {
                kind,
                boundary: fields.boundary,
                regular: fields.regular,
                sharpness: leaves.1[p],
                first: 0,
            };
            let points = if kind == PatchType::Gregory {
                let r = (cvs[0] - num_level_points) as usize;
                LeafPoints::EndCap {
                    offsets: &lp.offsets[r..r + 21],
                    indices: &lp.indices,
                    weights: &lp.weights,
                }
            } else {
                LeafPoints::Regular(cvs)
            };
            out.push(leaf, points);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::Topology;

    /// Kept levels without the re-formed rows of every step above the change are refused
    /// (an internal error: the edit is refused, the table left as it was), never resumed
    /// from.
    #[test]
    fn resuming_without_the_rows_above_is_refused() {
        let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../testdata/shapes/catmark_car.obj");
        let mesh = crate::io::obj::read_file(&p).unwrap();
        let t = Topology::new(&mesh).unwrap();
        let table = PatchTable::build_editable(&t, &Default::default()).unwrap();
        let st = table.edit_state.as_deref().unwrap().clone();
        for d in [0, 2, st.trace.levels.len()] {
            let rules = (
                &FeatureMask::new(true),
                &LeafOptions::new(&table.options, 4),
            );
            let r = table.rebuilt_from(d, st.clone(), Vec::new(), Vec::new(), rules);
            assert!(matches!(r, Err(Error::Internal(_))), "level {d}");
        }
    }
}
