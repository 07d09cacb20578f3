//! Small shape generators for tests, benches and examples (as pmp-library's `shapes.h`).

use crate::mesh::Mesh;

/// The unit cube `[-1, 1]^3` as six outward-facing quads.
pub fn cube() -> Mesh {
    let p = vec![
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [-1.0, 1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, -1.0],
        [1.0, 1.0, -1.0],
        [-1.0, -1.0, -1.0],
        [1.0, -1.0, -1.0],
    ];
    let f: [[u32; 4]; 6] = [
        [0, 1, 3, 2],
        [2, 3, 5, 4],
        [4, 5, 7, 6],
        [6, 7, 1, 0],
        [1, 7, 5, 3],
        [6, 0, 2, 4],
    ];
    Mesh::from_faces(p, &f)
}

/// An open `nx × ny` grid of quads in the plane z = 0, spacing 1, counter-clockwise seen from +z.
pub fn grid(nx: usize, ny: usize) -> Mesh {
    let mut p = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            p.push([i as f32, j as f32, 0.0]);
        }
    }
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut faces = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh::from_faces(p, &faces)
}

/// A closed torus of `nu × nv` quads (every vertex has valence 4), radii `big` and `small`.
pub fn torus(nu: usize, nv: usize, big: f32, small: f32) -> Mesh {
    let mut p = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        let b = j as f32 / nv as f32 * std::f32::consts::TAU;
        for i in 0..nu {
            let a = i as f32 / nu as f32 * std::f32::consts::TAU;
            let r = big + small * b.cos();
            p.push([r * a.cos(), r * a.sin(), small * b.sin()]);
        }
    }
    let id = |i: usize, j: usize| ((j % nv) * nu + (i % nu)) as u32;
    let mut faces = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh::from_faces(p, &faces)
}

/// A disk of `n` quads around one interior vertex of valence `n` (a "pole"), with a boundary.
pub fn pole(n: usize) -> Mesh {
    let mut p = vec![[0.0, 0.0, 0.0]];
    for k in 0..2 * n {
        let a = k as f32 / (2 * n) as f32 * std::f32::consts::TAU;
        let r = if k % 2 == 0 { 1.0 } else { 1.2 };
        p.push([r * a.cos(), r * a.sin(), 0.1 * (k % 3) as f32]);
    }
    let ring = |k: usize| (1 + k % (2 * n)) as u32;
    let faces: Vec<[u32; 4]> = (0..n)
        .map(|i| [0, ring(2 * i), ring(2 * i + 1), ring(2 * i + 2)])
        .collect();
    Mesh::from_faces(p, &faces)
}

/// [`pole`]`(n)` with face 2 a hole and a semi-sharp crease (sharpness 2.5) on its first edge:
/// every patch kind in a small mesh (regular patches with and without boundary folds,
/// single-crease and Gregory patches), for tests of the evaluators.
pub fn creased_pole(n: usize) -> Mesh {
    let mut mesh = pole(n);
    mesh.holes.push(2);
    // Edge 0: the first edge of face 0 (edges are numbered face by face, corner by corner).
    let (v0, v1) = (mesh.face_indices[0], mesh.face_indices[1]);
    mesh.creases.push(crate::mesh::Crease {
        v0,
        v1,
        sharpness: 2.5,
    });
    mesh
}

/// The OBJ files of `dir` whose names start with one of `prefixes` (OpenSubdiv's regression
/// shapes: `catmark_`, `bilinear_`, …), sorted by name.
pub fn regression_shapes(
    dir: &std::path::Path,
    prefixes: &[&str],
) -> std::io::Result<Vec<std::path::PathBuf>> {
    let mut v = Vec::new();
    for e in std::fs::read_dir(dir)? {
        let path = e?.path();
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        if let Some(n) = name {
            if n.ends_with(".obj") && prefixes.iter().any(|p| n.starts_with(p)) {
                v.push(path);
            }
        }
    }
    v.sort();
    Ok(v)
}
