//! Mesh files: one reader/writer module per format, chosen by the file extension.
//!
//! - [`obj`]: Wavefront OBJ with OpenSubdiv's `t` tag lines (creases, corners, holes, options)
//!   and face-varying UVs.
//! - [`ply`]: Stanford PLY, ASCII and binary in, binary little-endian out.
//! - [`gltf`]: glTF 2.0 in (`.gltf` with its buffers, `.glb`: triangle primitives welded
//!   into one cage, `TEXCOORD_0` as face-varying UVs) and binary glTF (`.glb`) out.
//! - [`usd`]: USD stages (`.usda`, `.usdc`, `.usdz`) in and out, `UsdGeomMesh` prims.
//!
//! Every malformed input is reported as [`Error::Parse`] with the 1-based line at fault
//! ([`Error::Gltf`] with the JSON path at fault for glTF, [`Error::Usd`] with the prim and
//! attribute for USD); no input makes a reader panic.
//!
//! # Example
//!
//! An OBJ quad with UVs and a crease tag, parsed, written as binary PLY and OBJ files (the
//! format chosen by the extension) and read back; a bad index is a typed error:
//!
//! ```
//! use subsurf::{io, Error};
//!
//! let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
//!             vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
//!             f 1/1 2/2 3/3 4/4\nt crease 2/1/0 0 1 2.5\n";
//! let mesh = io::obj::read(text)?;
//! assert_eq!((mesh.num_vertices(), mesh.num_faces()), (4, 1));
//! assert_eq!(mesh.creases[0].sharpness, 2.5);
//! assert_eq!(mesh.uvs.as_ref().map(|uv| uv.values.len()), Some(4));
//!
//! let dir = std::env::temp_dir().join(format!("subsurf-io-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! for name in ["quad.ply", "quad.obj"] {
//!     let path = dir.join(name);
//!     io::write_path(&path, &mesh, None)?;
//!     let back = io::read_path(&path)?;
//!     assert_eq!(back.positions, mesh.positions);
//!     assert_eq!(back.face_indices, mesh.face_indices);
//! }
//! std::fs::remove_dir_all(&dir)?;
//!
//! let err = io::obj::read("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n").unwrap_err();
//! assert!(matches!(err, Error::Parse { line: 4, .. }), "{err}");
//! # Ok::<(), subsurf::Error>(())
//! ```

pub mod gltf;
mod gltf_access;
mod gltf_read;
pub mod obj;
mod obj_tags;
pub mod ply;
pub mod usd;

use crate::error::{Error, MeshError, Result};
use crate::mesh::Mesh;
use std::path::Path;

/// The file formats known to [`read_path`] and [`write_path`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// Stanford PLY (`.ply`).
    Ply,
    /// Binary glTF 2.0 (`.glb`), read and written.
    Glb,
    /// glTF 2.0 JSON (`.gltf`, buffers in files next to it or `data:` URIs), read only.
    Gltf,
    /// A USD stage (`.usda`, `.usdc`, `.usd`, `.usdz`): one mesh prim read (see
    /// [`usd::Stage`] for stages of several), one written (`.usda`, `.usdz`).
    Usd(usd::UsdFormat),
}

impl Format {
    /// The format named by a path's extension (case-insensitive), or
    /// [`Error::Unsupported`] for any other extension.
    pub fn from_path(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("obj") => Ok(Format::Obj),
            Some("ply") => Ok(Format::Ply),
            Some("glb") => Ok(Format::Glb),
            Some("gltf") => Ok(Format::Gltf),
            Some(_) if usd::format_of_path(path).is_some() => {
                Ok(Format::Usd(usd::format_of_path(path).expect("checked")))
            }
            Some(other) => Err(Error::Unsupported(format!(
                "mesh file extension '.{other}' (known: .obj, .ply, .glb, .gltf, .usda, .usdc, .usd, .usdz)"
            ))),
            None => Err(Error::Unsupported(format!(
                "mesh file '{}' has no extension (known: .obj, .ply, .glb, .gltf, .usda, .usdc, .usd, .usdz)",
                path.display()
            ))),
        }
    }
}

