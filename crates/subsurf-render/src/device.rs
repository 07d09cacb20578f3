//! Headless wgpu device: an adapter chosen from `WGPU_BACKEND` (or every backend), no surface.

use crate::RenderError;

/// How to get a GPU adapter on a machine without one.
pub const INSTALL_HINT: &str =
    "no GPU adapter found. On Linux without a GPU install Mesa's software \
Vulkan driver (Debian/Ubuntu: `apt-get install mesa-vulkan-drivers`) and run with \
WGPU_BACKEND=vulkan";

/// A wgpu device and queue with the adapter they came from.
#[derive(Debug)]
pub struct Gpu {
    /// The adapter (kept for format queries).
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// Opens the first adapter the environment allows (`WGPU_BACKEND=vulkan|gl|metal|dx12`),
    /// requesting the adapter's own limits so that large meshes fit in one buffer.
    pub fn new() -> Result<Gpu, RenderError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        }))
        .map_err(|e| RenderError::NoAdapter(format!("{INSTALL_HINT} ({e})")))?;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("subsurf-render"),
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Gpu {
            adapter,
            device,
            queue,
        })
    }

    /// `name (backend)` of the adapter, for logs.
    pub fn describe(&self) -> String {
        let i = self.adapter.get_info();
        format!("{} ({:?})", i.name, i.backend)
    }
}
