//! GPU kernels: each uploads its tables once and dispatches the matching WGSL shader.
//!
//! Helpers shared by kernels (pipeline creation, dispatch-grid shape) live here.

pub(crate) mod chunked_pass;
pub mod stencil;

use crate::error::{GpuError, Result};
use stencil::ChunkLimits;

/// Binding `binding` to the whole of `buffer`.
pub(crate) fn whole(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// Binding `binding` to `size` bytes of `buffer` from `offset` (at least one word: empty
/// bindings are invalid).
pub(crate) fn part(
    binding: u32,
    buffer: &wgpu::Buffer,
    offset: u64,
    size: u64,
) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
            buffer,
            offset,
            size: wgpu::BufferSize::new(size.max(4)),
        }),
    }
}

/// The item ranges `[start, end)` of `count` items dispatched in chunks: each chunk binds
/// `words_per_item` words per item within `limits.max_binding_bytes` and dispatches at most
/// `limits.max_workgroups_per_dimension²` workgroups of `workgroup_size`; when there is more
/// than one chunk, starts are multiples of `align` items (so that binding offsets are
/// aligned). [`GpuError::TooLarge`] naming `what` when not even `align` items fit.
pub(crate) fn aligned_chunks(
    count: usize,
    words_per_item: usize,
    limits: &ChunkLimits,
    workgroup_size: u32,
    align: usize,
    what: &'static str,
) -> Result<Vec<(usize, usize)>> {
    let max_words = (limits.max_binding_bytes / 4) as usize;
    let max_dispatch =
        u64::from(limits.max_workgroups_per_dimension).pow(2) * u64::from(workgroup_size);
    let mut per = (max_words / words_per_item.max(1)).min(max_dispatch as usize);
    if count > per {
        per -= per % align.max(1);
    }
    if per == 0 {
        return Err(GpuError::TooLarge {
            what,
            needed: (align * words_per_item) as u64 * 4,
            limit: limits.max_binding_bytes,
        });
    }
    Ok((0..count)
        .step_by(per)
        .map(|s| (s, (s + per).min(count)))
        .collect())
}

/// Records one compute pass of `pipeline` over `chunks` (bind group, workgroup grid) into
/// `encoder`.
pub(crate) fn encode_pass<'a>(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    pipeline: &wgpu::ComputePipeline,
    chunks: impl IntoIterator<Item = (&'a wgpu::BindGroup, (u32, u32))>,
) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: None,
    });
    pass.set_pipeline(pipeline);
    for (bind_group, (gx, gy)) in chunks {
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(gx, gy, 1);
    }
}

/// Workgroup grid covering `invocations` invocations of `workgroup_size` each without
/// exceeding `max_per_dim` workgroups along x or y: returns `(x, y)` workgroup counts.
/// Invocation `(gx, gy)` handles item `gy * x * workgroup_size + gx`.
pub fn grid_2d(invocations: u32, workgroup_size: u32, max_per_dim: u32) -> (u32, u32) {
    let groups = invocations.div_ceil(workgroup_size).max(1);
    let x = groups.min(max_per_dim.max(1));
    (x, groups.div_ceil(x))
}

#[cfg(test)]
mod tests {
    use super::grid_2d;

    #[test]
    fn grid_covers_every_invocation_within_limits() {
        for (n, wg, max) in [
            (1, 64, 65535),
            (64, 64, 65535),
            (65, 64, 1),
            (10_000, 64, 3),
            (1 << 30, 64, 65535),
        ] {
            let (x, y) = grid_2d(n, wg, max);
            assert!(x <= max && x >= 1);
            // Covers n, and the last row of workgroups is needed.
            assert!(u64::from(x) * u64::from(y) * u64::from(wg) >= u64::from(n));
            assert!(u64::from(x) * u64::from(y - 1) * u64::from(wg) < u64::from(n));
        }
    }
}
