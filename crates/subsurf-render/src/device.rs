//! The GPU device: [`subsurf_gpu::GpuContext`] (adapter from `WGPU_BACKEND` and
//! `SUBSURF_ADAPTER`, no surface), with errors mapped to [`RenderError`].

use crate::RenderError;
pub use subsurf_gpu::GpuContext as Gpu;

/// Opens the device that [`Gpu::new`] picks; a missing adapter is
/// [`RenderError::NoAdapter`], whose message says how to install a software driver
/// (Mesa's lavapipe, `mesa-vulkan-drivers`, with `WGPU_BACKEND=vulkan`).
pub fn open() -> Result<Gpu, RenderError> {
    Gpu::new().map_err(|e| match e {
        subsurf_gpu::GpuError::NoAdapter { .. } => RenderError::NoAdapter(e.to_string()),
        other => RenderError::Device(other.to_string()),
    })
}

/// `name (backend)` of the adapter, for logs.
pub fn describe(gpu: &Gpu) -> String {
    let i = gpu.adapter_info();
    format!("{} ({:?})", i.name, i.backend)
}
