//! Watertight triangle tessellation of the Loop limit surface: a triangular grid of
//! `n` segments per edge on every base triangle, `(u, v) = (i/n, j/n)`, `i + j ≤ n`, with every
//! seam sample shared.
//!
//! Samples are numbered once per mesh element: one per base vertex, `n − 1` per base edge
//! (in the edge's own direction, from `edge_verts[e][0]`), `(n − 1)(n − 2)/2` inside each
//! face; each is evaluated once, from the first face that reaches it. Neighbouring faces
//! thus use the very same vertices along their common edge, whatever their patches.

use super::loop_eval::LoopLimit;
use crate::error::{Error, Result};
use crate::topology::Topology;

/// A triangle mesh sampled on the limit surface.
#[derive(Debug, Clone, PartialEq)]
pub struct TriTessellation {
    /// Segments per base edge.
    pub segments: usize,
    /// Sample positions.
    pub positions: Vec<[f64; 3]>,
    /// Unit normals (`∂P/∂u × ∂P/∂v`, zero where degenerate).
    pub normals: Vec<[f64; 3]>,
    /// Counter-clockwise triangles (as their base faces).
    pub triangles: Vec<[u32; 3]>,
}

/// Sample numbering of a triangular grid over the mesh elements.
struct Numbering<'a> {
    t: &'a Topology,
    n: usize,
    edge_base: usize,
    face_base: usize,
}

impl Numbering<'_> {
    /// The sample `(i, j)` of face `f`.
    fn id(&self, f: usize, i: usize, j: usize) -> usize {
        let (t, n) = (self.t, self.n);
        let fv = t.face_vertices(f);
        let fe = t.face_edges(f);
        // `along(k, from)`: sample k of edge fe[k_edge] counted from corner `from`.
        let along = |edge: usize, from: u32, k: usize| {
            let e = fe[edge] as usize;
            let k = if t.edge_verts[e][0] == from { k } else { n - k };
            self.edge_base + e * (n - 1) + (k - 1)
        };
        match (i, j) {
            (0, 0) => fv[0] as usize,
            (i, 0) if i == n => fv[1] as usize,
            (0, j) if j == n => fv[2] as usize,
            (i, 0) => along(0, fv[0], i),
            (i, j) if i + j == n => along(1, fv[1], j),
            (0, j) => along(2, fv[2], n - j),
            (i, j) => {
                // Interior (i, j ≥ 1, i + j ≤ n − 1), row by row in j.
                let m = n - 2; // interior samples on the first row
                let row_start: usize = (0..j - 1).map(|r| m - r).sum();
                self.face_base + f * (n - 1) * (n - 2) / 2 + row_start + (i - 1)
            }
        }
    }
}

/// The samples and triangles of [`LoopLimit::tessellate`], before evaluation: what a
/// backend evaluating the samples elsewhere needs to produce the very same mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct TriTessellationPlan {
    /// Segments per base edge.
    pub segments: usize,
    /// Per sample: the base face it is evaluated on (the first non-hole face reaching it)
    /// and its `(u, v)` there; `None` for a sample no non-hole face reaches.
    pub samples: Vec<Option<(u32, [f64; 2])>>,
    /// Counter-clockwise triangles (as their base faces), indices into `samples`.
    pub triangles: Vec<[u32; 3]>,
}

