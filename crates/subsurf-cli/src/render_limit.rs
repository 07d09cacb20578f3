//! The Catmull-Clark limit surface as a renderable mesh: the watertight tessellation of
//! `subsurf::limit` with one colour class per grid cell from the patch that covers the
//! cell's centre (found through the ptex quadtree, as OpenSubdiv's `Far::PatchMap` does).

use crate::render_mesh::{cage_lines, class};
use anyhow::bail;
use subsurf::limit::patch_map::EMPTY;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable, PatchType};
use subsurf::{Mesh, Topology};
use subsurf_render::RenderMesh;

/// What a cell's class shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitColors {
    /// One colour.
    None,
    /// Patch kind: regular at the base level, regular at an adaptive level, single crease,
    /// Gregory end cap.
    PatchKind,
    /// Adaptive refinement level of the patch within its ptex face (palette index).
    Level,
}

/// The class of a patch for `colors`.
fn patch_class(table: &PatchTable, p: usize, colors: LimitColors) -> u8 {
    let param = &table.params[p];
    let level = (param.depth() as i32 - param.non_quad_root() as i32).max(0) as u8;
    match colors {
        LimitColors::None => class::PLAIN,
        LimitColors::Level => level,
        LimitColors::PatchKind => match table.patch_type(p) {
            PatchType::Regular if level == 0 => class::REGULAR,
            PatchType::Regular => class::ADAPTIVE,
            PatchType::SingleCrease => class::SINGLE_CREASE,
            PatchType::Gregory => class::END_CAP,
        },
    }
}

/// Limit surface of `mesh` with `n` samples per ptex-face side, classes by `colors`.
pub fn limit(
    mesh: &Mesh,
    n: usize,
    colors: LimitColors,
    cage: bool,
) -> anyhow::Result<(RenderMesh, String)> {
    let topo = Topology::new(mesh)?;
    let table = PatchTable::build(&topo, &PatchOptions::default())?;
    let counts = table.counts();
    let surface = LimitSurface::new(table, &mesh.positions);
    let tess = surface.tessellate(n)?;
    let table = &surface.table;
    let n = tess.samples_per_side;
    // The grids in the tessellation's order: non-hole ptex faces in base face order, quads
    // with n samples per side, n-gon sub-faces with (n + 1) / 2, (g - 1)^2 cells each.
    let mut cell_class = Vec::with_capacity(tess.quads.len());
    let t = &table.base;
    for f in 0..t.num_faces() {
        let size = t.face_size(f);
        for k in 0..(if size == 4 { 1 } else { size }) {
            let ptex = table.ptex_offsets[f] as usize + k;
            if table.patch_map.roots[ptex] == EMPTY {
                continue;
            }
            let g = if size == 4 { n } else { n.div_ceil(2) };
            let d = (g - 1) as f32;
            for j in 0..g - 1 {
                for i in 0..g - 1 {
                    let (u, v) = ((i as f32 + 0.5) / d, (j as f32 + 0.5) / d);
                    let c = table
                        .patch_map
                        .find(ptex, u, v)
                        .map_or(class::PLAIN, |p| patch_class(table, p as usize, colors));
                    cell_class.push(c);
                }
            }
        }
    }
    if cell_class.len() != tess.quads.len() {
        bail!(
            "limit tessellation: {} cells for {} quads",
            cell_class.len(),
            tess.quads.len()
        );
    }
    let mut indices = Vec::with_capacity(6 * tess.quads.len());
    let mut classes = Vec::with_capacity(2 * tess.quads.len());
    for (q, &c) in tess.quads.iter().zip(&cell_class) {
        for tri in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                indices.extend_from_slice(&tri);
                classes.push(c);
            }
        }
    }
    let summary = format!(
        "limit: {} regular, {} single-crease, {} end-cap patches",
        counts.regular, counts.single_crease, counts.gregory
    );
    let rm = RenderMesh {
        positions: tess.positions,
        normals: tess.normals,
        indices,
        triangle_class: (colors != LimitColors::None).then_some(classes),
        lines: if cage {
            cage_lines(&topo, &mesh.positions)
        } else {
            vec![]
        },
    };
    Ok((rm, summary))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_cells_are_end_caps_at_the_corners_and_regular_elsewhere() {
        // Every cube vertex has valence 3: isolated to level 4, the patches next to a
        // corner are Gregory end caps and the rest regular at adaptive levels 1..=4; no
        // patch sits at level 0 and none is single-crease.
        let mesh = subsurf::shapes::cube();
        let (rm, _) = limit(&mesh, 17, LimitColors::PatchKind, false).unwrap();
        let c = rm.triangle_class.unwrap();
        assert_eq!(c.len(), rm.indices.len() / 3);
        let count = |k: u8| c.iter().filter(|&&x| x == k).count();
        assert!(count(class::END_CAP) > 0 && count(class::ADAPTIVE) > 0);
        assert_eq!(count(class::REGULAR) + count(class::SINGLE_CREASE), 0);
        // By level: every level-1 quadrant of a face holds an extraordinary corner, so
        // the coarsest patches are the level-2 ones next to the face centre; cells at a
        // corner are in level-4 patches (the isolation level).
        let (rm, _) = limit(&mesh, 17, LimitColors::Level, false).unwrap();
        let c = rm.triangle_class.unwrap();
        assert!(c.iter().all(|&l| (2..=4).contains(&l)));
        // 16x16 cells per face, 2 triangles each: cell (7, 7) touches the face centre.
        let per_face = 2 * 16 * 16;
        assert_eq!(c[2 * (7 * 16 + 7)], 2);
        assert_eq!(c[0], 4);
        assert_eq!(c.len(), 6 * per_face);
    }
}
