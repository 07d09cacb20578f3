//! `subsurf refine`: uniform subdivision to a level, written as OBJ or PLY.

use crate::common::{gpu_context, read_mesh, write_mesh, Backend, SchemeArgs};
use anyhow::Context as _;
use std::path::PathBuf;
use subsurf::{refine::refine_uvs_linear, FaceVarying, Refiner, Topology};

/// Refine a mesh uniformly.
#[derive(Debug, clap::Args)]
pub struct RefineArgs {
    /// Input mesh (.obj with OpenSubdiv tags, or .ply).
    pub input: PathBuf,
    /// Number of refinement steps.
    #[arg(short, long, default_value_t = 2)]
    pub level: usize,
    /// Output file (.obj or .ply, by extension).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Move the last level's vertices to their limit positions.
    #[arg(long)]
    pub limit: bool,
    /// Where the refinement stencils are applied.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

pub fn run(a: &RefineArgs) -> anyhow::Result<()> {
    let mut mesh = read_mesh(&a.input)?;
    a.scheme.apply(&mut mesh);
    let topo = Topology::new(&mesh)?;
    let refiner = Refiner::new(topo, a.level)?;
    let mut positions = match a.backend {
        Backend::Cpu => refiner.refine_positions(&mesh.positions),
        Backend::Gpu => {
            let ctx = gpu_context()?;
            subsurf_gpu::GpuRefiner::new(&ctx, &refiner)
                .and_then(|g| g.refine(&ctx, &mesh.positions))
                .context("--backend gpu: refining on the GPU")?
        }
    };
    if a.limit {
        positions = refiner.limit(&positions);
    }
    let mut out = refiner.to_mesh(a.level, positions);
    if let Some(fv) = &mesh.uvs {
        // Linear face-varying interpolation, one value per face corner.
        let mut corner: Vec<[f32; 2]> = fv.indices.iter().map(|&i| fv.values[i as usize]).collect();
        for k in 0..a.level {
            corner = refine_uvs_linear(&refiner.levels[k], &corner);
        }
        let t = refiner.last();
        let mut values = Vec::with_capacity(out.face_indices.len());
        for f in 0..t.num_faces() {
            if !t.face_is_hole[f] {
                let (s, e) = (t.face_offsets[f] as usize, t.face_offsets[f + 1] as usize);
                values.extend_from_slice(&corner[s..e]);
            }
        }
        let indices = (0..values.len() as u32).collect();
        out.uvs = Some(FaceVarying { values, indices });
    }
    out.creases.clear();
    out.corners.clear();
    write_mesh(&a.output, &out, None)?;
    eprintln!(
        "refined {} faces to level {}: {} vertices, {} faces -> {}",
        mesh.num_faces(),
        a.level,
        out.positions.len(),
        out.num_faces(),
        a.output.display()
    );
    Ok(())
}
