//! `LimitSurface`: the limit surface of a mesh, built once, its control points updatable. A
//! Catmull-Clark or bilinear mesh gets the patch table (`PatchTable` + `LimitSurface`, ptex
//! faces, unit-square parameters, float32), whose crease and corner sharpness can be edited
//! live (`PatchTable::apply_sharpness`); a Loop mesh the Loop limit surface (`LoopLimit`,
//! base triangles, `u, v >= 0, u + v <= 1`, evaluated in float64). A mesh given float64
//! positions gets the double-precision surface (`PatchTable::<f64>`, Loop points refined in
//! f64): its samples are float64.
//!
//! Writers (`update`, `set_sharpness`) release the GIL, then take the positions' lock and the
//! surface's write lock, and release both before they need the GIL again: a reader waiting for
//! the surface while holding the GIL cannot block them.

use std::sync::{Arc, Mutex, RwLock};

use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use subsurf::limit::LoopLimit;
use subsurf::limit::{EditOutcome, LimitSurface, PatchOptions, PatchTable, SharpnessEdit};
use subsurf::{Mesh, Scheme, Topology};

use crate::arrays::{out2, rows, vec1};
use crate::errors::{lib_error, value_error};
use crate::mesh::PyMesh;
use crate::ops::{check_tess, tess_out};

/// The patch table (with its kept levels, for sharpness edits) and its points, in float32 or
/// float64.
enum Quads {
    F32(RwLock<Arc<LimitSurface>>),
    F64(RwLock<Arc<LimitSurface<f64>>>),
}

/// `$body` with `$s` the surface's lock, whichever precision it has.
macro_rules! each {
    ($q:expr, $s:ident => $body:expr) => {
        match $q {
            Quads::F32($s) => $body,
            Quads::F64($s) => $body,
        }
    };
}

/// What the surface is built from: a patch table or the Loop patches.
enum Kind {
    Quad {
        /// The base positions the surface's points were made from.
        positions: Mutex<subsurf::Positions>,
        surface: Quads,
        num_ptex_faces: usize,
    },
    Loop {
        topo: Arc<Topology>,
        isolation: u32,
        surface: RwLock<Arc<LoopLimit>>,
    },
}

/// The limit surface: patches built once, positions updatable.
#[pyclass(frozen, name = "_LimitSurface", module = "subsurf._subsurf")]
pub struct PyLimit {
    kind: Kind,
    num_vertices: usize,
    /// Built in double precision (from float64 positions): samples and updates are float64.
    f64: bool,
}

fn poisoned<T>(_: T) -> PyErr {
    value_error("limit surface lock poisoned")
}

fn read<T>(lock: &RwLock<Arc<T>>) -> PyResult<Arc<T>> {
    lock.read().map(|s| s.clone()).map_err(poisoned)
}

fn build(m: &Mesh, isolation: u32, editable: bool, f64: bool) -> subsurf::Result<Kind> {
    let topo = Topology::new(m)?;
    if m.options.scheme == Scheme::Loop {
        if editable {
            return Err(subsurf::Error::Unsupported(
                "an editable Loop limit surface (crease edits of Loop surfaces are not \
                 supported: build it again from the edited mesh)"
                    .into(),
            ));
        }
        // The points in f64 wherever the positions are held in f64, as the library's Loop
        // limit method refines them (`surface::build`, `subsurf limit`).
        let limit = LoopLimit::at_precision(&topo, &m.positions, isolation)?;
        return Ok(Kind::Loop {
            topo: Arc::new(topo),
            isolation,
            surface: RwLock::new(Arc::new(limit)),
        });
    }
    let options = PatchOptions {
        isolation_level: isolation,
        ..Default::default()
    };
    let (surface, num_ptex_faces) = if f64 {
        let table = match editable {
            true => PatchTable::<f64>::build_editable_real(&topo, &options)?,
            false => PatchTable::<f64>::build_real(&topo, &options)?,
        };
        let n = table.num_ptex_faces();
        let s = LimitSurface::new(table, &m.positions);
        (Quads::F64(RwLock::new(Arc::new(s))), n)
    } else {
        let table = match editable {
            true => PatchTable::build_editable(&topo, &options)?,
            false => PatchTable::build(&topo, &options)?,
        };
        let n = table.num_ptex_faces();
        let s = LimitSurface::new(table, &m.positions);
        (Quads::F32(RwLock::new(Arc::new(s))), n)
    };
    Ok(Kind::Quad {
        positions: Mutex::new(m.positions.clone()),
        surface,
        num_ptex_faces,
    })
}

