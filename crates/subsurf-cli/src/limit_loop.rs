//! `subsurf limit` on a Loop mesh: the Loop limit surface (box-spline patches and
//! Gregory-triangle end caps, `subsurf::limit::loop_eval`), a triangular grid of `--tess − 1`
//! segments per base edge, watertight, written with normals.

use anyhow::Context;
use subsurf::limit::loop_eval::LoopLimit;
use subsurf::{Mesh, Topology};

use crate::cmd_limit::LimitArgs;
use crate::common::{shown, write_mesh, Backend};

/// Tessellates the Loop limit surface of `mesh` as `a` asks.
pub fn run(a: &LimitArgs, mesh: Mesh) -> anyhow::Result<()> {
    anyhow::ensure!(
        a.surface.backend == Backend::Cpu,
        "the Loop limit surface is evaluated on the CPU only (drop --backend gpu)"
    );
    anyhow::ensure!(
        !a.adaptive.any(),
        "adaptive tessellation rates are implemented for the Catmull-Clark limit surface only; \
         use --tess with --scheme loop"
    );
    anyhow::ensure!(
        !a.quads,
        "--quads: the Loop limit surface is tessellated into triangles"
    );
    anyhow::ensure!(
        a.tess >= 2,
        "--tess {}: at least 2 samples per edge (1 segment)",
        a.tess
    );
    let topo = Topology::new(&mesh)?;
    let surface = LoopLimit::new(&topo, &mesh.positions, a.surface.isolation)
        .context("building the Loop limit patches")?;
    let regular = surface.patches.iter().filter(|p| p.regular).count();
    let tess = surface.tessellate(&topo, a.tess - 1)?;
    let (out, normals) = tess.to_mesh();
    write_mesh(&a.output, &out, Some(&normals))?;
    crate::say!(
        "{} Loop patches ({} box-spline, {} Gregory-triangle) on {} faces; \
         {} segments per edge: {} vertices, {} triangles -> {}",
        surface.patches.len(),
        regular,
        surface.patches.len() - regular,
        topo.num_faces(),
        a.tess - 1,
        out.positions.len(),
        out.num_faces(),
        shown(&a.output, true)
    );
    Ok(())
}
