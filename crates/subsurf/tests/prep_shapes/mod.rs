//! Shape generators and helpers shared by the p-rep integration tests.
#![allow(dead_code)]

use subsurf::prep::quadrangulate;
use subsurf::prep::{PrepPatches, Sample};
use subsurf::Mesh;
use subsurf::Real;

/// Unit cube `[0,1]^3`, vertex `(x,y,z)` has index `4x+2y+z` (spec §10).
pub fn cube() -> Mesh {
    let p: Vec<[f32; 3]> = (0..8)
        .map(|i| [(i >> 2) as f32, ((i >> 1) & 1) as f32, (i & 1) as f32])
        .collect();
    let f = [
        [0u32, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    Mesh::from_faces(p, &f)
}

/// Torus with `nu × nv` quads, all valence 4; face `(i, j)` is
/// `[ix(i,j), ix(i+1,j), ix(i+1,j+1), ix(i,j+1)]`, `ix(i,j) = (i mod nu) nv + (j mod nv)`.
pub fn torus(nu: usize, nv: usize) -> Mesh {
    let tau = std::f64::consts::TAU;
    let mut p = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (a, b) = (tau * i as f64 / nu as f64, tau * j as f64 / nv as f64);
            let r = 2.0 + 0.7 * b.cos();
            p.push([
                (r * a.cos()) as f32,
                (r * a.sin()) as f32,
                (0.7 * b.sin()) as f32,
            ]);
        }
    }
    let ix = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    let mut f = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            f.push([ix(i, j), ix(i + 1, j), ix(i + 1, j + 1), ix(i, j + 1)]);
        }
    }
    Mesh::from_faces(p, &f)
}

/// Capped n-gonal prism: cap centres of valence n, corners of valence 3, mid-edges of
/// valence 4 — edges `<n,4>`, `<3,4>`, `<3,3>`, `<4,4>` (same as `verify_prep.py`).
pub fn capped_prism(n: usize) -> Mesh {
    let a = |i: f64| std::f64::consts::TAU * i / n as f64;
    let mut v: Vec<[f64; 3]> = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    for z in [1.0, -1.0] {
        for i in 0..n {
            v.push([a(i as f64).cos(), a(i as f64).sin(), z]);
        }
        for i in 0..n {
            let t = a(i as f64 + 0.5);
            v.push([t.cos(), t.sin(), z]);
        }
    }
    let w = |base: usize, i: isize| (base as isize + i.rem_euclid(n as isize)) as u32;
    let (t, m, b, bm) = (2, 2 + n, 2 + 2 * n, 2 + 3 * n);
    let mut f = Vec::new();
    for i in 0..n as isize {
        f.push([0, w(m, i - 1), w(t, i), w(m, i)]);
        f.push([1, w(bm, i), w(b, i), w(bm, i - 1)]);
        f.push([w(t, i), w(b, i), w(bm, i), w(m, i)]);
        f.push([w(m, i), w(bm, i), w(b, i + 1), w(t, i + 1)]);
    }
    Mesh::from_faces(
        v.iter().map(|p| p.map(|x| x as f32)).collect::<Vec<_>>(),
        &f,
    )
}

