// Body of the `gpu_pipeline` bench and example (documented in benches/gpu_pipeline.rs).
use std::time::{Duration, Instant};

use subsurf::prep::{Grid, PrepPatches, PrepTopology};
use subsurf::{Mesh, Refiner, Scheme, Topology};
use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf_gpu::{ChunkLimits, GpuContext, GpuLimit, GpuPrep, GpuRefiner};

const CAR: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../testdata/shapes/catmark_car.obj"));
const LEFTHANDED: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../subsurf/tests/data/prep/catmark_lefthanded.obj"));

/// Median wall time of `f`, run at least 3 and at most 50 times or for about 2 seconds.
fn median(mut f: impl FnMut()) -> Duration {
    f(); // warm-up
    let mut times = Vec::new();
    let start = Instant::now();
    while times.len() < 3 || (times.len() < 50 && start.elapsed() < Duration::from_secs(2)) {
        let t = Instant::now();
        f();
        times.push(t.elapsed());
    }
    times.sort();
    times[times.len() / 2]
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Largest coordinate difference between `got` and `want`, relative to the bounding-box
/// diagonal of `mesh`.
fn max_rel_diff(got: &[[f32; 3]], want: &[[f32; 3]], mesh: &Mesh) -> f32 {
    let d = got.iter().zip(want).flat_map(|(a, b)| (0..3).map(move |k| (a[k] - b[k]).abs())).fold(0.0f32, f32::max);
    d / subsurf::mesh::bbox_diagonal(&mesh.positions)
}

/// `binding`: a binding limit forced below the adapter's (the split paths), or `None`.
fn refine_case(ctx: Option<&GpuContext>, adapter: &str, name: &str, mesh: &Mesh, level: usize, binding: Option<u64>) {
    let refiner = match Refiner::new(Topology::new(mesh).expect("topology"), level) {
        Ok(r) => r,
        Err(e) => {
            println!("refine {name} level {level}: skipped ({e})");
            return;
        }
    };
    let out = refiner.last().num_vertices() as f64;
    let cpu = median(|| {
        std::hint::black_box(refiner.refine_positions(&mesh.positions));
    });
    println!(
        "refine {name} L{level} ({out:.0} vertices) | CPU ({} threads) | {:9.3} ms | {:8.1} Mvert/s",
        rayon::current_num_threads(),
        ms(cpu),
        out / cpu.as_secs_f64() / 1e6
    );
    let Some(ctx) = ctx else { return };
    let limits = ChunkLimits {
        max_binding_bytes: binding.unwrap_or(u64::MAX),
        ..ChunkLimits::from_context(ctx)
    };
    let adapter = match binding {
        Some(b) => format!("{adapter} at {} MiB bindings", b >> 20),
        None => adapter.to_string(),
    };
    let gpu = match GpuRefiner::with_limits(ctx, &refiner, limits) {
        Ok(g) => g,
        Err(e) => {
            println!("refine {name} L{level} | GPU {adapter} | failed: {e}");
            return;
        }
    };
    let resident = median(|| {
        gpu.update(ctx, &mesh.positions).expect("update");
        ctx.wait_idle().expect("wait");
    });
    let readback = median(|| {
        std::hint::black_box(gpu.refine(ctx, &mesh.positions).expect("refine"));
    });
    // The frame loop's read-back: into a kept buffer, through the context's kept staging.
    let mut kept = vec![[0.0f32; 3]; refiner.last().num_vertices()];
    let into = median(|| {
        gpu.update(ctx, &mesh.positions).expect("update");
        gpu.download_into(ctx, &mut kept).expect("read-back");
        std::hint::black_box(&kept);
    });
    for (what, t) in [
        ("resident", resident),
        ("+ read-back", readback),
        ("+ read-back into a kept buffer", into),
    ] {
        println!(
            "refine {name} L{level} ({out:.0} vertices) | GPU {adapter} {what} | {:9.3} ms | {:8.1} Mvert/s",
            ms(t),
            out / t.as_secs_f64() / 1e6
        );
    }
    let last_bytes = 12 * refiner.last().num_vertices() as u64;
    let binding = binding.unwrap_or(ctx.limits().max_storage_buffer_binding_size);
    if last_bytes > binding {
        // Levels past one binding are refined from gathered inputs: check them.
        let got = gpu.refine(ctx, &mesh.positions).expect("refine");
        let want = refiner.refine_positions(&mesh.positions);
        println!(
            "refine {name} L{level} | last level {} MiB > {} MiB binding | GPU vs CPU max |dp| = {:.2e} of the diagonal",
            last_bytes >> 20,
            binding >> 20,
            max_rel_diff(&got, &want, mesh)
        );
    }
}

fn prep_case(ctx: Option<&GpuContext>, adapter: &str, mesh: &Mesh, sizes: &[usize], check: bool) {
    let topo = PrepTopology::new(&Topology::new(mesh).expect("topology")).expect("closed quads");
    let mut cpu =
        PrepPatches::<f32>::from_prep_topology(topo.clone(), &mesh.positions).expect("p-rep");
    let nf = topo.num_faces();
    let t0 = Instant::now();
    let mut gpu = ctx.map(|c| GpuPrep::new(c, &topo).expect("GPU p-rep upload"));
    if let Some(g) = &gpu {
        println!(
            "prep {nf} faces | GpuPrep::new (tables, {} sub-problems, upload) | {:9.3} ms",
            g.chunks().chunks.len(),
            ms(t0.elapsed())
        );
    }
    for &n in sizes {
        let mut grid = Grid::default();
        let t_grid = median(|| {
            cpu.update(&mesh.positions).expect("update");
            cpu.eval_grid_into(n, &mut grid);
        });
        let t_tess = median(|| {
            cpu.update(&mesh.positions).expect("update");
            std::hint::black_box(cpu.tessellate(n));
        });
        for (what, t) in [("eval_grid, reused buffers", t_grid), ("watertight tessellate", t_tess)] {
            println!(
                "prep {nf} faces N={n:2} | CPU ({} threads) {what} | {:9.3} ms | {:8.1} fps",
                rayon::current_num_threads(),
                ms(t),
                1.0 / t.as_secs_f64()
            );
        }
        if let (Some(ctx), Some(gpu)) = (ctx, gpu.as_mut()) {
            let grid = gpu.grid(ctx, n).expect("grid buffers");
            let t = median(|| {
                gpu.update(ctx, &mesh.positions).expect("update");
                gpu.eval_grid(ctx, &grid).expect("eval");
                ctx.wait_idle().expect("wait");
            });
            println!(
                "prep {nf} faces N={n:2} | GPU {adapter} | {:9.3} ms | {:8.1} fps ({} vertices, {} sub-problems)",
                ms(t),
                1.0 / t.as_secs_f64(),
                grid.num_vertices,
                gpu.chunks().chunks.len()
            );
            if check {
                // The GPU tessellation against the CPU's: same triangles, largest position
                // difference relative to the bounding-box diagonal.
                let got = grid.download(ctx).expect("read back");
                cpu.update(&mesh.positions).expect("update");
                let want = cpu.tessellate(n);
                assert_eq!(got.triangles, want.triangles, "GPU index buffer differs");
                println!(
                    "prep {nf} faces N={n:2} | GPU vs CPU: triangles identical, max |dp| = {:.2e} of the diagonal",
                    max_rel_diff(&got.positions, &want.positions, mesh)
                );
            }
        }
    }
}

fn limit_case(ctx: Option<&GpuContext>, adapter: &str, name: &str, mesh: &Mesh, iso: u32, sizes: &[usize]) {
    let options = PatchOptions { isolation_level: iso, ..Default::default() };
    let table = PatchTable::build(&Topology::new(mesh).expect("topology"), &options).expect("patch table");
    let c = table.counts();
    println!(
        "limit {name} iso {iso}: {} patches ({} regular, {} single-crease, {} Gregory), {} points",
        table.num_patches(), c.regular, c.single_crease, c.gregory, table.num_points()
    );
    let mut surface = LimitSurface::new(table.clone(), &mesh.positions);
    let mut gpu = ctx.map(|c| GpuLimit::new(c, &table).expect("GPU limit upload"));
    for &n in sizes {
        let plan = table.tessellation_plan(n).expect("plan");
        let samples = plan.queries.len() as f64;
        let t_eval = median(|| {
            surface.set_positions(&mesh.positions);
            std::hint::black_box(surface.eval_batch(&plan.queries));
        });
        let t_tess = median(|| {
            surface.set_positions(&mesh.positions);
            std::hint::black_box(surface.tessellate(n).expect("tessellate"));
        });
        for (what, t) in [("points + eval_batch(plan)", t_eval), ("points + tessellate", t_tess)] {
            println!(
                "limit {name} N={n:2} ({samples:.0} samples) | CPU ({} threads) {what} | {:9.3} ms | {:8.2} Msamples/s",
                rayon::current_num_threads(),
                ms(t),
                samples / t.as_secs_f64() / 1e6
            );
        }
        if let (Some(ctx), Some(gpu)) = (ctx, gpu.as_mut()) {
            let tess = gpu.tessellation(ctx, &table, n).expect("tessellation buffers");
            let resident = median(|| {
                gpu.update(ctx, &mesh.positions).expect("update");
                gpu.eval(ctx, &tess.samples).expect("eval");
                ctx.wait_idle().expect("wait");
            });
            let readback = median(|| {
                gpu.update(ctx, &mesh.positions).expect("update");
                gpu.eval(ctx, &tess.samples).expect("eval");
                std::hint::black_box(tess.download(ctx).expect("download"));
            });
            let eval_only = median(|| {
                gpu.eval(ctx, &tess.samples).expect("eval");
                ctx.wait_idle().expect("wait");
            });
            // The same with 256 KiB bindings: patch tables and points compacted per chunk.
            let small = ChunkLimits { max_binding_bytes: 1 << 18, ..ChunkLimits::from_context(ctx) };
            let mut compact = GpuLimit::with_limits(ctx, &table, small).expect("GPU limit upload");
            let ctess = compact.tessellation(ctx, &table, n).expect("tessellation buffers");
            assert!(ctess.samples.inputs_compacted());
            let c_resident = median(|| {
                compact.update(ctx, &mesh.positions).expect("update");
                compact.eval(ctx, &ctess.samples).expect("eval");
                ctx.wait_idle().expect("wait");
            });
            let c_eval = median(|| {
                compact.eval(ctx, &ctess.samples).expect("eval");
                ctx.wait_idle().expect("wait");
            });
            let compacted = format!("update + eval, 256 KiB bindings ({} chunks)", ctess.samples.num_dispatches());
            for (what, t) in [
                ("update + eval, resident", resident),
                ("+ read-back", readback),
                ("eval only", eval_only),
                (compacted.as_str(), c_resident),
                ("eval only, 256 KiB bindings", c_eval),
            ] {
                println!(
                    "limit {name} N={n:2} ({samples:.0} samples) | GPU {adapter} {what} | {:9.3} ms | {:8.2} Msamples/s",
                    ms(t),
                    samples / t.as_secs_f64() / 1e6
                );
            }
        }
    }
}

/// `n` disjoint copies of `base` side by side in x (the shape is 0.69 wide), as subsurf's
/// `prep` bench builds its 1,302-face mesh.
fn copies(base: &Mesh, n: usize) -> Mesh {
    let nv = base.positions.len() as u32;
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for c in 0..n {
        positions.extend(base.positions.iter().map(|p| [p[0] + c as f32, p[1], p[2]]));
        let mut start = 0;
        for &k in &base.face_counts {
            let f = &base.face_indices[start..start + k as usize];
            faces.push(f.iter().map(|&v| v + c as u32 * nv).collect());
            start += k as usize;
        }
    }
    Mesh::from_faces(positions, &faces)
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is expected.
    let quick = std::env::var("GPU_PIPELINE_QUICK").is_ok_and(|v| v == "1");
    let ctx = match GpuContext::new() {
        Ok(c) => Some(c),
        Err(e) => {
            println!("gpu_pipeline: no GPU ({e}); CPU figures only");
            None
        }
    };
    let adapter = ctx
        .as_ref()
        .map(|c| {
            let i = c.adapter_info();
            format!("[{} / {}]", i.name, i.backend)
        })
        .unwrap_or_else(|| "[none]".into());
    println!(
        "gpu_pipeline: adapter {adapter}, {} CPU threads",
        rayon::current_num_threads()
    );
    let car = subsurf::io::obj::read_with_scheme(CAR, Scheme::Catmark).expect("catmark_car");
    let torus = subsurf::shapes::torus(512, 512, 1.0, 0.3);
    let mut cases: Vec<(&str, &Mesh, usize)> =
        vec![("catmark_car", &car, 3), ("torus262k", &torus, 1)];
    if !quick {
        cases.push(("catmark_car", &car, 4));
        cases.push(("torus262k", &torus, 2));
    }
    // `GPU_PIPELINE_ONLY=refine|refine_large|prep|prep_large|limit` runs one section.
    let only = std::env::var("GPU_PIPELINE_ONLY").unwrap_or_default();
    let run = |section: &str| only.is_empty() || only == section;
    if run("refine") {
        for (name, mesh, level) in cases {
            refine_case(ctx.as_ref(), &adapter, name, mesh, level, None);
        }
    }
    // A refined level past one 128 MiB binding: the car at level 7 (25 M vertices, 302 MB).
    if only == "refine_large" {
        refine_case(ctx.as_ref(), &adapter, "catmark_car", &car, 7, None);
        // The cost of the split: level 6 (77 MiB) whole, and split at 16 MiB bindings.
        refine_case(ctx.as_ref(), &adapter, "catmark_car", &car, 6, None);
        refine_case(ctx.as_ref(), &adapter, "catmark_car", &car, 6, Some(16 << 20));
    }
    let sizes: &[usize] = if quick { &[5, 9] } else { &[5, 9, 17, 33] };
    if run("prep") {
        let lh =
            subsurf::io::obj::read_with_scheme(LEFTHANDED, Scheme::Catmark).expect("lefthanded");
        prep_case(ctx.as_ref(), &adapter, &copies(&lh, 3), sizes, false);
    }
    // A p-rep past one 128 MiB binding: the three copies refined 5 times (1.33 M quads,
    // valences 3-5), split into sub-problems on adapters with 128 MiB bindings.
    if only == "prep_large" || (!quick && run("prep")) {
        let lh =
            subsurf::io::obj::read_with_scheme(LEFTHANDED, Scheme::Catmark).expect("lefthanded");
        let base = copies(&lh, 3);
        let refiner = Refiner::new(Topology::new(&base).expect("topology"), 5).expect("refine");
        let big = refiner.to_mesh(5, refiner.refine_positions(&base.positions));
        prep_case(ctx.as_ref(), &adapter, &big, &[3, 5], true);
    }
    if run("limit") {
        limit_case(ctx.as_ref(), &adapter, "catmark_car", &car, 3, sizes);
    }
}
