//! `limit_eval` with its random-access inputs (patch map, patch data, control indices, point
//! array) compacted per chunk of samples ([`subsurf_gpu::limit_chunks`]): the chunks' local
//! tables give bit for bit the results of the whole tables, on the CPU twin and on the GPU.

mod common;

use common::{bits, context_or_skip, load};
use subsurf::limit::{PatchOptions, PatchTable};
use subsurf::Topology;
use subsurf_gpu::cpu::limit_eval::{limit_eval, pack_queries, LimitInputs, LimitTables};
use subsurf_gpu::limit::eval_cpu;
use subsurf_gpu::limit_chunks::{plan, PlanLimits};
use subsurf_gpu::shared::LimitConfig;
use subsurf_gpu::{ChunkLimits, GpuLimit};

/// Samples of the tessellation plan plus ptex faces out of range (zeros either way), 1024 of
/// them first so that the first chunks read no point at all.
fn queries(table: &PatchTable, n: usize) -> Vec<(u32, f32, f32)> {
    let roots = table.patch_map().roots().len() as u32;
    let mut q = vec![(roots, 0.5, 0.5); 1024];
    q.extend(table.tessellation_plan(n).unwrap().queries);
    q.insert(q.len() / 2, (roots + 7, 0.5, 0.5));
    q.push((u32::MAX, 0.25, 0.75));
    q
}

#[test]
fn compacted_chunks_reproduce_the_whole_tables_bit_for_bit() {
    for (name, level, max_words) in [
        ("catmark_car", 1, 4096),
        ("catmark_gregory_test1", 3, 2048),
        ("catmark_hole_test1", 2, 1600),
    ] {
        let (mesh, table) = load(name, level);
        let points = table.points(&mesh.positions);
        let q = queries(&table, 4);
        let stride = 12;
        let want = eval_cpu(&table, &points, &q, stride);
        let t = LimitTables::new(&table);
        let words = pack_queries(&q);
        let chunks = plan(
            &t,
            table.cv_offsets(),
            points.len(),
            &words,
            stride,
            PlanLimits {
                max_words,
                max_samples: 1000,
                align: 16,
                compact_points: true,
            },
        )
        .unwrap();
        assert!(chunks.len() > 1, "{name}: {} chunks", chunks.len());
        assert!(chunks
            .iter()
            .any(|c| c.points.is_empty() && c.num_roots == 0));
        let flat = points.as_flattened();
        let mut got = vec![f32::NAN; want.len()];
        let mut next = 0;
        for c in &chunks {
            // Contiguous, aligned, within the limits.
            assert_eq!(c.start, next);
            assert_eq!(c.start % 16, 0);
            next = c.end;
            let n = c.end - c.start;
            assert!(n <= 1000);
            for len in [
                c.patch_map.len(),
                c.patch_info.len(),
                c.cvs.len(),
                3 * c.points.len(),
                n * stride,
            ] {
                assert!(len <= max_words, "{name}: a table of {len} words");
            }
            let local: Vec<f32> = c
                .points
                .iter()
                .flat_map(|&i| flat[3 * i as usize..3 * i as usize + 3].iter().copied())
                .collect();
            let cfg = LimitConfig {
                item_count: n as u32,
                grid_width: n as u32,
                out_stride: stride as u32,
                num_roots: c.num_roots,
            };
            let inp = LimitInputs {
                queries: &c.queries,
                patch_map: &c.patch_map,
                patch_info: &c.patch_info,
                cvs: &c.cvs,
                points: &local,
            };
            limit_eval(&cfg, &inp, &mut got[c.start * stride..c.end * stride]);
        }
        assert_eq!(next, q.len());
        let same = got
            .iter()
            .zip(&want)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(
            same,
            "{name}: compacted chunks differ from the whole tables"
        );
    }
}

#[test]
fn a_block_too_big_for_one_binding_is_a_typed_error() {
    let (mesh, table) = load("catmark_car", 1);
    let q = pack_queries(&queries(&table, 3));
    let r = plan(
        &LimitTables::new(&table),
        table.cv_offsets(),
        table.points(&mesh.positions).len(),
        &q,
        6,
        PlanLimits {
            max_words: 40,
            max_samples: 1000,
            align: 16,
            compact_points: true,
        },
    );
    assert!(
        matches!(r, Err(subsurf_gpu::GpuError::TooLarge { .. })),
        "{r:?}"
    );
}

