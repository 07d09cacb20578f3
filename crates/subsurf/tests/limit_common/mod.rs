//! Helpers shared by the limit-surface tests: shapes, the loud OpenSubdiv skip, measures.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

use subsurf::Mesh;

/// Returns false (after a loud message) when OpenSubdiv is missing; panics under CI.
pub fn osd_or_skip(test: &str) -> bool {
    osd_ref::available_or_skip(test)
}

/// `<repo>/testdata/shapes`.
pub fn shapes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../testdata/shapes")
}

/// Reads a regression shape by name.
pub fn load_shape(name: &str) -> Mesh {
    let path = shapes_dir().join(format!("{name}.obj"));
    subsurf::io::obj::read_file(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Names of every `catmark_*` shape, sorted.
pub fn shape_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(shapes_dir())
        .unwrap()
        .filter_map(|e| {
            let n = e.ok()?.file_name().into_string().ok()?;
            let stem = n.strip_suffix(".obj")?;
            stem.starts_with("catmark_").then(|| stem.to_string())
        })
        .collect();
    names.sort();
    names
}

/// Length of the bounding-box diagonal.
pub fn bbox_diagonal(p: &[[f32; 3]]) -> f32 {
    subsurf::mesh::bbox_diagonal(p)
}

/// Patch options isolated to level `l`, the rest default.
pub fn isolated(l: u32) -> subsurf::limit::PatchOptions {
    subsurf::limit::PatchOptions {
        isolation_level: l,
        ..Default::default()
    }
}

/// The distance between two points.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The cross product.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The dot product.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Angle between two non-zero vectors, accurate for small angles.
pub fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = cross(a, b);
    dot(c, c).sqrt().atan2(dot(a, b))
}

/// A small deterministic generator (64-bit LCG, high bits).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self, n: usize) -> usize {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 33) as usize) % n
    }
}
