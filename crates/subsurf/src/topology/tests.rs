use super::tags;
use super::Topology;
use crate::error::{Error, MeshError};
use crate::mesh::{Corner, Crease, Mesh};
use crate::options::BoundaryInterpolation;
use crate::shapes;
use crate::SHARPNESS_INFINITE;

/// Structural invariants that hold for every topology.
pub(crate) fn check_invariants(t: &Topology) {
    if let Err(e) = t.check_consistency() {
        panic!("{e}");
    }
}

#[test]
fn cube_is_closed_euler_two() {
    let t = Topology::new(&shapes::cube()).unwrap();
    assert_eq!((t.num_vertices(), t.num_edges(), t.num_faces()), (8, 12, 6));
    assert_eq!(
        t.num_vertices() as i64 - t.num_edges() as i64 + t.num_faces() as i64,
        2
    );
    assert!(t.is_closed() && t.is_manifold() && t.is_all_quads());
    check_invariants(&t);
    assert!((0..8).all(|v| t.valence(v) == 3 && t.vert_tags[v] & tags::V_XORDINARY != 0));
}

#[test]
fn torus_is_regular_euler_zero() {
    let t = Topology::new(&shapes::torus(7, 5, 2.0, 0.5)).unwrap();
    assert_eq!(
        t.num_vertices() as i64 - t.num_edges() as i64 + t.num_faces() as i64,
        0
    );
    assert!(t.is_closed());
    check_invariants(&t);
    assert!(
        (0..t.num_vertices()).all(|v| t.valence(v) == 4 && t.vert_tags[v] & tags::V_XORDINARY == 0)
    );
}

#[test]
fn grid_boundary_is_infinitely_sharp() {
    let mut m = shapes::grid(3, 2);
    m.options.boundary = BoundaryInterpolation::EdgeAndCorner;
    let t = Topology::new(&m).unwrap();
    check_invariants(&t);
    assert_eq!(t.boundary_edges().len(), 2 * (3 + 2));
    assert!(!t.is_closed() && t.is_manifold());
    for e in t.boundary_edges() {
        assert_eq!(t.edge_sharpness[e as usize], 10.0);
    }
    // Corners of the grid are sharpened with edge-and-corner.
    for v in [0usize, 3, 8, 11] {
        assert_eq!(t.vert_sharpness[v], 10.0, "corner {v}");
        assert_eq!(t.vert_rule[v], tags::rule::CORNER);
    }
    assert_eq!(t.vert_rule[1], tags::rule::CREASE);
    assert_eq!(t.vert_rule[5], tags::rule::SMOOTH);
}

#[test]
fn pole_has_valence_n() {
    for n in [3usize, 5, 12, 64] {
        let t = Topology::new(&shapes::pole(n)).unwrap();
        check_invariants(&t);
        assert_eq!(t.valence(0), n);
        assert_eq!(t.vertex_faces(0).len(), n);
    }
}

#[test]
fn creases_and_corners_are_assigned() {
    let mut m = shapes::cube();
    m.creases.push(Crease {
        v0: 1,
        v1: 0,
        sharpness: 2.5,
    });
    m.creases.push(Crease {
        v0: 2,
        v1: 3,
        sharpness: -1.0,
    });
    m.corners.push(Corner {
        vertex: 5,
        sharpness: 30.0,
    });
    let t = Topology::new(&m).unwrap();
    let e = t.find_edge(0, 1).unwrap() as usize;
    assert_eq!(t.edge_sharpness[e], 2.5);
    assert_eq!(t.edge_tags[e] & tags::E_SEMI_SHARP, tags::E_SEMI_SHARP);
    assert_eq!(t.edge_sharpness[t.find_edge(2, 3).unwrap() as usize], 0.0);
    assert_eq!(t.vert_sharpness[5], 10.0);
    assert_eq!(t.vert_rule[0], tags::rule::DART);
}

#[test]
fn crease_on_missing_edge_is_an_error() {
    let mut m = shapes::cube();
    m.creases.push(Crease {
        v0: 0,
        v1: 5,
        sharpness: 1.0,
    });
    match Topology::new(&m) {
        Err(Error::Mesh(MeshError::CreaseEdgeMissing {
            tag: 0,
            v0: 0,
            v1: 5,
        })) => {}
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn bad_input_is_named() {
    let mut m = shapes::cube();
    m.face_indices[5] = 99;
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::VertexIndexOutOfRange {
            face: 1,
            corner: 1,
            index: 99,
            count: 8
        }))
    ));
    let mut m = shapes::cube();
    m.positions.as_f32_mut()[3][1] = f32::NAN;
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::NonFiniteCoordinate {
            vertex: 3,
            ..
        }))
    ));
    let m = Mesh::from_faces(vec![[0.0; 3]; 3], &[[0u32, 1]]);
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::FaceTooSmall { face: 0, count: 2 }))
    ));
    let mut m = shapes::cube();
    m.holes.push(6);
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::TagIndexOutOfRange {
            kind: "hole",
            tag: 0,
            index: 6,
            count: 6
        }))
    ));
    let mut m = shapes::cube();
    m.corners.push(Corner {
        vertex: 8,
        sharpness: 1.0,
    });
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::TagIndexOutOfRange {
            kind: "corner",
            ..
        }))
    ));
    let mut m = shapes::cube();
    m.creases.push(Crease {
        v0: 0,
        v1: 1,
        sharpness: f32::NAN,
    });
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::NanSharpness {
            kind: "crease",
            tag: 0
        }))
    ));
    let mut m = shapes::cube();
    m.face_counts[0] = 5;
    assert!(matches!(
        Topology::new(&m),
        Err(Error::Mesh(MeshError::FaceIndexCountMismatch { .. }))
    ));
}

