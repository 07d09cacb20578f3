//! Validated mesh connectivity as flat tables (OpenSubdiv `Vtr::Level` layout).
//!
//! Every relation is stored as separate flat integer arrays with `n + 1` offsets, so that any
//! backend can upload them as they are. Built in linear time by counting sorts (no edge hash
//! map); edges are numbered as OpenSubdiv numbers them (first use by a face).

mod relations;
mod sharpen;
pub mod tags;
mod validate;

pub(crate) use relations::offsets_from_counts;
pub(crate) use validate::{clamp_sharpness, validate_mesh};

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::options::Options;

/// Connectivity and sharpness of a polygon mesh. All index arrays are `u32`.
///
/// Ring order at a manifold vertex `v`: [`Topology::vertex_faces`] runs counter-clockwise seen
/// from outside; `vertex_edges(v)[i]` is the edge leaving `v` along face `i` and
/// `vertex_edges(v)[i + 1]` is that face's other edge at `v`. An interior vertex has as many
/// edges as faces (cyclic); a boundary vertex has one more, its first and last edges being the
/// boundary edges.
///
/// # Example
///
/// A 2×2 grid of quads with one semi-sharp crease; the mesh's tags become per-edge
/// sharpness, boundaries are infinitely sharp, and bad input is a typed error:
///
/// ```
/// use subsurf::{shapes, Crease, Error, MeshError, Topology, SHARPNESS_INFINITE};
///
/// let mut mesh = shapes::grid(2, 2); // 9 vertices, vertex 4 in the middle
/// mesh.creases.push(Crease { v0: 1, v1: 4, sharpness: 2.5 });
/// let t = Topology::new(&mesh)?;
/// assert_eq!((t.num_vertices(), t.num_edges(), t.num_faces()), (9, 12, 4));
/// assert_eq!((t.valence(4), t.valence(0)), (4, 2));
/// assert!(!t.is_boundary_vertex(4) && t.is_boundary_vertex(1));
/// assert_eq!(t.boundary_edges().len(), 8);
/// assert!(t.is_manifold() && !t.is_closed() && t.is_all_quads());
///
/// let crease = t.find_edge(1, 4).expect("1 and 4 are joined") as usize;
/// assert_eq!(t.edge_sharpness(crease), 2.5);
/// assert_eq!(t.edge_faces(crease).len(), 2);
/// let boundary = t.find_edge(0, 1).expect("0 and 1 are joined") as usize;
/// assert_eq!(t.edge_sharpness(boundary), SHARPNESS_INFINITE);
///
/// mesh.face_indices[0] = 99;
/// assert!(matches!(
///     Topology::new(&mesh),
///     Err(Error::Mesh(MeshError::VertexIndexOutOfRange { face: 0, index: 99, .. }))
/// ));
/// # Ok::<(), subsurf::Error>(())
/// ```
#[derive(Debug, Clone, Default)]
pub struct Topology {
    /// The options the surface is built with.
    pub(crate) options: Options,
    /// Number of vertices.
    pub(crate) num_vertices: usize,
    /// `F + 1` offsets: face `f`'s corners are `face_offsets[f]..face_offsets[f + 1]`.
    pub(crate) face_offsets: Vec<u32>,
    /// One vertex per face corner, counter-clockwise.
    pub(crate) face_verts: Vec<u32>,
    /// One edge per face corner: edge `k` of a face joins its corners `k` and `k + 1`.
    pub(crate) face_edges: Vec<u32>,
    /// Two vertices per edge, oriented as the first face that uses the edge.
    pub(crate) edge_verts: Vec<[u32; 2]>,
    /// `E + 1` offsets into `edge_faces` / `edge_face_local`.
    pub(crate) edge_face_offsets: Vec<u32>,
    /// Faces of each edge, in face order.
    pub(crate) edge_faces: Vec<u32>,
    /// For each entry of `edge_faces`: which edge of that face (`k` in `face_edges`).
    pub(crate) edge_face_local: Vec<u16>,
    /// `V + 1` offsets into `vert_faces` / `vert_face_local`.
    pub(crate) vert_face_offsets: Vec<u32>,
    /// Faces of each vertex (ring order where manifold).
    pub(crate) vert_faces: Vec<u32>,
    /// For each entry of `vert_faces`: the corner index of the vertex in that face.
    pub(crate) vert_face_local: Vec<u16>,
    /// `V + 1` offsets into `vert_edges`.
    pub(crate) vert_edge_offsets: Vec<u32>,
    /// Edges of each vertex (ring order where manifold).
    pub(crate) vert_edges: Vec<u32>,
    /// One sharpness per edge in `[0, 10]`; boundary and non-manifold edges are 10 (infinite).
    pub(crate) edge_sharpness: Vec<f32>,
    /// One sharpness per vertex in `[0, 10]`.
    pub(crate) vert_sharpness: Vec<f32>,
    /// One flag per face: a hole is not emitted, yet it shapes its neighbours.
    pub(crate) face_is_hole: Vec<bool>,
    /// One tag set per edge ([`tags`]`::E_*`).
    pub(crate) edge_tags: Vec<u8>,
    /// One tag set per vertex ([`tags`]`::V_*`).
    pub(crate) vert_tags: Vec<u16>,
    /// One crease rule per vertex ([`tags::rule`]).
    pub(crate) vert_rule: Vec<u8>,
}

