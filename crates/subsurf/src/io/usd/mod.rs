//! USD stages (`.usda`, `.usdc`, `.usdz`): `UsdGeomMesh` prims in and out.
//!
//! Layers are read and written by the `openusd` crate (a native Rust implementation of
//! Pixar's Sdf layer formats); this module maps its spec store to [`Mesh`]es and back:
//!
//! - [`Stage::read`] loads one layer (the root layer of a `.usdz` package) and keeps every
//!   prim, so a stage written back holds the same hierarchy, transforms and other prims.
//! - [`Stage::meshes`] lists the `Mesh` prims (defined, outside `class` prims, in document
//!   order) as [`MeshPrim`]s: the cage as subsurf models it (see `mesh_read` for the
//!   attribute mapping and USD's defaults), whether it subdivides
//!   (`subdivisionScheme = "none"` does not) and its world transform.
//! - [`Stage::set_mesh`] replaces a prim's mesh, as a cage or as a refined polygon mesh.
//! - [`Stage::to_bytes`] writes `.usda`, `.usdc` (crate version 0.8.0, by subsurf's own
//!   crate writer: the crate files the `openusd` crate writes do not open in Pixar's USD) or
//!   `.usdz` (a package of one crate layer).
//!
//! Composition (references, payloads, sublayers, variants) is not evaluated: a mesh is read
//! as its own layer states it. Every malformed input is an [`Error::Usd`] naming the file,
//! the prim and the attribute at fault.
//!
//! # Example
//!
//! ```
//! use subsurf::io::usd::{Stage, UsdFormat};
//!
//! let text = r#"#usda 1.0
//! def Xform "World" {
//!     double3 xformOp:translate = (0, 0, 5)
//!     uniform token[] xformOpOrder = ["xformOp:translate"]
//!     def Mesh "Quad" {
//!         point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
//!         int[] faceVertexCounts = [4]
//!         int[] faceVertexIndices = [0, 1, 2, 3]
//!     }
//! }
//! "#;
//! let stage = Stage::read(text.as_bytes(), "quad.usda")?;
//! let meshes = stage.meshes()?;
//! assert_eq!(meshes[0].path, "/World/Quad");
//! assert_eq!(meshes[0].world[3][2], 5.0);
//! // USD's default boundary rule, not OBJ's.
//! assert_eq!(meshes[0].mesh.options.boundary, subsurf::BoundaryInterpolation::EdgeAndCorner);
//!
//! let bytes = stage.to_bytes(UsdFormat::Usdz)?;
//! let back = Stage::read(&bytes, "quad.usdz")?;
//! assert_eq!(back.meshes()?[0].mesh, meshes[0].mesh);
//!
//! let bad = text.replace("[0, 1, 2, 3]", "[0, 1, 2, 7]");
//! let err = Stage::read(bad.as_bytes(), "quad.usda")?.meshes().unwrap_err();
//! assert!(matches!(&err, subsurf::Error::Usd { prim, attribute, .. }
//!     if prim == "/World/Quad" && attribute == "faceVertexIndices"), "{err}");
//! # Ok::<(), subsurf::Error>(())
//! ```

mod attrs;
mod crate_codec;
mod crate_types;
mod crate_values;
mod crate_write;
mod layer;
mod mesh_read;
mod mesh_write;
pub(crate) mod xform;

use crate::error::{Error, Result};
use crate::mesh::Mesh;
use attrs::PrimReader;
use openusd::sdf::{self, schema::ChildrenKey, schema::FieldKey, AbstractData, SpecType, Value};
use std::path::Path;
pub use xform::{transform_point, Matrix};

/// Prim nesting deeper than this is refused (a guard against stack exhaustion).
const MAX_DEPTH: usize = 256;

/// The three USD file formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UsdFormat {
    /// Text (`.usda`).
    Usda,
    /// Binary crate (`.usdc`; `.usd` is read by its content, written as crate).
    Usdc,
    /// Zip package (`.usdz`); written with one crate layer.
    Usdz,
}

impl UsdFormat {
    /// The format of the bytes of a USD file, by magic (`None` when they are not USD).
    pub fn sniff(bytes: &[u8]) -> Option<UsdFormat> {
        layer::sniff(bytes)
    }
}

/// A mesh prim of a stage.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshPrim {
    /// The prim path, e.g. `/World/Body`.
    pub path: String,
    /// The cage, in the prim's own coordinates.
    pub mesh: Mesh,
    /// `false` for a polygon mesh (`subdivisionScheme = "none"`), which is not subdivided.
    pub subdivide: bool,
    /// The prim's local-to-world transform (USD convention: row vectors, `p * world`).
    pub world: Matrix,
}

/// One USD layer, every prim of it kept.
#[derive(Debug, Clone)]
pub struct Stage {
    data: sdf::Data,
    file: String,
}

fn spec_path(file: &str, path: &str) -> Result<sdf::Path> {
    sdf::Path::new(path).map_err(|e| Error::Usd {
        file: file.to_string(),
        prim: path.to_string(),
        attribute: String::new(),
        reason: format!("bad prim path: {e}"),
    })
}

