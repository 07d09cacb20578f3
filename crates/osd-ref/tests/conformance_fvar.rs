//! Face-varying (UV) refinement against OpenSubdiv 3.5: every `catmark_*` and `bilinear_*`
//! regression shape with UVs, levels 1–3 (4 for small shapes), every
//! `FVarLinearInterpolation` mode, value for value at each face corner (within 1e-5 of the
//! UV bounding box).

#[macro_use]
mod common;

use subsurf::{FVarLinearInterpolation, Mesh, Refiner, Topology};

use common::{osd_mesh, uv_extent, MODES};

/// Compares one shape in one mode at levels 1..=`max_level`; returns the worst error
/// relative to the UV extent, or a description of the first mismatch.
fn compare(
    name: &str,
    mesh: &Mesh,
    mode: FVarLinearInterpolation,
    code: u8,
    max_level: usize,
) -> Result<f32, String> {
    let fv = mesh.uvs.as_ref().expect("shape has UVs");
    let extent = uv_extent(&fv.values);
    let osd = osd_ref::refine_uniform(&osd_mesh(mesh, code), max_level)
        .map_err(|e| format!("{name}: OpenSubdiv: {e}"))?;
    let refiner = Refiner::new(Topology::new(mesh).unwrap(), max_level).unwrap();
    let ours = refiner
        .refine_uvs(fv, mode)
        .map_err(|e| format!("{name}: {e}"))?;
    let mut worst = 0.0f32;
    for level in 1..=max_level {
        let (values, indices) = osd[level].uvs.as_ref().expect("OpenSubdiv returned UVs");
        let s = &ours[level];
        if s.indices.len() != indices.len() {
            return Err(format!(
                "{name} {mode:?} level {level}: {} corners vs {}",
                s.indices.len(),
                indices.len()
            ));
        }
        for (c, (&i, &j)) in s.indices.iter().zip(indices).enumerate() {
            let (a, b) = (s.values[i as usize], values[j as usize]);
            let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) / extent;
            if d > 1e-5 {
                return Err(format!(
                    "{name} {mode:?} level {level} corner {c} (face {}): subsurf {a:?} OpenSubdiv {b:?} (error {d:e})",
                    c / 4
                ));
            }
            worst = worst.max(d);
        }
    }
    Ok(worst)
}

fn shapes_with_uvs() -> Vec<(String, Mesh)> {
    let names = common::shape_names(&["catmark_", "bilinear_"]);
    names
        .into_iter()
        .filter_map(|name| {
            let mesh =
                subsurf::io::obj::read_file(common::shapes_dir().join(format!("{name}.obj")))
                    .unwrap();
            mesh.uvs.is_some().then_some((name, mesh))
        })
        .collect()
}

fn check_mode(mode: FVarLinearInterpolation) {
    let code = MODES.iter().find(|m| m.0 == mode).unwrap().1;
    let shapes = shapes_with_uvs();
    assert!(
        shapes.len() >= 40,
        "expected the regression shapes with UVs, found {}",
        shapes.len()
    );
    let mut failures = Vec::new();
    let mut report = Vec::new();
    for (name, mesh) in &shapes {
        let level = if mesh.face_indices.len() * 64 <= 20_000 {
            4
        } else {
            3
        };
        match compare(name, mesh, mode, code, level) {
            Ok(w) => report.push(format!(
                "{name:32} {mode:?} levels 1-{level}: max error {w:.2e} of the UV extent"
            )),
            Err(e) => failures.push(e),
        }
    }
    eprintln!("{}", report.join("\n"));
    assert!(
        failures.is_empty(),
        "{} of {} shapes differ:\n{}",
        failures.len(),
        shapes.len(),
        failures.join("\n")
    );
}

#[test]
fn uvs_corners_only_match_opensubdiv() {
    require_osd!();
    check_mode(FVarLinearInterpolation::CornersOnly);
}

#[test]
fn uvs_none_match_opensubdiv() {
    require_osd!();
    check_mode(FVarLinearInterpolation::None);
}

#[test]
fn uvs_corners_plus1_match_opensubdiv() {
    require_osd!();
    check_mode(FVarLinearInterpolation::CornersPlus1);
}

