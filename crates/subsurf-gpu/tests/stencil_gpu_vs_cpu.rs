//! `stencil_apply` on the GPU against its CPU twin.

mod common;

use common::{assert_close_to_twin, bits, context_or_skip, random_table, random_values, Rng};
use subsurf_gpu::cpu::stencil_apply::apply_stencil_table;
use subsurf_gpu::{ChunkLimits, GpuError, StencilKernel, StencilTable, VertexBuffer};

fn run_gpu(
    ctx: &subsurf_gpu::GpuContext,
    kernel: &StencilKernel,
    src: &[f32],
    stride: usize,
) -> Vec<f32> {
    let src_buf = VertexBuffer::upload(ctx, src, stride).unwrap();
    let mut dst_buf = VertexBuffer::zeroed(ctx, kernel.rows(), stride).unwrap();
    kernel.apply(ctx, &src_buf, &mut dst_buf).unwrap();
    dst_buf.download(ctx).unwrap()
}

#[test]
fn random_tables_match_cpu_twin() {
    let Some(ctx) = context_or_skip("random_tables_match_cpu_twin") else {
        return;
    };
    let mut rng = Rng::new(0x5EED);
    for (case, &(rows, sources, max_len, stride, magnitude)) in [
        (1usize, 1u32, 1u32, 3usize, 1.0f32),
        (63, 10, 4, 3, 1.0),
        (1000, 300, 12, 3, 100.0),
        (777, 50, 30, 2, 1e-3),
        (500, 64, 8, 1, 1e4),
        (300, 40, 9, 4, 1.0),
        (257, 40, 9, 7, 1.0),
    ]
    .iter()
    .enumerate()
    {
        let t = random_table(&mut rng, rows, sources, max_len);
        let src = random_values(&mut rng, sources as usize * stride, magnitude);
        let table = StencilTable::new(&t.offsets, &t.indices, &t.weights).unwrap();
        let cpu = apply_stencil_table(&table, &src, stride).unwrap();
        let kernel = StencilKernel::new(&ctx, &t.offsets, &t.indices, &t.weights).unwrap();
        assert_eq!(
            kernel.num_chunks(),
            1,
            "case {case}: small table in one chunk"
        );
        let gpu = run_gpu(&ctx, &kernel, &src, stride);
        assert_close_to_twin(&t, &src, stride, &gpu, &cpu);
    }
}

#[test]
fn exact_stencils_are_exact() {
    // Copies, dyadic midpoints and empty rows are exact in f32 on any hardware, with or
    // without fused multiply-add: the GPU must reproduce them bit for bit.
    let Some(ctx) = context_or_skip("exact_stencils_are_exact") else {
        return;
    };
    let n = 200u32;
    let mut offsets = vec![0u32];
    let mut indices = Vec::new();
    let mut weights = Vec::new();
    for i in 0..n {
        match i % 3 {
            0 => {
                indices.push(n - 1 - i);
                weights.push(1.0);
            }
            1 => {
                indices.extend([i, (i * 7) % n]);
                weights.extend([0.5, 0.5]);
            }
            _ => {}
        }
        offsets.push(indices.len() as u32);
    }
    let src: Vec<f32> = (0..n * 3).map(|x| (x as f32) * 0.25 - 40.0).collect();
    let kernel = StencilKernel::new(&ctx, &offsets, &indices, &weights).unwrap();
    let gpu = run_gpu(&ctx, &kernel, &src, 3);
    for i in 0..n as usize {
        let want: [f32; 3] = std::array::from_fn(|k| match i % 3 {
            0 => src[(n as usize - 1 - i) * 3 + k],
            1 => 0.5 * src[i * 3 + k] + 0.5 * src[((i * 7) % n as usize) * 3 + k],
            _ => 0.0,
        });
        assert_eq!(&gpu[i * 3..i * 3 + 3], &want, "row {i}");
    }
}

#[test]
fn big_table_is_chunked_and_matches() {
    let Some(ctx) = context_or_skip("big_table_is_chunked_and_matches") else {
        return;
    };
    let mut rng = Rng::new(42);
    let (rows, sources, stride) = (20_000usize, 5_000u32, 3usize);
    let t = random_table(&mut rng, rows, sources, 16);
    let src = random_values(&mut rng, sources as usize * stride, 10.0);
    let table = StencilTable::new(&t.offsets, &t.indices, &t.weights).unwrap();
    let cpu = apply_stencil_table(&table, &src, stride).unwrap();
    // 16 KiB bindings and at most 3 workgroups per dimension: many chunks, 2D grids.
    let limits = ChunkLimits {
        max_binding_bytes: 16 * 1024,
        max_workgroups_per_dimension: 3,
        max_stride: stride,
    };
    let kernel = StencilKernel::with_limits(&ctx, &table, limits).unwrap();
    assert!(kernel.num_chunks() > 10, "{} chunks", kernel.num_chunks());
    let gpu = run_gpu(&ctx, &kernel, &src, stride);
    assert_close_to_twin(&t, &src, stride, &gpu, &cpu);
}

