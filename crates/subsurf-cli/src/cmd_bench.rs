//! `subsurf bench`: time the refinement stages on a mesh (medians of repeated runs).

use crate::common::SchemeArgs;
use std::path::PathBuf;
use std::time::Instant;
use subsurf::{Refiner, Topology};

/// Time topology refinement, stencil application and the whole pipeline.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Input mesh.
    pub input: PathBuf,
    /// Refinement level.
    #[arg(short, long, default_value_t = 3)]
    pub level: usize,
    /// Repetitions (the median is printed).
    #[arg(short, long, default_value_t = 7)]
    pub runs: usize,
    #[command(flatten)]
    pub scheme: SchemeArgs,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

pub fn run(a: &BenchArgs) -> anyhow::Result<()> {
    let mesh = a.scheme.read(&a.input)?;
    let base = Topology::new(&mesh)?;
    let runs = a.runs.max(1);
    let mut topo = Vec::new();
    let mut refiner = None;
    for _ in 0..runs {
        let t = Instant::now();
        let r = Refiner::new(base.clone(), a.level)?;
        topo.push(t.elapsed().as_secs_f64() * 1e3);
        refiner = Some(r);
    }
    let refiner = refiner.ok_or_else(|| anyhow::anyhow!("no run"))?;
    let mut pos = Vec::new();
    let mut verts = 0;
    for _ in 0..runs {
        let t = Instant::now();
        let p = refiner.refine_positions(&mesh.positions);
        pos.push(t.elapsed().as_secs_f64() * 1e3);
        verts = p.len();
    }
    println!(
        "{}: level {} -> {} vertices, {} threads: topology+stencils {:.2} ms, positions {:.2} ms (medians of {runs})",
        a.input.display(),
        a.level,
        verts,
        rayon::current_num_threads(),
        median(topo),
        median(pos)
    );
    Ok(())
}
