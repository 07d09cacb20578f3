//! USD stages on the command line: choosing mesh prims (`--prim`), merging a stage's meshes
//! in world space (render, `--flatten`), and writing refined prims back into their stage.

use anyhow::Context as _;
use std::path::Path;
use subsurf::io::usd::{transform_point, MeshPrim, Stage};
use subsurf::{Corner, Crease, FaceVarying, Mesh};

/// Whether `path` names a USD file (`.usda`, `.usdc`, `.usd`, `.usdz`).
pub fn is_usd(path: &Path) -> bool {
    subsurf::io::usd::format_of_path(path).is_some()
}

/// Reads a stage, with the path in the error.
pub fn read_stage(path: &Path) -> anyhow::Result<Stage> {
    Stage::read_path(path).with_context(|| format!("reading {}", path.display()))
}

/// The mesh prims to work on: `prim` alone, or all of them.
pub fn select(stage: &Stage, path: &Path, prim: Option<&str>) -> anyhow::Result<Vec<MeshPrim>> {
    let meshes = match prim {
        Some(p) => vec![stage.mesh(p)?],
        None => stage.meshes()?,
    };
    anyhow::ensure!(
        !meshes.is_empty(),
        "{}: the stage has no mesh prims",
        path.display()
    );
    Ok(meshes)
}

/// One mesh from a USD file: `prim`, else the only mesh prim, in its own coordinates; with
/// `flatten`, in world space (`prim` moved by its world transform, or every mesh prim
/// merged).
pub fn read_mesh(path: &Path, prim: Option<&str>, flatten: bool) -> anyhow::Result<Mesh> {
    let stage = read_stage(path)?;
    let read = || -> anyhow::Result<Mesh> {
        if flatten {
            return Ok(merge_world(&select(&stage, path, prim)?));
        }
        Ok(match prim {
            Some(p) => stage.mesh(p)?.mesh,
            None => stage.single_mesh()?.mesh,
        })
    };
    read().with_context(|| format!("reading {}", path.display()))
}

/// The meshes merged into one, each moved by its world transform. Options are the first
/// mesh's; UVs are kept only when every mesh has them.
pub fn merge_world(meshes: &[MeshPrim]) -> Mesh {
    let mut out = Mesh {
        options: meshes.first().map(|m| m.mesh.options).unwrap_or_default(),
        ..Default::default()
    };
    let all_uvs = meshes.iter().all(|m| m.mesh.uvs.is_some());
    let mut uvs = FaceVarying::default();
    for m in meshes {
        let v0 = out.positions.len() as u32;
        let f0 = out.face_counts.len() as u32;
        out.positions
            .append(&m.mesh.positions.map(|p| transform_point(&m.world, p)));
        out.face_counts.extend_from_slice(&m.mesh.face_counts);
        out.face_indices
            .extend(m.mesh.face_indices.iter().map(|&i| i + v0));
        out.creases.extend(m.mesh.creases.iter().map(|c| Crease {
            v0: c.v0 + v0,
            v1: c.v1 + v0,
            sharpness: c.sharpness,
        }));
        out.corners.extend(m.mesh.corners.iter().map(|c| Corner {
            vertex: c.vertex + v0,
            sharpness: c.sharpness,
        }));
        out.holes.extend(m.mesh.holes.iter().map(|&h| h + f0));
        if let (true, Some(uv)) = (all_uvs, &m.mesh.uvs) {
            let u0 = uvs.values.len() as u32;
            uvs.values.extend_from_slice(&uv.values);
            uvs.indices.extend(uv.indices.iter().map(|&i| i + u0));
        }
    }
    if all_uvs && !meshes.is_empty() {
        out.uvs = Some(uvs);
    }
    out
}
