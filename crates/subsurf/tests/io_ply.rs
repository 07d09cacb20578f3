//! PLY reader and writer: binary round trips of every shape, ASCII and big-endian input, and
//! malformed files.

mod common;

use subsurf::io::{obj, ply};
use subsurf::{Error, Mesh};

fn bits(points: &[[f32; 3]]) -> Vec<[u32; 3]> {
    points.iter().map(|p| p.map(f32::to_bits)).collect()
}

#[test]
fn binary_round_trip_of_every_shape() {
    for row in common::index() {
        let name = row.get("name");
        let mesh = obj::read_file(common::shape_path(name)).unwrap();
        let mut out = Vec::new();
        ply::write(&mesh, None, &mut out).unwrap();
        let again = ply::read(&out).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(bits(&again.positions), bits(&mesh.positions), "{name}");
        // PLY cannot tag holes: their faces are left out.
        let (mut counts, mut indices, mut start) = (Vec::new(), Vec::new(), 0);
        for (f, &n) in mesh.face_counts.iter().enumerate() {
            let end = start + n as usize;
            if !mesh.holes.contains(&(f as u32)) {
                counts.push(n);
                indices.extend_from_slice(&mesh.face_indices[start..end]);
            }
            start = end;
        }
        assert_eq!(again.face_counts, counts, "{name}");
        assert_eq!(again.face_indices, indices, "{name}");
        assert_eq!(again.uvs, None, "{name}");
    }
}

#[test]
fn normals_round_trip() {
    let mesh = obj::read_file(common::shape_path("catmark_torus")).unwrap();
    let normals: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| [p[1], -p[0], p[2] * 0.5])
        .collect();
    let mut out = Vec::new();
    ply::write(&mesh, Some(&normals), &mut out).unwrap();
    let (again, n) = ply::read_with_normals(&out).unwrap();
    assert_eq!(bits(&n.unwrap()), bits(&normals));
    assert_eq!(bits(&again.positions), bits(&mesh.positions));
    assert_eq!(again.face_indices, mesh.face_indices);
    assert!(ply::write(&mesh, Some(&normals[1..]), &mut Vec::new()).is_err());
}

#[test]
fn faces_longer_than_255_use_a_wide_count() {
    let n = 300u32;
    let positions: Vec<[f32; 3]> = (0..n)
        .map(|i| {
            let a = i as f32 / n as f32 * std::f32::consts::TAU;
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    let face: Vec<u32> = (0..n).collect();
    let mesh = Mesh::from_faces(positions, &[face]);
    let mut out = Vec::new();
    ply::write(&mesh, None, &mut out).unwrap();
    let again = ply::read(&out).unwrap();
    assert_eq!(again.face_counts, [n]);
    assert_eq!(again.face_indices, mesh.face_indices);
}

const ASCII: &str = "ply\r
format ascii 1.0\r
comment a square and a triangle\r
element vertex 5\r
property double x\r
property float y\r
property float z\r
property uchar red\r
property float u\r
property float v\r
element face 2\r
property list uchar int vertex_index\r
property int material\r
element edge 1\r
property int vertex1\r
property int vertex2\r
end_header\r
0 0 0 255 0 0\r
1 0 0 255 1 0\r
1 1 0 255 1 1\r
0 1 0 255 0 1\r
\r
2 2 1.5 0 0.5 0.5\r
4 0 1 2 3 7\r
3 1 4 2 7\r
0 1\r
";

#[test]
fn ascii_with_extra_properties_and_elements() {
    let mesh = ply::read(ASCII.as_bytes()).unwrap();
    assert_eq!(mesh.positions.len(), 5);
    assert_eq!(mesh.positions[4], [2.0, 2.0, 1.5]);
    assert_eq!(mesh.face_counts, [4, 3]);
    assert_eq!(mesh.face_indices, [0, 1, 2, 3, 1, 4, 2]);
    let uv = mesh.uvs.unwrap();
    assert_eq!(uv.values[2], [1.0, 1.0]);
    assert_eq!(uv.indices, mesh.face_indices);
}

#[test]
fn big_endian_binary() {
    let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\n\
property float y\nproperty float z\nelement face 1\nproperty list uchar ushort vertex_indices\nend_header\n"
        .to_vec();
    let pts = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.25, 1.0, -3.0]];
    for p in &pts {
        for c in p {
            bytes.extend_from_slice(&c.to_be_bytes());
        }
    }
    bytes.push(3);
    for i in [0u16, 1, 2] {
        bytes.extend_from_slice(&i.to_be_bytes());
    }
    let mesh = ply::read(&bytes).unwrap();
    assert_eq!(mesh.positions, pts.to_vec());
    assert_eq!(mesh.face_indices, [0, 1, 2]);
}

#[test]
fn write_path_and_read_path_handle_ply() {
    let dir = std::env::temp_dir().join(format!("subsurf-io-ply-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = obj::read_file(common::shape_path("catmark_pyramid")).unwrap();
    let path = dir.join("pyramid.ply");
    subsurf::io::write_path(&path, &mesh, None).unwrap();
    let again = subsurf::io::read_path(&path).unwrap();
    assert_eq!(again.positions, mesh.positions);
    assert_eq!(again.face_indices, mesh.face_indices);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[track_caller]
fn assert_parse_error(bytes: &[u8], line: usize, needle: &str) {
    match ply::read(bytes) {
        Err(Error::Parse { line: l, reason }) => {
            assert_eq!(l, line, "wrong line for error '{reason}'");
            assert!(
                reason.contains(needle),
                "reason '{reason}' lacks '{needle}'"
            );
        }
        other => panic!("expected a parse error on line {line}, got {other:?}"),
    }
}

#[test]
fn malformed_files() {
    assert_parse_error(b"solid cube\n", 1, "not a PLY");
    assert_parse_error(
        b"ply\nformat ascii 1.0\nelement vertex 1\n",
        4,
        "end_header",
    );
    assert_parse_error(
        b"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
        3,
        "before any element",
    );
    assert_parse_error(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n",
        4,
        "unknown property type",
    );
    assert_parse_error(b"ply\nelement vertex 0\nend_header\n", 3, "no 'format'");
    // ASCII body errors name the body line.
    let text = ASCII.replace("3 1 4 2 7", "3 1 9 2 7");
    assert_parse_error(text.as_bytes(), 25, "out of range");
    let text = ASCII.replace("3 1 4 2 7", "2 1 4 7");
    assert_parse_error(text.as_bytes(), 25, "at least 3");
    let text = ASCII.replace("1 1 0 255 1 1", "1 nan 0 255 1 1");
    assert_parse_error(text.as_bytes(), 20, "non-finite");
    let text = ASCII.replace("1 1 0 255 1 1", "1 1 0 255 1");
    assert_parse_error(text.as_bytes(), 20, "ends too early");
    let text = ASCII.replace("1 1 0 255 1 1", "1 1 0 255 1 1 1");
    assert_parse_error(text.as_bytes(), 20, "left over");
    // Binary body errors name the header line of the element being read.
    let mesh = obj::read_file(common::shape_path("catmark_cube")).unwrap();
    let mut out = Vec::new();
    ply::write(&mesh, None, &mut out).unwrap();
    out.truncate(out.len() - 3);
    assert_parse_error(&out, 8, "ends early");
}
