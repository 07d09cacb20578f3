//! The p-rep kernels (vertex pass, patch pass, watertight grid evaluation) on the GPU against
//! the CPU construction of `subsurf::prep` in f32, and their CPU twins against the library.

mod common;

use common::{bits, context_or_skip};
use subsurf::prep::quadrangulate;
use subsurf::prep::{PrepPatches, PrepTopology, Tessellation};
use subsurf::{Mesh, Topology};
use subsurf_gpu::{ChunkLimits, GpuPrep, PrepChunks, PrepTables};

/// Closed quad meshes: the p-rep test shapes (split into quads where needed) and a cube.
fn meshes() -> Vec<(String, Mesh)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../subsurf/tests/data/prep");
    let mut out = vec![("cube".to_string(), subsurf::shapes::cube())];
    for name in [
        "catmark_lefthanded",
        "catmark_toroidal_tet",
        "catmark_torus",
    ] {
        let m = subsurf::io::read_path(dir.join(format!("{name}.obj"))).unwrap();
        let m = if m.face_counts.iter().all(|&c| c == 4) {
            m
        } else {
            quadrangulate(&m).unwrap()
        };
        out.push((name.to_string(), m));
    }
    out
}

fn bbox_diagonal(p: &[[f32; 3]]) -> f64 {
    subsurf::mesh::bbox_diagonal(p) as f64
}

/// The library's f32 construction as the kernels' flat layouts.
fn cpu_flat(p: &PrepPatches<f32>) -> (Vec<f32>, Vec<f32>) {
    let v = &p.vertex();
    let vd = [&v.limit, &v.e1, &v.e2, &v.tangent, &v.interior]
        .into_iter()
        .flat_map(|a| a.iter().flatten().copied())
        .collect();
    let pd = p.g().iter().chain(p.h()).flatten().copied().collect();
    (vd, pd)
}

fn assert_all_close(what: &str, got: &[f32], want: &[f32], tol: f64) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(g.is_finite(), "{what}[{i}] is {g}");
        let d = (*g as f64 - *w as f64).abs();
        assert!(d <= tol, "{what}[{i}]: {g} vs {w} (|diff| {d:e} > {tol:e})");
    }
}

/// A closed mesh: every triangle edge is used exactly twice, once in each direction.
fn assert_watertight(what: &str, t: &Tessellation<f32>) {
    let mut edges = std::collections::HashMap::new();
    for tri in &t.triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            assert!(
                (a as usize) < t.positions.len(),
                "{what}: index {a} out of range"
            );
            *edges.entry((a, b)).or_insert(0u32) += 1;
        }
    }
    for (&(a, b), &c) in &edges {
        assert_eq!(c, 1, "{what}: directed edge {a}->{b} used {c} times");
        assert_eq!(
            edges.get(&(b, a)),
            Some(&1),
            "{what}: edge {a}-{b} is a crack (no twin)"
        );
    }
}

fn compare_tessellation(what: &str, got: &Tessellation<f32>, want: &Tessellation<f32>, diag: f64) {
    assert_eq!(
        got.triangles, want.triangles,
        "{what}: index buffers differ"
    );
    assert_all_close(
        &format!("{what} positions"),
        got.positions.as_flattened(),
        want.positions.as_flattened(),
        1e-5 * diag,
    );
    assert_all_close(
        &format!("{what} normals"),
        got.normals.as_flattened(),
        want.normals.as_flattened(),
        1e-3,
    );
    assert_watertight(what, got);
}

/// The same tessellation bit for bit: triangles, positions, normals.
fn assert_same_bits(what: &str, got: &Tessellation<f32>, want: &Tessellation<f32>) {
    assert_eq!(got.triangles, want.triangles, "{what}: triangles");
    assert_eq!(
        bits(got.positions.as_flattened()),
        bits(want.positions.as_flattened()),
        "{what}: positions"
    );
    assert_eq!(
        bits(got.normals.as_flattened()),
        bits(want.normals.as_flattened()),
        "{what}: normals"
    );
}

