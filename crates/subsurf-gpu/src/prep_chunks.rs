//! The p-rep split into sub-problems that each fit the adapter's storage bindings.
//!
//! A sub-problem is a contiguous range of faces with everything its three kernels read,
//! renumbered locally: its CORE vertices (the faces' corners, whose vertex data it computes)
//! followed by its HALO (the other vertices of the core vertices' rings, positions only), the
//! core vertices' rings and sectors, and its faces' h blocks. Every table of a sub-problem is
//! bound whole, and the partition makes each one fit `max_binding_bytes`, so the p-rep runs at
//! any size the adapter's buffers can hold; a mesh that fits is one sub-problem whose local
//! numbering is the global one.
//!
//! Each tessellation sample is written by exactly one sub-problem: a vertex's by its OWNER (the
//! sub-problem of the first face that has it as a corner; vertices of no face belong to the
//! first), an edge's by the sub-problem of the face running along it in its canonical
//! direction (as in the unsplit mesh), a face's by its own. Owned vertices come first in the
//! local numbering. The vertex buffer holds, per sub-problem in order, its owned vertices, its
//! owned edges' samples and its faces' samples ([`PrepChunks::region_len`]); with one
//! sub-problem that is the layout of `PrepPatches::tessellate`, and in general
//! [`PrepChunks::canonical_slots`] maps it there. Seam samples are still computed once, so the
//! tessellation stays watertight bit for bit.

use crate::cpu::prep_eval_grid::FORWARD;
use crate::cpu::prep_vertex_pass::valence_consts;
use crate::error::{GpuError, Result};
use crate::prep::PrepTables;
use crate::shared::PrepConfig;
use std::ops::Range;
use subsurf::prep::{PrepTopology, Tessellation};

const NONE: u32 = u32::MAX;

/// Sizes of one sub-problem's tables, in elements.
#[derive(Debug, Clone, Copy, Default)]
struct Load {
    /// Core + halo vertices.
    local: u64,
    core: u64,
    sectors: u64,
    faces: u64,
    perturbed: u64,
    edges: u64,
}

impl Load {
    /// Bytes of the largest table (each is one binding).
    fn largest_binding(&self) -> u64 {
        [
            12 * self.local,                         // positions
            4 * (self.core + 1),                     // ring offsets
            8 * self.sectors,                        // rings
            12 * (3 * self.core + 2 * self.sectors), // vertex data
            192 * (self.faces + self.perturbed),     // patch data
            32 * self.faces,                         // corner slots (8 words per face)
            4 * self.edges,                          // edge corners
        ]
        .into_iter()
        .max()
        .unwrap_or(0)
    }
}

/// The sub-problems of a p-rep, with the global tables their outputs are placed by.
#[derive(Debug, Clone)]
pub struct PrepChunks {
    /// One table set per sub-problem, in face order.
    pub chunks: Vec<PrepTables>,
    /// Global vertex count `V`.
    pub num_vertices: usize,
    /// Global edge count `E`.
    pub num_edges: usize,
    /// Global face count `F`.
    pub num_faces: usize,
    ring_offsets: Vec<u32>,
    face_verts: Vec<u32>,
    face_edges: Vec<u32>,
    num_perturbed: usize,
}

fn ring(t: &PrepTopology, v: u32) -> &[u32] {
    let v = v as usize;
    &t.ring_indices()[t.ring_offsets()[v] as usize..t.ring_offsets()[v + 1] as usize]
}

