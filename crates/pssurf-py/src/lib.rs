//! The native half of the `pssurf` Python package (`pssurf._core`): interpolation of
//! scattered data, smoothing fits and surfaces, with NumPy arrays in and out and the GIL
//! released in every loop. The SciPy-style interface (`PsInterpolator`, broadcasting,
//! `grid=True`) is in `python/pssurf/__init__.py`.

mod arrays;
mod errors;
mod evaluate;
mod interpolator;
mod smoothing;
mod surface;

use pyo3::prelude::*;

// mimalloc keeps freed memory for reuse and per-thread heaps: with glibc's allocator each
// interpolant's large fresh buffers were mapped, faulted in and unmapped again, and the
// threads of a parallel fit contended for its arena lock (measured in docs/performance.md).
// Arrays handed to NumPy are freed by the same allocator when NumPy drops them.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// The module `pssurf._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<interpolator::Interpolant>()?;
    m.add_class::<surface::PySurface>()?;
    m.add_class::<surface::Wavelet>()?;
    m.add_function(wrap_pyfunction!(surface::load, m)?)?;
    m.add_function(wrap_pyfunction!(surface::ups, m)?)?;
    m.add_function(wrap_pyfunction!(smoothing::fit_smooth, m)?)?;
    Ok(())
}
