//! `subsurf prep`: convert a closed quad mesh to its p-rep G1 surface (Myles, Yeo & Peters
//! 2008), tessellate it to OBJ with normals and/or export the bi-5 Bézier control points.

use std::path::PathBuf;

use anyhow::Context;

use crate::common::{gpu_context, Backend};
use subsurf::prep::quadrangulate::quadrangulate;
use subsurf::prep::{PrepPatches, Real};
use subsurf::Mesh;

/// Arguments of `subsurf prep`.
#[derive(clap::Args, Debug, Clone)]
pub struct PrepArgs {
    /// Input mesh (.obj or .ply): a closed, oriented quad mesh.
    pub input: PathBuf,
    /// Samples per patch side of the tessellation (>= 2).
    #[arg(long = "tess", default_value_t = 9, value_parser = clap::value_parser!(u32).range(2..=1025))]
    pub tess: u32,
    /// Write the watertight tessellated surface (with normals) to this file (.obj or .ply).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Write the bi-5 Bézier control points as a (faces, 6, 6, 3) float64 .npy array.
    #[arg(long = "bezier")]
    pub bezier: Option<PathBuf>,
    /// Split every face into quads first (face centroid + edge midpoints) if the input has
    /// faces that are not quads.
    #[arg(long = "quadrangulate")]
    pub quadrangulate: bool,
    /// Build and evaluate in double precision (the output files are written from it).
    #[arg(long = "f64")]
    pub f64: bool,
    /// Where the p-rep is built and tessellated (the GPU backend is f32 only).
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    pub backend: Backend,
}

/// Runs `subsurf prep`.
pub fn run(args: &PrepArgs) -> anyhow::Result<()> {
    let mut mesh = subsurf::io::read_path(&args.input)
        .with_context(|| format!("reading {}", args.input.display()))?;
    let needs_quads = args.quadrangulate && mesh.face_counts.iter().any(|&c| c != 4);
    if args.backend == Backend::Gpu {
        anyhow::ensure!(!args.f64, "--backend gpu computes in f32 only; drop --f64");
        return convert_gpu(args, &mesh, needs_quads);
    }
    if needs_quads {
        mesh = quadrangulate(&mesh)?;
        eprintln!("quadrangulated: {} quads", mesh.num_faces());
    }
    if args.f64 {
        convert::<f64>(args, &mesh)
    } else {
        convert::<f32>(args, &mesh)
    }
}

fn convert<T: Real>(args: &PrepArgs, mesh: &Mesh) -> anyhow::Result<()> {
    let p = PrepPatches::<T>::build(mesh).with_context(|| {
        format!(
            "building the p-rep of {} (use --quadrangulate for non-quad input)",
            args.input.display()
        )
    })?;
    let nf = p.num_faces();
    let bquads = nf - p.topology.perturbed_faces.len();
    eprintln!(
        "p-rep ({}): {nf} patches, {bquads} B-quads ({:.1}%), max valence {}",
        T::NAME,
        100.0 * bquads as f64 / nf.max(1) as f64,
        p.topology.max_valence
    );
    if let Some(out) = &args.output {
        let t = p.tessellate(args.tess as usize);
        let to32 = |v: &[[T; 3]]| -> Vec<[f32; 3]> {
            v.iter().map(|x| x.map(|c| c.to_f64() as f32)).collect()
        };
        let tri = Mesh::from_faces(to32(&t.positions), &t.triangles);
        let normals = to32(&t.normals);
        subsurf::io::write_path(out, &tri, Some(&normals))
            .with_context(|| format!("writing {}", out.display()))?;
        eprintln!(
            "wrote {}: {} vertices, {} triangles",
            out.display(),
            t.positions.len(),
            t.triangles.len()
        );
    }
    if let Some(out) = &args.bezier {
        let file =
            std::fs::File::create(out).with_context(|| format!("creating {}", out.display()))?;
        let mut w = std::io::BufWriter::new(file);
        p.write_bezier_npy(&mut w)
            .and_then(|_| std::io::Write::flush(&mut w))
            .with_context(|| format!("writing {}", out.display()))?;
        eprintln!("wrote {}: ({nf}, 6, 6, 3) float64", out.display());
    }
    Ok(())
}

