//! Library errors as the package's Python exceptions (defined in `subsurf/_errors.py`):
//! `MeshError(ValueError)` with `.face`, `.corner`, `.vertex` (`.edit` for a sharpness edit); `ParseError(ValueError)` with
//! `.path`, `.line` (`.location` for glTF, `.prim` and `.attribute` for USD); `GpuError(RuntimeError)`; `SubsurfError` for the rest.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use subsurf::surface::SurfaceError;
use subsurf::{Error, MeshError};

/// Raises `subsurf._errors.<class>(message)` with `attrs` set on it.
pub fn raise(
    py: Python<'_>,
    class: &str,
    message: String,
    attrs: &[(&str, Option<usize>)],
) -> PyErr {
    raise_with(py, class, message, |d| {
        for (k, v) in attrs {
            d.set_item(*k, *v)?;
        }
        Ok(())
    })
}

fn raise_with(
    py: Python<'_>,
    class: &str,
    message: String,
    fill: impl FnOnce(&Bound<'_, PyDict>) -> PyResult<()>,
) -> PyErr {
    let make = || -> PyResult<PyErr> {
        let cls = py.import("subsurf._errors")?.getattr(class)?;
        let attrs = PyDict::new(py);
        fill(&attrs)?;
        let e = cls.call((message.clone(),), Some(&attrs))?;
        Ok(PyErr::from_value(e))
    };
    make().unwrap_or_else(|e| e)
}

/// A mesh error with the element named.
pub fn mesh_error(py: Python<'_>, e: &MeshError) -> PyErr {
    let (face, corner, vertex) = match e {
        MeshError::FaceTooSmall { face, .. } | MeshError::NotTriangle { face, .. } => {
            (Some(*face), None, None)
        }
        MeshError::VertexIndexOutOfRange {
            face,
            corner,
            index,
            ..
        } => (Some(*face), Some(*corner), Some(*index as usize)),
        MeshError::NonFiniteCoordinate { vertex, .. } => (None, None, Some(*vertex)),
        MeshError::CreaseEdgeMissing { v0, .. } => (None, None, Some(*v0 as usize)),
        _ => (None, None, None),
    };
    let edit = match e {
        MeshError::BadSharpnessEdit { edit, .. } => Some(*edit),
        _ => None,
    };
    raise(
        py,
        "MeshError",
        e.to_string(),
        &[
            ("face", face),
            ("corner", corner),
            ("vertex", vertex),
            ("edit", edit),
        ],
    )
}

/// Any library error; `path` names the file read or written, if any.
pub fn lib_error(py: Python<'_>, e: Error, path: Option<&str>) -> PyErr {
    match e {
        Error::Mesh(m) => mesh_error(py, &m),
        Error::Parse { line, reason } => {
            let where_ = path.map_or(String::new(), |p| format!("{p}: "));
            let path = path.map(str::to_owned);
            raise_with(
                py,
                "ParseError",
                format!("{where_}line {line}: {reason}"),
                |d| {
                    d.set_item("path", path)?;
                    d.set_item("line", line)
                },
            )
        }
        Error::Gltf { location, reason } => {
            let where_ = path.map_or(String::new(), |p| format!("{p}: "));
            let path = path.map(str::to_owned);
            raise_with(
                py,
                "ParseError",
                format!("{where_}glTF {location}: {reason}"),
                |d| {
                    d.set_item("path", path)?;
                    d.set_item("line", py.None())?;
                    d.set_item("location", location)
                },
            )
        }
        Error::Usd {
            ref file,
            ref prim,
            ref attribute,
            ..
        } => {
            let path = path.map_or_else(|| file.clone(), str::to_owned);
            let (prim, attribute) = (prim.clone(), attribute.clone());
            raise_with(py, "ParseError", e.to_string(), |d| {
                d.set_item("path", path)?;
                d.set_item("line", py.None())?;
                d.set_item("prim", (!prim.is_empty()).then_some(prim))?;
                d.set_item("attribute", (!attribute.is_empty()).then_some(attribute))
            })
        }
        Error::Io(io) => {
            let msg = match path {
                Some(p) => format!("{p}: {io}"),
                None => io.to_string(),
            };
            PyErr::new::<pyo3::exceptions::PyOSError, _>(msg)
        }
        Error::Query(q) => value_error(q.to_string()),
        Error::Tess(t) => value_error(t.to_string()),
        Error::Unsupported(s) => raise(py, "UnsupportedError", format!("unsupported: {s}"), &[]),
        other => PyRuntimeError::new_err(other.to_string()),
    }
}

/// An error of `subsurf::surface::build`.
pub fn surface_error(py: Python<'_>, e: SurfaceError) -> PyErr {
    match e {
        SurfaceError::Library(e) => lib_error(py, e, None),
        SurfaceError::Backend { .. } => raise(py, "GpuError", e.to_string(), &[]),
        SurfaceError::Unsupported(s) => raise(py, "UnsupportedError", s, &[]),
    }
}

/// A GPU that could not be opened or failed.
pub fn gpu_error(py: Python<'_>, message: String) -> PyErr {
    raise(py, "GpuError", message, &[])
}

/// A bad argument.
pub fn value_error(message: impl Into<String>) -> PyErr {
    pyo3::exceptions::PyValueError::new_err(message.into())
}
