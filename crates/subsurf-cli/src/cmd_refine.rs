//! `subsurf refine`: uniform subdivision to a level, written as OBJ, PLY, glTF or USD (a USD
//! stage refines every mesh prim, or `--prim`, and is written back whole).

use crate::cmd_limit::surface_backend;
use crate::common::{
    check_mesh_output, option_parser, output_mesh, shown, write_mesh, write_options, Backend,
    SchemeArgs,
};
use crate::usd_stage::{is_usd, read_stage, select};
use anyhow::Context as _;
use std::path::PathBuf;
use subsurf::surface::{self, refine_mesh};
use subsurf::FVarLinearInterpolation;

/// Refine a mesh uniformly.
#[derive(Debug, clap::Args)]
pub struct RefineArgs {
    /// Input mesh: .obj (with OpenSubdiv's tags), .ply, .gltf, .glb, or a USD stage (.usda,
    /// .usdc, .usd, .usdz); `-` reads OBJ, PLY or GLB from standard input.
    pub input: PathBuf,
    /// Number of refinement steps.
    #[arg(short, long, default_value_t = 2)]
    pub level: usize,
    /// Output file, format by extension: .obj (with the remaining crease tags), .ply, .glb, or
    /// .usda/.usdc/.usdz (the input stage with its mesh prims refined, subdivisionScheme none);
    /// `-` writes standard output (`--format obj|ply|glb`, OBJ by default).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Move the last level's vertices to their limit positions, and its UVs to their
    /// face-varying limit (OpenSubdiv `Limit` and `LimitFaceVarying`).
    #[arg(long)]
    pub limit: bool,
    /// Face-varying (UV) interpolation; default: the mesh's own option (linear unless tagged).
    #[arg(long, alias = "uv-interp", value_parser = option_parser::<FVarLinearInterpolation>())]
    pub uv_interpolation: Option<FVarLinearInterpolation>,
    /// Where the refinement stencils are applied.
    #[arg(long, value_parser = option_parser::<Backend>(), default_value_t = Backend::Cpu)]
    pub backend: Backend,
    /// Double precision from the file to the output: the positions as the file holds them
    /// (OBJ digits, PLY doubles, USD point3d), every step's masks in f64 (CPU only), the
    /// result written in f64 (OBJ shortest round-trip digits, PLY double, USD point3d[]).
    #[arg(long)]
    pub f64: bool,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

pub fn run(a: &RefineArgs) -> anyhow::Result<()> {
    check_mesh_output(&a.output)?;
    anyhow::ensure!(
        !(a.f64 && a.backend == Backend::Gpu),
        "--f64 refines on the CPU: it cannot be combined with --backend gpu"
    );
    crate::common::set_f64_output(a.f64);
    let backend = surface_backend(a.backend)?;
    if is_usd(&a.input) {
        return run_stage(a, backend.as_ref());
    }
    let mesh = a.scheme.read(&a.input)?;
    let out = refine_one(a, &mesh, backend.as_ref())?;
    finish(a, &mesh, out)
}

/// A USD stage: every mesh prim (or `--prim`) refined in place, the stage written back with
/// its other prims, or the one refined mesh written in another format.
fn run_stage(a: &RefineArgs, backend: &dyn surface::Backend) -> anyhow::Result<()> {
    let mut stage = read_stage(&a.input)?;
    let prims = select(&stage, &a.input, a.scheme.prim.as_deref())?;
    let usd_out = is_usd(&a.output);
    anyhow::ensure!(
        usd_out || prims.len() == 1,
        "{}: {} mesh prims; write a USD stage (-o out.usda) or choose one with --prim",
        a.input.display(),
        prims.len()
    );
    for p in prims {
        if !p.subdivide {
            crate::say!("{}: subdivisionScheme none, kept as it is", p.path);
            continue;
        }
        let mut mesh = p.mesh;
        a.scheme.apply(&mut mesh);
        let out = refine_one(a, &mesh, backend).with_context(|| format!("refining {}", p.path))?;
        crate::say!(
            "{}: refined {} faces to level {}: {} vertices, {} faces",
            p.path,
            mesh.num_faces(),
            a.level,
            out.positions.len(),
            out.num_faces()
        );
        if !usd_out {
            return finish(a, &mesh, out);
        }
        stage.set_mesh_with(&p.path, &output_mesh(&out), true, &write_options())?;
    }
    stage
        .write_path(&a.output)
        .with_context(|| format!("writing {}", a.output.display()))?;
    crate::say!("-> {}", shown(&a.output, true));
    Ok(())
}

/// One mesh refined as the arguments ask (the library's `surface::refine_mesh`).
fn refine_one(
    a: &RefineArgs,
    mesh: &subsurf::Mesh,
    backend: &dyn surface::Backend,
) -> anyhow::Result<subsurf::Mesh> {
    if a.f64 {
        return Ok(surface::refine_mesh_f64(
            mesh,
            a.level,
            a.limit,
            a.uv_interpolation,
        )?);
    }
    Ok(refine_mesh(
        mesh,
        a.level,
        a.limit,
        a.uv_interpolation,
        backend,
    )?)
}

/// Writes the refined mesh and reports what was made.
fn finish(a: &RefineArgs, mesh: &subsurf::Mesh, out: subsurf::Mesh) -> anyhow::Result<()> {
    let written = output_mesh(&out);
    if is_usd(&a.output) {
        // A refined mesh in USD is a polygon mesh (subdivisionScheme none).
        let mut stage = subsurf::io::usd::Stage::from_mesh_with(&written, &write_options());
        stage.set_mesh_with("/Mesh", &written, true, &write_options())?;
        stage
            .write_path(&a.output)
            .with_context(|| format!("writing {}", a.output.display()))?;
    } else {
        write_mesh(&a.output, &written, None)?;
    }
    let left_out = out.num_faces() - written.num_faces();
    crate::say!(
        "refined {} faces to level {}: {} vertices, {} faces{} -> {}",
        mesh.num_faces(),
        a.level,
        out.positions.len(),
        written.num_faces(),
        if left_out > 0 {
            format!(" ({left_out} hole faces left out; --keep-holes writes them tagged)")
        } else {
            String::new()
        },
        shown(&a.output, true)
    );
    Ok(())
}
