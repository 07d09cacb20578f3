//! One-ring gathering and input checking for the p-rep (spec §1).
//!
//! At a vertex `p0` of valence `n` the one-ring `p1 … p2n` is listed counter-clockwise:
//! odd `p_{2l-1}` are the edge neighbours, even `p_{2l}` the face-diagonal neighbours.
//!
//! ```text
//!        p_{2k+3} ── p_{2k+2}
//!          │  sector k │         sector k = face (p0, p_{2k+1}, p_{2k+2}, p_{2k+3}), ccw
//!         p0 ─────── p_{2k+1}
//! ```
//!
//! The walk: take any face at `p0`, rotate it to `(p0, x, y, z)`; then `p_{2k+1} = x`,
//! `p_{2k+2} = y`, and the next sector is the face that owns the directed edge `p0 → z`.
//!
//! Everything is computed once per connectivity and stored in flat tables
//! ([`PrepTopology`]); the vertex and patch passes only index into them.

use super::constants::{MAX_VALENCE, MIN_VALENCE};
use crate::error::{Error, MeshError, Result};
use crate::topology::Topology;

/// Flat connectivity tables of a closed quad mesh, in the p-rep's ring order.
///
/// Counts per element are given as `(count: ..)`. `V` vertices, `F` faces, `E = 2F` edges,
/// `S = Σ valence = 4F` sectors (one per face corner).
#[derive(Debug, Clone, Default)]
pub struct PrepTopology {
    /// Number of vertices `V`.
    pub(crate) num_vertices: usize,
    /// Valence of each vertex (count: V); 0 for a vertex used by no face.
    pub(crate) valence: Vec<u32>,
    /// Offsets into `ring_indices` (count: V + 1); vertex v's ring is `2 valence(v)` long.
    pub(crate) ring_offsets: Vec<u32>,
    /// `p1 … p2n` of every vertex, concatenated (count: 2 S).
    pub(crate) ring_indices: Vec<u32>,
    /// The vertex of each sector (count: S); vertex v's sectors are `ring_offsets[v]/2 ..`.
    pub(crate) sector_vertex: Vec<u32>,
    /// Vertex of each face corner (count: 4 F) (faces are quads).
    pub(crate) face_verts: Vec<u32>,
    /// Sector number `k` of face f at corner c (count: 4 F), i.e. the face is `(p0, p_{2k+1}, p_{2k+2}, p_{2k+3})`
    /// of the corner's vertex.
    pub(crate) corner_sector: Vec<u32>,
    /// Edge of each face corner (count: 4 F): edge c of a face joins corner c and corner c+1.
    pub(crate) face_edges: Vec<u32>,
    /// End vertices of each edge (count: E), lower index first (the canonical direction).
    pub(crate) edge_verts: Vec<[u32; 2]>,
    /// For each edge (count: E), the face corner `4 f + c` whose edge runs in the canonical direction.
    pub(crate) edge_corner: Vec<u32>,
    /// Index of each face's block of 16 `h` coefficients (count: F), `u32::MAX` for a B-quad
    /// (all four vertices of valence 4).
    pub(crate) h_index: Vec<u32>,
    /// The faces that are not B-quads, in `h_index` order.
    pub(crate) perturbed_faces: Vec<u32>,
    /// Largest valence.
    pub(crate) max_valence: usize,
}

impl PrepTopology {
    /// Number of vertices `V`.
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.num_vertices
    }

    /// Valence of each vertex (count: V); 0 for a vertex used by no face.
    #[inline]
    pub fn valence(&self) -> &[u32] {
        &self.valence
    }

    /// Offsets into `ring_indices` (count: V + 1); vertex v's ring is `2 valence(v)` long.
    #[inline]
    pub fn ring_offsets(&self) -> &[u32] {
        &self.ring_offsets
    }

    /// `p1 … p2n` of every vertex, concatenated (count: 2 S).
    #[inline]
    pub fn ring_indices(&self) -> &[u32] {
        &self.ring_indices
    }

    /// The vertex of each sector (count: S); vertex v's sectors are `ring_offsets[v]/2 ..`.
    #[inline]
    pub fn sector_vertex(&self) -> &[u32] {
        &self.sector_vertex
    }

    /// Vertex of each face corner (count: 4 F) (faces are quads).
    #[inline]
    pub fn face_verts(&self) -> &[u32] {
        &self.face_verts
    }

    /// Sector number `k` of face f at corner c (count: 4 F), i.e. the face is `(p0, p_{2k+1}, p_{2k+2}, p_{2k+3})`
    /// of the corner's vertex.
    #[inline]
    pub fn corner_sector(&self) -> &[u32] {
        &self.corner_sector
    }

    /// Edge of each face corner (count: 4 F): edge c of a face joins corner c and corner c+1.
    #[inline]
    pub fn face_edges(&self) -> &[u32] {
        &self.face_edges
    }

    /// End vertices of each edge (count: E), lower index first (the canonical direction).
    #[inline]
    pub fn edge_verts(&self) -> &[[u32; 2]] {
        &self.edge_verts
    }

    /// For each edge (count: E), the face corner `4 f + c` whose edge runs in the canonical direction.
    #[inline]
    pub fn edge_corner(&self) -> &[u32] {
        &self.edge_corner
    }

    /// Index of each face's block of 16 `h` coefficients (count: F), `u32::MAX` for a B-quad
    /// (all four vertices of valence 4).
    #[inline]
    pub fn h_index(&self) -> &[u32] {
        &self.h_index
    }

    /// The faces that are not B-quads, in `h_index` order.
    #[inline]
    pub fn perturbed_faces(&self) -> &[u32] {
        &self.perturbed_faces
    }

    /// Largest valence.
    #[inline]
    pub fn max_valence(&self) -> usize {
        self.max_valence
    }
}

