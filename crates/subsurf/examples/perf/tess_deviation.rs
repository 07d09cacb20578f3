//! Triangles at equal *geometric* deviation: `--tolerance E` against the coarsest uniform
//! `--tess N` that is as close to the limit surface, both measured as the two-sided
//! (Hausdorff) distance to the limit surface (`subsurf::tess::deviation`: the isolation-10,
//! double-precision surface as the reference), as a fraction of the bounding-box diagonal.
//!
//! `cargo run --release -p subsurf --example tess_deviation [-- FILE ...]` (default: the car,
//! the pawn, the rook, the bishop and the helmet of `testdata/shapes`); one row per shape and
//! tolerance (3e-3, 1e-3).

use std::error::Error;
use std::time::Instant;

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::surface::{adaptive_surface, tessellate_adaptive, Cpu};
use subsurf::tess::{deviation, Deviation, DeviationOptions, RatePolicy};
use subsurf::Topology;

fn main() -> Result<(), Box<dyn Error>> {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../testdata/shapes/");
    let mut files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        files = ["car", "pawn", "rook", "bishop", "helmet"]
            .iter()
            .map(|n| format!("{root}catmark_{n}.obj"))
            .collect();
    }
    let opts = DeviationOptions {
        surface_samples: 12,
        triangle_samples: 2,
    };
    println!(
        "| shape | tolerance | adaptive triangles | reached (of tolerance) | coarsest uniform N as \
         close | its triangles | uniform / adaptive |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for file in &files {
        let mesh = subsurf::io::read_path(file)?;
        let name = std::path::Path::new(file)
            .file_stem()
            .unwrap()
            .to_string_lossy();
        let topo = Topology::new(&mesh)?;
        let reference: LimitSurface<f64> = LimitSurface::new(
            PatchTable::build_real(
                &topo,
                &PatchOptions {
                    isolation_level: 10,
                    ..PatchOptions::default()
                },
            )?,
            &mesh.positions,
        );
        let uniform = LimitSurface::new(
            PatchTable::build(&topo, &PatchOptions::default())?,
            &mesh.positions,
        );
        let mut cache: Vec<Option<(Deviation, usize)>> = vec![None; 65];
        let mut uniform_at = |n: usize| -> Result<(Deviation, usize), Box<dyn Error>> {
            if let Some(d) = cache[n] {
                return Ok(d);
            }
            let t = uniform.tessellate(n)?;
            let tris = t.triangles();
            let d = (
                deviation(&reference, &t.positions, &tris, &opts),
                tris.len(),
            );
            cache[n] = Some(d);
            Ok(d)
        };
        for tol in [3e-3f32, 1e-3] {
            let t0 = Instant::now();
            let policy = RatePolicy::Tolerance(tol);
            let (s, p) = adaptive_surface(
                &topo,
                &mesh.positions,
                &policy,
                "--tolerance",
                &PatchOptions::default(),
            )?;
            let a = tessellate_adaptive(&s, &p, "--tolerance", &Cpu)?;
            let ms = t0.elapsed().as_secs_f64() * 1e3;
            let t = &a.tessellation;
            let d = deviation(&reference, &t.positions, &t.triangles, &opts);
            let reached = d.hausdorff();
            // The coarsest uniform rate within `reached`: doubling, then bisection.
            let (mut lo, mut hi) = (1usize, 2usize); // rate 2 is the coarsest uniform one
            while hi < 64 && uniform_at(hi)?.0.hausdorff() > reached {
                (lo, hi) = (hi, (2 * hi).min(64));
            }
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if uniform_at(mid)?.0.hausdorff() > reached {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let (du, ntri) = uniform_at(hi)?;
            println!(
                "| {name} | {tol:.0e} | {} | {reached:.2e} ({:.2}; mesh {:.2e}, surface {:.2e}) | {hi}{} | {ntri} | {:.2}x |",
                t.triangles.len(),
                reached / f64::from(tol),
                d.mesh_to_surface,
                d.surface_to_mesh,
                if du.hausdorff() > reached { " (not reached)" } else { "" },
                ntri as f64 / t.triangles.len() as f64,
            );
            eprintln!("{name} {tol:e}: rates + tessellation {ms:.1} ms");
        }
    }
    Ok(())
}
