//! One surface API for every front end: mesh + method (refine | limit | prep) + backend ->
//! triangle mesh with smooth normals, UVs where the method carries them, and a class per
//! triangle (what a renderer colours).
//!
//! ```
//! use subsurf::surface::{build, Colors, Cpu, Method, SurfaceOptions};
//! let mesh = subsurf::shapes::cube();
//! let options = SurfaceOptions { method: Method::Refine { level: 2, limit: false }, ..Default::default() };
//! let s = build(&mesh, &options, &Cpu)?;
//! assert_eq!(s.triangles.len(), 6 * 16 * 2);
//! assert_eq!(s.normals.len(), s.positions.len());
//! # Ok::<(), subsurf::surface::SurfaceError>(())
//! ```
//!
//! On a Loop mesh, `limit` is the Loop limit surface (box-spline patches and Gregory-triangle
//! end caps, `samples` per base edge, triangles, no UVs); `refine` is Loop refinement;
//! `adaptive` and `prep` are Catmull-Clark constructions and are refused
//! ([`SurfaceError::Unsupported`]).
//!
//! The GPU runs behind the same call: [`Backend`] is implemented by `subsurf_gpu::GpuBackend`;
//! this crate knows no GPU.

mod adaptive;
mod backend;
mod limit;
mod loop_limit;
mod prep;
mod refine_mesh;
mod refined;
mod triangulate;

pub use adaptive::{adaptive_surface, tessellate as tessellate_adaptive, Adaptive};
pub use backend::{Backend, Cpu, PrepOutput};
pub use loop_limit::MAX_LOOP_SAMPLES;
pub use refine_mesh::{refine_mesh, refine_mesh_f64};
pub use refined::{corner_uvs, crease_classes};
pub use triangulate::{newell, triangulate, unit, Fans};

use crate::limit::PatchOptions;
use crate::{Error, Mesh, MeshError, Scheme, Topology};

/// Triangle classes (indices into a categorical palette: 0 grey, 1 orange, 2 blue, 3 green,
/// 4 red).
pub mod class {
    /// No particular property.
    pub const PLAIN: u8 = 0;
    /// Next to a semi-sharp crease (0 < s < 10).
    pub const SEMI_SHARP: u8 = 1;
    /// Next to an infinitely sharp crease.
    pub const INF_SHARP: u8 = 4;
    /// A p-rep B-quad (bicubic patch, no perturbation).
    pub const B_QUAD: u8 = 2;
    /// A p-rep patch with the bi-5 perturbation.
    pub const PERTURBED: u8 = 1;
    /// A regular B-spline limit patch of a base face.
    pub const REGULAR: u8 = 2;
    /// A regular B-spline limit patch at an adaptive refinement level.
    pub const ADAPTIVE: u8 = 3;
    /// A single-crease limit patch.
    pub const SINGLE_CREASE: u8 = 1;
    /// A Gregory end-cap limit patch.
    pub const END_CAP: u8 = 4;
}

/// How the surface is made.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// Uniform refinement to `level` (the last level moved to the limit when `limit`).
    Refine {
        /// Refinement steps.
        level: usize,
        /// Move the last level (positions and UVs) to the limit.
        limit: bool,
    },
    /// The limit surface, `samples` per ptex-face side.
    Limit {
        /// Samples per ptex-face side (>= 2).
        samples: usize,
        /// Patch-table options (isolation level, single-crease patches).
        options: PatchOptions,
    },
    /// The limit surface with per-edge rates chosen by `policy` (evaluated on the CPU).
    Adaptive {
        /// How the rates are chosen.
        policy: crate::tess::RatePolicy,
        /// Where the policy came from (a flag, a file), named in errors.
        origin: String,
        /// Patch-table options (isolation level, single-crease patches).
        options: PatchOptions,
    },
    /// The p-rep, `samples` per patch side.
    Prep {
        /// Samples per patch side (>= 2).
        samples: usize,
        /// Keep the bi-5 perturbations.
        perturbed: bool,
    },
}

/// What the triangle classes show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Colors {
    /// All [`class::PLAIN`].
    #[default]
    None,
    /// Refine: faces next to semi-sharp or infinitely sharp creases of the base mesh.
    Sharpness,
    /// Limit: regular / adaptive regular / single-crease / end cap; prep: B-quad / perturbed.
    PatchKind,
    /// Limit: adaptive level of the patch.
    Level,
}

