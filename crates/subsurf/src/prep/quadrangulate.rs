//! Making any polygon mesh acceptable to the p-rep: one Catmull-Clark step (Catmull & Clark
//! 1978) turns every n-gon into n quads, with the scheme's own positions, creases and holes.

use crate::error::Result;
use crate::mesh::Mesh;
use crate::refine::Refiner;
use crate::topology::Topology;

/// One uniform Catmull-Clark refinement step of `mesh`: every face becomes quads
/// (`(v_i, edge point, face point, edge point)`), positions follow the subdivision rules, and
/// the mesh's options are kept. Crease tags are consumed by the step (their effect is in the
/// positions); UVs are dropped.
pub fn quadrangulate(mesh: &Mesh) -> Result<Mesh> {
    let refiner = Refiner::new(Topology::new(mesh)?, 1)?;
    let positions = refiner.refine_positions(&mesh.positions);
    Ok(refiner.to_mesh(1, positions))
}
