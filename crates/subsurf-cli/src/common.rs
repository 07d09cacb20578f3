//! Options shared by several subcommands.

use anyhow::Context;
use std::io::{Read, Write};
use std::path::Path;
use std::sync::OnceLock;
use subsurf::io::Format;
use subsurf::OptionValue;
use subsurf::{BoundaryInterpolation, CreaseMethod, Mesh, Scheme, TriangleSubdivision};

/// The parser of an option flag: the option's names ([`OptionValue`], one per value, as in
/// `docs/vocabulary.md`) as clap's possible values, shown in `--help` and listed in errors.
pub fn option_parser<T: OptionValue>() -> impl clap::builder::TypedValueParser<Value = T> {
    use clap::builder::TypedValueParser as _;
    clap::builder::PossibleValuesParser::new(T::names())
        .map(|s: String| T::from_name(&s).expect("one of the possible values"))
}

/// Scheme and crease options that override what the input file says.
#[derive(Debug, Clone, clap::Args)]
pub struct SchemeArgs {
    /// Boundary interpolation (default: from the file's tags, else edge-only).
    #[arg(long, value_parser = option_parser::<BoundaryInterpolation>())]
    pub boundary: Option<BoundaryInterpolation>,
    /// Crease decay method (default: from the file's tags, else uniform).
    #[arg(long, value_parser = option_parser::<CreaseMethod>())]
    pub crease_method: Option<CreaseMethod>,
    /// Subdivision scheme (default: from the file name prefix, else catmark).
    #[arg(long, value_parser = option_parser::<Scheme>())]
    pub scheme: Option<Scheme>,
    /// Triangle rule for Catmull-Clark (default: from the file's tags, else catmark).
    #[arg(long, alias = "triangles", value_parser = option_parser::<TriangleSubdivision>())]
    pub triangle_subdivision: Option<TriangleSubdivision>,
    /// glTF and USD input: apply node (prim) transforms and merge every mesh of the scene
    /// in world space (default: each mesh in its own coordinates, an error when the scene
    /// places several meshes under different transforms).
    #[arg(long)]
    pub flatten: bool,
    /// USD input: the mesh prim to use (e.g. `/World/Body`; default: the stage's only mesh
    /// prim; `refine` and `render` default to all of them).
    #[arg(long)]
    pub prim: Option<String>,
}

impl SchemeArgs {
    /// Reads a mesh file and applies the overrides.
    pub fn read(&self, path: &Path) -> anyhow::Result<Mesh> {
        let mut mesh = if crate::usd_stage::is_usd(path) {
            crate::usd_stage::read_mesh(path, self.prim.as_deref(), self.flatten)?
        } else {
            read_mesh_with(path, self.flatten)?
        };
        self.apply(&mut mesh);
        Ok(mesh)
    }

    /// Applies the overrides to `mesh`.
    pub fn apply(&self, mesh: &mut Mesh) {
        let o = &mut mesh.options;
        if let Some(b) = self.boundary {
            o.boundary = b;
        }
        if let Some(c) = self.crease_method {
            o.crease_method = c;
        }
        if let Some(s) = self.scheme {
            o.scheme = s;
        }
        if let Some(t) = self.triangle_subdivision {
            o.triangle_subdivision = t;
        }
    }
}

/// The path that stands for standard input (as input) or standard output (as `-o`).
pub const STDIO: &str = "-";

/// Whether `path` is `-` (standard input or output).
pub fn is_stdio(path: &Path) -> bool {
    path.as_os_str() == STDIO
}

/// The format of mesh output to standard output (`--format`, OBJ by default).
static STDOUT_FORMAT: OnceLock<Format> = OnceLock::new();

/// Mesh formats `--format` accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FormatArg {
    /// Wavefront OBJ with OpenSubdiv's tags.
    Obj,
    /// Binary PLY.
    Ply,
    /// Binary glTF 2.0.
    Glb,
}

/// The global `--keep-holes`: mesh output writes hole faces tagged instead of leaving them out.
static KEEP_HOLES: OnceLock<bool> = OnceLock::new();

/// Sets the global `--keep-holes`.
pub fn set_keep_holes(keep: bool) {
    let _ = KEEP_HOLES.set(keep);
}

/// Whether mesh output writes positions held in `f64` as `f64` where the format has the
/// choice (USD `point3d[]`): set by a command's `--f64`.
static F64_OUTPUT: OnceLock<bool> = OnceLock::new();

/// Sets the output precision of a command run with `--f64`.
pub fn set_f64_output(f64: bool) {
    let _ = F64_OUTPUT.set(f64);
}

/// How mesh output is written (the global `--keep-holes`, a command's `--f64`).
pub fn write_options() -> subsurf::io::WriteOptions {
    subsurf::io::WriteOptions {
        keep_holes: *KEEP_HOLES.get().unwrap_or(&false),
        f64: *F64_OUTPUT.get().unwrap_or(&false),
    }
}

/// `mesh` as mesh output writes it: without its hole faces unless `--keep-holes` is given
/// (for writers outside [`write_mesh`], such as a USD stage's).
pub fn output_mesh(mesh: &subsurf::Mesh) -> std::borrow::Cow<'_, subsurf::Mesh> {
    write_options().mesh_to_write(mesh)
}

/// Sets the format of `-o -` (the global `--format`).
pub fn set_stdout_format(f: Option<FormatArg>) {
    let f = match f {
        None | Some(FormatArg::Obj) => Format::Obj,
        Some(FormatArg::Ply) => Format::Ply,
        Some(FormatArg::Glb) => Format::Glb,
    };
    let _ = STDOUT_FORMAT.set(f);
}

