//! From a subdivision mesh to a renderable triangle mesh: refinement to a level, fan
//! triangulation, smooth vertex normals, per-face colour classes and the control cage.
//!
//! Vertex normals are the normalized sum of the unit normals of the incident faces; a face
//! normal is Newell's normal of the polygon (Newell 1972, as in Sutherland, Sproull and
//! Schumacker 1974), which is robust for non-planar quads.

use anyhow::{bail, Context};
use subsurf::prep::quadrangulate::quadrangulate;
use subsurf::prep::PrepPatches;
use subsurf::topology::tags;
use subsurf::{Mesh, Refiner, Topology};
use subsurf_render::RenderMesh;

/// Colour classes (indices into `subsurf_render::PALETTE`).
pub mod class {
    /// No particular property.
    pub const PLAIN: u8 = 0;
    /// Next to a semi-sharp crease (0 < s < 10).
    pub const SEMI_SHARP: u8 = 1;
    /// Next to an infinitely sharp crease.
    pub const INF_SHARP: u8 = 4;
    /// A p-rep B-quad (bicubic patch, no perturbation).
    pub const B_QUAD: u8 = 2;
    /// A p-rep patch with the bi-5 perturbation.
    pub const PERTURBED: u8 = 1;
    /// A regular B-spline limit patch of a base face.
    pub const REGULAR: u8 = 2;
    /// A regular B-spline limit patch at an adaptive refinement level.
    pub const ADAPTIVE: u8 = 3;
    /// A single-crease limit patch.
    pub const SINGLE_CREASE: u8 = 1;
    /// A Gregory end-cap limit patch.
    pub const END_CAP: u8 = 4;
}

/// Newell's normal of a polygon (twice its vector area).
pub fn newell(positions: &[[f32; 3]], poly: &[u32]) -> [f32; 3] {
    let mut n = [0.0f32; 3];
    for (k, &a) in poly.iter().enumerate() {
        let p = positions[a as usize];
        let q = positions[poly[(k + 1) % poly.len()] as usize];
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    n
}

fn unit(n: [f32; 3]) -> [f32; 3] {
    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if l > 0.0 && l.is_finite() {
        [n[0] / l, n[1] / l, n[2] / l]
    } else {
        [0.0; 3]
    }
}

/// Triangulates polygons (fans from the first corner) and computes smooth vertex normals.
/// `faces` yields each polygon's vertex indices and its colour class.
pub fn triangulate<'a>(
    positions: Vec<[f32; 3]>,
    faces: impl Iterator<Item = (&'a [u32], u8)>,
    with_classes: bool,
) -> RenderMesh {
    let mut normals = vec![[0.0f32; 3]; positions.len()];
    let mut indices = Vec::new();
    let mut classes = Vec::new();
    for (poly, c) in faces {
        let n = unit(newell(&positions, poly));
        for &v in poly {
            let m = &mut normals[v as usize];
            m[0] += n[0];
            m[1] += n[1];
            m[2] += n[2];
        }
        for k in 1..poly.len().saturating_sub(1) {
            indices.extend_from_slice(&[poly[0], poly[k], poly[k + 1]]);
            classes.push(c);
        }
    }
    for n in &mut normals {
        *n = unit(*n);
    }
    RenderMesh {
        positions,
        normals,
        indices,
        triangle_class: with_classes.then_some(classes),
        lines: vec![],
    }
}

/// The edges of the base mesh as line segments.
pub fn cage_lines(topo: &Topology, positions: &[[f32; 3]]) -> Vec<[[f32; 3]; 2]> {
    topo.edge_verts
        .iter()
        .map(|&[a, b]| [positions[a as usize], positions[b as usize]])
        .collect()
}

/// For each face of the last level, its class by the base-mesh creases it touches: an edge
/// of a refined level lies on a tagged base edge exactly when it descends from it (child
/// edges `corners + 2e` and `corners + 2e + 1` of parent edge `e`, see `refine::level`).
/// Boundary and non-manifold edges, sharp by rule rather than by tag, do not count.
pub fn crease_classes(refiner: &Refiner) -> anyhow::Result<Vec<u8>> {
    let base = &refiner.levels[0];
    let mut sharp: Vec<f32> = (0..base.num_edges())
        .map(|e| {
            let t = base.edge_tags[e];
            if t & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD) != 0 {
                0.0
            } else {
                base.edge_sharpness[e]
            }
        })
        .collect();
    for k in 0..refiner.max_level() {
        let (p, c) = (&refiner.levels[k], &refiner.levels[k + 1]);
        let nc = p.face_verts.len();
        if c.num_edges() != nc + 2 * p.num_edges() {
            bail!(
                "unexpected child edge numbering at level {} ({} edges)",
                k + 1,
                c.num_edges()
            );
        }
        let mut child = vec![0.0f32; c.num_edges()];
        for (e, &s) in sharp.iter().enumerate() {
            child[nc + 2 * e] = s;
            child[nc + 2 * e + 1] = s;
        }
        sharp = child;
    }
    let t = refiner.last();
    Ok((0..t.num_faces())
        .map(|f| {
            let s = t
                .face_edges(f)
                .iter()
                .map(|&e| sharp[e as usize])
                .fold(0.0f32, f32::max);
            if s >= subsurf::SHARPNESS_INFINITE {
                class::INF_SHARP
            } else if s > 0.0 {
                class::SEMI_SHARP
            } else {
                class::PLAIN
            }
        })
        .collect())
}

