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
/// `f64` from the file's values, as the library does for a mesh holding `f64` positions).
pub fn run(a: &LimitArgs, mut mesh: Mesh) -> anyhow::Result<()> {
    if a.surface.f64 && !mesh.positions.is_f64() {
        mesh.positions = subsurf::Positions::from_f64(mesh.positions.to_f64().into_owned());
    }
    anyhow::ensure!(
        !a.adaptive.any(),
        "adaptive tessellation rates are implemented for the Catmull-Clark limit surface only; \
         use --tess with --scheme loop"
    );
    anyhow::ensure!(
        !a.quads,
        "--quads: the Loop limit surface is tessellated into triangles"
    );
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
