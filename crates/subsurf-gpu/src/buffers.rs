//! Vertex data resident on the GPU, and upload / read-back helpers.

use wgpu::util::DeviceExt;

use crate::context::GpuContext;
use crate::error::{GpuError, Result};

/// Size of an f32 or u32 in bytes.
const WORD: u64 = 4;

/// Vertex data on the GPU: `vertex_count * stride` f32, usable as a kernel's source or
/// destination. Reuse it frame after frame: [`VertexBuffer::write`] replaces the contents
/// without reallocating.
#[derive(Debug)]
pub struct VertexBuffer {
    buffer: wgpu::Buffer,
    vertex_count: usize,
    stride: usize,
}

impl VertexBuffer {
    /// Uploads `data` (`stride` floats per vertex).
    pub fn upload(ctx: &GpuContext, data: &[f32], stride: usize) -> Result<Self> {
        let vertex_count = whole_vertices(data.len(), stride)?;
        let buffer = storage_buffer_init(ctx, "subsurf vertices", bytemuck::cast_slice(data))?;
        Ok(Self {
            buffer,
            vertex_count,
            stride,
        })
    }

    /// A zero-filled buffer of `vertex_count` vertices of `stride` floats.
    pub fn zeroed(ctx: &GpuContext, vertex_count: usize, stride: usize) -> Result<Self> {
        if stride == 0 {
            return Err(GpuError::BufferMismatch("stride must be positive".into()));
        }
        let bytes = (vertex_count as u64)
            .checked_mul(stride as u64 * WORD)
            .ok_or_else(|| GpuError::BufferMismatch("vertex buffer size overflows".into()))?;
        check_buffer_size(ctx, "vertex buffer", bytes)?;
        let buffer = ctx.scoped(|| {
            Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("subsurf vertices"),
                size: bytes.max(WORD),
                usage: STORAGE_USAGE,
                mapped_at_creation: false,
            }))
        })?;
        Ok(Self {
            buffer,
            vertex_count,
            stride,
        })
    }

    /// Replaces the contents with `data`, which must have the buffer's exact length.
    pub fn write(&self, ctx: &GpuContext, data: &[f32]) -> Result<()> {
        if data.len() != self.len_floats() {
            return Err(GpuError::BufferMismatch(format!(
                "writing {} floats into a buffer of {}",
                data.len(),
                self.len_floats()
            )));
        }
        if !data.is_empty() {
            ctx.queue
                .write_buffer(&self.buffer, 0, bytemuck::cast_slice(data));
        }
        Ok(())
    }

    /// Reads the contents back (blocks until the GPU has finished the work submitted so far).
    pub fn download(&self, ctx: &GpuContext) -> Result<Vec<f32>> {
        read_back(ctx, &self.buffer, self.len_floats() as u64 * WORD)
    }

    /// Reads the contents back into `out`, which must hold [`Self::len_floats`] floats
    /// (blocks as [`Self::download`]): a caller that reads every frame keeps `out`, and the
    /// context keeps its staging buffer, so nothing is allocated per frame.
    pub fn download_into(&self, ctx: &GpuContext, out: &mut [f32]) -> Result<()> {
        if out.len() != self.len_floats() {
            return Err(GpuError::BufferMismatch(format!(
                "reading {} floats into a buffer of {}",
                self.len_floats(),
                out.len()
            )));
        }
        read_back_into(ctx, &self.buffer, bytemuck::cast_slice_mut(out))
    }

    /// Reads back a buffer of stride 3 (positions) as one `[f32; 3]` per vertex, copied once
    /// from the staging buffer into the result. Another stride is
    /// [`GpuError::BufferMismatch`].
    pub fn download_triples(&self, ctx: &GpuContext) -> Result<Vec<[f32; 3]>> {
        if self.stride != 3 {
            return Err(GpuError::BufferMismatch(format!(
                "reading vertices of stride {} as positions (stride 3)",
                self.stride
            )));
        }
        let mut out = vec![[0.0f32; 3]; self.vertex_count];
        self.download_into(ctx, out.as_flattened_mut())?;
        Ok(out)
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Floats per vertex.
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// Number of floats (`vertex_count * stride`).
    pub fn len_floats(&self) -> usize {
        self.vertex_count * self.stride
    }

    /// The underlying wgpu buffer (at least 4 bytes even when empty).
    pub fn raw(&self) -> &wgpu::Buffer {
        &self.buffer
    }
}

