//! Per-chunk compacted inputs of `limit_eval`, for patch tables and point arrays larger than
//! one storage binding.
//!
//! The kernel reads its inputs at arbitrary indices: the sample's ptex face selects a root of
//! the patch map, the quadtree leads to a patch, the patch to its control indices and those to
//! points. A chunk of samples reads only the sub-trees of the ptex faces it samples. For each
//! chunk, at upload time, [`plan`] copies exactly that part of the tables into chunk-local
//! tables with local indices:
//!
//! ```text
//! queries     ptex f            → local root  r(f)   (ptex out of range → EMPTY: zeros, as before)
//! patch_map   [roots | nodes]   → [r(f)… | the nodes of their sub-trees, renumbered]
//! patch_info  first cv          → offset into the local cvs
//! cvs         point i           → local point l(i); `points[l]` = i (the gather list)
//! ```
//!
//! When the flat point array itself exceeds one binding, the chunks' points are gathered per
//! frame into a scratch buffer (one unit-weight `stencil_apply` for all chunks, exact), so
//! every binding of a chunk holds only what the chunk reads; otherwise the control indices
//! keep their flat indices and the point array is bound whole (no per-frame cost: the usual
//! case, since a regular patch has 16 control indices but about one point of its own). The kernel does the same arithmetic on the same values, so the results are bit
//! for bit those of the unchunked tables. Chunks grow by blocks of `align` samples (their
//! starts stay aligned for the output binding) while every local table fits `max_words`.

use crate::buffers::{storage_buffer_init, VertexBuffer};
use crate::context::GpuContext;
use crate::cpu::limit_eval::{LimitTables, PATCH_WORDS, QUERY_WORDS, WORKGROUP_SIZE};
use crate::error::{GpuError, Result};
use crate::kernels::grid_2d;
use crate::kernels::stencil::{ChunkLimits, StencilKernel};
use crate::refine::uniform_init;
use crate::shared::LimitConfig;
use crate::table::StencilTable;

const EMPTY: u32 = u32::MAX;
const LEAF: u32 = 1 << 31;

/// The compacted inputs of samples `start..end`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ChunkInputs {
    /// First sample.
    pub start: usize,
    /// One past the last sample.
    pub end: usize,
    /// Local roots (the ptex faces sampled by the chunk).
    pub num_roots: u32,
    /// `[local roots | local nodes]`, handles renumbered.
    pub patch_map: Vec<u32>,
    /// [`PATCH_WORDS`] per local patch, first cv local.
    pub patch_info: Vec<u32>,
    /// Control indices into the local points.
    pub cvs: Vec<u32>,
    /// Flat point index of each local point (the gather list).
    pub points: Vec<u32>,
    /// [`QUERY_WORDS`] per sample, ptex local.
    pub queries: Vec<u32>,
}

/// The global tables and the `global → local` maps of the chunk being built.
struct Builder<'a> {
    t: &'a LimitTables,
    compact_points: bool,
    cv_offsets: &'a [u32],
    root_local: Vec<u32>,
    patch_local: Vec<u32>,
    point_local: Vec<u32>,
    roots: Vec<u32>,
    handles: Vec<u32>,
    nodes: Vec<u32>,
    patches: Vec<u32>,
    patch_info: Vec<u32>,
    cvs: Vec<u32>,
    points: Vec<u32>,
    queries: Vec<u32>,
}

type Mark = [usize; 8];

impl<'a> Builder<'a> {
    fn new(
        t: &'a LimitTables,
        cv_offsets: &'a [u32],
        num_points: usize,
        compact_points: bool,
    ) -> Self {
        Self {
            t,
            compact_points,
            cv_offsets,
            root_local: vec![EMPTY; t.num_roots as usize],
            patch_local: vec![EMPTY; cv_offsets.len().saturating_sub(1)],
            point_local: vec![EMPTY; num_points],
            roots: Vec::new(),
            handles: Vec::new(),
            nodes: Vec::new(),
            patches: Vec::new(),
            patch_info: Vec::new(),
            cvs: Vec::new(),
            points: Vec::new(),
            queries: Vec::new(),
        }
    }

