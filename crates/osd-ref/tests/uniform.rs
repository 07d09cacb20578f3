//! Self-tests of the uniform-refinement side of the shim against closed-form results.

#[macro_use]
mod common;

use common::{dist, load_shape, unique_edges};
use osd_ref::{refine_uniform, Error, OsdBoundary, OsdMesh, OsdRefiner, OsdScheme, OsdStencils};

fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f32; 3], s: f32) -> [f32; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn centroid(points: impl Iterator<Item = [f32; 3]>) -> [f32; 3] {
    let (mut sum, mut n) = ([0.0; 3], 0.0);
    for p in points {
        sum = add(sum, p);
        n += 1.0;
    }
    scale(sum, 1.0 / n)
}

fn unit_cube() -> (Vec<[f32; 3]>, Vec<u32>, Vec<u32>) {
    let mut pos = Vec::new();
    for i in 0..8u32 {
        pos.push([(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32]);
    }
    // Counter-clockwise seen from outside.
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    (pos, vec![4; 6], faces.concat())
}

/// Level 1 of a cube against Catmull & Clark (1978): face point = centroid; edge point =
/// average of the two ends and the two adjacent face points; vertex point =
/// (Q + 2R + (n − 3)S)/n with Q the average of adjacent face points, R of adjacent edge
/// midpoints, S the vertex, n its valence. OpenSubdiv orders vertex points first, then face
/// points, then edge points.
#[test]
fn cube_level1_matches_catmull_clark_rules() {
    require_osd!();
    let (pos, counts, idx) = unit_cube();
    let levels = refine_uniform(&OsdMesh::new(&pos, &counts, &idx), 1).unwrap();
    assert_eq!(levels.len(), 2);
    assert_eq!(levels[0].positions, pos);
    let l1 = &levels[1];
    assert_eq!(
        (
            l1.positions.len(),
            l1.face_counts.len(),
            l1.edge_verts.len()
        ),
        (26, 24, 48)
    );
    assert!(l1.face_counts.iter().all(|&c| c == 4));

    let faces: Vec<&[u32]> = idx.chunks(4).collect();
    let face_pts: Vec<[f32; 3]> = faces
        .iter()
        .map(|f| centroid(f.iter().map(|&v| pos[v as usize])))
        .collect();
    let edges = unique_edges(&counts, &idx);
    let faces = &faces;
    let edge_faces =
        |e: [u32; 2]| (0..6).filter(move |&f| faces[f].contains(&e[0]) && faces[f].contains(&e[1]));
    let edge_pts: Vec<[f32; 3]> = edges
        .iter()
        .map(|&e| {
            let fp = edge_faces(e).map(|f| face_pts[f]);
            centroid(
                [pos[e[0] as usize], pos[e[1] as usize]]
                    .into_iter()
                    .chain(fp),
            )
        })
        .collect();
    let vert_pts: Vec<[f32; 3]> = (0..8u32)
        .map(|v| {
            let q = centroid(
                (0..6)
                    .filter(|&f| faces[f].contains(&v))
                    .map(|f| face_pts[f]),
            );
            let mids = edges.iter().filter(|e| e.contains(&v));
            let r = centroid(mids.map(|e| scale(add(pos[e[0] as usize], pos[e[1] as usize]), 0.5)));
            let n = 3.0;
            scale(
                add(add(q, scale(r, 2.0)), scale(pos[v as usize], n - 3.0)),
                1.0 / n,
            )
        })
        .collect();

    let groups = [(0..8, &vert_pts), (8..14, &face_pts), (14..26, &edge_pts)];
    for (range, expected) in groups {
        let mut unmatched: Vec<[f32; 3]> = expected.clone();
        for p in &l1.positions[range] {
            let k = unmatched.iter().position(|e| dist(*e, *p) < 1e-6);
            let k = k.unwrap_or_else(|| panic!("OpenSubdiv point {p:?} matches no expected point"));
            unmatched.swap_remove(k);
        }
        assert!(unmatched.is_empty());
    }
}

/// On catmark_car (all quads, with boundary and creases) every level obeys
/// V' = V + E + F, E' = 2E + Σ|f|, F' = Σ|f|, and level 0 has the OBJ's own edge count.
#[test]
fn car_counts_follow_refinement_recurrences() {
    require_osd!();
    let mesh = load_shape("catmark_car");
    let levels = refine_uniform(&OsdMesh::from(&mesh), 3).unwrap();
    assert_eq!(
        levels[0].edge_verts.len(),
        unique_edges(&mesh.face_counts, &mesh.face_indices).len()
    );
    assert_eq!(levels[0].positions.len(), mesh.positions.len());
    for w in levels.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let corners: usize = a.face_counts.iter().map(|&c| c as usize).sum();
        assert_eq!(
            b.positions.len(),
            a.positions.len() + a.edge_verts.len() + a.face_counts.len()
        );
        assert_eq!(b.edge_verts.len(), 2 * a.edge_verts.len() + corners);
        assert_eq!(b.face_counts.len(), corners);
        assert_eq!(b.face_verts.len(), 4 * b.face_counts.len());
        let nv = b.positions.len() as u32;
        assert!(b
            .face_verts
            .iter()
            .chain(b.edge_verts.iter().flatten())
            .all(|&v| v < nv));
        let (uvs, uv_idx) = b.uvs.as_ref().expect("the car has UVs");
        assert_eq!(uv_idx.len(), b.face_verts.len());
        assert!(uv_idx.iter().all(|&i| (i as usize) < uvs.len()));
    }
}

/// A flat grid with UV = (x, y): with corners kept sharp, Catmull-Clark reproduces the
/// bilinear parameterisation, and linear face-varying interpolation (FVAR_LINEAR_ALL)
/// gives bilinear UVs, so at every refined face corner UV equals the position's (x, y).
#[test]
fn flat_grid_uvs_follow_positions() {
    require_osd!();
    let n = 3u32;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push([i as f32, j as f32, 0.0]);
        }
    }
    let uvs: Vec<[f32; 2]> = pos.iter().map(|p| [p[0], p[1]]).collect();
    let mut idx = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            idx.extend([v, v + 1, v + n + 2, v + n + 1]);
        }
    }
    let counts = vec![4; (n * n) as usize];
    let mut mesh = OsdMesh::new(&pos, &counts, &idx);
    mesh.uvs = Some((&uvs, &idx));
    mesh.options.boundary = OsdBoundary::EdgeAndCorner;
    let levels = refine_uniform(&mesh, 2).unwrap();
    for l in &levels {
        let (values, fv) = l.uvs.as_ref().unwrap();
        for (c, &v) in l.face_verts.iter().enumerate() {
            let (p, uv) = (l.positions[v as usize], values[fv[c] as usize]);
            assert!(
                (p[0] - uv[0]).abs() < 1e-5 && (p[1] - uv[1]).abs() < 1e-5,
                "{p:?} vs {uv:?}"
            );
        }
    }
    assert_eq!(levels[2].positions.len(), 13 * 13);
}

