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

use std::collections::HashMap;

use super::constants::{MAX_VALENCE, MIN_VALENCE};
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;

/// The faces of a polygon mesh as flat tables: the p-rep's input connectivity.
#[derive(Debug, Clone)]
pub struct FaceList<'a> {
    /// Number of vertices.
    pub num_vertices: usize,
    /// `F + 1` offsets into `face_verts`.
    pub face_offsets: Vec<u32>,
    /// Vertex indices of all faces, ccw seen from outside.
    pub face_verts: &'a [u32],
    /// Faces tagged as holes.
    pub holes: &'a [u32],
}

impl<'a> From<&'a Mesh> for FaceList<'a> {
    fn from(m: &'a Mesh) -> Self {
        let mut face_offsets = Vec::with_capacity(m.face_counts.len() + 1);
        let mut o = 0u32;
        face_offsets.push(0);
        for &c in &m.face_counts {
            o = o.saturating_add(c);
            face_offsets.push(o);
        }
        FaceList {
            num_vertices: m.num_vertices(),
            face_offsets,
            face_verts: &m.face_indices,
            holes: &m.holes,
        }
    }
}

impl FaceList<'_> {
    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.face_offsets.len() - 1
    }
}

/// Flat connectivity tables of a closed quad mesh, in the p-rep's ring order.
///
/// Counts per element are given in brackets. `V` vertices, `F` faces, `E = 2F` edges,
/// `S = Σ valence = 4F` sectors (one per face corner).
#[derive(Debug, Clone, Default)]
pub struct PrepTopology {
    /// Number of vertices `V`.
    pub num_vertices: usize,
    /// Valence of each vertex [V]; 0 for a vertex used by no face.
    pub valence: Vec<u32>,
    /// Offsets into `ring_indices` [V + 1]; vertex v's ring is `2 valence(v)` long.
    pub ring_offsets: Vec<u32>,
    /// `p1 … p2n` of every vertex, concatenated [2 S].
    pub ring_indices: Vec<u32>,
    /// The vertex of each sector [S]; vertex v's sectors are `ring_offsets[v]/2 ..`.
    pub sector_vertex: Vec<u32>,
    /// Vertex of each face corner [4 F] (faces are quads).
    pub face_verts: Vec<u32>,
    /// Sector number `k` of face f at corner c [4 F], i.e. the face is `(p0, p_{2k+1}, p_{2k+2}, p_{2k+3})`
    /// of the corner's vertex.
    pub corner_sector: Vec<u32>,
    /// Edge of each face corner [4 F]: edge c of a face joins corner c and corner c+1.
    pub face_edges: Vec<u32>,
    /// End vertices of each edge [E], lower index first (the canonical direction).
    pub edge_verts: Vec<[u32; 2]>,
    /// For each edge [E], the face corner `4 f + c` whose edge runs in the canonical direction.
    pub edge_corner: Vec<u32>,
    /// Index of each face's block of 16 `h` coefficients [F], `u32::MAX` for a B-quad
    /// (all four vertices of valence 4).
    pub h_index: Vec<u32>,
    /// The faces that are not B-quads, in `h_index` order.
    pub perturbed_faces: Vec<u32>,
    /// Largest valence.
    pub max_valence: usize,
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

fn unsupported(details: Vec<String>) -> crate::error::Error {
    MeshError::Unsupported {
        construction: CONSTRUCTION,
        requirement: REQUIREMENT,
        details: details.join("; "),
    }
    .into()
}

/// Checks that `input` is a closed, oriented 2-manifold quad mesh with valences
/// `3..=MAX_VALENCE` and no holes. The error names the offending faces, edges or
/// vertices (the first few of each kind, with their count).
pub fn check_input<'a>(input: impl Into<FaceList<'a>>) -> Result<()> {
    PrepTopology::new(&input.into()).map(|_| ())
}

