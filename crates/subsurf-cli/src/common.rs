//! Options shared by several subcommands.

use anyhow::Context;
use std::path::Path;
use subsurf::{BoundaryInterpolation, CreaseMethod, Mesh, Scheme, TriangleSubdivision};

/// Scheme and crease options that override what the input file says.
#[derive(Debug, Clone, clap::Args)]
pub struct SchemeArgs {
    /// Boundary interpolation (default: from the file's tags, else edge-only).
    #[arg(long, value_enum)]
    pub boundary: Option<BoundaryArg>,
    /// Crease decay method (default: from the file's tags, else uniform).
    #[arg(long, value_enum)]
    pub crease_method: Option<CreaseArg>,
    /// Subdivision scheme (default: from the file name prefix, else catmark).
    #[arg(long, value_enum)]
    pub scheme: Option<SchemeArg>,
    /// Triangle rule for Catmull-Clark.
    #[arg(long, value_enum)]
    pub triangles: Option<TriArg>,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum BoundaryArg {
    None,
    EdgeOnly,
    EdgeAndCorner,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum CreaseArg {
    Uniform,
    Chaikin,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum SchemeArg {
    Catmark,
    Bilinear,
}

#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum TriArg {
    Catmark,
    Smooth,
}

impl SchemeArgs {
    /// Reads a mesh file and applies the overrides.
    pub fn read(&self, path: &Path) -> anyhow::Result<Mesh> {
        let mut mesh = read_mesh(path)?;
        self.apply(&mut mesh);
        Ok(mesh)
    }

    /// Applies the overrides to `mesh`.
    pub fn apply(&self, mesh: &mut Mesh) {
        if let Some(b) = self.boundary {
            mesh.options.boundary = match b {
                BoundaryArg::None => BoundaryInterpolation::None,
                BoundaryArg::EdgeOnly => BoundaryInterpolation::EdgeOnly,
                BoundaryArg::EdgeAndCorner => BoundaryInterpolation::EdgeAndCorner,
            };
        }
        if let Some(c) = self.crease_method {
            mesh.options.crease_method = match c {
                CreaseArg::Uniform => CreaseMethod::Uniform,
                CreaseArg::Chaikin => CreaseMethod::Chaikin,
            };
        }
        if let Some(s) = self.scheme {
            mesh.options.scheme = match s {
                SchemeArg::Catmark => Scheme::Catmark,
                SchemeArg::Bilinear => Scheme::Bilinear,
            };
        }
        if let Some(t) = self.triangles {
            mesh.options.triangle_subdivision = match t {
                TriArg::Catmark => TriangleSubdivision::Catmark,
                TriArg::Smooth => TriangleSubdivision::Smooth,
            };
        }
    }
}

/// Reads a mesh file, with the path in the error.
pub fn read_mesh(path: &Path) -> anyhow::Result<Mesh> {
    subsurf::io::read_path(path).with_context(|| format!("reading {}", path.display()))
}

/// Writes a mesh file, with the path in the error.
pub fn write_mesh(path: &Path, mesh: &Mesh, normals: Option<&[[f32; 3]]>) -> anyhow::Result<()> {
    subsurf::io::write_path(path, mesh, normals)
        .with_context(|| format!("writing {}", path.display()))
}

/// Where the numeric work runs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Backend {
    /// Multithreaded CPU.
    #[default]
    Cpu,
    /// wgpu compute kernels (Vulkan, Metal, DX12; `WGPU_BACKEND`, `SUBSURF_ADAPTER` respected).
    Gpu,
}

/// Opens the GPU device, with a message that says what to do when there is none.
pub fn gpu_context() -> anyhow::Result<subsurf_gpu::GpuContext> {
    let ctx = subsurf_gpu::GpuContext::new().context(
        "--backend gpu: no usable GPU device (run `subsurf gpu-info --all`, or use --backend cpu)",
    )?;
    eprintln!("GPU backend: {}", ctx.adapter_info().name);
    Ok(ctx)
}