/// The samples of a ptex-face surface at `q`, as three (n, 3) arrays in its precision.
fn eval_quads<R: subsurf::Real + numpy::Element>(
    py: Python<'_>,
    s: &RwLock<Arc<LimitSurface<R>>>,
    q: &[(u32, f64, f64)],
) -> PyResult<Arrays3> {
    let s = read(s)?;
    let q: Vec<(u32, R, R)> = q
        .iter()
        .map(|&(f, u, v)| (f, R::from_f64(u), R::from_f64(v)))
        .collect();
    let r = py.detach(move || {
        split(
            s.eval_batch(&q)
                .into_iter()
                .map(|x| x.map(|l| [l.p, l.du, l.dv])),
            R::from_f64(f64::NAN),
        )
    });
    out3x(py, r)
}

/// Points, `du` and `dv` of a batch, one row each per query.
type Columns<T> = (Vec<[T; 3]>, Vec<[T; 3]>, Vec<[T; 3]>);

/// Samples as three (n, 3) arrays, NaN where no patch holds the point (holes).
fn split<T: Copy + numpy::Element>(
    samples: impl Iterator<Item = Option<[[T; 3]; 3]>>,
    nan: T,
) -> Columns<T> {
    let (mut p, mut du, mut dv) = (Vec::new(), Vec::new(), Vec::new());
    for s in samples {
        let [a, b, c] = s.unwrap_or([[nan; 3]; 3]);
        p.push(a);
        du.push(b);
        dv.push(c);
    }
    (p, du, dv)
}

type Arrays3 = (Py<PyAny>, Py<PyAny>, Py<PyAny>);

fn out3x<T: numpy::Element>(py: Python<'_>, (p, du, dv): Columns<T>) -> PyResult<Arrays3> {
    Ok((out2(py, p)?, out2(py, du)?, out2(py, dv)?))
}

/// The surface's points made again from `p` (checked: one finite row per vertex).
fn set_points(this: &PyLimit, py: Python<'_>, p: subsurf::Positions) -> PyResult<()> {
    if p.len() != this.num_vertices {
        return Err(value_error(format!(
            "positions: {} rows for {} vertices",
            p.len(),
            this.num_vertices
        )));
    }
    if let Some(v) = (0..p.len()).position(|i| p.get_f64(i).iter().any(|x| !x.is_finite())) {
        return Err(crate::errors::mesh_error(
            py,
            &subsurf::MeshError::NonFiniteCoordinate {
                vertex: v,
                value: f32::NAN,
            },
        ));
    }
    match &this.kind {
        Kind::Quad {
            positions, surface, ..
        } => py.detach(|| {
            let mut pos = positions.lock().map_err(poisoned)?;
            each!(surface, surface => {
                let mut s = surface.write().map_err(poisoned)?;
                // A copy only while an evaluation still holds the surface.
                Arc::make_mut(&mut s).set_positions(&p);
            });
            *pos = p;
            Ok::<_, PyErr>(())
        })?,
        Kind::Loop {
            topo,
            isolation,
            surface,
        } => {
            let (t, iso) = (topo.clone(), *isolation);
            let s = py
                .detach(move || LoopLimit::at_precision(&t, &p, iso))
                .map_err(|e| lib_error(py, e, None))?;
            *surface.write().map_err(poisoned)? = Arc::new(s);
        }
    }
    Ok(())
}

#[pymethods]
impl PyLimit {
    #[new]
    #[pyo3(signature = (mesh, isolation=4, editable=false))]
    fn new(py: Python<'_>, mesh: &PyMesh, isolation: u32, editable: bool) -> PyResult<Self> {
        if isolation > subsurf::limit::MAX_ISOLATION_LEVEL {
            return Err(value_error(format!(
                "isolation {isolation}: at most {}",
                subsurf::limit::MAX_ISOLATION_LEVEL
            )));
        }
        let m = mesh.inner.clone();
        let f64 = mesh.f64 && m.positions.is_f64();
        let kind = py
            .detach(move || build(&m, isolation, editable, f64))
            .map_err(|e| lib_error(py, e, None))?;
        Ok(PyLimit {
            kind,
            num_vertices: mesh.inner.positions.len(),
            f64,
        })
    }

