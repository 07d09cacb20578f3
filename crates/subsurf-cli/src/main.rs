//! The `subsurf` command-line tool.

<<<<<<< HEAD
use clap::{Parser, Subcommand};

mod cmd_prep;

#[derive(Parser, Debug)]
#[command(name = "subsurf", version, about = "Subdivision surfaces in pure Rust")]
=======
mod cmd_bench;
mod cmd_info;
mod cmd_refine;
mod common;

use clap::{Parser, Subcommand};

/// Subdivision surfaces: Catmull-Clark refinement, limit surfaces and p-rep conversion.
#[derive(Debug, Parser)]
#[command(name = "subsurf", version, about)]
>>>>>>> main
struct Cli {
    #[command(subcommand)]
    command: Command,
}

<<<<<<< HEAD
#[derive(Subcommand, Debug)]
enum Command {
    /// Convert a closed quad mesh to a G1 p-rep surface (Myles, Yeo & Peters 2008).
    Prep(cmd_prep::PrepArgs),
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Prep(a) => cmd_prep::run(&a),
=======
#[derive(Debug, Subcommand)]
enum Command {
    /// Print counts, histograms and features of a mesh.
    Info(cmd_info::InfoArgs),
    /// Refine a mesh uniformly (Catmull-Clark or bilinear).
    Refine(cmd_refine::RefineArgs),
    /// Time refinement on a mesh.
    Bench(cmd_bench::BenchArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Info(a) => cmd_info::run(a),
        Command::Refine(a) => cmd_refine::run(a),
        Command::Bench(a) => cmd_bench::run(a),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        for cause in e.chain().skip(1) {
            eprintln!("  caused by: {cause}");
        }
        std::process::exit(1);
>>>>>>> main
    }
}
