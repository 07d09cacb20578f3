//! GPU pipeline figures, GPU backend vs CPU backend, as medians of repeated runs:
//!
//! * refinement throughput (output vertices per second): `catmark_car` at levels 3–4 and a
//!   262,144-quad torus at levels 1–2. CPU = `Refiner::refine_positions` (rayon, all cores);
//!   GPU = `GpuRefiner::update` + wait (data stays on the GPU), and the same plus read-back;
//! * p-rep frames per second (Myles, Yeo & Peters 2008, Table 1): construction (vertex + patch
//!   pass) + N×N evaluation into a watertight mesh, N = 5, 9, 17, 33, on `catmark_lefthanded`
//!   split once into quads (1,736 faces, valences 3–5, the mesh of subsurf's `prep` bench).
//!   CPU = `PrepPatches::update` + `tessellate(N)`; GPU = `GpuPrep::update` + `eval_grid` + wait.
//!
//! Every line names the adapter. Plain `main` (no criterion) so that the same file also
//! builds as a standalone example binary to copy to a machine with a real GPU:
//!
//! ```text
//! cargo build --release -p subsurf-gpu --example gpu_pipeline
//! target/release/examples/gpu_pipeline            # or: cargo bench -p subsurf-gpu --bench gpu_pipeline
//! ```
//!
//! The meshes are embedded in the binary. `GPU_PIPELINE_QUICK=1` runs only the smaller cases.

include!("common/pipeline.rs");
