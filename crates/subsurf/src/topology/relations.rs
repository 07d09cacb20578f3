//! Building every incidence relation from face-vertex lists alone, without hashing edges.
//!
//! Edges are found by a counting sort of the face corners on their smaller end vertex, then a
//! sort of each (small) bucket on the other end. Edge numbering, edge orientation and the
//! handling of non-manifold cases follow OpenSubdiv's `Vtr::Level` exactly, so that refined
//! vertices come out in OpenSubdiv's order:
//! - edges are numbered in the order the faces first use them, oriented as first used;
//! - a degenerate edge `(v, v)` is always a new, non-manifold edge;
//! - an edge used twice by one face gets a second, non-manifold instance;
//! - an edge with more than two faces, or two faces wound the same way, is non-manifold.

use crate::util::par;
use rayon::prelude::*;

/// The relations derived from face-vertex lists (see [`super::Topology`] for each array).
#[derive(Debug, Default, Clone)]
pub(crate) struct Relations {
    pub face_edges: Vec<u32>,
    pub edge_verts: Vec<[u32; 2]>,
    pub edge_face_offsets: Vec<u32>,
    pub edge_faces: Vec<u32>,
    pub edge_face_local: Vec<u16>,
    pub edge_non_manifold: Vec<bool>,
    pub vert_face_offsets: Vec<u32>,
    pub vert_faces: Vec<u32>,
    pub vert_face_local: Vec<u16>,
    pub vert_edge_offsets: Vec<u32>,
    pub vert_edges: Vec<u32>,
    pub vert_non_manifold: Vec<bool>,
}

/// Prefix sums of `counts` into `n + 1` offsets.
pub(crate) fn offsets_from_counts(counts: &[u32]) -> Vec<u32> {
    let mut off = Vec::with_capacity(counts.len() + 1);
    let mut acc = 0u32;
    off.push(0);
    for &c in counts {
        acc += c;
        off.push(acc);
    }
    off
}

/// Counting sort of `0..keys.len()` by `keys[i] < n`, stable; returns (offsets, items).
pub(crate) fn bucket_by(keys: &[u32], n: usize) -> (Vec<u32>, Vec<u32>) {
    let mut counts = vec![0u32; n];
    for &k in keys {
        counts[k as usize] += 1;
    }
    let offsets = offsets_from_counts(&counts);
    let mut fill: Vec<u32> = offsets[..n].to_vec();
    let mut items = vec![0u32; keys.len()];
    for (i, &k) in keys.iter().enumerate() {
        let slot = &mut fill[k as usize];
        items[*slot as usize] = i as u32;
        *slot += 1;
    }
    (offsets, items)
}

