//! The limit method on a Loop mesh: the Loop limit surface (quartic box-spline patches and
//! Gregory-triangle end caps, [`crate::limit::loop_eval`]) tessellated watertight with
//! `samples − 1` segments per base edge ([`crate::limit::loop_tessellate`]), one class per
//! triangle from the patch under its centroid (found through the triangle patch map).
//!
//! No UVs: face-varying data is not evaluated on Loop limit patches (the Catmull-Clark limit
//! method carries none either); `refine` refines a Loop mesh's UVs.

use super::{class, Backend, Colors, Surface, SurfaceError};
use crate::limit::loop_eval::{LoopLimit, LoopPatch};
use crate::limit::loop_tessellate::triangle_centres;
use crate::limit::PatchOptions;
use crate::{Error, Mesh, Topology};

/// Most samples per base edge (the tessellation's 1024 segments).
pub const MAX_LOOP_SAMPLES: usize = 1025;

/// The class of Loop patch `p` for `colors`: its depth (`Level`), or box spline of a base
/// face / box spline at an adaptive level / Gregory-triangle end cap (`PatchKind`).
pub(super) fn loop_patch_class(p: &LoopPatch, colors: Colors) -> u8 {
    let level = p.param.depth();
    match colors {
        Colors::Level => level,
        Colors::PatchKind if !p.regular => class::END_CAP,
        Colors::PatchKind if level == 0 => class::REGULAR,
        Colors::PatchKind => class::ADAPTIVE,
        _ => class::PLAIN,
    }
}

