//! `subsurf eval`: limit positions and first derivatives, one line per sample:
//! `face u v px py pz dux duy duz dvx dvy dvz` (holes write nothing).
//!
//! Catmull-Clark and bilinear: an `N × N` grid of every ptex face (`face` the ptex index,
//! `u, v = i/(N−1)`, `v` the outer loop). Loop (`--scheme loop`, the `loop_` file-name
//! prefix or the file's scheme tag): the triangular grid `u = i/(N−1)`, `v = j/(N−1)`,
//! `i + j ≤ N − 1` of every base triangle (`face` the triangle, `v` the outer loop), the
//! library's Loop limit surface evaluated in double precision (`--backend gpu`: by the GPU's
//! `loop_eval`, in single precision). `--at FILE` evaluates the
//! `face u v` lines of a file instead; a query off the surface's domain (no such face,
//! `u + v > 1` on a triangle, outside `[0, 1]²` on a ptex face) is an error naming it.

use crate::cmd_limit::SurfaceArgs;
use crate::common::{check_output_folder, create_output, gpu_context, shown, Backend};
use anyhow::Context;
use std::fmt::Display;
use std::io::Write;
use std::path::{Path, PathBuf};
use subsurf::limit::LoopLimit;
use subsurf::limit::{check_square, check_triangle};
use subsurf::limit::{LimitPoint, LimitSurface};
use subsurf::{Mesh, Real, Scheme, Topology};

/// Sample the limit surface and its derivatives.
#[derive(Debug, clap::Args)]
pub struct EvalArgs {
    #[command(flatten)]
    pub surface: SurfaceArgs,
    /// Samples per side of each ptex face, or per edge of each Loop triangle (at least 2).
    #[arg(long, alias = "samples", default_value_t = 5)]
    pub tess: usize,
    /// Evaluate at the queries of this text file instead of a grid: one `face u v` per line
    /// (whitespace-separated, `#` starts a comment).
    #[arg(long, conflicts_with = "tess")]
    pub at: Option<PathBuf>,
    /// Output text file (any name; `-` writes standard output).
    #[arg(short, long)]
    pub output: PathBuf,
}

/// One written sample: face, parameters, position, `∂P/∂u`, `∂P/∂v`.
type Row<R> = (u32, R, R, [[R; 3]; 3]);

