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
mod limit_loop;
mod progress;
mod tess_args;
mod usd_stage;

use clap::{Parser, Subcommand};

/// mimalloc keeps freed pages for reuse instead of handing them back to the kernel, which saves
/// the page faults that otherwise dominate refinement of large meshes.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Subdivision surfaces: Catmull-Clark refinement, limit surfaces and p-rep conversion.
#[derive(Debug, Parser)]
#[command(name = "subsurf", version, about)]
struct Cli {
    /// Nothing on stderr but errors: no progress, notes or summary lines.
    #[arg(short, long, global = true)]
    quiet: bool,
    /// Format of mesh output written to standard output (`-o -`); input from standard input
    /// (`-`) is PLY when it starts with `ply`, binary glTF with `glTF`, OBJ otherwise.
    #[arg(long, value_enum, global = true, value_name = "obj|ply|glb")]
    format: Option<common::FormatArg>,
    /// Write hole faces into mesh output, tagged (OBJ `t hole`, USD `holeIndices`), so that
    /// refining the file again continues the same surface. Without it hole faces are left out
    /// of every format, as viewers that ignore the tags would draw them closed; PLY and glb
    /// cannot tag them and refuse it.
    #[arg(long, global = true)]
    keep_holes: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print counts, histograms and features of a mesh.
    Info(cmd_info::InfoArgs),
    /// Refine a mesh uniformly (Catmull-Clark, bilinear or Loop).
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

/// Restores the default action of `SIGPIPE` (Rust ignores it), so that a closed pipe
/// (`subsurf info car.obj | head -1`) ends the process quietly, as it ends other Unix tools,
/// instead of a write error or a panic in whatever is printing.
#[cfg(unix)]
#[allow(unsafe_code)]
fn exit_quietly_on_closed_pipe() {
    // SAFETY: called once at start-up, before any thread exists; `signal` with `SIG_DFL`
    // installs no handler code.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

#[cfg(not(unix))]
fn exit_quietly_on_closed_pipe() {}

/// Prints an error and its causes, each cause once: a cause whose text the line above already
/// contains (an I/O error wrapped in a library error, say) is left out.
fn report(e: &anyhow::Error) {
    let mut last = e.to_string();
    eprintln!("error: {last}");
    for cause in e.chain().skip(1) {
        let text = cause.to_string();
        if !last.contains(&text) {
            eprintln!("  caused by: {text}");
        }
        last = text;
    }
}

fn main() {
    exit_quietly_on_closed_pipe();
    // Before any thread exists: keeps Mesa's display layer from printing a Wayland error on
    // machines without a display server.
    subsurf_gpu::headless::disable_display_layers_when_headless();
    let cli = Cli::parse();
    progress::set_quiet(cli.quiet);
    common::set_stdout_format(cli.format);
    common::set_keep_holes(cli.keep_holes);
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
        report(&e);
        std::process::exit(1);
    }
}
