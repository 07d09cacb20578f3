//! OBJ reader and writer: the regression shapes against their index, round trips, every index
//! form, and one test per class of bad input (error kind and line number).

mod common;

use std::collections::BTreeMap;
use subsurf::io::obj;
use subsurf::{
    BoundaryInterpolation, CreaseMethod, Error, FVarLinearInterpolation, Mesh, Scheme,
    TriangleSubdivision,
};

/// Counts of a sharpness summary such as `17 (16 inf, 1 semi [0.1..0.1])` from index.tsv.
#[derive(Debug, Default, PartialEq)]
struct SharpSummary {
    total: usize,
    inf: usize,
    zero: usize,
    semi: usize,
    semi_range: Option<(f32, f32)>,
}

fn parse_summary(cell: &str) -> SharpSummary {
    let mut s = SharpSummary::default();
    if cell == "-" {
        return s;
    }
    let (total, rest) = cell.split_once(' ').expect("summary");
    s.total = total.parse().unwrap();
    let inner = rest.trim_start_matches('(').trim_end_matches(')');
    for part in inner.split(", ") {
        let mut it = part.splitn(3, ' ');
        let k: usize = it.next().unwrap().parse().unwrap();
        match it.next().unwrap() {
            "inf" => s.inf = k,
            "zero" => s.zero = k,
            "semi" => {
                s.semi = k;
                let range = it.next().unwrap().trim_matches(|c| c == '[' || c == ']');
                let (a, b) = range.split_once("..").unwrap();
                s.semi_range = Some((a.parse().unwrap(), b.parse().unwrap()));
            }
            other => panic!("unknown sharpness class {other}"),
        }
    }
    s
}

fn summarize(sharpness: impl Iterator<Item = f32>) -> SharpSummary {
    let mut s = SharpSummary::default();
    for x in sharpness {
        s.total += 1;
        if x >= 10.0 {
            s.inf += 1;
        } else if x <= 0.0 {
            s.zero += 1;
        } else {
            s.semi += 1;
            let (lo, hi) = s.semi_range.unwrap_or((x, x));
            s.semi_range = Some((lo.min(x), hi.max(x)));
        }
    }
    s
}