pub fn run(a: &EvalArgs) -> anyhow::Result<()> {
    check_output_folder(&a.output)?;
    anyhow::ensure!(
        (2..=4096).contains(&a.tess),
        "--tess {} not in 2..=4096",
        a.tess
    );
    let mesh = a.surface.scheme.read(&a.surface.input)?;
    if mesh.options.scheme == Scheme::Loop {
        return run_loop(a, mesh);
    }
    if a.surface.f64 {
        let (mesh, table) = a.surface.table_for::<f64>(mesh)?;
        let queries = queries(a, table.num_ptex_faces())?;
        let surface = LimitSurface::new(table, &mesh.positions);
        let results = surface.eval_batch(&queries);
        let n = surface.table().num_ptex_faces();
        return write_samples(a, rows(&queries, &results), n, "ptex faces");
    }
    let (mesh, table) = a.surface.table_for(mesh)?;
    let queries = queries(a, table.num_ptex_faces())?;
    let results = match a.surface.backend {
        Backend::Cpu => LimitSurface::new(table.clone(), &mesh.positions).eval_batch(&queries),
        Backend::Gpu => {
            // Holes (no patch) are known from the patch map alone: only the rest is sent.
            let found: Vec<bool> = queries
                .iter()
                .map(|&(f, u, v)| table.patch_map().find(f as usize, u, v).is_some())
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
    write_samples(
        a,
        rows(&queries, &results),
        table.num_ptex_faces(),
        "ptex faces",
    )
}

/// `eval` on a Loop mesh: the library's Loop limit surface evaluated in f64 on the CPU (its
/// points refined in f64 from the file's values with `--f64` or where the file holds digits
/// `f32` cannot, as the library's Loop limit method refines them, else in f32), or in f32 by
/// the GPU's `loop_eval` (`--backend gpu`).
fn run_loop(a: &EvalArgs, mesh: Mesh) -> anyhow::Result<()> {
    let topo = Topology::new(&mesh)?;
    let surface = if a.surface.f64 {
        LoopLimit::new_f64(&topo, &mesh.positions, a.surface.isolation)
    } else {
        LoopLimit::at_precision(&topo, &mesh.positions, a.surface.isolation)
    }
    .context("building the Loop limit patches")?;
    let queries: Vec<(u32, f64, f64)> = match &a.at {
        Some(path) => read_queries(path)?,
        None => {
            let n = a.tess;
            let samples = topo.num_faces() as f64 * (n * (n + 1) / 2) as f64;
            check_memory::<f64>(a, samples, "Loop triangles")?;
            let d = (n - 1) as f64;
            let mut q = Vec::with_capacity(topo.num_faces() * n * (n + 1) / 2);
            for f in 0..topo.num_faces() as u32 {
                for j in 0..n {
                    for i in 0..n - j {
                        q.push((f, i as f64 / d, j as f64 / d));
                    }
                }
            }
            q
        }
    };
    let results: Vec<Option<[[f64; 3]; 3]>> = match a.surface.backend {
        Backend::Cpu => surface
            .eval_batch(&queries)
            .with_context(|| query_source(a))?
            .into_iter()
            .map(|r| r.map(|r| [r.p, r.du, r.dv]))
            .collect(),
        Backend::Gpu => loop_eval_gpu(a, &surface, &queries)?,
    };
    let rows = queries
        .iter()
        .zip(&results)
        .filter_map(|(&(f, u, v), r)| r.map(|r| (f, u, v, r)));
    write_samples(a, rows, topo.num_faces(), "Loop triangles")
}

/// The Loop queries (checked as on the CPU) evaluated by `loop_eval`: the patch of each is
/// found with the patch map (holes: none, not sent), position and derivatives widened.
fn loop_eval_gpu(
    a: &EvalArgs,
    surface: &LoopLimit,
    queries: &[(u32, f64, f64)],
) -> anyhow::Result<Vec<Option<[[f64; 3]; 3]>>> {
    for (k, &(f, u, v)) in queries.iter().enumerate() {
        check_triangle(k, f as u64, u, v, surface.num_faces())
            .map_err(subsurf::Error::from)
            .with_context(|| query_source(a))?;
    }
    let patches: Vec<Option<u32>> = queries
        .iter()
        .map(|&(f, u, v)| surface.patch_map.find_triangle(f as usize, u, v))
        .collect();
    let sent: Vec<(u32, f32, f32)> = queries
        .iter()
        .zip(&patches)
        .filter_map(|(&(_, u, v), p)| p.map(|p| (p, u as f32, v as f32)))
        .collect();
    let ctx = gpu_context()?;
    let gpu = subsurf_gpu::GpuLoopLimit::new(&ctx, surface)
        .context("--backend gpu: uploading the Loop patches")?;
    let samples = gpu.samples(&ctx, &sent, true)?;
    gpu.eval(&ctx, &samples)
        .context("--backend gpu: evaluating the samples")?;
    let out = samples
        .download(&ctx)
        .context("--backend gpu: reading the samples back")?;
    let mut points = out.chunks_exact(12).map(|o| {
        let v = |k: usize| [o[k], o[k + 1], o[k + 2]].map(f64::from);
        [v(0), v(6), v(9)]
    });
    Ok(patches
        .iter()
        .map(|p| p.and_then(|_| points.next()))
        .collect())
}

/// Refuses `samples` evaluations in `R` that would pass the memory limit, before the queries
/// are allocated: per sample a query and its result (64 bytes in `f32`, the peak resident
/// memory of `eval` on the car at 200 samples per side), twice that with the GPU path's
/// copies of both.
fn check_memory<R: Real>(a: &EvalArgs, samples: f64, on: &str) -> anyhow::Result<()> {
    let copies = match a.surface.backend {
        Backend::Cpu => 1,
        Backend::Gpu => 2,
    };
    let per = copies
        * (std::mem::size_of::<(u32, R, R)>() + std::mem::size_of::<Option<LimitPoint<R>>>());
    subsurf::budget::check(samples * per as f64, || {
        format!(
            "evaluating {} samples on the {on}",
            subsurf::budget::count(samples)
        )
    })
    .map_err(subsurf::Error::from)?;
    Ok(())
}

/// Where the queries came from, for errors.
fn query_source(a: &EvalArgs) -> String {
    match &a.at {
        Some(p) => format!("--at {}", p.display()),
        None => format!("--tess {}", a.tess),
    }
}

/// The Catmull-Clark queries: the lines of `--at` (checked against the `num_ptex` ptex
/// faces), else `(ptex, i/(n−1), j/(n−1))` for every ptex face, `j` the outer loop.
fn queries<R: Real>(a: &EvalArgs, num_ptex: usize) -> anyhow::Result<Vec<(u32, R, R)>> {
    if let Some(path) = &a.at {
        let q = read_queries(path)?;
        for (k, &(f, u, v)) in q.iter().enumerate() {
            check_square(k, f as u64, u, v, num_ptex)
                .map_err(subsurf::Error::from)
                .with_context(|| query_source(a))?;
        }
        return Ok(q
            .into_iter()
            .map(|(f, u, v)| (f, R::from_f64(u), R::from_f64(v)))
            .collect());
    }
    let n = a.tess;
    check_memory::<R>(a, num_ptex as f64 * (n * n) as f64, "ptex faces")?;
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
    Ok(queries)
}

/// The `face u v` lines of `path` (`#` comments and blank lines skipped).
fn read_queries(path: &Path) -> anyhow::Result<Vec<(u32, f64, f64)>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("reading --at {}", path.display()))?;
    let mut q = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let at = || format!("{}:{}", path.display(), k + 1);
        let w: Vec<&str> = line.split_whitespace().collect();
        anyhow::ensure!(w.len() == 3, "{}: expected `face u v`, got {line:?}", at());
        let face = w[0]
            .parse::<u32>()
            .with_context(|| format!("{}: face {:?} is not an index", at(), w[0]))?;
        let num = |s: &str| {
            s.parse::<f64>()
                .with_context(|| format!("{}: {s:?} is not a number", at()))
        };
        q.push((face, num(w[1])?, num(w[2])?));
    }
    Ok(q)
}

/// The evaluated samples of `queries` as rows (holes dropped).
fn rows<'a, R: Real>(
    queries: &'a [(u32, R, R)],
    results: &'a [Option<LimitPoint<R>>],
) -> impl Iterator<Item = Row<R>> + 'a {
    queries
        .iter()
        .zip(results)
        .filter_map(|(&(f, u, v), r)| r.as_ref().map(|r| (f, u, v, [r.p, r.du, r.dv])))
}

/// One line per sample, values in their shortest round-trip form.
fn write_samples<R: Display>(
    a: &EvalArgs,
    rows: impl Iterator<Item = Row<R>>,
    num_faces: usize,
    faces: &str,
) -> anyhow::Result<()> {
    let mut w = create_output(&a.output)?;
    let mut written = 0usize;
    for (f, u, v, [p, du, dv]) in rows {
        writeln!(
            w,
            "{f} {u} {v} {} {} {} {} {} {} {} {} {}",
            p[0], p[1], p[2], du[0], du[1], du[2], dv[0], dv[1], dv[2]
        )?;
        written += 1;
    }
    w.flush()?;
    crate::say!(
        "{written} samples on {num_faces} {faces} -> {}",
        shown(&a.output, true)
    );
    Ok(())
}