/// Vertices of the once-split icosahedron on the unit sphere (42 points, as `verify_prep.py`).
pub fn icosphere1() -> Vec<[f64; 3]> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let norm = |p: [f64; 3]| {
        let l = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|x| x / l)
    };
    let mut v: Vec<[f64; 3]> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .into_iter()
    .map(norm)
    .collect();
    let tris = ICO_TRIS;
    let mut mid = std::collections::HashMap::new();
    for tri in tris {
        for (x, y) in [(tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])] {
            let key = (x.min(y), x.max(y));
            if let std::collections::hash_map::Entry::Vacant(e) = mid.entry(key) {
                let (p, q) = (v[x], v[y]);
                v.push(norm([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                e.insert(v.len() - 1);
            }
        }
    }
    v
}

/// Icosahedron triangles (ccw).
pub const ICO_TRIS: [[usize; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// 40 quads on the icosphere vertices: valences 3–6, every valence pair (from `verify_prep.py`).
pub const MIXED40: [[u32; 4]; 40] = [
    [35, 4, 24, 27],
    [33, 4, 35, 34],
    [7, 19, 20, 12],
    [1, 15, 22, 23],
    [7, 18, 16, 15],
    [23, 9, 32, 41],
    [34, 36, 3, 32],
    [3, 36, 37, 38],
    [30, 17, 1, 23],
    [12, 21, 11, 13],
    [34, 35, 2, 36],
    [37, 6, 39, 8],
    [32, 3, 38, 40],
    [37, 36, 2, 26],
    [28, 29, 19, 7],
    [28, 7, 17, 31],
    [39, 28, 31, 8],
    [28, 39, 6, 29],
    [16, 18, 0, 14],
    [41, 32, 40, 8],
    [15, 1, 17, 7],
    [12, 20, 10, 21],
    [37, 26, 29, 6],
    [12, 0, 18, 7],
    [21, 10, 29, 26],
    [22, 33, 9, 23],
    [8, 40, 38, 37],
    [34, 32, 9, 33],
    [33, 22, 25, 4],
    [8, 30, 23, 41],
    [27, 26, 2, 35],
    [31, 17, 30, 8],
    [5, 14, 0, 12],
    [19, 29, 10, 20],
    [13, 11, 27, 24],
    [13, 24, 4, 25],
    [11, 21, 26, 27],
    [16, 14, 5, 15],
    [15, 5, 25, 22],
    [12, 13, 25, 5],
];

/// The mixed 40-quad mesh (valences 3–6 with adjacent extraordinary vertices).
pub fn mixed40() -> Mesh {
    let p: Vec<[f32; 3]> = icosphere1().iter().map(|p| p.map(|x| x as f32)).collect();
    Mesh::from_faces(p, &MIXED40)
}

/// Deterministic non-symmetric perturbation, as `verify_prep.py`'s `wobble`.
pub fn wobble(mut m: Mesh, a: f64) -> Mesh {
    for (i, p) in m.positions.as_f32_mut().iter_mut().enumerate() {
        for (k, off) in [0.0, 1.7, 3.1].into_iter().enumerate() {
            p[k] = (p[k] as f64 + a * (12.9898 * i as f64 + off).sin()) as f32;
        }
    }
    m
}

/// Icosahedron split into quads: valences 5 (original), 4 (edge midpoints), 3 (centres).
pub fn quad_icosahedron() -> Mesh {
    let v: Vec<[f32; 3]> = icosphere1()[..12]
        .iter()
        .map(|p| p.map(|x| x as f32))
        .collect();
    let tris: Vec<[u32; 3]> = ICO_TRIS.iter().map(|t| t.map(|x| x as u32)).collect();
    quadrangulate(&Mesh::from_faces(v, &tris)).unwrap()
}

/// Octahedron split into quads: valences 4 and 3.
pub fn quad_octahedron() -> Mesh {
    let v = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let t = [
        [0u32, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    quadrangulate(&Mesh::from_faces(v, &t)).unwrap()
}

/// An n-pole "spindle": poles of valence `n`, `bands` bands of `2n` quads between rims of
/// `2n` vertices; the first rim alternates valence 3 and 4 (as in [`capped_prism`], which is
/// the one-band case with a different profile).
pub fn spindle(n: usize, bands: usize) -> Mesh {
    let m = 2 * n;
    let mut p: Vec<[f32; 3]> = vec![[0.0, 0.0, 1.6], [0.0, 0.0, -1.6]];
    for r in 0..=bands {
        let z = 1.2 - 2.4 * r as f64 / bands as f64;
        let rad =
            0.5 + 0.5 * (std::f64::consts::PI * (r as f64 + 0.5) / (bands as f64 + 1.0)).sin();
        for j in 0..m {
            let th = std::f64::consts::PI * j as f64 / n as f64;
            let rr = rad * (1.0 + 0.1 * (j % 2) as f64);
            p.push([(rr * th.cos()) as f32, (rr * th.sin()) as f32, z as f32]);
        }
    }
    let rim = |r: usize, j: isize| (2 + r * m + j.rem_euclid(m as isize) as usize) as u32;
    let mut f: Vec<[u32; 4]> = Vec::new();
    for i in 0..n as isize {
        f.push([0, rim(0, 2 * i - 1), rim(0, 2 * i), rim(0, 2 * i + 1)]);
        f.push([
            1,
            rim(bands, 2 * i + 1),
            rim(bands, 2 * i),
            rim(bands, 2 * i - 1),
        ]);
    }
    for r in 0..bands {
        for j in 0..m as isize {
            f.push([rim(r, j), rim(r + 1, j), rim(r + 1, j + 1), rim(r, j + 1)]);
        }
    }
    Mesh::from_faces(p, &f)
}

/// Reads an OBJ's `v` and `f` lines.
pub fn read_obj(path: &str) -> Mesh {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut p = Vec::new();
    let mut f: Vec<Vec<u32>> = Vec::new();
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first() {
            Some(&"v") => p.push([1, 2, 3].map(|k| w[k].parse::<f32>().unwrap())),
            Some(&"f") => f.push(
                w[1..]
                    .iter()
                    .map(|s| s.split('/').next().unwrap().parse::<u32>().unwrap() - 1)
                    .collect(),
            ),
            _ => {}
        }
    }
    Mesh::from_faces(p, &f)
}

/// Path of a test OBJ in `tests/data/prep`.
pub fn data(name: &str) -> String {
    format!("{}/tests/data/prep/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// The closed test meshes with their names.
pub fn closed_meshes() -> Vec<(&'static str, Mesh)> {
    vec![
        ("cube", cube()),
        ("cube, wobbled", wobble(cube(), 0.03)),
        ("capped prism 3", wobble(capped_prism(3), 0.02)),
        ("capped prism 5, wobbled", wobble(capped_prism(5), 0.03)),
        ("capped prism 6", capped_prism(6)),
        ("capped prism 7, wobbled", wobble(capped_prism(7), 0.02)),
        ("capped prism 8", capped_prism(8)),
        ("mixed40", mixed40()),
        ("mixed40, wobbled", wobble(mixed40(), 0.02)),
        ("quad icosahedron", quad_icosahedron()),
        ("quad octahedron, wobbled", wobble(quad_octahedron(), 0.03)),
        (
            "mixed40 quadrangulated",
            quadrangulate(&wobble(mixed40(), 0.02)).unwrap(),
        ),
        ("spindle 5", spindle(5, 3)),
        ("spindle 6, wobbled", wobble(spindle(6, 2), 0.02)),
        ("spindle 7", spindle(7, 3)),
        ("spindle 8, wobbled", wobble(spindle(8, 4), 0.02)),
        ("torus 8x6, wobbled", wobble(torus(8, 6), 0.03)),
        ("catmark_cube", read_obj(&data("catmark_cube.obj"))),
        (
            "catmark_toroidal_tet",
            read_obj(&data("catmark_toroidal_tet.obj")),
        ),
        ("catmark_torus", read_obj(&data("catmark_torus.obj"))),
        (
            "catmark_lefthanded",
            read_obj(&data("catmark_lefthanded.obj")),
        ),
    ]
}

/// Sample at local parameter `t` of the edge leaving corner `c` of `face` (local `(t, 0)`).
pub fn eval_on_edge<T: Real>(p: &PrepPatches<T>, face: usize, c: usize, t: f64) -> Sample<T> {
    let (u, v) = match c {
        0 => (t, 0.0),
        1 => (1.0, t),
        2 => (1.0 - t, 1.0),
        _ => (0.0, 1.0 - t),
    };
    p.eval(face, T::from_f64(u), T::from_f64(v))
}

/// For each edge, its two face corners `4 f + c`.
pub fn edge_corners<T: Real>(p: &PrepPatches<T>) -> Vec<[usize; 2]> {
    let topo = &p.topology();
    let mut out = vec![[usize::MAX; 2]; topo.num_edges()];
    for (i, &e) in topo.face_edges().iter().enumerate() {
        let slot = &mut out[e as usize];
        if slot[0] == usize::MAX {
            slot[0] = i;
        } else {
            slot[1] = i;
        }
    }
    out
}

/// Angle in radians between two vectors, computed in f64.
pub fn angle<T: Real>(a: [T; 3], b: [T; 3]) -> f64 {
    let (a, b) = (a.map(|x| x.to_f64()), b.map(|x| x.to_f64()));
    let d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let x = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt().atan2(d)
}

/// Largest angle (radians) between the normals of the two patches along every shared edge,
/// `samples` points per edge (both ends included).
pub fn max_normal_angle<T: Real>(p: &PrepPatches<T>, samples: usize) -> f64 {
    let mut worst = 0.0f64;
    for [a, b] in edge_corners(p) {
        let ((f1, c1), (f2, c2)) = ((a / 4, a % 4), (b / 4, b % 4));
        for s in 0..samples {
            let t = s as f64 / (samples - 1) as f64;
            let n1 = eval_on_edge(p, f1, c1, t).normal();
            let n2 = eval_on_edge(p, f2, c2, 1.0 - t).normal();
            worst = worst.max(angle(n1, n2));
        }
    }
    worst
}
