//! `subsurf render`: a PNG image of a subdivision surface, rendered headlessly with wgpu.
//!
//! Methods: `refine` (uniform refinement to `--level`, triangulated), `prep` (the p-rep
//! of Myles, Yeo and Peters 2008, `--tess` samples per patch side) and `prep-bicubic` (the
//! p-rep without its bi-5 perturbations). Colouring by `sharpness`
//! marks the faces next to tagged creases of the base mesh (orange: semi-sharp, red:
//! infinitely sharp); `patch-kind` on a p-rep marks B-quads (blue) and perturbed patches
//! (orange), as in the paper's Figure 7. `limit` tessellates the limit surface's patches
//! (`--tess` samples per ptex-face side); `patch-kind` colours regular patches of base faces
//! (blue), regular patches at adaptive levels (green), single-crease patches (orange) and
//! Gregory end caps (red); `level` colours by adaptive level (palette order: grey 0, orange
//! 1, blue 2, green 3, red 4, ...). With `--tolerance`, `--max-edge-length`, `--pixels` (the
//! image's own camera) or `--edge-rates`, `limit` takes per-edge rates instead.
//!
//! On a Loop mesh (`--scheme loop`, the `loop_` prefix or the file's tag), `refine` is Loop
//! refinement and `limit` the Loop limit surface evaluated on the CPU (`--tess` samples per
//! base edge; `patch-kind`: box splines of base faces blue, at adaptive levels green,
//! Gregory-triangle end caps red); per-edge rates and `prep` are Catmull-Clark constructions
//! and are refused.

use crate::common::{option_parser, read_mesh_with, SchemeArgs};
use crate::progress::{note, quiet, Progress};
use anyhow::{bail, Context};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use subsurf::surface::{Colors, Method as SurfaceMethod, SurfaceOptions};
use subsurf::Mesh;
use subsurf_render::{Fit, Gpu, RenderMesh, RenderOptions, RgbaImage, UpAxis, View};

/// How the surface is turned into triangles: `refine` (uniform refinement to `--level`),
/// `limit` (limit patches, `--tess` samples per patch side), `prep` (the p-rep, `--tess`
/// samples per patch side) or `prep-bicubic` (the p-rep without its bi-5 perturbations).
pub use subsurf::surface::MethodName as Method;

/// Image options shared by `render` and `compare`.
#[derive(Debug, Clone, clap::Args)]
pub struct LookArgs {
    /// Draw the control cage (base mesh edges) over the surface.
    #[arg(long)]
    pub cage: bool,
    /// Face colouring: patch-kind (limit: regular blue, adaptive-level regular green, single
    /// crease orange, end cap red; p-rep: B-quad blue, perturbed orange), level (adaptive level
    /// of the limit patch), sharpness (faces next to semi-sharp (orange) and infinitely sharp
    /// (red) creases of the base mesh).
    #[arg(long, value_parser = option_parser::<Colors>(), default_value_t = Colors::None)]
    pub color_by: Colors,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    pub size: (u32, u32),
    /// View direction.
    #[arg(long, value_parser = option_parser::<View>(), default_value_t = View::Iso)]
    pub view: View,
    /// Model axis pointing up.
    #[arg(long, value_parser = option_parser::<UpAxis>(), default_value_t = UpAxis::Y)]
    pub up: UpAxis,
    /// Background: white, black, transparent or RRGGBB.
    #[arg(long, default_value = "white", value_parser = subsurf_render::parse_background)]
    pub background: [u8; 4],
    /// Cage line width in pixels.
    #[arg(long, default_value_t = 1.5)]
    pub line_width: f32,
    /// Framing: `tight` fits the model's points, `sphere` its bounding sphere (the same
    /// distance from every view).
    #[arg(long, value_parser = option_parser::<Fit>(), default_value_t = Fit::Tight)]
    pub fit: Fit,
}

