//! The limit method: the watertight tessellation of `crate::limit` with one class per grid
//! cell from the patch that covers the cell's centre (found through the ptex quadtree, as
//! OpenSubdiv's `Far::PatchMap` does).

use super::{class, Backend, Colors, Surface, SurfaceError};
use crate::limit::patch_map::EMPTY;
use crate::limit::{PatchOptions, PatchTable, PatchType};
use crate::{Error, Mesh, Topology};

/// The class of patch `p` for `colors`.
pub(super) fn patch_class(table: &PatchTable, p: usize, colors: Colors) -> u8 {
    let param = &table.params[p];
    let level = (param.depth() as i32 - param.non_quad_root() as i32).max(0) as u8;
    match colors {
        Colors::Level => level,
        Colors::PatchKind => match table.patch_type(p) {
            PatchType::Regular if level == 0 => class::REGULAR,
            PatchType::Regular => class::ADAPTIVE,
            PatchType::SingleCrease => class::SINGLE_CREASE,
            PatchType::Gregory => class::END_CAP,
        },
        _ => class::PLAIN,
    }
}

/// Limit surface of `mesh` with `samples` per ptex-face side on `backend`.
pub fn limit(
    mesh: &Mesh,
    samples: usize,
    options: &PatchOptions,
    colors: Colors,
    backend: &dyn Backend,
) -> Result<Surface, SurfaceError> {
    let topo = Topology::new(mesh)?;
    let table = PatchTable::build(&topo, options)?;
    let tess = backend.limit(&table, &mesh.positions, samples)?;
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
                        .map_or(class::PLAIN, |p| patch_class(&table, p as usize, colors));
                    cell_class.push(c);
                }
            }
        }
    }
    if cell_class.len() != tess.quads.len() {
        return Err(Error::Internal(format!(
            "limit tessellation: {} cells for {} quads",
            cell_class.len(),
            tess.quads.len()
        ))
        .into());
    }
    let mut triangles = Vec::with_capacity(2 * tess.quads.len());
    let mut classes = Vec::with_capacity(2 * tess.quads.len());
    for (q, &c) in tess.quads.iter().zip(&cell_class) {
        for tri in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                triangles.push(tri);
                classes.push(c);
            }
        }
    }
    let counts = table.counts();
    Ok(Surface {
        summary: format!(
            "limit: {} regular, {} single-crease, {} end-cap patches",
            counts.regular, counts.single_crease, counts.gregory
        ),
        positions: tess.positions,
        normals: tess.normals,
        triangles,
        triangle_class: classes,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::super::Cpu;
    use super::*;

    #[test]
    fn cube_cells_are_end_caps_at_the_corners_and_regular_elsewhere() {
        // Every cube vertex has valence 3: isolated to level 4, the patches next to a
        // corner are Gregory end caps and the rest regular at adaptive levels 1..=4; no
        // patch sits at level 0 and none is single-crease.
        let mesh = crate::shapes::cube();
        let o = PatchOptions::default();
        let s = limit(&mesh, 17, &o, Colors::PatchKind, &Cpu).unwrap();
        let c = &s.triangle_class;
        assert_eq!(c.len(), s.triangles.len());
        let count = |k: u8| c.iter().filter(|&&x| x == k).count();
        assert!(count(class::END_CAP) > 0 && count(class::ADAPTIVE) > 0);
        assert_eq!(count(class::REGULAR) + count(class::SINGLE_CREASE), 0);
        // By level: every level-1 quadrant of a face holds an extraordinary corner, so
        // the coarsest patches are the level-2 ones next to the face centre; cells at a
        // corner are in level-4 patches (the isolation level).
        let s = limit(&mesh, 17, &o, Colors::Level, &Cpu).unwrap();
        let c = &s.triangle_class;
        assert!(c.iter().all(|&l| (2..=4).contains(&l)));
        // 16x16 cells per face, 2 triangles each: cell (7, 7) touches the face centre.
        assert_eq!(c[2 * (7 * 16 + 7)], 2);
        assert_eq!(c[0], 4);
        assert_eq!(c.len(), 6 * 2 * 16 * 16);
    }
}
