//! Face-varying data moved to the limit surface (OpenSubdiv
//! `PrimvarRefiner::LimitFaceVarying`): one stencil row per face-varying value of a level.
//!
//! - A value whose topology matches its vertex's (no seam, no boundary treatment) takes the
//!   vertex's limit mask (smooth, crease or corner rule of its sharpness; Halstead, Kass &
//!   DeRose 1993), applied to the face-varying values around it: face weights to the value at
//!   the corner opposite the vertex in each face, edge weights to the value across each edge.
//! - Every other value is a corner (kept as it is: seam corners, semi-sharp values not yet
//!   decayed) or a crease along its seam, `2/3 v + 1/6 (a + b)` over the values `a`, `b`
//!   across the seam edges bounding its span.
//! - With linear face-varying interpolation (`All`) and at vertices without edges, values
//!   stay where they are; under the bilinear scheme the vertex limit mask is the identity,
//!   but seam creases still take the crease limit (as OpenSubdiv does).

use super::fvar_topology::{FVarTopology, V_CREASE, V_MISMATCH};
use super::stencil::StencilTable;
use crate::options::{FVarLinearInterpolation, Scheme};
use crate::rules::catmark::{limit_mask, VertexMask};
use crate::topology::Topology;

/// Stencils moving each face-varying value of level `t` (value topology `fv`) to the limit.
pub fn fvar_limit_stencils(t: &Topology, fv: &FVarTopology) -> StencilTable {
    let n = fv.num_values;
    // Identity unless a vertex below says otherwise.
    let mut rows: Vec<Vec<(u32, f32)>> = (0..n as u32).map(|x| vec![(x, 1.0)]).collect();
    let linear = fv.mode == FVarLinearInterpolation::All;
    let bilinear = t.options.scheme == Scheme::Bilinear;
    let mut mask = VertexMask::default();
    let (mut sharpness, mut edge_values) = (Vec::new(), Vec::new());
    for v in 0..t.num_vertices() {
        let edges = t.vertex_edges(v);
        let values = fv.vertex_values(v);
        if linear || edges.is_empty() || values.is_empty() {
            continue;
        }
        let tags = fv.vertex_value_tags(v);
        if tags[0] & V_MISMATCH == 0 && bilinear {
            continue;
        } else if tags[0] & V_MISMATCH == 0 {
            sharpness.clear();
            sharpness.extend(edges.iter().map(|&e| t.edge_sharpness[e as usize]));
            let faces = t.vertex_faces(v);
            limit_mask(t.vert_rule[v], &sharpness, faces.len(), &mut mask);
            let mut row = Vec::with_capacity(1 + mask.edges.len() + mask.faces.len());
            for (&w, (&f, &k)) in mask
                .faces
                .iter()
                .zip(faces.iter().zip(t.vertex_faces_local(v)))
            {
                let (s, m) = (t.face_offsets[f as usize] as usize, t.face_size(f as usize));
                row.push((fv.corner_values[s + (k as usize + 2) % m], w));
            }
            if !mask.edges.is_empty() {
                fv.vertex_edge_values(t, v, &mut edge_values);
                row.extend(edge_values.iter().copied().zip(mask.edges.iter().copied()));
            }
            row.push((values[0], mask.vertex));
            rows[values[0] as usize] = row;
        } else {
            for (sib, (&x, &tag)) in values.iter().zip(tags).enumerate() {
                if tag & V_CREASE != 0 {
                    let [a, b] = fv.crease_end_values(t, v, sib);
                    rows[x as usize] = vec![(a, 1.0 / 6.0), (b, 1.0 / 6.0), (x, 2.0 / 3.0)];
                }
            }
        }
    }
    let mut table = StencilTable {
        offsets: Vec::with_capacity(n + 1),
        indices: Vec::new(),
        weights: Vec::new(),
        num_inputs: n,
    };
    table.offsets.push(0);
    for row in rows {
        for (x, w) in row {
            table.indices.push(x);
            table.weights.push(w);
        }
        table.offsets.push(table.indices.len() as u32);
    }
    table
}
