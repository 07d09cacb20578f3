//! Time of rates + tessellation alone (the per-frame work of a renderer that re-tessellates),
//! on the surface `--tolerance` tessellates (`surface::adaptive_surface`):
//! `cargo run --release -p subsurf --example tess_speed [-- FILE TOLERANCE RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, `1e-3`, 21 runs). Prints the medians of the rate step,
//! the tessellation (with the check of every triangle, `tess::check`) and both, in milliseconds, on all threads (`RAYON_NUM_THREADS`
//! sets how many). One run under `valgrind --tool=callgrind` counts instructions.

use std::time::Instant;

use subsurf::limit::PatchOptions;
use subsurf::tess::{tessellate_within_tolerance, RatePolicy};
use subsurf::Topology;

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let file = args
        .first()
        .cloned()
        .unwrap_or_else(|| "testdata/shapes/catmark_car.obj".into());
    let tol: f32 = args.get(1).map_or(1e-3, |s| s.parse().unwrap());
    let runs: usize = args.get(2).map_or(21, |s| s.parse().unwrap());
    let mesh = subsurf::io::obj::read_file(std::path::Path::new(&file)).unwrap();
    let t = Topology::new(&mesh).unwrap();
    // The surface `--tolerance` tessellates: isolation chosen per region, chords at 3/4.
    let (s, policy) = subsurf::surface::adaptive_surface(
        &t,
        &mesh.positions,
        &RatePolicy::Tolerance(tol),
        "--tolerance",
        &PatchOptions::default(),
    )
    .unwrap();
    let RatePolicy::Tolerance(chords) = policy else {
        unreachable!()
    };
    let (mut rates_ms, mut tess_ms, mut total_ms) = (Vec::new(), Vec::new(), Vec::new());
    let mut triangles = 0;
    for _ in 0..runs {
        let t0 = Instant::now();
        let r = policy.rates(&s, "--tolerance").unwrap();
        let t1 = Instant::now();
        let t2 = Instant::now();
        let (_, out, _) = tessellate_within_tolerance(&s, r, chords, "").unwrap();
        let t3 = Instant::now();
        triangles = std::hint::black_box(out).triangles.len();
        rates_ms.push((t1 - t0).as_secs_f64() * 1e3);
        tess_ms.push((t3 - t2).as_secs_f64() * 1e3);
        total_ms.push(((t1 - t0) + (t3 - t2)).as_secs_f64() * 1e3);
    }
    println!(
        "{file} tolerance {tol:e}: {triangles} triangles, {} patches; rates {:.2} ms, tessellation \
         checked {:.2} ms, both {:.2} ms (medians of {runs}, {} \
         threads)",
        s.table.num_patches(),
        median(rates_ms),
        median(tess_ms),
        median(total_ms),
        rayon::current_num_threads()
    );
}
