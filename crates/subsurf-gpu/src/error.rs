//! Typed errors of the GPU backend.

/// An error of the GPU backend.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter could be created (no GPU and no software driver).
    #[error(
        "no GPU adapter available{detail}. Install a Vulkan driver (on Debian/Ubuntu: \
         `apt-get install mesa-vulkan-drivers` gives the lavapipe software rasterizer), \
         or set SUBSURF_SKIP_GPU=1 to skip GPU tests"
    )]
    NoAdapter {
        /// What was tried (backends, adapter filter, adapters seen).
        detail: String,
    },
    /// The adapter refused to open a device.
    #[error("could not open a device on adapter `{adapter}`: {source}")]
    RequestDevice {
        /// Adapter name.
        adapter: String,
        /// The error reported by wgpu.
        #[source]
        source: wgpu::RequestDeviceError,
    },
    /// A stencil table is malformed.
    #[error("invalid stencil table: {0}")]
    InvalidStencil(String),
    /// Buffers passed to a kernel do not fit it (stride, vertex count).
    #[error("buffer mismatch: {0}")]
    BufferMismatch(String),
    /// Data does not fit the adapter's limits.
    #[error("{what} needs {needed} bytes but the adapter allows {limit}")]
    TooLarge {
        /// Which buffer or binding.
        what: &'static str,
        /// Bytes needed.
        needed: u64,
        /// The adapter's limit in bytes.
        limit: u64,
    },
    /// wgpu reported a validation, out-of-memory or internal error.
    #[error("wgpu error: {0}")]
    Wgpu(String),
    /// The library refused the request (for example a tessellation density out of range).
    #[error(transparent)]
    Library(#[from] subsurf::Error),
    /// Reading a buffer back failed.
    #[error("buffer read-back failed: {0}")]
    Map(String),
}

/// Result alias of the GPU backend.
pub type Result<T> = std::result::Result<T, GpuError>;
