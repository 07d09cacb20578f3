//! `subsurf::patch` triangular bases (Loop's quartic box spline with every boundary mask,
//! and the quartic Gregory triangle) against OpenSubdiv's `Far::internal::EvaluatePatchBasis`,
//! including the sub-triangle parameterization (upright and rotated children) and the
//! derivative scaling to the base face.

#[macro_use]
mod common;

use osd_ref::{patch_basis, OsdPatchType};
use subsurf::patch::{tri_patch_weights, PatchParam, PatchParamFields, TriPatchKind};

/// Every valid 5-bit mask: edges (upper bits 0), corners (1), edges plus opposite corners (2).
fn masks() -> impl Iterator<Item = u8> {
    (0..3u8).flat_map(|upper| (0..8u8).map(move |low| (upper << 3) | low))
}

/// Patches at several depths, upright and rotated.
fn params(boundary: u8) -> Vec<PatchParam> {
    [
        (0u8, 0u16, 0u16),
        (1, 1, 1),
        (1, 0, 1),
        (2, 1, 2),
        (2, 3, 1),
        (3, 4, 2),
        (3, 2, 5),
    ]
    .into_iter()
    .map(|(depth, u, v)| {
        PatchParam::new(PatchParamFields {
            face_id: 5,
            u,
            v,
            depth,
            boundary,
            regular: true,
            ..Default::default()
        })
        .unwrap()
    })
    .collect()
}

/// Samples inside the patch's own triangle, mapped to the base face.
fn samples(p: &PatchParam) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 0..=4 {
        for j in 0..=(4 - i) {
            let (s, t) = (i as f64 / 4.0, j as f64 / 4.0);
            out.push(p.unnormalize_triangle(s * 0.98 + 0.005, t * 0.98 + 0.005));
        }
    }
    out
}

fn compare(kind: TriPatchKind, ty: OsdPatchType, mask: u8) -> f64 {
    let mut worst = 0.0f64;
    for p in params(mask) {
        for (u, v) in samples(&p) {
            let ours = tri_patch_weights(kind, &p, u, v);
            let theirs = patch_basis(ty, p.field0, p.field1, u, v).unwrap();
            assert_eq!(theirs.n, kind.num_points());
            let rows = [ours.p, ours.du, ours.dv, ours.duu, ours.duv, ours.dvv];
            // Relative to the scale of the derivative order at this depth.
            let scale =
                [1.0, 1.0, 1.0, 2.0, 2.0, 2.0].map(|e: f64| ((1u32 << p.depth()) as f64).powf(e));
            for (k, row) in rows.iter().enumerate() {
                for i in 0..theirs.n {
                    worst = worst.max((row[i] - theirs.w[k][i]).abs() / scale[k]);
                }
            }
        }
    }
    worst
}

#[test]
fn box_spline_matches_opensubdiv_for_every_boundary_mask() {
    require_osd!();
    for mask in masks() {
        let d = compare(TriPatchKind::BoxSpline, OsdPatchType::Loop, mask);
        assert!(d < 1e-12, "boundary mask {mask:#07b}: deviation {d}");
    }
}

#[test]
fn gregory_triangle_matches_opensubdiv() {
    require_osd!();
    let d = compare(
        TriPatchKind::GregoryTriangle,
        OsdPatchType::GregoryTriangle,
        0,
    );
    assert!(d < 1e-12, "deviation {d}");
}

/// The comparison has teeth: an interior patch's weights differ from a boundary one's.
#[test]
fn boundary_masks_change_the_weights() {
    require_osd!();
    let p = params(0)[3];
    // A sample near edge 0, whose phantom points carry the most weight.
    let (u, v) = samples(&p)[9];
    let theirs = patch_basis(OsdPatchType::Loop, p.field0, p.field1 | (1 << 7), u, v).unwrap();
    let ours = tri_patch_weights(TriPatchKind::BoxSpline, &p, u, v);
    let d = (0..12)
        .map(|i| (ours.p[i] - theirs.w[0][i]).abs())
        .fold(0.0, f64::max);
    assert!(d > 1e-3);
}

/// A jittered triangulated `n × n` grid: vertex `(x, y)` is `y (n+1) + x`; cell `(x, y)` is
/// split along its diagonal into the lower triangle `(x,y), (x+1,y), (x+1,y+1)` and the
/// upper one `(x,y), (x+1,y+1), (x,y+1)`. Its lattice has the directions `(1,0)`, `(1,1)`,
/// `(0,1)`, so every interior vertex has valence 6 and every non-corner boundary vertex 3
/// faces: a regular Loop mesh away from its four corners.
struct TriGrid {
    n: i64,
    pos: Vec<[f32; 3]>,
    indices: Vec<u32>,
    /// Lattice coordinates of the corners of each face.
    corners: Vec<[(i64, i64); 3]>,
}