/// The flat arrays of a [`Topology`], borrowed: what a backend uploads as they are
/// ([`Topology::arrays`]).
#[derive(Debug, Clone, Copy)]
pub struct TopologyArrays<'a> {
    /// `F + 1` offsets: face `f`'s corners are `face_offsets[f]..face_offsets[f + 1]`.
    pub face_offsets: &'a [u32],
    /// One vertex per face corner, counter-clockwise.
    pub face_verts: &'a [u32],
    /// One edge per face corner: edge `k` of a face joins its corners `k` and `k + 1`.
    pub face_edges: &'a [u32],
    /// Two vertices per edge, oriented as the first face that uses the edge.
    pub edge_verts: &'a [[u32; 2]],
    /// `E + 1` offsets into `edge_faces` / `edge_face_local`.
    pub edge_face_offsets: &'a [u32],
    /// Faces of each edge, in face order.
    pub edge_faces: &'a [u32],
    /// For each entry of `edge_faces`: which edge of that face (`k` in `face_edges`).
    pub edge_face_local: &'a [u16],
    /// `V + 1` offsets into `vert_faces` / `vert_face_local`.
    pub vert_face_offsets: &'a [u32],
    /// Faces of each vertex (ring order where manifold).
    pub vert_faces: &'a [u32],
    /// For each entry of `vert_faces`: the corner index of the vertex in that face.
    pub vert_face_local: &'a [u16],
    /// `V + 1` offsets into `vert_edges`.
    pub vert_edge_offsets: &'a [u32],
    /// Edges of each vertex (ring order where manifold).
    pub vert_edges: &'a [u32],
    /// One sharpness per edge in `[0, 10]`; boundary and non-manifold edges are 10 (infinite).
    pub edge_sharpness: &'a [f32],
    /// One sharpness per vertex in `[0, 10]`.
    pub vert_sharpness: &'a [f32],
    /// One flag per face: a hole is not emitted, yet it shapes its neighbours.
    pub face_is_hole: &'a [bool],
    /// One tag set per edge (`E_*` bits of OpenSubdiv's `Vtr::Level::ETag`).
    pub edge_tags: &'a [u8],
    /// One tag set per vertex (`V_*` bits of `Vtr::Level::VTag`).
    pub vert_tags: &'a [u16],
    /// One crease rule per vertex (smooth 1, dart 2, crease 4, corner 8).
    pub vert_rule: &'a [u8],
}

#[inline]
fn range(off: &[u32], i: usize) -> std::ops::Range<usize> {
    off[i] as usize..off[i + 1] as usize
}

impl Topology {
    /// Validates `mesh` and builds its topology: relations, sharpness and tags.
    ///
    /// Errors name the offending element: an index out of range, a face with fewer than three
    /// vertices, a non-finite coordinate, a tag naming a missing element, or a crease between
    /// vertices that share no edge. Non-manifold edges and vertices and degenerate faces are
    /// accepted as OpenSubdiv accepts them (made infinitely sharp).
    pub fn new(mesh: &Mesh) -> Result<Topology> {
        validate_mesh(mesh)?;
        let face_offsets = offsets_from_counts(&mesh.face_counts);
        let mut t = Self::from_face_lists(
            mesh.positions.len(),
            face_offsets,
            mesh.face_indices.clone(),
            mesh.options,
        );
        for &h in &mesh.holes {
            t.face_is_hole[h as usize] = true;
        }
        for (tag, c) in mesh.creases.iter().enumerate() {
            let e = t
                .find_edge(c.v0, c.v1)
                .ok_or(MeshError::CreaseEdgeMissing {
                    tag,
                    v0: c.v0,
                    v1: c.v1,
                })?;
            t.edge_sharpness[e as usize] = clamp_sharpness(c.sharpness);
        }
        for c in &mesh.corners {
            t.vert_sharpness[c.vertex as usize] = clamp_sharpness(c.sharpness);
        }
        sharpen::apply_tags_and_boundary_sharpness(&mut t);
        Ok(t)
    }

