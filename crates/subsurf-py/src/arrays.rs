//! numpy in and out. Inputs arrive C-contiguous with the right dtype (the Python layer calls
//! `numpy.ascontiguousarray`, which copies only when needed); outputs are numpy arrays that
//! own the Rust buffers (`Vec` handed over, no copy).

use numpy::ndarray::{Array1, Array2, Array3, Array4};
use numpy::{Element, IntoPyArray, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::value_error;

/// Rows of a (n, N) array.
pub fn rows<const N: usize, T: Element + Copy + Default>(
    a: &PyReadonlyArray2<'_, T>,
    what: &str,
) -> PyResult<Vec<[T; N]>> {
    let s = a.shape();
    if s[1] != N {
        return Err(value_error(format!(
            "{what}: expected shape (n, {N}), got {s:?}"
        )));
    }
    let flat = a
        .as_slice()
        .map_err(|_| value_error(format!("{what}: not C-contiguous")))?;
    Ok(flat
        .chunks_exact(N)
        .map(|c| {
            let mut r = [T::default(); N];
            r.copy_from_slice(c);
            r
        })
        .collect())
}

/// A 1-D array as a Vec.
pub fn vec1<T: Element + Copy>(a: &PyReadonlyArray1<'_, T>, what: &str) -> PyResult<Vec<T>> {
    Ok(a.as_slice()
        .map_err(|_| value_error(format!("{what}: not C-contiguous")))?
        .to_vec())
}

fn shape_err(e: impl std::fmt::Display) -> PyErr {
    pyo3::exceptions::PyRuntimeError::new_err(format!("internal array shape error: {e}"))
}

/// (n, N) array owning `v`.
pub fn out2<const N: usize, T: Element>(py: Python<'_>, v: Vec<[T; N]>) -> PyResult<Py<PyAny>> {
    let n = v.len();
    let a = Array2::from_shape_vec((n, N), v.into_flattened()).map_err(shape_err)?;
    Ok(a.into_pyarray(py).into_any().unbind())
}

/// (n,) array owning `v`.
pub fn out1<T: Element>(py: Python<'_>, v: Vec<T>) -> Py<PyAny> {
    Array1::from_vec(v).into_pyarray(py).into_any().unbind()
}

/// (n, a, b) array owning `v`.
pub fn out3<T: Element>(py: Python<'_>, v: Vec<T>, a: usize, b: usize) -> PyResult<Py<PyAny>> {
    let n = v.len() / (a * b).max(1);
    let arr = Array3::from_shape_vec((n, a, b), v).map_err(shape_err)?;
    Ok(arr.into_pyarray(py).into_any().unbind())
}

/// (n, a, b, c) array owning `v`.
pub fn out4<T: Element>(
    py: Python<'_>,
    v: Vec<T>,
    a: usize,
    b: usize,
    c: usize,
) -> PyResult<Py<PyAny>> {
    let n = v.len() / (a * b * c).max(1);
    let arr = Array4::from_shape_vec((n, a, b, c), v).map_err(shape_err)?;
    Ok(arr.into_pyarray(py).into_any().unbind())
}
