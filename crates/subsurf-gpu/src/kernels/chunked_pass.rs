//! Compute passes chunked over items, shared by the p-rep kernels.
//!
//! A pass runs one entry point over `item_count` items (vertices, faces, grid vertices, grid
//! cells) in chunks: a chunk's first item is the `first_item` field of its uniform
//! ([`PrepConfig`]), so no dispatch exceeds `max_compute_workgroups_per_dimension`², and
//! the binding marked [`Bind::PerItem`] (an output written at the item's position in the
//! chunk) is bound from the aligned offset at or before the chunk's first item, which lies
//! `out_shift` words into the binding, so none exceeds `max_storage_buffer_binding_size`.
//! Other bindings are bound whole.

use crate::buffers::{storage_buffer_init, STORAGE_USAGE};
use crate::context::GpuContext;
use crate::error::{GpuError, Result};
use crate::kernels::grid_2d;
use crate::kernels::stencil::ChunkLimits;
use crate::refine::{auto_pipeline, uniform_init};
use crate::shared::PrepConfig;

/// Invocations per workgroup of the p-rep kernels.
pub(crate) const WORKGROUP_SIZE: u32 = 64;
const WORD: u64 = 4;

#[derive(Debug)]
pub(crate) struct Pass {
    pipeline: wgpu::ComputePipeline,
    /// One bind group and workgroup grid per chunk of items.
    pub(crate) dispatches: Vec<(wgpu::BindGroup, (u32, u32))>,
    _configs: Vec<wgpu::Buffer>,
}

/// A binding of a pass: bound whole, or per chunk of items at `words` words per item
/// (an output indexed by the item's position in the chunk), item 0 of the pass being item
/// `base` of the buffer. A pass has at most one `PerItem` binding (its shift is the
/// config's `out_shift`).
#[derive(Clone, Copy)]
pub(crate) enum Bind<'a> {
    Whole(u32, &'a wgpu::Buffer),
    PerItem {
        binding: u32,
        buffer: &'a wgpu::Buffer,
        words: u32,
        base: u64,
    },
}

/// Limits a pass is chunked against, with the binding offset alignment in words.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PassLimits {
    pub(crate) limits: ChunkLimits,
    pub(crate) row_align: usize,
}

pub(crate) fn checked_size(ctx: &GpuContext, what: &'static str, bytes: u64) -> Result<u64> {
    let limit = ctx
        .limits()
        .max_storage_buffer_binding_size
        .min(ctx.limits().max_buffer_size);
    if bytes > limit {
        return Err(GpuError::TooLarge {
            what,
            needed: bytes,
            limit,
        });
    }
    Ok(bytes.max(WORD))
}

/// An uninitialised buffer of `bytes`: bound whole (`whole`), it must fit one binding;
/// bound per chunk, only the adapter's buffer size limits it.
pub(crate) fn empty_storage(
    ctx: &GpuContext,
    what: &'static str,
    bytes: u64,
    whole: bool,
) -> Result<wgpu::Buffer> {
    let size = if whole {
        checked_size(ctx, what, bytes)?
    } else {
        let limit = ctx.limits().max_buffer_size;
        if bytes > limit {
            return Err(GpuError::TooLarge {
                what,
                needed: bytes,
                limit,
            });
        }
        bytes.max(WORD)
    };
    ctx.scoped(|| {
        Ok(ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(what),
            size,
            usage: STORAGE_USAGE | wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::INDEX,
            mapped_at_creation: false,
        }))
    })
}

pub(crate) fn upload_u32(
    ctx: &GpuContext,
    what: &'static str,
    data: &[u32],
) -> Result<wgpu::Buffer> {
    checked_size(ctx, what, data.len() as u64 * WORD)?;
    storage_buffer_init(ctx, what, bytemuck::cast_slice(data))
}

