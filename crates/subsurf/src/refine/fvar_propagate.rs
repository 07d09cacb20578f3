//! Propagation of the face-varying value topology to the next level (OpenSubdiv
//! `Vtr::FVarRefinement`): no re-analysis, only inheritance through the child numbering of
//! [`super::refine_topology`], and the decay of semi-sharp values into creases.

use super::fvar_topology::{
    FVarTopology, E_LINEAR, E_MISMATCH, V_CREASE, V_DEP_SHARP, V_MISMATCH, V_SEMI_SHARP,
};
use crate::options::FVarLinearInterpolation as Mode;
use crate::topology::tags;
use crate::topology::Topology;

impl FVarTopology {
    /// The face-varying topology of the child level `c` of `p` (numbered as
    /// [`super::refine_topology`] numbers it): values are numbered by child vertex, siblings
    /// first by parent sibling (vertex children) or by incident parent face (edge points on a
    /// seam). Tags are inherited, and semi-sharp values whose sharpness has decayed become
    /// creases (OpenSubdiv `FVarRefinement`).
    pub fn refine(&self, p: &Topology, c: &Topology) -> FVarTopology {
        let (nv, nf, ne) = (p.num_vertices(), p.num_faces(), p.num_edges());
        let ncv = c.num_vertices();
        let smooth_boundaries = !matches!(self.mode, Mode::All | Mode::Boundaries);
        let dependent = matches!(self.mode, Mode::CornersPlus1 | Mode::CornersPlus2);
        let mut counts = vec![1u32; ncv];
        for (v, n) in counts.iter_mut().enumerate().take(nv) {
            if self.vertex_value_tags(v)[0] & V_MISMATCH != 0 {
                *n = self.num_vertex_values(v) as u32;
            }
        }
        for e in 0..ne {
            if self.edge_tags[e] & E_MISMATCH != 0 {
                counts[nv + nf + e] = p.edge_faces(e).len().max(1) as u32;
            }
        }
        let offsets = crate::topology::offsets_from_counts(&counts);
        let total = offsets[ncv] as usize;
        let mut f = FVarTopology {
            mode: self.mode,
            num_values: total,
            corner_values: Vec::new(),
            vert_value_offsets: offsets,
            vert_values: (0..total as u32).collect(),
            vert_face_siblings: vec![0; c.vert_faces.len()],
            value_tags: vec![0; total],
            crease_ends: vec![[0, 0]; total],
            edge_tags: vec![0; c.num_edges()],
        };

        // Vertex children: same values, same ring, same tags.
        for v in 0..nv {
            let n = counts[v] as usize;
            if self.vertex_value_tags(v)[0] & V_MISMATCH == 0 {
                continue;
            }
            let (po, co) = (
                self.vert_value_offsets[v] as usize,
                f.vert_value_offsets[v] as usize,
            );
            f.value_tags[co..co + n].copy_from_slice(&self.value_tags[po..po + n]);
            f.crease_ends[co..co + n].copy_from_slice(&self.crease_ends[po..po + n]);
            if n > 1 {
                let (ps, cs) = (
                    p.vert_face_offsets[v] as usize,
                    c.vert_face_offsets[v] as usize,
                );
                let k = p.vertex_faces(v).len();
                f.vert_face_siblings[cs..cs + k]
                    .copy_from_slice(&self.vert_face_siblings[ps..ps + k]);
            }
        }

        // Edge points: one value per incident face on a seam.
        let split = V_MISMATCH | if smooth_boundaries { V_CREASE } else { 0 };
        for e in 0..ne {
            let et = self.edge_tags[e];
            if et & (E_MISMATCH | E_LINEAR) == 0 {
                continue;
            }
            let cv = nv + nf + e;
            let co = f.vert_value_offsets[cv] as usize;
            let n = counts[cv] as usize;
            f.value_tags[co..co + n].fill(split);
            let faces = p.edge_faces(e);
            let ring = c.vertex_faces(cv);
            let cs = c.vert_face_offsets[cv] as usize;
            let parent_slot = |cf: u32| -> Option<usize> {
                faces.iter().rposition(|&pf| {
                    let r = p.face_offsets[pf as usize]..p.face_offsets[pf as usize + 1];
                    r.contains(&cf)
                })
            };
            if n > 1 {
                for (i, &cf) in ring.iter().enumerate() {
                    f.vert_face_siblings[cs + i] = parent_slot(cf).unwrap_or(0) as u16;
                }
            }
            if smooth_boundaries {
                for (i, (&pf, &k)) in faces.iter().zip(p.edge_faces_local(e)).enumerate().take(n) {
                    let (s, size) = (p.face_offsets[pf as usize], p.face_size(pf as usize));
                    let kn = if k as usize + 1 == size {
                        0
                    } else {
                        k as u32 + 1
                    };
                    let find = |cf: u32| ring.iter().position(|&x| x == cf).unwrap_or(0) as u16;
                    f.crease_ends[co + i] = [find(s + kn), find(s + k as u32)];
                }
            }
        }

        if smooth_boundaries {
            f.reclassify_semi_sharp(p, c, dependent);
        }

        // Corner values from the siblings.
        f.corner_values = c
            .face_verts
            .iter()
            .map(|&v| f.vert_value_offsets[v as usize])
            .collect();
        for v in 0..ncv {
            if counts[v] > 1 {
                let faces = c.vertex_faces(v);
                let local = c.vertex_faces_local(v);
                let sib = &f.vert_face_siblings[c.vert_face_offsets[v] as usize..];
                for i in 0..faces.len() {
                    let corner = c.face_offsets[faces[i] as usize] as usize + local[i] as usize;
                    f.corner_values[corner] += sib[i] as u32;
                }
            }
        }

        // Edge tags: edges inside parent faces are continuous; halves of edges inherit.
        let nc = p.num_corners();
        for e in 0..ne {
            f.edge_tags[nc + 2 * e] = self.edge_tags[e];
            f.edge_tags[nc + 2 * e + 1] = self.edge_tags[e];
        }
        f
    }

