//! Isolation chosen per region for an end-cap budget (`limit::build_for_tolerance`): per
//! budget, the time of the choice and build, the patches, the end caps' largest distance to
//! an isolation-10 reference (9 x 9 samples per end cap, f64) against the budget and the
//! estimate, and how many base faces took each level.
//!
//! `cargo run --release -p subsurf --example tolerance_isolation [-- FILE]` (default
//! `testdata/shapes/catmark_car.obj`).

use subsurf::limit::{build_for_tolerance, LimitSurface, PatchOptions, PatchTable, PatchType};
use subsurf::Topology;
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let file = args
        .first()
        .cloned()
        .unwrap_or("testdata/shapes/catmark_car.obj".into());
    let mesh = subsurf::io::obj::read_file(std::path::Path::new(&file)).unwrap();
    let t = Topology::new(&mesh).unwrap();
    let diag = subsurf::mesh::bbox_diagonal(&mesh.positions) as f64;
    let r = LimitSurface::new(
        PatchTable::<f64>::build_real(
            &t,
            &PatchOptions {
                isolation_level: 10,
                ..Default::default()
            },
        )
        .unwrap(),
        &mesh.positions,
    );
    for b in [1e-3f32, 2.5e-4, 1e-4, 2.5e-5] {
        let t0 = std::time::Instant::now();
        let (tb, ch) =
            build_for_tolerance::<f64>(&t, &PatchOptions::default(), &mesh.positions, b).unwrap();
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let s = LimitSurface::new(tb, &mesh.positions);
        let tb = &s.table();
        let mut worst = 0.0f64;
        for p in 0..tb.num_patches() {
            if tb.patch_type(p) != PatchType::Gregory {
                continue;
            }
            let pp = tb.params()[p];
            let ptex = pp.face_id() as usize;
            for a in 0..=8 {
                for c in 0..=8 {
                    let (u, v) = pp.unnormalize(a as f64 / 8.0, c as f64 / 8.0);
                    let x = s.eval_position(ptex, u, v).unwrap();
                    let y = r.eval_position(ptex, u, v).unwrap();
                    let d = ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2))
                        .sqrt()
                        / diag;
                    worst = worst.max(d);
                }
            }
        }
        let mut hist = [0usize; 11];
        for &l in &ch.face_levels {
            hist[l as usize] += 1;
        }
        let est = ch.deviation.iter().cloned().fold(0.0f32, f32::max);
        println!("budget {b:.1e}: {ms:.1} ms, {} patches, worst true {worst:.2e} ({:.2} of budget), est max {est:.2e}, levels {:?}", tb.num_patches(), worst / b as f64, hist);
    }
}