    /// Whether the surface is double precision (built from float64 positions).
    #[getter]
    fn f64(&self) -> bool {
        self.f64
    }

    /// New control points (same count), e.g. after a deformation.
    fn update(&self, py: Python<'_>, positions: PyReadonlyArray2<'_, f32>) -> PyResult<()> {
        let p = rows::<3, f32>(&positions, "positions")?;
        set_points(self, py, subsurf::Positions::from(p))
    }

    /// New control points in float64 (a double-precision surface keeps them unrounded).
    fn update_f64(&self, py: Python<'_>, positions: PyReadonlyArray2<'_, f64>) -> PyResult<()> {
        let p = rows::<3, f64>(&positions, "positions")?;
        set_points(self, py, subsurf::Positions::from_f64(p))
    }

    /// (positions, du, dv) at faces `faces` and parameters `u`, `v`: ptex faces and `[0, 1]²`
    /// (float32 results, float64 for a double-precision surface) or Loop base triangles and
    /// `u, v >= 0, u + v <= 1` (float64).
    fn evaluate(
        &self,
        py: Python<'_>,
        faces: PyReadonlyArray1<'_, u32>,
        u: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Arrays3> {
        let f = vec1(&faces, "faces")?;
        let u = vec1(&u, "u")?;
        let v = vec1(&v, "v")?;
        if f.len() != u.len() || f.len() != v.len() {
            return Err(value_error(format!(
                "faces, u, v: lengths {}, {}, {}",
                f.len(),
                u.len(),
                v.len()
            )));
        }
        let q: Vec<(u32, f64, f64)> = f
            .iter()
            .zip(&u)
            .zip(&v)
            .map(|((&f, &u), &v)| (f, u, v))
            .collect();
        match &self.kind {
            Kind::Quad {
                surface,
                num_ptex_faces,
                ..
            } => {
                let count = *num_ptex_faces;
                for (k, &(f, u, v)) in q.iter().enumerate() {
                    subsurf::limit::check_square(k, f as u64, u, v, count)
                        .map_err(|e| value_error(e.to_string()))?;
                }
                each!(surface, s => eval_quads(py, s, &q))
            }
            Kind::Loop { surface, .. } => {
                let s = read(surface)?;
                let r = py
                    .detach(move || {
                        s.eval_batch(&q).map(|r| {
                            split(
                                r.into_iter().map(|x| x.map(|l| [l.p, l.du, l.dv])),
                                f64::NAN,
                            )
                        })
                    })
                    .map_err(|e| lib_error(py, e, None))?;
                out3x(py, r)
            }
        }
    }

    /// New crease sharpness for the base edges `creases` (vertex pairs, `crease_sharpness` one
    /// value each) and corner sharpness for the vertices `corners` (`corner_sharpness`), later
    /// entries of the same element winning: the patch table is updated in place where its
    /// isolation structure is kept, rebuilt locally where it changes over a bounded region
    /// (`"local"`) and rebuilt otherwise (from the first level whose faces are decided
    /// differently, the levels above kept), its surface either way that of the edited mesh,
    /// and the points are made again from the current control points.
    /// Returns `"unchanged"`, `"updated"`, `"local"` or `"rebuilt"`. Every edit is checked first
    /// (`MeshError` naming the edit, `.edit`); Loop meshes are refused.
    fn set_sharpness(
        &self,
        py: Python<'_>,
        creases: PyReadonlyArray2<'_, u32>,
        crease_sharpness: PyReadonlyArray1<'_, f32>,
        corners: PyReadonlyArray1<'_, u32>,
        corner_sharpness: PyReadonlyArray1<'_, f32>,
    ) -> PyResult<&'static str> {
        let pairs = rows::<2, u32>(&creases, "creases")?;
        let s = vec1(&crease_sharpness, "crease sharpness")?;
        let cv = vec1(&corners, "corners")?;
        let cs = vec1(&corner_sharpness, "corner sharpness")?;
        if pairs.len() != s.len() || cv.len() != cs.len() {
            return Err(value_error(format!(
                "{} creases with {} sharpness values, {} corners with {} values",
                pairs.len(),
                s.len(),
                cv.len(),
                cs.len()
            )));
        }
        let edits: Vec<SharpnessEdit> = (pairs.iter().zip(&s))
            .map(|(&[v0, v1], &sharpness)| SharpnessEdit::Edge { v0, v1, sharpness })
            .chain(
                cv.iter()
                    .zip(&cs)
                    .map(|(&vertex, &sharpness)| SharpnessEdit::Vertex { vertex, sharpness }),
            )
            .collect();
        let Kind::Quad {
            positions, surface, ..
        } = &self.kind
        else {
            return Err(lib_error(
                py,
                subsurf::Error::Unsupported(
                    "sharpness edits of a Loop limit surface (build it again from the edited \
                     mesh)"
                        .into(),
                ),
                None,
            ));
        };
        let outcome = py.detach(|| {
            let pos = positions.lock().map_err(|_| None)?;
            each!(surface, surface => {
                let mut s = surface.write().map_err(|_| None)?;
                Arc::make_mut(&mut s).apply_sharpness(&edits, &*pos).map_err(Some)
            })
        });
        match outcome {
            Ok(EditOutcome::Unchanged) => Ok("unchanged"),
            Ok(EditOutcome::Updated) => Ok("updated"),
            Ok(EditOutcome::Rebuilt | EditOutcome::RebuiltFrom { .. }) => Ok("rebuilt"),
            Ok(EditOutcome::Local { .. }) => Ok("local"),
            Err(Some(e)) => Err(lib_error(py, e, None)),
            Err(None) => Err(poisoned(())),
        }
    }

