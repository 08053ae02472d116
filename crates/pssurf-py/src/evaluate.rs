//! Evaluating a functional PS-spline at many points, in parallel, for the Python layer.

use nalgebra::Point2;
use pssurf::bezier::Jet;
use pssurf::interrogate::PrincipalCurvatures;
use pssurf::ps::{Evaluator, PsSpline};
use pssurf::surface::graph_jet;
use pyo3::PyResult;

use crate::errors::value_error;

/// Which partial derivative ∂^(dx+dy) s / ∂x^dx ∂y^dy to return.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Derivative {
    dx: u32,
    dy: u32,
}

impl Derivative {
    /// Checks the orders: non-negative by type; any total order is allowed (those above 2
    /// are zero inside each quadratic piece).
    pub fn new(dx: u32, dy: u32) -> PyResult<Self> {
        if dx > 64 || dy > 64 {
            return Err(value_error(format!(
                "derivative orders dx={dx}, dy={dy} are absurd"
            )));
        }
        Ok(Derivative { dx, dy })
    }

    /// The total order.
    fn order(self) -> u32 {
        self.dx + self.dy
    }

    /// The entry of a jet (zero for orders above two: the pieces are quadratic).
    fn pick(self, j: &Jet<f64>) -> f64 {
        match (self.dx, self.dy) {
            (0, 0) => j.value,
            (1, 0) => j.dx,
            (0, 1) => j.dy,
            (2, 0) => j.dxx,
            (1, 1) => j.dxy,
            (0, 2) => j.dyy,
            _ => 0.0,
        }
    }
}

/// What to do at points outside the triangulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outside {
    /// Return this value.
    Fill(f64),
    /// Fail, naming the first such point.
    Error,
}

impl From<Option<f64>> for Outside {
    fn from(fill: Option<f64>) -> Self {
        fill.map_or(Outside::Error, Outside::Fill)
    }
}

/// The points (x[k], y[k]), or an error when the lengths differ.
fn zip_points(x: &[f64], y: &[f64]) -> Result<Vec<Point2<f64>>, String> {
    if x.len() != y.len() {
        return Err(format!("x has {} entries but y has {}", x.len(), y.len()));
    }
    Ok(x.iter().zip(y).map(|(&a, &b)| Point2::new(a, b)).collect())
}

/// Replaces the `None`s of `values` (points outside) by the fill value, `width` numbers each,
/// or fails naming the first.
fn finish<const W: usize>(
    values: Vec<Option<[f64; W]>>,
    points: &[Point2<f64>],
    outside: Outside,
) -> Result<Vec<f64>, String> {
    let mut out = Vec::with_capacity(values.len() * W);
    for (k, v) in values.into_iter().enumerate() {
        match (v, outside) {
            (Some(v), _) => out.extend_from_slice(&v),
            (None, Outside::Fill(f)) => out.extend_from_slice(&[f; W]),
            (None, Outside::Error) => {
                let p = points[k];
                return Err(format!(
                    "point {k} ({}, {}) is outside the triangulation's convex hull",
                    p.x, p.y
                ));
            }
        }
    }
    Ok(out)
}

/// s or one of its derivatives at the points (x[k], y[k]).
pub fn evaluate_points(
    spline: &PsSpline<f64>,
    x: &[f64],
    y: &[f64],
    d: Derivative,
    outside: Outside,
) -> Result<Vec<f64>, String> {
    let points = zip_points(x, y)?;
    evaluate_at(spline, &points, d, outside)
}

/// Below this many points the queries are evaluated in the caller's order (sorting them
/// along the Morton curve does not pay).
const SORT_QUERIES: usize = 4096;

