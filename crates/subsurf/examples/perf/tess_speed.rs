//! Time of rates + tessellation alone (the per-frame work of a renderer that re-tessellates),
//! on the surface `--tolerance` tessellates (`surface::adaptive_surface`):
//! `cargo run --release -p subsurf --example tess_speed [-- FILE TOLERANCE RUNS]` (default
//! `testdata/shapes/catmark_car.obj`, `1e-3`, 21 runs). Prints medians in milliseconds, on all
//! threads (`RAYON_NUM_THREADS` sets how many):
//!
//! - `one call`: `RatePolicy::rates` (its rate curves measured and turned into rates; the
//!   table lays them out on its first call and keeps them, `PatchTable::rate_curves`, so a
//!   table's first call adds the `layout` stage below) and the tessellation with the check of
//!   every triangle (`tess::check`);
//! - `per frame`: the same with the caller's own layout (`RateCurves::new` reads only the
//!   patch table, as `subsurf-gpu`'s `GpuRates` keeps it): measure, rates, checked
//!   tessellation;
//! - the stages of one plan: layout, measure, rates from the measures, plan, chord check,
//!   evaluation of the output;
//! - a frame under the screen-space policy (no check: what a renderer re-tessellates when its
//!   camera moves), the curves kept: measure, rates, plan, evaluation, on an 800 x 600 image
//!   framing the model seen along `-z` (orthographic), 16 pixels per edge.
//!
//! `ONLY=measure`, `ONLY=chord`, `ONLY=plan` or `ONLY=rates` runs that stage alone RUNS times after one warm-up (for
//! `valgrind --tool=callgrind`: the difference of two run counts is the stage's instructions).

use std::time::Instant;