impl PrepChunks {
    /// Splits `t` into sub-problems whose tables each fit `max_binding_bytes` (one
    /// sub-problem, numbered as `t`, when the whole mesh fits). A face that does not fit on
    /// its own (with its corners' rings) is [`GpuError::TooLarge`].
    pub fn new(t: &PrepTopology, max_binding_bytes: u64) -> Result<Self> {
        let too_big =
            |what: &str| GpuError::BufferMismatch(format!("{what} exceed 32-bit indexing"));
        let s = t.sector_vertex().len();
        if 3 * (3 * t.num_vertices() + 2 * s) >= u32::MAX as usize {
            return Err(too_big("vertex data"));
        }
        if 3 * 16 * (t.num_faces() + t.perturbed_faces().len()) >= u32::MAX as usize {
            return Err(too_big("patch coefficients"));
        }
        let whole = Load {
            local: t.num_vertices() as u64,
            core: t.num_vertices() as u64,
            sectors: s as u64,
            faces: t.num_faces() as u64,
            perturbed: t.perturbed_faces().len() as u64,
            edges: t.num_edges() as u64,
        };
        if whole.largest_binding() <= max_binding_bytes {
            return Ok(Self::whole(t));
        }
        let ranges = partition(t, max_binding_bytes)?;
        let mut owner = vec![0u32; t.num_vertices()];
        let mut seen = vec![false; t.num_vertices()];
        for (k, r) in ranges.iter().enumerate() {
            for &v in &t.face_verts()[4 * r.start..4 * r.end] {
                if !seen[v as usize] {
                    seen[v as usize] = true;
                    owner[v as usize] = k as u32;
                }
            }
        }
        let consts = valence_consts(t.max_valence().max(3));
        let mut local_id = vec![NONE; t.num_vertices()];
        let chunks = ranges
            .iter()
            .enumerate()
            .map(|(k, r)| build_chunk(t, k as u32, r.clone(), &owner, &mut local_id, &consts))
            .collect();
        Ok(Self::with_chunks(t, chunks))
    }

    /// `chunks` with the global tables of `t` their outputs are placed by.
    fn with_chunks(t: &PrepTopology, chunks: Vec<PrepTables>) -> Self {
        Self {
            chunks,
            num_vertices: t.num_vertices(),
            num_edges: t.num_edges(),
            num_faces: t.num_faces(),
            ring_offsets: t.ring_offsets().to_vec(),
            face_verts: t.face_verts().to_vec(),
            face_edges: t.face_edges().to_vec(),
            num_perturbed: t.perturbed_faces().len(),
        }
    }

    /// The whole mesh as one sub-problem, numbered as the mesh.
    fn whole(t: &PrepTopology) -> Self {
        let iota = |n: usize| (0..n as u32).collect::<Vec<_>>();
        let tables = PrepTables {
            config: PrepConfig {
                num_vertices: t.num_vertices() as u32,
                num_sectors: t.sector_vertex().len() as u32,
                num_faces: t.num_faces() as u32,
                num_edges: t.num_edges() as u32,
                owned_vertices: t.num_vertices() as u32,
                ..Default::default()
            },
            ring_offsets: t.ring_offsets().to_vec(),
            ring_indices: t.ring_indices().to_vec(),
            valence_consts: valence_consts(t.max_valence().max(3)),
            face_verts: t.face_verts().to_vec(),
            corner_sector: t.corner_sector().to_vec(),
            edge_corner: t.edge_corner().to_vec(),
            h_index: t.h_index().to_vec(),
            num_perturbed: t.perturbed_faces().len(),
            vertex_ids: iota(t.num_vertices()),
            edge_ids: iota(t.num_edges()),
            first_face: 0,
            first_h: 0,
        };
        Self::with_chunks(t, vec![tables])
    }

    /// Positions of sub-problem `k`'s local vertices (core, then halo).
    pub fn gather_positions(&self, k: usize, positions: &[[f32; 3]]) -> Vec<[f32; 3]> {
        self.chunks[k]
            .vertex_ids
            .iter()
            .map(|&v| positions[v as usize])
            .collect()
    }

    /// Vertices of an `n×n` tessellation (all sub-problems' regions).
    pub fn grid_vertices(&self, n: usize) -> usize {
        (0..self.chunks.len()).map(|k| self.region_len(k, n)).sum()
    }

    /// Vertices of sub-problem `k`'s region of the vertex buffer: owned vertices, `n − 2`
    /// per owned edge, `(n − 2)²` per face.
    pub fn region_len(&self, k: usize, n: usize) -> usize {
        let c = &self.chunks[k].config;
        let m = n - 2;
        c.owned_vertices as usize + c.num_edges as usize * m + c.num_faces as usize * m * m
    }

    /// Slot of sub-problem `k`'s first face-interior sample, given its region's `start`
    /// (after its owned vertices' and owned edges' samples).
    pub fn face_slot_base(&self, k: usize, start: usize, n: usize) -> usize {
        let c = &self.chunks[k].config;
        start + c.owned_vertices as usize + c.num_edges as usize * (n - 2)
    }

    /// First slot of each sub-problem's region.
    pub fn region_starts(&self, n: usize) -> Vec<usize> {
        let mut start = 0;
        (0..self.chunks.len())
            .map(|k| {
                let s = start;
                start += self.region_len(k, n);
                s
            })
            .collect()
    }