    fn mark(&self) -> Mark {
        [
            self.roots.len(),
            self.handles.len(),
            self.nodes.len(),
            self.patches.len(),
            self.patch_info.len(),
            self.cvs.len(),
            self.points.len(),
            self.queries.len(),
        ]
    }

    /// Forgets everything added since `m`.
    fn rollback(&mut self, m: Mark) {
        for &g in &self.roots[m[0]..] {
            self.root_local[g as usize] = EMPTY;
        }
        for &p in &self.patches[m[3]..] {
            self.patch_local[p as usize] = EMPTY;
        }
        for &i in &self.points[m[6]..] {
            self.point_local[i as usize] = EMPTY;
        }
        self.roots.truncate(m[0]);
        self.handles.truncate(m[1]);
        self.nodes.truncate(m[2]);
        self.patches.truncate(m[3]);
        self.patch_info.truncate(m[4]);
        self.cvs.truncate(m[5]);
        self.points.truncate(m[6]);
        self.queries.truncate(m[7]);
    }

    /// Largest local table, in words.
    fn max_words(&self, samples: usize, stride: usize) -> usize {
        [
            self.handles.len() + self.nodes.len(),
            self.patch_info.len(),
            self.cvs.len(),
            3 * self.points.len(),
            QUERY_WORDS * samples,
            stride * samples,
        ]
        .into_iter()
        .max()
        .unwrap_or(0)
    }

    fn point(&mut self, i: u32) -> Result<u32> {
        let slot = self.point_local.get_mut(i as usize).ok_or_else(|| {
            GpuError::InvalidStencil(format!("control index {i} outside the point array"))
        })?;
        if !self.compact_points {
            return Ok(i);
        }
        if *slot == EMPTY {
            *slot = self.points.len() as u32;
            self.points.push(i);
        }
        Ok(*slot)
    }

    fn patch(&mut self, p: u32) -> Result<u32> {
        let pi = p as usize;
        if pi + 1 >= self.cv_offsets.len() {
            return Err(GpuError::InvalidStencil(format!(
                "patch map names patch {p}"
            )));
        }
        if self.patch_local[pi] != EMPTY {
            return Ok(self.patch_local[pi]);
        }
        let local = self.patches.len() as u32;
        self.patch_local[pi] = local;
        self.patches.push(p);
        let info = &self.t.patch_info[PATCH_WORDS * pi..PATCH_WORDS * (pi + 1)];
        let mut info: [u32; PATCH_WORDS] = info.try_into().expect("PATCH_WORDS words");
        info[1] = self.cvs.len() as u32;
        self.patch_info.extend(info);
        let (a, b) = (
            self.cv_offsets[pi] as usize,
            self.cv_offsets[pi + 1] as usize,
        );
        for k in a..b {
            let l = self.point(self.t.cvs[k])?;
            self.cvs.push(l);
        }
        Ok(local)
    }

    /// The local handle of global handle `h` (sub-tree copied, depth-first).
    fn handle(&mut self, h: u32) -> Result<u32> {
        if h == EMPTY {
            return Ok(EMPTY);
        }
        if h & LEAF != 0 {
            return Ok(LEAF | self.patch(h & !LEAF)?);
        }
        let base = self.t.num_roots as usize + 4 * h as usize;
        if base + 4 > self.t.patch_map.len() {
            return Err(GpuError::InvalidStencil(format!(
                "patch map names node {h}"
            )));
        }
        let local = (self.nodes.len() / 4) as u32;
        self.nodes.extend([EMPTY; 4]);
        for q in 0..4 {
            let child = self.handle(self.t.patch_map[base + q])?;
            self.nodes[4 * local as usize + q] = child;
        }
        Ok(local)
    }