use subsurf::limit::PatchOptions;
use subsurf::tess::{
    chord_errors, plan, tessellate_within_tolerance, CurveMeasure, RateCurves, RatePolicy,
};
use subsurf::Topology;

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn ms(a: Instant, b: Instant) -> f64 {
    (b - a).as_secs_f64() * 1e3
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
    let m = CurveMeasure::SecondDerivative;
    let curves = RateCurves::new(s.table());
    let face_of_ptex = s.table().ptex_base_faces();
    let diagonal = |s: &subsurf::limit::LimitSurface| subsurf::mesh::bbox_diagonal(s.points());
    if let Ok(only) = std::env::var("ONLY") {
        let measures = curves.measure(&s, &m);
        let r = policy
            .rates_from_measures(s.table(), diagonal(&s), &curves, &measures, "")
            .unwrap();
        let p = plan(s.table(), &r, "").unwrap();
        for _ in 0..runs {
            match only.as_str() {
                "measure" => drop(std::hint::black_box(curves.measure(&s, &m))),
                "chord" => drop(std::hint::black_box(chord_errors(
                    &s,
                    &p,
                    &face_of_ptex,
                    None,
                ))),
                "plan" => drop(std::hint::black_box(plan(s.table(), &r, ""))),
                "rates" => drop(std::hint::black_box(policy.rates_from_measures(
                    s.table(),
                    diagonal(&s),
                    &curves,
                    &measures,
                    "",
                ))),
                other => panic!("ONLY={other}: measure, chord, plan or rates"),
            }
        }
        return;
    }
    let mut one_call = (Vec::new(), Vec::new(), Vec::new());
    let mut frame = (Vec::new(), Vec::new());
    let mut stages = vec![Vec::new(); 6];
    let mut triangles = 0;
    // Orthographic, along -z, the bounding box framed in 800 x 600 pixels.
    let (lo, hi) = subsurf::mesh::bounding_box(s.points()).unwrap();
    let half = 0.55 * (hi[0] - lo[0]).max((hi[1] - lo[1]) * 4.0 / 3.0);
    let (cx, cy) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
    let (sx, sy) = (1.0 / half, 4.0 / 3.0 / half);
    let screen = RatePolicy::Screen {
        camera: subsurf::tess::ScreenCamera {
            view_proj: [
                [sx, 0.0, 0.0, 0.0],
                [0.0, sy, 0.0, 0.0],
                [0.0, 0.0, 0.0, 0.0],
                [-cx * sx, -cy * sy, 0.0, 1.0],
            ],
            width: 800,
            height: 600,
        },
        pixels: 16.0,
    };
    let screen_m = screen.measure().unwrap();
    let (mut screen_ms, mut screen_triangles) = (Vec::new(), 0);
    for _ in 0..runs {
        let t0 = Instant::now();
        let measures = curves.measure(&s, &screen_m);
        let r = screen
            .rates_from_measures(s.table(), diagonal(&s), &curves, &measures, "")
            .unwrap();
        let out = s.tessellate_rates(&r, "").unwrap();
        let t1 = Instant::now();
        screen_triangles = std::hint::black_box(out).triangles.len();
        screen_ms.push(ms(t0, t1));
    }
    for _ in 0..runs {
        // One call.
        let t0 = Instant::now();
        let r = policy.rates(&s, "--tolerance").unwrap();
        let t1 = Instant::now();
        let (_, out, _) = tessellate_within_tolerance(&s, r, chords, "").unwrap();
        let t2 = Instant::now();
        triangles = std::hint::black_box(out).triangles.len();
        one_call.0.push(ms(t0, t1));
        one_call.1.push(ms(t1, t2));
        one_call.2.push(ms(t0, t2));
        // Per frame, the curves kept.
        let t0 = Instant::now();
        let measures = curves.measure(&s, &m);
        let r = policy
            .rates_from_measures(s.table(), diagonal(&s), &curves, &measures, "")
            .unwrap();
        let t1 = Instant::now();
        let (_, out, _) = tessellate_within_tolerance(&s, r, chords, "").unwrap();
        let t2 = Instant::now();
        std::hint::black_box(out);
        frame.0.push(ms(t0, t1));
        frame.1.push(ms(t0, t2));
        // The stages of one plan.
        let t0 = Instant::now();
        let c = RateCurves::new(s.table());
        let t1 = Instant::now();
        let measures = c.measure(&s, &m);
        let t2 = Instant::now();
        let r = policy
            .rates_from_measures(s.table(), diagonal(&s), &c, &measures, "")
            .unwrap();
        let t3 = Instant::now();
        let p = plan(s.table(), &r, "").unwrap();
        let t4 = Instant::now();
        let e = chord_errors(&s, &p, &face_of_ptex, None);
        let t5 = Instant::now();
        let out = s.eval_plan(p);
        let t6 = Instant::now();
        std::hint::black_box((e, out));
        for (k, (a, b)) in [(t0, t1), (t1, t2), (t2, t3), (t3, t4), (t4, t5), (t5, t6)]
            .into_iter()
            .enumerate()
        {
            stages[k].push(ms(a, b));
        }
    }
    println!(
        "{file} tolerance {tol:e}: {triangles} triangles, {} patches, {} rate curves; medians of \
         {runs}, {} threads",
        s.table().num_patches(),
        curves.num_curves(),
        rayon::current_num_threads()
    );
    println!(
        "  one call (layout kept with the table): rates {:.2} ms, tessellation checked {:.2} ms, both {:.2} ms",
        median(one_call.0),
        median(one_call.1),
        median(one_call.2)
    );
    println!(
        "  per frame (curves kept): rates {:.2} ms, with the checked tessellation {:.2} ms",
        median(frame.0),
        median(frame.1)
    );
    println!(
        "  screen-space frame (curves kept, 16 px, no check): {:.2} ms, {screen_triangles} \
         triangles",
        median(screen_ms)
    );
    let names = ["layout", "measure", "rates", "plan", "check", "evaluation"];
    let parts: Vec<String> = names
        .iter()
        .zip(stages)
        .map(|(n, t)| format!("{n} {:.2}", median(t)))
        .collect();
    println!("  stages (ms): {}", parts.join(", "));
}
