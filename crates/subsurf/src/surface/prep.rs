//! The prep method: the p-rep (Myles, Yeo and Peters 2008) tessellated with `n` samples per
//! patch side; meshes with non-quad faces get one Catmull-Clark step first.

use super::{class, Backend, Colors, Surface, SurfaceError};
use crate::prep::quadrangulate::quadrangulate;
use crate::{Error, Mesh};

/// The p-rep surface of `mesh` on `backend`; with `perturbed = false` the bi-5
/// perturbations are dropped (every patch drawn as its bicubic part), which shows what they
/// correct (the paper's Figure 7). Classes: B-quad or perturbed patch.
pub fn prep(
    mesh: &Mesh,
    samples: usize,
    perturbed: bool,
    colors: Colors,
    backend: &dyn Backend,
) -> Result<Surface, SurfaceError> {
    let mut notes = Vec::new();
    if !mesh.creases.is_empty() || !mesh.corners.is_empty() {
        notes.push("the p-rep ignores crease and corner tags".to_string());
    }
    let quads;
    let input = if mesh.face_counts.iter().any(|&c| c != 4) {
        notes.push("the p-rep needs quads: one Catmull-Clark step first".to_string());
        quads = quadrangulate(mesh)?;
        &quads
    } else {
        mesh
    };
    let n = samples.max(2);
    let out = backend.prep(input, n, perturbed)?;
    let nf = out.perturbed.len();
    let np = out.perturbed.iter().filter(|&&p| p).count();
    let t = out.tessellation;
    let per_face = 2 * (n - 1) * (n - 1);
    if t.triangles.len() != nf * per_face {
        return Err(Error::Internal(format!(
            "p-rep tessellation: {} triangles for {nf} patches of {per_face}",
            t.triangles.len()
        ))
        .into());
    }
    let triangle_class = if colors == Colors::PatchKind {
        out.perturbed
            .iter()
            .flat_map(|&p| {
                std::iter::repeat_n(if p { class::PERTURBED } else { class::B_QUAD }, per_face)
            })
            .collect()
    } else {
        vec![class::PLAIN; t.triangles.len()]
    };
    Ok(Surface {
        summary: format!(
            "p-rep: {nf} patches, {} B-quads, {np} perturbed{}",
            nf - np,
            if perturbed {
                ""
            } else {
                " (perturbation left out)"
            }
        ),
        notes,
        positions: t.positions,
        normals: t.normals,
        triangles: t.triangles,
        triangle_class,
        ..Default::default()
    })
}