/// Usages of every buffer a kernel binds as storage.
pub(crate) const STORAGE_USAGE: wgpu::BufferUsages = wgpu::BufferUsages::STORAGE
    .union(wgpu::BufferUsages::COPY_DST)
    .union(wgpu::BufferUsages::COPY_SRC);

fn whole_vertices(len: usize, stride: usize) -> Result<usize> {
    if stride == 0 || !len.is_multiple_of(stride) {
        return Err(GpuError::BufferMismatch(format!(
            "{len} floats are not a whole number of vertices of stride {stride}"
        )));
    }
    Ok(len / stride)
}

fn check_buffer_size(ctx: &GpuContext, what: &'static str, bytes: u64) -> Result<()> {
    let limit = ctx.limits().max_buffer_size;
    if bytes > limit {
        return Err(GpuError::TooLarge {
            what,
            needed: bytes,
            limit,
        });
    }
    Ok(())
}

/// A storage buffer holding `bytes`; empty data gives a 4-byte zero buffer, since bindings
/// of size 0 are invalid.
pub(crate) fn storage_buffer_init(
    ctx: &GpuContext,
    label: &'static str,
    bytes: &[u8],
) -> Result<wgpu::Buffer> {
    check_buffer_size(ctx, label, bytes.len() as u64)?;
    let zero = [0u8; WORD as usize];
    let contents = if bytes.is_empty() { &zero[..] } else { bytes };
    ctx.scoped(|| {
        Ok(ctx
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: STORAGE_USAGE,
            }))
    })
}

/// Largest staging buffer a [`GpuContext`] keeps between read-backs (256 MiB); a larger read
/// allocates its own and frees it after.
pub const KEEP_STAGING_MAX: u64 = 256 << 20;

/// The first `bytes` bytes of `buffer` as floats (words), through [`read_back_into`].
pub(crate) fn read_back(ctx: &GpuContext, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<f32>> {
    let mut out = vec![0.0f32; (bytes / WORD) as usize];
    read_back_into(ctx, buffer, bytemuck::cast_slice_mut(&mut out))?;
    Ok(out)
}

/// Copies the first `dst.len()` bytes of `buffer` (a multiple of 4) into `dst`: one copy on
/// the GPU into the context's staging buffer (kept and reused while it is large enough and at
/// most [`KEEP_STAGING_MAX`]; allocating and mapping fresh host-visible memory each time cost
/// more than the copy itself), then one copy from the mapped range into `dst`.
pub(crate) fn read_back_into(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
    dst: &mut [u8],
) -> Result<()> {
    let bytes = dst.len() as u64;
    if bytes == 0 {
        return Ok(());
    }
    let mut kept = ctx
        .staging
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let staging = ctx.scoped(|| {
        let staging = match kept.take() {
            Some(b) if b.size() >= bytes => b,
            _ => ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("subsurf read-back"),
                size: bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("subsurf read-back"),
            });
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, bytes);
        ctx.queue.submit([encoder.finish()]);
        Ok(staging)
    })?;
    let (tx, rx) = std::sync::mpsc::channel();
    let range = staging.slice(..bytes);
    range.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    ctx.wait_idle()?;
    rx.recv()
        .map_err(|e| GpuError::Map(e.to_string()))?
        .map_err(|e| GpuError::Map(e.to_string()))?;
    {
        let view = range
            .get_mapped_range()
            .map_err(|e| GpuError::Map(e.to_string()))?;
        dst.copy_from_slice(&view);
    }
    staging.unmap();
    if staging.size() <= KEEP_STAGING_MAX {
        *kept = Some(staging);
    }
    Ok(())
}

impl VertexBuffer {
    /// A second handle on the same GPU buffer (kernels writing it through either handle
    /// write the same memory; submission order orders them).
    pub(crate) fn alias(&self) -> Self {
        Self {
            buffer: self.buffer.clone(),
            vertex_count: self.vertex_count,
            stride: self.stride,
        }
    }
}
