//! Boundary interpolation `none` with infinitely sharp boundary edges, against OpenSubdiv 3.5.
//!
//! OpenSubdiv (`makeBoundaryFacesHoles`) makes every face of a boundary vertex a hole when one
//! of the vertex's boundary edges is not tagged infinitely sharp; a boundary vertex whose
//! boundary edges are all tagged keeps its faces. Built here: grids with some boundary rows
//! tagged, a cube with an open side, non-manifold boundary vertices, and regression shapes with
//! part of their boundary tagged — compared on refinement (topology, holes, positions), limit
//! stencils, face-varying data in all six modes and limit-surface evaluation.

#[macro_use]
mod common;

use osd_ref::{EndCap, OsdMesh, PatchOptions as OsdPatchOptions};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::{BoundaryInterpolation, Crease, FaceVarying, Mesh};
use subsurf::{Refiner, Topology};

use common::MODES;

fn crease(v0: u32, v1: u32, sharpness: f32) -> Crease {
    Crease { v0, v1, sharpness }
}

/// A bumpy `n × n` grid with UVs split along a seam in the middle column, boundary `none`.
fn grid(n: usize) -> Mesh {
    let mut m = subsurf::shapes::grid(n, n);
    for (i, p) in m.positions.as_f32_mut().iter_mut().enumerate() {
        p[2] = ((i * 7919) % 13) as f32 * 0.05;
    }
    let values: Vec<[f32; 2]> = m
        .positions
        .iter()
        .map(|p| [p[0] / n as f32, p[1] / n as f32])
        .chain(
            m.positions
                .iter()
                .map(|p| [p[0] / n as f32 + 0.5, p[1] / n as f32]),
        )
        .collect();
    let nv = m.positions.len() as u32;
    let indices = m
        .face_indices
        .iter()
        .enumerate()
        .map(|(c, &v)| {
            let face = c / 4;
            if face % n >= n / 2 {
                v + nv
            } else {
                v
            }
        })
        .collect();
    m.uvs = Some(FaceVarying { values, indices });
    m.options.boundary = BoundaryInterpolation::None;
    m
}

/// Boundary edges `(a, b)` of `m`, each once, in face order.
fn boundary_edges(m: &Mesh) -> Vec<(u32, u32)> {
    let edges = common::unique_edges(&m.face_counts, &m.face_indices);
    let mut count = std::collections::HashMap::new();
    let mut k = 0;
    for &n in &m.face_counts {
        let f = &m.face_indices[k..k + n as usize];
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            *count.entry([a.min(b), a.max(b)]).or_insert(0) += 1;
        }
        k += n as usize;
    }
    edges
        .into_iter()
        .filter(|e| count[e] == 1)
        .map(|e| (e[0], e[1]))
        .collect()
}

