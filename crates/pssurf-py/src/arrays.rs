//! NumPy arrays in and out. The Python layer hands over C-contiguous float64 / int64 arrays
//! (it converts float32, non-contiguous and read-only input); these helpers check shapes and
//! name the argument in every error.

use nalgebra::{Point2, Vector2};
use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::errors::value_error;

/// The contiguous data of a 1-D array.
pub fn slice<'a>(a: &'a PyReadonlyArray1<'_, f64>, name: &str) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| value_error(format!("{name} must be a contiguous float64 array")))
}

/// The rows of an (n, width) array, flat.
fn rows<'a, T: numpy::Element>(
    a: &'a PyReadonlyArray2<'_, T>,
    width: usize,
    name: &str,
) -> PyResult<&'a [T]> {
    let shape = a.shape();
    if shape[1] != width {
        return Err(value_error(format!(
            "{name} must have shape (n, {width}), not ({}, {})",
            shape[0], shape[1]
        )));
    }
    a.as_slice()
        .map_err(|_| value_error(format!("{name} must be a contiguous array")))
}

/// Any array-like (list, float32, strided, read-only) as a C-contiguous float64 NumPy array,
/// converted by NumPy itself; a `ValueError` naming `name` when NumPy cannot.
pub fn float64_array<'py>(obj: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = obj.py().import("numpy")?;
    let kwargs = pyo3::types::PyDict::new(obj.py());
    kwargs.set_item("dtype", "float64")?;
    np.call_method("ascontiguousarray", (obj,), Some(&kwargs))
        .map_err(|e| value_error(format!("{name} must be an array of real numbers: {e}")))
}

/// Points from an (n, 2) array.
pub fn points_from(a: &PyReadonlyArray2<'_, f64>, name: &str) -> PyResult<Vec<Point2<f64>>> {
    Ok(rows(a, 2, name)?
        .chunks_exact(2)
        .map(|r| Point2::new(r[0], r[1]))
        .collect())
}

/// Vectors from an (n, 2) array.
pub fn vectors_from(a: &PyReadonlyArray2<'_, f64>, name: &str) -> PyResult<Vec<Vector2<f64>>> {
    Ok(rows(a, 2, name)?
        .chunks_exact(2)
        .map(|r| Vector2::new(r[0], r[1]))
        .collect())
}

/// Triangles from an (m, 3) array of indices into `vertices` points.
pub fn triangles_from(a: &PyReadonlyArray2<'_, i64>, vertices: usize) -> PyResult<Vec<[usize; 3]>> {
    rows(a, 3, "triangles")?
        .chunks_exact(3)
        .enumerate()
        .map(|(t, r)| {
            let mut out = [0usize; 3];
            for (o, &i) in out.iter_mut().zip(r) {
                *o = usize::try_from(i)
                    .ok()
                    .filter(|&i| i < vertices)
                    .ok_or_else(|| {
                        value_error(format!(
                            "triangle {t} refers to point {i}, but there are {vertices} points"
                        ))
                    })?;
            }
            Ok(out)
        })
        .collect()
}

/// A flat row-major vector of indices as an (m, 3) array.
pub fn rows3<'py>(py: Python<'py>, flat: Vec<i64>) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let n = flat.len() / 3;
    PyArray1::from_vec(py, flat).reshape([n, 3])
}

/// A flat row-major vector as an (n, width) float array.
pub fn float_rows<'py>(
    py: Python<'py>,
    flat: Vec<f64>,
    width: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = flat.len() / width;
    PyArray1::from_vec(py, flat).reshape([n, width])
}
