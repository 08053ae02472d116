//! `PsInterpolator`'s engine: the Hermite PS-spline through scattered data (thesis (2.30),
//! (2.49)) and its evaluation at many points with the GIL released.

use std::sync::Arc;

use nalgebra::{Point2, Vector2};
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pssurf::prelude::*;
use pssurf::scattered::{
    FitError, GradientMethod, NEAR_DUPLICATE, check_points, data_basis_with, estimate_gradients_by,
    hermite_data, hermite_spline_with, interpolate_with, merge_near_duplicates,
};
use pssurf::triangulation::{MAX_COORDINATE, morton_order};
use pyo3::prelude::*;

use crate::arrays::{float_rows, points_from, rows3, slice, triangles_from, vectors_from};
use crate::errors::{check_budget, value_error};
use crate::evaluate::{
    Derivative, Outside, evaluate_grid, evaluate_points, graph_curvatures, jet_entries, jet_rows,
    pointwise_bytes,
};

/// The interpolant of scattered data: a functional PS-spline z = s(x, y) on a triangulation
/// of the data points (the engine of `pssurf.PsInterpolator`).
#[pyclass(module = "pssurf._core", frozen)]
pub struct Interpolant {
    /// The spline; its PS-triangles are Dierckx's optimal ones unless `deferred`.
    spline: PsSpline<f64>,
    /// For a spline on [`PsTriangleChoice::Circumscribed`] triangles (its function does not
    /// depend on them, and they cost a tenth as much): what builds its B-spline form on the
    /// optimal ones when asked for.
    deferred: Option<Deferred>,
}

/// What an interpolant on circumscribed PS-triangles keeps to build its B-spline form on
/// the optimal ones, exactly as `pssurf fit` builds it.
struct Deferred {
    /// The Hermite data at each vertex.
    hermite: Vec<Hermite<f64>>,
    /// The caller's point of each vertex, for errors.
    point_of: Vec<usize>,
}

impl Interpolant {
    /// An (n, W) array of `row` evaluated from the jet at each point, the GIL released.
    fn rows<'py, const W: usize>(
        &self,
        py: Python<'py>,
        x: &PyReadonlyArray1<'_, f64>,
        y: &PyReadonlyArray1<'_, f64>,
        fill: Option<f64>,
        row: impl Fn(nalgebra::Point2<f64>, &pssurf::bezier::Jet<f64>) -> [f64; W] + Sync + Send,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (x, y) = (slice(x, "x")?, slice(y, "y")?);
        check_budget(
            &format!("{W} numbers at each of {} points", x.len()),
            x.len() as u128 * pointwise_bytes(W),
        )?;
        let out = py
            .detach(|| jet_rows(&self.spline, x, y, Outside::from(fill), row))
            .map_err(value_error)?;
        float_rows(py, out, W)
    }

    /// The spline, for evaluation: its B-spline coefficients and PS-triangles may be the
    /// circumscribed ones (see `surface` for the optimal form).
    pub fn spline(&self) -> &PsSpline<f64> {
        &self.spline
    }

    /// Wraps a spline made elsewhere (a smoothing fit).
    pub fn from_spline(spline: PsSpline<f64>) -> Self {
        Interpolant {
            spline,
            deferred: None,
        }
    }
}

/// Bytes per data point of building an interpolant (measured for `pssurf fit`: 2.2 kB local,
/// 2.1 kB global, 7.2 kB least-jump; rounded up as the CLI's budget does).
fn bytes_per_point(method: GradientMethod) -> u128 {
    match method {
        GradientMethod::Local => 3 * 1024,
        GradientMethod::Global => 4 * 1024,
        GradientMethod::Jumps => 9 * 1024,
    }
}

/// Parses the gradient method's name.
fn gradient_method(name: &str) -> PyResult<GradientMethod> {
    match name {
        "local" => Ok(GradientMethod::Local),
        "global" => Ok(GradientMethod::Global),
        "jumps" => Ok(GradientMethod::Jumps),
        _ => Err(value_error(format!(
            "gradient_method must be \"local\", \"global\" or \"jumps\", not {name:?}"
        ))),
    }
}

/// Parses the split rule's name.
fn split_rule(name: &str) -> PyResult<SplitRule> {
    match name {
        "incenter" | "incentre" => Ok(SplitRule::Incenter),
        "centroid" => Ok(SplitRule::Centroid),
        _ => Err(value_error(format!(
            "split must be \"incenter\" or \"centroid\", not {name:?}"
        ))),
    }
}