    /// Per sub-problem, the `corner_slots` table of `prep_eval_grid`'s `indices` entry:
    /// per local face, the slots of its 4 corner vertices, then of the first sample of its 4
    /// edges ([`FORWARD`] set when the face runs along the edge's canonical direction).
    pub fn corner_slots(&self, n: usize) -> Vec<Vec<u32>> {
        let m = n - 2;
        let starts = self.region_starts(n);
        let mut vertex_slot = vec![0u32; self.num_vertices];
        let mut edge_slot = vec![0u32; self.num_edges];
        for (ch, &start) in self.chunks.iter().zip(&starts) {
            let owned = ch.config.owned_vertices as usize;
            for (i, &v) in ch.vertex_ids[..owned].iter().enumerate() {
                vertex_slot[v as usize] = (start + i) as u32;
            }
            for (r, &e) in ch.edge_ids.iter().enumerate() {
                edge_slot[e as usize] = (start + owned + r * m) as u32;
            }
        }
        self.chunks
            .iter()
            .map(|ch| {
                let faces = ch.first_face as usize..ch.first_face as usize + ch.h_index.len();
                let mut out = Vec::with_capacity(8 * faces.len());
                for f in faces {
                    let fv = &self.face_verts[4 * f..4 * f + 4];
                    out.extend(fv.iter().map(|&v| vertex_slot[v as usize]));
                    out.extend((0..4).map(|c| {
                        let e = self.face_edges[4 * f + c] as usize;
                        let forward = if fv[c] < fv[(c + 1) % 4] { FORWARD } else { 0 };
                        edge_slot[e] | forward
                    }));
                }
                out
            })
            .collect()
    }

    /// For each slot of the `n×n` vertex buffer, its index in the layout of
    /// `PrepPatches::tessellate` (`V` vertices, `n − 2` per edge, `(n − 2)²` per face).
    pub fn canonical_slots(&self, n: usize) -> Vec<u32> {
        let m = n - 2;
        let (nv, ne) = (self.num_vertices, self.num_edges);
        let mut out = Vec::with_capacity(self.grid_vertices(n));
        for ch in &self.chunks {
            let owned = ch.config.owned_vertices as usize;
            out.extend_from_slice(&ch.vertex_ids[..owned]);
            for &e in &ch.edge_ids {
                out.extend((0..m).map(|s| (nv + e as usize * m + s) as u32));
            }
            let f0 = nv + ne * m + ch.first_face as usize * m * m;
            out.extend((f0..f0 + ch.h_index.len() * m * m).map(|s| s as u32));
        }
        out
    }

    /// A tessellation in the vertex-buffer layout, re-laid as `PrepPatches::tessellate`'s.
    pub fn to_canonical(&self, n: usize, t: Tessellation<f32>) -> Tessellation<f32> {
        if self.chunks.len() == 1 {
            return t;
        }
        let canon = self.canonical_slots(n);
        let mut positions = vec![[0.0f32; 3]; t.positions.len()];
        let mut normals = vec![[0.0f32; 3]; t.normals.len()];
        for (slot, &c) in canon.iter().enumerate() {
            positions[c as usize] = t.positions[slot];
            normals[c as usize] = t.normals[slot];
        }
        let triangles = t
            .triangles
            .iter()
            .map(|tri| tri.map(|i| canon[i as usize]))
            .collect();
        Tessellation {
            positions,
            normals,
            triangles,
        }
    }