impl PrepTopology {
    /// Builds the ring tables, refusing input the p-rep does not cover (see [`check_input`]).
    pub fn new(input: &FaceList<'_>) -> Result<Self> {
        let nf = input.num_faces();
        let nv = input.num_vertices;
        // 1. Quads only, indices in range, no holes.
        let mut bad: Vec<String> = Vec::new();
        let mut non_quads = Vec::new();
        let mut out_of_range = Vec::new();
        for f in 0..nf {
            let (a, b) = (
                input.face_offsets[f] as usize,
                input.face_offsets[f + 1] as usize,
            );
            if b < a || b > input.face_verts.len() {
                return Err(MeshError::FaceIndexCountMismatch {
                    expected: b,
                    found: input.face_verts.len(),
                }
                .into());
            }
            if b - a != 4 {
                non_quads.push(format!("face {f} ({} vertices)", b - a));
            }
            if input.face_verts[a..b].iter().any(|&v| v as usize >= nv) {
                out_of_range.push(format!("face {f}"));
            }
        }
        if !non_quads.is_empty() {
            bad.push(listing("non-quad faces", &non_quads));
        }
        if !out_of_range.is_empty() {
            bad.push(listing(
                "faces with out-of-range vertex indices",
                &out_of_range,
            ));
        }
        if !input.holes.is_empty() {
            let h: Vec<String> = input.holes.iter().map(|h| format!("face {h}")).collect();
            bad.push(listing("faces tagged as holes", &h));
        }
        if !bad.is_empty() {
            return Err(unsupported(bad));
        }
        let fv: Vec<u32> = input.face_verts[..4 * nf].to_vec();

        // 2. Directed edges: each once, each with its opposite.
        let key = |a: u32, b: u32| ((a as u64) << 32) | b as u64;
        let mut he: HashMap<u64, u32> = HashMap::with_capacity(4 * nf);
        let mut repeated = Vec::new();
        let mut degenerate = Vec::new();
        for f in 0..nf {
            for c in 0..4 {
                let (a, b) = (fv[4 * f + c], fv[4 * f + (c + 1) % 4]);
                if a == b {
                    degenerate.push(format!("face {f} (repeats vertex {a})"));
                } else if he.insert(key(a, b), (4 * f + c) as u32).is_some() {
                    repeated.push(format!("{a}->{b}"));
                }
            }
        }
        if !degenerate.is_empty() {
            bad.push(listing("degenerate faces", &degenerate));
        }
        if !repeated.is_empty() {
            bad.push(listing(
                "non-manifold or inconsistently oriented edges (directed edge used twice)",
                &repeated,
            ));
        }
        if bad.is_empty() {
            let mut boundary: Vec<String> = Vec::new();
            for f in 0..nf {
                for c in 0..4 {
                    let (a, b) = (fv[4 * f + c], fv[4 * f + (c + 1) % 4]);
                    if !he.contains_key(&key(b, a)) {
                        boundary.push(format!("{a}-{b} (face {f})"));
                    }
                }
            }
            if !boundary.is_empty() {
                bad.push(listing("boundary edges", &boundary));
            }
        }
        if !bad.is_empty() {
            return Err(unsupported(bad));
        }

        // 3. Rings: walk around each vertex from its first corner.
        let mut first = vec![u32::MAX; nv];
        let mut incident = vec![0u32; nv];
        for (i, &v) in fv.iter().enumerate() {
            if first[v as usize] == u32::MAX {
                first[v as usize] = i as u32;
            }
            incident[v as usize] += 1;
        }
        let mut valence = vec![0u32; nv];
        let mut ring_offsets = Vec::with_capacity(nv + 1);
        let mut ring_indices = Vec::with_capacity(8 * nf);
        let mut sector_vertex = Vec::with_capacity(4 * nf);
        let mut corner_sector = vec![u32::MAX; 4 * nf];
        let mut non_manifold = Vec::new();
        let mut bad_valence = Vec::new();
        ring_offsets.push(0u32);
        for v in 0..nv {
            let start = first[v];
            if start != u32::MAX {
                let mut corner = start as usize;
                let mut k = 0u32;
                loop {
                    let (f, c) = (corner / 4, corner % 4);
                    corner_sector[corner] = k;
                    ring_indices.push(fv[4 * f + (c + 1) % 4]);
                    ring_indices.push(fv[4 * f + (c + 2) % 4]);
                    sector_vertex.push(v as u32);
                    k += 1;
                    let z = fv[4 * f + (c + 3) % 4];
                    corner = he[&key(v as u32, z)] as usize;
                    if corner == start as usize || k > incident[v] {
                        break;
                    }
                }
                if k != incident[v] {
                    non_manifold.push(format!("vertex {v} ({} faces, fan of {k})", incident[v]));
                } else if !(MIN_VALENCE..=MAX_VALENCE).contains(&(k as usize)) {
                    bad_valence.push(format!("vertex {v} (valence {k})"));
                }
                valence[v] = k;
            }
            ring_offsets.push(ring_indices.len() as u32);
        }
        if !non_manifold.is_empty() {
            bad.push(listing("non-manifold vertices", &non_manifold));
        }
        if !bad_valence.is_empty() {
            bad.push(listing("vertices with unsupported valence", &bad_valence));
        }
        if !bad.is_empty() {
            return Err(unsupported(bad));
        }

        // 4. Edges (canonical direction: lower vertex index first) and B-quad flags.
        let mut face_edges = vec![u32::MAX; 4 * nf];
        let mut edge_verts = Vec::with_capacity(2 * nf);
        let mut edge_corner = Vec::with_capacity(2 * nf);
        for i in 0..4 * nf {
            let (a, b) = (fv[i], fv[i - i % 4 + (i + 1) % 4]);
            if a < b {
                let e = edge_verts.len() as u32;
                edge_verts.push([a, b]);
                edge_corner.push(i as u32);
                face_edges[i] = e;
                face_edges[he[&key(b, a)] as usize] = e;
            }
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
            face_verts: fv,
            corner_sector,
            face_edges,
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
        let t = PrepTopology::new(&FaceList::from(&m)).unwrap();
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