    /// Semi-sharp values of vertex children whose spans are no longer semi-sharp become
    /// creases (OpenSubdiv `FVarRefinement::reclassifySemisharpValues`).
    fn reclassify_semi_sharp(&mut self, p: &Topology, c: &Topology, dependent: bool) {
        for v in 0..p.num_vertices() {
            let o = self.vert_value_offsets[v] as usize;
            let n = self.num_vertex_values(v);
            if self.value_tags[o] & V_MISMATCH == 0 {
                continue;
            }
            let pt = p.vert_tags[v];
            if pt & (tags::V_SEMI_SHARP | tags::V_SEMI_SHARP_EDGES) == 0 {
                continue;
            }
            let ct = c.vert_tags[v];
            if ct & (tags::V_SEMI_SHARP | tags::V_INF_SHARP) != 0 {
                continue;
            }
            let to_crease = |t: &mut u8| {
                if *t & V_SEMI_SHARP != 0 {
                    *t = V_MISMATCH | V_CREASE;
                }
            };
            if ct & tags::V_SEMI_SHARP_EDGES == 0 {
                self.value_tags[o..o + n].iter_mut().for_each(to_crease);
                continue;
            }
            let edges = c.vertex_edges(v);
            for j in 0..n {
                let t = self.value_tags[o + j];
                if t & V_SEMI_SHARP == 0 || t & V_DEP_SHARP != 0 {
                    continue;
                }
                let [a, b] = self.crease_ends[o + j];
                let still = span_interior_edges(a, b, edges.len())
                    .any(|k| c.edge_tags[edges[k] as usize] & tags::E_SEMI_SHARP != 0);
                if !still {
                    self.value_tags[o + j] = V_MISMATCH | V_CREASE;
                }
            }
            if n == 2 && dependent {
                let (t0, t1) = (self.value_tags[o], self.value_tags[o + 1]);
                if t0 & V_DEP_SHARP != 0 && t1 & V_SEMI_SHARP == 0 {
                    self.value_tags[o] &= !V_DEP_SHARP;
                } else if t1 & V_DEP_SHARP != 0 && t0 & V_SEMI_SHARP == 0 {
                    self.value_tags[o + 1] &= !V_DEP_SHARP;
                }
            }
        }
    }
}

/// Ring positions of the edges strictly inside a span running from face `a` to face `b`
/// (wrapping around a ring of `n` edges when `b < a`).
pub(crate) fn span_interior_edges(a: u16, b: u16, n: usize) -> impl Iterator<Item = usize> {
    let (a, b) = (a as usize, b as usize);
    let (first, second) = if b > a {
        (a + 1..b + 1, 0..0)
    } else if a > b {
        (a + 1..n, 0..b + 1)
    } else {
        (0..0, 0..0)
    };
    first.chain(second)
}
