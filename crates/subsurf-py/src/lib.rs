//! `subsurf._subsurf`: the compiled part of the `subsurf` Python package. The Python layer
//! (`python/subsurf/__init__.py`) normalizes arguments (dtypes, shapes, the three face
//! layouts) and documents the API; this module does the work with the GIL released.

mod arrays;
mod errors;
mod limit;
mod mesh;
mod ops;

use pyo3::prelude::*;

#[pymodule]
fn _subsurf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // At import, before the package starts any thread: keeps Mesa's display layer from printing
    // a Wayland error on machines without a display server (see `subsurf_gpu::headless`).
    #[cfg(feature = "gpu")]
    subsurf_gpu::headless::disable_display_layers_when_headless();
    m.add_class::<mesh::PyMesh>()?;
    m.add_class::<ops::PyRefiner>()?;
    m.add_class::<limit::PyLimit>()?;
    m.add_class::<ops::PyPrep>()?;
    m.add_function(wrap_pyfunction!(ops::refine, m)?)?;
    m.add_function(wrap_pyfunction!(ops::tessellate, m)?)?;
    #[cfg(feature = "gpu")]
    m.add_function(wrap_pyfunction!(ops::render, m)?)?;
    Ok(())
}
