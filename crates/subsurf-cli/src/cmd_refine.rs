//! `subsurf refine`: uniform subdivision to a level, written as OBJ or PLY.

use crate::cmd_limit::surface_backend;
use crate::common::{check_mesh_output, shown, write_mesh, Backend, SchemeArgs};
use std::path::PathBuf;
use subsurf::surface::refine_mesh;
use subsurf::FVarLinearInterpolation;

/// Refine a mesh uniformly.
#[derive(Debug, clap::Args)]
pub struct RefineArgs {
    /// Input mesh: .obj (with OpenSubdiv's tags), .ply, .gltf or .glb; `-` reads OBJ, PLY or GLB
    /// from standard input.
    pub input: PathBuf,
    /// Number of refinement steps.
    #[arg(short, long, default_value_t = 2)]
    pub level: usize,
    /// Output file, format by extension: .obj (with the remaining crease tags), .ply or .glb;
    /// `-` writes standard output (`--format obj|ply|glb`, OBJ by default).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Move the last level's vertices to their limit positions, and its UVs to their
    /// face-varying limit (OpenSubdiv `Limit` and `LimitFaceVarying`).
    #[arg(long)]
    pub limit: bool,
    /// Face-varying (UV) interpolation; default: the mesh's own option (linear unless tagged).
    #[arg(long, value_enum)]
    pub uv_interp: Option<UvInterp>,
    /// Where the refinement stencils are applied.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

/// OpenSubdiv's `FVarLinearInterpolation` modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum UvInterp {
    /// Smooth everywhere, UV boundaries included.
    None,
    /// Smooth, with sharp UV corners.
    CornersOnly,
    /// Smooth, with sharp UV corners and junctions (variant 1).
    CornersPlus1,
    /// Smooth, with sharp UV corners and junctions (variant 2).
    CornersPlus2,
    /// Smooth inside, linear along UV boundaries.
    Boundaries,
    /// Linear everywhere.
    Linear,
}

impl From<UvInterp> for FVarLinearInterpolation {
    fn from(u: UvInterp) -> Self {
        match u {
            UvInterp::None => FVarLinearInterpolation::None,
            UvInterp::CornersOnly => FVarLinearInterpolation::CornersOnly,
            UvInterp::CornersPlus1 => FVarLinearInterpolation::CornersPlus1,
            UvInterp::CornersPlus2 => FVarLinearInterpolation::CornersPlus2,
            UvInterp::Boundaries => FVarLinearInterpolation::Boundaries,
            UvInterp::Linear => FVarLinearInterpolation::All,
        }
    }
}

pub fn run(a: &RefineArgs) -> anyhow::Result<()> {
    check_mesh_output(&a.output)?;
    let mesh = a.scheme.read(&a.input)?;
    let backend = surface_backend(a.backend)?;
    let out = refine_mesh(
        &mesh,
        a.level,
        a.limit,
        a.uv_interp.map(Into::into),
        backend.as_ref(),
    )?;
    finish(a, &mesh, out)
}

/// Writes the refined mesh and reports what was made.
fn finish(a: &RefineArgs, mesh: &subsurf::Mesh, out: subsurf::Mesh) -> anyhow::Result<()> {
    write_mesh(&a.output, &out, None)?;
    crate::say!(
        "refined {} faces to level {}: {} vertices, {} faces -> {}",
        mesh.num_faces(),
        a.level,
        out.positions.len(),
        out.num_faces(),
        shown(&a.output, true)
    );
    Ok(())
}
