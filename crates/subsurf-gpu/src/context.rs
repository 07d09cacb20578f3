//! Adapter and device selection.
//!
//! Backends come from `WGPU_BACKEND` (e.g. `vulkan`, `metal`, `dx12`, `gl`) when set. When
//! it is not set the primary backends (Vulkan, Metal, DX12) are tried first and OpenGL only
//! as a fallback, so that a headless machine does not probe EGL when Vulkan (for example
//! Mesa's lavapipe) is present. `SUBSURF_ADAPTER` picks the first adapter whose name
//! contains the given text (case-insensitive); otherwise wgpu's choice for
//! `WGPU_POWER_PREF` (default: high performance) is used.

use crate::error::{GpuError, Result};

/// Environment variable: substring of the adapter name to use.
pub const ADAPTER_ENV: &str = "SUBSURF_ADAPTER";

/// An open device on one adapter, with the adapter's description and limits.
#[derive(Debug)]
pub struct GpuContext {
    /// The wgpu instance the adapter came from.
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: wgpu::Adapter,
    /// The device opened on it.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    limits: wgpu::Limits,
    features: wgpu::Features,
    /// The read-back staging buffer kept between read-backs (see
    /// [`GpuContext::release_staging`]).
    pub(crate) staging: std::sync::Mutex<Option<wgpu::Buffer>>,
    /// Compute pipelines made on this device, one per kernel (see [`GpuContext::kernel`]).
    /// Keyed by shader source and entry point.
    kernels: std::sync::Mutex<
        std::collections::HashMap<(&'static str, &'static str), wgpu::ComputePipeline>,
    >,
}

impl GpuContext {
    /// Opens a device on the adapter chosen as described in the module documentation,
    /// requesting the adapter's best limits and `SHADER_F64` when the adapter has it.
    pub fn new() -> Result<Self> {
        pollster::block_on(Self::new_async())
    }

    async fn new_async() -> Result<Self> {
        crate::headless::quiet_once();
        let from_env = wgpu::Backends::from_env();
        let attempts: Vec<wgpu::Backends> = match from_env {
            Some(b) => vec![b],
            None => vec![wgpu::Backends::PRIMARY, wgpu::Backends::GL],
        };
        let filter = std::env::var(ADAPTER_ENV).ok().filter(|s| !s.is_empty());
        let mut tried = Vec::new();
        for backends in attempts {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle().with_env();
            desc.backends = backends;
            let instance = wgpu::Instance::new(desc);
            match pick_adapter(&instance, backends, filter.as_deref()).await {
                Ok(adapter) => return Self::open(instance, adapter).await,
                Err(seen) => tried.push(format!("backends {backends:?}: {seen}")),
            }
        }
        let filter_note = filter
            .map(|f| format!(" matching {ADAPTER_ENV}={f:?}"))
            .unwrap_or_default();
        Err(GpuError::NoAdapter {
            detail: format!("{filter_note} (tried {})", tried.join("; ")),
        })
    }

    async fn open(instance: wgpu::Instance, adapter: wgpu::Adapter) -> Result<Self> {
        let info = adapter.get_info();
        let required_features = adapter.features() & wgpu::Features::SHADER_F64;
        let desc = wgpu::DeviceDescriptor {
            label: Some("subsurf"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) =
            adapter
                .request_device(&desc)
                .await
                .map_err(|source| GpuError::RequestDevice {
                    adapter: info.name.clone(),
                    source,
                })?;
        let limits = device.limits();
        let features = device.features();
        Ok(Self {
            instance,
            adapter,
            device,
            queue,
            info,
            limits,
            features,
            staging: std::sync::Mutex::new(None),
            kernels: Default::default(),
        })
    }

    /// The compute pipeline of the kernel `source` / `entry`, made by `make` inside an error
    /// scope on first use and kept for the device's life: compiling a shader costs
    /// milliseconds (tens on a software adapter), and every upload of tables (a patch table's
    /// levels, a crease edit's re-uploaded level, each stencil kernel) used to compile its
    /// kernel again. Wgpu pipelines are shared handles, so every user binds groups made
    /// from the same layout (`get_bind_group_layout`). A pipeline that failed is not kept.
    pub(crate) fn kernel(
        &self,
        source: &'static str,
        entry: &'static str,
        make: impl FnOnce() -> wgpu::ComputePipeline,
    ) -> Result<wgpu::ComputePipeline> {
        let mut kernels = self
            .kernels
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let key = (source, entry);
        if let Some(k) = kernels.get(&key) {
            return Ok(k.clone());
        }
        let k = self.scoped(|| Ok(make()))?;
        kernels.insert(key, k.clone());
        Ok(k)
    }

    /// Frees the host-visible staging buffer that read-backs keep between calls (up to
    /// [`crate::buffers::KEEP_STAGING_MAX`] bytes, the size of the largest read so far), for
    /// a program that has finished reading results back; the next read-back allocates one
    /// again.
    pub fn release_staging(&self) {
        *self
            .staging
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner) = None;
    }

    /// The adapter's description (name, backend, driver).
    pub fn adapter_info(&self) -> &wgpu::AdapterInfo {
        &self.info
    }

    /// The limits of the opened device.
    pub fn limits(&self) -> &wgpu::Limits {
        &self.limits
    }

    /// Whether shaders may use `f64`.
    pub fn has_f64(&self) -> bool {
        self.features.contains(wgpu::Features::SHADER_F64)
    }

