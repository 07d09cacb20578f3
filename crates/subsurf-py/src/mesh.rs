//! `_Mesh`: a validated `subsurf::Mesh` shared (immutable) between Python threads.

use std::sync::Arc;

use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use subsurf::OptionValue;
use subsurf::{Corner, Crease, FaceVarying, Mesh, Positions, Topology};

use crate::arrays::{out1, out2, rows, vec1};
use crate::errors::{lib_error, mesh_error, value_error};

/// A polygon mesh with creases, corners, holes, UVs and scheme options (immutable).
#[pyclass(frozen, name = "_Mesh", module = "subsurf._subsurf")]
#[derive(Debug, Clone)]
pub struct PyMesh {
    pub inner: Arc<Mesh>,
    /// Whether Python sees the positions as float64: given as a float64 array (or refined
    /// from one). A mesh read from a file is float32 to Python, though it keeps the file's
    /// digits for writing.
    pub f64: bool,
}

/// An option value from its name (`docs/vocabulary.md`), a `ValueError` listing the accepted
/// names otherwise.
pub fn parse<T: OptionValue>(name: &str) -> PyResult<T> {
    T::from_name(name).map_err(|e| value_error(e.to_string()))
}

pub fn parse_options(
    mesh: &mut Mesh,
    scheme: &str,
    boundary: &str,
    crease_method: &str,
    triangle_subdivision: &str,
    uv_interpolation: &str,
) -> PyResult<()> {
    let o = &mut mesh.options;
    o.scheme = parse(scheme)?;
    o.boundary = parse(boundary)?;
    o.crease_method = parse(crease_method)?;
    o.triangle_subdivision = parse(triangle_subdivision)?;
    o.uv_interpolation = parse(uv_interpolation)?;
    Ok(())
}

/// The option names in the order of the Python `Mesh.options` keys.
fn option_names(m: &Mesh) -> [&'static str; 5] {
    let o = &m.options;
    [
        o.scheme.name(),
        o.boundary.name(),
        o.crease_method.name(),
        o.triangle_subdivision.name(),
        o.uv_interpolation.name(),
    ]
}

/// Checks everything the library would otherwise trust: index ranges, finiteness, UVs.
pub fn validate(py: Python<'_>, mesh: &Mesh) -> PyResult<()> {
    let n = mesh.positions.len() as u32;
    if let Some(fv) = &mesh.uvs {
        if fv.indices.len() != mesh.face_indices.len() {
            return Err(mesh_error(
                py,
                &subsurf::MeshError::FaceVarying {
                    reason: format!(
                        "{} UV indices for {} face corners",
                        fv.indices.len(),
                        mesh.face_indices.len()
                    ),
                },
            ));
        }
        let nv = fv.values.len() as u32;
        if let Some(k) = fv.indices.iter().position(|&i| i >= nv) {
            return Err(mesh_error(
                py,
                &subsurf::MeshError::FaceVarying {
                    reason: format!("corner {k}: UV index {} >= {nv} UVs", fv.indices[k]),
                },
            ));
        }
        if fv.values.iter().flatten().any(|x| !x.is_finite()) {
            return Err(mesh_error(
                py,
                &subsurf::MeshError::FaceVarying {
                    reason: "a UV is not finite".into(),
                },
            ));
        }
    }
    let _ = n;
    let m = mesh.clone();
    py.detach(move || Topology::new(&m).map(|_| ()))
        .map_err(|e| lib_error(py, e, None))
}

