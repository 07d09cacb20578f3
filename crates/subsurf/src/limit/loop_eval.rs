//! The Loop limit surface on its regular patches: the 12 box-spline points of every regular
//! leaf triangle ([`super::loop_patches`]) gathered from its sparsely refined level, and evaluation
//! at a base face's `(u, v)`, `u + v ≤ 1`.
//!
//! # Gathering the 12 points
//!
//! With the triangle's corners as points 4, 5, 8 ([`crate::patch::box_spline`]), every other
//! point is the vertex opposite an edge, across it from a known triangle:
//!
//! ```text
//! 1 = across 4–5 from 8     9 = across 5–8 from 4     7 = across 8–4 from 5
//! 0 = across 4–1 from 5     2 = across 5–1 from 4     6 = across 5–9 from 8
//! 3 = across 4–7 from 8    10 = across 8–7 from 4    11 = across 8–9 from 5
//! ```
//!
//! Where an edge is on the boundary, or non-manifold (it bounds the manifold span of its
//! corners), the point does not exist: it is a phantom, its index is corner 0's and the
//! boundary mask gives it weight 0. Non-manifold corners count as boundary corners.
//!
//! Irregular leaves get OpenSubdiv's end caps, quartic Gregory triangles
//! ([`super::loop_endcap`]), evaluated with [`TriPatchKind::GregoryTriangle`].

use super::loop_patches::{loop_isolation, LoopLeaf, LoopLevel};
use super::patch_map::PatchMap;
use super::sparse::Selection;
use crate::error::{Error, Result};
use crate::patch::{tri_patch_weights, PatchParam, PatchParamFields, TriPatchKind};
use crate::real::{Real, VertexData};
use crate::topology::tags;
use crate::topology::Topology;

/// One patch: its parameter and, for a regular patch, its 12 points.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopPatch {
    /// Packed parameter (face, sub-triangle, depth, boundary mask).
    pub param: PatchParam,
    /// A regular box-spline patch.
    pub regular: bool,
    /// The 12 box-spline points of a regular patch, or the 18 Gregory-triangle points of an
    /// irregular one.
    pub points: Vec<[f64; 3]>,
}

/// A point of the limit surface with its derivatives along the base face's `u` and `v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopSample {
    /// Position.
    pub p: [f64; 3],
    /// `∂P/∂u`.
    pub du: [f64; 3],
    /// `∂P/∂v`.
    pub dv: [f64; 3],
}

/// The patches of a Loop mesh with their points (see the module documentation).
#[derive(Debug, Clone)]
pub struct LoopLimit {
    /// Every patch, base face by base face.
    pub patches: Vec<LoopPatch>,
    /// `F + 1` offsets: the patches of base face `f` are `offsets[f]..offsets[f + 1]`.
    pub offsets: Vec<u32>,
    /// The tree per base face ([`PatchMap::find_triangle`]).
    pub patch_map: PatchMap,
}

/// The triangle across the edge `a–b` of triangle `f` and its vertex opposite that edge;
/// `None` across a boundary or non-manifold edge (which bounds the manifold span a regular
/// patch sees). The neighbour is found through `f`'s own edge, so degenerate neighbourhoods
/// (two triangles on the same three vertices) are followed correctly.
fn across(t: &Topology, f: u32, a: u32, b: u32) -> Option<(u32, u32)> {
    let fv = t.face_vertices(f as usize);
    let n = fv.len();
    let k = (0..n).find(|&k| {
        let (x, y) = (fv[k], fv[(k + 1) % n]);
        (x == a && y == b) || (x == b && y == a)
    })?;
    let e = t.face_edges(f as usize)[k] as usize;
    if t.edge_tags[e] & tags::E_NON_MANIFOLD != 0 {
        return None;
    }
    let g = t.edge_faces(e).iter().copied().find(|&g| g != f)?;
    let gv = t.face_vertices(g as usize);
    // The corner of `g` that is not on the shared edge: the one after the edge's end in `g`.
    let m = gv.len();
    let j = (0..m).find(|&j| {
        let (x, y) = (gv[j], gv[(j + 1) % m]);
        (x == a && y == b) || (x == b && y == a)
    })?;
    Some((g, gv[(j + 2) % m]))
}

