//! The refine method: uniform refinement to a level, fan-triangulated, with the last
//! level's UVs carried to the triangle corners and faces classed by the creases they touch.

use super::triangulate::triangulate;
use super::{class, Backend, Colors, Surface, SurfaceError};
use crate::topology::tags;
use crate::{Error, Mesh, Refiner, Topology};

/// For each face of the last level, its class by the base-mesh creases it touches: an edge
/// of a refined level lies on a tagged base edge exactly when it descends from it (child
/// edges `corners + 2e` and `corners + 2e + 1` of parent edge `e`, see `refine::level`).
/// Boundary and non-manifold edges, sharp by rule rather than by tag, do not count.
pub fn crease_classes(refiner: &Refiner) -> Result<Vec<u8>, SurfaceError> {
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
            return Err(Error::Internal(format!(
                "unexpected child edge numbering at level {} ({} edges)",
                k + 1,
                c.num_edges()
            ))
            .into());
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
            if s >= crate::SHARPNESS_INFINITE {
                class::INF_SHARP
            } else if s > 0.0 {
                class::SEMI_SHARP
            } else {
                class::PLAIN
            }
        })
        .collect())
}

/// The UV of every corner of the last level (faces in order, holes included), refined in the
/// mesh's face-varying mode and moved to the limit when `limit`.
pub fn corner_uvs(
    refiner: &Refiner,
    mesh: &Mesh,
    limit: bool,
) -> Result<Option<Vec<[f32; 2]>>, SurfaceError> {
    let Some(fv) = &mesh.uvs else {
        return Ok(None);
    };
    let fvar =
        refiner.fvar_refinement(&fv.indices, fv.values.len(), mesh.options.uv_interpolation)?;
    let mut last = fvar
        .refine(&fv.values)?
        .pop()
        .ok_or_else(|| Error::Internal("face-varying refinement without levels".into()))?;
    if limit {
        last.values = refiner.limit_face_varying(&fvar, &last.values)?;
    }
    Ok(Some(
        last.indices
            .iter()
            .map(|&i| last.values[i as usize])
            .collect(),
    ))
}

/// Refines `mesh` `level` times on `backend` and triangulates the last level (holes left
/// out).
pub fn refined(
    mesh: &Mesh,
    level: usize,
    limit: bool,
    colors: Colors,
    backend: &dyn Backend,
) -> Result<Surface, SurfaceError> {
    let refiner = Refiner::new(Topology::new(mesh)?, level)?;
    let positions = backend.refine(&refiner, &mesh.positions, limit)?;
    let classes = match colors {
        Colors::Sharpness => Some(crease_classes(&refiner)?),
        _ => None,
    };
    let uvs = corner_uvs(&refiner, mesh, limit)?;
    let t = refiner.last();
    let kept: Vec<usize> = (0..t.num_faces()).filter(|&f| !t.face_is_hole[f]).collect();
    let faces = kept.iter().map(|&f| {
        let c = classes.as_ref().map_or(class::PLAIN, |c| c[f]);
        (t.face_vertices(f), c)
    });
    let fans = triangulate(&positions, faces);
    // Fan corners count the kept faces' corners; map them back to the level's corners.
    let corner_uvs = uvs.map(|uvs| {
        let mut kept_corners = Vec::new();
        for &f in &kept {
            kept_corners.extend(t.face_offsets[f] as usize..t.face_offsets[f + 1] as usize);
        }
        fans.corners
            .iter()
            .map(|c| c.map(|k| uvs[kept_corners[k as usize]]))
            .collect()
    });
    Ok(Surface {
        summary: format!(
            "refined {} faces to level {level}: {} vertices, {} triangles",
            mesh.num_faces(),
            positions.len(),
            fans.triangles.len()
        ),
        positions,
        normals: fans.normals,
        triangles: fans.triangles,
        triangle_class: fans.classes,
        corner_uvs,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crease_faces_follow_the_tagged_edge() {
        // A 4x4 grid with its middle column line tagged: at every level, the faces touching
        // that line (x = 0.5) are exactly the ones classed, the others are plain.
        let mut mesh = crate::shapes::grid(4, 4);
        let (lo, hi) = mesh.bounding_box().unwrap();
        let xm = 0.5 * (lo[0] + hi[0]);
        let on = |v: u32| (mesh.positions[v as usize][0] - xm).abs() < 1e-6;
        let mut creases = vec![];
        let mut s = 0;
        for f in 0..mesh.face_counts.len() {
            let c = mesh.face_counts[f] as usize;
            let poly = &mesh.face_indices[s..s + c];
            for k in 0..c {
                let (a, b) = (poly[k], poly[(k + 1) % c]);
                if a < b && on(a) && on(b) {
                    creases.push(crate::Crease {
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
            let r = Refiner::new(Topology::new(&mesh).unwrap(), level).unwrap();
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
