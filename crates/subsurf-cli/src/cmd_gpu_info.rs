//! `subsurf gpu-info`: describe the GPU adapter subsurf would use.

use anyhow::Context as _;

/// Arguments of `subsurf gpu-info`.
#[derive(Debug, clap::Args)]
pub struct GpuInfoArgs {
    /// Also list every adapter visible to wgpu (all backends, or those in WGPU_BACKEND).
    #[arg(long)]
    pub all: bool,
}

/// Prints the chosen adapter (SUBSURF_ADAPTER / WGPU_BACKEND respected), its driver and limits.
pub fn run(args: &GpuInfoArgs) -> anyhow::Result<()> {
    if args.all {
        println!("adapters:");
        for line in subsurf_gpu::context::list_adapters() {
            println!("  {line}");
        }
        println!();
    }
    let ctx = subsurf_gpu::GpuContext::new().context("opening a GPU device")?;
    println!("{}", ctx.gpu_info());
    Ok(())
}