/// The GPU path: vertex and patch pass and the watertight tessellation as compute kernels;
/// with `quadrangulate`, the Catmull-Clark step to quads runs on the GPU too and its
/// positions feed the p-rep without leaving the GPU.
fn convert_gpu(args: &PrepArgs, mesh: &Mesh, quadrangulate: bool) -> anyhow::Result<()> {
    use subsurf::prep::{bezier::face_bezier, npy, PrepTopology};
    let ctx = gpu_context()?;
    let mut refined = None;
    let quads;
    let mesh = if quadrangulate {
        let refiner = subsurf::Refiner::new(subsurf::Topology::new(mesh)?, 1)?;
        let gpu = subsurf_gpu::GpuRefiner::new(&ctx, &refiner)
            .context("--backend gpu: uploading the quadrangulation step")?;
        gpu.update(&ctx, &mesh.positions)
            .context("--backend gpu: quadrangulating")?;
        // The refined connectivity; its positions stay on the GPU.
        quads = refiner.to_mesh(1, vec![[0.0; 3]; refiner.last().num_vertices()]);
        eprintln!("quadrangulated (GPU): {} quads", quads.num_faces());
        refined = Some(gpu);
        &quads
    } else {
        mesh
    };
    let topo = PrepTopology::new(&subsurf::Topology::new(mesh)?).with_context(|| {
        format!(
            "building the p-rep of {} (use --quadrangulate for non-quad input)",
            args.input.display()
        )
    })?;
    let mut gpu =
        subsurf_gpu::GpuPrep::new(&ctx, &topo).context("--backend gpu: uploading the p-rep")?;
    match &refined {
        Some(r) => gpu.update_from(&ctx, r.output()),
        None => gpu.update(&ctx, &mesh.positions),
    }
    .context("--backend gpu: vertex and patch pass")?;
    let nf = topo.num_faces();
    eprintln!(
        "p-rep (f32, GPU): {nf} patches, {} perturbed, max valence {}",
        topo.perturbed_faces.len(),
        topo.max_valence
    );
    if let Some(out) = &args.output {
        let grid = gpu
            .grid(&ctx, args.tess as usize)
            .and_then(|g| gpu.eval_grid(&ctx, &g).and_then(|_| g.download(&ctx)))
            .context("--backend gpu: tessellating")?;
        let tri = Mesh::from_faces(grid.positions.clone(), &grid.triangles);
        subsurf::io::write_path(out, &tri, Some(&grid.normals))
            .with_context(|| format!("writing {}", out.display()))?;
        eprintln!(
            "wrote {}: {} vertices, {} triangles",
            out.display(),
            grid.positions.len(),
            grid.triangles.len()
        );
    }
    if let Some(out) = &args.bezier {
        let (_, pd) = gpu
            .download_coefficients(&ctx)
            .context("--backend gpu: reading coefficients back")?;
        let pt = |s: usize| [pd[3 * s], pd[3 * s + 1], pd[3 * s + 2]];
        let mut data = Vec::with_capacity(36 * 3 * nf);
        for f in 0..nf {
            let g: Vec<[f32; 3]> = (16 * f..16 * f + 16).map(pt).collect();
            let hi = topo.h_index[f];
            let h: Option<Vec<[f32; 3]>> = (hi != u32::MAX).then(|| {
                (16 * (nf + hi as usize)..16 * (nf + hi as usize) + 16)
                    .map(pt)
                    .collect()
            });
            for b in face_bezier(&g, h.as_deref()) {
                data.extend(b.map(f64::from));
            }
        }
        let file =
            std::fs::File::create(out).with_context(|| format!("creating {}", out.display()))?;
        let mut w = std::io::BufWriter::new(file);
        npy::write_f64(&mut w, &data, &[nf, 6, 6, 3])
            .and_then(|_| std::io::Write::flush(&mut w))
            .with_context(|| format!("writing {}", out.display()))?;
        eprintln!("wrote {}: ({nf}, 6, 6, 3) float64", out.display());
    }
    Ok(())
}
