//! `subsurf limit`: the limit surface (B-spline, single-crease and Gregory patches),
//! tessellated watertight with `N` samples per ptex-face side, written as OBJ or PLY with
//! normals.

use crate::common::{check_mesh_output, gpu_context, shown, write_mesh, Backend, SchemeArgs};
use anyhow::Context;
use std::path::PathBuf;
use subsurf::limit::{PatchOptions, PatchTable};
use subsurf::{Mesh, Topology};

/// The limit surface of a mesh file: the input and the patch-table options shared by
/// `limit` and `eval`.
#[derive(Debug, clap::Args)]
pub struct SurfaceArgs {
    /// Input mesh: .obj (with OpenSubdiv's tags), .ply, .gltf, .glb or USD (.usda, .usdc, .usdz;
    /// one mesh prim, or `--prim`); `-` reads OBJ, PLY or GLB from standard input.
    pub input: PathBuf,
    /// Isolation level of extraordinary and irregular features (0..=10).
    #[arg(long, default_value_t = 4)]
    pub isolation: u32,
    /// Isolate semi-sharp creases by refinement instead of single-crease patches.
    #[arg(long)]
    pub no_single_crease: bool,
    #[command(flatten)]
    pub scheme: SchemeArgs,
    /// Where the surface is evaluated: the GPU runs refinement, end-cap points and patch
    /// evaluation as wgpu kernels (same samples, f32 rounding of the device).
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
}

impl SurfaceArgs {
    /// Reads the mesh and builds its patch table.
    pub fn load_table(&self) -> anyhow::Result<(Mesh, PatchTable)> {
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
        Ok((mesh, table))
    }

    /// Uploads the patch table to the GPU and computes its points from `mesh`'s positions.
    pub fn upload(
        &self,
        ctx: &subsurf_gpu::GpuContext,
        mesh: &Mesh,
        table: &PatchTable,
    ) -> anyhow::Result<subsurf_gpu::GpuLimit> {
        let mut gpu = subsurf_gpu::GpuLimit::new(ctx, table)
            .context("--backend gpu: uploading the patch table")?;
        gpu.update(ctx, &mesh.positions)
            .context("--backend gpu: refining and computing end-cap points")?;
        Ok(gpu)
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
    /// Output file, format by extension: .obj, .ply or .glb (with normals); `-` writes standard
    /// output (`--format obj|ply|glb`, OBJ by default).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write the grid quads instead of triangles.
    #[arg(long)]
    pub quads: bool,
}

pub fn run(a: &LimitArgs) -> anyhow::Result<()> {
    check_mesh_output(&a.output)?;
    let (mesh, table) = a.surface.load_table()?;
    let tess = surface_backend(a.surface.backend)?.limit(&table, &mesh.positions, a.tess)?;
    let out = tess.to_mesh(a.quads);
    write_mesh(&a.output, &out, Some(&tess.normals))?;
    let c = table.counts();
    crate::say!(
        "{} patches ({} regular, {} single-crease, {} Gregory) on {} ptex faces; \
         {} samples per side: {} vertices, {} faces -> {}",
        table.num_patches(),
        c.regular,
        c.single_crease,
        c.gregory,
        table.num_ptex_faces(),
        tess.samples_per_side,
        out.positions.len(),
        out.num_faces(),
        shown(&a.output, true)
    );
    Ok(())
}

/// The `subsurf::surface` backend for `--backend`: the CPU, or the GPU opened with the
/// install hint on failure.
pub fn surface_backend(b: Backend) -> anyhow::Result<Box<dyn subsurf::surface::Backend>> {
    Ok(match b {
        Backend::Cpu => Box::new(subsurf::surface::Cpu),
        Backend::Gpu => Box::new(subsurf_gpu::GpuBackend {
            ctx: gpu_context()?,
        }),
    })
}