/// The 12 point indices of triangle `f` (phantoms: corner 0's index).
pub fn gather_box_spline_points(t: &Topology, f: usize) -> [u32; 12] {
    let fv = t.face_vertices(f);
    let (p4, p5, p8) = (fv[0], fv[1], fv[2]);
    let f = f as u32;
    let g1 = across(t, f, p4, p5);
    let g9 = across(t, f, p5, p8);
    let g7 = across(t, f, p8, p4);
    let next = |g: Option<(u32, u32)>, corner: u32| {
        let (g, x) = g?;
        across(t, g, corner, x).map(|(_, y)| y)
    };
    let p0 = next(g1, p4);
    let p2 = next(g1, p5);
    let p6 = next(g9, p5);
    let p11 = next(g9, p8);
    let p3 = next(g7, p4);
    let p10 = next(g7, p8);
    let v = |g: Option<(u32, u32)>| g.map(|(_, x)| x);
    [
        p0,
        v(g1),
        p2,
        p3,
        Some(p4),
        Some(p5),
        p6,
        v(g7),
        Some(p8),
        v(g9),
        p10,
        p11,
    ]
    .map(|p| p.unwrap_or(p4))
}

/// OpenSubdiv's 5-bit boundary mask of a regular triangle: its boundary edges, or (upper
/// bits 1) its boundary corners when no edge is on the boundary, or (upper bits 2) its
/// boundary edges when the corner opposite one is on the boundary too.
pub fn tri_boundary_mask(t: &Topology, f: usize) -> u8 {
    let fe = t.face_edges(f);
    let fv = t.face_vertices(f);
    let edges = (0..3).fold(0u8, |m, k| {
        let et = t.edge_tags[fe[k] as usize];
        m | (((et & (tags::E_BOUNDARY | tags::E_NON_MANIFOLD) != 0) as u8) << k)
    });
    let verts = (0..3).fold(0u8, |m, k| {
        let vt = t.vert_tags[fv[k] as usize];
        m | (((vt & (tags::V_BOUNDARY | tags::V_NON_MANIFOLD) != 0) as u8) << k)
    });
    if edges == 0 {
        return if verts == 0 { 0 } else { (1 << 3) | verts };
    }
    let on_edges = (0..3).fold(0u8, |m, k| {
        if edges & (1 << k) != 0 {
            m | (1 << k) | (1 << ((k + 1) % 3))
        } else {
            m
        }
    });
    if verts & !on_edges != 0 {
        (2 << 3) | edges
    } else {
        edges
    }
}

impl LoopLimit {
    /// Isolates `base` to `isolation_level` (`loop_leaves`), refines `positions` (rounded to
    /// `f32`) through the levels in `f32` and gathers the points of every patch.
    pub fn new(
        base: &Topology,
        positions: &(impl VertexData<3> + ?Sized),
        isolation_level: u32,
    ) -> Result<Self> {
        Self::build::<f32>(base, positions, isolation_level)
    }

    /// [`LoopLimit::new`] in double precision: `positions` as they are held (a file's
    /// digits, without rounding), refined through the levels with the masks in `f64`
    /// (OpenSubdiv's `PrimvarRefinerReal<double>`).
    pub fn new_f64(
        base: &Topology,
        positions: &(impl VertexData<3> + ?Sized),
        isolation_level: u32,
    ) -> Result<Self> {
        Self::build::<f64>(base, positions, isolation_level)
    }

    /// [`LoopLimit::new_f64`] where `positions` are held in `f64` (digits of a file that `f32`
    /// cannot hold, float64 arrays: [`crate::mesh::Positions::is_f64`]), else
    /// [`LoopLimit::new`]: the precision every front end refines a mesh's Loop points in.
    pub fn at_precision(
        base: &Topology,
        positions: &crate::mesh::Positions,
        isolation_level: u32,
    ) -> Result<Self> {
        match positions.is_f64() {
            true => Self::new_f64(base, positions, isolation_level),
            false => Self::new(base, positions, isolation_level),
        }
    }