    /// A human-readable summary: adapter, backend, driver and the limits that bound the
    /// kernels' chunking.
    pub fn gpu_info(&self) -> String {
        let i = &self.info;
        let l = &self.limits;
        let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
        format!(
            "adapter: {}\n\
             device type: {:?}\n\
             backend: {}\n\
             driver: {} ({})\n\
             vendor/device id: {:#06x}/{:#06x}\n\
             shader f64: {}\n\
             max_storage_buffer_binding_size: {} ({:.0} MiB)\n\
             max_buffer_size: {} ({:.0} MiB)\n\
             max_storage_buffers_per_shader_stage: {}\n\
             min_storage_buffer_offset_alignment: {}\n\
             max_compute_workgroup_size_x: {}\n\
             max_compute_invocations_per_workgroup: {}\n\
             max_compute_workgroups_per_dimension: {}",
            i.name,
            i.device_type,
            i.backend,
            i.driver,
            i.driver_info,
            i.vendor,
            i.device,
            if self.has_f64() { "yes" } else { "no" },
            l.max_storage_buffer_binding_size,
            mib(l.max_storage_buffer_binding_size),
            l.max_buffer_size,
            mib(l.max_buffer_size),
            l.max_storage_buffers_per_shader_stage,
            l.min_storage_buffer_offset_alignment,
            l.max_compute_workgroup_size_x,
            l.max_compute_invocations_per_workgroup,
            l.max_compute_workgroups_per_dimension,
        )
    }

    /// Runs `f` inside a wgpu error scope and turns any validation, out-of-memory or
    /// internal error it raised into [`GpuError::Wgpu`] instead of wgpu's default panic.
    pub fn scoped<T>(&self, f: impl FnOnce() -> Result<T>) -> Result<T> {
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let out = f();
        let errors = [
            pollster::block_on(validation.pop()),
            pollster::block_on(internal.pop()),
            pollster::block_on(oom.pop()),
        ];
        if let Some(e) = errors.into_iter().flatten().next() {
            return Err(GpuError::Wgpu(e.to_string()));
        }
        out
    }

    /// Blocks until the queue has finished all submitted work.
    pub fn wait_idle(&self) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| GpuError::Wgpu(e.to_string()))
    }
}

/// Lists the adapters visible with the given backends, as `name (backend, type)` lines.
pub fn list_adapters() -> Vec<String> {
    crate::headless::quiet_once();
    let backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all());
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle().with_env();
    desc.backends = backends;
    let instance = wgpu::Instance::new(desc);
    pollster::block_on(instance.enumerate_adapters(backends))
        .iter()
        .map(|a| {
            let i = a.get_info();
            format!(
                "{} ({}, {:?}, driver {})",
                i.name, i.backend, i.device_type, i.driver
            )
        })
        .collect()
}

/// Picks an adapter: the first whose name contains `filter`, else wgpu's default choice.
/// On failure returns a description of what was seen.
async fn pick_adapter(
    instance: &wgpu::Instance,
    backends: wgpu::Backends,
    filter: Option<&str>,
) -> std::result::Result<wgpu::Adapter, String> {
    match filter {
        Some(f) => {
            let needle = f.to_lowercase();
            let adapters = instance.enumerate_adapters(backends).await;
            let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
            adapters
                .into_iter()
                .find(|a| a.get_info().name.to_lowercase().contains(&needle))
                .ok_or_else(|| format!("adapters seen: {names:?}"))
        }
        None => {
            let options = wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::from_env()
                    .unwrap_or(wgpu::PowerPreference::HighPerformance),
                ..Default::default()
            };
            instance
                .request_adapter(&options)
                .await
                .map_err(|e| e.to_string())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::GpuContext;
    use crate::{GpuRefiner, StencilKernel};
    use subsurf::{shapes, Refiner, Topology};

    /// Two refiners and two stencil applications on one device compile two kernels, not
    /// four, and the shared pipelines still give each job its own result.
    #[test]
    fn kernels_compile_once_per_device() {
        let ctx = match GpuContext::new() {
            Ok(c) => c,
            Err(e) if std::env::var("SUBSURF_SKIP_GPU").as_deref() == Ok("1") => {
                eprintln!("SKIPPED kernels_compile_once_per_device: {e}");
                return;
            }
            Err(e) => panic!("{e}"),
        };
        let count = || ctx.kernels.lock().map(|k| k.len()).unwrap_or(usize::MAX);
        assert_eq!(count(), 0);
        let cube = shapes::cube();
        let r2 = Refiner::new(Topology::new(&cube).unwrap(), 2).unwrap();
        let r1 = Refiner::new(Topology::new(&cube).unwrap(), 1).unwrap();
        let a = GpuRefiner::new(&ctx, &r2).unwrap();
        let b = GpuRefiner::new(&ctx, &r1).unwrap();
        assert_eq!(count(), 1);
        let (pa, pb) = (
            a.refine(&ctx, &cube.positions).unwrap(),
            b.refine(&ctx, &cube.positions).unwrap(),
        );
        assert_eq!(pa.len(), r2.last().num_vertices());
        assert_eq!(pb.len(), r1.last().num_vertices());
        for _ in 0..2 {
            let limit = StencilKernel::apply_once(&ctx, r2.limit_table(), a.output()).unwrap();
            assert_eq!(limit.len(), 3 * r2.last().num_vertices());
        }
        assert_eq!(count(), 2);
    }
}