/// The meshes of this test, with names.
fn cases() -> Vec<(String, Mesh)> {
    let mut out = Vec::new();
    // 6 x 6 grid: the bottom row and the left column tagged infinitely sharp (vertices on
    // both keep their faces; the rest of the boundary does not).
    let n = 6u32;
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut m = grid(n as usize);
    for i in 0..n {
        m.creases.push(crease(id(i, 0), id(i + 1, 0), 10.0));
        m.creases.push(crease(id(0, i), id(0, i + 1), 10.0));
    }
    out.push(("grid6 bottom+left".to_string(), m));
    // The whole boundary tagged: nothing becomes a hole.
    let mut m = grid(4);
    m.creases = boundary_edges(&m)
        .into_iter()
        .map(|(a, b)| crease(a, b, 10.0))
        .collect();
    out.push(("grid4 all".to_string(), m));
    // Part of a row, semi-sharp and infinite tags mixed, an interior crease and a corner.
    let mut m = grid(n as usize);
    m.creases.push(crease(id(1, 0), id(2, 0), 10.0));
    m.creases.push(crease(id(2, 0), id(3, 0), 10.0));
    m.creases.push(crease(id(3, 0), id(4, 0), 3.0));
    m.creases.push(crease(id(n, 2), id(n, 3), 10.0));
    m.creases.push(crease(id(2, 2), id(3, 2), 2.5));
    m.corners.push(subsurf::Corner {
        vertex: id(n, n),
        sharpness: 10.0,
    });
    out.push(("grid6 partial".to_string(), m));
    // A cube with an open side: the boundary loop tagged, then half of it.
    let cube = subsurf::shapes::cube();
    let mut open = cube.clone();
    open.face_counts.pop();
    open.face_indices.truncate(20);
    open.uvs = None;
    open.options.boundary = BoundaryInterpolation::None;
    let loop_edges = boundary_edges(&open);
    assert_eq!(loop_edges.len(), 4);
    let mut m = open.clone();
    m.creases = loop_edges
        .iter()
        .map(|&(a, b)| crease(a, b, 10.0))
        .collect();
    out.push(("open cube, loop tagged".to_string(), m));
    let mut m = open.clone();
    m.creases = loop_edges[..2]
        .iter()
        .map(|&(a, b)| crease(a, b, 10.0))
        .collect();
    out.push(("open cube, half tagged".to_string(), m));
    // Non-manifold boundary vertices: two 3 x 3 grids sharing one corner vertex, and two
    // quads sharing an edge with a third (a fin).
    let mut m = subsurf::shapes::grid(3, 3);
    let g = subsurf::shapes::grid(3, 3);
    let base = m.positions.len() as u32;
    let shared = 15u32; // corner (3, 3) of the first grid
    m.positions
        .append(&g.positions.map(|p| [p[0] + 3.0, p[1] + 3.0, 0.5 * p[0]]));
    for &v in &g.face_indices {
        m.face_indices.push(if v == 0 { shared } else { base + v });
    }
    m.face_counts.extend(&g.face_counts);
    m.options.boundary = BoundaryInterpolation::None;
    for (a, b) in boundary_edges(&m) {
        if a == shared || b == shared || a < 4 || b < 4 {
            m.creases.push(crease(a, b, 10.0));
        }
    }
    out.push(("bowtie grids".to_string(), m));
    let mut m = subsurf::shapes::grid(3, 2);
    m.positions.push([1.0, 1.0, 1.0]);
    m.positions.push([2.0, 1.0, 1.0]);
    let top = m.positions.len() as u32;
    m.face_counts.push(4);
    m.face_indices.extend([5, 6, top - 1, top - 2]);
    m.options.boundary = BoundaryInterpolation::None;
    m.creases = boundary_edges(&m)
        .into_iter()
        .filter(|&(a, b)| a.max(b) < 8)
        .map(|(a, b)| crease(a, b, 10.0))
        .collect();
    out.push(("fin".to_string(), m));
    // Regression shapes with every other boundary edge tagged.
    for name in [
        "catmark_edgeonly",
        "catmark_quadstrips",
        "catmark_xord_boundary",
        "catmark_tent_creases0",
        "catmark_nonman_verts",
        "catmark_hole_test2",
        "catmark_car",
    ] {
        let mut m = common::load_shape(name);
        m.options.boundary = BoundaryInterpolation::None;
        let tagged: std::collections::HashSet<[u32; 2]> = m
            .creases
            .iter()
            .map(|c| [c.v0.min(c.v1), c.v0.max(c.v1)])
            .collect();
        for (k, (a, b)) in boundary_edges(&m).into_iter().enumerate() {
            if k % 3 != 0 && !tagged.contains(&[a, b]) {
                m.creases.push(crease(a, b, 10.0));
            }
        }
        out.push((name.to_string(), m));
    }
    out
}

fn diagonal(points: &[[f32; 3]]) -> f32 {
    subsurf::mesh::bbox_diagonal(points).max(1e-30)
}

#[test]
fn base_level_holes_match_opensubdiv() {
    require_osd!();
    let mut kept_some_partial = false;
    for (name, mesh) in cases() {
        let mut o = OsdMesh::from(&mesh);
        o.uvs = None;
        let osd = osd_ref::refine_uniform(&o, 1).unwrap();
        let topo = Topology::new(&mesh).unwrap();
        assert_eq!(
            topo.arrays().face_is_hole,
            osd[0].face_is_hole,
            "{name}: base-level holes"
        );
        let kept = topo.arrays().face_is_hole.iter().filter(|&&h| !h).count();
        eprintln!("{name:28} keeps {kept} of {} faces", topo.num_faces());
        kept_some_partial |= name == "grid6 bottom+left" && kept > 4;
    }
    assert!(kept_some_partial);
}