/// `f` at every point: in Morton order for many points, else in the given order.
fn map<T: Send + Copy + Default>(
    spline: &PsSpline<f64>,
    points: &[Point2<f64>],
    f: impl Fn(&mut Evaluator<'_, f64>, Point2<f64>) -> T + Sync,
) -> Vec<T> {
    if points.len() >= SORT_QUERIES {
        spline.map_scattered(points, f)
    } else {
        spline.map_points(points, f)
    }
}

/// The derivative `d` of s at `p`, computing no more than it needs (the value alone, the
/// gradient, or the whole jet); `None` outside.
#[inline]
fn derivative_at(ev: &mut Evaluator<'_, f64>, p: Point2<f64>, d: Derivative) -> Option<[f64; 1]> {
    match d.order() {
        0 => ev.value(p).map(|v| [v]),
        1 => ev
            .gradient(p)
            .map(|(_, sx, sy)| [if d.dx == 1 { sx } else { sy }]),
        _ => ev.jet(p).map(|j| [d.pick(&j.jet)]),
    }
}

/// s or one of its derivatives at `points`, in parallel.
fn evaluate_at(
    spline: &PsSpline<f64>,
    points: &[Point2<f64>],
    d: Derivative,
    outside: Outside,
) -> Result<Vec<f64>, String> {
    let values = map(spline, points, |ev, p| derivative_at(ev, p, d));
    finish(values, points, outside)
}

/// s or one of its derivatives on the grid x × y, row-major: entry i·len(y) + j is at
/// (x[i], y[j]).
pub fn evaluate_grid(
    spline: &PsSpline<f64>,
    x: &[f64],
    y: &[f64],
    d: Derivative,
    outside: Outside,
) -> Result<Vec<f64>, String> {
    if d.order() == 0 {
        // The fast path: runs inside one piece along each grid line.
        let fill = match outside {
            Outside::Fill(f) => f,
            Outside::Error => f64::NAN,
        };
        let mut values = spline.values_on_grid(x, y, fill);
        if outside == Outside::Error {
            check_inside(spline, x, y, &mut values)?;
        }
        return Ok(values);
    }
    // Grid lines are coherent paths: evaluate in the grid's own order, a chunk at a time so
    // that the points and results in flight stay small next to the output.
    let (n, ny) = (x.len() * y.len(), y.len());
    let mut out = Vec::new();
    out.try_reserve_exact(n)
        .map_err(|_| format!("a {} × {ny} grid does not fit in memory", x.len()))?;
    let mut points = Vec::with_capacity(GRID_CHUNK.min(n));
    for start in (0..n).step_by(GRID_CHUNK) {
        points.clear();
        points.extend(
            (start..(start + GRID_CHUNK).min(n)).map(|k| Point2::new(x[k / ny], y[k % ny])),
        );
        let values = spline.map_points(&points, |ev, p| derivative_at(ev, p, d));
        for (p, v) in points.iter().zip(values) {
            out.push(match (v, outside) {
                (Some([v]), _) => v,
                (None, Outside::Fill(f)) => f,
                (None, Outside::Error) => return Err(outside_grid(*p)),
            });
        }
    }
    Ok(out)
}

/// Grid points evaluated together on the derivative path (each takes 32 bytes while in
/// flight: its point and its result).
const GRID_CHUNK: usize = 1 << 16;

/// Bytes per point that pointwise evaluation of `width` numbers per point holds at its peak:
/// the points (16), their Morton order and sorted copy (24), the results with a flag (8 + 8 ×
/// width) and the output (8 × width).
pub fn pointwise_bytes(width: usize) -> u128 {
    48 + 16 * width as u128
}

/// The error for a grid point outside.
fn outside_grid(p: Point2<f64>) -> String {
    format!(
        "grid point ({}, {}) is outside the triangulation's convex hull",
        p.x, p.y
    )
}

/// With `extrapolate="error"`: fails at the first grid point outside (a NaN value is either
/// outside or a NaN coordinate; both are located again to tell). A NaN at a point that
/// location takes as inside is evaluated there: an answer, never a silent NaN.
fn check_inside(
    spline: &PsSpline<f64>,
    x: &[f64],
    y: &[f64],
    values: &mut [f64],
) -> Result<(), String> {
    let mut ev = spline.evaluator();
    for (k, v) in values.iter_mut().enumerate() {
        if v.is_nan() {
            let p = Point2::new(x[k / y.len()], y[k % y.len()]);
            match ev.value(p) {
                Some(value) => *v = value,
                None => return Err(outside_grid(p)),
            }
        }
    }
    Ok(())
}

/// One row of `W` numbers computed by `row` from the jet at each point (x[k], y[k]).
pub fn jet_rows<const W: usize>(
    spline: &PsSpline<f64>,
    x: &[f64],
    y: &[f64],
    outside: Outside,
    row: impl Fn(Point2<f64>, &Jet<f64>) -> [f64; W] + Sync,
) -> Result<Vec<f64>, String> {
    let points = zip_points(x, y)?;
    let values = map(spline, &points, |ev, p| ev.jet(p).map(|j| row(p, &j.jet)));
    finish(values, &points, outside)
}

/// The row [s, s_x, s_y, s_xx, s_xy, s_yy].
pub fn jet_entries(_: Point2<f64>, j: &Jet<f64>) -> [f64; 6] {
    [j.value, j.dx, j.dy, j.dxx, j.dxy, j.dyy]
}

/// The row [K, H, κ1, κ2] of the graph (x, y, s(x, y)) (curvature seed, (20) and (21));
/// a graph is never singular.
pub fn graph_curvatures(p: Point2<f64>, j: &Jet<f64>) -> [f64; 4] {
    let c = PrincipalCurvatures::from_jet(&graph_jet(p, j))
        .map_or(PrincipalCurvatures::UNDEFINED, |(c, _)| c);
    [c.gaussian, c.mean, c.k1, c.k2]
}