/// Refines `mesh` `level` times and triangulates the last level (holes left out).
pub fn refined(
    mesh: &Mesh,
    level: usize,
    sharpness_classes: bool,
    cage: bool,
) -> anyhow::Result<RenderMesh> {
    let topo = Topology::new(mesh).context("building the topology")?;
    let refiner = Refiner::new(topo, level)?;
    let positions = refiner.refine_positions(&mesh.positions);
    let classes = if sharpness_classes {
        Some(crease_classes(&refiner)?)
    } else {
        None
    };
    let t = refiner.last();
    let faces = (0..t.num_faces()).filter(|&f| !t.face_is_hole[f]).map(|f| {
        let c = classes.as_ref().map_or(class::PLAIN, |c| c[f]);
        (t.face_vertices(f), c)
    });
    let mut out = triangulate(positions, faces, sharpness_classes);
    if cage {
        out.lines = cage_lines(&refiner.levels[0], &mesh.positions);
    }
    Ok(out)
}

/// The p-rep of `mesh` (Myles, Yeo and Peters 2008), tessellated with `n` samples per patch
/// side. Non-quad meshes get one Catmull-Clark step first. With `perturbed = false` the bi-5
/// perturbations are dropped (every patch drawn as its bicubic `g` part), which shows what
/// they correct (the paper's Figure 7). Classes: B-quad or perturbed patch.
pub fn prep(
    mesh: &Mesh,
    n: usize,
    patch_classes: bool,
    perturbed: bool,
    cage: bool,
) -> anyhow::Result<(RenderMesh, usize, usize)> {
    let quads;
    let input = if mesh.face_counts.iter().any(|&c| c != 4) {
        crate::progress::note("the p-rep needs quads: one Catmull-Clark step first");
        quads = quadrangulate(mesh)?;
        &quads
    } else {
        mesh
    };
    let mut p = PrepPatches::<f32>::build(input)
        .context("building the p-rep (closed, oriented quad meshes only)")?;
    let nf = p.num_faces();
    let num_perturbed = p.topology.perturbed_faces.len();
    let face_class: Vec<u8> = p
        .h_index
        .iter()
        .map(|&h| {
            if h == u32::MAX {
                class::B_QUAD
            } else {
                class::PERTURBED
            }
        })
        .collect();
    if !perturbed {
        p.h_index = vec![u32::MAX; nf];
    }
    let n = n.max(2);
    let t = p.tessellate(n);
    let per_face = 2 * (n - 1) * (n - 1);
    if t.triangles.len() != nf * per_face {
        bail!(
            "p-rep tessellation: {} triangles for {nf} patches of {per_face}",
            t.triangles.len()
        );
    }
    let mut out = RenderMesh {
        positions: t.positions,
        normals: t.normals,
        indices: t.triangles.iter().flatten().copied().collect(),
        triangle_class: patch_classes.then(|| {
            face_class
                .iter()
                .flat_map(|&c| std::iter::repeat_n(c, per_face))
                .collect()
        }),
        lines: vec![],
    };
    if cage {
        let topo = Topology::new(mesh)?;
        out.lines = cage_lines(&topo, &mesh.positions);
    }
    Ok((out, nf, num_perturbed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_normals_point_along_the_diagonals() {
        let mesh = subsurf::shapes::cube();
        let faces = mesh
            .face_counts
            .iter()
            .scan(0usize, |s, &n| {
                let r = *s..*s + n as usize;
                *s += n as usize;
                Some(r)
            })
            .map(|r| (&mesh.face_indices[r], 0u8))
            .collect::<Vec<_>>();
        let rm = triangulate(mesh.positions.clone(), faces.into_iter(), false);
        assert_eq!(rm.indices.len(), 6 * 2 * 3);
        let (lo, hi) = mesh.bounding_box().unwrap();
        let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
        for (p, n) in rm.positions.iter().zip(&rm.normals) {
            // Three unit face normals summed: the outward corner diagonal.
            let d = unit([p[0] - c[0], p[1] - c[1], p[2] - c[2]]);
            let dot = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
            assert!(dot > 0.9999, "{p:?} {n:?}");
        }
    }

    #[test]
    fn crease_faces_follow_the_tagged_edge() {
        // A 4x4 grid with its middle column line tagged: at every level, the faces touching
        // that line (x = 0.5) are exactly the ones classed, the others are plain.
        let mut mesh = subsurf::shapes::grid(4, 4);
        let (lo, hi) = mesh.bounding_box().unwrap();
        let xm = 0.5 * (lo[0] + hi[0]);
        let on = |v: u32| (mesh.positions[v as usize][0] - xm).abs() < 1e-6;
        let mut creases = vec![];
        let n = mesh.face_counts.len();
        let mut s = 0;
        for f in 0..n {
            let c = mesh.face_counts[f] as usize;
            let poly = &mesh.face_indices[s..s + c];
            for k in 0..c {
                let (a, b) = (poly[k], poly[(k + 1) % c]);
                if a < b && on(a) && on(b) {
                    creases.push(subsurf::Crease {
                        v0: a,
                        v1: b,
                        sharpness: 2.0,
                    });
                }
            }
            s += c;
        }
        assert!(!creases.is_empty());
        mesh.creases = creases;
        for level in 0..3 {
            let topo = Topology::new(&mesh).unwrap();
            let r = Refiner::new(topo, level).unwrap();
            let pos = r.refine_positions(&mesh.positions);
            let classes = crease_classes(&r).unwrap();
            let t = r.last();
            for f in 0..t.num_faces() {
                let fv = t.face_vertices(f);
                let touches = (0..fv.len()).any(|k| {
                    let (a, b) = (fv[k] as usize, fv[(k + 1) % fv.len()] as usize);
                    (pos[a][0] - xm).abs() < 1e-5 && (pos[b][0] - xm).abs() < 1e-5
                });
                let want = if touches {
                    class::SEMI_SHARP
                } else {
                    class::PLAIN
                };
                assert_eq!(classes[f], want, "level {level} face {f}");
            }
        }
    }
}