fn tri_grid(n: i64, seed: u64) -> TriGrid {
    let mut state = seed;
    let mut rnd = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as f64 / (1u64 << 31) as f64 - 0.5) as f32
    };
    let mut pos = Vec::new();
    for y in 0..=n {
        for x in 0..=n {
            pos.push([x as f32 + 0.2 * rnd(), y as f32 + 0.2 * rnd(), 0.6 * rnd()]);
        }
    }
    let mut g = TriGrid {
        n,
        pos,
        indices: Vec::new(),
        corners: Vec::new(),
    };
    for y in 0..n {
        for x in 0..n {
            for tri in [
                [(x, y), (x + 1, y), (x + 1, y + 1)],
                [(x, y), (x + 1, y + 1), (x, y + 1)],
            ] {
                g.indices.extend(tri.map(|(a, b)| g.index(a, b)));
                g.corners.push(tri);
            }
        }
    }
    g
}

impl TriGrid {
    fn index(&self, x: i64, y: i64) -> u32 {
        (y.clamp(0, self.n) * (self.n + 1) + x.clamp(0, self.n)) as u32
    }

    fn on_border(&self, (x, y): (i64, i64)) -> bool {
        x == 0 || y == 0 || x == self.n || y == self.n
    }

    fn num_faces_at(&self, v: (i64, i64)) -> usize {
        self.corners.iter().filter(|c| c.contains(&v)).count()
    }

    /// Regular for Loop: 6 faces inside, 3 on the boundary.
    fn is_regular(&self, v: (i64, i64)) -> bool {
        self.num_faces_at(v) == if self.on_border(v) { 3 } else { 6 }
    }

    fn edge_is_boundary(&self, a: (i64, i64), b: (i64, i64)) -> bool {
        self.corners
            .iter()
            .filter(|c| c.contains(&a) && c.contains(&b))
            .count()
            == 1
    }

    /// The 12 box-spline points of face `f` in OpenSubdiv's order: point `(i, j)` of the
    /// patch lattice is corner 0 + `i` (corner 1 − corner 0) + `j` (corner 2 − corner 0).
    /// Points beyond the grid are clamped (phantoms, of weight 0).
    fn patch_points(&self, f: usize) -> [[f64; 3]; 12] {
        const LOCAL: [(i64, i64); 12] = [
            (0, -1),
            (1, -1),
            (2, -1),
            (-1, 0),
            (0, 0),
            (1, 0),
            (2, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
            (-1, 2),
            (0, 2),
        ];
        let [c0, c1, c2] = self.corners[f];
        let a = (c1.0 - c0.0, c1.1 - c0.1);
        let b = (c2.0 - c0.0, c2.1 - c0.1);
        LOCAL.map(|(i, j)| {
            let p =
                self.pos[self.index(c0.0 + i * a.0 + j * b.0, c0.1 + i * a.1 + j * b.1) as usize];
            p.map(f64::from)
        })
    }

    /// OpenSubdiv's 5-bit boundary mask of face `f`.
    fn boundary_mask(&self, f: usize) -> u8 {
        let c = self.corners[f];
        let edges = (0..3).fold(0u8, |m, k| {
            m | ((self.edge_is_boundary(c[k], c[(k + 1) % 3]) as u8) << k)
        });
        let verts = (0..3).fold(0u8, |m, k| m | ((self.on_border(c[k]) as u8) << k));
        if edges == 0 {
            if verts == 0 {
                0
            } else {
                (1 << 3) | verts
            }
        } else {
            let opposite = ((edges & 1) << 2) | (edges >> 1);
            if verts & opposite & !edges_vertices(edges) != 0 {
                (2 << 3) | edges
            } else {
                edges
            }
        }
    }
}

/// Corners lying on the given boundary edges.
fn edges_vertices(edges: u8) -> u8 {
    (0..3).fold(0, |m, k| {
        if edges & (1 << k) != 0 {
            m | (1 << k) | (1 << ((k + 1) % 3))
        } else {
            m
        }
    })
}

#[test]
fn regular_loop_patches_match_opensubdiv_limit_surface() {
    require_osd!();
    let g = tri_grid(5, 41);
    let counts = vec![3u32; g.corners.len()];
    let mut mesh = osd_ref::OsdMesh::new(&g.pos, &counts, &g.indices);
    mesh.options.scheme = osd_ref::OsdScheme::Loop;
    let o = osd_ref::PatchOptions {
        isolation_level: 2,
        ..Default::default()
    };
    let samples = osd_ref::eval_limit_grid_with(&mesh, 7, &o).unwrap();
    let mut worst = 0.0f64;
    let mut masks_seen = std::collections::BTreeSet::new();
    let mut compared = 0;
    for s in &samples {
        let f = s.face as usize;
        if !g.corners[f].iter().all(|&v| g.is_regular(v)) {
            continue;
        }
        let mask = g.boundary_mask(f);
        masks_seen.insert(mask);
        let e =
            subsurf::patch::eval_box_spline_patch(&g.patch_points(f), s.u as f64, s.v as f64, mask);
        for k in 0..3 {
            let d = (e.p[k] - s.p[k] as f64)
                .abs()
                .max((e.du[k] - s.du[k] as f64).abs())
                .max((e.dv[k] - s.dv[k] as f64).abs());
            worst = worst.max(d);
        }
        compared += 1;
    }
    // Interior patches, boundary-edge patches and boundary-vertex patches were all seen.
    assert!(
        masks_seen.contains(&0) && masks_seen.len() >= 4,
        "{masks_seen:?}"
    );
    assert!(compared > 28 * 20, "{compared} samples compared");
    assert!(worst < 2e-5, "largest deviation from OpenSubdiv: {worst}");
}