#[test]
fn twins_reproduce_the_cpu_construction() {
    for (name, mesh) in meshes() {
        let p = PrepPatches::<f32>::build(&mesh).unwrap();
        let whole = PrepChunks::new(p.topology(), u64::MAX).unwrap();
        assert_eq!(
            whole.chunks.len(),
            1,
            "{name}: one sub-problem without a limit"
        );
        let (vd, pd) = whole.run_passes_cpu(&mesh.positions);
        let (want_vd, want_pd) = cpu_flat(&p);
        assert_eq!(bits(&vd), bits(&want_vd), "{name}: vertex pass");
        assert_eq!(bits(&pd), bits(&want_pd), "{name}: patch pass");
        let diag = bbox_diagonal(&mesh.positions);
        for n in [2, 3, 6] {
            let t = whole.tessellate_cpu(&mesh.positions, n);
            compare_tessellation(&format!("{name} twin n={n}"), &t, &p.tessellate(n), diag);
        }
    }
}

/// A mesh that fits is one sub-problem numbered exactly as the mesh.
#[test]
fn one_sub_problem_is_the_mesh() {
    for (name, mesh) in meshes() {
        let topo = PrepTopology::new(&Topology::new(&mesh).unwrap()).unwrap();
        let t = PrepTables::new(&topo).unwrap();
        let iota = |n: usize| (0..n as u32).collect::<Vec<_>>();
        assert_eq!(t.vertex_ids, iota(topo.num_vertices()), "{name}");
        assert_eq!(t.edge_ids, iota(topo.num_edges()), "{name}");
        assert_eq!(
            t.config.owned_vertices as usize,
            topo.num_vertices(),
            "{name}"
        );
        assert_eq!(t.ring_offsets, topo.ring_offsets(), "{name}");
        assert_eq!(t.ring_indices, topo.ring_indices(), "{name}");
        assert_eq!(t.face_verts, topo.face_verts(), "{name}");
        assert_eq!(t.edge_corner, topo.edge_corner(), "{name}");
        assert_eq!(t.h_index, topo.h_index(), "{name}");
    }
}

/// The closed test meshes, the torus refined twice (512 quads), and the lefthanded mesh with
/// two vertices used by no face (first and last).
fn meshes_and_a_refined_torus() -> Vec<(String, Mesh)> {
    let mut out = meshes();
    let base = out[3].1.clone();
    let refiner = subsurf::Refiner::new(Topology::new(&base).unwrap(), 2).unwrap();
    out.push((
        "catmark_torus level 2".to_string(),
        refiner.to_mesh(2, refiner.refine_positions(&base.positions)),
    ));
    let lh = &out[1].1;
    let mut positions = vec![[9.0, 9.0, 9.0]];
    positions.extend(&lh.positions);
    positions.push([-9.0, 0.0, 0.0]);
    let faces: Vec<Vec<u32>> = lh
        .face_indices
        .chunks_exact(4)
        .map(|f| f.iter().map(|&v| v + 1).collect())
        .collect();
    out.push((
        "catmark_lefthanded with unused vertices".to_string(),
        Mesh::from_faces(positions, &faces),
    ));
    out
}

