//! A crease slider on the GPU limit surface, headless: every crease of a mesh moved between
//! 3.5 and its own sharpness `N` times; per step the table is edited on the CPU
//! (`PatchTable::apply_sharpness`, in place), the upload edited (`GpuLimit::apply_edit`:
//! changed ranges only), the points refreshed and a 9×9 sample grid per ptex face evaluated.
//! Prints the median time of each part next to a fresh build and upload
//! (`PatchTable::build` + `GpuLimit::new`), and what each edit wrote.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p subsurf-gpu --example crease_slider_gpu
//! [-- FILE N]` (default `testdata/shapes/catmark_car.obj`, 11 steps).

mod common;
use std::time::Instant;
use subsurf::limit::{PatchOptions, PatchTable, SharpnessEdit};
use subsurf::Topology;
use subsurf_gpu::{GpuContext, GpuLimit};

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = common::mesh_path(&args);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(11);
    let mesh = subsurf::io::read_path(path)?;
    let ctx = GpuContext::new()?;
    let options = PatchOptions::default();
    let edits = |s: Option<f32>| -> Vec<SharpnessEdit> { SharpnessEdit::creases(&mesh.creases, s) };
    // Editable: the table keeps its levels, so every edit of the slider is made in place.
    let mut table = PatchTable::build_editable(&Topology::new(&mesh)?, &options)?;
    table.set_sharpness(&edits(Some(3.5)))?;
    let mut gpu = GpuLimit::new(&ctx, &table)?;
    let queries: Vec<(u32, f32, f32)> = (0..table.num_ptex_faces() as u32)
        .flat_map(|f| (0..81).map(move |k| (f, (k % 9) as f32 / 8.0, (k / 9) as f32 / 8.0)))
        .collect();
    let samples = gpu.samples(&ctx, &queries, false)?;
    println!(
        "{path}: {} creases, {} patches, {} samples, adapter {}",
        mesh.creases.len(),
        table.num_patches(),
        queries.len(),
        ctx.adapter_info().name
    );
    let (mut cpu, mut upload, mut eval, mut fresh) = (vec![], vec![], vec![], vec![]);
    for step in 0..steps {
        let s = if step % 2 == 0 { None } else { Some(3.5) };
        let t = Instant::now();
        let outcome = table.apply_sharpness(&edits(s))?;
        cpu.push(ms(t));
        let t = Instant::now();
        let up = gpu.apply_edit(&ctx, &table)?;
        upload.push(ms(t));
        let t = Instant::now();
        gpu.update(&ctx, &mesh.positions)?;
        gpu.eval(&ctx, &samples)?;
        let _ = samples.download(&ctx)?;
        eval.push(ms(t));
        let t = Instant::now();
        let mut m = mesh.clone();
        if let Some(s) = s {
            m.creases.iter_mut().for_each(|c| c.sharpness = s);
        }
        let rebuilt = PatchTable::build(&Topology::new(&m)?, &options)?;
        std::hint::black_box(GpuLimit::new(&ctx, &rebuilt)?);
        fresh.push(ms(t));
        println!("  step {step}: creases {s:?}: {outcome:?}, wrote {up:?}");
    }
    let (c, u, e, f) = (
        common::median(&mut cpu),
        common::median(&mut upload),
        common::median(&mut eval),
        common::median(&mut fresh),
    );
    println!(
        "medians of {steps} edits: table edit {c:.2} ms + upload edit {u:.2} ms (fresh build + \
         upload {f:.2} ms: {:.1}x), then points + evaluation + read-back {e:.2} ms",
        f / (c + u)
    );
    Ok(())
}