    fn query(&mut self, q: &[u32]) -> Result<()> {
        let f = q[0];
        let local = if f >= self.t.num_roots {
            EMPTY
        } else if self.root_local[f as usize] != EMPTY {
            self.root_local[f as usize]
        } else {
            let local = self.roots.len() as u32;
            self.root_local[f as usize] = local;
            self.roots.push(f);
            let h = self.handle(self.t.patch_map[f as usize])?;
            self.handles.push(h);
            local
        };
        self.queries.extend([local, q[1], q[2]]);
        Ok(())
    }
}

/// What one chunk may hold: words per binding, samples per dispatch, and the alignment of
/// chunk starts in samples.
#[derive(Debug, Clone, Copy)]
pub struct PlanLimits {
    /// Largest binding, in 32-bit words.
    pub max_words: usize,
    /// Largest dispatch, in samples.
    pub max_samples: usize,
    /// Chunk starts are multiples of this many samples.
    pub align: usize,
    /// Whether to compact the points too; if not, control indices stay indices into the
    /// flat point array (bound whole) and [`ChunkInputs::points`] stays empty.
    pub compact_points: bool,
}

/// Chunks of `queries` (packed, [`QUERY_WORDS`] per sample) whose local tables, queries and
/// outputs (`stride` words per sample) each fit `max_words` and whose dispatch fits
/// `max_samples`; starts are multiples of `align` samples.
pub fn plan(
    t: &LimitTables,
    cv_offsets: &[u32],
    num_points: usize,
    queries: &[u32],
    stride: usize,
    lim: PlanLimits,
) -> Result<Vec<ChunkInputs>> {
    let count = queries.len() / QUERY_WORDS;
    let PlanLimits {
        max_words,
        max_samples,
        align,
        compact_points,
    } = lim;
    let align = align.max(1);
    let mut b = Builder::new(t, cv_offsets, num_points, compact_points);
    let mut chunks = Vec::new();
    let mut start = 0;
    let mut end = 0;
    while end < count {
        let block_end = (end + align).min(count);
        let m = b.mark();
        for s in end..block_end {
            b.query(&queries[QUERY_WORDS * s..QUERY_WORDS * (s + 1)])?;
        }
        let n = block_end - start;
        let words = b.max_words(n, stride);
        if words <= max_words && n <= max_samples {
            end = block_end;
            continue;
        }
        b.rollback(m);
        if end == start {
            return Err(GpuError::TooLarge {
                what: "the limit tables read by one aligned block of samples",
                needed: words as u64 * 4,
                limit: max_words as u64 * 4,
            });
        }
        chunks.push(take(&mut b, start, end));
        start = end;
    }
    if end > start || chunks.is_empty() {
        chunks.push(take(&mut b, start, end));
    }
    Ok(chunks)
}

/// Moves the chunk's tables out of `b` and clears its maps.
fn take(b: &mut Builder<'_>, start: usize, end: usize) -> ChunkInputs {
    let mut patch_map = std::mem::take(&mut b.handles);
    patch_map.extend(&b.nodes);
    let chunk = ChunkInputs {
        start,
        end,
        num_roots: b.roots.len() as u32,
        patch_map,
        patch_info: std::mem::take(&mut b.patch_info),
        cvs: std::mem::take(&mut b.cvs),
        points: b.points.clone(),
        queries: std::mem::take(&mut b.queries),
    };
    b.rollback([0; 8]);
    chunk
}

/// The GPU side of one chunked sample set: per chunk a bind group and grid, the buffers they
/// bind, and one gather of every chunk's points into a scratch buffer (chunk `c`'s points
/// from an aligned row, bound there).
pub(crate) struct ChunkedSet {
    pub(crate) dispatches: Vec<(wgpu::BindGroup, (u32, u32))>,
    pub(crate) buffers: Vec<wgpu::Buffer>,
    pub(crate) gather: Option<(StencilKernel, VertexBuffer)>,
}