#[test]
fn gpu_compacted_inputs_match_whole_tables_bit_for_bit() {
    let Some(ctx) = context_or_skip("gpu_compacted_inputs_match_whole_tables_bit_for_bit") else {
        return;
    };
    // A regular torus: 16 control indices per patch, one point per vertex, so the control
    // indices outgrow a binding long before the points do.
    let mesh = subsurf::shapes::torus(24, 24, 1.0, 0.3);
    let table =
        PatchTable::build(&Topology::new(&mesh).unwrap(), &PatchOptions::default()).unwrap();
    let t = LimitTables::new(&table);
    let point_bytes = 12 * table.num_points() as u64;
    // 4 KiB bindings: the patch tables and the point array exceed one binding (points
    // gathered per chunk); then bindings that hold the point array but not the control
    // indices (tables compacted, points bound whole).
    let fit_points = point_bytes.next_multiple_of(256);
    assert!(4 * t.cvs.len() as u64 > fit_points && point_bytes > 1 << 12);
    let mut full = GpuLimit::new(&ctx, &table).unwrap();
    full.update(&ctx, &mesh.positions).unwrap();
    let q = queries(&table, 5);
    let points = table.points(&mesh.positions);
    for binding in [1 << 12, fit_points] {
        let limits = ChunkLimits {
            max_binding_bytes: binding,
            max_workgroups_per_dimension: 1 << 12,
            max_stride: 12,
        };
        let mut small = GpuLimit::with_limits(&ctx, &table, limits).unwrap();
        small.update(&ctx, &mesh.positions).unwrap();
        for derivatives in [false, true] {
            let a = small.samples(&ctx, &q, derivatives).unwrap();
            let b = full.samples(&ctx, &q, derivatives).unwrap();
            assert!(a.inputs_compacted() && !b.inputs_compacted());
            assert!(a.num_dispatches() > 1, "{} dispatches", a.num_dispatches());
            small.eval(&ctx, &a).unwrap();
            full.eval(&ctx, &b).unwrap();
            let (ga, gb) = (a.download(&ctx).unwrap(), b.download(&ctx).unwrap());
            assert!(
                ga.iter().zip(&gb).all(|(x, y)| x.to_bits() == y.to_bits()),
                "{binding}-byte bindings: compacted GPU evaluation differs from the whole tables"
            );
            // And both follow the CPU twin (f32 rounding of the GPU's arithmetic).
            let want = eval_cpu(&table, &points, &q, a.stride);
            let worst = ga
                .iter()
                .zip(&want)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0f32, f32::max);
            assert!(worst < 1e-3, "GPU vs CPU twin: {worst}");
        }
        // A second update moves the points: the compacted chunks follow.
        let moved: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|p| [p[0] + 1.0, p[1], p[2]])
            .collect();
        small.update(&ctx, &moved).unwrap();
        let a = small.samples(&ctx, &q, false).unwrap();
        small.eval(&ctx, &a).unwrap();
        let ga = a.download(&ctx).unwrap();
        let want = eval_cpu(&table, &table.points(&moved), &q, 6);
        let worst = ga
            .iter()
            .zip(&want)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-3, "after update, GPU vs CPU twin: {worst}");
    }
}

/// A point array larger than one binding: the sparse levels' gathers and refinement, the
/// end-cap stencils and the evaluation all split their sources, and `update` and the
/// tessellation are bit for bit those of whole bindings.
#[test]
fn point_array_over_one_binding_matches_whole_bindings() {
    let Some(ctx) = context_or_skip("point_array_over_one_binding_matches_whole_bindings") else {
        return;
    };
    for (name, isolation, binding) in [("catmark_car", 2, 32 << 10), ("catmark_car", 3, 64 << 10)] {
        let (mesh, table) = load(name, isolation);
        let point_bytes = 12 * table.num_points() as u64;
        // Sparse levels, end caps, and points several times the binding.
        assert!(
            !table.level_stencils().is_empty() && table.local_points().num_rows() > 0,
            "{name}"
        );
        assert!(
            point_bytes > 4 * binding,
            "{name}: {point_bytes} bytes of points"
        );
        let limits = ChunkLimits {
            max_binding_bytes: binding,
            max_workgroups_per_dimension: 1 << 12,
            max_stride: 12,
        };
        let mut small = GpuLimit::with_limits(&ctx, &table, limits).unwrap();
        let mut full = GpuLimit::new(&ctx, &table).unwrap();
        small.update(&ctx, &mesh.positions).unwrap();
        full.update(&ctx, &mesh.positions).unwrap();
        let (ps, pf) = (
            small.download_points(&ctx).unwrap(),
            full.download_points(&ctx).unwrap(),
        );
        assert_eq!(
            bits(ps.as_flattened()),
            bits(pf.as_flattened()),
            "{name}: points"
        );
        // And the CPU's points (f32 rounding of the same sums).
        let want = table.points(&mesh.positions);
        let diag = subsurf::mesh::bbox_diagonal(&mesh.positions);
        let worst = ps
            .iter()
            .zip(&want)
            .flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs()))
            .fold(0.0f32, f32::max);
        assert!(worst < 1e-5 * diag, "{name}: points vs CPU {worst}");
        let ts = small.tessellation(&ctx, &table, 5).unwrap();
        let tf = full.tessellation(&ctx, &table, 5).unwrap();
        small.eval(&ctx, &ts.samples).unwrap();
        full.eval(&ctx, &tf.samples).unwrap();
        let (gs, gf) = (
            ts.samples.download(&ctx).unwrap(),
            tf.samples.download(&ctx).unwrap(),
        );
        assert!(gs.iter().all(|x| x.is_finite()), "{name}: NaN");
        assert_eq!(bits(&gs), bits(&gf), "{name}: tessellation");
    }
}