/// Render a subdivision surface to PNG.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Input mesh: .obj (with OpenSubdiv's tags), .ply, .gltf, .glb or a USD stage (.usda,
    /// .usdc, .usdz: every mesh prim placed by its transforms, or `--prim`); `-` reads OBJ,
    /// PLY or GLB from standard input.
    pub input: PathBuf,
    /// Output image (.png; `-` writes the PNG to standard output).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Surface construction.
    #[arg(long, value_parser = option_parser::<Method>(), default_value_t = Method::Refine)]
    pub method: Method,
    /// Refinement level (method refine).
    #[arg(short, long, conflicts_with = "tess")]
    pub level: Option<usize>,
    /// Samples per patch side (methods limit, prep and prep-bicubic).
    #[arg(long)]
    pub tess: Option<usize>,
    /// The older spelling of `--method prep-bicubic` (hidden; read for one release).
    #[arg(long, hide = true)]
    pub no_perturbation: bool,
    #[command(flatten)]
    pub look: LookArgs,
    #[command(flatten)]
    pub scheme: SchemeArgs,
    /// Per-edge rates of `--method limit` (the camera of `--pixels` is the image's).
    #[command(flatten)]
    pub adaptive: crate::tess_args::AdaptiveArgs,
}

/// `WxH` to `(W, H)`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("size '{s}' is not WIDTHxHEIGHT"))?;
    let p = |t: &str| {
        t.trim()
            .parse::<u32>()
            .ok()
            .filter(|&v| (1..=16384).contains(&v))
            .ok_or_else(|| format!("size '{s}': '{t}' is not a number in 1..=16384"))
    };
    Ok((p(w)?, p(h)?))
}

impl LookArgs {
    /// Renderer options for these arguments.
    pub fn options(&self) -> RenderOptions {
        RenderOptions {
            width: self.size.0,
            height: self.size.1,
            view: self.view,
            up: self.up,
            background: self.background,
            line_width: self.line_width,
            fit: self.fit,
            ..Default::default()
        }
    }
}

/// One surface to draw: mesh, method and level or tessellation rate.
#[derive(Debug, Clone)]
pub struct SurfaceSpec {
    /// Mesh file.
    pub path: PathBuf,
    /// Construction.
    pub method: Method,
    /// Level (refine) or tessellation rate (limit, prep).
    pub level: usize,
    /// Method limit: per-edge rates instead of `level` samples per side.
    pub adaptive: Option<crate::tess_args::AdaptiveArgs>,
}

/// Builds the triangles of `spec` for `mesh`.
pub fn build(
    mesh: &Mesh,
    spec: &SurfaceSpec,
    look: &LookArgs,
    progress: &Progress,
) -> anyhow::Result<RenderMesh> {
    let color_by = match (spec.method, look.color_by) {
        (Method::Refine, c @ (Colors::Level | Colors::PatchKind))
        | (Method::Prep | Method::PrepBicubic, c @ (Colors::Level | Colors::Sharpness))
        | (Method::Limit, c @ Colors::Sharpness) => {
            note(format!(
                "--color-by {c} is not available with --method {}; drawing without colours",
                spec.method
            ));
            Colors::None
        }
        (_, c) => c,
    };
    let (method, what) = match spec.method {
        Method::Refine => (
            SurfaceMethod::Refine {
                level: spec.level,
                limit: false,
            },
            format!("refining {} to level {}", spec.path.display(), spec.level),
        ),
        Method::Prep | Method::PrepBicubic => (
            SurfaceMethod::Prep {
                samples: spec.level,
                perturbed: spec.method == Method::Prep,
            },
            format!(
                "p-rep of {} at {} samples per side",
                spec.path.display(),
                spec.level
            ),
        ),
        Method::Limit if spec.adaptive.as_ref().is_some_and(|a| a.any()) => {
            let args = spec.adaptive.as_ref().expect("checked");
            let camera =
                crate::tess_args::screen_camera(look.size, look.view, look.up, &mesh.positions);
            let topo = subsurf::Topology::new(mesh)?;
            let (policy, origin) = args.policy(camera, &topo, spec.level)?;
            let what = format!(
                "adaptive limit surface of {} ({origin})",
                spec.path.display()
            );
            (
                SurfaceMethod::Adaptive {
                    policy,
                    origin,
                    options: Default::default(),
                },
                what,
            )
        }
        Method::Limit => (
            SurfaceMethod::Limit {
                samples: spec.level,
                options: Default::default(),
            },
            format!(
                "limit surface of {} at {} samples per side",
                spec.path.display(),
                spec.level
            ),
        ),
    };
    progress.stage(what);
    let options = SurfaceOptions {
        method,
        colors: color_by,
        cage: look.cage,
    };
    let surface = subsurf::surface::build(mesh, &options, &subsurf::surface::Cpu)
        .with_context(|| format!("building the surface of {}", spec.path.display()))?;
    for n in &surface.notes {
        note(n.as_str());
    }
    if !quiet() && spec.method != Method::Refine {
        crate::say!("{}", surface.summary);
    }
    Ok(surface.into())
}

