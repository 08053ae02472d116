//! Subdivision curves (seed 004): Chaikin's corner cutting, the cubic B-spline scheme and the
//! four-point interpolatory scheme, on open and closed polygons.
//!
//! - **Chaikin**: each edge (p_i, p_{i+1}) gives ¾ p_i + ¼ p_{i+1} and ¼ p_i + ¾ p_{i+1}. This is
//!   knot insertion at every midpoint of the uniform quadratic B-spline of the polygon, so the
//!   polygons converge to it; the curve passes through the midpoints of every polygon's
//!   edges ([`limit_points`]).
//! - **Cubic B-spline**: edge points (p_i + p_{i+1})/2 and vertex points
//!   (p_{i−1} + 6 p_i + p_{i+1})/8, knot insertion for the uniform cubic B-spline; the limit of
//!   vertex i is (p_{i−1} + 4 p_i + p_{i+1})/6.
//! - **Four-point** (Dyn, Levin, Gregory): old points stay and each edge gets
//!   (½ + w)(p_i + p_{i+1}) − w (p_{i−1} + p_{i+2}); w = 1/16 reproduces cubics. The limit
//!   passes through every point of every polygon.
//!
//! Open polygons: Chaikin and the cubic scheme refine every edge (and every inner vertex), so
//! the polygons describe the same uniform B-spline curve as the original one, from
//! parameter d to n (d the degree, n the number of points): its ends are not the polygon's
//! ends. The four-point scheme keeps the end points; the missing neighbours of the end edges
//! are extrapolated cubically, p_{−1} = 4 p₀ − 6 p₁ + 4 p₂ − p₃, so cubics are reproduced up to
//! the ends.

use thiserror::Error;

use crate::vector::Vector;

/// The most points one call may make (the output doubles with every step).
pub const MAX_SUBDIVISION_POINTS: usize = 1 << 26;

/// A curve subdivision scheme.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CurveScheme {
    /// Chaikin's corner cutting: the uniform quadratic B-spline.
    Chaikin,
    /// The uniform cubic B-spline.
    CubicBSpline,
    /// The interpolatory four-point scheme with tension w (1/16 reproduces cubics; the limit is
    /// C¹ for 0 < w < (√5 − 1)/8).
    FourPoint {
        /// The tension w.
        tension: f64,
    },
}

impl CurveScheme {
    /// The fewest points a polygon needs for the scheme.
    fn min_points(self, closed: bool) -> usize {
        match (self, closed) {
            (CurveScheme::Chaikin, false) => 3,
            (CurveScheme::CubicBSpline, false) => 4,
            (CurveScheme::FourPoint { .. }, false) => 4,
            (_, true) => 3,
        }
    }

    /// The number of points after one step from n.
    fn next_len(self, n: usize, closed: bool) -> usize {
        match (self, closed) {
            (_, true) => 2 * n,
            (CurveScheme::Chaikin, false) => 2 * n - 2,
            (CurveScheme::CubicBSpline, false) => 2 * n - 3,
            (CurveScheme::FourPoint { .. }, false) => 2 * n - 1,
        }
    }
}

/// Why a polygon cannot be subdivided.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SubdivisionError {
    /// Too few points.
    #[error("the scheme needs at least {needed} points for this polygon, not {found}")]
    TooFewPoints {
        /// The minimum.
        needed: usize,
        /// The count given.
        found: usize,
    },
    /// A point is not finite.
    #[error("point {0} has a coordinate that is not a finite number within ±1e60")]
    NonFinite(usize),
    /// The tension is not finite.
    #[error("the tension must be a finite number, not {0}")]
    BadTension(f64),
    /// A point left the representable range (a four-point tension far outside the scheme's
    /// convergent range multiplies the polygon at every step).
    #[error(
        "after {step} steps a point has a coordinate beyond ±1e60 (tension {tension}): the scheme diverges"
    )]
    Diverges {
        /// The step (from 1) after which it happened.
        step: usize,
        /// The tension w.
        tension: f64,
    },
    /// The result would be too large.
    #[error("{times} steps would make {points} points (at most {MAX_SUBDIVISION_POINTS})")]
    TooLarge {
        /// The steps asked for.
        times: usize,
        /// The points they would make (saturating).
        points: usize,
    },
}

