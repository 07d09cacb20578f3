//! Helpers shared by the shim's self-tests: locating and reading the regression shapes,
//! and skipping loudly when OpenSubdiv is absent.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use subsurf::{FVarLinearInterpolation, Mesh};

/// Every `FVarLinearInterpolation` mode with OpenSubdiv's integer code for it (0 NONE …
/// 5 ALL).
pub const MODES: [(FVarLinearInterpolation, u8); 6] = [
    (FVarLinearInterpolation::None, 0),
    (FVarLinearInterpolation::CornersOnly, 1),
    (FVarLinearInterpolation::CornersPlus1, 2),
    (FVarLinearInterpolation::CornersPlus2, 3),
    (FVarLinearInterpolation::Boundaries, 4),
    (FVarLinearInterpolation::All, 5),
];

/// `require_osd!()` at the top of a test: returns from it (after a loud message) when
/// OpenSubdiv is missing, and fails under CI.
#[allow(unused_macros)]
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
    osd_ref::available_or_skip(test)
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

/// Reads `<shapes_dir>/<name>.obj` with subsurf's OBJ reader (tags, UVs, scheme from the
/// name prefix).
pub fn load_shape(name: &str) -> Mesh {
    let path = shapes_dir().join(format!("{name}.obj"));
    subsurf::io::obj::read_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
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

/// Names (without `.obj`) of the regression shapes whose names start with one of `prefixes`,
/// sorted.
pub fn shape_names(prefixes: &[&str]) -> Vec<String> {
    subsurf::shapes::regression_shapes(&shapes_dir(), prefixes)
        .expect("testdata/shapes is readable")
        .iter()
        .filter_map(|p| Some(p.file_stem()?.to_string_lossy().into_owned()))
        .collect()
}

/// `m` for OpenSubdiv with face-varying interpolation `fvar_interp` (one of [`MODES`]' codes).
pub fn osd_mesh(m: &Mesh, fvar_interp: u8) -> osd_ref::OsdMesh<'_> {
    let mut o = osd_ref::OsdMesh::from(m);
    o.options.fvar_interp = fvar_interp;
    o
}

/// Largest side of the UVs' bounding box.
pub fn uv_extent(values: &[[f32; 2]]) -> f32 {
    let mut lo = [f32::MAX; 2];
    let mut hi = [f32::MIN; 2];
    for v in values {
        for c in 0..2 {
            lo[c] = lo[c].min(v[c]);
            hi[c] = hi[c].max(v[c]);
        }
    }
    (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-30)
}

/// Calls `each(name, pool, mesh)` for each shape of `names` with random face-varying layouts
/// (fixed seed): every corner draws its value index from a pool of 2, 3 or 5 values, so
/// seams, darts, disjoint values and repeated values around a vertex are everywhere.
pub fn for_random_uv_layouts(names: &[&str], mut each: impl FnMut(&str, u64, &Mesh)) {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for name in names {
        let mut mesh =
            subsurf::io::obj::read_file(shapes_dir().join(format!("{name}.obj"))).unwrap();
        for pool in [2u64, 3, 5] {
            let values: Vec<[f32; 2]> = (0..pool)
                .map(|k| [(k as f32 * 0.37).fract(), (k as f32 * 0.61).fract()])
                .collect();
            let indices = mesh
                .face_indices
                .iter()
                .map(|_| (next() % pool) as u32)
                .collect();
            mesh.uvs = Some(subsurf::FaceVarying { values, indices });
            each(name, pool, &mesh);
        }
    }
}
