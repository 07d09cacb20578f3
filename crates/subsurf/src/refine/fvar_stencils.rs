//! Per-level stencils for face-varying data (UVs), matching OpenSubdiv's
//! `PrimvarRefiner::InterpolateFaceVarying`.
//!
//! Each table maps the values of one level ([`FVarTopology::num_values`] inputs) to the
//! values of the next, one row per child value, face points expanded so that every row refers
//! to parent values only:
//!
//! - a face point's value is the average of its face's corner values (Loop makes none);
//! - an edge point off a seam uses the edge's Catmull-Clark mask (smooth, crease or the
//!   semi-sharp blend), on the values at its ends and the face points of its faces, or its
//!   Loop mask, on the values at its ends and the value opposite the edge in each triangle;
//!   on a seam (or a linear boundary) each of its values is the midpoint of the edge's end
//!   values in the matching face;
//! - a vertex child whose values follow the vertex uses the vertex's own mask (the same
//!   masks as positions, Catmull-Clark or Loop, over the values across its edges); otherwise each value is copied
//!   (a corner) or takes the crease rule `3/4 v + 1/8 (a + b)` along the seam, blended with
//!   the corner by the fractional weight while semi-sharp features decay (DeRose, Kass &
//!   Truong 1998).
//!
//! In the `All` mode (and for the bilinear scheme) every rule is linear.

use super::fvar_propagate::{span_interior_edges, ChildFaces};
use super::fvar_topology::{FVarTopology, V_CREASE, V_DEP_SHARP, V_MISMATCH, V_SEMI_SHARP};
use super::stencil::StencilTable;
use super::Refiner;
use crate::error::{MeshError, Result};
use crate::mesh::FaceVarying;
use crate::options::{FVarLinearInterpolation, Scheme};
use crate::rules::catmark::edge_mask;
use crate::rules::crease::fractional_weight_at_vertex;
use crate::rules::r#loop::edge_mask as loop_edge_mask;
use crate::topology::Topology;
use rayon::prelude::*;

/// The table mapping values of level `p` (topology `pf`) to values of its child `c` (`cf`),
/// built in parallel over ranges of child vertices.
pub fn fvar_level_stencils(
    p: &Topology,
    c: &Topology,
    pf: &FVarTopology,
    cf: &FVarTopology,
) -> StencilTable {
    let ncv = c.num_vertices();
    let threads = rayon::current_num_threads().max(1);
    let chunk = ncv.div_ceil(threads * 4).max(2048);
    let parts: Vec<Part> = (0..ncv.div_ceil(chunk))
        .into_par_iter()
        .map(|k| {
            let mut s = Scratch::default();
            let mut part = Part::default();
            for cv in k * chunk..((k + 1) * chunk).min(ncv) {
                vertex_rows(p, c, pf, cf, cv, &mut s, &mut part);
            }
            part
        })
        .collect();
    let total: usize = parts.iter().map(|q| q.idx.len()).sum();
    let mut t = StencilTable {
        offsets: Vec::with_capacity(cf.num_values + 1),
        indices: Vec::with_capacity(total),
        weights: Vec::with_capacity(total),
        num_inputs: pf.num_values,
    };
    t.offsets.push(0);
    for q in parts {
        let base = t.indices.len() as u32;
        t.offsets.extend(q.ends.iter().map(|&e| base + e));
        t.indices.extend_from_slice(&q.idx);
        t.weights.extend_from_slice(&q.wts);
    }
    debug_assert_eq!(t.num_rows(), cf.num_values);
    t
}

/// Rows of one chunk of child vertices: row ends (relative to the chunk), inputs, weights.
#[derive(Debug, Default)]
struct Part {
    ends: Vec<u32>,
    idx: Vec<u32>,
    wts: Vec<f32>,
}

/// One row being accumulated in double precision, repeated inputs merged (rows are short).
#[derive(Debug, Default)]
struct Row {
    idx: Vec<u32>,
    wts: Vec<f64>,
}

impl Row {
    fn add(&mut self, i: u32, w: f32) {
        self.add_f64(i, w as f64);
    }

    fn add_f64(&mut self, i: u32, w: f64) {
        match self.idx.iter().position(|&x| x == i) {
            Some(k) => self.wts[k] += w,
            None => {
                self.idx.push(i);
                self.wts.push(w);
            }
        }
    }

    fn end_row(&mut self, out: &mut Part) {
        out.idx.extend_from_slice(&self.idx);
        out.wts.extend(self.wts.iter().map(|&w| w as f32));
        out.ends.push(out.idx.len() as u32);
        self.idx.clear();
        self.wts.clear();
    }
}