/// The data of a fit, converted from NumPy.
struct Data {
    points: Vec<Point2<f64>>,
    values: Vec<f64>,
    gradients: Option<Vec<Vector2<f64>>>,
    triangles: Option<Vec<[usize; 3]>>,
}

/// The PS-triangles an interpolant is built on: circumscribed ones when its gradients are
/// given or estimated locally or globally (see the `deferred` field of [`Interpolant`]),
/// the optimal ones for the least-jump estimate. That estimate's system is assembled on the
/// PS-triangles, so its rounding depends on them; on the optimal ones it is the CLI's to
/// the last bit. (The global estimate does not read the PS-triangles.)
fn ps_triangles_for(method: GradientMethod, gradients_given: bool) -> PsTriangleChoice {
    match method {
        GradientMethod::Jumps if !gradients_given => PsTriangleChoice::Optimal,
        _ => PsTriangleChoice::Circumscribed,
    }
}

/// What a spline built on `choice` keeps for its optimal form (see [`Deferred`]).
fn deferred(
    choice: &PsTriangleChoice,
    hermite: Vec<Hermite<f64>>,
    point_of: impl FnOnce() -> Vec<usize>,
) -> Option<Deferred> {
    (*choice != PsTriangleChoice::Optimal).then(|| Deferred {
        hermite,
        point_of: point_of(),
    })
}

/// A built interpolant and what the caller should be warned about.
struct Built {
    spline: PsSpline<f64>,
    /// What builds its optimal form, unless it has it.
    deferred: Option<Deferred>,
    /// Groups of nearly coincident points merged into one vertex (indices of the points
    /// given; only the Delaunay path merges).
    merged: Vec<Vec<usize>>,
    /// Boundary slivers left out of the Delaunay domain (indices of the points given).
    peeled: Vec<[usize; 3]>,
}

/// Builds the spline: the library's [`interpolate_with`] when only values are given on the
/// Delaunay triangulation with the incentre split; else triangulate (or take the given
/// triangles), build the basis, and take or estimate the gradients. Errors name the
/// caller's points, whatever order the vertices are in.
fn build(data: Data, method: GradientMethod, split: SplitRule) -> Result<Built, String> {
    if data.points.len() != data.values.len() {
        return Err(format!(
            "{} points but {} values",
            data.points.len(),
            data.values.len()
        ));
    }
    if data.gradients.is_none() && data.triangles.is_none() && split == SplitRule::Incenter {
        let choice = ps_triangles_for(method, false);
        return interpolate_with(&data.points, &data.values, method, &choice)
            .map(|i| Built {
                deferred: deferred(&choice, i.hermite, || i.data_index),
                spline: i.spline,
                merged: i.merged,
                peeled: i.peeled,
            })
            .map_err(|e| e.to_string());
    }
    if let Some(k) = data
        .values
        .iter()
        .position(|v| !(v.abs() <= MAX_COORDINATE))
    {
        return Err(FitError::NonFiniteValue(k).to_string());
    }
    // Checked in the caller's numbering, before any reordering.
    if let Some(g) = &data.gradients {
        if g.len() != data.points.len() {
            return Err(format!(
                "{} points but {} gradients",
                data.points.len(),
                g.len()
            ));
        }
        if let Some(k) = g.iter().position(|g| !(g.x.is_finite() && g.y.is_finite())) {
            return Err(format!("the gradient of point {k} is not finite"));
        }
    }
    check_points(&data.points).map_err(|e| e.to_string())?;
    let Data {
        mut points,
        mut values,
        mut gradients,
        triangles,
    } = data;
    // Vertex k of the triangulation is point vertex_point[k] (no reordering: None).
    let mut vertex_point: Option<Vec<usize>> = None;
    let (mut peeled, mut merged) = (Vec::new(), Vec::new());
    let tri = match triangles {
        Some(t) => Triangulation::try_new(points, t).map_err(|e| e.to_string())?,
        None => {
            // Nearly coincident points become one at their mean, with the mean value and
            // gradient, as `pssurf fit` merges its rows.
            let data = merge_near_duplicates(&points, &values, NEAR_DUPLICATE);
            let gradients_merged = gradients.map(|g| data.mean_of(&g));
            // A space-filling-curve order keeps neighbours close in memory.
            let o = morton_order(&data.points);
            points = o.iter().map(|&i| data.points[i as usize]).collect();
            values = o.iter().map(|&i| data.values[i as usize]).collect();
            gradients = gradients_merged.map(|g| o.iter().map(|&i| g[i as usize]).collect());
            let vp: Vec<usize> = o.iter().map(|&i| data.first_index[i as usize]).collect();
            let (tri, sliver) = Triangulation::delaunay_with_peeled(points)
                .map_err(|e| FitError::from(e).map_points(|v| vp[v]).to_string())?;
            peeled = sliver.iter().map(|t| t.map(|v| vp[v])).collect();
            merged = data.merged;
            vertex_point = Some(vp);
            tri
        }
    };
    let point_of = |v: usize| vertex_point.as_ref().map_or(v, |vp| vp[v]);
    let named = |e: FitError| e.map_points(point_of).to_string();
    let choice = ps_triangles_for(method, gradients.is_some());
    let basis = Arc::new(data_basis_with(tri, split, &choice).map_err(named)?);
    let gradients = match gradients {
        Some(g) => g,
        None => {
            estimate_gradients_by(&basis, &values, method)
                .map_err(named)?
                .0
        }
    };
    let hermite = hermite_data(&values, &gradients);
    let n = basis.triangulation().vertex_count();
    let spline = hermite_spline_with(basis, &hermite, &choice).map_err(named)?;
    Ok(Built {
        deferred: deferred(&choice, hermite, || (0..n).map(point_of).collect()),
        spline,
        merged,
        peeled,
    })
}