/// Split into sub-problems of a few faces each, the twins compute exactly the unsplit
/// result: the same coefficient bits, the same tessellation bits in the same layout.
#[test]
fn sub_problems_reproduce_the_whole_bit_for_bit() {
    for (name, mesh) in meshes_and_a_refined_torus() {
        let topo = PrepTopology::new(&Topology::new(&mesh).unwrap()).unwrap();
        let whole = PrepChunks::new(&topo, u64::MAX).unwrap();
        let (wvd, wpd) = whole.run_passes_cpu(&mesh.positions);
        for limit in [1 << 11, 1 << 13, 1 << 16] {
            let split = PrepChunks::new(&topo, limit).unwrap();
            let what = format!("{name}, {limit}-byte bindings");
            // Every table of every sub-problem fits the limit.
            for t in &split.chunks {
                let c = &t.config;
                for (table, bytes) in [
                    ("positions", 12 * t.vertex_ids.len()),
                    ("rings", 4 * t.ring_indices.len()),
                    ("vertex data", 4 * t.vertex_data_len()),
                    ("patch data", 4 * t.patch_data_len()),
                    ("corner slots", 32 * c.num_faces as usize),
                ] {
                    assert!(bytes as u64 <= limit, "{what}: {table} {bytes} bytes");
                }
            }
            if 192 * topo.num_faces() as u64 > 2 * limit {
                assert!(split.chunks.len() > 1, "{what}: not split");
            }
            let (vd, pd) = split.run_passes_cpu(&mesh.positions);
            assert_eq!(bits(&vd), bits(&wvd), "{what}: vertex data");
            assert_eq!(bits(&pd), bits(&wpd), "{what}: patch data");
            for n in [2, 3, 5] {
                // Every sample is written by exactly one sub-problem.
                let mut canon = split.canonical_slots(n);
                canon.sort_unstable();
                assert!(
                    canon.iter().enumerate().all(|(i, &c)| i as u32 == c),
                    "{what}"
                );
                let got = split.tessellate_cpu(&mesh.positions, n);
                let want = whole.tessellate_cpu(&mesh.positions, n);
                assert_same_bits(&format!("{what} n={n}"), &got, &want);
            }
        }
    }
}

/// A face that cannot fit one binding with its corners' rings is a typed error.
#[test]
fn a_face_over_the_limit_is_too_large() {
    let (_, mesh) = meshes().swap_remove(0);
    let topo = PrepTopology::new(&Topology::new(&mesh).unwrap()).unwrap();
    match PrepChunks::new(&topo, 100) {
        Err(subsurf_gpu::GpuError::TooLarge { needed, limit, .. }) => {
            assert!(needed > limit && limit == 100)
        }
        other => panic!("expected TooLarge, got {other:?}"),
    }
}

/// The twin of `prep_eval_grid` run in dispatches (`first_item`, output bound from the
/// aligned word at or before the dispatch's first item, `out_shift` words in) writes exactly
/// what one dispatch writes.
#[test]
fn twin_chunks_compose() {
    use subsurf_gpu::cpu::prep_eval_grid::{grid_params, prep_eval_grid_invocation, EvalInputs};
    let (_, mesh) = meshes().swap_remove(3);
    let p = PrepPatches::<f32>::build(&mesh).unwrap();
    let tables = PrepTables::new(p.topology()).unwrap();
    let (vd, pd) = tables.run_passes_cpu(&mesh.positions);
    let n = 5;
    let params = grid_params(n);
    let inp = EvalInputs {
        params: &params,
        edge_corner: &tables.edge_corner,
        h_index: &tables.h_index,
        vertex_data: &vd,
        patch_data: &pd,
    };
    let total = PrepChunks::new(p.topology(), u64::MAX)
        .unwrap()
        .grid_vertices(n) as u32;
    let mut whole = vec![0.0f32; 6 * total as usize];
    tables.eval_region_cpu(n, &vd, &pd, &mut whole);
    let mut out = vec![0.0f32; 6 * total as usize];
    let align = 64;
    for start in (0..total).step_by(37) {
        let count = 37.min(total - start);
        let shift = 6 * start % align;
        let cfg = subsurf_gpu::shared::PrepConfig {
            item_count: count,
            grid_width: count,
            samples: n as u32,
            first_item: start,
            out_shift: shift,
            ..tables.config
        };
        let window = &mut out[(6 * start - shift) as usize..6 * (start + count) as usize];
        for local in 0..count {
            prep_eval_grid_invocation(local, &cfg, &inp, window);
        }
    }
    assert_eq!(bits(&out), bits(&whole));
}