impl Format {
    /// The format named `name` (`obj`, `ply`, `glb`, `gltf`, `usda`, `usdc` or `usdz`,
    /// case-insensitive), as a
    /// command line's `--format` gives it.
    pub fn from_name(name: &str) -> Result<Format> {
        match name.to_ascii_lowercase().as_str() {
            "obj" => Ok(Format::Obj),
            "ply" => Ok(Format::Ply),
            "glb" => Ok(Format::Glb),
            "gltf" => Ok(Format::Gltf),
            "usda" => Ok(Format::Usd(usd::UsdFormat::Usda)),
            "usdc" => Ok(Format::Usd(usd::UsdFormat::Usdc)),
            "usdz" => Ok(Format::Usd(usd::UsdFormat::Usdz)),
            other => Err(Error::Unsupported(format!(
                "mesh format '{other}' (known: obj, ply, glb, gltf, usda, usdc, usdz)"
            ))),
        }
    }

    /// The format of a file's bytes, by their magic: GLB (`glTF`), PLY (`ply`), USD
    /// (`#usda`, `PXR-USDC`, a zip), else OBJ (which has none). A `.gltf` JSON file cannot
    /// be told from text and is never returned.
    pub fn sniff(bytes: &[u8]) -> Format {
        if let Some(u) = usd::UsdFormat::sniff(bytes) {
            Format::Usd(u)
        } else if gltf_read::is_glb(bytes) {
            Format::Glb
        } else if bytes.starts_with(b"ply") {
            Format::Ply
        } else {
            Format::Obj
        }
    }

    /// Whether [`write_to`] can write this format (all but `.gltf`).
    pub fn writable(self) -> bool {
        !matches!(self, Format::Gltf)
    }
}

/// Reads a mesh in `format` from `reader` (for example standard input). OBJ input gets the
/// default (Catmull-Clark) scheme unless its tags say otherwise. glTF is read with
/// [`gltf_read::ReadOptions::default`] and can only use its GLB chunk and `data:` URIs.
pub fn read_from(mut reader: impl std::io::Read, format: Format) -> Result<Mesh> {
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes)?;
    read_bytes(&bytes, format)
}

/// Reads a mesh in `format` from the bytes of a whole file, as [`read_from`].
pub fn read_bytes(bytes: &[u8], format: Format) -> Result<Mesh> {
    match format {
        // As in `obj::read_file`: bytes that are not UTF-8 can only matter inside comments.
        Format::Obj => obj::read(&String::from_utf8_lossy(bytes)),
        Format::Ply => ply::read(bytes),
        Format::Glb | Format::Gltf => Ok(gltf_read::read(bytes, None, &Default::default())?.mesh),
        Format::Usd(_) => usd::read(bytes, "<bytes>"),
    }
}

/// How a mesh is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct WriteOptions {
    /// Write hole faces, tagged, so that refining the file again continues the same surface
    /// (OBJ: `t hole` tags, USD: `holeIndices`; PLY and glTF cannot tag them and are refused).
    /// Off by default: hole faces are left out of every format, as viewers and libraries that
    /// ignore the tags (trimesh, Blender, MeshLab) would otherwise draw the holes closed.
    pub keep_holes: bool,
    /// Write positions held in `f64` ([`crate::mesh::Positions::is_f64`]) as `f64` where the
    /// format would otherwise round them: USD `point3d[]` instead of the UsdGeom schema's
    /// `point3f[]`. (OBJ and PLY always write what the mesh holds: the shortest digits that
    /// read back to the same `f64` values, and `double` properties.)
    pub f64: bool,
}

impl WriteOptions {
    /// `mesh` as a format that tags holes (OBJ, USD) writes it under these options: itself
    /// with `keep_holes` or without holes, else [`Mesh::without_holes`]. For writers of tagging
    /// formats outside this module, such as a USD stage's prims.
    pub fn mesh_to_write<'a>(&self, mesh: &'a Mesh) -> std::borrow::Cow<'a, Mesh> {
        if self.keep_holes || mesh.holes.is_empty() {
            std::borrow::Cow::Borrowed(mesh)
        } else {
            std::borrow::Cow::Owned(mesh.without_holes())
        }
    }
}

/// Writes a mesh in `format` to `w` (for example standard output); `normals` as in
/// [`write_path`]. Hole faces are left out ([`WriteOptions`]).
pub fn write_to(
    w: &mut impl std::io::Write,
    format: Format,
    mesh: &Mesh,
    normals: Option<&[[f32; 3]]>,
) -> Result<()> {
    write_to_with(w, format, mesh, normals, WriteOptions::default())
}