/// A source larger than one binding is gathered window by window into a scratch buffer:
/// bit for bit what one binding of the whole source gives, for strides in one block of 4 and
/// above it.
#[test]
fn gathered_source_matches_one_binding_bit_for_bit() {
    let Some(ctx) = context_or_skip("gathered_source_matches_one_binding_bit_for_bit") else {
        return;
    };
    let mut rng = Rng::new(0xB16);
    let (rows, sources) = (6_000usize, 50_000u32);
    let t = random_table(&mut rng, rows, sources, 12);
    let table = StencilTable::new(&t.offsets, &t.indices, &t.weights).unwrap();
    let limits = ChunkLimits {
        max_binding_bytes: 256 * 1024,
        max_workgroups_per_dimension: 8,
        max_stride: 7,
    };
    let small = StencilKernel::with_limits(&ctx, &table, limits).unwrap();
    let whole = StencilKernel::with_limits(
        &ctx,
        &table,
        ChunkLimits {
            max_stride: 7,
            ..ChunkLimits::from_context(&ctx)
        },
    )
    .unwrap();
    assert!(small.num_chunks() >= 4, "{} chunks", small.num_chunks());
    assert!(small.gathers_source() && !whole.gathers_source());
    for stride in [3usize, 7] {
        // The source (50,000 vertices) is 2.3-5.3 times the limit.
        assert!(sources as u64 * stride as u64 * 4 > 2 * limits.max_binding_bytes);
        let src = random_values(&mut rng, sources as usize * stride, 10.0);
        let got = run_gpu(&ctx, &small, &src, stride);
        let want = run_gpu(&ctx, &whole, &src, stride);
        assert_eq!(bits(&got), bits(&want), "stride {stride}");
        let cpu = apply_stencil_table(&table, &src, stride).unwrap();
        assert_close_to_twin(&t, &src, stride, &got, &cpu);
    }
    // Gathers were planned for strides up to 7.
    let src = VertexBuffer::upload(&ctx, &vec![0.0; sources as usize * 8], 8).unwrap();
    let mut dst = VertexBuffer::zeroed(&ctx, rows, 8).unwrap();
    assert!(matches!(
        small.apply(&ctx, &src, &mut dst),
        Err(GpuError::TooLarge { .. })
    ));
}

#[test]
fn buffers_are_reused_frame_after_frame() {
    let Some(ctx) = context_or_skip("buffers_are_reused_frame_after_frame") else {
        return;
    };
    let mut rng = Rng::new(7);
    let t = random_table(&mut rng, 400, 100, 8);
    let table = StencilTable::new(&t.offsets, &t.indices, &t.weights).unwrap();
    let kernel = StencilKernel::new(&ctx, &t.offsets, &t.indices, &t.weights).unwrap();
    let first = random_values(&mut rng, 300, 1.0);
    let src_buf = VertexBuffer::upload(&ctx, &first, 3).unwrap();
    let mut dst_buf = VertexBuffer::zeroed(&ctx, 400, 3).unwrap();
    for frame in 0..3 {
        let src = random_values(&mut rng, 300, 1.0 + frame as f32);
        src_buf.write(&ctx, &src).unwrap();
        kernel.apply(&ctx, &src_buf, &mut dst_buf).unwrap();
        let gpu = dst_buf.download(&ctx).unwrap();
        let cpu = apply_stencil_table(&table, &src, 3).unwrap();
        assert_close_to_twin(&t, &src, 3, &gpu, &cpu);
    }
}

#[test]
fn mismatched_buffers_are_rejected() {
    let Some(ctx) = context_or_skip("mismatched_buffers_are_rejected") else {
        return;
    };
    let kernel = StencilKernel::new(&ctx, &[0, 1, 2], &[0, 4], &[1.0, 1.0]).unwrap();
    let src = VertexBuffer::upload(&ctx, &[0.0; 15], 3).unwrap();
    let short_src = VertexBuffer::upload(&ctx, &[0.0; 12], 3).unwrap();
    let mut dst = VertexBuffer::zeroed(&ctx, 2, 3).unwrap();
    let mut wrong_rows = VertexBuffer::zeroed(&ctx, 3, 3).unwrap();
    let mut wrong_stride = VertexBuffer::zeroed(&ctx, 2, 2).unwrap();
    for result in [
        kernel.apply(&ctx, &short_src, &mut dst),
        kernel.apply(&ctx, &src, &mut wrong_rows),
        kernel.apply(&ctx, &src, &mut wrong_stride),
    ] {
        assert!(
            matches!(result, Err(GpuError::BufferMismatch(_))),
            "{result:?}"
        );
    }
    assert!(matches!(
        StencilKernel::new(&ctx, &[0, 2], &[0], &[1.0]),
        Err(GpuError::InvalidStencil(_))
    ));
    assert!(kernel.apply(&ctx, &src, &mut dst).is_ok());
}