/// Builds all relations. `face_offsets` has `F + 1` entries into `face_verts`.
pub(crate) fn build_relations(
    num_vertices: usize,
    face_offsets: &[u32],
    face_verts: &[u32],
) -> Relations {
    let nc = face_verts.len();
    let nf = face_offsets.len() - 1;
    let fo = |f: usize| face_offsets[f] as usize;
    // Next vertex of each corner, and the face of each corner.
    let fb = par::bounds(nf);
    let mut next_vert = vec![0u32; nc];
    let mut corner_face = vec![0u32; nc];
    par::ranges(&fb)
        .into_par_iter()
        .zip(par::split(&mut next_vert, &fb, fo))
        .zip(par::split(&mut corner_face, &fb, fo))
        .for_each(|((r, nx), cf)| {
            let base = fo(r.start);
            for f in r {
                let (s, e) = (fo(f), fo(f + 1));
                for c in s..e {
                    nx[c - base] = face_verts[if c + 1 == e { s } else { c + 1 }];
                    cf[c - base] = f as u32;
                }
            }
        });
    let mut lo = vec![0u32; nc];
    lo.par_iter_mut()
        .zip(face_verts.par_iter().zip(&next_vert))
        .with_min_len(4096)
        .for_each(|(l, (&a, &b))| *l = a.min(b));
    let (lo_off, lo_items) = bucket_by(&lo, num_vertices);
    drop(lo);

    // For each corner in bucket order (`lo_items`): the corner that created the edge instance
    // it lies on, and whether that instance is non-manifold. Buckets are independent.
    let vb = par::bounds(num_vertices);
    let lstart = |v: usize| lo_off[v] as usize;
    let mut creator_item = vec![u32::MAX; nc];
    let mut nm_item = vec![false; nc];
    par::ranges(&vb)
        .into_par_iter()
        .zip(par::split(&mut creator_item, &vb, lstart))
        .zip(par::split(&mut nm_item, &vb, lstart))
        .for_each(|((r, creator), nm)| {
            let base = lstart(r.start);
            let mut keys: Vec<u64> = Vec::new();
            // Per-instance state: (creator item, creator corner, last face, face count, first
            // vertex).
            let mut instances: Vec<(u32, u32, u32, u32, u32)> = Vec::new();
            for v in r {
                let (bs, be) = (lstart(v), lstart(v + 1));
                if bs == be {
                    continue;
                }
                // Sort the bucket on the other end vertex, then on the corner; keys hold the
                // item position (bucket order is corner order, so it sorts like the corner).
                keys.clear();
                keys.extend((bs..be).map(|q| {
                    let c = lo_items[q] as usize;
                    let hi = face_verts[c].max(next_vert[c]);
                    ((hi as u64) << 32) | q as u64
                }));
                keys.sort_unstable();
                let mut i = 0;
                while i < keys.len() {
                    let hi = (keys[i] >> 32) as u32;
                    let mut j = i;
                    while j < keys.len() && (keys[j] >> 32) as u32 == hi {
                        j += 1;
                    }
                    instances.clear();
                    for &k in &keys[i..j] {
                        let q = (k & 0xffff_ffff) as usize;
                        let c = lo_items[q];
                        let (a, b, f) = (
                            face_verts[c as usize],
                            next_vert[c as usize],
                            corner_face[c as usize],
                        );
                        let mut target = None;
                        if a != b {
                            if let Some(e) = instances.first_mut() {
                                if e.2 == f {
                                    nm[e.0 as usize - base] = true;
                                    nm[q - base] = true;
                                } else {
                                    if e.3 > 1 || a == e.4 {
                                        nm[e.0 as usize - base] = true;
                                    }
                                    e.2 = f;
                                    e.3 += 1;
                                    target = Some(e.1);
                                }
                            }
                        } else {
                            nm[q - base] = true;
                        }
                        match target {
                            Some(t) => creator[q - base] = t,
                            None => {
                                creator[q - base] = c;
                                instances.push((q as u32, c, f, 1, a));
                            }
                        }
                    }
                    i = j;
                }
            }
        });
    // Back to corner order.
    let mut creator = vec![u32::MAX; nc];
    let mut non_manifold_creator = vec![false; nc];
    for (q, &c) in lo_items.iter().enumerate() {
        creator[c as usize] = creator_item[q];
        non_manifold_creator[c as usize] = nm_item[q];
    }
    drop((creator_item, nm_item, lo_items, lo_off));

    // Number edges in the order of their creating corners.
    let mut face_edges = vec![0u32; nc];
    let mut edge_verts = Vec::with_capacity(nc / 2 + 4);
    let mut edge_non_manifold = Vec::with_capacity(nc / 2 + 4);
    for c in 0..nc {
        let cr = creator[c] as usize;
        if cr == c {
            face_edges[c] = edge_verts.len() as u32;
            edge_verts.push([face_verts[c], next_vert[c]]);
            edge_non_manifold.push(non_manifold_creator[c]);
        } else {
            face_edges[c] = face_edges[cr];
        }
    }
    let ne = edge_verts.len();

    // Edge -> faces, in face order.
    let (edge_face_offsets, ef_items) = bucket_by(&face_edges, ne);
    let edge_faces: Vec<u32> = ef_items
        .par_iter()
        .map(|&c| corner_face[c as usize])
        .collect();
    let edge_face_local: Vec<u16> = ef_items
        .par_iter()
        .map(|&c| (c - face_offsets[corner_face[c as usize] as usize]) as u16)
        .collect();

    // Vertex -> faces, in face order.
    let (vert_face_offsets, vf_items) = bucket_by(face_verts, num_vertices);
    let mut vert_faces: Vec<u32> = vf_items
        .par_iter()
        .map(|&c| corner_face[c as usize])
        .collect();
    let mut vert_face_local: Vec<u16> = vf_items
        .par_iter()
        .map(|&c| (c - face_offsets[corner_face[c as usize] as usize]) as u16)
        .collect();

    // Vertex -> edges, in edge order (both ends, twice for a degenerate edge).
    let mut ve_counts = vec![0u32; num_vertices];
    for ev in &edge_verts {
        ve_counts[ev[0] as usize] += 1;
        ve_counts[ev[1] as usize] += 1;
    }
    let vert_edge_offsets = offsets_from_counts(&ve_counts);
    let mut fill: Vec<u32> = vert_edge_offsets[..num_vertices].to_vec();
    let mut vert_edges = vec![0u32; vert_edge_offsets[num_vertices] as usize];
    for (e, ev) in edge_verts.iter().enumerate() {
        for &v in ev {
            vert_edges[fill[v as usize] as usize] = e as u32;
            fill[v as usize] += 1;
        }
    }

    let mut vert_non_manifold = vec![false; num_vertices];
    for (e, ev) in edge_verts.iter().enumerate() {
        if edge_non_manifold[e] {
            vert_non_manifold[ev[0] as usize] = true;
            vert_non_manifold[ev[1] as usize] = true;
        }
    }

    let mut rel = Relations {
        face_edges,
        edge_verts,
        edge_face_offsets,
        edge_faces,
        edge_face_local,
        edge_non_manifold,
        vert_face_offsets,
        vert_faces: Vec::new(),
        vert_face_local: Vec::new(),
        vert_edge_offsets,
        vert_edges,
        vert_non_manifold,
    };
    // Orient the fans of manifold vertices counter-clockwise; vertices are independent.
    let mut vert_edges = std::mem::take(&mut rel.vert_edges);
    let mut vert_nm = std::mem::take(&mut rel.vert_non_manifold);
    let vfo = |v: usize| rel.vert_face_offsets[v] as usize;
    let veo = |v: usize| rel.vert_edge_offsets[v] as usize;
    par::ranges(&vb)
        .into_par_iter()
        .zip(par::split(&mut vert_faces, &vb, vfo))
        .zip(par::split(&mut vert_face_local, &vb, vfo))
        .zip(par::split(&mut vert_edges, &vb, veo))
        .zip(par::split(&mut vert_nm, &vb, |v| v))
        .for_each(|((((r, vf), vl), ve), nm)| {
            let (fbase, ebase, vbase) = (vfo(r.start), veo(r.start), r.start);
            let (mut of, mut oe) = (Vec::new(), Vec::new());
            for v in r {
                if nm[v - vbase] {
                    continue;
                }
                let (fs, fe) = (vfo(v) - fbase, vfo(v + 1) - fbase);
                let (es, ee) = (veo(v) - ebase, veo(v + 1) - ebase);
                if order_fan(
                    &rel,
                    face_offsets,
                    face_verts,
                    v as u32,
                    &vf[fs..fe],
                    &ve[es..ee],
                    &mut of,
                    &mut oe,
                ) {
                    for (i, &f) in of.iter().enumerate() {
                        vf[fs + i] = f;
                        let fv = &face_verts[fo(f as usize)..fo(f as usize + 1)];
                        vl[fs + i] = fv.iter().position(|&x| x == v as u32).unwrap_or(0) as u16;
                    }
                    ve[es..ee].copy_from_slice(&oe);
                } else {
                    nm[v - vbase] = true;
                }
            }
        });
    rel.vert_edges = vert_edges;
    rel.vert_non_manifold = vert_nm;
    rel.vert_faces = vert_faces;
    rel.vert_face_local = vert_face_local;
    rel
}

