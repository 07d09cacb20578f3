//! `subsurf eval`: limit positions and first derivatives on an `N × N` grid of every ptex
//! face, one line per sample: `face u v px py pz dux duy duz dvx dvy dvz` (`face` the ptex
//! index, `u, v = i/(N−1)`, `v` the outer loop; holes write nothing).

use crate::cmd_limit::SurfaceArgs;
use crate::common::{check_output_folder, create_output, gpu_context, shown, Backend};
use anyhow::Context;
use std::fmt::Display;
use std::io::Write;
use std::path::PathBuf;
use subsurf::limit::{LimitPoint, LimitSurface};
use subsurf::Real;

/// Sample the limit surface and its derivatives.
#[derive(Debug, clap::Args)]
pub struct EvalArgs {
    #[command(flatten)]
    pub surface: SurfaceArgs,
    /// Samples per side of each ptex face (at least 2).
    #[arg(long, default_value_t = 5)]
    pub samples: usize,
    /// Output text file (any name; `-` writes standard output).
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(a: &EvalArgs) -> anyhow::Result<()> {
    check_output_folder(&a.output)?;
    anyhow::ensure!(
        (2..=4096).contains(&a.samples),
        "--samples {} not in 2..=4096",
        a.samples
    );
    if a.surface.f64 {
        let (mesh, table) = a.surface.load_table_real::<f64>()?;
        let queries = grid_queries(table.num_ptex_faces(), a.samples);
        let surface = LimitSurface::new(table, &mesh.positions);
        let results = surface.eval_batch(&queries);
        return write_samples(a, &queries, &results, surface.table.num_ptex_faces());
    }
    let (mesh, table) = a.surface.load_table()?;
    let queries = grid_queries(table.num_ptex_faces(), a.samples);
    let results = match a.surface.backend {
        Backend::Cpu => LimitSurface::new(table.clone(), &mesh.positions).eval_batch(&queries),
        Backend::Gpu => {
            // Holes (no patch) are known from the patch map alone: only the rest is sent.
            let found: Vec<bool> = queries
                .iter()
                .map(|&(f, u, v)| table.patch_map.find(f as usize, u, v).is_some())
                .collect();
            let sent: Vec<(u32, f32, f32)> = queries
                .iter()
                .zip(&found)
                .filter(|(_, &k)| k)
                .map(|(q, _)| *q)
                .collect();
            let ctx = gpu_context()?;
            let gpu = a.surface.upload(&ctx, &mesh, &table)?;
            let samples = gpu.samples(&ctx, &sent, true)?;
            gpu.eval(&ctx, &samples)
                .context("--backend gpu: evaluating the samples")?;
            let mut points = samples
                .download_points(&ctx)
                .context("--backend gpu: reading the samples back")?
                .into_iter();
            found
                .iter()
                .map(|&k| if k { points.next() } else { None })
                .collect::<Vec<Option<LimitPoint>>>()
        }
    };
    write_samples(a, &queries, &results, table.num_ptex_faces())
}

/// `(ptex, i/(n−1), j/(n−1))` for every ptex face, `j` the outer loop.
fn grid_queries<R: Real>(num_ptex: usize, n: usize) -> Vec<(u32, R, R)> {
    let d = R::from_f64((n - 1) as f64);
    let mut queries = Vec::with_capacity(num_ptex * n * n);
    for f in 0..num_ptex as u32 {
        for j in 0..n {
            for i in 0..n {
                let at = |k: usize| R::from_f64(k as f64) / d;
                queries.push((f, at(i), at(j)));
            }
        }
    }
    queries
}

/// One line per sample (holes write nothing), values in their shortest round-trip form.
fn write_samples<R: Real + Display>(
    a: &EvalArgs,
    queries: &[(u32, R, R)],
    results: &[Option<LimitPoint<R>>],
    num_ptex: usize,
) -> anyhow::Result<()> {
    let mut w = create_output(&a.output)?;
    let mut written = 0usize;
    for (&(f, u, v), r) in queries.iter().zip(results) {
        let Some(r) = r else { continue };
        writeln!(
            w,
            "{f} {u} {v} {} {} {} {} {} {} {} {} {}",
            r.p[0], r.p[1], r.p[2], r.du[0], r.du[1], r.du[2], r.dv[0], r.dv[1], r.dv[2]
        )?;
        written += 1;
    }
    w.flush()?;
    crate::say!(
        "{written} samples on {num_ptex} ptex faces -> {}",
        shown(&a.output, true)
    );
    Ok(())
}
