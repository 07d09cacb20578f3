//! The sharpness tags and holes a refined level keeps, as the [`Mesh`] tags that rebuild it.
//!
//! A refined level written out and read back as a base mesh must refine to the same surface
//! as the refinement it came from: level `k` of the file's level `j` equals level `j + k` of
//! the original. So the file carries every edge and vertex sharpness that remains after the
//! decay of `j` steps (OpenSubdiv's, Chaikin's rule included: DeRose, Kass & Truong 1998), the
//! children of holes as holes, and the options (which [`Mesh::options`] holds).
//!
//! What the base level sharpens by itself is left out, as it would be sharpened again:
//! non-manifold edges, boundary edges, and topological corners under `EdgeAndCorner`. One
//! exception: under boundary interpolation `None` the base level turns every face at a
//! boundary vertex into a hole unless the vertex's boundary edges are all tagged infinitely
//! sharp (see `topology::sharpen`), so there every boundary edge is written, infinitely sharp:
//! the faces the refined level kept stay faces, and those it made holes are tagged holes.
//!
//! A full level holds its sharpness; a lean last level ([`super::RefineOptions::lean`]) does
//! not, so its tags are derived from its parent and the child sharpness of the last step.

use super::last_level::ChildSharpness;
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, Crease, Mesh};
use crate::options::BoundaryInterpolation;
use crate::topology::tags;
use crate::topology::Topology;

/// The tags of one level, indexed as the level numbers its vertices and faces (0-based, as
/// OpenSubdiv's OBJ tags).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LevelTags {
    /// Semi-sharp and infinitely sharp edges the base level would not sharpen by itself.
    pub creases: Vec<Crease>,
    /// Sharp vertices the base level would not sharpen by itself.
    pub corners: Vec<Corner>,
    /// Faces that are holes.
    pub holes: Vec<u32>,
}

impl LevelTags {
    /// Moves the tags into `mesh` (a mesh of all the level's faces, holes included).
    pub fn apply(self, mesh: &mut Mesh) {
        mesh.creases = self.creases;
        mesh.corners = self.corners;
        mesh.holes = self.holes;
    }
}

/// Whether an edge with tags `et` of a level with options `t` is written.
#[inline]
fn written_edge(t: &Topology, et: u8, s: f32) -> bool {
    if s <= 0.0 || et & tags::E_NON_MANIFOLD != 0 {
        return false;
    }
    et & tags::E_BOUNDARY == 0 || t.options.boundary == BoundaryInterpolation::None
}

/// Whether a vertex with tags `vt` of sharpness `s` is written.
#[inline]
fn written_vertex(t: &Topology, vt: u16, s: f32) -> bool {
    s > 0.0
        && !(vt & tags::V_CORNER != 0 && t.options.boundary == BoundaryInterpolation::EdgeAndCorner)
}

fn holes(t: &Topology) -> Vec<u32> {
    (0..t.num_faces() as u32)
        .filter(|&f| t.face_is_hole[f as usize])
        .collect()
}

/// The tags of a level with its full topology (any level of a [`super::Refiner`] but a lean
/// last one). Refuses a lean level, whose sharpness is not stored:
/// [`super::Refiner::to_tagged_mesh`] derives it from the parent instead.
pub fn level_tags(t: &Topology) -> Result<LevelTags> {
    if t.num_edges() == 0 && t.num_faces() > 0 {
        return Err(MeshError::Unsupported {
            construction: "the tags of a refined level",
            requirement: "a level with its full topology",
            details: "a lean last level keeps no sharpness; derive it from its parent".into(),
        }
        .into());
    }
    let creases = (0..t.num_edges())
        .filter(|&e| written_edge(t, t.edge_tags[e], t.edge_sharpness[e]))
        .map(|e| Crease {
            v0: t.edge_verts[e][0],
            v1: t.edge_verts[e][1],
            sharpness: t.edge_sharpness[e],
        })
        .collect();
    let corners = (0..t.num_vertices())
        .filter(|&v| written_vertex(t, t.vert_tags[v], t.vert_sharpness[v]))
        .map(|v| Corner {
            vertex: v as u32,
            sharpness: t.vert_sharpness[v],
        })
        .collect();
    Ok(LevelTags {
        creases,
        corners,
        holes: holes(t),
    })
}

/// The tags of `child`, a (lean or full) refinement of `p` whose child sharpness is `cs`: the
/// same as [`level_tags`] of the full child. Only children of the parent's edges and vertices
/// can be sharp (edges inside a face and face and edge points are smooth); child edge
/// `2e + end` of parent edge `e` joins its edge point to end `end`, and inherits the edge's
/// boundary and non-manifold tags, as the child of a vertex inherits its corner tag.
pub(crate) fn child_level_tags(
    p: &Topology,
    cs: ChildSharpness<'_>,
    child: &Topology,
) -> LevelTags {
    let (nv, nf) = (p.num_vertices(), super::last_level::face_points(p));
    let mut creases = Vec::new();
    for e in 0..p.num_edges() {
        let et = p.edge_tags[e] & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD);
        for end in 0..2 {
            let s = cs.edge(2 * e + end);
            if written_edge(p, et, s) {
                creases.push(Crease {
                    v0: (nv + nf + e) as u32,
                    v1: p.edge_verts[e][end],
                    sharpness: s,
                });
            }
        }
    }
    let corners = (0..nv)
        .filter_map(|v| {
            let s = cs.vertex(v);
            written_vertex(p, p.vert_tags[v], s).then_some(Corner {
                vertex: v as u32,
                sharpness: s,
            })
        })
        .collect();
    LevelTags {
        creases,
        corners,
        holes: holes(child),
    }
}

/// All faces of a refined level, holes included and tagged, with its remaining sharpness and
/// options: a mesh that, read back as a base level, refines as the level itself would.
/// Contrast [`super::level_mesh`], which leaves holes out and keeps no tags (for display).
pub fn tagged_level_mesh(
    t: &Topology,
    positions: impl Into<crate::mesh::Positions>,
    tags: LevelTags,
) -> Mesh {
    let mut m = Mesh {
        positions: positions.into(),
        face_counts: (0..t.num_faces())
            .map(|f| t.face_offsets[f + 1] - t.face_offsets[f])
            .collect(),
        face_indices: t.face_verts.clone(),
        options: t.options,
        ..Default::default()
    };
    tags.apply(&mut m);
    m
}