/// Warnings of one kind issued one by one, at most (then one for the rest).
const NAMED_WARNINGS: usize = 5;

/// A `UserWarning` for each merged group of nearly coincident points (as the CLI warns).
fn warn_merged(py: Python<'_>, groups: &[Vec<usize>], gradients_given: bool) -> PyResult<()> {
    let means = if gradients_given {
        "value and gradient"
    } else {
        "value"
    };
    let messages = groups.iter().map(|g| {
        let named: Vec<String> = g.iter().map(|k| k.to_string()).collect();
        format!(
            "points {} are nearly coincident: merged into one vertex at their mean, with their mean {means}",
            named.join(", ")
        )
    });
    let more = |n: usize| format!("{n} more groups of nearly coincident points were merged");
    warn_each(py, messages, groups.len(), more)
}

/// A `UserWarning` for each boundary sliver left out of the domain (as the CLI warns).
fn warn_peeled(py: Python<'_>, peeled: &[[usize; 3]]) -> PyResult<()> {
    let messages = peeled.iter().map(|[a, b, c]| {
        format!(
            "points {a}, {b} and {c} are nearly collinear on the boundary: the sliver between them (thinner than {:e} of its length) is left out of the domain",
            pssurf::triangulation::PEEL_THICKNESS
        )
    });
    let more = |n: usize| format!("{n} more boundary slivers left out");
    warn_each(py, messages, peeled.len(), more)
}

/// Issues the first [`NAMED_WARNINGS`] of `count` messages as `UserWarning`s, and one
/// `more(rest)` for the rest.
fn warn_each(
    py: Python<'_>,
    messages: impl Iterator<Item = String>,
    count: usize,
    more: impl Fn(usize) -> String,
) -> PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    let rest = count.saturating_sub(NAMED_WARNINGS);
    let tail = (rest > 0).then(|| more(rest));
    for message in messages.take(NAMED_WARNINGS).chain(tail) {
        let message = std::ffi::CString::new(message).expect("no NUL in the message");
        PyErr::warn(py, category.as_any(), &message, 2)?;
    }
    Ok(())
}

/// The spline of the deferred Hermite data on the refinement of `spline` and optimal
/// PS-triangles; errors name the caller's points.
fn optimal_spline(spline: &PsSpline<f64>, deferred: &Deferred) -> Result<PsSpline<f64>, String> {
    let named = |e: FitError| e.map_points(|v| deferred.point_of[v]).to_string();
    let optimal = spline
        .basis()
        .with_ps_triangles(&PsTriangleChoice::Optimal)
        .map_err(|e| named(e.into()))?;
    hermite_spline_with(
        Arc::new(optimal),
        &deferred.hermite,
        &PsTriangleChoice::Optimal,
    )
    .map_err(named)
}