#[test]
fn refinement_and_limit_stencils_match_opensubdiv() {
    require_osd!();
    for (name, mesh) in cases() {
        let level = if mesh.num_faces() > 200 { 2 } else { 3 };
        let mut o = OsdMesh::from(&mesh);
        o.uvs = None;
        let diag = diagonal(&mesh.positions);
        let osd = osd_ref::refine_uniform(&o, level).unwrap();
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
        let ours = refiner.refine_all(&mesh.positions);
        for l in 1..=level {
            let t = &refiner.levels[l];
            assert_eq!(
                t.arrays().face_verts,
                osd[l].face_verts,
                "{name} level {l}: faces"
            );
            assert_eq!(
                t.arrays().edge_verts,
                osd[l].edge_verts,
                "{name} level {l}: edges"
            );
            assert_eq!(
                t.arrays().face_is_hole,
                osd[l].face_is_hole,
                "{name} level {l}: holes"
            );
            assert_eq!(ours[l].len(), osd[l].positions.len(), "{name} level {l}");
            for (i, (a, b)) in ours[l].iter().zip(&osd[l].positions).enumerate() {
                let d = common::dist(*a, *b) / diag;
                assert!(d <= 1e-6, "{name} level {l} vertex {i}: {a:?} vs {b:?}");
            }
        }
        let theirs = osd_ref::limit_stencil_positions(&o, 2).unwrap();
        let refiner = Refiner::new(Topology::new(&mesh).unwrap(), 2).unwrap();
        let ours = refiner.limit(&refiner.refine_positions(&mesh.positions));
        assert_eq!(ours.len(), theirs.len(), "{name}: limit count");
        for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            let d = common::dist(*a, *b) / diag;
            assert!(d <= 1e-5, "{name} limit vertex {i}: {a:?} vs {b:?}");
        }
    }
}

#[test]
fn face_varying_data_matches_opensubdiv_in_every_mode() {
    require_osd!();
    let mut compared = 0;
    for (name, mesh) in cases() {
        let Some(fv) = mesh.uvs.as_ref() else {
            continue;
        };
        for (mode, code) in MODES {
            let level = 2;
            let mut o = OsdMesh::from(&mesh);
            o.options.fvar_interp = code;
            let osd = osd_ref::refine_uniform(&o, level).unwrap();
            let refiner = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
            let ours = refiner.refine_uvs(fv, mode).unwrap();
            for l in 1..=level {
                let (values, indices) = osd[l].uvs.as_ref().unwrap();
                let s = &ours[l];
                assert_eq!(s.indices.len(), indices.len(), "{name} {mode:?} level {l}");
                for (c, (&i, &j)) in s.indices.iter().zip(indices).enumerate() {
                    let (a, b) = (s.values[i as usize], values[j as usize]);
                    let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
                    assert!(
                        d <= 1e-5,
                        "{name} {mode:?} level {l} corner {c}: {a:?} vs {b:?}"
                    );
                }
                compared += 1;
            }
        }
    }
    assert!(compared >= 30, "{compared} level comparisons");
}

#[test]
fn limit_surface_evaluation_matches_opensubdiv() {
    require_osd!();
    for (name, mesh) in cases() {
        let n = if mesh.num_faces() > 200 { 4 } else { 7 };
        let mut o = OsdMesh::from(&mesh);
        o.uvs = None;
        let opts = OsdPatchOptions {
            isolation_level: 4,
            // OpenSubdiv's CPU basis evaluation ignores single-crease sharpness
            // (tests/limit_osd.rs); without those patches both evaluate the same surface.
            use_single_crease: false,
            use_inf_sharp: false,
            end_cap: EndCap::Gregory,
        };
        let osd = osd_ref::eval_limit_grid_with(&o, n, &opts).unwrap();
        let stats = osd_ref::patch_stats(&o, &opts).unwrap();
        let table = PatchTable::build(
            &Topology::new(&mesh).unwrap(),
            &PatchOptions {
                isolation_level: 4,
                single_crease: false,
                cap_crease_sharpness: true,
            },
        )
        .unwrap();
        assert_eq!(
            table.num_patches(),
            stats.num_patches,
            "{name}: patch count"
        );
        let s = LimitSurface::new(table, &mesh.positions);
        let diag = diagonal(&mesh.positions);
        // Every ptex face OpenSubdiv samples has a patch here, and no other.
        let map = &s.table().patch_map();
        let with_patch = (0..map.num_ptex()).filter(|&f| map.has_patches(f)).count();
        assert_eq!(with_patch * n * n, osd.len(), "{name}: sampled faces");
        for q in &osd {
            let r = s
                .eval(q.face as usize, q.u, q.v)
                .unwrap_or_else(|| panic!("{name}: no patch at ptex {}", q.face));
            let d = common::dist(r.p, q.p) / diag;
            assert!(
                d <= 5e-5,
                "{name} ptex {} ({}, {}): {:?} vs {:?}",
                q.face,
                q.u,
                q.v,
                r.p,
                q.p
            );
        }
    }
}
