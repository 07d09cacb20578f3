//! Tags and boundary sharpening of the base level (OpenSubdiv
//! `TopologyRefinerFactoryBase::prepareComponentTagsAndSharpness`).
//!
//! - Boundary and non-manifold edges become infinitely sharp.
//! - With `EdgeAndCorner`, a topological corner (one face, two edges) becomes an infinitely
//!   sharp vertex; a non-manifold vertex does too, unless it lies on an interior non-manifold
//!   crease (two non-manifold edges, no boundary, more faces than edges).
//! - With boundary interpolation `None`, every face at a boundary vertex becomes a hole unless
//!   all the vertex's boundary edges were tagged infinitely sharp (OpenSubdiv
//!   `makeBoundaryFacesHoles`: decided on the user's tags, before boundary sharpening).

use super::tags::{self, rule};
use super::Topology;
use crate::options::{BoundaryInterpolation, Scheme};
use crate::SHARPNESS_INFINITE;

pub(super) fn apply_tags_and_boundary_sharpness(t: &mut Topology) {
    let make_holes =
        t.options.boundary == BoundaryInterpolation::None && t.options.scheme != Scheme::Bilinear;
    let sharpen_corners = t.options.boundary == BoundaryInterpolation::EdgeAndCorner;
    let (reg_interior, reg_boundary) = match t.options.scheme {
        Scheme::Loop => (6, 3),
        _ => (4, 2),
    };

    if make_holes {
        mark_boundary_holes(t);
    }

    for e in 0..t.num_edges() {
        let mut tag = t.edge_tags[e] & tags::E_NON_MANIFOLD;
        if t.edge_faces(e).len() < 2 {
            tag |= tags::E_BOUNDARY;
        }
        if tag != 0 {
            t.edge_sharpness[e] = SHARPNESS_INFINITE;
        }
        let s = t.edge_sharpness[e];
        if s >= SHARPNESS_INFINITE {
            tag |= tags::E_INF_SHARP;
        } else if s > 0.0 {
            tag |= tags::E_SEMI_SHARP;
        }
        t.edge_tags[e] = tag;
    }

    for v in 0..t.num_vertices {
        let (mut boundary, mut inf, mut semi, mut nonman) = (0usize, 0usize, 0usize, 0usize);
        for &e in t.vertex_edges(v) {
            let et = t.edge_tags[e as usize];
            boundary += (et & tags::E_BOUNDARY != 0) as usize;
            inf += (et & tags::E_INF_SHARP != 0) as usize;
            semi += (et & tags::E_SEMI_SHARP != 0) as usize;
            nonman += (et & tags::E_NON_MANIFOLD != 0) as usize;
        }
        let nfaces = t.vertex_faces(v).len();
        let nedges = t.vertex_edges(v).len();
        let mut vt = t.vert_tags[v] & tags::V_NON_MANIFOLD;
        let topological_corner = nfaces == 1 && nedges == 2;
        // A non-manifold vertex is sharpened unless it lies on an interior non-manifold crease.
        let non_manifold_corner =
            vt & tags::V_NON_MANIFOLD != 0 && !(nonman == 2 && boundary == 0 && nfaces > nedges);
        if (topological_corner && sharpen_corners) || non_manifold_corner {
            t.vert_sharpness[v] = SHARPNESS_INFINITE;
        }
        let s = t.vert_sharpness[v];
        if s >= SHARPNESS_INFINITE {
            vt |= tags::V_INF_SHARP;
        } else if s > 0.0 {
            vt |= tags::V_SEMI_SHARP;
        }
        if semi > 0 {
            vt |= tags::V_SEMI_SHARP_EDGES;
        }
        if inf > 0 {
            vt |= tags::V_INF_SHARP_EDGES;
        }
        t.vert_rule[v] = rule::determine(s, inf + semi);
        if boundary > 0 {
            vt |= tags::V_BOUNDARY;
        }
        let corner = topological_corner && s >= SHARPNESS_INFINITE;
        if corner {
            vt |= tags::V_CORNER;
        } else if (boundary > 0 && nfaces != reg_boundary)
            || (boundary == 0 && nfaces != reg_interior)
        {
            vt |= tags::V_XORDINARY;
        }
        t.vert_tags[v] = vt;
    }
    for f in 0..t.num_faces() {
        if t.face_is_hole[f] {
            let (s, e) = (t.face_offsets[f] as usize, t.face_offsets[f + 1] as usize);
            for c in s..e {
                let v = t.face_verts[c] as usize;
                t.vert_tags[v] |= tags::V_INCIDENT_HOLE;
            }
        }
    }
}

/// Boundary interpolation `None`: the faces of every boundary (or non-manifold) vertex with a
/// boundary edge not tagged infinitely sharp by the user become holes. Runs before boundary
/// edges are sharpened, so it sees the tags as given.
fn mark_boundary_holes(t: &mut Topology) {
    for v in 0..t.num_vertices {
        let manifold_interior = t.vertex_edges(v).len() == t.vertex_faces(v).len()
            && t.vert_tags[v] & tags::V_NON_MANIFOLD == 0;
        if manifold_interior {
            continue;
        }
        let exclude = t.vertex_edges(v).iter().any(|&e| {
            let e = e as usize;
            t.edge_faces(e).len() == 1 && t.edge_sharpness[e] < SHARPNESS_INFINITE
        });
        if exclude {
            let (s, e) = (
                t.vert_face_offsets[v] as usize,
                t.vert_face_offsets[v + 1] as usize,
            );
            for i in s..e {
                let f = t.vert_faces[i] as usize;
                t.face_is_hole[f] = true;
            }
        }
    }
}