    /// The sub-problems' pass outputs `(vertex_data, patch_data)` combined into the global
    /// layouts of [`PrepConfig`] (each vertex's data from its owner).
    pub fn to_canonical_coefficients(
        &self,
        per_chunk: &[(Vec<f32>, Vec<f32>)],
    ) -> (Vec<f32>, Vec<f32>) {
        let nv = self.num_vertices;
        let s = self.ring_offsets[nv] as usize / 2;
        let mut vd = vec![0.0f32; 3 * (3 * nv + 2 * s)];
        let mut pd = vec![0.0f32; 3 * 16 * (self.num_faces + self.num_perturbed)];
        let put = |dst: &mut [f32], d: usize, src: &[f32], s: usize| {
            dst[3 * d..3 * d + 3].copy_from_slice(&src[3 * s..3 * s + 3]);
        };
        for (ch, (cvd, cpd)) in self.chunks.iter().zip(per_chunk) {
            let (nc, cs) = (
                ch.config.num_vertices as usize,
                ch.config.num_sectors as usize,
            );
            for i in 0..ch.config.owned_vertices as usize {
                let g = ch.vertex_ids[i] as usize;
                for a in 0..3 {
                    put(&mut vd, a * nv + g, cvd, a * nc + i);
                }
                let gs = self.ring_offsets[g] as usize / 2;
                let ls = ch.ring_offsets[i] as usize / 2;
                let n = (self.ring_offsets[g + 1] - self.ring_offsets[g]) as usize / 2;
                for j in 0..n {
                    put(&mut vd, 3 * nv + gs + j, cvd, 3 * nc + ls + j);
                    put(&mut vd, 3 * nv + s + gs + j, cvd, 3 * nc + cs + ls + j);
                }
            }
            let (f0, nf) = (ch.first_face as usize, ch.h_index.len());
            pd[48 * f0..48 * (f0 + nf)].copy_from_slice(&cpd[..48 * nf]);
            let h0 = 48 * (self.num_faces + ch.first_h as usize);
            let hl = 48 * ch.num_perturbed;
            pd[h0..h0 + hl].copy_from_slice(&cpd[48 * nf..48 * nf + hl]);
        }
        (vd, pd)
    }

    /// CPU twin of `GpuPrep::update` followed by `download_coefficients`: every
    /// sub-problem's passes, combined into the global layouts.
    pub fn run_passes_cpu(&self, positions: &[[f32; 3]]) -> (Vec<f32>, Vec<f32>) {
        let per: Vec<_> = (0..self.chunks.len())
            .map(|k| self.chunks[k].run_passes_cpu(&self.gather_positions(k, positions)))
            .collect();
        self.to_canonical_coefficients(&per)
    }

    /// CPU twin of `GpuPrep::update`, `eval_grid` and `GpuGrid::download`: the `n×n`
    /// watertight tessellation in `PrepPatches::tessellate`'s layout.
    pub fn tessellate_cpu(&self, positions: &[[f32; 3]], n: usize) -> Tessellation<f32> {
        let n = n.max(2);
        let starts = self.region_starts(n);
        let slots = self.corner_slots(n);
        let mut vertices = vec![0.0f32; 6 * self.grid_vertices(n)];
        let mut indices = Vec::new();
        for (k, ch) in self.chunks.iter().enumerate() {
            let (vd, pd) = ch.run_passes_cpu(&self.gather_positions(k, positions));
            let region = &mut vertices[6 * starts[k]..6 * (starts[k] + self.region_len(k, n))];
            ch.eval_region_cpu(n, &vd, &pd, region);
            let base = self.face_slot_base(k, starts[k], n) as u32;
            indices.extend(ch.indices_cpu(n, &slots[k], base));
        }
        self.to_canonical(n, crate::prep::unpack(&vertices, &indices))
    }
}

/// Face ranges of the sub-problems: greedy in face order, each as large as the limit allows.
fn partition(t: &PrepTopology, limit: u64) -> Result<Vec<Range<usize>>> {
    let nf = t.num_faces();
    let mut core = vec![NONE; t.num_vertices()];
    let mut local = vec![NONE; t.num_vertices()];
    let mut load = Load::default();
    // Vertices of no face: the first sub-problem's.
    for v in 0..t.num_vertices() {
        if t.valence()[v] == 0 {
            core[v] = 0;
            local[v] = 0;
            load.core += 1;
            load.local += 1;
        }
    }
    let (mut k, mut start) = (0u32, 0usize);
    let mut ranges = Vec::new();
    let (mut added_core, mut added_local) = (Vec::new(), Vec::new());
    for f in 0..nf {
        loop {
            let before = load;
            added_core.clear();
            added_local.clear();
            for &v in &t.face_verts()[4 * f..4 * f + 4] {
                if core[v as usize] == k {
                    continue;
                }
                core[v as usize] = k;
                added_core.push(v);
                load.core += 1;
                load.sectors += u64::from(t.valence()[v as usize]);
                for &u in std::iter::once(&v).chain(ring(t, v)) {
                    if local[u as usize] != k {
                        local[u as usize] = k;
                        added_local.push(u);
                        load.local += 1;
                    }
                }
            }
            load.faces += 1;
            load.perturbed += u64::from(t.h_index()[f] != NONE);
            load.edges += (0..4)
                .filter(|&c| {
                    t.edge_corner()[t.face_edges()[4 * f + c] as usize] as usize == 4 * f + c
                })
                .count() as u64;
            let needed = load.largest_binding();
            if needed <= limit {
                break;
            }
            if before.faces == 0 {
                return Err(GpuError::TooLarge {
                    what: "one p-rep face with its corners' rings",
                    needed,
                    limit,
                });
            }
            for &v in &added_core {
                core[v as usize] = NONE;
            }
            for &u in &added_local {
                local[u as usize] = NONE;
            }
            ranges.push(start..f);
            (start, k, load) = (f, k + 1, Load::default());
        }
    }
    ranges.push(start..nf);
    Ok(ranges)
}

