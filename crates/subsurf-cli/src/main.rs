//! The `subsurf` command-line tool.

#![warn(missing_docs)]
mod cmd_bench;
mod cmd_compare;
mod cmd_eval;
mod cmd_gpu_info;
mod cmd_info;
mod cmd_limit;
mod cmd_prep;
mod cmd_refine;
mod cmd_render;
mod common;
mod progress;
mod render_limit;
mod render_mesh;

use clap::{Parser, Subcommand};

/// mimalloc keeps freed pages for reuse instead of handing them back to the kernel, which saves
/// the page faults that otherwise dominate refinement of large meshes.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Subdivision surfaces: Catmull-Clark refinement, limit surfaces and p-rep conversion.
#[derive(Debug, Parser)]
#[command(name = "subsurf", version, about)]
struct Cli {
    /// No progress output or notes on stderr.
    #[arg(short, long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print counts, histograms and features of a mesh.
    Info(cmd_info::InfoArgs),
    /// Refine a mesh uniformly (Catmull-Clark or bilinear).
    Refine(cmd_refine::RefineArgs),
    /// Time refinement on a mesh.
    Bench(cmd_bench::BenchArgs),
    /// Render a surface to PNG (headless GPU).
    Render(cmd_render::RenderArgs),
    /// Render two surfaces side by side.
    Compare(cmd_compare::CompareArgs),
    /// Convert a closed quad mesh to a G1 p-rep surface (Myles, Yeo & Peters 2008).
    Prep(cmd_prep::PrepArgs),
    /// Describe the GPU adapter and its limits (SUBSURF_ADAPTER, WGPU_BACKEND respected).
    GpuInfo(cmd_gpu_info::GpuInfoArgs),
    /// Tessellate the limit surface (watertight, with normals).
    Limit(cmd_limit::LimitArgs),
    /// Sample limit positions and derivatives on every ptex face.
    Eval(cmd_eval::EvalArgs),
}

fn main() {
    let cli = Cli::parse();
    progress::set_quiet(cli.quiet);
    let result = match &cli.command {
        Command::Info(a) => cmd_info::run(a),
        Command::Refine(a) => cmd_refine::run(a),
        Command::Bench(a) => cmd_bench::run(a),
        Command::Render(a) => cmd_render::run(a),
        Command::Compare(a) => cmd_compare::run(a),
        Command::Prep(a) => cmd_prep::run(a),
        Command::GpuInfo(a) => cmd_gpu_info::run(a),
        Command::Limit(a) => cmd_limit::run(a),
        Command::Eval(a) => cmd_eval::run(a),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        for cause in e.chain().skip(1) {
            eprintln!("  caused by: {cause}");
        }
        std::process::exit(1);
    }
}