/// How a path is named in messages (`standard input/output` for `-`).
pub fn shown(path: &Path, output: bool) -> String {
    match (is_stdio(path), output) {
        (true, true) => "standard output".into(),
        (true, false) => "standard input".into(),
        (false, _) => path.display().to_string(),
    }
}

/// Checks, before any work, that a mesh can be written to `path` (its extension names a
/// format subsurf writes, its folder exists); `-` is standard output.
pub fn check_mesh_output(path: &Path) -> anyhow::Result<()> {
    if is_stdio(path) {
        return Ok(());
    }
    let format = Format::from_path(path).with_context(|| format!("output {}", path.display()))?;
    anyhow::ensure!(
        format.writable(),
        "output {}: subsurf writes glTF as .glb, not .gltf",
        path.display()
    );
    check_folder(path)
}

/// Checks, before any work, that `path`'s extension is `ext` (case-insensitive) and its folder
/// exists; `-` is standard output.
pub fn check_output_ext(path: &Path, ext: &str) -> anyhow::Result<()> {
    if is_stdio(path) {
        return Ok(());
    }
    let e = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    anyhow::ensure!(
        e.eq_ignore_ascii_case(ext),
        "output {}: expected a .{ext} file name",
        path.display()
    );
    check_folder(path)
}

/// Checks, before any work, that the folder of output `path` exists (`-`: standard output).
pub fn check_output_folder(path: &Path) -> anyhow::Result<()> {
    if is_stdio(path) {
        return Ok(());
    }
    check_folder(path)
}

fn check_folder(path: &Path) -> anyhow::Result<()> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.is_dir() => {
            anyhow::bail!("output {}: no folder {}", path.display(), dir.display())
        }
        _ => Ok(()),
    }
}

/// Reads a mesh file, with the path in the error. `-` reads standard input: PLY when it starts
/// with the `ply` magic line, binary glTF with the `glTF` magic, OBJ otherwise. glTF scenes
/// are read with their node transforms kept out of the geometry.
pub fn read_mesh(path: &Path) -> anyhow::Result<Mesh> {
    read_mesh_with(path, false)
}

/// [`read_mesh`], with `flatten` applying glTF node transforms (`--flatten`). Notes on what a
/// glTF file held that was left out are printed.
pub fn read_mesh_with(path: &Path, flatten: bool) -> anyhow::Result<Mesh> {
    use subsurf::io::gltf as gltf_read;
    let opts = gltf_read::ReadOptions { flatten };
    let read = if is_stdio(path) {
        let mut bytes = Vec::new();
        std::io::stdin()
            .lock()
            .read_to_end(&mut bytes)
            .context("reading standard input")?;
        match Format::sniff(&bytes) {
            // glTF through its reader directly, for the options and the notes.
            Format::Glb => {
                gltf_read::read(&bytes, None, &opts).context("reading standard input")?
            }
            format => {
                return subsurf::io::read_bytes(&bytes, format).context("reading standard input")
            }
        }
    } else {
        match Format::from_path(path) {
            Ok(Format::Glb | Format::Gltf) => gltf_read::read_file(path, &opts)
                .with_context(|| format!("reading {}", path.display()))?,
            _ => {
                return subsurf::io::read_path(path)
                    .with_context(|| format!("reading {}", path.display()))
            }
        }
    };
    for note in &read.notes {
        crate::say!("{}: {note}", shown(path, false));
    }
    Ok(read.mesh)
}

/// Writes a mesh file, with the path in the error; `-` writes standard output in the
/// `--format` format.
pub fn write_mesh(path: &Path, mesh: &Mesh, normals: Option<&[[f32; 3]]>) -> anyhow::Result<()> {
    if is_stdio(path) {
        let format = *STDOUT_FORMAT.get().unwrap_or(&Format::Obj);
        let mut w = std::io::BufWriter::new(std::io::stdout().lock());
        return subsurf::io::write_to_with(&mut w, format, mesh, normals, write_options())
            .context("writing standard output");
    }
    subsurf::io::write_path_with(path, mesh, normals, write_options())
        .with_context(|| format!("writing {}", path.display()))
}

/// Opens an output file (or standard output for `-`) for writing.
pub fn create_output(path: &Path) -> anyhow::Result<Box<dyn Write>> {
    if is_stdio(path) {
        return Ok(Box::new(std::io::BufWriter::new(std::io::stdout())));
    }
    let file =
        std::fs::File::create(path).with_context(|| format!("creating {}", path.display()))?;
    Ok(Box::new(std::io::BufWriter::new(file)))
}

/// Where the numeric work runs (`--backend cpu|gpu`; the GPU: wgpu compute kernels on
/// Vulkan, Metal or DX12, `WGPU_BACKEND` and `SUBSURF_ADAPTER` respected).
pub use subsurf::surface::BackendName as Backend;

/// Opens the GPU device, with a message that says what to do when there is none.
pub fn gpu_context() -> anyhow::Result<subsurf_gpu::GpuContext> {
    let ctx = subsurf_gpu::GpuContext::new().context(
        "--backend gpu: no usable GPU device (run `subsurf gpu-info --all`, or use --backend cpu)",
    )?;
    crate::say!("GPU backend: {}", ctx.adapter_info().name);
    Ok(ctx)
}
