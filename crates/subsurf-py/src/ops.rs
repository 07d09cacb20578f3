//! The work: refine, Refiner, Prep, tessellate, render (`LimitSurface` in `limit.rs`). Every call releases
//! the GIL for its computation (`Python::detach`).

use std::sync::Arc;

use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use subsurf::limit::PatchOptions;
use subsurf::prep::PrepPatches;
use subsurf::surface::{self, Backend, BackendName, Colors, Method, MethodName, SurfaceOptions};
use subsurf::tess::{set_edge_rate, EdgeRates, RatePolicy};
use subsurf::{FaceVarying, Mesh, Refiner, Topology};

use crate::arrays::{out1, out2, out4, rows, vec1};
use crate::errors::{gpu_error, lib_error, surface_error, value_error};
use crate::mesh::{parse, validate, PyMesh};

/// The backend named `name`; the GPU is opened once per process.
pub fn backend(py: Python<'_>, name: &str) -> PyResult<&'static dyn Backend> {
    static CPU: surface::Cpu = surface::Cpu;
    match parse(name)? {
        BackendName::Cpu => Ok(&CPU),
        BackendName::Gpu => gpu(py),
    }
}

#[cfg(feature = "gpu")]
fn gpu(py: Python<'_>) -> PyResult<&'static dyn Backend> {
    static GPU: std::sync::OnceLock<Result<subsurf_gpu::GpuBackend, String>> =
        std::sync::OnceLock::new();
    let g = py.detach(|| {
        GPU.get_or_init(|| {
            subsurf_gpu::GpuBackend::new().map_err(|e| {
                format!(
                    "{e} (install a Vulkan, Metal or DX12 driver; without a GPU, Mesa's lavapipe \
                     (`apt-get install mesa-vulkan-drivers`) with WGPU_BACKEND=vulkan works)"
                )
            })
        })
    });
    match g {
        Ok(b) => Ok(b),
        Err(e) => Err(gpu_error(py, e.clone())),
    }
}

#[cfg(not(feature = "gpu"))]
fn gpu(py: Python<'_>) -> PyResult<&'static dyn Backend> {
    Err(gpu_error(
        py,
        "this build of subsurf has no GPU backend (feature `gpu`)".into(),
    ))
}

/// Samples per side (`tess`) in 2..=1025.
pub fn check_tess(tess: usize) -> PyResult<()> {
    if !(2..=1025).contains(&tess) {
        return Err(value_error(format!("tess = {tess}: use 2..=1025")));
    }
    Ok(())
}

fn check_level(level: usize) -> PyResult<()> {
    if level > 12 {
        return Err(value_error(format!("level {level}: at most 12")));
    }
    Ok(())
}

#[pyfunction]
#[pyo3(signature = (mesh, level, limit=false, backend="cpu"))]
pub fn refine(
    py: Python<'_>,
    mesh: &PyMesh,
    level: usize,
    limit: bool,
    backend: &str,
) -> PyResult<PyMesh> {
    check_level(level)?;
    let b = self::backend(py, backend)?;
    let m = mesh.inner.clone();
    // float64 positions given from Python refine in double precision on the CPU.
    let wide = mesh.f64 && m.positions.is_f64() && backend == "cpu";
    let out = py
        .detach(move || match wide {
            true => surface::refine_mesh_f64(&m, level, limit, None),
            false => surface::refine_mesh(&m, level, limit, None, b),
        })
        .map_err(|e| surface_error(py, e))?;
    Ok(PyMesh {
        inner: Arc::new(out),
        f64: wide,
    })
}

/// Refinement tables built once, applied to any per-vertex data.
#[pyclass(frozen, name = "_Refiner", module = "subsurf._subsurf")]
pub struct PyRefiner {
    refiner: Arc<Refiner>,
    mesh: Arc<Mesh>,
    level: usize,
}

/// `flat` (rows of `N` values, read in place) through `r`.
fn apply<const N: usize>(r: &Refiner, flat: &[f32], limit: bool) -> Vec<f32> {
    let v: &[[f32; N]] = bytemuck::cast_slice(flat);
    if limit {
        return r.limit(v).into_flattened();
    }
    // Into a fresh buffer that becomes the returned array; the smooth rows of each step are
    // applied from their indices alone (`Refiner::refine_positions_into`).
    let mut out = vec![[0.0f32; N]; r.last().num_vertices()];
    let mut scratch = Vec::new();
    match r.refine_positions_into(v, &mut out, &mut scratch) {
        Ok(()) => out.into_flattened(),
        // Unreachable with the shape checked by the caller; the table path as a fallback.
        Err(_) => r.refine_positions(v).into_flattened(),
    }
}

fn apply_n(r: &Refiner, flat: &[f32], w: usize, limit: bool) -> Vec<f32> {
    match w {
        1 => apply::<1>(r, flat, limit),
        2 => apply::<2>(r, flat, limit),
        3 => apply::<3>(r, flat, limit),
        _ => apply::<4>(r, flat, limit),
    }
}

/// Per-vertex data of any width through `r`: up to 4 columns read in place, wider data in
/// groups of up to 4 columns.
fn apply_any(r: &Refiner, flat: &[f32], n: usize, d: usize, limit: bool) -> Vec<f32> {
    if d <= 4 {
        return apply_n(r, &flat[..n * d], d, limit);
    }
    let mut cols: Vec<Vec<f32>> = Vec::new();
    let mut k = 0;
    while k < d {
        let w = (d - k).min(4);
        let part: Vec<f32> = (0..n)
            .flat_map(|i| flat[i * d + k..i * d + k + w].to_vec())
            .collect();
        cols.push(apply_n(r, &part, w, limit));
        k += w;
    }
    if cols.len() == 1 {
        return cols.pop().unwrap_or_default();
    }
    let m = cols[0].len() / d.min(4);
    let mut out = Vec::with_capacity(m * d);
    for i in 0..m {
        let mut k = 0;
        for c in &cols {
            let w = (d - k).min(4);
            out.extend_from_slice(&c[i * w..(i + 1) * w]);
            k += w;
        }
    }
    out
}

/// `(n, d)` of `values` and its data, read in place: `n_expected` rows, `d >= 1`, C-contiguous.
fn value_rows<'a, T: numpy::Element>(
    values: &'a PyReadonlyArray2<'_, T>,
    n_expected: usize,
) -> PyResult<(usize, usize, &'a [T])> {
    let s = values.shape();
    if s[0] != n_expected || s[1] == 0 {
        return Err(value_error(format!(
            "values: expected shape ({n_expected}, d) with d >= 1, got {s:?}"
        )));
    }
    let flat = values
        .as_slice()
        .map_err(|_| value_error("values: not C-contiguous"))?;
    Ok((s[0], s[1], flat))
}

impl PyRefiner {
    fn run(
        &self,
        py: Python<'_>,
        values: PyReadonlyArray2<'_, f32>,
        limit: bool,
        n_expected: usize,
    ) -> PyResult<Py<PyAny>> {
        let (n, d, flat) = value_rows(&values, n_expected)?;
        let r = &self.refiner;
        let out = py.detach(|| apply_any(r, flat, n, d, limit));
        let m = out.len() / d;
        let a = numpy::ndarray::Array2::from_shape_vec((m, d), out)
            .map_err(|e| value_error(e.to_string()))?;
        Ok(numpy::IntoPyArray::into_pyarray(a, py).into_any().unbind())
    }
}

#[pymethods]
impl PyRefiner {
    #[new]
    fn new(py: Python<'_>, mesh: &PyMesh, level: usize) -> PyResult<Self> {
        check_level(level)?;
        let m = mesh.inner.clone();
        let r = py
            .detach(move || Topology::new(&m).and_then(|t| Refiner::new(t, level)))
            .map_err(|e| lib_error(py, e, None))?;
        Ok(PyRefiner {
            refiner: Arc::new(r),
            mesh: mesh.inner.clone(),
            level,
        })
    }

    fn refine(&self, py: Python<'_>, values: PyReadonlyArray2<'_, f32>) -> PyResult<Py<PyAny>> {
        self.run(py, values, false, self.mesh.positions.len())
    }

    /// float64 data in double precision: every step's masks in f64
    /// (`Refiner::refine_f64`), float64 out.
    fn refine_f64(&self, py: Python<'_>, values: PyReadonlyArray2<'_, f64>) -> PyResult<Py<PyAny>> {
        let (_, d, flat) = value_rows(&values, self.mesh.positions.len())?;
        let r = &self.refiner;
        // Column groups of up to 3 values, gathered back into rows.
        let out = py.detach(|| -> subsurf::Result<Vec<f64>> {
            let mut cols: Vec<(usize, Vec<f64>)> = Vec::new();
            let mut k = 0;
            while k < d {
                let w = (d - k).min(3);
                let part: Vec<[f64; 3]> = flat
                    .chunks_exact(d)
                    .map(|row| std::array::from_fn(|c| if c < w { row[k + c] } else { 0.0 }))
                    .collect();
                cols.push((w, r.refine_f64(&part)?.into_flattened()));
                k += w;
            }
            let m = r.last().num_vertices();
            let mut out = Vec::with_capacity(m * d);
            for i in 0..m {
                for (w, c) in &cols {
                    out.extend_from_slice(&c[3 * i..3 * i + w]);
                }
            }
            Ok(out)
        });
        let out = out.map_err(|e| lib_error(py, e, None))?;
        let a = numpy::ndarray::Array2::from_shape_vec((out.len() / d, d), out)
            .map_err(|e| value_error(e.to_string()))?;
        Ok(numpy::IntoPyArray::into_pyarray(a, py).into_any().unbind())
    }

    fn limit(&self, py: Python<'_>, values: PyReadonlyArray2<'_, f32>) -> PyResult<Py<PyAny>> {
        self.run(py, values, true, self.refiner.last().num_vertices())
    }

    /// UVs (values, per-corner indices of the base mesh) refined in the mesh's mode: the
    /// last level's (values, indices).
    fn refine_uvs(
        &self,
        py: Python<'_>,
        values: PyReadonlyArray2<'_, f32>,
        indices: PyReadonlyArray1<'_, u32>,
    ) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
        let v = rows::<2, f32>(&values, "uvs")?;
        let i = vec1(&indices, "uv_indices")?;
        let mut probe = (*self.mesh).clone();
        probe.uvs = Some(FaceVarying {
            values: v.clone(),
            indices: i.clone(),
        });
        validate(py, &probe)?;
        let r = self.refiner.clone();
        let mode = self.mesh.options.uv_interpolation;
        let last = py
            .detach(move || {
                let f = r.fvar_refinement(&i, v.len(), mode)?;
                f.refine(&v)
            })
            .map_err(|e| lib_error(py, e, None))?
            .pop()
            .ok_or_else(|| value_error("no levels"))?;
        Ok((out2(py, last.values)?, out1(py, last.indices)))
    }

    /// The refined mesh (all faces, holes and remaining sharpness tagged) with `positions`
    /// (n_last, 3).
    fn mesh(&self, py: Python<'_>, positions: PyReadonlyArray2<'_, f32>) -> PyResult<PyMesh> {
        let p = rows::<3, f32>(&positions, "positions")?;
        if p.len() != self.refiner.last().num_vertices() {
            return Err(value_error(format!(
                "positions: {} rows for {} refined vertices",
                p.len(),
                self.refiner.last().num_vertices()
            )));
        }
        let m = self
            .refiner
            .to_tagged_mesh(self.level, p)
            .map_err(|e| lib_error(py, e, None))?;
        Ok(PyMesh {
            inner: Arc::new(m),
            f64: false,
        })
    }

    /// (offsets, indices, weights): CSR rows from the base vertices to the last level.
    fn stencils(&self, py: Python<'_>) -> (Py<PyAny>, Py<PyAny>, Py<PyAny>) {
        let r = self.refiner.clone();
        let t = py.detach(move || r.stencil_table());
        (
            out1(py, t.offsets().to_vec()),
            out1(py, t.indices().to_vec()),
            out1(py, t.weights().to_vec()),
        )
    }

    #[getter]
    fn num_vertices(&self) -> usize {
        self.refiner.last().num_vertices()
    }
    #[getter]
    fn level(&self) -> usize {
        self.level
    }
}

pub(crate) fn tess_out<T: numpy::Element>(
    py: Python<'_>,
    positions: Vec<[T; 3]>,
    normals: Vec<[T; 3]>,
    triangles: Vec<[u32; 3]>,
) -> PyResult<(Py<PyAny>, Py<PyAny>, Py<PyAny>)> {
    Ok((
        out2(py, positions)?,
        out2(py, normals)?,
        out2(py, triangles)?,
    ))
}

/// The p-rep of a closed quad mesh (built in f64).
#[pyclass(frozen, name = "_Prep", module = "subsurf._subsurf")]
pub struct PyPrep {
    patches: Arc<PrepPatches<f64>>,
}

#[pymethods]
impl PyPrep {
    #[new]
    fn new(py: Python<'_>, mesh: &PyMesh) -> PyResult<Self> {
        let m = mesh.inner.clone();
        let p = py
            .detach(move || PrepPatches::<f64>::build(&m))
            .map_err(|e| lib_error(py, e, None))?;
        Ok(PyPrep {
            patches: Arc::new(p),
        })
    }

    /// (faces, 6, 6, 3) float64 bi-5 Bezier control points.
    fn bezier(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let p = self.patches.clone();
        let b = py.detach(move || p.to_bezier().into_flattened());
        out4(py, b, 6, 6, 3)
    }

    /// Watertight tessellation, `tess` samples per patch side (float64).
    fn tessellate(
        &self,
        py: Python<'_>,
        tess: usize,
    ) -> PyResult<(Py<PyAny>, Py<PyAny>, Py<PyAny>)> {
        check_tess(tess)?;
        let p = self.patches.clone();
        let t = py.detach(move || p.tessellate(tess));
        Ok((
            out2(py, t.positions)?,
            out2(py, t.normals)?,
            out2(py, t.triangles)?,
        ))
    }

    #[getter]
    fn num_faces(&self) -> usize {
        self.patches.num_faces()
    }
}

/// The surface options of `method` with `level` (refine) or `tess` (the others; `None`: the
/// default of each), as the command line's `--level` and `--tess`.
fn surface_options(
    method: &str,
    level: Option<usize>,
    tess: Option<usize>,
    color_by: &str,
    cage: bool,
    isolation: u32,
) -> PyResult<SurfaceOptions> {
    let name: MethodName = parse(method)?;
    match (name, level, tess) {
        (MethodName::Refine, _, Some(_)) => {
            return Err(value_error(
                "tess applies to method 'limit', 'prep' or 'prep-bicubic'; use level",
            ))
        }
        (MethodName::Limit | MethodName::Prep | MethodName::PrepBicubic, Some(_), _) => {
            return Err(value_error(format!(
                "level applies to method 'refine'; use tess (samples per side) with {method:?}"
            )))
        }
        _ => {}
    }
    let tess = tess.unwrap_or(8);
    let method = match name {
        MethodName::Refine => {
            let level = level.unwrap_or(3);
            check_level(level)?;
            Method::Refine {
                level,
                limit: false,
            }
        }
        MethodName::Limit => Method::Limit {
            samples: tess,
            options: PatchOptions {
                isolation_level: isolation,
                ..Default::default()
            },
        },
        MethodName::Prep | MethodName::PrepBicubic => Method::Prep {
            samples: tess,
            perturbed: name == MethodName::Prep,
        },
    };
    if name != MethodName::Refine {
        check_tess(tess)?;
    }
    if isolation > subsurf::limit::MAX_ISOLATION_LEVEL {
        return Err(value_error(format!("isolation {isolation}: too large")));
    }
    Ok(SurfaceOptions {
        method,
        colors: parse::<Colors>(color_by)?,
        cage,
    })
}

/// The adaptive rate policy of `tessellate`'s keywords (at most one), with its origin for
/// errors; `None` when none is given. `edge_rates` rows are `(v0, v1, rate)`; unlisted edges
/// take `tess − 1` segments, as `--edge-rates` takes `--tess`.
fn rate_policy(
    py: Python<'_>,
    mesh: &Mesh,
    tess: usize,
    tolerance: Option<f32>,
    max_edge_length: Option<f32>,
    edge_rates: Option<Vec<[u64; 3]>>,
) -> PyResult<Option<(RatePolicy, String)>> {
    let given = [
        tolerance.is_some(),
        max_edge_length.is_some(),
        edge_rates.is_some(),
    ];
    if given.iter().filter(|&&g| g).count() > 1 {
        return Err(value_error(
            "tolerance, max_edge_length, edge_rates: give at most one",
        ));
    }
    if let Some(e) = tolerance {
        return Ok(Some((RatePolicy::Tolerance(e), "tolerance".into())));
    }
    if let Some(l) = max_edge_length {
        return Ok(Some((
            RatePolicy::MaxEdgeLength(l),
            "max_edge_length".into(),
        )));
    }
    let Some(rows) = edge_rates else {
        return Ok(None);
    };
    let py_err = |e| lib_error(py, e, None);
    let t = Topology::new(mesh).map_err(py_err)?;
    let default = u32::try_from(tess.saturating_sub(1))
        .unwrap_or(u32::MAX)
        .max(1);
    let mut rates = EdgeRates::uniform(&t, default);
    for (k, [v0, v1, r]) in rows.into_iter().enumerate() {
        set_edge_rate(&mut rates, &t, &format!("edge_rates[{k}]"), [v0, v1], r).map_err(py_err)?;
    }
    Ok(Some((RatePolicy::Explicit(rates), "edge_rates".into())))
}

#[pyfunction]
#[pyo3(signature = (mesh, method="limit", *, level=None, tess=None, backend="cpu", isolation=4, tolerance=None, max_edge_length=None, edge_rates=None))]
// One argument per keyword of the Python `tessellate`.
#[allow(clippy::too_many_arguments)]
pub fn tessellate(
    py: Python<'_>,
    mesh: &PyMesh,
    method: &str,
    level: Option<usize>,
    tess: Option<usize>,
    backend: &str,
    isolation: u32,
    tolerance: Option<f32>,
    max_edge_length: Option<f32>,
    edge_rates: Option<PyReadonlyArray2<'_, u64>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>, Py<PyAny>)> {
    let mut o = surface_options(method, level, tess, "none", false, isolation)?;
    let rows = edge_rates
        .map(|a| rows::<3, u64>(&a, "edge_rates"))
        .transpose()?;
    if let Some((policy, origin)) = rate_policy(
        py,
        &mesh.inner,
        tess.unwrap_or(8),
        tolerance,
        max_edge_length,
        rows,
    )? {
        let Method::Limit { options, .. } = o.method else {
            return Err(value_error(format!(
                "{origin}: adaptive rates need method 'limit', not {method:?}"
            )));
        };
        o.method = Method::Adaptive {
            policy,
            origin,
            options,
        };
    }
    let b = self::backend(py, backend)?;
    let m = mesh.inner.clone();
    let s = py
        .detach(move || surface::build(&m, &o, b))
        .map_err(|e| surface_error(py, e))?;
    tess_out(py, s.positions, s.normals, s.triangles)
}

#[cfg(feature = "gpu")]
#[pyfunction]
#[pyo3(signature = (mesh, width, height, method, level, tess, view, up, color_by, cage, background, output=None))]
// One argument per keyword of the Python `render`.
#[allow(clippy::too_many_arguments)]
pub fn render(
    py: Python<'_>,
    mesh: &PyMesh,
    width: u32,
    height: u32,
    method: &str,
    level: Option<usize>,
    tess: Option<usize>,
    view: &str,
    up: &str,
    color_by: &str,
    cage: bool,
    background: &Bound<'_, PyAny>,
    output: Option<String>,
) -> PyResult<Py<PyAny>> {
    use subsurf_render::{RenderOptions, UpAxis, View};
    if !(1..=16384).contains(&width) || !(1..=16384).contains(&height) {
        return Err(value_error(format!(
            "size {width}x{height}: 1..=16384 each"
        )));
    }
    let view: View = parse(view)?;
    let up: UpAxis = parse(up)?;
    // A name or RRGGBB (as `--background`), or (r, g, b, a).
    let background = match background.extract::<String>() {
        Ok(name) => subsurf_render::parse_background(&name).map_err(value_error)?,
        Err(_) => background.extract::<[u8; 4]>().map_err(|_| {
            value_error("background: a name (white, black, transparent), RRGGBB or (r, g, b, a)")
        })?,
    };
    let o = surface_options(method, level, tess, color_by, cage, 4)?;
    let m = mesh.inner.clone();
    let r = py.detach(move || {
        let s = surface::build(&m, &o, &surface::Cpu).map_err(Err)?;
        let options = RenderOptions {
            width,
            height,
            view,
            up,
            background,
            ..Default::default()
        };
        let img = subsurf_render::render(&s.into(), &options).map_err(|e| Ok((None, e)))?;
        // Encoded by the render crate, as the command line writes its PNG files.
        if let Some(p) = &output {
            img.save_png(p).map_err(|e| Ok((Some(p.clone()), e)))?;
        }
        Ok(img)
    });
    match r {
        Ok(img) => {
            let (h, w) = (img.height as usize, img.width as usize);
            crate::arrays::out3(py, img.data, h, w * 4).and_then(|a| {
                a.bind(py)
                    .call_method1("reshape", ((h, w, 4),))
                    .map(|x| x.unbind())
            })
        }
        Err(Err(e)) => Err(surface_error(py, e)),
        Err(Ok((None, e))) => Err(gpu_error(py, e.to_string())),
        Err(Ok((Some(p), e))) => Err(pyo3::exceptions::PyOSError::new_err(format!(
            "writing {p}: {e}"
        ))),
    }
}