const CONSTRUCTION: &str = "the p-rep";
const REQUIREMENT: &str = "a closed, oriented 2-manifold quad mesh without holes, valences 3..=64";

/// "`count` `what`: a, b, c, … (first 8)".
fn listing<I: std::fmt::Display>(what: &str, items: &[I]) -> String {
    const SHOWN: usize = 8;
    let head: Vec<String> = items.iter().take(SHOWN).map(|i| i.to_string()).collect();
    let more = if items.len() > SHOWN { ", …" } else { "" };
    format!("{} {what}: {}{more}", items.len(), head.join(", "))
}

/// Checks that `topo` is a closed, oriented 2-manifold quad mesh with valences
/// `3..=MAX_VALENCE` and no holes. The [`MeshError::Unsupported`] error names the offending
/// faces, edges or vertices (the first few of each kind, with their count).
pub fn check_input(topo: &Topology) -> Result<()> {
    let mut bad: Vec<String> = Vec::new();
    let nf = topo.num_faces();
    let edge_name = |e: u32| {
        let [a, b] = topo.edge_verts[e as usize];
        format!("edge {e} ({}-{})", a.min(b), a.max(b))
    };
    let non_quads: Vec<String> = (0..nf)
        .filter(|&f| topo.face_size(f) != 4)
        .map(|f| format!("face {f} ({} vertices)", topo.face_size(f)))
        .collect();
    if !non_quads.is_empty() {
        bad.push(listing("non-quad faces", &non_quads));
    }
    let holes: Vec<String> = (0..nf)
        .filter(|&f| topo.face_is_hole[f])
        .map(|f| format!("face {f}"))
        .collect();
    if !holes.is_empty() {
        bad.push(listing("faces tagged as holes", &holes));
    }
    let degenerate: Vec<String> = topo
        .degenerate_faces()
        .iter()
        .map(|f| format!("face {f}"))
        .collect();
    if !degenerate.is_empty() {
        bad.push(listing("degenerate faces (repeated vertex)", &degenerate));
    }
    let nm: Vec<String> = topo
        .non_manifold_edges()
        .into_iter()
        .map(edge_name)
        .collect();
    if !nm.is_empty() {
        bad.push(listing(
            "non-manifold edges (more than two faces, or two faces wound the same way)",
            &nm,
        ));
    }
    let boundary: Vec<String> = topo.boundary_edges().into_iter().map(edge_name).collect();
    if !boundary.is_empty() {
        bad.push(listing("boundary edges", &boundary));
    }
    let nmv: Vec<String> = topo
        .non_manifold_vertices()
        .iter()
        .map(|v| format!("vertex {v}"))
        .collect();
    if !nmv.is_empty() {
        bad.push(listing("non-manifold vertices", &nmv));
    }
    let valence: Vec<String> = (0..topo.num_vertices)
        .filter(|&v| {
            let n = topo.valence(v);
            !topo.vertex_faces(v).is_empty() && !(MIN_VALENCE..=MAX_VALENCE).contains(&n)
        })
        .map(|v| format!("vertex {v} (valence {})", topo.valence(v)))
        .collect();
    if !valence.is_empty() {
        bad.push(listing("vertices with unsupported valence", &valence));
    }
    if bad.is_empty() {
        Ok(())
    } else {
        Err(MeshError::Unsupported {
            construction: CONSTRUCTION,
            requirement: REQUIREMENT,
            details: bad.join("; "),
        }
        .into())
    }
}