    /// The patches, the level points refined in `R` through the sparse levels.
    fn build<R: Real>(
        base: &Topology,
        positions: &(impl VertexData<3> + ?Sized),
        isolation_level: u32,
    ) -> Result<Self> {
        Self::build_with::<R>(base, positions, isolation_level, Selection::Sparse)
    }

    /// [`LoopLimit::build`] with the levels refined as `selection` says (the uniform
    /// refinement is the reference of the sparse one's tests).
    pub(crate) fn build_with<R: Real>(
        base: &Topology,
        positions: &(impl VertexData<3> + ?Sized),
        isolation_level: u32,
        selection: Selection,
    ) -> Result<Self> {
        if positions.num_vertices() != base.num_vertices() {
            return Err(Error::Unsupported(format!(
                "{} positions for {} vertices",
                positions.num_vertices(),
                base.num_vertices()
            )));
        }
        let l = loop_isolation::<R>(base, isolation_level, selection, true)?;
        let h = &l.hierarchy;
        let first: Vec<[R; 3]> = (0..base.num_vertices())
            .map(|i| positions.vertex::<R>(i))
            .collect();
        let mut points = vec![first];
        for (s, inputs) in h.stencils.iter().zip(&h.inputs) {
            let last = &points[points.len() - 1];
            let sub: Vec<[R; 3]> = inputs.iter().map(|&v| last[v as usize]).collect();
            points.push(s.apply_real(&sub));
        }
        let mut patches = Vec::new();
        let mut offsets = vec![0u32; base.num_faces() + 1];
        let patch_map = l.walk(base, |leaf| {
            patches.push(Self::patch(
                &l.levels[leaf.depth],
                &points[leaf.depth],
                leaf,
            )?);
            offsets[leaf.base_face as usize + 1] += 1;
            Ok(())
        })?;
        for f in 0..base.num_faces() {
            offsets[f + 1] += offsets[f];
        }
        Ok(LoopLimit {
            patches,
            offsets,
            patch_map,
        })
    }

    fn patch<R: Real>(level: &LoopLevel, points: &[[R; 3]], leaf: &LoopLeaf) -> Result<LoopPatch> {
        let l = level.leaves[leaf.index as usize];
        let param = PatchParam::new(PatchParamFields {
            face_id: leaf.base_face,
            u: leaf.uv.0,
            v: leaf.uv.1,
            depth: leaf.depth as u8,
            boundary: l.boundary,
            regular: l.regular,
            ..Default::default()
        })?;
        let first = l.first as usize;
        let pts = if l.regular {
            level.cvs[12 * first..12 * first + 12]
                .iter()
                .map(|&i| points[i as usize].map(R::to_f64))
                .collect()
        } else {
            level.rows[18 * first..18 * first + 18]
                .iter()
                .map(|r| {
                    let mut x = [0.0f64; 3];
                    for &(i, w) in r {
                        let q = points[i as usize];
                        for c in 0..3 {
                            x[c] += w * q[c].to_f64();
                        }
                    }
                    x
                })
                .collect()
        };
        Ok(LoopPatch {
            param,
            regular: l.regular,
            points: pts,
        })
    }

    /// The patch of base face `face` holding `(u, v)`, found with the patch map.
    pub fn find(&self, face: usize, u: f64, v: f64) -> Option<&LoopPatch> {
        let p = self.patch_map.find_triangle(face, u, v)?;
        self.patches.get(p as usize)
    }