/// Item ranges `[start, end)` of a pass's dispatches: each within the dispatch grid limit,
/// each per-item binding (with up to `row_align` words of lead-in to its aligned start)
/// within the binding limit.
pub(crate) fn chunk_items(
    items: u32,
    words_per_item: u32,
    lim: &PassLimits,
) -> Result<Vec<(u32, u32)>> {
    let max_dispatch =
        u64::from(lim.limits.max_workgroups_per_dimension).pow(2) * u64::from(WORKGROUP_SIZE);
    let mut per = max_dispatch.min(u64::from(u32::MAX));
    if words_per_item > 0 {
        let words = (lim.limits.max_binding_bytes / WORD).saturating_sub(lim.row_align as u64);
        per = per.min(words / u64::from(words_per_item));
    }
    if per == 0 {
        return Err(GpuError::TooLarge {
            what: "one aligned chunk of p-rep items",
            needed: lim.row_align as u64 * u64::from(words_per_item) * WORD,
            limit: lim.limits.max_binding_bytes,
        });
    }
    let per = per as u32;
    Ok((0..items.div_ceil(per))
        .map(|k| (k * per, (k * per).saturating_add(per).min(items)))
        .collect())
}

pub(crate) fn pass(
    ctx: &GpuContext,
    lim: &PassLimits,
    label: &'static str,
    source: &'static str,
    entry: &'static str,
    config: PrepConfig,
    bindings: &[Bind<'_>],
) -> Result<Pass> {
    let per_item = bindings.iter().find_map(|b| match *b {
        Bind::PerItem { words, base, .. } => Some((words, base)),
        Bind::Whole(..) => None,
    });
    let words = per_item.map_or(0, |(w, _)| w);
    let pipeline = auto_pipeline(ctx, label, source, entry)?;
    let layout = pipeline.get_bind_group_layout(0);
    let mut dispatches = Vec::new();
    let mut configs = Vec::new();
    for (start, end) in chunk_items(config.item_count, words, lim)? {
        let n = end - start;
        let (gx, gy) = grid_2d(n, WORKGROUP_SIZE, lim.limits.max_workgroups_per_dimension);
        // The per-item binding's window: from the aligned word at or before the chunk's
        // first item.
        let (offset, shift) = per_item.map_or((0, 0), |(w, base)| {
            let first = (base + u64::from(start)) * u64::from(w);
            let shift = first % lim.row_align as u64;
            ((first - shift) * WORD, shift)
        });
        let chunk_config = PrepConfig {
            item_count: n,
            grid_width: gx * WORKGROUP_SIZE,
            first_item: start,
            out_shift: shift as u32,
            ..config
        };
        let config_buf = uniform_init(ctx, bytemuck::bytes_of(&chunk_config))?;
        let bind_group = ctx.scoped(|| {
            let mut entries = vec![wgpu::BindGroupEntry {
                binding: 0,
                resource: config_buf.as_entire_binding(),
            }];
            entries.extend(bindings.iter().map(|b| match *b {
                Bind::Whole(binding, buf) => wgpu::BindGroupEntry {
                    binding,
                    resource: buf.as_entire_binding(),
                },
                Bind::PerItem {
                    binding,
                    buffer,
                    words,
                    ..
                } => wgpu::BindGroupEntry {
                    binding,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer,
                        offset,
                        size: wgpu::BufferSize::new(
                            (shift + u64::from(n) * u64::from(words)) * WORD,
                        ),
                    }),
                },
            }));
            Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &layout,
                entries: &entries,
            }))
        })?;
        dispatches.push((bind_group, (gx, gy)));
        configs.push(config_buf);
    }
    Ok(Pass {
        pipeline,
        dispatches,
        _configs: configs,
    })
}

pub(crate) fn submit(ctx: &GpuContext, label: &'static str, passes: &[Pass]) -> Result<()> {
    ctx.scoped(|| {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        encode_passes(&mut encoder, label, passes);
        ctx.queue.submit([encoder.finish()]);
        Ok(())
    })
}

/// Records `passes`' dispatches, in order, into one compute pass of `encoder`.
pub(crate) fn encode_passes(
    encoder: &mut wgpu::CommandEncoder,
    label: &'static str,
    passes: &[Pass],
) {
    let mut cp = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: None,
    });
    for p in passes {
        cp.set_pipeline(&p.pipeline);
        for (bind_group, (gx, gy)) in &p.dispatches {
            cp.set_bind_group(0, bind_group, &[]);
            cp.dispatch_workgroups(*gx, *gy, 1);
        }
    }
}