impl Stage {
    /// Reads a layer from the bytes of a `.usda`, `.usdc` or `.usdz` file (the format told by
    /// the bytes). `file` names it in errors.
    pub fn read(bytes: &[u8], file: &str) -> Result<Stage> {
        Ok(Stage {
            data: layer::read(bytes, file)?,
            file: file.to_string(),
        })
    }

    /// Reads a layer file.
    pub fn read_path(path: impl AsRef<Path>) -> Result<Stage> {
        let path = path.as_ref();
        let bytes = std::fs::read(path)?;
        Stage::read(&bytes, &path.display().to_string())
    }

    /// A stage of one mesh prim, `/Mesh` (the default prim), written as a cage.
    pub fn from_mesh(mesh: &Mesh) -> Stage {
        Stage::from_mesh_with(mesh, &crate::io::WriteOptions::default())
    }

    /// [`Stage::from_mesh`] with options: with [`crate::io::WriteOptions::f64`] positions
    /// held in `f64` are written as `point3d[]`.
    pub fn from_mesh_with(mesh: &Mesh, options: &crate::io::WriteOptions) -> Stage {
        let mut data = sdf::Data::new();
        let root = data.create_spec(sdf::Path::abs_root(), SpecType::PseudoRoot);
        root.add(FieldKey::DefaultPrim.as_str(), Value::token("Mesh"));
        root.add(
            ChildrenKey::PrimChildren.as_str(),
            Value::token_vec(["Mesh"]),
        );
        let path = sdf::Path::abs_root()
            .append_path(sdf::Path::new("Mesh").expect("a valid prim name"))
            .expect("a valid prim path");
        let prim = data.create_spec(path.clone(), SpecType::Prim);
        prim.add(
            FieldKey::Specifier.as_str(),
            Value::Specifier(sdf::Specifier::Def),
        );
        prim.add(FieldKey::TypeName.as_str(), Value::token("Mesh"));
        mesh_write::write_mesh(&mut data, &path, mesh, false, options.f64);
        Stage {
            data,
            file: "<memory>".into(),
        }
    }

    fn reader<'a>(&'a self, prim: &'a sdf::Path) -> PrimReader<'a> {
        PrimReader {
            data: &self.data,
            file: &self.file,
            prim,
        }
    }

    fn children(&self, path: &sdf::Path) -> Vec<sdf::Path> {
        let Some(Value::TokenVec(names)) = self
            .data
            .spec(path)
            .and_then(|s| s.get(ChildrenKey::PrimChildren.as_str()))
        else {
            return Vec::new();
        };
        names
            .iter()
            .filter_map(|n| sdf::Path::new(n.as_str()).ok())
            .filter_map(|n| path.append_path(n).ok())
            .filter(|p| self.data.spec_type(p) == Some(SpecType::Prim))
            .collect()
    }

    /// Walks defined prims below `path` in document order (`class` subtrees skipped),
    /// with each prim's world transform.
    fn walk(
        &self,
        path: &sdf::Path,
        parent: &Matrix,
        depth: usize,
        out: &mut Vec<(sdf::Path, Matrix)>,
    ) -> Result<()> {
        if depth > MAX_DEPTH {
            return Err(layer::file_error(
                &self.file,
                format!(
                    "prims nested more than {MAX_DEPTH} deep below {}",
                    path.as_str()
                ),
            ));
        }
        for child in self.children(path) {
            let spec = self.data.spec(&child);
            let specifier = spec.and_then(|s| s.get(FieldKey::Specifier.as_str()));
            if matches!(specifier, Some(Value::Specifier(sdf::Specifier::Class))) {
                continue;
            }
            let (local, reset) = xform::local(&self.reader(&child))?;
            let world = if reset {
                local
            } else {
                xform::mul(&local, parent)
            };
            let is_mesh = matches!(spec.and_then(|s| s.get(FieldKey::TypeName.as_str())),
                Some(Value::Token(t)) if t.as_str() == "Mesh");
            let defined = matches!(specifier, Some(Value::Specifier(sdf::Specifier::Def)));
            if is_mesh && defined {
                out.push((child.clone(), world));
            }
            self.walk(&child, &world, depth + 1, out)?;
        }
        Ok(())
    }

    fn mesh_prims(&self) -> Result<Vec<(sdf::Path, Matrix)>> {
        let mut out = Vec::new();
        self.walk(&sdf::Path::abs_root(), &xform::IDENTITY, 0, &mut out)?;
        Ok(out)
    }

    /// The paths of the mesh prims, in document order.
    pub fn mesh_paths(&self) -> Result<Vec<String>> {
        Ok(self
            .mesh_prims()?
            .into_iter()
            .map(|(p, _)| p.as_str().to_string())
            .collect())
    }