/// Uploads the chunks of `plan` and creates their bind groups for `limit_eval`
/// (`layout`), the output bound at each chunk's first sample; chunk scratch rows start at
/// multiples of `align` points.
pub(crate) fn upload(
    ctx: &GpuContext,
    layout: &wgpu::BindGroupLayout,
    limits: ChunkLimits,
    chunks: &[ChunkInputs],
    stride: usize,
    align: usize,
    output: &wgpu::Buffer,
    whole_points: Option<&wgpu::Buffer>,
) -> Result<ChunkedSet> {
    // One unit-weight gather (exact): row base_c + l copies flat point chunks[c].points[l];
    // padding rows are empty (zero).
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    let mut bases = Vec::with_capacity(chunks.len());
    for c in chunks {
        while (offsets.len() - 1) % align.max(1) != 0 {
            offsets.push(indices.len() as u32);
        }
        bases.push(offsets.len() - 1);
        for &i in &c.points {
            indices.push(i);
            offsets.push(indices.len() as u32);
        }
    }
    let rows = offsets.len() - 1;
    let weights = vec![1.0f32; indices.len()];
    let scratch = VertexBuffer::zeroed(ctx, rows.max(1), 3)?;
    let gather = if rows == 0 {
        None
    } else {
        Some(StencilKernel::with_limits(
            ctx,
            &StencilTable::new(&offsets, &indices, &weights)?,
            ChunkLimits {
                max_stride: 3,
                ..limits
            },
        )?)
    };
    let mut set = ChunkedSet {
        dispatches: Vec::with_capacity(chunks.len()),
        buffers: Vec::new(),
        gather: None,
    };
    for (c, &base) in chunks.iter().zip(&bases) {
        let n = (c.end - c.start) as u32;
        let (gx, gy) = grid_2d(n, WORKGROUP_SIZE, limits.max_workgroups_per_dimension);
        let config = LimitConfig {
            item_count: n,
            grid_width: gx * WORKGROUP_SIZE,
            out_stride: stride as u32,
            num_roots: c.num_roots,
        };
        let config = uniform_init(ctx, bytemuck::bytes_of(&config))?;
        let up = |what, words: &[u32]| {
            let zero = [0u32];
            let words = if words.is_empty() { &zero[..] } else { words };
            storage_buffer_init(ctx, what, bytemuck::cast_slice(words))
        };
        let queries = up("limit chunk queries", &c.queries)?;
        let patch_map = up("limit chunk patch map", &c.patch_map)?;
        let patch_info = up("limit chunk patch data", &c.patch_info)?;
        let cvs = up("limit chunk control indices", &c.cvs)?;
        let range = |buffer, first: usize, count: usize, words: usize| {
            wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: (first * words) as u64 * 4,
                size: wgpu::BufferSize::new((count.max(1) * words) as u64 * 4),
            })
        };
        let bind_group = ctx.scoped(|| {
            let entry = |binding, resource| wgpu::BindGroupEntry { binding, resource };
            Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("limit_eval chunk"),
                layout,
                entries: &[
                    entry(0, config.as_entire_binding()),
                    entry(1, queries.as_entire_binding()),
                    entry(2, patch_map.as_entire_binding()),
                    entry(3, patch_info.as_entire_binding()),
                    entry(4, cvs.as_entire_binding()),
                    entry(
                        5,
                        // A chunk reading no point (only holes or ptex faces out of
                        // range) binds the first row, unread.
                        match whole_points {
                            Some(points) => points.as_entire_binding(),
                            None => range(
                                scratch.raw(),
                                if c.points.is_empty() { 0 } else { base },
                                c.points.len(),
                                3,
                            ),
                        },
                    ),
                    entry(6, range(output, c.start, n as usize, stride)),
                ],
            }))
        })?;
        set.dispatches.push((bind_group, (gx, gy)));
        set.buffers
            .extend([config, queries, patch_map, patch_info, cvs]);
    }
    set.gather = gather.map(|g| (g, scratch));
    Ok(set)
}