/// Per-thread buffers.
#[derive(Debug, Default)]
struct Scratch {
    row: Row,
    masks: super::masks::Scratch,
    pe: Vec<f32>,
    ce: Vec<f32>,
    edge_values: Vec<u32>,
}

/// Appends the rows of the values of child vertex `cv` (one per sibling).
fn vertex_rows(
    p: &Topology,
    c: &Topology,
    pf: &FVarTopology,
    cf: &FVarTopology,
    cv: usize,
    s: &mut Scratch,
    out: &mut Part,
) {
    let nv = p.num_vertices();
    let ep = ChildFaces::of(p).first_edge_point;
    let opts = p.options;
    let tri_split = opts.scheme == Scheme::Loop;
    let linear = pf.mode == FVarLinearInterpolation::All || opts.scheme == Scheme::Bilinear;
    let add_face = |b: &mut Row, f: usize, w: f64| {
        let (st, n) = (p.face_offsets[f] as usize, p.face_size(f));
        for &x in &pf.corner_values[st..st + n] {
            b.add_f64(x, w / n as f64);
        }
    };
    let mut row = std::mem::take(&mut s.row);
    let b = &mut row;
    let ctags = cf.vertex_value_tags(cv);
    let matches = ctags[0] & V_MISMATCH == 0;
    if cv < nv {
        let v = cv;
        let pvals = pf.vertex_values(v);
        if p.vertex_faces(v).is_empty() {
            // A vertex without faces carries no face-varying value: an empty row.
            b.end_row(out);
        } else if matches && linear {
            b.add(pvals[0], 1.0);
            b.end_row(out);
        } else if matches {
            let faces = p.vertex_faces(v);
            // Loop's mask has no face weights (no face points): the face loop adds nothing.
            let mask = if tri_split {
                super::loop_masks::loop_vertex_mask(
                    p,
                    super::last_level::ChildSharpness::of_child(p, c),
                    v,
                    &mut s.masks,
                )
            } else {
                s.masks.vertex_mask_at(p, c, v)
            };
            for (&f, &w) in faces.iter().zip(&mask.faces) {
                if w != 0.0 {
                    add_face(b, f as usize, w as f64);
                }
            }
            if !mask.edges.is_empty() {
                pf.vertex_edge_values(p, v, &mut s.edge_values);
                for (&x, &w) in s.edge_values.iter().zip(&mask.edges) {
                    if w != 0.0 {
                        b.add(x, w);
                    }
                }
            }
            b.add(pvals[0], mask.vertex);
            b.end_row(out);
        } else {
            let ptags = pf.vertex_value_tags(v);
            for (sib, &ct) in ctags.iter().enumerate() {
                if linear || ct & V_CREASE == 0 {
                    b.add(pvals[sib], 1.0);
                } else {
                    let ends = pf.crease_end_values(p, v, sib);
                    let (mut vw, mut ew) = (0.75f32, 0.125f32);
                    if ptags[sib] & V_SEMI_SHARP != 0 {
                        let q = if ptags[sib] & V_DEP_SHARP != 0 {
                            1 - sib.min(1)
                        } else {
                            sib
                        };
                        let wc = fractional_weight(p, c, pf, v, q, &mut s.pe, &mut s.ce);
                        vw = (1.0 - wc) * 0.75 + wc;
                        ew = (1.0 - wc) * 0.125;
                    }
                    b.add(ends[0], ew);
                    b.add(ends[1], ew);
                    b.add(pvals[sib], vw);
                }
                b.end_row(out);
            }
        }
    } else if cv < ep {
        add_face(b, cv - nv, 1.0);
        b.end_row(out);
    } else {
        let e = cv - ep;
        let faces = p.edge_faces(e);
        if matches {
            let ends = pf.edge_face_values(p, e, 0);
            if linear {
                b.add(ends[0], 0.5);
                b.add(ends[1], 0.5);
            } else if tri_split {
                // Loop: the "face" weights go to the value opposite the edge in each face.
                let m = loop_edge_mask(p.edge_sharpness[e], c.vert_rule[cv], faces.len());
                b.add(ends[0], m.vertex);
                b.add(ends[1], m.vertex);
                if m.opposite != 0.0 {
                    for (&f, &k) in faces.iter().zip(p.edge_faces_local(e)) {
                        let (o, n) = (p.face_offsets[f as usize] as usize, p.face_size(f as usize));
                        b.add(pf.corner_values[o + (k as usize + 2) % n], m.opposite);
                    }
                }
            } else {
                let tri = [
                    faces.first().is_some_and(|&f| p.face_size(f as usize) == 3),
                    faces.get(1).is_some_and(|&f| p.face_size(f as usize) == 3),
                ];
                let m = edge_mask(
                    p.edge_sharpness[e],
                    c.vert_rule[cv],
                    faces.len(),
                    tri,
                    opts.triangle_subdivision,
                );
                if m.face != 0.0 {
                    for &f in faces {
                        add_face(b, f as usize, m.face as f64);
                    }
                }
                b.add(ends[0], m.vertex);
                b.add(ends[1], m.vertex);
            }
            b.end_row(out);
        } else {
            for i in 0..ctags.len() {
                let ends = pf.edge_face_values(p, e, i.min(faces.len() - 1));
                b.add(ends[0], 0.5);
                b.add(ends[1], 0.5);
                b.end_row(out);
            }
        }
    }
    s.row = row;
}