/// Orders the faces and edges around manifold vertex `v` counter-clockwise (OpenSubdiv
/// `Level::orderVertexFacesAndEdges`): edge `i` leads face `i`, edge `i + 1` trails it. Returns
/// false when the incident faces do not form a single fan.
fn order_fan(
    rel: &Relations,
    face_offsets: &[u32],
    face_verts: &[u32],
    v: u32,
    v_faces: &[u32],
    v_edges: &[u32],
    out_faces: &mut Vec<u32>,
    out_edges: &mut Vec<u32>,
) -> bool {
    let f_count = v_faces.len();
    let e_count = v_edges.len();
    out_faces.clear();
    out_edges.clear();
    if f_count == 0 || e_count < 2 || e_count as isize - f_count as isize > 1 {
        return false;
    }
    let face = |f: u32| face_offsets[f as usize] as usize..face_offsets[f as usize + 1] as usize;
    let find_vert = |f: u32| {
        face_verts[face(f)]
            .iter()
            .position(|&x| x == v)
            .unwrap_or(0)
    };
    let edge_faces = |e: u32| {
        &rel.edge_faces[rel.edge_face_offsets[e as usize] as usize
            ..rel.edge_face_offsets[e as usize + 1] as usize]
    };
    let (mut f_start, mut fv_start, mut e_start);
    if e_count == f_count {
        f_start = v_faces[0];
        fv_start = find_vert(f_start);
        e_start = rel.face_edges[face(f_start).start + fv_start];
    } else {
        f_start = u32::MAX;
        fv_start = 0;
        e_start = u32::MAX;
        for &e in v_edges {
            let ef = edge_faces(e);
            if ef.len() == 1 {
                e_start = e;
                f_start = ef[0];
                fv_start = find_vert(f_start);
                if e_start == rel.face_edges[face(f_start).start + fv_start] {
                    break;
                }
            }
        }
        if f_start == u32::MAX {
            return false;
        }
    }
    out_faces.push(f_start);
    out_edges.push(e_start);
    let e_first = e_start;
    while out_edges.len() < e_count {
        let r = face(f_start);
        let n = r.len();
        let fe_next = if fv_start > 0 { fv_start - 1 } else { n - 1 };
        let e_next = rel.face_edges[r.start + fe_next];
        if e_next == e_start || e_next == e_first {
            return false;
        }
        out_edges.push(e_next);
        if out_faces.len() < f_count {
            let ef = edge_faces(e_next);
            if ef.is_empty() || (ef.len() == 1 && ef[0] == f_start) {
                return false;
            }
            f_start = if ef[0] == f_start { ef[1] } else { ef[0] };
            let r = face(f_start);
            fv_start = match rel.face_edges[r].iter().position(|&x| x == e_next) {
                Some(p) => p,
                None => return false,
            };
            out_faces.push(f_start);
        }
        e_start = e_next;
    }
    out_faces.len() == f_count
}