impl Colors {
    /// Whether `method` can show these classes.
    pub fn applies_to(self, method: &Method) -> bool {
        matches!(
            (self, method),
            (Colors::None, _)
                | (Colors::Sharpness, Method::Refine { .. })
                | (
                    Colors::PatchKind | Colors::Level,
                    Method::Limit { .. } | Method::Adaptive { .. }
                )
                | (Colors::PatchKind, Method::Prep { .. })
        )
    }
}

crate::option_value!(Colors, "color_by", {
    None => "none",
    PatchKind => "patch-kind",
    Level => "level",
    Sharpness => "sharpness",
});

/// The name of a [`Method`], as the front ends spell it (`--method`, `method=`): `refine`
/// takes a level, the others samples per side (`--tess`); `prep-bicubic` is the p-rep
/// without its bi-5 perturbations; `limit` with per-edge rates is [`Method::Adaptive`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MethodName {
    /// [`Method::Refine`].
    Refine,
    /// [`Method::Limit`] (or [`Method::Adaptive`] with rates).
    Limit,
    /// [`Method::Prep`] with the perturbations.
    Prep,
    /// [`Method::Prep`] without the perturbations.
    PrepBicubic,
}

crate::option_value!(MethodName, "method", {
    Refine => "refine",
    Limit => "limit",
    Prep => "prep",
    PrepBicubic => "prep-bicubic",
});

impl Method {
    /// The method's name.
    pub fn name(&self) -> MethodName {
        match self {
            Method::Refine { .. } => MethodName::Refine,
            Method::Limit { .. } | Method::Adaptive { .. } => MethodName::Limit,
            Method::Prep {
                perturbed: true, ..
            } => MethodName::Prep,
            Method::Prep {
                perturbed: false, ..
            } => MethodName::PrepBicubic,
        }
    }
}

/// Where a front end runs the numeric work (`--backend`, `backend=`): [`Cpu`], or the GPU
/// (`subsurf_gpu::GpuBackend`, which this crate does not know).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub enum BackendName {
    /// Multithreaded CPU.
    #[default]
    Cpu,
    /// wgpu compute kernels.
    Gpu,
}

crate::option_value!(BackendName, "backend", {
    Cpu => "cpu",
    Gpu => "gpu",
});

/// What to build.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceOptions {
    /// The construction.
    pub method: Method,
    /// The triangle classes (ignored where they do not apply to the method).
    pub colors: Colors,
    /// Also return the base mesh's edges ([`Surface::cage`]).
    pub cage: bool,
}

impl Default for SurfaceOptions {
    fn default() -> Self {
        SurfaceOptions {
            method: Method::Limit {
                samples: 8,
                options: PatchOptions::default(),
            },
            colors: Colors::None,
            cage: false,
        }
    }
}

/// A triangle mesh of the surface.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Surface {
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals (zero where undefined).
    pub normals: Vec<[f32; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// One class per triangle (see [`class`]).
    pub triangle_class: Vec<u8>,
    /// The classes actually computed (`Colors::None` when the request did not apply).
    pub colors: Colors,
    /// UVs of the three corners of each triangle (method refine on meshes with UVs).
    pub corner_uvs: Option<Vec<[[f32; 2]; 3]>>,
    /// The base mesh's edges, when asked for.
    pub cage: Vec<[[f32; 3]; 2]>,
    /// One line on what was built.
    pub summary: String,
    /// Remarks for the user (tags ignored, an extra refinement step).
    pub notes: Vec<String>,
}

/// Errors of [`build`].
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// Bad mesh content or a library failure.
    #[error(transparent)]
    Library(#[from] Error),
    /// The backend failed (for the GPU: no adapter, device lost, out of memory).
    #[error("{backend} backend: {message}")]
    Backend {
        /// The backend's name.
        backend: &'static str,
        /// What failed.
        message: String,
        /// The backend's own error.
        #[source]
        source: Option<Box<dyn std::error::Error + Send + Sync>>,
    },
    /// The backend cannot do what was asked.
    #[error("{0}")]
    Unsupported(String),
}

impl From<MeshError> for SurfaceError {
    fn from(e: MeshError) -> Self {
        SurfaceError::Library(e.into())
    }
}

/// The edges of the base mesh as line segments.
pub fn cage_lines(topo: &Topology, positions: &[[f32; 3]]) -> Vec<[[f32; 3]; 2]> {
    topo.edge_verts
        .iter()
        .map(|&[a, b]| [positions[a as usize], positions[b as usize]])
        .collect()
}

