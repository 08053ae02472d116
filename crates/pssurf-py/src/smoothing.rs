//! `pssurf.fit_smooth`: the least-squares PS-spline with a fairness penalty, on a coarse
//! triangulation, with λ given or chosen by generalised cross-validation.

use std::sync::Arc;

use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pssurf::ps::{Energy, SplitRule};
use pssurf::scattered::{Smoothing, data_basis, smooth_scattered, smoothing_fit};
use pssurf::triangulation::Triangulation;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{points_from, slice, triangles_from};
use crate::errors::{check_budget, value_error};
use crate::interpolator::Interpolant;

/// The coarse triangulation: about `m` vertices chosen by the library, or given vertices
/// (and optionally triangles).
enum Coarse {
    /// About this many vertices on a grid over the data.
    Count(usize),
    /// These vertices (Delaunay unless triangles are given).
    Given(Vec<nalgebra::Point2<f64>>, Option<Vec<[usize; 3]>>),
}

/// Smoothing fit of values at points: returns (interpolant engine, report dict).
#[pyfunction]
#[pyo3(signature = (points, values, vertices, triangles, smooth, energy))]
#[allow(clippy::too_many_arguments)]
pub fn fit_smooth<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'_, f64>,
    values: PyReadonlyArray1<'_, f64>,
    vertices: &Bound<'_, PyAny>,
    triangles: Option<PyReadonlyArray2<'_, i64>>,
    smooth: &Bound<'_, PyAny>,
    energy: &str,
) -> PyResult<(Interpolant, Bound<'py, PyDict>)> {
    let pts = points_from(&points, "points")?;
    let values = slice(&values, "values")?.to_vec();
    let coarse = if let Ok(m) = vertices.extract::<usize>() {
        if triangles.is_some() {
            return Err(value_error(
                "triangles need explicit vertices (an (m, 2) array), not a count",
            ));
        }
        if m < 3 {
            return Err(value_error(format!("vertices={m}: needs at least 3")));
        }
        Coarse::Count(m)
    } else {
        let v: PyReadonlyArray2<'_, f64> = vertices.extract().map_err(|_| {
            value_error("vertices must be a count or an (m, 2) array of coordinates")
        })?;
        let v = points_from(&v, "vertices")?;
        let t = triangles.map(|t| triangles_from(&t, v.len())).transpose()?;
        Coarse::Given(v, t)
    };
    let smoothing = if let Ok(l) = smooth.extract::<f64>() {
        if !(l >= 0.0 && l.is_finite()) {
            return Err(value_error(format!(
                "smooth must be finite and ≥ 0, not {l}"
            )));
        }
        Smoothing::Fixed(l + 0.0)
    } else if smooth.extract::<String>().is_ok_and(|s| s == "gcv") {
        Smoothing::Gcv
    } else {
        return Err(value_error("smooth must be a number λ ≥ 0 or \"gcv\""));
    };
    let energy = match energy {
        "hessian_jumps" => Energy::HessianJumps,
        "thin_plate" => Energy::ThinPlate,
        _ => {
            return Err(value_error(format!(
                "energy must be \"hessian_jumps\" or \"thin_plate\", not {energy:?}"
            )));
        }
    };
    let coarse_vertices = match &coarse {
        Coarse::Count(m) => (*m).min(pts.len()),
        Coarse::Given(v, _) => v.len(),
    };
    // The CLI's measured bound: 2 kB per data point and 20 kB per coarse vertex.
    check_budget(
        &format!("a smoothing fit on {coarse_vertices} vertices"),
        pts.len() as u128 * 2048 + coarse_vertices as u128 * 20 * 1024,
    )?;
    let fit = py
        .detach(|| {
            let mut quiet = |_: &pssurf::scattered::Trial| {};
            match coarse {
                Coarse::Count(m) => {
                    smooth_scattered(&pts, &values, m, energy, smoothing, &mut quiet)
                        .map_err(|e| e.to_string())
                }
                Coarse::Given(v, t) => {
                    let tri = match t {
                        Some(t) => Triangulation::try_new(v, t),
                        None => Triangulation::delaunay(v),
                    }
                    .map_err(|e| format!("the coarse triangulation: {e}"))?;
                    let basis = data_basis(tri, SplitRule::Incenter).map_err(|e| e.to_string())?;
                    smoothing_fit(
                        Arc::new(basis),
                        &pts,
                        &values,
                        energy,
                        smoothing,
                        &mut quiet,
                    )
                    .map_err(|e| e.to_string())
                }
            }
        })
        .map_err(value_error)?;
    let report = PyDict::new(py);
    report.set_item("smooth", fit.lambda)?;
    report.set_item("rms_residual", fit.rms_residual)?;
    report.set_item("effective_dof", fit.effective_dof)?;
    report.set_item("dof_estimated", fit.dof_estimated)?;
    report.set_item("gcv", fit.gcv)?;
    Ok((Interpolant::from_spline(fit.spline), report))
}
