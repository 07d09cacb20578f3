//! Face-varying data moved to the limit surface (OpenSubdiv
//! `PrimvarRefiner::LimitFaceVarying`): one stencil row per face-varying value of a level.
//!
//! - A value whose topology matches its vertex's (no seam, no boundary treatment) takes the
//!   vertex's limit mask (smooth, crease or corner rule of its sharpness; Halstead, Kass &
//!   DeRose 1993; Loop's masks under the Loop scheme), applied to the face-varying values around it: face weights to the value at
//!   the corner opposite the vertex in each face, edge weights to the value across each edge.
//! - Every other value is a corner (kept as it is: seam corners, semi-sharp values not yet
//!   decayed) or a crease along its seam, `2/3 v + 1/6 (a + b)` over the values `a`, `b`
//!   across the seam edges bounding its span.
//! - With linear face-varying interpolation (`All`) and at vertices without edges, values
//!   stay where they are; under the bilinear scheme the vertex limit mask is the identity,
//!   but seam creases still take the crease limit (as OpenSubdiv does).

use super::fvar_topology::{FVarTopology, V_CREASE, V_MISMATCH};
use super::masks::build_rows;
use super::stencil::StencilTable;
use crate::options::{FVarLinearInterpolation, Scheme};
use crate::rules::catmark::limit_mask;
use crate::rules::r#loop::limit_mask as loop_limit_mask;
use crate::topology::Topology;

/// Stencils moving each face-varying value of level `t` (value topology `fv`) to the limit.
pub fn fvar_limit_stencils(t: &Topology, fv: &FVarTopology) -> StencilTable {
    let n = fv.num_values;
    let linear = fv.mode == FVarLinearInterpolation::All;
    let bilinear = t.options.scheme == Scheme::Bilinear;
    // The vertex and sibling each value is computed at: after refinement every value has
    // one; a base value several vertices share takes the last one's (OpenSubdiv's loop).
    let mut at = vec![(u32::MAX, 0u32); n];
    for v in 0..t.num_vertices() {
        for (sib, &x) in fv.vertex_values(v).iter().enumerate() {
            at[x as usize] = (v as u32, sib as u32);
        }
    }
    build_rows(n, n, |x, b, s| {
        let (v, sib) = at[x];
        let (v, sib) = (v as usize, sib as usize);
        let keep = linear || v == u32::MAX as usize || t.vertex_edges(v).is_empty();
        if keep {
            b.add(x as u32, 1.0);
            return;
        }
        let tags = fv.vertex_value_tags(v);
        if tags[0] & V_MISMATCH != 0 {
            if tags[sib] & V_CREASE != 0 {
                let [e0, e1] = fv.crease_end_values(t, v, sib);
                b.add(e0, 1.0 / 6.0);
                b.add(e1, 1.0 / 6.0);
                b.add(x as u32, 2.0 / 3.0);
            } else {
                b.add(x as u32, 1.0);
            }
            return;
        }
        if bilinear {
            b.add(x as u32, 1.0);
            return;
        }
        let edges = t.vertex_edges(v);
        s.pe.clear();
        s.pe.extend(edges.iter().map(|&e| t.edge_sharpness[e as usize]));
        let faces = t.vertex_faces(v);
        if t.options.scheme == Scheme::Loop {
            loop_limit_mask(t.vert_rule[v], &s.pe, faces.len(), &mut s.mask);
        } else {
            limit_mask(t.vert_rule[v], &s.pe, faces.len(), &mut s.mask);
        }
        for (&w, (&f, &k)) in s
            .mask
            .faces
            .iter()
            .zip(faces.iter().zip(t.vertex_faces_local(v)))
        {
            let (o, m) = (t.face_offsets[f as usize] as usize, t.face_size(f as usize));
            b.add(fv.corner_values[o + (k as usize + 2) % m], w);
        }
        if !s.mask.edges.is_empty() {
            fv.vertex_edge_values(t, v, &mut s.values);
            for (&e, &w) in s.values.iter().zip(&s.mask.edges) {
                b.add(e, w);
            }
        }
        b.add(x as u32, s.mask.vertex);
    })
}
