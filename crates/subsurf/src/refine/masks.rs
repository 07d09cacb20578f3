//! Stencils of one refinement level and of the limit, built from the scheme's masks.
//!
//! Face points are folded into the edge and vertex rows (a face point is the average of its
//! face's vertices), so each row refers to parent vertices only and one sparse table maps a
//! level's vertex data to the next level's.

use super::stencil::{RowBuilder, StencilTable};
use crate::options::Scheme;
use crate::rules::catmark::{edge_mask, limit_mask, vertex_mask, VertexMask, VertexNeighbourhood};
use crate::topology::Topology;
use rayon::prelude::*;

/// Builds a table of `rows` rows over `num_inputs` inputs, in parallel chunks.
pub(crate) fn build_rows<F>(rows: usize, num_inputs: usize, row: F) -> StencilTable
where
    F: Fn(usize, &mut RowBuilder, &mut Scratch) + Sync,
{
    let threads = rayon::current_num_threads().max(1);
    let chunk = rows.div_ceil(threads * 4).max(1024);
    let parts: Vec<(Vec<u32>, Vec<u32>, Vec<f32>)> = (0..rows.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut b = RowBuilder::new(num_inputs);
            let mut scratch = Scratch::default();
            let range = c * chunk..((c + 1) * chunk).min(rows);
            let mut counts = Vec::with_capacity(range.len());
            let mut idx = Vec::with_capacity(range.len() * 8);
            let mut wts = Vec::with_capacity(range.len() * 8);
            for r in range {
                row(r, &mut b, &mut scratch);
                counts.push(b.len() as u32);
                b.drain_into(&mut idx, &mut wts);
            }
            (counts, idx, wts)
        })
        .collect();
    let total: usize = parts.iter().map(|p| p.1.len()).sum();
    let mut t = StencilTable {
        offsets: Vec::with_capacity(rows + 1),
        indices: Vec::with_capacity(total),
        weights: Vec::with_capacity(total),
        num_inputs,
    };
    t.offsets.push(0);
    let mut acc = 0u32;
    for (counts, idx, wts) in parts {
        for c in counts {
            acc += c;
            t.offsets.push(acc);
        }
        t.indices.extend_from_slice(&idx);
        t.weights.extend_from_slice(&wts);
    }
    t
}

/// Per-thread scratch buffers.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    mask: VertexMask,
    child_mask: VertexMask,
    pe: Vec<f32>,
    ce: Vec<f32>,
}

fn add_face_point(p: &Topology, f: usize, w: f32, b: &mut RowBuilder) {
    let fv = p.face_vertices(f);
    let wf = w as f64 / fv.len() as f64;
    for &u in fv {
        b.add_f64(u, wf);
    }
}

/// The stencils mapping parent vertex data to child vertex data (rows in child order).
pub fn level_stencils(p: &Topology, c: &Topology) -> StencilTable {
    let (nv, nf) = (p.num_vertices(), p.num_faces());
    let opts = p.options;
    let bilinear = opts.scheme == Scheme::Bilinear;
    build_rows(c.num_vertices(), nv, |r, b, s| {
        if r < nv {
            let v = r;
            if bilinear {
                b.add(v as u32, 1.0);
                return;
            }
            let pe = p.vertex_edges(v);
            s.pe.clear();
            s.pe.extend(pe.iter().map(|&e| p.edge_sharpness[e as usize]));
            s.ce.clear();
            s.ce.extend(
                c.vertex_edges(v)
                    .iter()
                    .map(|&e| c.edge_sharpness[e as usize]),
            );
            let faces = p.vertex_faces(v);
            let h = VertexNeighbourhood {
                num_faces: faces.len(),
                parent_sharpness: p.vert_sharpness[v],
                child_sharpness: c.vert_sharpness[v],
                parent_edges: &s.pe,
                child_edges: &s.ce,
                parent_rule: p.vert_rule[v],
                child_rule: c.vert_rule[v],
            };
            vertex_mask(&h, opts.crease_method, &mut s.mask, &mut s.child_mask);
            for (i, &f) in faces.iter().enumerate() {
                if let Some(&w) = s.mask.faces.get(i) {
                    add_face_point(p, f as usize, w, b);
                }
            }
            for (i, &e) in pe.iter().enumerate() {
                if let Some(&w) = s.mask.edges.get(i) {
                    b.add(p.other_vertex(e as usize, v as u32), w);
                }
            }
            b.add(v as u32, s.mask.vertex);
        } else if r < nv + nf {
            add_face_point(p, r - nv, 1.0, b);
        } else {
            let e = r - nv - nf;
            let ev = p.edge_verts[e];
            if bilinear {
                b.add(ev[0], 0.5);
                b.add(ev[1], 0.5);
                return;
            }
            let faces = p.edge_faces(e);
            let tri = [
                faces.first().is_some_and(|&f| p.face_size(f as usize) == 3),
                faces.get(1).is_some_and(|&f| p.face_size(f as usize) == 3),
            ];
            let m = edge_mask(
                p.edge_sharpness[e],
                c.vert_rule[r],
                faces.len(),
                tri,
                opts.triangle_subdivision,
            );
            if m.face != 0.0 {
                for &f in faces {
                    add_face_point(p, f as usize, m.face, b);
                }
            }
            b.add(ev[0], m.vertex);
            b.add(ev[1], m.vertex);
        }
    })
}

/// Stencils moving each vertex of `t` to its limit position (OpenSubdiv
/// `PrimvarRefiner::Limit`): the smooth, crease or corner limit mask of its rule.
pub fn limit_stencils(t: &Topology) -> StencilTable {
    let bilinear = t.options.scheme == Scheme::Bilinear;
    build_rows(t.num_vertices(), t.num_vertices(), |v, b, s| {
        let edges = t.vertex_edges(v);
        if edges.is_empty() || bilinear {
            b.add(v as u32, 1.0);
            return;
        }
        s.pe.clear();
        s.pe.extend(edges.iter().map(|&e| t.edge_sharpness[e as usize]));
        let faces = t.vertex_faces(v);
        limit_mask(t.vert_rule[v], &s.pe, faces.len(), &mut s.mask);
        for (i, (&f, &k)) in faces.iter().zip(t.vertex_faces_local(v)).enumerate() {
            if let Some(&w) = s.mask.faces.get(i) {
                let fv = t.face_vertices(f as usize);
                b.add(fv[(k as usize + 2) % fv.len()], w);
            }
        }
        for (i, &e) in edges.iter().enumerate() {
            if let Some(&w) = s.mask.edges.get(i) {
                b.add(t.other_vertex(e as usize, v as u32), w);
            }
        }
        b.add(v as u32, s.mask.vertex);
    })
}