/// The polygon `points` (open or `closed`) subdivided `times` times by `scheme`.
pub fn subdivide_curve<V: Vector>(
    points: &[V],
    closed: bool,
    scheme: CurveScheme,
    times: usize,
) -> Result<Vec<V>, SubdivisionError> {
    check(points, closed, scheme)?;
    let mut n = points.len();
    for _ in 0..times {
        n = scheme.next_len(n, closed);
        if n > MAX_SUBDIVISION_POINTS {
            return Err(SubdivisionError::TooLarge { times, points: n });
        }
    }
    let mut p = points.to_vec();
    for k in 1..=times {
        p = step(&p, closed, scheme);
        if let CurveScheme::FourPoint { tension } = scheme
            && !p.iter().all(|q| q.in_range())
        {
            return Err(SubdivisionError::Diverges { step: k, tension });
        }
    }
    Ok(p)
}

fn check<V: Vector>(
    points: &[V],
    closed: bool,
    scheme: CurveScheme,
) -> Result<(), SubdivisionError> {
    if let CurveScheme::FourPoint { tension } = scheme
        && !tension.is_finite()
    {
        return Err(SubdivisionError::BadTension(tension));
    }
    let needed = scheme.min_points(closed);
    if points.len() < needed {
        return Err(SubdivisionError::TooFewPoints {
            needed,
            found: points.len(),
        });
    }
    match points.iter().position(|p| !p.in_range()) {
        Some(k) => Err(SubdivisionError::NonFinite(k)),
        None => Ok(()),
    }
}

/// One step.
fn step<V: Vector>(p: &[V], closed: bool, scheme: CurveScheme) -> Vec<V> {
    let n = p.len();
    let at = |i: isize| -> V { p[i.rem_euclid(n as isize) as usize] };
    let edges = if closed { n } else { n - 1 };
    let mut out = Vec::with_capacity(scheme.next_len(n, closed));
    match scheme {
        CurveScheme::Chaikin => {
            for i in 0..edges as isize {
                let (a, b) = (at(i), at(i + 1));
                out.push(a * 0.75 + b * 0.25);
                out.push(a * 0.25 + b * 0.75);
            }
        }
        CurveScheme::CubicBSpline => {
            let vertex = |i: isize| (at(i - 1) + at(i) * 6.0 + at(i + 1)) * 0.125;
            let edge = |i: isize| (at(i) + at(i + 1)) * 0.5;
            if closed {
                for i in 0..n as isize {
                    out.push(vertex(i));
                    out.push(edge(i));
                }
            } else {
                out.push(edge(0));
                for i in 1..n as isize - 1 {
                    out.push(vertex(i));
                    out.push(edge(i));
                }
            }
        }
        CurveScheme::FourPoint { tension: w } => {
            // Neighbours beyond the ends of an open polygon, extrapolated cubically.
            let get = |i: isize| -> V {
                if closed || (0..n as isize).contains(&i) {
                    at(i)
                } else if i < 0 {
                    at(0) * 4.0 - at(1) * 6.0 + at(2) * 4.0 - at(3)
                } else {
                    let m = n as isize - 1;
                    at(m) * 4.0 - at(m - 1) * 6.0 + at(m - 2) * 4.0 - at(m - 3)
                }
            };
            for i in 0..edges as isize {
                out.push(at(i));
                out.push((get(i) + get(i + 1)) * (0.5 + w) - (get(i - 1) + get(i + 2)) * w);
            }
            if !closed {
                out.push(at(n as isize - 1));
            }
        }
    }
    out
}

/// Points of the limit curve in closed form: for Chaikin the midpoints of the edges, for the
/// cubic scheme (p_{i−1} + 4 p_i + p_{i+1})/6 at every vertex with two neighbours, for the
/// four-point scheme the points themselves.
pub fn limit_points<V: Vector>(
    points: &[V],
    closed: bool,
    scheme: CurveScheme,
) -> Result<Vec<V>, SubdivisionError> {
    check(points, closed, scheme)?;
    let n = points.len();
    let at = |i: usize| points[i % n];
    Ok(match scheme {
        CurveScheme::Chaikin => {
            let edges = if closed { n } else { n - 1 };
            (0..edges).map(|i| (at(i) + at(i + 1)) * 0.5).collect()
        }
        CurveScheme::CubicBSpline => {
            let inner = |i: usize| (at(i + n - 1) + at(i) * 4.0 + at(i + 1)) * (1.0 / 6.0);
            if closed {
                (0..n).map(inner).collect()
            } else {
                (1..n - 1).map(inner).collect()
            }
        }
        CurveScheme::FourPoint { .. } => points.to_vec(),
    })
}

#[cfg(test)]
mod tests;
