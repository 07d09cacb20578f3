//! Crease edits on a built [`PatchTable`]: new sharpness for edges and vertices of the base
//! mesh, the table made to give the surface of a fresh [`PatchTable::build`] of the edited
//! mesh, bit for bit (and its arrays, unless the edit was made locally).
//!
//! Sharpness enters a table in three places: which faces are isolated (a semi-sharp edge is
//! an irregular feature unless it makes a single-crease patch), the stored sharpness of the
//! single-crease patches, and the refinement stencils of every level around the crease (the
//! crease and corner masks, and the fractional blends of a decaying crease, change the refined
//! points to the isolation level). All the edits are checked before any work: an edge must
//! exist, a value must be finite and non-negative (values above
//! [`crate::SHARPNESS_INFINITE`] are clamped, as [`crate::Topology::new`] clamps the tags).
//!
//! The table is then updated in place where the edit keeps its isolation structure
//! ([`super::edit_region`]); where the faces of a level are decided differently, the base
//! faces whose patches the edit can change are rebuilt from a sub-mesh around them and
//! spliced in ([`super::edit_local`]: the same surface, bit for bit, numbered differently),
//! unless that region is too large: it is then rebuilt from that level down, the levels above
//! kept ([`super::edit_rebuild`]), and in full where that level is the base. A table edited
//! locally keeps no levels: its later edits are local too. Edits that change nothing (the same values, or edges and
//! vertices that boundary and non-manifold sharpening keep infinitely sharp) leave it
//! untouched.

use super::edit_region::Incremental;
use super::sparse::Selection;
use super::table::{PatchOptions, PatchTable};
use crate::error::{Error, MeshError, Result};
use crate::mesh::Crease;
use crate::options::BoundaryInterpolation;
use crate::real::Real;
use crate::topology::{clamp_sharpness, Topology};
use crate::util::budget::Budget;

/// One sharpness edit of [`PatchTable::set_sharpness`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SharpnessEdit {
    /// The crease sharpness of the edge joining two base vertices (either order).
    Edge {
        /// One end.
        v0: u32,
        /// The other end.
        v1: u32,
        /// New sharpness (`0` smooth, `>= 10` infinitely sharp).
        sharpness: f32,
    },
    /// The corner sharpness of a base vertex.
    Vertex {
        /// The vertex.
        vertex: u32,
        /// New sharpness.
        sharpness: f32,
    },
}

impl SharpnessEdit {
    /// One edge edit per crease of `creases`, each to `sharpness` (its own value for `None`):
    /// the edit list of a slider that moves every crease of a mesh at once.
    pub fn creases(creases: &[Crease], sharpness: Option<f32>) -> Vec<SharpnessEdit> {
        creases
            .iter()
            .map(|c| SharpnessEdit::Edge {
                v0: c.v0,
                v1: c.v1,
                sharpness: sharpness.unwrap_or(c.sharpness),
            })
            .collect()
    }
}

fn bad(edit: usize, reason: String) -> Error {
    MeshError::BadSharpnessEdit { edit, reason }.into()
}

/// The base topology with `edits` applied, or the first bad edit (nothing is changed then).
fn edited(base: &Topology, edits: &[SharpnessEdit]) -> Result<Topology> {
    // Every edit is checked first.
    let mut resolved = Vec::with_capacity(edits.len());
    for (i, e) in edits.iter().enumerate() {
        let s = match *e {
            SharpnessEdit::Edge { sharpness, .. } | SharpnessEdit::Vertex { sharpness, .. } => {
                sharpness
            }
        };
        if !(s.is_finite() && s >= 0.0) {
            return Err(bad(
                i,
                format!("sharpness {s} is not a finite non-negative value"),
            ));
        }
        match *e {
            SharpnessEdit::Edge { v0, v1, .. } => {
                let nv = base.num_vertices() as u32;
                let edge = (v0 < nv && v1 < nv)
                    .then(|| base.find_edge(v0, v1))
                    .flatten()
                    .ok_or_else(|| {
                        bad(
                            i,
                            format!("vertices {v0} and {v1} are not joined by an edge"),
                        )
                    })?;
                if base.options.boundary == BoundaryInterpolation::None
                    && base.is_boundary_edge(edge as usize)
                {
                    // The holes of that mode are decided on the boundary edges' own tags,
                    // which sharpening has replaced.
                    return Err(Error::Unsupported(format!(
                        "sharpness edit {i}: boundary edge {v0}-{v1} under boundary \
                         interpolation None (its tag decides holes: rebuild from the mesh)"
                    )));
                }
                resolved.push((true, edge as usize, clamp_sharpness(s)));
            }
            SharpnessEdit::Vertex { vertex, .. } => {
                if vertex as usize >= base.num_vertices() {
                    return Err(bad(
                        i,
                        format!(
                            "vertex {vertex} does not exist ({} vertices)",
                            base.num_vertices()
                        ),
                    ));
                }
                resolved.push((false, vertex as usize, clamp_sharpness(s)));
            }
        }
    }
    let mut t = base.clone();
    for (edge, k, s) in resolved {
        if edge {
            t.edge_sharpness[k] = s;
        } else {
            t.vert_sharpness[k] = s;
        }
    }
    t.retag();
    Ok(t)
}

