//! `subsurf limit` on a Loop mesh: the Loop limit surface of `subsurf::surface::build`
//! (box-spline patches and Gregory-triangle end caps), a triangular grid of `--tess − 1`
//! segments per base edge, watertight, written with normals.

use anyhow::Context;
use subsurf::limit::PatchOptions;
use subsurf::surface::{Colors, Method, SurfaceOptions};
use subsurf::Mesh;

use crate::cmd_limit::{surface_backend, LimitArgs};
use crate::common::{shown, write_mesh};

/// Tessellates the Loop limit surface of `mesh` as `a` asks (`--f64`: its points refined in
/// `f64` from the file's values and its positions written in `f64`).
pub fn run(a: &LimitArgs, mesh: Mesh) -> anyhow::Result<()> {
    anyhow::ensure!(
        !a.adaptive.any(),
        "adaptive tessellation rates are implemented for the Catmull-Clark limit surface only; \
         use --tess with --scheme loop"
    );
    anyhow::ensure!(
        !a.quads,
        "--quads: the Loop limit surface is tessellated into triangles"
    );
    if a.surface.f64 {
        return run_f64(a, &mesh);
    }
    let options = SurfaceOptions {
        method: Method::Limit {
            samples: a.tess,
            options: PatchOptions {
                isolation_level: a.surface.isolation,
                ..Default::default()
            },
        },
        colors: Colors::None,
        cage: false,
    };
    let backend = surface_backend(a.surface.backend)?;
    let s = subsurf::surface::build(&mesh, &options, backend.as_ref())
        .context("building the Loop limit surface")?;
    let out = Mesh::from_faces(s.positions, &s.triangles);
    write_mesh(&a.output, &out, Some(&s.normals))?;
    crate::say!(
        "{}: {} vertices, {} triangles -> {}",
        s.summary,
        out.positions.len(),
        out.num_faces(),
        shown(&a.output, true)
    );
    Ok(())
}

/// `limit --f64` on a Loop mesh: the Loop patches refined in `f64` from the file's values
/// (`LoopLimit::new_f64`), tessellated on the CPU and written with `f64` positions.
fn run_f64(a: &LimitArgs, mesh: &Mesh) -> anyhow::Result<()> {
    anyhow::ensure!(
        a.surface.backend == crate::common::Backend::Cpu,
        "--f64 evaluates on the CPU: it cannot be combined with --backend gpu"
    );
    let max = subsurf::surface::MAX_LOOP_SAMPLES;
    anyhow::ensure!(
        (2..=max).contains(&a.tess),
        "{} samples per edge of the Loop limit surface (2..={max})",
        a.tess
    );
    let topo = subsurf::Topology::new(mesh)?;
    let limit = subsurf::limit::LoopLimit::new_f64(&topo, &mesh.positions, a.surface.isolation)
        .context("building the Loop limit patches")?;
    let (out, normals) = limit.tessellate(&topo, a.tess - 1)?.to_mesh_f64();
    let normals: Vec<[f32; 3]> = normals.iter().map(|n| n.map(|x| x as f32)).collect();
    write_mesh(&a.output, &out, Some(&normals))?;
    crate::say!(
        "Loop limit in f64: {} patches on {} faces: {} vertices, {} triangles -> {}",
        limit.patches.len(),
        topo.num_faces(),
        out.positions.len(),
        out.num_faces(),
        shown(&a.output, true)
    );
    Ok(())
}