/// Reads and builds the triangles of one surface.
pub fn prepare_spec(
    spec: &SurfaceSpec,
    look: &LookArgs,
    scheme: &SchemeArgs,
    progress: &Progress,
) -> anyhow::Result<RenderMesh> {
    // A USD stage renders whole: every mesh prim (or --prim) placed by its transforms.
    let mut mesh = if crate::usd_stage::is_usd(&spec.path) {
        crate::usd_stage::read_mesh(&spec.path, scheme.prim.as_deref(), true)?
    } else {
        read_mesh_with(&spec.path, scheme.flatten)?
    };
    scheme.apply(&mut mesh);
    build(&mesh, spec, look, progress)
}

/// Renders prepared triangles on `gpu`.
pub fn render_prepared(
    gpu: &Gpu,
    rm: &RenderMesh,
    look: &LookArgs,
    progress: &Progress,
) -> anyhow::Result<RgbaImage> {
    progress.stage(format!("rendering {} triangles", rm.num_triangles()));
    Ok(subsurf_render::render_with(gpu, rm, &look.options())?)
}

/// Opens the GPU with a hint on failure.
pub fn open_gpu() -> anyhow::Result<Gpu> {
    subsurf_render::open().context("opening a GPU adapter for rendering")
}

/// Writes a PNG, with the path in the error.
pub fn save(image: &RgbaImage, path: &Path) -> anyhow::Result<()> {
    let mut w = crate::common::create_output(path)?;
    image
        .write_png(&mut w)
        .map_err(anyhow::Error::from)
        .and_then(|_| Ok(w.flush()?))
        .with_context(|| format!("writing {}", crate::common::shown(path, true)))
}

pub fn run(a: &RenderArgs) -> anyhow::Result<()> {
    crate::common::check_output_ext(&a.output, "png")?;
    let level = match (a.method, a.level, a.tess) {
        (Method::Refine, _, Some(_)) => {
            bail!("--tess applies to --method limit|prep|prep-bicubic; use --level")
        }
        (Method::Refine, l, None) => l.unwrap_or(3),
        (_, Some(_), _) => bail!("--level applies to --method refine; use --tess"),
        (_, None, t) => t.unwrap_or(8),
    };
    let method = match a.method {
        Method::Prep if a.no_perturbation => Method::PrepBicubic,
        _ if a.no_perturbation => bail!("--no-perturbation applies to --method prep"),
        m => m,
    };
    if a.adaptive.any() && a.method != Method::Limit {
        bail!("--tolerance, --max-edge-length, --pixels and --edge-rates apply to --method limit");
    }
    let spec = SurfaceSpec {
        path: a.input.clone(),
        method,
        level,
        adaptive: Some(a.adaptive.clone()),
    };
    let progress = Progress::start("reading");
    let rm = prepare_spec(&spec, &a.look, &a.scheme, &progress)?;
    progress.stage("opening the GPU");
    let gpu = open_gpu()?;
    let image = render_prepared(&gpu, &rm, &a.look, &progress)?;
    let tris = rm.num_triangles();
    progress.stage("writing PNG");
    save(&image, &a.output)?;
    drop(progress);
    crate::say!(
        "rendered {} triangles ({}, {}) at {}x{} on {} -> {}",
        tris,
        method,
        level,
        image.width,
        image.height,
        subsurf_render::describe(&gpu),
        crate::common::shown(&a.output, true)
    );
    Ok(())
}