/// What [`PatchTable::apply_sharpness`] did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EditOutcome {
    /// Nothing changed (the same values, or elements kept infinitely sharp).
    Unchanged,
    /// The isolation structure was kept: the table was updated in place
    /// (`super::edit_region`).
    Updated,
    /// The table was rebuilt (the first edit of a table that does not keep its levels, or a
    /// change of structure at the base).
    Rebuilt,
    /// The isolation structure changed from `level` down: the levels above it were kept and
    /// the table rebuilt from it (`super::edit_rebuild`), where the region the edit changes
    /// is too large to rebuild locally.
    RebuiltFrom {
        /// The first level (from the base) whose faces were decided differently.
        level: u32,
    },
    /// The base faces whose patches the edit can change were rebuilt from a sub-mesh around
    /// them and their patches spliced into the table (`super::edit_local`): the structure
    /// changed, or the table was edited locally before.
    Local {
        /// The base faces whose patches were re-made.
        faces: u32,
    },
}

impl PatchTable {
    /// [`PatchTable::build`], keeping the levels of the construction for crease edits (see
    /// [`PatchTable::build_editable_real`]).
    pub fn build_editable(base: &Topology, options: &PatchOptions) -> Result<PatchTable> {
        Self::build_editable_real(base, options)
    }
}

impl<R: Real> PatchTable<R> {
    /// [`PatchTable::build_real`], keeping the levels of the construction (the topology of
    /// every level and refined sub-mesh, the faces refined and the leaves, the vertex tags)
    /// for crease edits: the first [`PatchTable::set_sharpness`] that keeps the isolation
    /// structure is then made in place, as every later one is, where a table from
    /// [`PatchTable::build_real`] rebuilds itself on its first edit to keep them. The table is
    /// the same, bit for bit; the levels are kept in memory as long as the table (see the
    /// README's "Crease edits" for the car's figures).
    pub fn build_editable_real(base: &Topology, options: &PatchOptions) -> Result<PatchTable<R>> {
        Self::build_within_real(
            base,
            options,
            Selection::Sparse,
            Budget::of_available_memory(),
            true,
            None,
        )
    }

    /// Whether the table keeps its levels, so that a crease edit that keeps the isolation
    /// structure is made in place ([`PatchTable::build_editable`], or any table after its
    /// first edit; a table with per-region isolation levels never does).
    pub fn is_editable(&self) -> bool {
        self.edit_state.is_some()
    }

    /// The levels the table keeps for crease edits, as its last build or edit left them (the
    /// topology of refined levels 1, 2, … and of each refined sub-mesh, the maps between
    /// them, the faces refined and the leaves, the vertex tags; level 0 is the table's base
    /// and left empty); `None` where none are kept ([`PatchTable::is_editable`]). Read-only:
    /// what an edit that changes the structure has to bring up to date with the table.
    /// Hidden: the levels' type is internal; the crate's tests compare two tables' levels.
    #[doc(hidden)]
    pub fn kept_levels(&self) -> Option<&super::sparse::Trace> {
        self.edit_state.as_deref().map(|s| s.trace())
    }

    /// Sets the sharpness of base edges and vertices (any number at once, later edits of the
    /// same element winning) and updates the table to make the surface of a fresh build of the
    /// edited mesh, bit for bit (see the module documentation). Returns whether the table
    /// changed.
    ///
    /// Bad edits are refused before any work with [`MeshError::BadSharpnessEdit`], naming
    /// the edit and the value or element; the table is then unchanged.
    pub fn set_sharpness(&mut self, edits: &[SharpnessEdit]) -> Result<bool> {
        Ok(self.apply_sharpness(edits)? != EditOutcome::Unchanged)
    }

    /// [`PatchTable::set_sharpness`], saying how the table was updated: in place where the
    /// isolation structure is kept (`super::edit_region`), locally where it changes over a
    /// region whose sub-mesh holds at most half of the base faces (`super::edit_local`;
    /// every edit of a table edited locally), rebuilt from the first level
    /// whose faces are decided differently where that is below the base (the levels above
    /// kept, `super::edit_rebuild`), else rebuilt. The first edit of a table that does not
    /// keep its levels ([`PatchTable::is_editable`]) rebuilds it, keeping them for the next
    /// edits.
    pub fn apply_sharpness(&mut self, edits: &[SharpnessEdit]) -> Result<EditOutcome> {
        let t = edited(&self.base, edits)?;
        if t.edge_sharpness == self.base.edge_sharpness
            && t.vert_sharpness == self.base.vert_sharpness
        {
            return Ok(EditOutcome::Unchanged);
        }
        if let Some(levels) = &self.face_levels {
            // Per-region levels: a fresh build with the same levels (no kept levels).
            let share = self.local_share;
            *self = PatchTable::build_face_levels(&t, &self.options, levels)?;
            self.local_share = share;
            return Ok(EditOutcome::Rebuilt);
        }
        if self.edit_state.is_none() && self.spliced.is_some() {
            // Edited locally before: no levels kept, every edit is local.
            return match self.local_region(&t) {
                Some(region) => self.splice_local(t, region),
                None => self.rebuild(t),
            };
        }
        let t = match self.set_sharpness_incremental(t)? {
            Incremental::Updated => return Ok(EditOutcome::Updated),
            Incremental::Rebuilt(level) => return Ok(EditOutcome::RebuiltFrom { level }),
            Incremental::Local(t, region) => return self.splice_local(*t, region),
            Incremental::Rebuild(t) => *t,
        };
        self.rebuild(t)
    }
}