#[pymethods]
impl PyMesh {
    #[new]
    #[pyo3(signature = (positions, counts, indices, crease_pairs, crease_sharpness, corner_vertices,
        corner_sharpness, holes, uvs, uv_indices, scheme, boundary, crease_method,
        triangle_subdivision, uv_interpolation))]
    // One argument per keyword of the Python constructor.
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        counts: PyReadonlyArray1<'_, u32>,
        indices: PyReadonlyArray1<'_, u32>,
        crease_pairs: PyReadonlyArray2<'_, u32>,
        crease_sharpness: PyReadonlyArray1<'_, f32>,
        corner_vertices: PyReadonlyArray1<'_, u32>,
        corner_sharpness: PyReadonlyArray1<'_, f32>,
        holes: PyReadonlyArray1<'_, u32>,
        uvs: Option<PyReadonlyArray2<'_, f32>>,
        uv_indices: Option<PyReadonlyArray1<'_, u32>>,
        scheme: &str,
        boundary: &str,
        crease_method: &str,
        triangle_subdivision: &str,
        uv_interpolation: &str,
    ) -> PyResult<Self> {
        // float64 in stays float64 (the Python layer passes float64 arrays through).
        let positions = match positions.extract::<PyReadonlyArray2<'_, f64>>() {
            Ok(a) => Positions::from_f64(rows::<3, f64>(&a, "positions")?),
            Err(_) => {
                let a = positions.extract::<PyReadonlyArray2<'_, f32>>()?;
                Positions::from_f32(rows::<3, f32>(&a, "positions")?)
            }
        };
        let face_counts = vec1(&counts, "face counts")?;
        let face_indices = vec1(&indices, "face indices")?;
        let cp = rows::<2, u32>(&crease_pairs, "creases")?;
        let cs = vec1(&crease_sharpness, "crease sharpness")?;
        if cp.len() != cs.len() {
            return Err(value_error(format!(
                "{} crease pairs, {} sharpness values",
                cp.len(),
                cs.len()
            )));
        }
        let cv = vec1(&corner_vertices, "corners")?;
        let csh = vec1(&corner_sharpness, "corner sharpness")?;
        if cv.len() != csh.len() {
            return Err(value_error(format!(
                "{} corners, {} sharpness values",
                cv.len(),
                csh.len()
            )));
        }
        let uvs = match (uvs, uv_indices) {
            (None, None) => None,
            (Some(v), i) => {
                let values = rows::<2, f32>(&v, "uvs")?;
                let indices = match i {
                    Some(i) => vec1(&i, "uv_indices")?,
                    None => face_indices.clone(),
                };
                Some(FaceVarying { values, indices })
            }
            (None, Some(_)) => return Err(value_error("uv_indices given without uvs")),
        };
        let mut mesh = Mesh {
            positions,
            face_counts,
            face_indices,
            uvs,
            creases: cp
                .iter()
                .zip(&cs)
                .map(|(p, &s)| Crease {
                    v0: p[0],
                    v1: p[1],
                    sharpness: s,
                })
                .collect(),
            corners: cv
                .iter()
                .zip(&csh)
                .map(|(&v, &s)| Corner {
                    vertex: v,
                    sharpness: s,
                })
                .collect(),
            holes: vec1(&holes, "holes")?,
            options: Default::default(),
        };
        parse_options(
            &mut mesh,
            scheme,
            boundary,
            crease_method,
            triangle_subdivision,
            uv_interpolation,
        )?;
        validate(py, &mesh)?;
        Ok(PyMesh {
            f64: mesh.positions.is_f64(),
            inner: Arc::new(mesh),
        })
    }

    /// Reads a mesh file (.obj with OpenSubdiv tags, .ply).
    #[staticmethod]
    fn read(py: Python<'_>, path: String) -> PyResult<Self> {
        let p = path.clone();
        let mesh = py
            .detach(move || subsurf::io::read_path(&p))
            .map_err(|e| lib_error(py, e, Some(&path)))?;
        validate(py, &mesh)?;
        Ok(PyMesh {
            inner: Arc::new(mesh),
            f64: false,
        })
    }

    /// Writes the mesh (.obj, .ply, .glb or USD by extension), hole faces left out unless
    /// `keep_holes` (then tagged in OBJ and USD; refused for PLY and glb).
    #[pyo3(signature = (path, normals=None, keep_holes=false))]
    fn write(
        &self,
        py: Python<'_>,
        path: String,
        normals: Option<PyReadonlyArray2<'_, f32>>,
        keep_holes: bool,
    ) -> PyResult<()> {
        let normals = normals.map(|n| rows::<3, f32>(&n, "normals")).transpose()?;
        if let Some(n) = &normals {
            if n.len() != self.inner.positions.len() {
                return Err(value_error("one normal per position is needed"));
            }
        }
        let m = self.inner.clone();
        let p = path.clone();
        let options = subsurf::io::WriteOptions {
            keep_holes,
            ..Default::default()
        };
        py.detach(move || subsurf::io::write_path_with(&p, &m, normals.as_deref(), options))
            .map_err(|e| lib_error(py, e, Some(&path)))
    }

    /// The mesh with its hole faces left out (every vertex kept).
    fn without_holes(&self) -> PyMesh {
        let inner = if self.inner.holes.is_empty() {
            self.inner.clone()
        } else {
            Arc::new(self.inner.without_holes())
        };
        PyMesh {
            inner,
            f64: self.f64,
        }
    }

    #[getter]
    fn positions(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        match self.inner.positions.as_f64().filter(|_| self.f64) {
            Some(v) => out2(py, v.to_vec()),
            None => out2(py, self.inner.positions.to_vec()),
        }
    }
    #[getter]
    fn face_counts(&self, py: Python<'_>) -> Py<PyAny> {
        out1(py, self.inner.face_counts.clone())
    }
    #[getter]
    fn face_indices(&self, py: Python<'_>) -> Py<PyAny> {
        out1(py, self.inner.face_indices.clone())
    }
    #[getter]
    fn uvs(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        self.inner
            .uvs
            .as_ref()
            .map(|f| out2(py, f.values.clone()))
            .transpose()
    }
    #[getter]
    fn uv_indices(&self, py: Python<'_>) -> Option<Py<PyAny>> {
        self.inner.uvs.as_ref().map(|f| out1(py, f.indices.clone()))
    }
    #[getter]
    fn creases(&self, py: Python<'_>) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
        let c = &self.inner.creases;
        Ok((
            out2(py, c.iter().map(|c| [c.v0, c.v1]).collect())?,
            out1(py, c.iter().map(|c| c.sharpness).collect()),
        ))
    }
    #[getter]
    fn corners(&self, py: Python<'_>) -> (Py<PyAny>, Py<PyAny>) {
        let c = &self.inner.corners;
        (
            out1(py, c.iter().map(|c| c.vertex).collect()),
            out1(py, c.iter().map(|c| c.sharpness).collect()),
        )
    }
    #[getter]
    fn holes(&self, py: Python<'_>) -> Py<PyAny> {
        out1(py, self.inner.holes.clone())
    }
    #[getter]
    fn options(&self) -> [&'static str; 5] {
        option_names(&self.inner)
    }
    #[getter]
    fn num_vertices(&self) -> usize {
        self.inner.positions.len()
    }
    #[getter]
    fn num_faces(&self) -> usize {
        self.inner.face_counts.len()
    }
}