/// The tables of sub-problem `k` (faces `faces`); `local_id` is all [`NONE`] on entry and
/// on return.
fn build_chunk(
    t: &PrepTopology,
    k: u32,
    faces: Range<usize>,
    owner: &[u32],
    local_id: &mut [u32],
    consts: &[f32],
) -> PrepTables {
    const MARK: u32 = NONE - 1;
    let mut core: Vec<u32> = Vec::new();
    if k == 0 {
        core.extend((0..t.num_vertices() as u32).filter(|&v| t.valence()[v as usize] == 0));
    }
    for &v in &t.face_verts()[4 * faces.start..4 * faces.end] {
        if local_id[v as usize] == NONE {
            local_id[v as usize] = MARK;
            core.push(v);
        }
    }
    core.sort_unstable();
    let (mut vertex_ids, other): (Vec<u32>, Vec<u32>) =
        core.iter().partition(|&&v| owner[v as usize] == k);
    let owned = vertex_ids.len();
    vertex_ids.extend(other);
    let nc = vertex_ids.len();
    let mut halo = Vec::new();
    for &v in &vertex_ids {
        for &u in ring(t, v) {
            if local_id[u as usize] == NONE {
                local_id[u as usize] = MARK;
                halo.push(u);
            }
        }
    }
    halo.sort_unstable();
    vertex_ids.extend(halo);
    for (i, &v) in vertex_ids.iter().enumerate() {
        local_id[v as usize] = i as u32;
    }
    let mut ring_offsets = Vec::with_capacity(nc + 1);
    ring_offsets.push(0u32);
    let mut ring_indices = Vec::new();
    for &v in &vertex_ids[..nc] {
        ring_indices.extend(ring(t, v).iter().map(|&u| local_id[u as usize]));
        ring_offsets.push(ring_indices.len() as u32);
    }
    let f0 = faces.start;
    let face_verts = t.face_verts()[4 * f0..4 * faces.end]
        .iter()
        .map(|&v| local_id[v as usize])
        .collect();
    let mut num_perturbed = 0u32;
    let h_index: Vec<u32> = t.h_index()[faces.clone()]
        .iter()
        .map(|&h| {
            if h == NONE {
                NONE
            } else {
                num_perturbed += 1;
                num_perturbed - 1
            }
        })
        .collect();
    let first_h = t.h_index()[faces.clone()]
        .iter()
        .find(|&&h| h != NONE)
        .copied()
        .unwrap_or(0);
    let mut edges: Vec<(u32, u32)> = Vec::new();
    for f in faces.clone() {
        for c in 0..4 {
            let e = t.face_edges()[4 * f + c];
            if t.edge_corner()[e as usize] as usize == 4 * f + c {
                edges.push((e, (4 * (f - f0) + c) as u32));
            }
        }
    }
    edges.sort_unstable();
    for &v in &vertex_ids {
        local_id[v as usize] = NONE;
    }
    PrepTables {
        config: PrepConfig {
            num_vertices: nc as u32,
            num_sectors: ring_indices.len() as u32 / 2,
            num_faces: faces.len() as u32,
            num_edges: edges.len() as u32,
            owned_vertices: owned as u32,
            ..Default::default()
        },
        ring_offsets,
        ring_indices,
        valence_consts: consts.to_vec(),
        face_verts,
        corner_sector: t.corner_sector()[4 * f0..4 * faces.end].to_vec(),
        edge_corner: edges.iter().map(|e| e.1).collect(),
        h_index,
        num_perturbed: num_perturbed as usize,
        vertex_ids,
        edge_ids: edges.iter().map(|e| e.0).collect(),
        first_face: f0 as u32,
        first_h,
    }
}
