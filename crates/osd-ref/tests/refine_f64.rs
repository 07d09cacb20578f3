//! Double-precision uniform refinement against OpenSubdiv 3.5's `PrimvarRefinerReal<double>`
//! from the file's own digits: every `catmark_*`, `bilinear_*` and `loop_*` regression shape, levels 1–3
//! (2 for large shapes), every vertex within 1e-13 of the bounding-box diagonal, and the
//! `f32` path far from that on a mesh far from the origin.

#[macro_use]
mod common;

use osd_ref::{OsdMesh, OsdRefiner};
use subsurf::{Mesh, Refiner, Topology};

fn worst_f64(mesh: &Mesh, level: usize) -> f64 {
    let mut o = OsdMesh::from(mesh);
    o.uvs = None;
    let osd = OsdRefiner::new(&o, level)
        .and_then(|r| r.interpolate_f64(&mesh.positions.to_f64()))
        .expect("OpenSubdiv refines the shape");
    let refiner = Refiner::new(Topology::new(mesh).unwrap(), level).unwrap();
    let ours = refiner.refine_f64(&mesh.positions).unwrap();
    assert_eq!(ours.len(), osd.len());
    let diag = f64::from(subsurf::mesh::bbox_diagonal(&mesh.positions)).max(1e-300);
    ours.iter()
        .zip(&osd)
        .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max))
        .fold(0.0, f64::max)
        / diag
}

#[test]
fn refine_f64_matches_opensubdiv_double_on_every_shape() {
    require_osd!();
    let mut worst = (0.0f64, String::new());
    let mut checked = 0;
    let mut loops = 0;
    for name in common::shape_names(&["catmark_", "bilinear_", "loop_"]) {
        let mesh = common::load_shape(&name);
        if Topology::new(&mesh).is_err() {
            continue;
        }
        let max = if mesh.num_faces() > 500 { 2 } else { 3 };
        for level in 1..=max {
            let e = worst_f64(&mesh, level);
            assert!(e <= 1e-13, "{name} level {level}: {e:e} of the diagonal");
            if e > worst.0 {
                worst = (e, format!("{name} level {level}"));
            }
        }
        checked += 1;
        loops += name.starts_with("loop_") as usize;
    }
    eprintln!("worst: {:e} ({})", worst.0, worst.1);
    assert!(checked >= 50, "only {checked} shapes");
    assert!(loops >= 5, "only {loops} Loop shapes");
}

/// A mesh a million units away: double precision from the file's digits stays within a few
/// `f64` units in the last place of the coordinates (the sums' order differs from
/// OpenSubdiv's), the `f32` path (positions rounded on the way in) is off by the rounding of
/// the input, ten million times more.
#[test]
fn refine_f64_keeps_a_far_mesh_exact() {
    require_osd!();
    let car = common::load_shape("catmark_car");
    let far = Mesh {
        positions: car
            .positions
            .map(|p| [p[0] + 1e6 + 1.0 / 3.0, p[1], p[2] - 2.5e5]),
        ..car
    };
    assert!(far.positions.is_f64());
    let diag = f64::from(subsurf::mesh::bbox_diagonal(&far.positions));
    let ulps = 8.0 * 1e6 * f64::EPSILON / diag;
    let e = worst_f64(&far, 2);
    assert!(e <= ulps, "{e:e} > {ulps:e}");
    let f32_mesh = Mesh {
        positions: far.positions.to_vec().into(),
        ..far.clone()
    };
    assert!(worst_f64(&f32_mesh, 2) <= ulps);
    let refiner = Refiner::new(Topology::new(&far).unwrap(), 2).unwrap();
    let exact = refiner.refine_f64(&far.positions).unwrap();
    let rounded = refiner.refine_positions(&far.positions);
    let off = exact
        .iter()
        .zip(&rounded)
        .map(|(a, b)| {
            (0..3)
                .map(|k| (a[k] - b[k] as f64).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
        / diag;
    assert!(off > 1e7 * e.max(ulps / 8.0), "{off:e}");
}
