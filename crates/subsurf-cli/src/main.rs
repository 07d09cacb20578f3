//! The `subsurf` command-line tool.

use clap::{Parser, Subcommand};

mod cmd_prep;

#[derive(Parser, Debug)]
#[command(name = "subsurf", version, about = "Subdivision surfaces in pure Rust")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Convert a closed quad mesh to a G1 p-rep surface (Myles, Yeo & Peters 2008).
    Prep(cmd_prep::PrepArgs),
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Prep(a) => cmd_prep::run(&a),
    }
}