fn histogram(mesh: &Mesh) -> String {
    let mut h = BTreeMap::new();
    for &n in &mesh.face_counts {
        *h.entry(n).or_insert(0usize) += 1;
    }
    h.iter()
        .map(|(k, v)| format!("{k}:{v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn unused_vertices(mesh: &Mesh) -> usize {
    let mut used = vec![false; mesh.positions.len()];
    for &v in &mesh.face_indices {
        used[v as usize] = true;
    }
    used.iter().filter(|&&u| !u).count()
}

#[test]
fn every_shape_matches_the_index() {
    let rows = common::index();
    let files = std::fs::read_dir(common::shapes_dir())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "obj")
        })
        .count();
    assert_eq!(rows.len(), files, "index.tsv lists every .obj file once");
    for row in &rows {
        let name = row.get("name");
        let mesh =
            obj::read_file(common::shape_path(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let ctx = |what: &str| format!("{name}: {what}");
        assert_eq!(mesh.num_vertices(), row.usize("verts"), "{}", ctx("verts"));
        assert_eq!(mesh.num_faces(), row.usize("faces"), "{}", ctx("faces"));
        assert_eq!(
            histogram(&mesh),
            row.get("face_sizes"),
            "{}",
            ctx("face sizes")
        );
        assert_eq!(
            unused_vertices(&mesh),
            row.usize("unused_verts"),
            "{}",
            ctx("unused")
        );
        assert_eq!(mesh.holes.len(), row.usize("holes"), "{}", ctx("holes"));
        for (col, got) in [
            (
                "creases",
                summarize(mesh.creases.iter().map(|c| c.sharpness)),
            ),
            (
                "corners",
                summarize(mesh.corners.iter().map(|c| c.sharpness)),
            ),
        ] {
            let want = parse_summary(row.get(col));
            assert_eq!(
                (got.total, got.inf, got.zero, got.semi),
                (want.total, want.inf, want.zero, want.semi),
                "{}",
                ctx(col)
            );
            if let (Some(g), Some(w)) = (got.semi_range, want.semi_range) {
                assert!(
                    (g.0 - w.0).abs() < 0.01 && (g.1 - w.1).abs() < 0.01,
                    "{}: {g:?} vs {w:?}",
                    ctx(col)
                );
            }
        }
        let scheme = match row.get("scheme") {
            "catmark" => Scheme::Catmark,
            "bilinear" => Scheme::Bilinear,
            "loop" => Scheme::Loop,
            s => panic!("scheme {s}"),
        };
        assert_eq!(mesh.options.scheme, scheme, "{}", ctx("scheme"));
        let boundary = match row.get("boundary_tag") {
            "-" | "edge-only" => BoundaryInterpolation::EdgeOnly,
            "edge-and-corner" => BoundaryInterpolation::EdgeAndCorner,
            "none" => BoundaryInterpolation::None,
            s => panic!("boundary tag {s}"),
        };
        assert_eq!(mesh.options.boundary, boundary, "{}", ctx("boundary"));
        let crease = match row.get("crease_tag") {
            "-" | "uniform" => CreaseMethod::Uniform,
            "chaikin" => CreaseMethod::Chaikin,
            s => panic!("crease tag {s}"),
        };
        assert_eq!(
            mesh.options.crease_method,
            crease,
            "{}",
            ctx("crease method")
        );
        let tri = match row.get("tri_tag") {
            "-" | "catmark" => TriangleSubdivision::Catmark,
            "smooth" => TriangleSubdivision::Smooth,
            s => panic!("tri tag {s}"),
        };
        assert_eq!(
            mesh.options.triangle_subdivision,
            tri,
            "{}",
            ctx("triangles")
        );
        let has_uv = row.get("features").split(',').any(|f| f == "fvar-uv");
        assert_eq!(mesh.uvs.is_some(), has_uv, "{}", ctx("fvar-uv"));
        if let Some(uv) = &mesh.uvs {
            assert_eq!(
                uv.indices.len(),
                mesh.face_indices.len(),
                "{}",
                ctx("uv indices")
            );
        }
    }
}

#[test]
fn facevarying_boundary_tag_follows_opensubdiv() {
    // catmark_cubes_infsharp carries `t facevaryinginterpolateboundary 1/0/0 1`.
    let mesh = obj::read_file(common::shape_path("catmark_cubes_infsharp")).unwrap();
    assert_eq!(
        mesh.options.uv_interpolation,
        FVarLinearInterpolation::CornersOnly
    );
    let expected = [
        FVarLinearInterpolation::None,
        FVarLinearInterpolation::CornersOnly,
        FVarLinearInterpolation::CornersPlus1,
        FVarLinearInterpolation::CornersPlus2,
        FVarLinearInterpolation::Boundaries,
        FVarLinearInterpolation::All,
    ];
    for (k, want) in expected.iter().enumerate() {
        let text = format!("v 0 0 0\nt facevaryinginterpolateboundary 1/0/0 {k}\n");
        assert_eq!(obj::read(&text).unwrap().options.uv_interpolation, *want);
    }
    let m = obj::read("t facevaryingpropagatecorners 1/0/0 1\n").unwrap();
    assert!(m.options.fvar_propagate_corners);
}

#[test]
fn read_write_read_is_identity_on_every_shape() {
    for row in common::index() {
        let name = row.get("name");
        let mesh = obj::read_file(common::shape_path(name)).unwrap();
        let mut out = Vec::new();
        obj::write(&mesh, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let again = obj::read_with_scheme(&text, mesh.options.scheme)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(again, mesh, "{name}");
        // Bit-exact floats, not just ==.
        for (a, b) in mesh.positions.iter().zip(&again.positions) {
            assert_eq!(a.map(f32::to_bits), b.map(f32::to_bits), "{name}");
        }
    }
}

#[test]
fn scheme_comes_from_the_name_prefix() {
    assert_eq!(obj::scheme_from_name("catmark_cube"), Some(Scheme::Catmark));
    assert_eq!(
        obj::scheme_from_name("bilinear_cube"),
        Some(Scheme::Bilinear)
    );
    assert_eq!(obj::scheme_from_name("loop_cube"), Some(Scheme::Loop));
    assert_eq!(obj::scheme_from_name("loopy_cube"), None);
    assert_eq!(obj::scheme_from_name("cube"), None);
}

#[test]
fn every_index_form_gives_the_same_mesh() {
    let head = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";
    let plain = obj::read(&format!("{head}f 1 2 3 4\n")).unwrap();
    assert_eq!(plain.face_indices, [0, 1, 2, 3]);
    assert_eq!(plain.uvs, None);
    for f in [
        "f 1//1 2//1 3//1 4//1",
        "f -4 -3 -2 -1",
        "f -4//-1 2//1 -2 4",
    ] {
        let m = obj::read(&format!("{head}{f}\n")).unwrap();
        assert_eq!(m, plain, "{f}");
    }
    let with_uv = obj::read(&format!("{head}f 1/1 2/2 3/3 4/4\n")).unwrap();
    let uv = with_uv.uvs.as_ref().unwrap();
    assert_eq!(uv.indices, [0, 1, 2, 3]);
    assert_eq!(uv.values[2], [1.0, 1.0]);
    for f in [
        "f 1/1/1 2/2/1 3/3/1 4/4/1",
        "f -4/-4 -3/-3/1 -2/-2 -1/-1/-1",
    ] {
        let m = obj::read(&format!("{head}{f}\n")).unwrap();
        assert_eq!(m, with_uv, "{f}");
    }
}

#[test]
fn crlf_comments_continuations_and_ignored_statements() {
    let text = "# a square\r\nmtllib x.mtl\r\no thing\r\nv 0 0 0 1 0.5 0.5 0.5\r\nv 1 0 0\r\n\r\n\
                v 1 1 0 # trailing comment\r\ng group\r\ns off\r\nusemtl m\r\nv 0 1 \\\r\n 0\r\n\
                f 1 2 \\\n3 4\r\nt hole 1/0/0 0\r\n";
    let m = obj::read(text).unwrap();
    assert_eq!(
        m.positions,
        [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]
    );
    assert_eq!(m.face_counts, [4]);
    assert_eq!(m.face_indices, [0, 1, 2, 3]);
    assert_eq!(m.holes, [0]);
}

#[test]
fn tag_chains_and_per_element_sharpness() {
    let head = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    let m = obj::read(&format!("{head}t crease 4/1/0 0 1 2 3 2.5\n")).unwrap();
    let edges: Vec<_> = m
        .creases
        .iter()
        .map(|c| (c.v0, c.v1, c.sharpness))
        .collect();
    assert_eq!(edges, [(0, 1, 2.5), (1, 2, 2.5), (2, 3, 2.5)]);
    let m = obj::read(&format!("{head}t crease 3/2/0 0 1 2 1 4\n")).unwrap();
    let edges: Vec<_> = m
        .creases
        .iter()
        .map(|c| (c.v0, c.v1, c.sharpness))
        .collect();
    assert_eq!(edges, [(0, 1, 1.0), (1, 2, 4.0)]);
    let m = obj::read(&format!("{head}t corner 2/2/0 0 3 1 10\n")).unwrap();
    let corners: Vec<_> = m.corners.iter().map(|c| (c.vertex, c.sharpness)).collect();
    assert_eq!(corners, [(0, 1.0), (3, 10.0)]);
    let m = obj::read(&format!(
        "{head}t vertexedit 2/3/1 0 1 0.0 0.5 1.0 add\nt creasemethod 0/0/1 chaikin\nt smoothtriangles 0/0/1 smooth\nt interpolateboundary 1/0/0 0\n"
    ))
    .unwrap();
    assert_eq!(m.options.crease_method, CreaseMethod::Chaikin);
    assert_eq!(m.options.triangle_subdivision, TriangleSubdivision::Smooth);
    assert_eq!(m.options.boundary, BoundaryInterpolation::None);
    // Every option written back is read back.
    let mut out = Vec::new();
    obj::write(&m, &mut out).unwrap();
    assert_eq!(obj::read(std::str::from_utf8(&out).unwrap()).unwrap(), m);
}

#[test]
fn write_with_normals_adds_one_normal_per_vertex() {
    let mesh = obj::read_file(common::shape_path("catmark_cube")).unwrap();
    let normals: Vec<[f32; 3]> = mesh.positions.iter().map(|p| [p[0], p[1], -p[2]]).collect();
    let mut out = Vec::new();
    obj::write_with_normals(&mesh, &normals, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), 8);
    let again = obj::read_with_scheme(&text, mesh.options.scheme).unwrap();
    assert_eq!(again, mesh);
    assert!(obj::write_with_normals(&mesh, &normals[1..], &mut Vec::new()).is_err());
}

#[test]
fn read_path_and_write_path_choose_the_format() {
    let dir = std::env::temp_dir().join(format!("subsurf-io-obj-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = subsurf::io::read_path(common::shape_path("loop_cube_creases1")).unwrap();
    assert_eq!(mesh.options.scheme, Scheme::Loop);
    let path = dir.join("loop_copy.OBJ");
    subsurf::io::write_path(&path, &mesh, None).unwrap();
    assert_eq!(subsurf::io::read_path(&path).unwrap(), mesh);
    let bad = dir.join("mesh.stl");
    assert!(matches!(
        subsurf::io::write_path(&bad, &mesh, None),
        Err(Error::Unsupported(_))
    ));
    assert!(matches!(
        subsurf::io::read_path(&bad),
        Err(Error::Unsupported(_))
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Asserts that `text` fails with a parse error on `line` whose reason contains `needle`.
#[track_caller]
fn assert_parse_error(text: &str, line: usize, needle: &str) {
    match obj::read(text) {
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

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn bad_float() {
    assert_parse_error("v 0 0 0\nv 1 0.x 0\n", 2, "not a number");
    assert_parse_error("vt 0.5 zz\n", 1, "not a number");
}

#[test]
fn non_finite_coordinate() {
    assert_parse_error("v 0 0 0\n\nv nan 0 0\n", 3, "not finite");
    assert_parse_error("v 0 0 inf\n", 1, "not finite");
    assert_parse_error("v 0 0 1e39\n", 1, "not finite");
}

#[test]
fn too_few_coordinates() {
    assert_parse_error("v 0 0\n", 1, "3 coordinates");
}

#[test]
fn face_index_zero() {
    assert_parse_error(&format!("{SQUARE}f 1 2 0 4\n"), 5, "index 0");
}

#[test]
fn face_index_out_of_range() {
    assert_parse_error(&format!("{SQUARE}f 1 2 3 4\nf 1 2 5\n"), 6, "out of range");
    assert_parse_error(
        &format!("vt 0 0\n{SQUARE}f 1/1 2/1 3/2\n"),
        6,
        "out of range",
    );
    assert_parse_error(&format!("{SQUARE}f 1//1 2//1 3//1\n"), 5, "out of range");
}

#[test]
fn negative_index_out_of_range() {
    assert_parse_error(
        &format!("{SQUARE}f -1 -2 -5\nv 2 2 2\n"),
        5,
        "before the first",
    );
}

#[test]
fn face_with_two_vertices() {
    assert_parse_error(&format!("{SQUARE}# comment\nf 1 2\n"), 6, "at least 3");
}

#[test]
fn malformed_index() {
    assert_parse_error(&format!("{SQUARE}f 1 2 3/\n"), 5, "not an integer");
    assert_parse_error(&format!("{SQUARE}f 1 2 3.5\n"), 5, "not an integer");
    assert_parse_error(&format!("{SQUARE}f 1 2 3/1/1/1\n"), 5, "more than 3");
}

#[test]
fn malformed_tag() {
    assert_parse_error(
        &format!("{SQUARE}t crease 2-1-0 0 1 2\n"),
        5,
        "malformed counts",
    );
    assert_parse_error(&format!("{SQUARE}t crease\n"), 5, "counts");
    assert_parse_error(
        &format!("{SQUARE}t crease 2/1/0 0 x 2\n"),
        5,
        "not an integer",
    );
    assert_parse_error(&format!("{SQUARE}t corner 1/1/0 0 nan\n"), 5, "NaN");
    assert_parse_error(
        &format!("{SQUARE}t interpolateboundary 1/0/0 7\n"),
        5,
        "not valid",
    );
    assert_parse_error(
        &format!("{SQUARE}t creasemethod 0/0/1 wavy\n"),
        5,
        "unknown value 'wavy' (expected normal, uniform, chaikin)",
    );
    assert_parse_error(
        &format!("{SQUARE}t smoothtriangles 0/0/1 wavy\n"),
        5,
        "(expected catmark, smooth)",
    );
    assert_parse_error(&format!("{SQUARE}t sharpen 1/0/0 1\n"), 5, "unknown tag");
    assert_parse_error(
        &format!("{SQUARE}t crease 2/1/0 0 -1 2\n"),
        5,
        "not a valid index",
    );
}

#[test]
fn tag_arity_mismatch() {
    // The counts announce more (or fewer) arguments than follow.
    assert_parse_error(&format!("{SQUARE}t crease 2/1/0 0 1\n"), 5, "announce 3");
    assert_parse_error(&format!("{SQUARE}t corner 1/1/0 0 1 2\n"), 5, "announce 2");
    // Well-formed counts that the tag does not accept.
    assert_parse_error(&format!("{SQUARE}t crease 1/1/0 0 2\n"), 5, "expects");
    assert_parse_error(
        &format!("{SQUARE}t crease 3/3/0 0 1 2 1 1 1\n"),
        5,
        "expects",
    );
    assert_parse_error(
        &format!("{SQUARE}t interpolateboundary 2/0/0 1 1\n"),
        5,
        "expects",
    );
    assert_parse_error(&format!("{SQUARE}t hole 0/0/0\n"), 5, "expects");
}

#[test]
fn tag_index_out_of_range() {
    let text = format!("{SQUARE}f 1 2 3 4\nt crease 2/1/0 3 4 1\n");
    assert_parse_error(&text, 6, "vertex 4 is out of range");
    assert_parse_error(&format!("{SQUARE}f 1 2 3 4\nt hole 1/0/0 1\n"), 6, "face 1");
    assert_parse_error(&format!("{SQUARE}t corner 1/1/0 9 1\n"), 5, "vertex 9");
}

#[test]
fn mixed_faces_with_and_without_uvs() {
    let text = format!("{SQUARE}vt 0 0\nf 1/1 2/1 3/1\n\nf 1 3 4\n");
    assert_parse_error(&text, 8, "line 6");
    let text = format!("{SQUARE}vt 0 0\nf 1 2 3\nf 1/1 3/1 4/1\n");
    assert_parse_error(&text, 7, "texture");
    // Within one face.
    assert_parse_error(&format!("{SQUARE}vt 0 0\nf 1/1 2 3/1\n"), 6, "corner 2");
}

#[test]
fn unknown_statement() {
    assert_parse_error(&format!("{SQUARE}vx 1 2 3\n"), 5, "unknown statement");
    assert_parse_error("cstype bspline\n", 1, "free-form");
}

/// Every shape builds a topology. On manifold shapes (no non-manifold edge or vertex in the
/// index) boundary-edge count and maximum valence match the index; non-manifold and
/// degenerate configurations are counted by topology's own conventions (OpenSubdiv's), which
/// the index's simple edge census does not follow, so they are left to topology's tests.
#[test]
fn every_shape_builds_a_topology_matching_the_index() {
    use subsurf::Topology;
    let mut manifold = 0;
    for row in common::index() {
        let name = row.get("name");
        let mesh = obj::read_file(common::shape_path(name)).unwrap();
        let t = Topology::new(&mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(t.num_faces(), row.usize("faces"), "{name}");
        assert_eq!(t.num_vertices(), row.usize("verts"), "{name}");
        assert_eq!(
            t.unused_vertices().len(),
            row.usize("unused_verts"),
            "{name}: unused"
        );
        if row.usize("nonman_edges") != 0 || row.usize("nonman_verts") != 0 {
            continue;
        }
        manifold += 1;
        assert!(t.is_manifold(), "{name}");
        assert_eq!(
            t.boundary_edges().len(),
            row.usize("boundary_edges"),
            "{name}: boundary edges"
        );
        let max_valence = (0..t.num_vertices())
            .map(|v| t.valence(v))
            .max()
            .unwrap_or(0);
        assert_eq!(max_valence, row.usize("max_valence"), "{name}: max valence");
    }
    assert!(manifold > 80, "{manifold} manifold shapes");
}