/// [`write_to`] with options: with [`WriteOptions::keep_holes`] the hole faces are written
/// tagged (OBJ, USD) or the request is refused (PLY, glTF).
pub fn write_to_with(
    w: &mut impl std::io::Write,
    format: Format,
    mesh: &Mesh,
    normals: Option<&[[f32; 3]]>,
    options: WriteOptions,
) -> Result<()> {
    // PLY and glTF cannot tag holes: their writers always leave hole faces out. OBJ and USD
    // tag them, so leaving them out is done here.
    let tags_holes = matches!(format, Format::Obj | Format::Usd(_));
    if options.keep_holes && !tags_holes && !mesh.holes.is_empty() {
        return Err(Error::Unsupported(format!(
            "keeping holes in {}: the format cannot tag hole faces; write OBJ or USD",
            if format == Format::Ply { "PLY" } else { "glTF" }
        )));
    }
    let written = if tags_holes {
        options.mesh_to_write(mesh)
    } else {
        std::borrow::Cow::Borrowed(mesh)
    };
    let mesh = &*written;
    match (format, normals) {
        (Format::Obj, None) => obj::write(mesh, w)?,
        (Format::Obj, Some(n)) => obj::write_with_normals(mesh, n, w)?,
        (Format::Ply, n) => ply::write(mesh, n, w)?,
        (Format::Glb, n) => gltf::write(mesh, n, w)?,
        (Format::Usd(u), _) => usd::write_with(mesh, u, &options, w)?,
        (Format::Gltf, _) => {
            return Err(Error::Unsupported(
                "writing .gltf; subsurf writes binary glTF (.glb)".into(),
            ))
        }
    }
    w.flush()?;
    Ok(())
}

/// Reads a mesh, choosing the format by extension. OBJ files get their scheme from the file
/// name prefix (see [`obj::scheme_from_name`]); glTF files are read with
/// [`gltf_read::ReadOptions::default`] (see [`gltf_read::read_file`] for the options).
pub fn read_path(path: impl AsRef<Path>) -> Result<Mesh> {
    let path = path.as_ref();
    match Format::from_path(path)? {
        Format::Obj => obj::read_file(path),
        Format::Ply => ply::read_file(path),
        Format::Glb | Format::Gltf => Ok(gltf_read::read_file(path, &Default::default())?.mesh),
        Format::Usd(_) => Ok(usd::Stage::read_path(path)?.single_mesh()?.mesh),
    }
}

/// Writes a mesh, choosing the format by extension. With `normals` (one per vertex) OBJ gets
/// `vn` lines, PLY gets `nx ny nz` properties and glTF a `NORMAL` attribute. Hole faces are
/// left out ([`WriteOptions`]).
pub fn write_path(path: impl AsRef<Path>, mesh: &Mesh, normals: Option<&[[f32; 3]]>) -> Result<()> {
    write_path_with(path, mesh, normals, WriteOptions::default())
}

/// [`write_path`] with options ([`write_to_with`]).
pub fn write_path_with(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    normals: Option<&[[f32; 3]]>,
    options: WriteOptions,
) -> Result<()> {
    let path = path.as_ref();
    let format = Format::from_path(path)?;
    if !format.writable() {
        return write_to_with(&mut std::io::sink(), format, mesh, normals, options);
    }
    let file = std::fs::File::create(path)?;
    write_to_with(
        &mut std::io::BufWriter::new(file),
        format,
        mesh,
        normals,
        options,
    )
}

/// A [`Error::Parse`] at `line`.
pub(crate) fn parse_error(line: usize, reason: impl Into<String>) -> Error {
    Error::Parse {
        line,
        reason: reason.into(),
    }
}

/// Checks the buffer lengths the writer relies on.
pub(crate) fn check_writable(mesh: &Mesh) -> Result<()> {
    let expected: u64 = mesh.face_counts.iter().map(|&n| n as u64).sum();
    if expected != mesh.face_indices.len() as u64 {
        return Err(MeshError::FaceIndexCountMismatch {
            expected: expected as usize,
            found: mesh.face_indices.len(),
        }
        .into());
    }
    if let Some(uv) = &mesh.uvs {
        if uv.indices.len() != mesh.face_indices.len() {
            return Err(MeshError::FaceVarying {
                reason: format!(
                    "{} UV indices for {} face corners",
                    uv.indices.len(),
                    mesh.face_indices.len()
                ),
            }
            .into());
        }
    }
    Ok(())
}