#[pymethods]
impl Interpolant {
    /// Fits the interpolant; see `pssurf.PsInterpolator`.
    #[new]
    #[pyo3(signature = (points, values, gradients, triangles, gradient_method, split))]
    fn new(
        py: Python<'_>,
        points: PyReadonlyArray2<'_, f64>,
        values: PyReadonlyArray1<'_, f64>,
        gradients: Option<PyReadonlyArray2<'_, f64>>,
        triangles: Option<PyReadonlyArray2<'_, i64>>,
        gradient_method: &str,
        split: &str,
    ) -> PyResult<Self> {
        let method = self::gradient_method(gradient_method)?;
        let split = split_rule(split)?;
        let points = points_from(&points, "points")?;
        check_budget(
            &format!("an interpolant of {} points", points.len()),
            points.len() as u128 * bytes_per_point(method),
        )?;
        let data = Data {
            values: slice(&values, "values")?.to_vec(),
            gradients: gradients
                .map(|g| vectors_from(&g, "gradients"))
                .transpose()?,
            triangles: triangles
                .map(|t| triangles_from(&t, points.len()))
                .transpose()?,
            points,
        };
        let gradients_given = data.gradients.is_some();
        let built = py
            .detach(|| build(data, method, split))
            .map_err(value_error)?;
        warn_merged(py, &built.merged, gradients_given)?;
        warn_peeled(py, &built.peeled)?;
        Ok(Interpolant {
            spline: built.spline,
            deferred: built.deferred,
        })
    }

    /// The values (or the partial derivative ∂^(dx+dy)/∂x^dx ∂y^dy) at the points (x[k], y[k]);
    /// `fill` outside the triangulation, or a ValueError there when `fill` is None.
    #[pyo3(signature = (x, y, dx, dy, fill))]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'_, f64>,
        y: PyReadonlyArray1<'_, f64>,
        dx: u32,
        dy: u32,
        fill: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (x, y) = (slice(&x, "x")?, slice(&y, "y")?);
        let d = Derivative::new(dx, dy)?;
        check_budget(
            &format!("values at {} points", x.len()),
            x.len() as u128 * pointwise_bytes(1),
        )?;
        let out = py
            .detach(|| evaluate_points(&self.spline, x, y, d, Outside::from(fill)))
            .map_err(value_error)?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// The values (or a derivative) on the grid x × y, row-major with x[i] along rows:
    /// out[i·len(y) + j] = s(x[i], y[j]).
    #[pyo3(signature = (x, y, dx, dy, fill))]
    fn evaluate_grid<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'_, f64>,
        y: PyReadonlyArray1<'_, f64>,
        dx: u32,
        dy: u32,
        fill: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (x, y) = (slice(&x, "x")?, slice(&y, "y")?);
        let d = Derivative::new(dx, dy)?;
        check_budget(
            &format!("a {} × {} grid", x.len(), y.len()),
            (x.len() as u128) * (y.len() as u128) * 8,
        )?;
        let out = py
            .detach(|| evaluate_grid(&self.spline, x, y, d, Outside::from(fill)))
            .map_err(value_error)?;
        Ok(PyArray1::from_vec(py, out))
    }

    /// Rows [s, s_x, s_y, s_xx, s_xy, s_yy] at the points; `fill` outside.
    #[pyo3(signature = (x, y, fill))]
    fn jets<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'_, f64>,
        y: PyReadonlyArray1<'_, f64>,
        fill: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.rows(py, &x, &y, fill, jet_entries)
    }

    /// Rows [K, H, κ1, κ2] of the graph z = s(x, y) at the points; `fill` outside.
    #[pyo3(signature = (x, y, fill))]
    fn curvature<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'_, f64>,
        y: PyReadonlyArray1<'_, f64>,
        fill: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.rows(py, &x, &y, fill, graph_curvatures)
    }

    /// The triangulation's vertices, shape (n, 2) (in the spline's order).
    fn vertices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = self.spline.basis().triangulation();
        let flat: Vec<f64> = t.vertices().iter().flat_map(|p| [p.x, p.y]).collect();
        float_rows(py, flat, 2)
    }

    /// The triangles as vertex indices, shape (m, 3).
    fn triangles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let t = self.spline.basis().triangulation();
        let flat: Vec<i64> = t
            .triangles()
            .iter()
            .flat_map(|t| t.map(|v| v as i64))
            .collect();
        rows3(py, flat)
    }

    /// The interpolant as a functional PS surface (for `save`, `sample`, `fairness`).
    fn surface(&self, py: Python<'_>) -> PyResult<crate::surface::PySurface> {
        let spline = match &self.deferred {
            None => self.spline.clone(),
            Some(d) => py
                .detach(|| optimal_spline(&self.spline, d))
                .map_err(value_error)?,
        };
        Ok(crate::surface::PySurface::new(
            pssurf::surface::Surface::from(spline),
        ))
    }

    /// The number of triangles.
    fn triangle_count(&self) -> usize {
        self.spline.basis().triangulation().triangle_count()
    }
}
