//! `subsurf limit`: the limit surface (B-spline, single-crease and Gregory patches),
//! tessellated watertight with `N` samples per ptex-face side, written as OBJ or PLY with
//! normals.

use crate::common::{write_mesh, SchemeArgs};
use std::path::PathBuf;
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::Topology;

/// The limit surface of a mesh file: the input and the patch-table options shared by
/// `limit` and `eval`.
#[derive(Debug, clap::Args)]
pub struct SurfaceArgs {
    /// Input mesh (.obj with OpenSubdiv tags, or .ply).
    pub input: PathBuf,
    /// Isolation level of extraordinary and irregular features (0..=10).
    #[arg(long, default_value_t = 4)]
    pub isolation: u32,
    /// Isolate semi-sharp creases by refinement instead of single-crease patches.
    #[arg(long)]
    pub no_single_crease: bool,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

impl SurfaceArgs {
    /// Reads the mesh and builds its patch table.
    pub fn load(&self) -> anyhow::Result<LimitSurface> {
        let mesh = self.scheme.read(&self.input)?;
        let topo = Topology::new(&mesh)?;
        let table = PatchTable::build(
            &topo,
            &PatchOptions {
                isolation_level: self.isolation,
                single_crease: !self.no_single_crease,
                ..Default::default()
            },
        )?;
        Ok(LimitSurface::new(table, &mesh.positions))
    }
}

/// Tessellate the limit surface.
#[derive(Debug, clap::Args)]
pub struct LimitArgs {
    #[command(flatten)]
    pub surface: SurfaceArgs,
    /// Samples per side of each ptex face (odd values keep n-gon seams exact; even ones are
    /// raised by one on meshes with non-quad faces).
    #[arg(long, default_value_t = 9)]
    pub tess: usize,
    /// Output file (.obj or .ply, by extension).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write the grid quads instead of triangles.
    #[arg(long)]
    pub quads: bool,
}

pub fn run(a: &LimitArgs) -> anyhow::Result<()> {
    let s = a.surface.load()?;
    let tess = s.tessellate(a.tess)?;
    let out = tess.to_mesh(a.quads);
    write_mesh(&a.output, &out, Some(&tess.normals))?;
    let c = s.table.counts();
    eprintln!(
        "{} patches ({} regular, {} single-crease, {} Gregory) on {} ptex faces; \
         {} samples per side: {} vertices, {} faces -> {}",
        s.table.num_patches(),
        c.regular,
        c.single_crease,
        c.gregory,
        s.table.num_ptex_faces(),
        tess.samples_per_side,
        out.positions.len(),
        out.num_faces(),
        a.output.display()
    );
    Ok(())
}