/// The three routes to the last level agree: all levels at once, the last level only, and
/// the factorized stencil table.
#[test]
fn refiner_interpolate_and_stencils_agree() {
    require_osd!();
    let mesh = load_shape("catmark_car");
    let osd = OsdMesh::from(&mesh);
    let levels = refine_uniform(&osd, 2).unwrap();
    let refiner = OsdRefiner::new(&osd, 2).unwrap();
    assert_eq!(refiner.num_vertices(2), levels[2].positions.len());
    let last = refiner.interpolate(&mesh.positions).unwrap();
    assert_eq!(last, levels[2].positions);
    let stencils = OsdStencils::new(&refiner).unwrap();
    assert_eq!(stencils.num_stencils(), last.len());
    let via_stencils = stencils.update(&mesh.positions).unwrap();
    let worst = last
        .iter()
        .zip(&via_stencils)
        .map(|(a, b)| dist(*a, *b))
        .fold(0.0, f32::max);
    assert!(worst < 1e-4, "stencils differ by {worst}");
}

/// Hole tags come back on level 0 and propagate to the children of the hole.
#[test]
fn holes_are_reported_per_level() {
    require_osd!();
    let mesh = load_shape("catmark_hole_test1");
    assert!(!mesh.holes.is_empty());
    let levels = refine_uniform(&OsdMesh::from(&mesh), 1).unwrap();
    let tagged: Vec<u32> = (0..mesh.num_faces() as u32)
        .filter(|&f| levels[0].face_is_hole[f as usize])
        .collect();
    let mut holes = mesh.holes.clone();
    holes.sort_unstable();
    assert_eq!(tagged, holes);
    let child_holes = levels[1].face_is_hole.iter().filter(|&&h| h).count();
    let expected: u32 = holes.iter().map(|&f| mesh.face_counts[f as usize]).sum();
    assert_eq!(child_holes, expected as usize);
}

#[test]
fn bad_input_is_an_error_not_a_crash() {
    require_osd!();
    let (pos, counts, mut idx) = unit_cube();
    idx[3] = 99;
    let err = refine_uniform(&OsdMesh::new(&pos, &counts, &idx), 1).unwrap_err();
    assert!(matches!(err, Error::Invalid(_)), "{err}");

    // Loop subdivision of quads is refused by OpenSubdiv itself.
    let (pos, counts, idx) = unit_cube();
    let mut mesh = OsdMesh::new(&pos, &counts, &idx);
    mesh.options.scheme = OsdScheme::Loop;
    let err = refine_uniform(&mesh, 1).unwrap_err();
    assert!(matches!(err, Error::Osd(_)), "{err}");
}

/// Without OpenSubdiv every entry point reports `Unavailable`; with it, they work.
#[test]
fn entry_points_follow_availability() {
    let (pos, counts, idx) = unit_cube();
    let mesh = OsdMesh::new(&pos, &counts, &idx);
    let uniform = refine_uniform(&mesh, 1);
    let limit = osd_ref::eval_limit_grid(&mesh, 2, 2, false, osd_ref::EndCap::Gregory);
    if osd_ref::available() {
        assert_eq!(uniform.unwrap()[1].positions.len(), 26);
        assert_eq!(limit.unwrap().len(), 6 * 4);
    } else {
        assert_eq!(uniform.unwrap_err(), Error::Unavailable);
        assert_eq!(limit.unwrap_err(), Error::Unavailable);
        assert_eq!(OsdRefiner::new(&mesh, 1).unwrap_err(), Error::Unavailable);
    }
}