#[test]
fn gpu_coefficients_match_cpu() {
    let Some(ctx) = context_or_skip("gpu_coefficients_match_cpu") else {
        return;
    };
    for (name, mesh) in meshes() {
        let p = PrepPatches::<f32>::build(&mesh).unwrap();
        let mut gpu = GpuPrep::new(&ctx, p.topology()).unwrap();
        gpu.update(&ctx, &mesh.positions).unwrap();
        let (vd, pd) = gpu.download_coefficients(&ctx).unwrap();
        let (want_vd, want_pd) = cpu_flat(&p);
        // f32 rounding (with or without fused multiply-add) of sums of a few dozen terms of
        // the size of the mesh.
        let tol = 1e-6 * bbox_diagonal(&mesh.positions);
        assert_all_close(&format!("{name} vertex data"), &vd, &want_vd, tol);
        assert_all_close(&format!("{name} patch data"), &pd, &want_pd, tol);
    }
}

#[test]
fn gpu_tessellation_is_watertight_and_matches_cpu() {
    let Some(ctx) = context_or_skip("gpu_tessellation_is_watertight_and_matches_cpu") else {
        return;
    };
    for (name, mesh) in meshes() {
        let p = PrepPatches::<f32>::build(&mesh).unwrap();
        let mut gpu = GpuPrep::new(&ctx, p.topology()).unwrap();
        gpu.update(&ctx, &mesh.positions).unwrap();
        let diag = bbox_diagonal(&mesh.positions);
        for n in [2, 3, 5, 9] {
            let grid = gpu.grid(&ctx, n).unwrap();
            gpu.eval_grid(&ctx, &grid).unwrap();
            let t = grid.download(&ctx).unwrap();
            compare_tessellation(&format!("{name} GPU n={n}"), &t, &p.tessellate(n), diag);
        }
    }
}

#[test]
fn gpu_update_follows_a_deformation() {
    let Some(ctx) = context_or_skip("gpu_update_follows_a_deformation") else {
        return;
    };
    let (_, mesh) = meshes().swap_remove(1);
    let topo = PrepTopology::new(&Topology::new(&mesh).unwrap()).unwrap();
    let mut gpu = GpuPrep::new(&ctx, &topo).unwrap();
    let grid = gpu.grid(&ctx, 4).unwrap();
    for frame in 1..3 {
        let t = frame as f32;
        let moved: Vec<[f32; 3]> = mesh
            .positions
            .iter()
            .map(|q| {
                [
                    q[0] * (1.0 + 0.2 * t),
                    q[1] + 0.1 * (t * q[0]).sin(),
                    q[2] - t,
                ]
            })
            .collect();
        gpu.update(&ctx, &moved).unwrap();
        gpu.eval_grid(&ctx, &grid).unwrap();
        let got = grid.download(&ctx).unwrap();
        let p = PrepPatches::<f32>::from_prep_topology(topo.clone(), &moved).unwrap();
        compare_tessellation("deformed", &got, &p.tessellate(4), bbox_diagonal(&moved));
    }
    assert!(gpu.update(&ctx, &mesh.positions[1..]).is_err());
}

