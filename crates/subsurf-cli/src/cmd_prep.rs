//! `subsurf prep`: convert a closed quad mesh to its p-rep G1 surface (Myles, Yeo & Peters
//! 2008), tessellate it to OBJ with normals and/or export the bi-5 Bézier control points.

use std::path::PathBuf;

use anyhow::Context;

use crate::common::{
    check_mesh_output, check_output_ext, create_output, gpu_context, is_stdio, option_parser,
    read_mesh, shown, write_mesh, Backend,
};
use crate::progress::note;
use subsurf::prep::quadrangulate;
use subsurf::prep::PrepPatches;
use subsurf::Mesh;
use subsurf::Real;

/// Arguments of `subsurf prep`.
#[derive(clap::Args, Debug, Clone)]
pub struct PrepArgs {
    /// Input mesh (.obj, .ply, .gltf, .glb, or USD with one mesh prim; `-` reads OBJ, PLY or GLB from standard input): a
    /// closed, oriented quad mesh.
    pub input: PathBuf,
    /// Samples per patch side of the tessellation (>= 2).
    #[arg(long = "tess", default_value_t = 9, value_parser = clap::value_parser!(u32).range(2..=1025))]
    pub tess: u32,
    /// Write the watertight tessellated surface (with normals) to this file: .obj, .ply or .glb
    /// by extension; `-` writes standard output (`--format obj|ply|glb`).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Write the bi-5 Bézier control points as a (faces, 6, 6, 3) float64 .npy array (built in
    /// double precision unless --f32; `-` writes standard output).
    #[arg(long = "bezier")]
    pub bezier: Option<PathBuf>,
    /// Split every face into quads first if the input has faces that are not quads: one
    /// Catmull-Clark step (every n-gon becomes n quads, with the scheme's positions, creases
    /// and holes).
    #[arg(long = "quadrangulate")]
    pub quadrangulate: bool,
    /// Build and evaluate in double precision (the output files are written from it); the
    /// default when --bezier is given on the CPU.
    #[arg(long = "f64", conflicts_with = "f32")]
    pub f64: bool,
    /// Build in single precision even with --bezier (the CAD export is then not exact).
    #[arg(long = "f32")]
    pub f32: bool,
    /// Where the p-rep is built and tessellated (the GPU backend is f32 only).
    #[arg(long, value_parser = option_parser::<Backend>(), default_value_t = Backend::Cpu)]
    pub backend: Backend,
}

/// Runs `subsurf prep`.
pub fn run(args: &PrepArgs) -> anyhow::Result<()> {
    anyhow::ensure!(
        !(args.f64 && args.backend == Backend::Gpu),
        "--backend gpu computes in f32 only; drop --f64"
    );
    anyhow::ensure!(
        args.output.is_some() || args.bezier.is_some(),
        "nothing to write: give -o OUT (.obj, .ply or .glb) and/or --bezier OUT.npy"
    );
    if let Some(out) = &args.output {
        check_mesh_output(out)?;
    }
    if let Some(out) = &args.bezier {
        check_output_ext(out, "npy")?;
    }
    anyhow::ensure!(
        !(args.output.as_deref().is_some_and(is_stdio)
            && args.bezier.as_deref().is_some_and(is_stdio)),
        "-o - and --bezier - would both write standard output; name a file for one of them"
    );
    let mut mesh = read_mesh(&args.input)?;
    let needs_quads = args.quadrangulate && mesh.face_counts.iter().any(|&c| c != 4);
    if args.backend == Backend::Gpu {
        if args.bezier.is_some() && !args.f32 {
            note("--backend gpu builds in f32: the --bezier export is not exact (the CPU builds it in f64)");
        }
        return convert_gpu(args, &mesh, needs_quads);
    }
    if needs_quads {
        mesh = quadrangulate(&mesh)?;
        crate::say!("quadrangulated: {} quads", mesh.num_faces());
    }
    // The Bezier form is the CAD export: exact (f64) unless f32 is asked for.
    if args.f64 || (args.bezier.is_some() && !args.f32) {
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
    let bquads = nf - p.topology().perturbed_faces().len();
    crate::say!(
        "p-rep ({}): {nf} patches, {bquads} B-quads ({:.1}%), max valence {}",
        T::NAME,
        100.0 * bquads as f64 / nf.max(1) as f64,
        p.topology().max_valence()
    );
    if let Some(out) = &args.output {
        let t = p.tessellate(args.tess as usize);
        let to32 = |v: &[[T; 3]]| -> Vec<[f32; 3]> {
            v.iter().map(|x| x.map(|c| c.to_f64() as f32)).collect()
        };
        let tri = Mesh::from_faces(to32(&t.positions), &t.triangles);
        let normals = to32(&t.normals);
        write_mesh(out, &tri, Some(&normals))?;
        crate::say!(
            "wrote {}: {} vertices, {} triangles",
            shown(out, true),
            t.positions.len(),
            t.triangles.len()
        );
    }
    if let Some(out) = &args.bezier {
        let mut w = create_output(out)?;
        p.write_bezier_npy(&mut w)
            .and_then(|_| std::io::Write::flush(&mut w))
            .with_context(|| format!("writing {}", shown(out, true)))?;
        crate::say!("wrote {}: ({nf}, 6, 6, 3) float64", shown(out, true));
    }
    Ok(())
}

/// The GPU path: vertex and patch pass and the watertight tessellation as compute kernels;
/// with `quadrangulate`, the Catmull-Clark step to quads runs on the GPU too and its
/// positions feed the p-rep without leaving the GPU.
fn convert_gpu(args: &PrepArgs, mesh: &Mesh, quadrangulate: bool) -> anyhow::Result<()> {
    use subsurf::prep::{face_bezier, write_npy, PrepTopology};
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
        crate::say!("quadrangulated (GPU): {} quads", quads.num_faces());
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
    crate::say!(
        "p-rep (f32, GPU): {nf} patches, {} perturbed, max valence {}",
        topo.perturbed_faces().len(),
        topo.max_valence()
    );
    if let Some(out) = &args.output {
        let grid = gpu
            .grid(&ctx, args.tess as usize)
            .and_then(|g| gpu.eval_grid(&ctx, &g).and_then(|_| g.download(&ctx)))
            .context("--backend gpu: tessellating")?;
        let tri = Mesh::from_faces(grid.positions.clone(), &grid.triangles);
        write_mesh(out, &tri, Some(&grid.normals))?;
        crate::say!(
            "wrote {}: {} vertices, {} triangles",
            shown(out, true),
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
            let hi = topo.h_index()[f];
            let h: Option<Vec<[f32; 3]>> = (hi != u32::MAX).then(|| {
                (16 * (nf + hi as usize)..16 * (nf + hi as usize) + 16)
                    .map(pt)
                    .collect()
            });
            for b in face_bezier(&g, h.as_deref()) {
                data.extend(b.map(f64::from));
            }
        }
        let mut w = create_output(out)?;
        write_npy(&mut w, &data, &[nf, 6, 6, 3])
            .and_then(|_| std::io::Write::flush(&mut w))
            .with_context(|| format!("writing {}", shown(out, true)))?;
        crate::say!("wrote {}: ({nf}, 6, 6, 3) float64", shown(out, true));
    }
    Ok(())
}