    /// The patch of base face `face` holding `(u, v)` by a linear search: the first one
    /// whose closed sub-triangle contains it (the reference of the patch map's tests).
    pub fn find_linear(&self, face: usize, u: f64, v: f64) -> Option<&LoopPatch> {
        let range = self.offsets[face] as usize..*self.offsets.get(face + 1)? as usize;
        const EPS: f64 = 1e-9;
        self.patches[range].iter().find(|p| {
            let (s, t) = p.param.normalize_triangle(u, v);
            s >= -EPS && t >= -EPS && s + t <= 1.0 + EPS
        })
    }

    /// The limit point at `(u, v)` of base face `face`, with derivatives along the face's
    /// `u` and `v`; `None` outside the face or on a hole.
    pub fn eval(&self, face: usize, u: f64, v: f64) -> Option<LoopSample> {
        let p = self.find(face, u, v)?;
        let kind = if p.regular {
            TriPatchKind::BoxSpline
        } else {
            TriPatchKind::GregoryTriangle
        };
        let w = tri_patch_weights(kind, &p.param, u, v);
        let mut r = LoopSample {
            p: [0.0; 3],
            du: [0.0; 3],
            dv: [0.0; 3],
        };
        let x0 = p.points[if p.regular { 4 } else { 0 }];
        for (k, pt) in p.points.iter().enumerate() {
            for c in 0..3 {
                let x = pt[c] - x0[c];
                r.p[c] += w.p[k] * x;
                r.du[c] += w.du[k] * x;
                r.dv[c] += w.dv[k] * x;
            }
        }
        for c in 0..3 {
            r.p[c] += x0[c];
        }
        Some(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::obj;

    #[test]
    fn patch_map_finds_the_patch_whose_triangle_holds_the_point() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../testdata/shapes/loop_xord_interior.obj"
        );
        let mesh = obj::read_file(std::path::Path::new(path)).unwrap();
        let topo = Topology::new(&mesh).unwrap();
        let l = LoopLimit::new(&topo, &mesh.positions, 3).unwrap();
        assert!(l.patches.len() > topo.num_faces());
        let mut state = 7u64;
        let mut rnd = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..2000 {
            let f = (rnd() * topo.num_faces() as f64) as usize;
            let (a, b) = (rnd(), rnd());
            let (u, v) = if a + b > 1.0 {
                (1.0 - a, 1.0 - b)
            } else {
                (a, b)
            };
            let p = l.find(f, u, v).expect("every face has patches");
            assert_eq!(p.param.face_id() as usize, f);
            let (s, t) = p.param.normalize_triangle(u, v);
            assert!(
                s >= -1e-12 && t >= -1e-12 && s + t <= 1.0 + 1e-12,
                "{f} {u} {v}: {s} {t}"
            );
            // Off the sub-triangles' seams the patch is unique.
            if s > 1e-6 && t > 1e-6 && s + t < 1.0 - 1e-6 {
                assert_eq!(Some(p), l.find_linear(f, u, v));
            }
        }
    }

    fn shape(name: &str) -> (crate::mesh::Mesh, Topology) {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../testdata/shapes");
        let mesh = obj::read_file(std::path::Path::new(dir).join(name)).unwrap();
        let topo = Topology::new(&mesh).unwrap();
        (mesh, topo)
    }