/// The plan of the watertight tessellation of every non-hole triangle of `base` with
/// `segments` (`1..=1024`) segments per edge (see the module documentation).
pub fn tri_tessellation_plan(base: &Topology, segments: usize) -> Result<TriTessellationPlan> {
    let n = segments;
    if n == 0 || n > 1024 {
        return Err(Error::Unsupported(format!(
            "{n} segments per edge (1..=1024)"
        )));
    }
    let nb = Numbering {
        t: base,
        n,
        edge_base: base.num_vertices(),
        face_base: base.num_vertices() + base.num_edges() * (n - 1),
    };
    let total = nb.face_base + base.num_faces() * (n - 1) * n.saturating_sub(2) / 2;
    // Refused up front, with the estimate, as an oversize refinement level is. Per sample,
    // counted from the arrays: its parameters (24 bytes), f64 position and normal (48), two
    // triangles (24), and the f32 mesh written from them (about 60).
    crate::util::budget::check(total as f64 * 160.0, || {
        format!(
            "a Loop limit tessellation of {total} samples ({n} segments per edge of {} \
             triangles)",
            base.num_faces()
        )
    })?;
    let mut samples = vec![None; total];
    let mut triangles = Vec::new();
    for f in (0..base.num_faces()).filter(|&f| !base.face_is_hole[f]) {
        for j in 0..=n {
            for i in 0..=n - j {
                let id = nb.id(f, i, j);
                if samples[id].is_none() {
                    samples[id] = Some((f as u32, [i as f64 / n as f64, j as f64 / n as f64]));
                }
            }
        }
        for j in 0..n {
            for i in 0..n - j {
                let id = |a, b| nb.id(f, a, b) as u32;
                triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                if i + j + 2 <= n {
                    triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
        }
    }
    Ok(TriTessellationPlan {
        segments: n,
        samples,
        triangles,
    })
}

impl LoopLimit {
    /// Tessellates every non-hole base triangle of `base` (the topology the surface was
    /// built from) with `segments ≥ 1` segments per edge; regular patches and Gregory-triangle
    /// end caps alike. Samples no face reaches (those of hole faces only) are NaN.
    pub fn tessellate(&self, base: &Topology, segments: usize) -> Result<TriTessellation> {
        let plan = tri_tessellation_plan(base, segments)?;
        let total = plan.samples.len();
        let mut positions = vec![[f64::NAN; 3]; total];
        let mut normals = vec![[0.0; 3]; total];
        for (id, sample) in plan.samples.iter().enumerate() {
            let Some((f, [u, v])) = *sample else {
                continue;
            };
            let s = self.eval(f as usize, u, v).ok_or_else(|| {
                Error::Internal(format!("no Loop patch of face {f} holds ({u}, {v})"))
            })?;
            positions[id] = s.p;
            let c = [
                s.du[1] * s.dv[2] - s.du[2] * s.dv[1],
                s.du[2] * s.dv[0] - s.du[0] * s.dv[2],
                s.du[0] * s.dv[1] - s.du[1] * s.dv[0],
            ];
            let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            if len > 0.0 {
                normals[id] = c.map(|x| x / len);
            }
        }
        Ok(TriTessellation {
            segments: plan.segments,
            positions,
            normals,
            triangles: plan.triangles,
        })
    }
}

/// Per triangle of [`LoopLimit::tessellate`] on `base` with `segments` per edge, in its
/// order: the base face and the `(u, v)` of the triangle's centroid there (what a patch
/// lookup colours the triangle by).
pub fn triangle_centres(base: &Topology, segments: usize) -> Vec<(u32, [f64; 2])> {
    let n = segments.max(1);
    let d = n as f64;
    let mut out = Vec::new();
    for f in (0..base.num_faces()).filter(|&f| !base.face_is_hole[f]) {
        for j in 0..n {
            for i in 0..n - j {
                let (i, j) = (i as f64, j as f64);
                out.push((f as u32, [(i + 1.0 / 3.0) / d, (j + 1.0 / 3.0) / d]));
                if i + j + 2.0 <= d {
                    out.push((f as u32, [(i + 2.0 / 3.0) / d, (j + 2.0 / 3.0) / d]));
                }
            }
        }
    }
    out
}

impl TriTessellation {
    /// The triangles as an f32 [`crate::Mesh`] with its unit normals, keeping only the
    /// samples a triangle uses (the samples of hole faces are never evaluated), in sample
    /// order.
    pub fn to_mesh(&self) -> (crate::Mesh, Vec<[f32; 3]>) {
        let (mut mesh, kept) = self.compact();
        mesh.positions = kept
            .iter()
            .map(|&i| self.positions[i].map(|c| c as f32))
            .collect();
        let normals = kept
            .iter()
            .map(|&i| self.normals[i].map(|x| x as f32))
            .collect();
        (mesh, normals)
    }

    /// [`TriTessellation::to_mesh`] in `f64`: the mesh holds its positions in `f64`
    /// ([`crate::mesh::Positions::from_f64`]), with the unit normals in `f64`.
    pub fn to_mesh_f64(&self) -> (crate::Mesh, Vec<[f64; 3]>) {
        let (mut mesh, kept) = self.compact();
        mesh.positions =
            crate::mesh::Positions::from_f64(kept.iter().map(|&i| self.positions[i]).collect());
        (mesh, kept.iter().map(|&i| self.normals[i]).collect())
    }

    /// The triangles renumbered over the samples they use, and those samples in order.
    fn compact(&self) -> (crate::Mesh, Vec<usize>) {
        let mut new_index = vec![u32::MAX; self.positions.len()];
        for t in &self.triangles {
            for &v in t {
                new_index[v as usize] = 0;
            }
        }
        let mut kept = Vec::new();
        for (i, slot) in new_index.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = kept.len() as u32;
                kept.push(i);
            }
        }
        let mut mesh = crate::Mesh::default();
        for t in &self.triangles {
            mesh.face_counts.push(3);
            mesh.face_indices
                .extend(t.iter().map(|&v| new_index[v as usize]));
        }
        (mesh, kept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Mesh, Scheme};
    use std::collections::HashMap;

    /// A regular triangulated torus: every vertex has valence 6, so every patch is a
    /// regular box-spline patch.
    fn torus(m: u32, k: u32) -> Mesh {
        let mut pos = Vec::new();
        for j in 0..k {
            for i in 0..m {
                let (a, b) = (
                    i as f32 / m as f32 * std::f32::consts::TAU,
                    j as f32 / k as f32 * std::f32::consts::TAU,
                );
                let r = 2.0 + 0.7 * b.cos() + 0.05 * ((3 * i + j) % 4) as f32;
                pos.push([r * a.cos(), r * a.sin(), 0.7 * b.sin()]);
            }
        }
        let id = |i: u32, j: u32| (j % k) * m + (i % m);
        let mut faces = Vec::new();
        for j in 0..k {
            for i in 0..m {
                faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let mut mesh = Mesh::from_faces(pos, &faces);
        mesh.options.scheme = Scheme::Loop;
        mesh
    }

    /// Tessellates `mesh` (closed) and checks vertex/triangle counts, closedness and that the
    /// shared seam samples are the surface seen from either face.
    fn check_watertight(mesh: &Mesh, n: usize) -> LoopLimit {
        let topo = Topology::new(mesh).unwrap();
        let limit = LoopLimit::new(&topo, &mesh.positions, 2).unwrap();
        let tess = limit.tessellate(&topo, n).unwrap();
        let (v, e, f) = (topo.num_vertices(), topo.num_edges(), topo.num_faces());
        assert_eq!(
            tess.positions.len(),
            v + e * (n - 1) + f * (n - 1) * (n - 2) / 2
        );
        assert_eq!(tess.triangles.len(), f * n * n);
        assert!(tess.positions.iter().flatten().all(|x| x.is_finite()));
        // Closed: every edge of the output is used once in each direction.
        let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
        for t in &tess.triangles {
            for k in 0..3 {
                *uses.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        for (&(a, b), &c) in &uses {
            assert_eq!(c, 1, "edge {a}-{b}");
            assert_eq!(uses.get(&(b, a)), Some(&1), "edge {a}-{b} has no twin");
        }
        // The shared samples are the surface seen from either side of a seam: evaluating
        // each edge sample from the other face gives the same point.
        let mut worst = 0.0f64;
        for fi in 0..f {
            for i in 1..n {
                let id = Numbering {
                    t: &topo,
                    n,
                    edge_base: v,
                    face_base: v + e * (n - 1),
                }
                .id(fi, i, 0);
                let here = limit.eval(fi, i as f64 / n as f64, 0.0).unwrap().p;
                let shared = tess.positions[id];
                worst = worst.max(
                    (0..3)
                        .map(|c| (here[c] - shared[c]).abs())
                        .fold(0.0, f64::max),
                );
            }
        }
        assert!(worst < 1e-5, "seam mismatch {worst}");
        limit
    }

    #[test]
    fn tessellation_is_watertight_and_continuous_across_seams() {
        let limit = check_watertight(&torus(8, 6), 4);
        assert!(limit.patches.iter().all(|p| p.regular));
    }

    /// The icosahedron: every vertex has valence 5, so the patches next to the base
    /// vertices are Gregory-triangle end caps, which meet each other and the regular
    /// patches across the base edges.
    #[test]
    fn tessellation_with_end_caps_is_watertight() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../testdata/shapes/loop_icosahedron.obj"
        );
        let mut mesh = crate::io::obj::read_file(std::path::Path::new(path)).unwrap();
        mesh.options.scheme = Scheme::Loop;
        // 8 segments: the seam samples next to the corners (u = 1/8) lie inside the
        // end caps, which cover a quarter of each edge at isolation 2.
        let limit = check_watertight(&mesh, 8);
        assert!(limit.patches.iter().any(|p| !p.regular));
        assert!(limit.patches.iter().any(|p| p.regular));
    }
}
