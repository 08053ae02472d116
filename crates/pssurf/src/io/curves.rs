//! Curves on a surface as text: CSV with the columns `curve,u,v,x,y,z` (one row per point,
//! consecutive rows of one curve number form a polyline; a closed curve repeats its first
//! point at the end) and Wavefront OBJ line elements.

use std::io::Write;

use nalgebra::{Point2, Vector3};
use thiserror::Error;

use crate::interrogate::SurfaceCurve;

/// The header of a curves CSV file.
pub const CURVES_HEADER: &str = "curve,u,v,x,y,z";

/// The most points a curves file may hold when read.
pub const MAX_CURVE_POINTS: usize = 50_000_000;

/// A curves CSV file that cannot be read.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CurvesError {
    /// The first line is not the header.
    #[error("line 1: expected the header `{CURVES_HEADER}`")]
    Header,
    /// A row is not six numbers.
    #[error("line {0}: expected six comma-separated numbers curve,u,v,x,y,z")]
    Row(usize),
    /// A number is NaN or infinite, or the curve number is not a non-negative integer.
    #[error("line {0}: {1}")]
    Value(usize, &'static str),
    /// More points than [`MAX_CURVE_POINTS`].
    #[error("more than {MAX_CURVE_POINTS} points")]
    TooMany,
}

/// Writes `curves` as CSV (closed curves repeat their first point at the end).
pub fn write_curves_csv(w: &mut dyn Write, curves: &[SurfaceCurve]) -> std::io::Result<()> {
    writeln!(w, "{CURVES_HEADER}")?;
    for (k, c) in curves.iter().enumerate() {
        let closing = c.closed && !c.uvs.is_empty();
        let n = c.uvs.len() + usize::from(closing);
        for i in 0..n {
            let (uv, p) = (c.uvs[i % c.uvs.len()], c.points[i % c.points.len()]);
            writeln!(w, "{k},{},{},{},{},{}", uv.x, uv.y, p.x, p.y, p.z)?;
        }
    }
    Ok(())
}

/// Writes `curves` as Wavefront OBJ: their points as vertices and one line element each.
pub fn write_curves_obj(w: &mut dyn Write, curves: &[SurfaceCurve]) -> std::io::Result<()> {
    writeln!(w, "# curves on a surface written by pssurf")?;
    for c in curves {
        for p in &c.points {
            writeln!(w, "v {} {} {}", p.x, p.y, p.z)?;
        }
    }
    let mut first = 1usize;
    for c in curves {
        if c.points.len() >= 2 {
            write!(w, "l")?;
            for i in 0..c.points.len() {
                write!(w, " {}", first + i)?;
            }
            if c.closed {
                write!(w, " {first}")?;
            }
            writeln!(w)?;
        }
        first += c.points.len();
    }
    Ok(())
}

/// Reads curves written by [`write_curves_csv`]: a curve whose last point equals its first
/// is closed.
///
/// ```
/// use pssurf::io::{read_curves_csv, write_curves_csv};
/// use pssurf::interrogate::SurfaceCurve;
/// use nalgebra::{Point2, Vector3};
/// let c = SurfaceCurve {
///     uvs: vec![Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)],
///     points: vec![Vector3::zeros(), Vector3::x(), Vector3::y()],
///     closed: true,
/// };
/// let mut text = Vec::new();
/// write_curves_csv(&mut text, &[c.clone()]).unwrap();
/// assert_eq!(read_curves_csv(std::str::from_utf8(&text).unwrap()).unwrap(), vec![c]);
/// ```
pub fn read_curves_csv(text: &str) -> Result<Vec<SurfaceCurve>, CurvesError> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim().replace(' ', "") == CURVES_HEADER => {}
        _ => return Err(CurvesError::Header),
    }
    let mut curves: Vec<SurfaceCurve> = Vec::new();
    let mut current: Option<f64> = None;
    let mut count = 0usize;
    for (i, line) in lines {
        let line_no = i + 1;
        if line.trim().is_empty() {
            continue;
        }
        let values: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| CurvesError::Row(line_no))?;
        let [id, u, v, x, y, z] = values[..] else {
            return Err(CurvesError::Row(line_no));
        };
        if values.iter().any(|x| !x.is_finite()) {
            return Err(CurvesError::Value(
                line_no,
                "a value is not a finite number",
            ));
        }
        if id < 0.0 || id.fract() != 0.0 {
            return Err(CurvesError::Value(
                line_no,
                "the curve number must be a whole number ≥ 0",
            ));
        }
        count += 1;
        if count > MAX_CURVE_POINTS {
            return Err(CurvesError::TooMany);
        }
        if current != Some(id) {
            curves.push(SurfaceCurve::default());
            current = Some(id);
        }
        let c = curves.last_mut().expect("pushed");
        c.uvs.push(Point2::new(u, v));
        c.points.push(Vector3::new(x, y, z));
    }
    for c in &mut curves {
        if c.uvs.len() > 2 && c.uvs.first() == c.uvs.last() && c.points.first() == c.points.last() {
            c.uvs.pop();
            c.points.pop();
            c.closed = true;
        }
    }
    Ok(curves)
}
