//! `subsurf limit`: the limit surface (B-spline, single-crease and Gregory patches),
//! tessellated watertight with `N` samples per ptex-face side, written as OBJ or PLY with
//! normals.

use crate::common::{
    check_mesh_output, gpu_context, option_parser, shown, write_mesh, Backend, SchemeArgs,
};
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
    /// evaluation as wgpu kernels (same samples, f32 rounding of the device); with adaptive
    /// rates (`--tolerance`, `--max-edge-length`, `--pixels`) it measures the rate curves and
    /// the CPU evaluates the tessellation.
    #[arg(long, value_parser = option_parser::<Backend>(), default_value_t = Backend::Cpu)]
    pub backend: Backend,
    /// Double precision: refinement masks, end-cap points and evaluation in f64 (CPU only;
    /// `eval` prints f64 values, `limit` writes f64 positions).
    #[arg(long)]
    pub f64: bool,
}

impl SurfaceArgs {
    /// The `f32` or `f64` patch table of a mesh read with `self.scheme`; `--f64` needs the
    /// CPU.
    pub fn table_for<R: subsurf::Real>(&self, mesh: Mesh) -> anyhow::Result<(Mesh, PatchTable<R>)> {
        anyhow::ensure!(
            !(self.f64 && self.backend == Backend::Gpu),
            "--f64 evaluates on the CPU: it cannot be combined with --backend gpu"
        );
        let topo = Topology::new(&mesh)?;
        Ok((mesh, PatchTable::build_real(&topo, &self.patch_options())?))
    }

    /// The patch-table options of the flags.
    pub fn patch_options(&self) -> PatchOptions {
        PatchOptions {
            isolation_level: self.isolation,
            single_crease: !self.no_single_crease,
            ..Default::default()
        }
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
    #[command(flatten)]
    pub adaptive: crate::tess_args::AdaptiveArgs,
    #[command(flatten)]
    pub screen: crate::tess_args::ScreenArgs,
}

pub fn run(a: &LimitArgs) -> anyhow::Result<()> {
    check_mesh_output(&a.output)?;
    crate::common::set_f64_output(a.surface.f64);
    let mesh = a.surface.scheme.read(&a.surface.input)?;
    if mesh.options.scheme == subsurf::Scheme::Loop {
        return crate::limit_loop::run(a, mesh);
    }
    if a.adaptive.any() {
        anyhow::ensure!(
            !a.surface.f64,
            "--f64 works with a uniform --tess only (adaptive rates evaluate in f32)"
        );
        return run_adaptive(a, mesh);
    }
    // With --f64, the samples' f64 positions, written as the mesh holds them.
    let mut wide = None;
    let (tess, c, patches, ptex) = if a.surface.f64 {
        let (mesh, table) = a.surface.table_for::<f64>(mesh)?;
        let (c, p, x) = (table.counts(), table.num_patches(), table.num_ptex_faces());
        let surface = subsurf::limit::LimitSurface::new(table, &mesh.positions);
        let (plan, points) = surface.tessellate_real(a.tess)?;
        wide = Some(points.iter().map(|e| e.p).collect::<Vec<_>>());
        let tess = subsurf::limit::Tessellation::from_points(plan, &points);
        (tess, c, p, x)
    } else {
        let (mesh, table) = a.surface.table_for(mesh)?;
        let backend = surface_backend(a.surface.backend)?;
        let tess = backend.limit(&table, &mesh.positions, a.tess)?;
        (
            tess,
            table.counts(),
            table.num_patches(),
            table.num_ptex_faces(),
        )
    };
    let mut out = tess.to_mesh(a.quads);
    if let Some(p) = wide {
        out.positions = subsurf::Positions::from_f64(p);
    }
    write_mesh(&a.output, &out, Some(&tess.normals))?;
    crate::say!(
        "{} patches ({} regular, {} single-crease, {} Gregory) on {} ptex faces; \
         {} samples per side: {} vertices, {} faces -> {}",
        patches,
        c.regular,
        c.single_crease,
        c.gregory,
        ptex,
        tess.samples_per_side,
        out.positions.len(),
        out.num_faces(),
        shown(&a.output, true)
    );
    Ok(())
}

/// `limit` with per-edge rates (chosen on `--backend`, the tessellation evaluated on the CPU).
/// Under `--tolerance` the isolation is chosen per region (`surface::adaptive_surface`).
fn run_adaptive(a: &LimitArgs, mesh: Mesh) -> anyhow::Result<()> {
    if a.quads {
        anyhow::bail!("--quads needs a uniform --tess (adaptive tessellations are triangles)");
    }
    let topo = Topology::new(&mesh)?;
    let camera = a.screen.camera(&mesh.positions);
    let (policy, origin) = a.adaptive.policy(camera, &topo, a.tess)?;
    let (surface, policy) = subsurf::surface::adaptive_surface(
        &topo,
        &mesh.positions,
        &policy,
        &origin,
        &a.surface.patch_options(),
    )?;
    let backend = surface_backend(a.surface.backend)?;
    let adaptive =
        subsurf::surface::tessellate_adaptive(&surface, &policy, &origin, backend.as_ref())?;
    let tess = &adaptive.tessellation;
    let out = tess.to_mesh();
    write_mesh(&a.output, &out, Some(&tess.normals))?;
    let (lo, hi) = adaptive.rate_range();
    crate::say!(
        "{origin}: edge rates {lo}..={hi} on {} ptex faces: {} vertices, {} triangles -> {}",
        surface.table().num_ptex_faces(),
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