/// Split into sub-problems and dispatches far below the adapter's limits, the GPU computes
/// the unsplit GPU result bit for bit (coefficients and tessellation) and matches the CPU.
#[test]
fn chunked_passes_match_cpu() {
    let Some(ctx) = context_or_skip("chunked_passes_match_cpu") else {
        return;
    };
    // Grids of at most 2 x 2 workgroups and 16 KiB bindings: the mesh is split into
    // sub-problems, and every pass and the grid's vertex and index buffers into dispatches.
    let limits = ChunkLimits {
        max_binding_bytes: 1 << 14,
        max_workgroups_per_dimension: 2,
        max_stride: 6,
    };
    // The refined torus, and a mesh with vertices used by no face.
    for (name, mesh) in meshes_and_a_refined_torus().split_off(4) {
        let p = PrepPatches::<f32>::build(&mesh).unwrap();
        let mut gpu = GpuPrep::with_limits(&ctx, p.topology(), limits).unwrap();
        let mut whole = GpuPrep::new(&ctx, p.topology()).unwrap();
        assert!(gpu.chunks().chunks.len() > 2 && whole.chunks().chunks.len() == 1);
        gpu.update(&ctx, &mesh.positions).unwrap();
        whole.update(&ctx, &mesh.positions).unwrap();
        let (vd, pd) = gpu.download_coefficients(&ctx).unwrap();
        let (wvd, wpd) = whole.download_coefficients(&ctx).unwrap();
        assert_eq!(bits(&vd), bits(&wvd), "{name}: vertex data");
        assert_eq!(bits(&pd), bits(&wpd), "{name}: patch data");
        let diag = bbox_diagonal(&mesh.positions);
        for n in [2, 9] {
            let grid = gpu.grid(&ctx, n).unwrap();
            assert!(gpu.num_dispatches() > 2 && grid.num_dispatches() > 4);
            gpu.eval_grid(&ctx, &grid).unwrap();
            let t = grid.download(&ctx).unwrap();
            compare_tessellation(&format!("{name} chunked n={n}"), &t, &p.tessellate(n), diag);
            let wgrid = whole.grid(&ctx, n).unwrap();
            whole.eval_grid(&ctx, &wgrid).unwrap();
            let w = wgrid.download(&ctx).unwrap();
            assert_same_bits(&format!("{name} n={n}, split vs whole"), &t, &w);
        }
    }
}

/// Positions refined on the GPU feed the p-rep without a trip through the host: the same
/// bits as uploading them, whole and split into sub-problems.
#[test]
fn update_from_gpu_positions_matches_update() {
    let Some(ctx) = context_or_skip("update_from_gpu_positions_matches_update") else {
        return;
    };
    let (_, base) = meshes().swap_remove(1);
    let refiner = subsurf::Refiner::new(Topology::new(&base).unwrap(), 1).unwrap();
    let gpu_refiner = subsurf_gpu::GpuRefiner::new(&ctx, &refiner).unwrap();
    gpu_refiner.update(&ctx, &base.positions).unwrap();
    let refined = gpu_refiner.download(&ctx).unwrap();
    let mesh = refiner.to_mesh(1, refined.clone());
    let topo = PrepTopology::new(&Topology::new(&mesh).unwrap()).unwrap();
    let split = ChunkLimits {
        max_binding_bytes: 1 << 15,
        ..ChunkLimits::from_context(&ctx)
    };
    for limits in [ChunkLimits::from_context(&ctx), split] {
        let mut from_gpu = GpuPrep::with_limits(&ctx, &topo, limits).unwrap();
        let mut uploaded = GpuPrep::with_limits(&ctx, &topo, limits).unwrap();
        let chunks = from_gpu.chunks().chunks.len();
        assert_eq!(chunks > 1, limits == split, "{chunks} sub-problems");
        from_gpu.update_from(&ctx, gpu_refiner.output()).unwrap();
        uploaded.update(&ctx, &refined).unwrap();
        let (vd, pd) = from_gpu.download_coefficients(&ctx).unwrap();
        let (wvd, wpd) = uploaded.download_coefficients(&ctx).unwrap();
        assert_eq!(bits(&vd), bits(&wvd), "{chunks} sub-problems: vertex data");
        assert_eq!(bits(&pd), bits(&wpd), "{chunks} sub-problems: patch data");
        let (g, w) = (
            from_gpu.grid(&ctx, 5).unwrap(),
            uploaded.grid(&ctx, 5).unwrap(),
        );
        from_gpu.eval_grid(&ctx, &g).unwrap();
        uploaded.eval_grid(&ctx, &w).unwrap();
        assert_same_bits(
            &format!("{chunks} sub-problems"),
            &g.download(&ctx).unwrap(),
            &w.download(&ctx).unwrap(),
        );
    }
    let wrong = subsurf_gpu::VertexBuffer::zeroed(&ctx, topo.num_vertices(), 4).unwrap();
    let mut gpu = GpuPrep::new(&ctx, &topo).unwrap();
    assert!(matches!(
        gpu.update_from(&ctx, &wrong),
        Err(subsurf_gpu::GpuError::BufferMismatch(_))
    ));
}
