//! GPU kernels: each uploads its tables once and dispatches the matching WGSL shader.
//!
//! Helpers shared by kernels (pipeline creation, dispatch-grid shape) live here.

pub(crate) mod chunked_pass;
pub mod stencil;

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