#[test]
fn uvs_corners_plus2_match_opensubdiv() {
    require_osd!();
    check_mode(FVarLinearInterpolation::CornersPlus2);
}

#[test]
fn uvs_boundaries_match_opensubdiv() {
    require_osd!();
    check_mode(FVarLinearInterpolation::Boundaries);
}

#[test]
fn uvs_all_match_opensubdiv() {
    require_osd!();
    check_mode(FVarLinearInterpolation::All);
}

/// Random face-varying topologies (fixed seed): every corner draws its value index from a
/// small pool, so seams, darts, disjoint ("bowtie") values and repeated values around a
/// vertex are everywhere; semi-sharp creases and corners come from the shapes' tags.
#[test]
fn random_uv_topologies_match_opensubdiv() {
    require_osd!();
    let mut failures = Vec::new();
    common::for_random_uv_layouts(
        &[
            "catmark_cube_creases1",
            "catmark_chaikin1",
            "catmark_dart_edgecorner",
            "catmark_edgecorner",
            "catmark_nonman_verts",
            "catmark_nonman_edge100",
            "catmark_pyramid_creases0",
            "catmark_smoothtris0",
            "catmark_hole_test2",
            "catmark_val2_nonman",
        ],
        |name, pool, mesh| {
            for (mode, code) in MODES {
                if let Err(e) = compare(name, mesh, mode, code, 3) {
                    failures.push(format!("pool {pool}: {e}"));
                }
            }
        },
    );
    assert!(
        failures.is_empty(),
        "{} cases differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Face-varying limit values (`PrimvarRefiner::LimitFaceVarying`) at levels 1-2 of every
/// shape with UVs, in every mode, corner for corner.
#[test]
fn limit_uvs_match_opensubdiv() {
    require_osd!();
    let shapes = shapes_with_uvs();
    let mut failures = Vec::new();
    let mut worst = 0.0f32;
    let mut moved = 0usize;
    for (name, mesh) in &shapes {
        for (&(mode, code), level) in MODES.iter().flat_map(|m| (1..=2).map(move |l| (m, l))) {
            let fv = mesh.uvs.as_ref().expect("shape has UVs");
            let extent = uv_extent(&fv.values);
            let m = osd_mesh(mesh, code);
            let osd_levels = osd_ref::refine_uniform(&m, level).unwrap();
            let (values, indices) = osd_levels[level].uvs.clone().expect("OpenSubdiv UVs");
            let osd = osd_ref::OsdRefiner::new(&m, level)
                .and_then(|r| r.limit_fvar(&values))
                .unwrap();
            let refiner = Refiner::new(Topology::new(mesh).unwrap(), level).unwrap();
            let fr = refiner
                .fvar_refinement(&fv.indices, fv.values.len(), mode)
                .unwrap();
            let refined = fr.refine(&fv.values).unwrap();
            let ours = refiner
                .limit_face_varying(&fr, &refined[level].values)
                .unwrap();
            let ours_idx = &refined[level].indices;
            assert_eq!(ours_idx.len(), indices.len(), "{name} {mode:?}");
            for (c, (&i, &j)) in ours_idx.iter().zip(&indices).enumerate() {
                let (a, b) = (ours[i as usize], osd[j as usize]);
                let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) / extent;
                // The limit moved the value (the comparison is not of refined values).
                let r = refined[level].values[i as usize];
                moved += usize::from((a[0] - r[0]).abs().max((a[1] - r[1]).abs()) > 1e-6 * extent);
                if d > 1e-5 {
                    failures.push(format!(
                        "{name} {mode:?} level {level} corner {c}: subsurf {a:?} OpenSubdiv {b:?} ({d:e})"
                    ));
                    break;
                }
                worst = worst.max(d);
            }
        }
    }
    eprintln!(
        "{} shapes x 6 modes x levels 1-2: worst {worst:.2e} of the UV extent, {moved} corners moved by the limit",
        shapes.len()
    );
    assert!(moved > 1000, "the limit left the values in place");
    assert!(
        failures.is_empty(),
        "{} differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
