//! Helpers shared by the shim's self-tests: locating and reading the regression shapes,
//! and skipping loudly when OpenSubdiv is absent.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use subsurf::{
    BoundaryInterpolation, Corner, Crease, CreaseMethod, FaceVarying, Mesh, TriangleSubdivision,
};

/// `require_osd!()` at the top of a test: returns from it (after a loud message) when
/// OpenSubdiv is missing, and fails under CI.
macro_rules! require_osd {
    () => {{
        fn here() {}
        let name = std::any::type_name_of_val(&here);
        if !common::osd_or_skip(name.strip_suffix("::here").unwrap_or(name)) {
            return;
        }
    }};
}

/// Returns false (after a loud message) when OpenSubdiv is missing; panics under CI.
pub fn osd_or_skip(test: &str) -> bool {
    if osd_ref::available() {
        return true;
    }
    let ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "0" && v != "false");
    assert!(
        !ci,
        "OpenSubdiv not installed but CI is set: {test} must run"
    );
    // Straight to the process's stderr, past the test harness's output capture.
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "!!!!! OpenSubdiv not installed: SKIPPED {test} (apt-get install libosd-dev) !!!!!"
    );
    false
}

/// Directory of the OpenSubdiv regression shapes: `$SUBSURF_SHAPES_DIR`, else
/// `<repo>/testdata/shapes`, else the first `shared/shapes` beside the repository or one
/// of its ancestors.
pub fn shapes_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("SUBSURF_SHAPES_DIR") {
        return PathBuf::from(dir);
    }
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let local = repo.join("testdata/shapes");
    if local.is_dir() {
        return local;
    }
    let repo = repo.canonicalize().expect("repository root");
    repo.ancestors()
        .skip(1)
        .map(|a| a.join("shared/shapes"))
        .find(|d| d.is_dir())
        .unwrap_or_else(|| panic!("no shapes directory near {}", repo.display()))
}

/// Reads `<shapes_dir>/<name>.obj`.
pub fn load_shape(name: &str) -> Mesh {
    let path = shapes_dir().join(format!("{name}.obj"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_obj(&text)
}

/// A minimal reader for the shapes' OBJ dialect: `v`, `vt`, `f` (1-based `v[/vt[/vn]]`)
/// and the `t` tags crease, corner, hole, interpolateboundary, creasemethod,
/// smoothtriangles. UVs are kept only when every face corner has one.
pub fn parse_obj(text: &str) -> Mesh {
    let mut m = Mesh::default();
    let mut uv_values = Vec::new();
    let mut uv_indices = Vec::new();
    let mut all_uvs = true;
    for line in text.lines() {
        let mut w = line.split_whitespace();
        match w.next() {
            Some("v") => {
                let p: Vec<f32> = w.take(3).map(|x| x.parse().unwrap()).collect();
                m.positions.push([p[0], p[1], p[2]]);
            }
            Some("vt") => {
                let p: Vec<f32> = w.take(2).map(|x| x.parse().unwrap()).collect();
                uv_values.push([p[0], p[1]]);
            }
            Some("f") => {
                let mut n = 0;
                for c in w {
                    let mut parts = c.split('/');
                    m.face_indices
                        .push(parts.next().unwrap().parse::<u32>().unwrap() - 1);
                    match parts.next().filter(|s| !s.is_empty()) {
                        Some(t) => uv_indices.push(t.parse::<u32>().unwrap() - 1),
                        None => all_uvs = false,
                    }
                    n += 1;
                }
                m.face_counts.push(n);
            }
            Some("t") => parse_tag(&mut m, w.collect()),
            _ => {}
        }
    }
    if all_uvs && !uv_values.is_empty() {
        m.uvs = Some(FaceVarying {
            values: uv_values,
            indices: uv_indices,
        });
    }
    m
}

fn parse_tag(m: &mut Mesh, w: Vec<&str>) {
    let counts: Vec<usize> = w[1].split('/').map(|x| x.parse().unwrap()).collect();
    let ints: Vec<u32> = w[2..2 + counts[0]]
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    let floats: Vec<f32> = w[2 + counts[0]..2 + counts[0] + counts[1]]
        .iter()
        .map(|x| x.parse().unwrap())
        .collect();
    let strings = &w[2 + counts[0] + counts[1]..];
    match w[0] {
        "crease" => {
            for (k, pair) in ints.chunks_exact(2).enumerate() {
                let s = floats[k.min(floats.len() - 1)];
                m.creases.push(Crease {
                    v0: pair[0],
                    v1: pair[1],
                    sharpness: s,
                });
            }
        }
        "corner" => {
            for (k, &v) in ints.iter().enumerate() {
                m.corners.push(Corner {
                    vertex: v,
                    sharpness: floats[k.min(floats.len() - 1)],
                });
            }
        }
        "hole" => m.holes.extend(ints),
        "interpolateboundary" => {
            m.options.boundary = match ints[0] {
                0 => BoundaryInterpolation::None,
                1 => BoundaryInterpolation::EdgeAndCorner,
                _ => BoundaryInterpolation::EdgeOnly,
            }
        }
        "creasemethod" if strings.first() == Some(&"chaikin") => {
            m.options.crease_method = CreaseMethod::Chaikin
        }
        "smoothtriangles" if strings.first() == Some(&"smooth") => {
            m.options.triangle_subdivision = TriangleSubdivision::Smooth
        }
        _ => {}
    }
}

/// Undirected edges of a face list, each once.
pub fn unique_edges(face_counts: &[u32], face_indices: &[u32]) -> Vec<[u32; 2]> {
    let mut edges = Vec::new();
    let mut k = 0;
    for &n in face_counts {
        let f = &face_indices[k..k + n as usize];
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            edges.push([a.min(b), a.max(b)]);
        }
        k += n as usize;
    }
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Euclidean distance.
pub fn dist(a: [f32; 3], b: [f32; 3]) -> f32 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
