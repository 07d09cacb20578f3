//! Mesh in, refined mesh out: the refine step every front end shares (the CLI's `refine`, the
//! Python package's `subsurf.refine`). Positions and UVs refine on the backend; the result
//! keeps all faces, holes tagged, with the sharpness that remains after the decay, so that it
//! refines on as the level itself would.

use super::{Backend, SurfaceError};
use crate::options::FVarLinearInterpolation;
use crate::refine::{refine_once_mesh, RefineOptions};
use crate::{Error, Mesh, Positions, Refiner, Topology};

/// `mesh` refined `level` steps on `backend`, its last level (positions and UVs) moved to the
/// limit when `limit`. UVs refine in `uv_mode` (the mesh's own mode when `None`) and the
/// output records that mode.
///
/// Without limit and UVs, a backend whose [`Backend::one_pass`] is true (the CPU) refines in
/// one pass without keeping stencil tables ([`refine_once_mesh`]; the same numbers, about half
/// the peak memory).
///
/// ```
/// use subsurf::surface::{refine_mesh, Cpu};
/// let out = refine_mesh(&subsurf::shapes::cube(), 2, false, None, &Cpu)?;
/// assert_eq!(out.num_faces(), 6 * 16);
/// # Ok::<(), subsurf::surface::SurfaceError>(())
/// ```
pub fn refine_mesh(
    mesh: &Mesh,
    level: usize,
    limit: bool,
    uv_mode: Option<FVarLinearInterpolation>,
    backend: &dyn Backend,
) -> Result<Mesh, SurfaceError> {
    let topo = Topology::new(mesh)?;
    // The last level's full topology is read only by the limit step and the UV refinement.
    let full = limit || mesh.uvs.is_some();
    if !full && backend.one_pass() {
        return Ok(refine_once_mesh(
            topo,
            level,
            &mesh.positions,
            RefineOptions::lean(),
        )?);
    }
    let options = RefineOptions {
        full_topology_in_last_level: full,
    };
    let refiner = Refiner::with_options(topo, level, options)?;
    let positions = backend.refine(&refiner, &mesh.positions, limit)?;
    let out = refiner.to_tagged_mesh(level, positions)?;
    with_uvs(mesh, &refiner, out, limit, uv_mode, backend)
}

/// [`refine_mesh`] in double precision, on the CPU: the masks of every step (and the limit
/// masks) in `f64`, applied to the positions as the mesh holds them (a file's digits, without
/// rounding); the result holds its positions in `f64` ([`crate::mesh::Positions::from_f64`]).
/// UVs refine as [`refine_mesh`] refines them.
pub fn refine_mesh_f64(
    mesh: &Mesh,
    level: usize,
    limit: bool,
    uv_mode: Option<FVarLinearInterpolation>,
) -> Result<Mesh, SurfaceError> {
    let topo = Topology::new(mesh)?;
    let options = RefineOptions {
        full_topology_in_last_level: limit || mesh.uvs.is_some(),
    };
    let refiner = Refiner::with_options(topo, level, options)?;
    let mut positions = refiner.refine_f64(&mesh.positions)?;
    if limit {
        positions = refiner.limit_f64(&positions)?;
    }
    let out = refiner.to_tagged_mesh(level, Positions::from_f64(positions))?;
    with_uvs(mesh, &refiner, out, limit, uv_mode, &super::Cpu)
}

/// `out` with `mesh`'s UVs refined on `backend` (in `uv_mode`, the mesh's own mode when
/// `None`), moved to their limit when `limit`; `out` itself when the mesh has none.
fn with_uvs(
    mesh: &Mesh,
    refiner: &Refiner,
    mut out: Mesh,
    limit: bool,
    uv_mode: Option<FVarLinearInterpolation>,
    backend: &dyn Backend,
) -> Result<Mesh, SurfaceError> {
    if let Some(fv) = &mesh.uvs {
        let mode = uv_mode.unwrap_or(mesh.options.uv_interpolation);
        let fvar = refiner.fvar_refinement(&fv.indices, fv.values.len(), mode)?;
        let last = backend.refine_uvs(refiner, &fvar, &fv.values, limit)?;
        if last.indices.len() != out.face_indices.len() {
            return Err(Error::Internal(format!(
                "{} refined UV indices for {} face corners",
                last.indices.len(),
                out.face_indices.len()
            ))
            .into());
        }
        out.options.uv_interpolation = mode;
        out.uvs = Some(last);
    }
    Ok(out)
}