    /// Re-derives tags, rules and boundary sharpening after `edge_sharpness` or
    /// `vert_sharpness` changed (what [`Topology::new`] does after reading the tags; applying
    /// it again to a sharpened topology changes nothing else, holes included).
    pub(crate) fn retag(&mut self) {
        sharpen::apply_tags_and_boundary_sharpness(self);
    }

    /// Builds relations only (no sharpness from tags, no tag pass); sharpness arrays are zero.
    pub(crate) fn from_face_lists(
        num_vertices: usize,
        face_offsets: Vec<u32>,
        face_verts: Vec<u32>,
        options: Options,
    ) -> Topology {
        let rel = relations::build_relations(num_vertices, &face_offsets, &face_verts);
        let ne = rel.edge_verts.len();
        let nf = face_offsets.len() - 1;
        let mut edge_tags = vec![0u8; ne];
        for e in 0..ne {
            if rel.edge_non_manifold[e] {
                edge_tags[e] |= tags::E_NON_MANIFOLD;
            }
        }
        let mut vert_tags = vec![0u16; num_vertices];
        for v in 0..num_vertices {
            if rel.vert_non_manifold[v] {
                vert_tags[v] |= tags::V_NON_MANIFOLD;
            }
        }
        Topology {
            options,
            num_vertices,
            face_offsets,
            face_verts,
            face_edges: rel.face_edges,
            edge_verts: rel.edge_verts,
            edge_face_offsets: rel.edge_face_offsets,
            edge_faces: rel.edge_faces,
            edge_face_local: rel.edge_face_local,
            vert_face_offsets: rel.vert_face_offsets,
            vert_faces: rel.vert_faces,
            vert_face_local: rel.vert_face_local,
            vert_edge_offsets: rel.vert_edge_offsets,
            vert_edges: rel.vert_edges,
            edge_sharpness: vec![0.0; ne],
            vert_sharpness: vec![0.0; num_vertices],
            face_is_hole: vec![false; nf],
            edge_tags,
            vert_tags,
            vert_rule: vec![tags::rule::SMOOTH; num_vertices],
        }
    }