/// The Loop limit surface of `mesh` with `samples` per base edge (`2..=1025`), isolated to
/// `options.isolation_level` (single-crease patches are quad patches: the option is not
/// used), tessellated on `backend`. The patch points are refined in `f64` from positions the
/// mesh holds in `f64`, else in `f32` ([`LoopLimit::at_precision`]).
pub fn loop_limit(
    mesh: &Mesh,
    samples: usize,
    options: &PatchOptions,
    colors: Colors,
    backend: &dyn Backend,
) -> Result<Surface, SurfaceError> {
    if !(2..=MAX_LOOP_SAMPLES).contains(&samples) {
        return Err(Error::Unsupported(format!(
            "{samples} samples per edge of the Loop limit surface (2..={MAX_LOOP_SAMPLES})"
        ))
        .into());
    }
    let topo = Topology::new(mesh)?;
    let limit = LoopLimit::at_precision(&topo, &mesh.positions, options.isolation_level)?;
    let segments = samples - 1;
    let tess = backend.loop_limit(&limit, &topo, segments)?;
    let centres = triangle_centres(&topo, segments);
    if centres.len() != tess.triangles.len() {
        return Err(Error::Internal(format!(
            "Loop limit tessellation: {} triangles for {} centres",
            tess.triangles.len(),
            centres.len()
        ))
        .into());
    }
    let triangle_class = centres
        .iter()
        .map(|&(f, [u, v])| {
            limit
                .find(f as usize, u, v)
                .map_or(class::PLAIN, |p| loop_patch_class(p, colors))
        })
        .collect();
    let (out, normals) = tess.to_mesh();
    let regular = limit.patches.iter().filter(|p| p.regular).count();
    Ok(Surface {
        summary: format!(
            "Loop limit: {} box-spline, {} Gregory-triangle end-cap patches on {} faces, \
             {segments} segments per edge",
            regular,
            limit.patches.len() - regular,
            topo.num_faces()
        ),
        triangles: out
            .face_indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        positions: out.positions.into_f32(),
        normals,
        triangle_class,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::super::{build, Cpu, Method, SurfaceOptions};
    use super::*;
    use crate::Scheme;

    fn icosahedron() -> Mesh {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../testdata/shapes/loop_icosahedron.obj"
        );
        let mut mesh = crate::io::obj::read_file(std::path::Path::new(path)).unwrap();
        mesh.options.scheme = Scheme::Loop;
        mesh
    }

    fn options(samples: usize, isolation: u32, colors: Colors) -> SurfaceOptions {
        SurfaceOptions {
            method: Method::Limit {
                samples,
                options: PatchOptions {
                    isolation_level: isolation,
                    ..Default::default()
                },
            },
            colors,
            cage: true,
        }
    }

    #[test]
    fn build_gives_the_loop_limit_tessellation() {
        let mesh = icosahedron();
        let s = build(&mesh, &options(9, 3, Colors::None), &Cpu).unwrap();
        let topo = Topology::new(&mesh).unwrap();
        // The file's digits are not all `f32` values: the points are refined in `f64`.
        assert!(mesh.positions.is_f64());
        let limit = LoopLimit::at_precision(&topo, &mesh.positions, 3).unwrap();
        let (want, normals) = limit.tessellate(&topo, 8).unwrap().to_mesh();
        assert_eq!(s.positions, want.positions);
        assert_eq!(s.normals, normals);
        assert_eq!(s.triangles.concat(), want.face_indices);
        assert_eq!(s.triangles.len(), 20 * 64);
        assert_eq!(s.triangle_class.len(), s.triangles.len());
        assert!(s.triangle_class.iter().all(|&c| c == class::PLAIN));
        assert_eq!(s.cage.len(), 30);
        assert!(s.corner_uvs.is_none());
        // The icosahedron is convex and centred at the origin: the normals point out.
        for (p, n) in s.positions.iter().zip(&s.normals) {
            assert!(p[0] * n[0] + p[1] * n[1] + p[2] * n[2] > 0.0, "{p:?} {n:?}");
        }
    }

    #[test]
    fn triangles_are_classed_by_the_patch_under_their_centre() {
        // Every icosahedron vertex has valence 5: isolated to level 3, the patches at the
        // corners are Gregory-triangle end caps at depth 3, the rest box splines at depths
        // 1..=3 (every base triangle has extraordinary corners, none stays whole).
        let mesh = icosahedron();
        let kind = build(&mesh, &options(17, 3, Colors::PatchKind), &Cpu).unwrap();
        let level = build(&mesh, &options(17, 3, Colors::Level), &Cpu).unwrap();
        let count = |k: u8| kind.triangle_class.iter().filter(|&&x| x == k).count();
        assert!(count(class::END_CAP) > 0 && count(class::ADAPTIVE) > 0);
        assert_eq!(count(class::REGULAR), 0);
        assert_eq!(
            count(class::END_CAP) + count(class::ADAPTIVE),
            kind.triangles.len()
        );
        assert!(level.triangle_class.iter().all(|&l| (1..=3).contains(&l)));
        for (&k, &l) in kind.triangle_class.iter().zip(&level.triangle_class) {
            if k == class::END_CAP {
                assert_eq!(l, 3);
            }
        }
        // The first triangle of face 0 touches its corner 0 (an end cap); the centroid of
        // each triangle lies on the patch that the triangle's corners were sampled from:
        // the surface at the centre is within the triangle's size of its corners' mean.
        assert_eq!(kind.triangle_class[0], class::END_CAP);
        let topo = Topology::new(&mesh).unwrap();
        let limit = LoopLimit::new(&topo, &mesh.positions, 3).unwrap();
        for (t, &(f, [u, v])) in kind.triangles.iter().zip(&triangle_centres(&topo, 16)) {
            let p = limit.eval(f as usize, u, v).unwrap().p;
            let c: Vec<[f64; 3]> = t
                .iter()
                .map(|&i| kind.positions[i as usize].map(f64::from))
                .collect();
            let mean = [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0);
            let size = (0..3)
                .map(|k| {
                    (0..3)
                        .map(|a| (c[k][a] - c[(k + 1) % 3][a]).powi(2))
                        .sum::<f64>()
                })
                .fold(0.0, f64::max)
                .sqrt();
            let d = (0..3).map(|a| (p[a] - mean[a]).powi(2)).sum::<f64>().sqrt();
            assert!(d < 0.1 * size, "face {f} ({u}, {v}): {d} vs {size}");
        }
    }

    #[test]
    fn constructions_without_a_loop_form_are_refused() {
        let mesh = icosahedron();
        for method in [
            Method::Adaptive {
                policy: crate::tess::RatePolicy::Uniform(4),
                origin: "--tess".into(),
                options: PatchOptions::default(),
            },
            Method::Prep {
                samples: 4,
                perturbed: true,
            },
        ] {
            let o = SurfaceOptions {
                method,
                ..Default::default()
            };
            match build(&mesh, &o, &Cpu) {
                Err(SurfaceError::Unsupported(m)) => assert!(m.contains("Loop"), "{m}"),
                other => panic!("{o:?}: {other:?}"),
            }
        }
        for samples in [0, 1, MAX_LOOP_SAMPLES + 1] {
            let e = build(&mesh, &options(samples, 2, Colors::None), &Cpu).unwrap_err();
            assert!(e.to_string().contains("samples per edge"), "{e}");
        }
    }
}
