//! Input the p-rep does not cover is refused with a typed error naming the elements.

mod prep_shapes;

use subsurf::prep::{check_input as check_topology, PrepPatches};
use subsurf::{Error, Mesh, MeshError, Topology};

fn check_input(m: &Mesh) -> subsurf::Result<()> {
    check_topology(&Topology::new(m)?)
}

fn details(r: subsurf::Result<()>) -> String {
    match r {
        Err(Error::Mesh(MeshError::Unsupported { details, .. })) => details,
        other => panic!("expected MeshError::Unsupported, got {other:?}"),
    }
}

#[test]
fn closed_quads_are_accepted() {
    for (name, m) in prep_shapes::closed_meshes() {
        assert!(check_input(&m).is_ok(), "{name}");
    }
}

#[test]
fn non_quad_faces_are_named() {
    let mut m = prep_shapes::cube();
    // Replace face 5 by two triangles.
    m.face_counts.truncate(5);
    m.face_indices.truncate(20);
    for t in [[1u32, 5, 7], [1, 7, 3]] {
        m.face_counts.push(3);
        m.face_indices.extend_from_slice(&t);
    }
    let d = details(check_input(&m));
    assert!(
        d.contains("2 non-quad faces") && d.contains("face 5 (3 vertices)") && d.contains("face 6"),
        "{d}"
    );
    assert!(PrepPatches::<f32>::build(&m).is_err());
}

#[test]
fn boundary_edges_are_named() {
    let mut m = prep_shapes::cube();
    m.face_counts.pop();
    m.face_indices.truncate(20); // drop face [1,5,7,3]
    let d = details(check_input(&m));
    assert!(d.contains("4 boundary edges"), "{d}");
    for e in ["(1-3)", "(3-7)", "(5-7)", "(1-5)"] {
        assert!(d.contains(e), "{e} missing in: {d}");
    }
}

#[test]
fn non_manifold_edge_is_named() {
    let mut m = prep_shapes::cube();
    m.positions.push([-1.0, 0.0, 0.0]);
    m.positions.push([-1.0, 0.0, 1.0]);
    m.face_counts.push(4);
    m.face_indices.extend_from_slice(&[0, 1, 9, 8]); // a fin on edge 0-1 (same direction as face 0)
    let d = details(check_input(&m));
    assert!(
        d.contains("1 non-manifold edges") && d.contains("edge 0 (0-1)"),
        "{d}"
    );
}

#[test]
fn non_manifold_vertex_is_named() {
    // Two cubes sharing only vertex 7 of the first (= vertex 0 of the second).
    let a = prep_shapes::cube();
    let mut p = a.positions.to_vec();
    let mut f: Vec<[u32; 4]> = a
        .face_indices
        .chunks(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    let map = |v: u32| if v == 0 { 7 } else { v + 7 };
    p.extend(
        a.positions[1..]
            .iter()
            .map(|q| [q[0] + 1.0, q[1] + 1.0, q[2] + 1.0]),
    );
    f.extend(
        a.face_indices
            .chunks(4)
            .map(|c| [map(c[0]), map(c[1]), map(c[2]), map(c[3])]),
    );
    let m = Mesh::from_faces(p, &f);
    let d = details(check_input(&m));
    assert!(
        d.contains("1 non-manifold vertices") && d.contains("vertex 7"),
        "{d}"
    );
}

#[test]
fn holes_and_bad_valence_are_named() {
    let mut m = prep_shapes::cube();
    m.holes = vec![2];
    let d = details(check_input(&m));
    assert!(d.contains("faces tagged as holes: face 2"), "{d}");
    // Valence 2: two quads glued back to back.
    let m = Mesh::from_faces(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        &[[0u32, 1, 2, 3], [0, 3, 2, 1]],
    );
    let d = details(check_input(&m));
    assert!(
        d.contains("4 vertices with unsupported valence") && d.contains("vertex 0 (valence 2)"),
        "{d}"
    );
}

#[test]
fn non_finite_and_wrong_length_positions() {
    let mut m = prep_shapes::cube();
    m.positions.as_f32_mut()[3][1] = f32::NAN;
    assert!(matches!(
        PrepPatches::<f32>::build(&m),
        Err(Error::Mesh(MeshError::NonFiniteCoordinate {
            vertex: 3,
            ..
        }))
    ));
    let mut p = PrepPatches::<f32>::build(&prep_shapes::cube()).unwrap();
    assert!(p.update(&[[0.0f32; 3]; 7][..]).is_err());
}