#[test]
fn non_manifold_input_is_accepted_and_sharpened() {
    // Three quads sharing the edge 0-1 (a fin), and a degenerate quad repeating a vertex.
    let p = vec![[0.0; 3]; 9];
    let m = Mesh::from_faces(
        p,
        &[[0u32, 1, 2, 3], [1, 0, 4, 5], [0, 1, 6, 7], [2, 8, 8, 3]],
    );
    let t = Topology::new(&m).unwrap();
    check_invariants(&t);
    let e01 = t.find_edge(0, 1).unwrap() as usize;
    assert!(t.edge_tags[e01] & tags::E_NON_MANIFOLD != 0);
    assert_eq!(t.edge_sharpness[e01], 10.0);
    assert!(!t.is_manifold());
    assert_eq!(t.degenerate_faces(), vec![3]);
    let e88 = t.find_edge(8, 8).unwrap() as usize;
    assert!(t.edge_tags[e88] & tags::E_NON_MANIFOLD != 0);
    assert!(t.non_manifold_vertices().contains(&8));
}

#[test]
fn inconsistent_winding_is_non_manifold() {
    let p = vec![[0.0; 3]; 6];
    let m = Mesh::from_faces(p, &[[0u32, 1, 2, 3], [0, 1, 4, 5]]);
    let t = Topology::new(&m).unwrap();
    let e = t.find_edge(0, 1).unwrap() as usize;
    assert!(t.edge_tags[e] & tags::E_NON_MANIFOLD != 0);
}

#[test]
fn boundary_none_makes_boundary_faces_holes() {
    let mut m = shapes::grid(3, 3);
    m.options.boundary = BoundaryInterpolation::None;
    let t = Topology::new(&m).unwrap();
    let holes = t.face_is_hole.iter().filter(|&&h| h).count();
    assert_eq!(
        holes, 8,
        "only the centre face of a 3x3 grid touches no boundary vertex"
    );
    assert!(!t.face_is_hole[4]);
}

#[test]
fn boundary_none_keeps_faces_of_vertices_with_all_boundary_edges_infinitely_sharp() {
    let mut m = shapes::grid(3, 3);
    m.options.boundary = BoundaryInterpolation::None;
    // The bottom row's boundary edges (vertices 0..=3) infinitely sharp, one semi-sharp.
    for i in 0..3u32 {
        let sharpness = if i == 2 { 5.0 } else { SHARPNESS_INFINITE };
        m.creases.push(crate::Crease {
            v0: i,
            v1: i + 1,
            sharpness,
        });
    }
    let t = Topology::new(&m).unwrap();
    // Vertex 1 has both boundary edges tagged, but its faces 0 and 1 touch vertex 0 (edge
    // 0-4 untagged) and vertex 2 (edge 2-3 only semi-sharp): all 8 boundary faces are holes.
    assert_eq!(t.face_is_hole.iter().filter(|&&h| h).count(), 8);
    m.creases.push(crate::Crease {
        v0: 0,
        v1: 4,
        sharpness: SHARPNESS_INFINITE,
    });
    m.creases.push(crate::Crease {
        v0: 4,
        v1: 8,
        sharpness: SHARPNESS_INFINITE,
    });
    let t = Topology::new(&m).unwrap();
    // With the left column's lower edges tagged, vertices 0, 1 and 4 have only tagged
    // boundary edges: face 0 (corners 0, 1, 5, 4) is kept.
    let kept: Vec<usize> = (0..9).filter(|&f| !t.face_is_hole[f]).collect();
    assert_eq!(kept, vec![0, 4]);
}

#[test]
fn edges_are_numbered_in_first_use_order() {
    let t = Topology::new(&shapes::grid(2, 1)).unwrap();
    // Face 0 = (0,1,4,3) creates edges 0..4; face 1 = (1,2,5,4) reuses 1-4 as its last edge.
    assert_eq!(&t.edge_verts[..4], &[[0, 1], [1, 4], [4, 3], [3, 0]]);
    assert_eq!(&t.edge_verts[4..], &[[1, 2], [2, 5], [5, 4]]);
    assert_eq!(t.face_edges(1), &[4, 5, 6, 1]);
}
