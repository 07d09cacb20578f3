//! A self-check of the incidence tables, used by tests and fuzzing.

use super::{tags, Topology};

impl Topology {
    /// Checks the structural invariants of the tables: every face edge joins its two corners
    /// and lists the face; the valences add up to twice the number of edges; boundary edges have
    /// one face; local indices point back; and at every manifold vertex the faces and edges are
    /// in ring order (edge `i` leads face `i`, edge `i + 1` trails it). Returns the first
    /// violation found.
    pub fn check_consistency(&self) -> Result<(), String> {
        let t = self;
        let ne = t.num_edges();
        for f in 0..t.num_faces() {
            let fv = t.face_vertices(f);
            for (k, &e) in t.face_edges(f).iter().enumerate() {
                let ev = t.edge_verts[e as usize];
                let (a, b) = (fv[k], fv[(k + 1) % fv.len()]);
                if ev != [a, b] && ev != [b, a] {
                    return Err(format!(
                        "face {f} edge {k}: edge {e} joins {ev:?}, not {a}-{b}"
                    ));
                }
                if !t.edge_faces(e as usize).contains(&(f as u32)) {
                    return Err(format!("edge {e} does not list face {f}"));
                }
            }
        }
        let vsum: usize = (0..t.num_vertices()).map(|v| t.valence(v)).sum();
        if vsum != 2 * ne {
            return Err(format!("valences add up to {vsum}, not 2E = {}", 2 * ne));
        }
        for e in 0..ne {
            let nf = t.edge_faces(e).len();
            if nf == 0 || t.is_boundary_edge(e) != (nf == 1) {
                return Err(format!(
                    "edge {e}: {nf} faces, boundary tag {}",
                    t.is_boundary_edge(e)
                ));
            }
            for (&f, &k) in t.edge_faces(e).iter().zip(t.edge_faces_local(e)) {
                if t.face_edges(f as usize)[k as usize] != e as u32 {
                    return Err(format!("edge {e}: local index {k} in face {f} is wrong"));
                }
            }
        }
        for v in 0..t.num_vertices() {
            let faces = t.vertex_faces(v);
            let edges = t.vertex_edges(v);
            for (&f, &k) in faces.iter().zip(t.vertex_faces_local(v)) {
                if t.face_vertices(f as usize)[k as usize] != v as u32 {
                    return Err(format!("vertex {v}: local index {k} in face {f} is wrong"));
                }
            }
            if t.vert_tags[v] & tags::V_NON_MANIFOLD != 0 || faces.is_empty() {
                continue;
            }
            let boundary = t.is_boundary_vertex(v);
            if edges.len() != faces.len() + boundary as usize {
                return Err(format!(
                    "vertex {v}: {} edges for {} faces",
                    edges.len(),
                    faces.len()
                ));
            }
            for (i, (&f, &k)) in faces.iter().zip(t.vertex_faces_local(v)).enumerate() {
                let fe = t.face_edges(f as usize);
                let n = fe.len();
                if fe[k as usize] != edges[i]
                    || fe[(k as usize + n - 1) % n] != edges[(i + 1) % edges.len()]
                {
                    return Err(format!("vertex {v}: face {i} is out of ring order"));
                }
            }
        }
        Ok(())
    }
}
