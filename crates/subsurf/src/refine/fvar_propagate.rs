//! Propagation of the face-varying value topology to the next level (OpenSubdiv
//! `Vtr::FVarRefinement`): no re-analysis, only inheritance through the child numbering of
//! [`super::refine_topology`] (quad split) or [`super::refine_tri_topology`]
//! (triangle split), and the decay of semi-sharp values into creases.

use super::fvar_topology::{
    FVarTopology, E_LINEAR, E_MISMATCH, V_CREASE, V_DEP_SHARP, V_MISMATCH, V_SEMI_SHARP,
};
use crate::options::FVarLinearInterpolation as Mode;
use crate::topology::tags;
use crate::topology::Topology;

impl FVarTopology {
    /// The face-varying topology of the child level `c` of `p` (numbered as
    /// [`super::refine_topology`] or, for Loop, [`super::refine_tri_topology`] numbers it): values are numbered by child vertex, siblings
    /// first by parent sibling (vertex children) or by incident parent face (edge points on a
    /// seam). Tags are inherited, and semi-sharp values whose sharpness has decayed become
    /// creases (OpenSubdiv `FVarRefinement`).
    pub fn refine(&self, p: &Topology, c: &Topology) -> FVarTopology {
        let (nv, ne) = (p.num_vertices(), p.num_edges());
        let ncv = c.num_vertices();
        let split_faces = ChildFaces::of(p);
        let ep = split_faces.first_edge_point;
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
                counts[ep + e] = p.edge_faces(e).len().max(1) as u32;
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

        // Vertex children: same values, same tags; the same ring, but for its order.
        let mut perm: Vec<u16> = Vec::new();
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
            // Each child face takes the sibling of the parent corner it comes from, and span
            // ends (ring positions) move with the ring: the child's ring follows the parent's
            // (as OpenSubdiv builds it) except where it was rebuilt from the face lists.
            let (ps, cs) = (
                p.vert_face_offsets[v] as usize,
                c.vert_face_offsets[v] as usize,
            );
            let ring = c.vertex_faces(v);
            let pcorners = p
                .vertex_faces(v)
                .iter()
                .zip(p.vertex_faces_local(v))
                .map(|(&pf, &k)| p.face_offsets[pf as usize] + k as u32);
            perm.clear();
            for (i, pc) in pcorners.enumerate() {
                let from = |cf: &u32| split_faces.parent_corner(p, *cf) == Some(pc);
                let j = if ring.get(i).is_some_and(from) {
                    Some(i)
                } else {
                    ring.iter().position(from)
                };
                perm.push(j.map_or(i as u16, |j| j as u16));
                if let (Some(j), true) = (j, n > 1) {
                    f.vert_face_siblings[cs + j] = self.vert_face_siblings[ps + i];
                }
            }
            let at = |x: u16| perm.get(x as usize).copied().unwrap_or(x);
            for k in 0..n {
                let [a, b] = self.crease_ends[po + k];
                f.crease_ends[co + k] = [at(a), at(b)];
            }
        }

        // Edge points: one value per incident face on a seam.
        let split = V_MISMATCH | if smooth_boundaries { V_CREASE } else { 0 };
        for e in 0..ne {
            let et = self.edge_tags[e];
            if et & (E_MISMATCH | E_LINEAR) == 0 {
                continue;
            }
            let cv = ep + e;
            let co = f.vert_value_offsets[cv] as usize;
            let n = counts[cv] as usize;
            f.value_tags[co..co + n].fill(split);
            let faces = p.edge_faces(e);
            let ring = c.vertex_faces(cv);
            let cs = c.vert_face_offsets[cv] as usize;
            let parent_slot = |cf: u32| -> Option<usize> {
                faces
                    .iter()
                    .rposition(|&pf| split_faces.children(p, pf as usize).contains(&cf))
            };
            if n > 1 {
                for (i, &cf) in ring.iter().enumerate() {
                    f.vert_face_siblings[cs + i] = parent_slot(cf).unwrap_or(0) as u16;
                }
            }
            if smooth_boundaries {
                for (i, (&pf, &k)) in faces.iter().zip(p.edge_faces_local(e)).enumerate().take(n) {
                    let (s, size) = (
                        split_faces.children(p, pf as usize).start,
                        p.face_size(pf as usize),
                    );
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

/// Where the children of a parent level live in its child: the index of the first edge point
/// and the child faces of each parent face, the one at corner `k` first among them at
/// `start + k`. The quad split makes one face point per face and one child face per corner;
/// the triangle split (Loop) no face points and four children per triangle, the corner
/// children first and the middle one last.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChildFaces {
    /// Index of the child vertex of parent edge 0.
    pub first_edge_point: usize,
    /// Whether the parent is split into triangles (Loop).
    tri_split: bool,
}

impl ChildFaces {
    pub(crate) fn of(p: &Topology) -> ChildFaces {
        let tri_split = p.options.scheme == crate::options::Scheme::Loop;
        ChildFaces {
            first_edge_point: p.num_vertices() + if tri_split { 0 } else { p.num_faces() },
            tri_split,
        }
    }

    /// The parent face corner whose vertex child child face `cf` holds (`None` for the
    /// middle triangle of a triangle split).
    pub(crate) fn parent_corner(&self, p: &Topology, cf: u32) -> Option<u32> {
        if !self.tri_split {
            return Some(cf);
        }
        let (f, k) = (cf / 4, cf % 4);
        (k < 3).then(|| p.face_offsets[f as usize] + k)
    }

    /// The child faces of parent face `f`.
    pub(crate) fn children(&self, p: &Topology, f: usize) -> std::ops::Range<u32> {
        if self.tri_split {
            4 * f as u32..4 * f as u32 + 4
        } else {
            p.face_offsets[f]..p.face_offsets[f + 1]
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