/// Weight of the corner rule for value `sib` of `v` while the semi-sharp edges inside its
/// span (and the vertex's own sharpness) decay to smooth.
fn fractional_weight(
    p: &Topology,
    c: &Topology,
    pf: &FVarTopology,
    v: usize,
    sib: usize,
    pe: &mut Vec<f32>,
    ce: &mut Vec<f32>,
) -> f32 {
    let [a, b] = pf.crease_ends[pf.vert_value_offsets[v] as usize + sib];
    let (pedges, cedges) = (p.vertex_edges(v), c.vertex_edges(v));
    pe.clear();
    ce.clear();
    for k in span_interior_edges(a, b, pedges.len()) {
        pe.push(p.edge_sharpness[pedges[k] as usize]);
        ce.push(c.edge_sharpness[cedges[k] as usize]);
    }
    fractional_weight_at_vertex(
        p.options.crease_method,
        p.vert_sharpness[v],
        c.vert_sharpness[v],
        pe,
        ce,
    )
}

/// Face-varying topology and stencils of every level of a [`Refiner`].
#[derive(Debug, Clone)]
pub struct FVarRefinement {
    /// `levels[k]`: the value topology of level `k` (`levels[0]` is the base).
    pub levels: Vec<FVarTopology>,
    /// `stencils[k]` maps the values of level `k` to those of level `k + 1`.
    pub stencils: Vec<StencilTable>,
}

impl FVarRefinement {
    /// Refines base values (one per value of the base level) through every level; entry `k`
    /// holds level `k`'s values with one index per face corner of that level.
    pub fn refine(&self, values: &[[f32; 2]]) -> Result<Vec<FaceVarying>> {
        let base = &self.levels[0];
        if values.len() < base.num_values {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "{} values given, the indices refer to {}",
                    values.len(),
                    base.num_values
                ),
            }
            .into());
        }
        let mut out = vec![FaceVarying {
            values: values.to_vec(),
            indices: base.corner_values.clone(),
        }];
        for (k, s) in self.stencils.iter().enumerate() {
            let mut dst = vec![[0.0f32; 2]; s.num_rows()];
            s.apply(&out[k].values, &mut dst);
            out.push(FaceVarying {
                values: dst,
                indices: self.levels[k + 1].corner_values.clone(),
            });
        }
        Ok(out)
    }
}

impl Refiner {
    /// Analyses face-varying indices (one per base face corner, into `num_values` values)
    /// and builds the per-level value topology and stencils under `mode`.
    pub fn fvar_refinement(
        &self,
        indices: &[u32],
        num_values: usize,
        mode: FVarLinearInterpolation,
    ) -> Result<FVarRefinement> {
        let mut levels = vec![FVarTopology::new(
            &self.levels[0],
            indices,
            num_values,
            mode,
        )?];
        let mut stencils = Vec::with_capacity(self.max_level());
        for k in 0..self.max_level() {
            let (p, c) = (&self.levels[k], self.full_level(k + 1));
            let child = levels[k].refine(p, &c);
            stencils.push(fvar_level_stencils(p, &c, &levels[k], &child));
            levels.push(child);
        }
        Ok(FVarRefinement { levels, stencils })
    }

    /// Refines UVs (or any two-component face-varying data) through every level under
    /// `mode`, as OpenSubdiv's `PrimvarRefiner::InterpolateFaceVarying`. Entry `k` holds
    /// level `k`'s values and one index per face corner of level `k` (entry 0 is `uvs`).
    pub fn refine_uvs(
        &self,
        uvs: &FaceVarying,
        mode: FVarLinearInterpolation,
    ) -> Result<Vec<FaceVarying>> {
        self.fvar_refinement(&uvs.indices, uvs.values.len(), mode)?
            .refine(&uvs.values)
    }
}

#[cfg(test)]
#[path = "fvar_tests.rs"]
mod tests;