    /// The sparse isolation gives the uniform one's patches, bit for bit (parameters, kinds,
    /// points in `f32` and `f64`, offsets and patch map), on every Loop shape.
    #[test]
    fn sparse_isolation_equals_uniform_bit_for_bit() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../testdata/shapes");
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| n.starts_with("loop_") && n.ends_with(".obj"))
            .collect();
        names.sort();
        assert!(names.len() >= 31, "{names:?}");
        let (mut compared, mut end_caps) = (0, 0);
        for name in &names {
            let (mesh, topo) = shape(name);
            for level in 1..=5 {
                let build = |sel| {
                    let a = LoopLimit::build_with::<f32>(&topo, &mesh.positions, level, sel);
                    let b = LoopLimit::build_with::<f64>(&topo, &mesh.positions, level, sel);
                    (a.unwrap(), b.unwrap())
                };
                let (sparse, uniform) = (build(Selection::Sparse), build(Selection::Uniform));
                for (s, u) in [(&sparse.0, &uniform.0), (&sparse.1, &uniform.1)] {
                    assert!(s.patches == u.patches, "{name} isolation {level}");
                    assert_eq!(s.offsets, u.offsets, "{name} isolation {level}");
                    assert_eq!(s.patch_map.roots, u.patch_map.roots, "{name} {level}");
                    assert_eq!(s.patch_map.nodes, u.patch_map.nodes, "{name} {level}");
                }
                compared += sparse.0.patches.len();
                end_caps += sparse.0.patches.iter().filter(|p| !p.regular).count();
            }
        }
        assert!(
            compared > 50_000 && end_caps > 10_000,
            "{compared} {end_caps}"
        );
    }

    /// Around isolated extraordinary vertices a sparse level stays the same size from level to
    /// level once the features are apart (level 4 here), where a uniform one grows fourfold.
    #[test]
    fn sparse_levels_stay_small() {
        let (_, topo) = shape("loop_xord_interior.obj");
        let sizes = |sel| {
            let l = super::super::loop_patches::loop_isolation::<f32>(&topo, 6, sel, false);
            l.unwrap().hierarchy.num_vertices
        };
        let (sparse, uniform) = (sizes(Selection::Sparse), sizes(Selection::Uniform));
        assert_eq!(sparse.len(), 7);
        assert_eq!(sparse.len(), uniform.len());
        for d in 5..7 {
            assert!(sparse[d] <= sparse[d - 1], "{sparse:?}");
        }
        assert!(uniform[6] > 50 * sparse[6], "{sparse:?} {uniform:?}");
    }

    /// Without the ring around the refined faces, patches would read points that are not the
    /// uniform refinement's: the construction refuses instead of building them.
    #[test]
    fn too_small_a_sub_mesh_is_refused() {
        let (mesh, topo) = shape("loop_xord_interior.obj");
        let r = LoopLimit::build_with::<f32>(&topo, &mesh.positions, 3, Selection::Rings(0));
        assert!(
            matches!(r, Err(Error::Internal(_))),
            "{:?}",
            r.map(|l| l.patches.len())
        );
    }

    /// The memory estimate of the isolation covers what a `LoopLimit` holds at its peak:
    /// the stencils, points and leaves of every level and the patches with their points
    /// (heap bytes counted from the arrays' lengths), and is not far above it.
    #[test]
    fn the_memory_estimate_covers_the_built_surface() {
        use std::mem::size_of;
        let (mesh, topo) = shape("loop_pole64.obj");
        for level in [4, 8] {
            let l = super::super::loop_patches::loop_isolation::<f32>(
                &topo,
                level,
                Selection::Sparse,
                true,
            )
            .unwrap();
            let h = &l.hierarchy;
            let table =
                |t: &crate::refine::StencilTable<f32>| 4 * t.offsets.len() + 8 * t.indices.len();
            let stencils: usize = h
                .stencils
                .iter()
                .map(|s| table(&s.vertex) + table(&s.edge))
                .sum();
            let inputs: usize = h.inputs.iter().map(|i| 4 * i.len()).sum();
            let points: usize = h.num_vertices.iter().map(|n| 12 * n).sum();
            let leaves: usize = l
                .levels
                .iter()
                .map(|lv| {
                    let rows: usize = lv.rows.iter().map(|r| 24 + 16 * r.len()).sum();
                    4 * lv.slot.len() + 12 * lv.leaves.len() + 4 * lv.cvs.len() + rows
                })
                .sum();
            let limit = LoopLimit::new(&topo, &mesh.positions, level).unwrap();
            let patches: usize = limit
                .patches
                .iter()
                .map(|p| size_of::<LoopPatch>() + 24 * p.points.len())
                .sum();
            let held = (stencils + inputs + points + leaves + patches) as u64;
            let e = l.estimated_bytes;
            assert!(
                e >= held && e < 6 * held,
                "level {level}: {e} estimated, {held} held"
            );
        }
    }
}
