//! GPU pipeline figures, GPU backend vs CPU backend, as medians of repeated runs:
//!
//! * refinement throughput (output vertices per second): `catmark_car` at levels 3–4 and a
//!   262,144-quad torus at levels 1–2. CPU = `Refiner::refine_positions` (rayon, all cores);
//!   GPU = `GpuRefiner::update` + wait (data stays on the GPU), and the same plus read-back;
//! * p-rep frames per second (Myles, Yeo & Peters 2008, Table 1): construction (vertex + patch
//!   pass) + N×N evaluation, N = 5, 9, 17, 33, on three disjoint copies of
//!   `catmark_lefthanded` (1,302 closed quads, valences 3–5, 47.9% B-quads: the mesh of
//!   subsurf's `prep` bench). CPU = `PrepPatches::update` + `eval_grid_into` (unshared grid,
//!   reused buffers) and `update` + `tessellate(N)` (watertight, the GPU's output); GPU =
//!   `GpuPrep::update` + `eval_grid` (watertight) + wait;
//! * limit-surface tessellation throughput (samples per second): `catmark_car` (1,575 faces,
//!   creases, extraordinary vertices) at isolation level 3, the watertight N×N tessellation,
//!   N = 5, 9, 17, 33. CPU = new points (`PatchTable::points`) + `LimitSurface::eval_batch`
//!   of the plan's samples, and + `tessellate(N)` (which also rebuilds the plan); GPU =
//!   `GpuLimit::update` (refinement, end-cap points) + `eval` + wait, and the same plus
//!   read-back.
//!
//! Every line names the adapter. Plain `main` (no criterion) so that the same file also
//! builds as a standalone example binary to copy to a machine with a real GPU:
//!
//! ```text
//! cargo build --release -p subsurf-gpu --example gpu_pipeline
//! target/release/examples/gpu_pipeline            # or: cargo bench -p subsurf-gpu --bench gpu_pipeline
//! ```
//!
//! The meshes are embedded in the binary. `GPU_PIPELINE_QUICK=1` runs only the smaller cases,
//! `GPU_PIPELINE_ONLY=refine|refine_large|prep|prep_large|limit` one section (`refine_large`, the
//! car at level 7, only when named).

include!("../../benches/common/pipeline.rs");
