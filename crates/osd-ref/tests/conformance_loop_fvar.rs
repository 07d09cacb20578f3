//! Face-varying (UV) data under Loop refinement against OpenSubdiv 3.5
//! (`PrimvarRefiner::InterpolateFaceVarying` and `LimitFaceVarying` with `Sdc::SCHEME_LOOP`):
//! every `loop_*` regression shape with UVs at levels 1–2 (3 for small shapes), every
//! `FVarLinearInterpolation` mode, the same value topology (values per level, value index at
//! each face corner) and the values corner for corner within 1e-6 of the UV extent; random
//! seams on a few shapes; the limit of the values at level 2.

#[macro_use]
mod common;

use subsurf::{FVarLinearInterpolation, Mesh, Refiner, Scheme, Topology};

use common::{osd_mesh, uv_extent, MODES};

/// Compares one shape in one mode at levels 1..=`max_level`: value counts, value indices at
/// every corner, values. Returns the worst error relative to the UV extent.
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
        let at = format!("{name} {mode:?} level {level}");
        if s.values.len() != values.len() {
            return Err(format!(
                "{at}: {} values vs {}",
                s.values.len(),
                values.len()
            ));
        }
        if s.indices != *indices {
            let c = s.indices.iter().zip(indices).position(|(a, b)| a != b);
            return Err(format!(
                "{at}: value indices differ (first at corner {c:?})"
            ));
        }
        for (c, (&i, &j)) in s.indices.iter().zip(indices).enumerate() {
            let (a, b) = (s.values[i as usize], values[j as usize]);
            let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) / extent;
            if d > 1e-6 {
                return Err(format!(
                    "{at} corner {c} (face {}): subsurf {a:?} OpenSubdiv {b:?} (error {d:e})",
                    c / 3
                ));
            }
            worst = worst.max(d);
        }
    }
    Ok(worst)
}

fn loop_shapes_with_uvs() -> Vec<(String, Mesh)> {
    common::shape_names(&["loop_"])
        .into_iter()
        .filter_map(|name| {
            let mesh =
                subsurf::io::obj::read_file(common::shapes_dir().join(format!("{name}.obj")))
                    .unwrap();
            assert_eq!(mesh.options.scheme, Scheme::Loop, "{name}");
            mesh.uvs.is_some().then_some((name, mesh))
        })
        .collect()
}

fn check_modes(modes: &[(FVarLinearInterpolation, u8)]) {
    let shapes = loop_shapes_with_uvs();
    assert!(
        shapes.len() >= 25,
        "expected the Loop regression shapes with UVs, found {}",
        shapes.len()
    );
    let mut failures = Vec::new();
    let mut report = Vec::new();
    for &(mode, code) in modes {
        for (name, mesh) in &shapes {
            let level = if mesh.face_indices.len() * 16 <= 6_000 {
                3
            } else {
                2
            };
            match compare(name, mesh, mode, code, level) {
                Ok(w) => report.push(format!(
                    "{name:28} {mode:?} levels 1-{level}: max error {w:.2e} of the UV extent"
                )),
                Err(e) => failures.push(e),
            }
        }
    }
    eprintln!("{}", report.join("\n"));
    assert!(
        failures.is_empty(),
        "{} cases differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn loop_uvs_smooth_modes_match_opensubdiv() {
    require_osd!();
    check_modes(&MODES[..4]);
}

#[test]
fn loop_uvs_linear_modes_match_opensubdiv() {
    require_osd!();
    check_modes(&MODES[4..]);
}

/// Random face-varying topologies (fixed seed): each corner draws its value index from a
/// small pool, so seams, darts, disjoint values and repeated values around a vertex are
/// everywhere; semi-sharp creases and corners come from the shapes' tags.
#[test]
fn loop_random_uv_topologies_match_opensubdiv() {
    require_osd!();
    let mut failures = Vec::new();
    common::for_random_uv_layouts(
        &[
            "loop_cube_creases1",
            "loop_cubes_semisharp",
            "loop_icos_semisharp",
            "loop_chaikin1",
            "loop_nonman_verts",
            "loop_nonman_edges",
            "loop_triangle_edgecorner",
            "loop_xord_boundary",
        ],
        |name, pool, mesh| {
            for (mode, code) in MODES {
                if let Err(e) = compare(name, mesh, mode, code, 2) {
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

/// Face-varying limit values (`PrimvarRefiner::LimitFaceVarying`) at level 2 of every Loop
/// shape with UVs, in every mode, corner for corner.
#[test]
fn loop_limit_uvs_match_opensubdiv() {
    require_osd!();
    let level = 2;
    let mut failures = Vec::new();
    let mut worst = 0.0f32;
    let mut moved = 0usize;
    for (name, mesh) in &loop_shapes_with_uvs() {
        for (mode, code) in MODES {
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
            assert_eq!(ours_idx, &indices, "{name} {mode:?}");
            for (c, (&i, &j)) in ours_idx.iter().zip(&indices).enumerate() {
                let (a, b) = (ours[i as usize], osd[j as usize]);
                let d = (a[0] - b[0]).abs().max((a[1] - b[1]).abs()) / extent;
                let r = refined[level].values[i as usize];
                moved += usize::from((a[0] - r[0]).abs().max((a[1] - r[1]).abs()) > 1e-6 * extent);
                if d > 1e-6 {
                    failures.push(format!(
                        "{name} {mode:?} corner {c}: subsurf {a:?} OpenSubdiv {b:?} ({d:e})"
                    ));
                    break;
                }
                worst = worst.max(d);
            }
        }
    }
    eprintln!("6 modes at level {level}: worst {worst:.2e} of the UV extent, {moved} corners moved by the limit");
    assert!(moved > 1000, "the limit left the values in place");
    assert!(
        failures.is_empty(),
        "{} differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
