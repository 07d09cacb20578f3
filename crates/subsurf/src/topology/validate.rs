//! Checks a [`Mesh`] before its topology is built: every index in range, every coordinate finite.

use crate::error::MeshError;
use crate::mesh::Mesh;

/// Validates the face lists, positions, face-varying indices and tag indices of `mesh`.
///
/// Edge creases naming vertices that share no edge are checked later, once edges exist.
pub fn validate_mesh(mesh: &Mesh) -> Result<(), MeshError> {
    let nv = mesh.positions.len();
    let expected: usize = mesh.face_counts.iter().map(|&c| c as usize).sum();
    if expected != mesh.face_indices.len() {
        return Err(MeshError::FaceIndexCountMismatch {
            expected,
            found: mesh.face_indices.len(),
        });
    }
    if nv > u32::MAX as usize / 2 || expected > u32::MAX as usize / 2 {
        return Err(MeshError::TooLarge {
            what: "a mesh with more than 2^31 vertices or face corners".into(),
            bytes: expected as u64 * 4,
            human: format!("{expected} corners"),
            limit_human: "2^31 corners".into(),
        });
    }
    for (v, p) in mesh.positions.iter().enumerate() {
        if let Some(&value) = p.iter().find(|x| !x.is_finite()) {
            return Err(MeshError::NonFiniteCoordinate { vertex: v, value });
        }
    }
    let mut start = 0usize;
    for (face, &count) in mesh.face_counts.iter().enumerate() {
        if count < 3 {
            return Err(MeshError::FaceTooSmall { face, count });
        }
        let idx = &mesh.face_indices[start..start + count as usize];
        if let Some(corner) = idx.iter().position(|&i| i as usize >= nv) {
            return Err(MeshError::VertexIndexOutOfRange {
                face,
                corner,
                index: idx[corner],
                count: nv,
            });
        }
        start += count as usize;
    }
    if let Some(fv) = &mesh.uvs {
        if fv.indices.len() != mesh.face_indices.len() {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "{} UV indices for {} face corners",
                    fv.indices.len(),
                    mesh.face_indices.len()
                ),
            });
        }
        if let Some(c) = fv
            .indices
            .iter()
            .position(|&i| i as usize >= fv.values.len())
        {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "corner {c}: UV index {} out of range ({} values)",
                    fv.indices[c],
                    fv.values.len()
                ),
            });
        }
        if let Some(i) = fv
            .values
            .iter()
            .position(|v| !v[0].is_finite() || !v[1].is_finite())
        {
            return Err(MeshError::FaceVarying {
                reason: format!("UV value {i} is not finite"),
            });
        }
    }
    for (tag, c) in mesh.creases.iter().enumerate() {
        for index in [c.v0, c.v1] {
            if index as usize >= nv {
                return Err(MeshError::TagIndexOutOfRange {
                    kind: "crease",
                    tag,
                    index,
                    count: nv,
                });
            }
        }
        if c.sharpness.is_nan() {
            return Err(MeshError::NanSharpness {
                kind: "crease",
                tag,
            });
        }
    }
    for (tag, c) in mesh.corners.iter().enumerate() {
        if c.vertex as usize >= nv {
            return Err(MeshError::TagIndexOutOfRange {
                kind: "corner",
                tag,
                index: c.vertex,
                count: nv,
            });
        }
        if c.sharpness.is_nan() {
            return Err(MeshError::NanSharpness {
                kind: "corner",
                tag,
            });
        }
    }
    let nf = mesh.face_counts.len();
    for (tag, &h) in mesh.holes.iter().enumerate() {
        if h as usize >= nf {
            return Err(MeshError::TagIndexOutOfRange {
                kind: "hole",
                tag,
                index: h,
                count: nf,
            });
        }
    }
    Ok(())
}

/// Clamps a tag's sharpness into `[0, 10]` (negative is smooth, `>= 10` is infinite).
pub fn clamp_sharpness(s: f32) -> f32 {
    s.clamp(0.0, crate::SHARPNESS_INFINITE)
}