/// Builds the surface of `mesh` as `options` say, its heavy steps on `backend`.
pub fn build(
    mesh: &Mesh,
    options: &SurfaceOptions,
    backend: &dyn Backend,
) -> Result<Surface, SurfaceError> {
    let colors = if options.colors.applies_to(&options.method) {
        options.colors
    } else {
        Colors::None
    };
    let is_loop = mesh.options.scheme == Scheme::Loop;
    let mut s = match &options.method {
        Method::Refine { level, limit } => refined::refined(mesh, *level, *limit, colors, backend)?,
        Method::Limit { samples, options } if is_loop => {
            loop_limit::loop_limit(mesh, *samples, options, colors, backend)?
        }
        Method::Limit { samples, options } => {
            limit::limit(mesh, *samples, options, colors, backend)?
        }
        Method::Adaptive { origin, .. } if is_loop => {
            return Err(SurfaceError::Unsupported(format!(
                "{origin}: adaptive tessellation rates are implemented for the Catmull-Clark \
                 limit surface only; the Loop limit surface takes a uniform rate"
            )))
        }
        Method::Prep { .. } if is_loop => {
            return Err(SurfaceError::Unsupported(
                "the p-rep is built from Catmull-Clark quads; a Loop mesh has none \
                 (use the limit or refine method)"
                    .into(),
            ))
        }
        Method::Adaptive {
            policy,
            origin,
            options,
        } => adaptive::adaptive(mesh, policy, origin, options, colors, backend)?,
        Method::Prep { samples, perturbed } => {
            prep::prep(mesh, *samples, *perturbed, colors, backend)?
        }
    };
    s.colors = colors;
    if options.cage {
        s.cage = cage_lines(&Topology::new(mesh)?, &mesh.positions);
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_gives_consistent_triangles() {
        let mesh = crate::shapes::cube();
        for method in [
            Method::Refine {
                level: 2,
                limit: true,
            },
            Method::Limit {
                samples: 5,
                options: PatchOptions::default(),
            },
            Method::Prep {
                samples: 5,
                perturbed: true,
            },
        ] {
            let o = SurfaceOptions {
                method,
                colors: Colors::PatchKind,
                cage: true,
            };
            let s = build(&mesh, &o, &Cpu).unwrap();
            assert_eq!(s.normals.len(), s.positions.len());
            assert_eq!(s.triangle_class.len(), s.triangles.len());
            assert_eq!(s.cage.len(), 12);
            let n = s.positions.len() as u32;
            assert!(s.triangles.iter().flatten().all(|&i| i < n));
            // The cube's surfaces are convex and centred at the origin: normals point out.
            for (p, nn) in s.positions.iter().zip(&s.normals) {
                let d = p[0] * nn[0] + p[1] * nn[1] + p[2] * nn[2];
                assert!(d > 0.0, "{o:?}: {p:?} {nn:?}");
            }
        }
    }

    #[test]
    fn refined_uvs_follow_the_corners() {
        // Linear UV interpolation of the bilinear grid: refined UVs are the linear map of
        // the refined positions.
        let mut mesh = crate::shapes::grid(2, 2);
        mesh.options.scheme = crate::Scheme::Bilinear;
        mesh.options.uv_interpolation = crate::FVarLinearInterpolation::All;
        let (lo, hi) = mesh.bounding_box().unwrap();
        let values: Vec<[f32; 2]> = mesh
            .positions
            .iter()
            .map(|p| {
                [
                    (p[0] - lo[0]) / (hi[0] - lo[0]),
                    (p[1] - lo[1]) / (hi[1] - lo[1]),
                ]
            })
            .collect();
        mesh.uvs = Some(crate::FaceVarying {
            values,
            indices: mesh.face_indices.clone(),
        });
        let o = SurfaceOptions {
            method: Method::Refine {
                level: 2,
                limit: false,
            },
            ..Default::default()
        };
        let s = build(&mesh, &o, &Cpu).unwrap();
        let uvs = s.corner_uvs.unwrap();
        assert_eq!(uvs.len(), s.triangles.len());
        for (t, uv) in s.triangles.iter().zip(&uvs) {
            for k in 0..3 {
                let p = s.positions[t[k] as usize];
                let want = [
                    (p[0] - lo[0]) / (hi[0] - lo[0]),
                    (p[1] - lo[1]) / (hi[1] - lo[1]),
                ];
                assert!((uv[k][0] - want[0]).abs() < 1e-5 && (uv[k][1] - want[1]).abs() < 1e-5);
            }
        }
    }
}