    /// Every mesh prim, read.
    pub fn meshes(&self) -> Result<Vec<MeshPrim>> {
        self.mesh_prims()?
            .into_iter()
            .map(|(path, world)| {
                let read = mesh_read::read_mesh(&self.reader(&path))?;
                Ok(MeshPrim {
                    path: path.as_str().to_string(),
                    mesh: read.mesh,
                    subdivide: read.subdivide,
                    world,
                })
            })
            .collect()
    }

    /// The mesh prim at `path`.
    pub fn mesh(&self, path: &str) -> Result<MeshPrim> {
        let prims = self.mesh_paths()?;
        if !prims.iter().any(|p| p == path) {
            return Err(Error::Usd {
                file: self.file.clone(),
                prim: path.to_string(),
                attribute: String::new(),
                reason: format!("no mesh prim here (mesh prims: {})", list(&prims)),
            });
        }
        Ok(self
            .meshes()?
            .into_iter()
            .find(|m| m.path == path)
            .expect("listed above"))
    }

    /// The stage's only mesh prim; an error naming them when there are none or several.
    pub fn single_mesh(&self) -> Result<MeshPrim> {
        let mut meshes = self.meshes()?;
        match meshes.len() {
            1 => Ok(meshes.remove(0)),
            n => Err(layer::file_error(
                &self.file,
                format!(
                    "{n} mesh prims ({}); one mesh prim is needed here (refine and info take --prim)",
                    list(&meshes.iter().map(|m| m.path.clone()).collect::<Vec<_>>())
                ),
            )),
        }
    }

    /// Replaces the mesh of the prim at `path`: as a cage with its tags and options, or, when
    /// `refined`, as a polygon mesh (`subdivisionScheme = "none"`, holes kept).
    pub fn set_mesh(&mut self, path: &str, mesh: &Mesh, refined: bool) -> Result<()> {
        self.set_mesh_with(path, mesh, refined, &crate::io::WriteOptions::default())
    }

    /// [`Stage::set_mesh`] with options: with [`crate::io::WriteOptions::f64`] positions held
    /// in `f64` are written as `point3d[]`.
    pub fn set_mesh_with(
        &mut self,
        path: &str,
        mesh: &Mesh,
        refined: bool,
        options: &crate::io::WriteOptions,
    ) -> Result<()> {
        crate::io::check_writable(mesh)?;
        let p = spec_path(&self.file, path)?;
        if self.data.spec_type(&p) != Some(SpecType::Prim) {
            return Err(Error::Usd {
                file: self.file.clone(),
                prim: path.to_string(),
                attribute: String::new(),
                reason: "no prim here".into(),
            });
        }
        mesh_write::write_mesh(&mut self.data, &p, mesh, refined, options.f64);
        Ok(())
    }

    /// The stage as the bytes of a file in `format`.
    pub fn to_bytes(&self, format: UsdFormat) -> Result<Vec<u8>> {
        layer::write(&self.data, format, &self.file)
    }

    /// Writes the stage, in the format of the path's extension (`.usda`, `.usdc`, `.usd`
    /// (as crate) or `.usdz`).
    pub fn write_path(&self, path: impl AsRef<Path>) -> Result<()> {
        let path = path.as_ref();
        let format = format_of_path(path).ok_or_else(|| {
            Error::Unsupported(format!("'{}' is not a USD file name", path.display()))
        })?;
        let bytes = layer::write(&self.data, format, &path.display().to_string())?;
        std::fs::write(path, bytes)?;
        Ok(())
    }
}

fn list(paths: &[String]) -> String {
    if paths.is_empty() {
        "none".into()
    } else {
        paths.join(", ")
    }
}

/// The USD format named by a path's extension (case-insensitive): `.usda`, `.usdc`, `.usdz`;
/// `.usd` counts as crate (and is read by its content).
pub fn format_of_path(path: &Path) -> Option<UsdFormat> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "usda" => Some(UsdFormat::Usda),
        "usdc" | "usd" => Some(UsdFormat::Usdc),
        "usdz" => Some(UsdFormat::Usdz),
        _ => None,
    }
}

/// Reads the only mesh prim of a USD file's bytes (see [`Stage::single_mesh`]).
pub fn read(bytes: &[u8], file: &str) -> Result<Mesh> {
    Ok(Stage::read(bytes, file)?.single_mesh()?.mesh)
}

/// Writes `mesh` as a one-prim stage (see [`Stage::from_mesh`]).
pub fn write(mesh: &Mesh, format: UsdFormat, w: &mut impl std::io::Write) -> Result<()> {
    write_with(mesh, format, &crate::io::WriteOptions::default(), w)
}

/// [`write()`] with options ([`Stage::from_mesh_with`]).
pub fn write_with(
    mesh: &Mesh,
    format: UsdFormat,
    options: &crate::io::WriteOptions,
    w: &mut impl std::io::Write,
) -> Result<()> {
    crate::io::check_writable(mesh)?;
    w.write_all(&Stage::from_mesh_with(mesh, options).to_bytes(format)?)?;
    Ok(())
}