impl PrepTopology {
    /// Builds the ring tables from a validated [`Topology`], refusing input the p-rep does not
    /// cover (see [`check_input`]). Sector `k` of vertex `v` is `topo.vertex_faces(v)[k]`
    /// (counter-clockwise), so the ring is read off the faces in that order.
    pub fn new(topo: &Topology) -> Result<Self> {
        check_input(topo)?;
        let nv = topo.num_vertices;
        let nf = topo.num_faces();
        let fv = &topo.face_verts;
        let mut valence = vec![0u32; nv];
        let mut ring_offsets = Vec::with_capacity(nv + 1);
        let mut ring_indices = Vec::with_capacity(8 * nf);
        let mut sector_vertex = Vec::with_capacity(4 * nf);
        let mut corner_sector = vec![u32::MAX; 4 * nf];
        ring_offsets.push(0u32);
        for v in 0..nv {
            let (faces, local) = (topo.vertex_faces(v), topo.vertex_faces_local(v));
            let n = faces.len();
            for k in 0..n {
                let (f, c) = (faces[k] as usize, local[k] as usize);
                corner_sector[4 * f + c] = k as u32;
                ring_indices.push(fv[4 * f + (c + 1) % 4]);
                ring_indices.push(fv[4 * f + (c + 2) % 4]);
                sector_vertex.push(v as u32);
                // The next sector's first edge is this sector's last one (ccw order).
                let (f2, c2) = (faces[(k + 1) % n] as usize, local[(k + 1) % n] as usize);
                if fv[4 * f + (c + 3) % 4] != fv[4 * f2 + (c2 + 1) % 4] {
                    return Err(Error::Internal(format!(
                        "vertex {v}: faces {f} and {f2} are not consecutive counter-clockwise"
                    )));
                }
            }
            valence[v] = n as u32;
            ring_offsets.push(ring_indices.len() as u32);
        }
        // Edges: the canonical direction runs from the lower vertex index.
        let mut edge_verts = Vec::with_capacity(topo.num_edges());
        let mut edge_corner = Vec::with_capacity(topo.num_edges());
        for e in 0..topo.num_edges() {
            let [a, b] = topo.edge_verts[e];
            edge_verts.push([a.min(b), a.max(b)]);
            let corner = topo
                .edge_faces(e)
                .iter()
                .zip(topo.edge_faces_local(e))
                .map(|(&f, &k)| 4 * f as usize + k as usize)
                .find(|&i| fv[i] < fv[i - i % 4 + (i + 1) % 4])
                .ok_or_else(|| Error::Internal(format!("edge {e} has no canonical face")))?;
            edge_corner.push(corner as u32);
        }
        let mut h_index = vec![u32::MAX; nf];
        let mut perturbed_faces = Vec::new();
        for f in 0..nf {
            if fv[4 * f..4 * f + 4]
                .iter()
                .any(|&v| valence[v as usize] != 4)
            {
                h_index[f] = perturbed_faces.len() as u32;
                perturbed_faces.push(f as u32);
            }
        }
        let max_valence = valence.iter().copied().max().unwrap_or(0) as usize;
        Ok(PrepTopology {
            num_vertices: nv,
            valence,
            ring_offsets,
            ring_indices,
            sector_vertex,
            face_verts: fv.clone(),
            corner_sector,
            face_edges: topo.face_edges.clone(),
            edge_verts,
            edge_corner,
            h_index,
            perturbed_faces,
            max_valence,
        })
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_verts.len() / 4
    }

    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.edge_verts.len()
    }

    /// The ring `p1 … p2n` of vertex `v`.
    pub fn ring(&self, v: usize) -> &[u32] {
        &self.ring_indices[self.ring_offsets[v] as usize..self.ring_offsets[v + 1] as usize]
    }

    /// Index of sector 0 of vertex `v` in the per-sector tables.
    #[inline]
    pub fn sector_base(&self, v: usize) -> usize {
        self.ring_offsets[v] as usize / 2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    fn cube() -> Mesh {
        let p: Vec<[f32; 3]> = (0..8)
            .map(|i| [(i >> 2) as f32, ((i >> 1) & 1) as f32, (i & 1) as f32])
            .collect();
        let f = [
            [0u32, 1, 3, 2],
            [4, 6, 7, 5],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 5, 7, 3],
        ];
        Mesh::from_faces(p, &f)
    }

    /// Every sector k at v is a face whose corner at v is followed by p_{2k+1}, p_{2k+2},
    /// p_{2k+3} (cyclic), and every corner gets exactly one sector.
    #[test]
    fn cube_rings_follow_spec_order() {
        let m = cube();
        let t = PrepTopology::new(&Topology::new(&m).unwrap()).unwrap();
        assert!(t.valence.iter().all(|&n| n == 3));
        assert_eq!(t.num_edges(), 12);
        for f in 0..6 {
            for c in 0..4 {
                let v = t.face_verts[4 * f + c] as usize;
                let k = t.corner_sector[4 * f + c] as usize;
                let r = t.ring(v);
                let n = r.len() / 2;
                assert_eq!(r[2 * k], t.face_verts[4 * f + (c + 1) % 4]);
                assert_eq!(r[2 * k + 1], t.face_verts[4 * f + (c + 2) % 4]);
                assert_eq!(r[(2 * k + 2) % (2 * n)], t.face_verts[4 * f + (c + 3) % 4]);
            }
        }
        // Each edge appears in exactly two face corners.
        let mut count = [0; 12];
        for &e in &t.face_edges {
            count[e as usize] += 1;
        }
        assert!(count.iter().all(|&c| c == 2));
    }
}