    /// The flat arrays, borrowed.
    #[inline]
    pub fn arrays(&self) -> TopologyArrays<'_> {
        TopologyArrays {
            face_offsets: &self.face_offsets,
            face_verts: &self.face_verts,
            face_edges: &self.face_edges,
            edge_verts: &self.edge_verts,
            edge_face_offsets: &self.edge_face_offsets,
            edge_faces: &self.edge_faces,
            edge_face_local: &self.edge_face_local,
            vert_face_offsets: &self.vert_face_offsets,
            vert_faces: &self.vert_faces,
            vert_face_local: &self.vert_face_local,
            vert_edge_offsets: &self.vert_edge_offsets,
            vert_edges: &self.vert_edges,
            edge_sharpness: &self.edge_sharpness,
            vert_sharpness: &self.vert_sharpness,
            face_is_hole: &self.face_is_hole,
            edge_tags: &self.edge_tags,
            vert_tags: &self.vert_tags,
            vert_rule: &self.vert_rule,
        }
    }

    /// The options the surface is built with.
    #[inline]
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// The two vertices of edge `e`, oriented as the first face that uses it.
    #[inline]
    pub fn edge_vertices(&self, e: usize) -> [u32; 2] {
        self.edge_verts[e]
    }

    /// Whether face `f` is a hole (not emitted, yet it shapes its neighbours).
    #[inline]
    pub fn face_is_hole(&self, f: usize) -> bool {
        self.face_is_hole[f]
    }

    /// Sharpness of edge `e` in `[0, 10]` (boundary and non-manifold edges are 10).
    #[inline]
    pub fn edge_sharpness(&self, e: usize) -> f32 {
        self.edge_sharpness[e]
    }

    /// Sharpness of vertex `v` in `[0, 10]`.
    #[inline]
    pub fn vertex_sharpness(&self, v: usize) -> f32 {
        self.vert_sharpness[v]
    }

    /// Whether edge `e` is semi-sharp (sharpness in `(0, 10)`).
    #[inline]
    pub fn is_semi_sharp_edge(&self, e: usize) -> bool {
        self.edge_tags[e] & tags::E_SEMI_SHARP != 0
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }
    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.edge_verts.len()
    }
    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.num_vertices
    }
    /// Number of face corners (sum of face sizes).
    pub fn num_corners(&self) -> usize {
        self.face_verts.len()
    }
    /// Vertices of face `f`, counter-clockwise.
    pub fn face_vertices(&self, f: usize) -> &[u32] {
        &self.face_verts[range(&self.face_offsets, f)]
    }
    /// Edges of face `f` (edge `k` joins corners `k` and `k + 1`).
    pub fn face_edges(&self, f: usize) -> &[u32] {
        &self.face_edges[range(&self.face_offsets, f)]
    }
    /// Size of face `f`.
    pub fn face_size(&self, f: usize) -> usize {
        (self.face_offsets[f + 1] - self.face_offsets[f]) as usize
    }
    /// Faces of edge `e`.
    pub fn edge_faces(&self, e: usize) -> &[u32] {
        &self.edge_faces[range(&self.edge_face_offsets, e)]
    }
    /// Local indices matching [`Self::edge_faces`].
    pub fn edge_faces_local(&self, e: usize) -> &[u16] {
        &self.edge_face_local[range(&self.edge_face_offsets, e)]
    }
    /// Faces of vertex `v`.
    pub fn vertex_faces(&self, v: usize) -> &[u32] {
        &self.vert_faces[range(&self.vert_face_offsets, v)]
    }
    /// Corner indices of `v` in each of [`Self::vertex_faces`].
    pub fn vertex_faces_local(&self, v: usize) -> &[u16] {
        &self.vert_face_local[range(&self.vert_face_offsets, v)]
    }
    /// Edges of vertex `v`.
    pub fn vertex_edges(&self, v: usize) -> &[u32] {
        &self.vert_edges[range(&self.vert_edge_offsets, v)]
    }
    /// Number of edges at `v`.
    pub fn valence(&self, v: usize) -> usize {
        (self.vert_edge_offsets[v + 1] - self.vert_edge_offsets[v]) as usize
    }
    /// The other end of edge `e` seen from `v`.
    pub fn other_vertex(&self, e: usize, v: u32) -> u32 {
        let ev = self.edge_verts[e];
        if ev[0] == v {
            ev[1]
        } else {
            ev[0]
        }
    }
    /// The first edge joining `v0` and `v1`, if any (OpenSubdiv `Level::findEdge`).
    pub fn find_edge(&self, v0: u32, v1: u32) -> Option<u32> {
        self.vertex_edges(v0 as usize).iter().copied().find(|&e| {
            let ev = self.edge_verts[e as usize];
            if v0 == v1 {
                ev[0] == ev[1]
            } else {
                ev[0] == v1 || ev[1] == v1
            }
        })
    }
    /// True if edge `e` has one face.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.edge_tags[e] & tags::E_BOUNDARY != 0
    }
    /// True if vertex `v` lies on a boundary edge.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.vert_tags[v] & tags::V_BOUNDARY != 0
    }
    /// True if no edge and no vertex is non-manifold (vertices without faces are ignored).
    pub fn is_manifold(&self) -> bool {
        self.non_manifold_edges().is_empty() && self.non_manifold_vertices().is_empty()
    }
    /// True if the mesh is manifold and has no boundary edge.
    pub fn is_closed(&self) -> bool {
        self.is_manifold() && self.boundary_edges().is_empty()
    }
    /// True if every face is a quad.
    pub fn is_all_quads(&self) -> bool {
        (0..self.num_faces()).all(|f| self.face_size(f) == 4)
    }
    /// Indices of the non-manifold edges.
    pub fn non_manifold_edges(&self) -> Vec<u32> {
        (0..self.num_edges() as u32)
            .filter(|&e| self.edge_tags[e as usize] & tags::E_NON_MANIFOLD != 0)
            .collect()
    }
    /// Indices of the non-manifold vertices that have faces.
    pub fn non_manifold_vertices(&self) -> Vec<u32> {
        (0..self.num_vertices as u32)
            .filter(|&v| {
                self.vert_tags[v as usize] & tags::V_NON_MANIFOLD != 0
                    && !self.vertex_faces(v as usize).is_empty()
            })
            .collect()
    }
    /// Indices of the boundary edges.
    pub fn boundary_edges(&self) -> Vec<u32> {
        (0..self.num_edges() as u32)
            .filter(|&e| self.is_boundary_edge(e as usize))
            .collect()
    }
    /// Indices of the faces that repeat a vertex.
    pub fn degenerate_faces(&self) -> Vec<u32> {
        (0..self.num_faces() as u32)
            .filter(|&f| {
                let fv = self.face_vertices(f as usize);
                (0..fv.len()).any(|i| fv[i + 1..].contains(&fv[i]))
            })
            .collect()
    }
    /// Vertices with no incident face.
    pub fn unused_vertices(&self) -> Vec<u32> {
        (0..self.num_vertices as u32)
            .filter(|&v| self.vertex_faces(v as usize).is_empty())
            .collect()
    }
}

mod consistency;

#[cfg(test)]
pub(crate) mod tests;
