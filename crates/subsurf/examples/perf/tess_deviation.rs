//! Triangles at equal *geometric* deviation: `--tolerance E` against the coarsest uniform
//! rate that is as close to the limit surface, both measured as the two-sided (Hausdorff)
//! distance to the limit surface (`subsurf::tess::DeviationReference`: the isolation-10,
//! double-precision surface as the reference, its samples kept for every candidate), as a
//! fraction of the bounding-box diagonal. The uniform rates are planned on the same surface
//! as the adaptive tessellation (the table `--tolerance` isolates), so both see the same end
//! caps; every candidate's triangles carry their ptex face and `(u, v)`, from which their
//! samples are projected.
//!
//! `cargo run --release -p subsurf --example tess_deviation [-- FILE ...]` (default: the car,
//! the pawn, `lefthanded`, the torus, `toroidal_tet` and `pole64` of `testdata/shapes`); one
//! row per shape and tolerance (3e-3, 1e-3; `TOLERANCES=3e-3,1e-3` sets them). The time of
//! each candidate's measurement goes to stderr. `UNIFORM=0` skips the uniform rates: a scan
//! of what `--tolerance` reaches, shape by shape (`-- testdata/shapes/catmark_*.obj`).

use std::error::Error;
use std::time::Instant;

use subsurf::limit::{LimitSurface, PatchOptions, PatchTable};
use subsurf::surface::{adaptive_surface, tessellate_adaptive, Cpu};
use subsurf::tess::{
    plan, Deviation, DeviationOptions, DeviationReference, EdgeRates, RatePolicy,
    TriangleParameters,
};
use subsurf::Topology;

/// The highest uniform rate tried.
const MAX_UNIFORM: u32 = 96;

fn main() -> Result<(), Box<dyn Error>> {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../testdata/shapes/");
    let mut files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        files = [
            "car",
            "pawn",
            "lefthanded",
            "torus",
            "toroidal_tet",
            "pole64",
        ]
        .iter()
        .map(|n| format!("{root}catmark_{n}.obj"))
        .collect();
    }
    let tolerances: Vec<f32> = std::env::var("TOLERANCES")
        .unwrap_or_else(|_| "3e-3,1e-3".into())
        .split(',')
        .map(|s| s.trim().parse())
        .collect::<Result<_, _>>()?;
    let search = std::env::var("UNIFORM").map_or(true, |v| v != "0");
    let opts = DeviationOptions {
        surface_samples: 12,
        triangle_samples: 2,
    };
    println!(
        "| shape | tolerance | adaptive triangles | reached (of tolerance) | coarsest uniform rate \
         as close | its triangles | uniform / adaptive |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for file in &files {
        let mesh = subsurf::io::read_path(file)?;
        let name = std::path::Path::new(file)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .trim_start_matches("catmark_")
            .to_string();
        let topo = Topology::new(&mesh)?;
        let exact: LimitSurface<f64> = LimitSurface::new(
            PatchTable::build_real(
                &topo,
                &PatchOptions {
                    isolation_level: 10,
                    ..PatchOptions::default()
                },
            )?,
            &mesh.positions,
        );
        let reference = DeviationReference::new(&exact, &opts);
        let measure =
            |what: &str, positions: &[[f32; 3]], tris: &[[u32; 3]], uv: &[TriangleParameters]| {
                let t0 = Instant::now();
                let d = reference.measure(positions, tris, Some(uv));
                eprintln!(
                    "{name} {what}: {} triangles measured in {:.2} s",
                    tris.len(),
                    t0.elapsed().as_secs_f64()
                );
                d
            };
        for &tol in &tolerances {
            let policy = RatePolicy::Tolerance(tol);
            let (s, chords) = match adaptive_surface(
                &topo,
                &mesh.positions,
                &policy,
                "--tolerance",
                &PatchOptions::default(),
            ) {
                Ok(x) => x,
                Err(e) => {
                    println!("| {name} | {tol:.0e} | refused: {e} | | | | |");
                    continue;
                }
            };
            let a = tessellate_adaptive(&s, &chords, "--tolerance", &Cpu)?;
            let t = &a.tessellation;
            let d = measure("adaptive", &t.positions, &t.triangles, &a.triangle_uv);
            let reached = d.hausdorff();
            if !search {
                println!(
                    "| {name} | {tol:.0e} | {} | {reached:.2e} ({:.2}) | | | |",
                    t.triangles.len(),
                    reached / f64::from(tol)
                );
                continue;
            }
            // Uniform rates on the same surface, measured once each.
            let mut cache: Vec<Option<(Deviation, usize)>> = vec![None; MAX_UNIFORM as usize + 1];
            let mut uniform_at = |r: u32| -> Result<(Deviation, usize), Box<dyn Error>> {
                if let Some(d) = cache[r as usize] {
                    return Ok(d);
                }
                let p = plan(s.table(), &EdgeRates::uniform(&topo, r), "uniform")?;
                let uv = p.triangle_uv.clone();
                let out = s.eval_plan(p);
                let d = (
                    measure(&format!("rate {r}"), &out.positions, &out.triangles, &uv),
                    out.triangles.len(),
                );
                cache[r as usize] = Some(d);
                Ok(d)
            };
            // The coarsest uniform rate within `reached`: doubling, then bisection.
            let (mut lo, mut hi) = (1u32, 2u32);
            while hi < MAX_UNIFORM && uniform_at(hi)?.0.hausdorff() > reached {
                (lo, hi) = (hi, (2 * hi).min(MAX_UNIFORM));
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
        }
    }
    Ok(())
}