    /// Watertight tessellation with `tess` samples per side of every ptex face or Loop
    /// triangle (positions and normals float64 for a double-precision surface).
    fn tessellate(&self, py: Python<'_>, tess: usize) -> PyResult<Arrays3> {
        check_tess(tess)?;
        let n = tess;
        match &self.kind {
            Kind::Quad {
                surface: Quads::F32(surface),
                ..
            } => {
                let s = read(surface)?;
                let t = py
                    .detach(move || s.tessellate(n))
                    .map_err(|e| lib_error(py, e, None))?;
                let tris = t.triangles();
                tess_out(py, t.positions, t.normals, tris)
            }
            Kind::Quad {
                surface: Quads::F64(surface),
                ..
            } => {
                let s = read(surface)?;
                let (plan, points) = py
                    .detach(move || s.tessellate_real(n))
                    .map_err(|e| lib_error(py, e, None))?;
                let positions = points.iter().map(|e| e.p).collect();
                let normals = points.iter().map(|e| e.n).collect();
                tess_out(py, positions, normals, plan.triangles())
            }
            Kind::Loop { topo, surface, .. } => {
                let (s, t) = (read(surface)?, topo.clone());
                let tess = py
                    .detach(move || s.tessellate(&t, n - 1))
                    .map_err(|e| lib_error(py, e, None))?;
                let tris = |m: &Mesh| {
                    m.face_indices
                        .chunks_exact(3)
                        .map(|c| [c[0], c[1], c[2]])
                        .collect()
                };
                if self.f64 {
                    let (mesh, normals) = tess.to_mesh_f64();
                    let tris = tris(&mesh);
                    tess_out(py, mesh.positions.to_f64().into_owned(), normals, tris)
                } else {
                    let (mesh, normals) = tess.to_mesh();
                    let tris = tris(&mesh);
                    tess_out(py, mesh.positions.into_f32(), normals, tris)
                }
            }
        }
    }

    /// Faces a query may name: ptex faces, or base triangles of a Loop mesh.
    #[getter]
    fn num_ptex_faces(&self) -> usize {
        match &self.kind {
            Kind::Quad { num_ptex_faces, .. } => *num_ptex_faces,
            Kind::Loop { surface, .. } => read(surface).map_or(0, |s| s.num_faces()),
        }
    }

    /// `"square"` (ptex faces, `[0, 1]²`) or `"triangle"` (Loop, `u + v <= 1`).
    #[getter]
    fn domain(&self) -> &'static str {
        match &self.kind {
            Kind::Quad { .. } => "square",
            Kind::Loop { .. } => "triangle",
        }
    }
}
