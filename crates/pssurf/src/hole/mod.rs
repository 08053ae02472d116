//! Filling polygonal holes with UPS-spline patches (thesis chapter 5).
//!
//! The input is a loop of 3 to 6 boundary curves with their unit tangents γ and the unit
//! normals n of the surrounding surfaces ([`curves`], validated by [`HoleBoundary`]); a gap
//! between two curves is split into two triangular holes ([`two_curve_gap`]). The patch is a
//! UPS-spline on the standard lattice polygon with as many sides (Figure 5.25):
//!
//! 1. an initial solution interpolating position and tangent plane at the corners
//!    (5.19)–(5.22), [`HoleFill::new`];
//! 2. refinement steps on the boundary, each interpolating the data at the new boundary
//!    vertices and fitting the curve and its cross-boundary tangent between them (5.23)–(5.27),
//!    [`HoleFill::step`], until the fitting residual is within a tolerance (5.3.3);
//! 3. the interior control triangles by one of the methods of 5.4 ([`Interior`]);
//! 4. a [`QualityReport`].
//!
//! The patch's normal agrees with the given normals; δ = γ × n points out of the hole.

pub mod boundary;
pub mod curves;
pub mod examples;
pub mod fill;
pub mod fitting;
pub mod interior;
pub mod quality;

pub use boundary::{DynCurve, HoleBoundary};
pub use curves::{BoundaryCurve, CurveFns, NormalField, NurbsBoundary, Reversed, SurfaceEdge};
pub use fill::{BoundaryVertex, HoleFill, IterationRecord, MAX_ITERATIONS};
pub use interior::Interior;
pub use quality::{QualityReport, SingularCorner, quality};

use nalgebra::Vector3;
use thiserror::Error;

use crate::ups::{Ups, UpsError};

/// Why a hole cannot be filled. Curves are numbered from 1 in the order given.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum HoleError {
    /// Not 3 to 6 curves.
    #[error(
        "a hole needs 3 to 6 boundary curves, not {0} (a gap between 2 curves is filled as two triangles)"
    )]
    Sides(usize),
    /// A value that is not a finite number.
    #[error("curve {curve}: its {what} at t = {t} is not a finite number")]
    NotFinite {
        /// The curve.
        curve: usize,
        /// Where.
        t: f64,
        /// "point", "tangent" or "normal".
        what: &'static str,
    },
    /// A tangent of length zero.
    #[error("curve {curve}: its tangent vanishes at t = {t} (a cusp or a repeated point)")]
    ZeroTangent {
        /// The curve.
        curve: usize,
        /// Where.
        t: f64,
    },
    /// A normal along the tangent.
    #[error(
        "curve {curve}: its normal at t = {t} is parallel to its tangent (a normal must be perpendicular to the curve)"
    )]
    NormalAlongTangent {
        /// The curve.
        curve: usize,
        /// Where.
        t: f64,
    },
    /// The curves do not form a closed loop.
    #[error(
        "curve {curve} ends {} away from the start or end of every other curve (curves must join within {})",
        crate::text::Short(*gap),
        crate::text::Short(*tolerance)
    )]
    DoNotJoin {
        /// The curve whose end is open.
        curve: usize,
        /// The smallest gap found.
        gap: f64,
        /// The join tolerance (1e-6 of the model size).
        tolerance: f64,
    },
    /// Two curves meet tangentially.
    #[error(
        "curves {} and {} meet without a corner (their tangents are parallel): join them into one curve",
        curves.0,
        curves.1
    )]
    NoCorner {
        /// The curves.
        curves: (usize, usize),
    },
    /// The normals point to different sides.
    #[error(
        "the normals of curves {} and {} point to opposite sides of the hole (flip one of them), or the curves cross each other",
        curves.0,
        curves.1
    )]
    Orientation {
        /// The curves at the joint where the orientation changes.
        curves: (usize, usize),
    },
    /// All curves in one point.
    #[error("the boundary curves have no extent")]
    ZeroSize,
    /// Two curves given as a gap coincide in their middles: there is no gap between them.
    #[error(
        "curves 1 and 2 meet in their middles too ({} apart): there is no gap between them to fill",
        crate::text::Short(*distance)
    )]
    NoGap {
        /// The distance between the curves' middles.
        distance: f64,
    },
    /// A tolerance outside (0, 1).
    #[error("the tolerance must be a number between 0 and 1 (relative to the model size), not {}", crate::text::Short(*.0))]
    BadTolerance(f64),
    /// An angle tolerance outside (0°, 90°).
    #[error("the angle tolerance must be between 0 and 90 degrees, not {0}")]
    BadAngleTolerance(f64),
    /// Too many refinement steps.
    #[error(
        "{requested} iterations are too many: at most {MAX_ITERATIONS} (a hexagonal patch then has about 788,000 vertices)"
    )]
    TooManyIterations {
        /// The step asked for.
        requested: usize,
    },
    /// The UPS machinery failed (cannot happen for the standard polygons).
    #[error("{0}")]
    Ups(UpsError),
    /// Constrained fairing of the interior failed.
    #[error("fairing the interior failed: {0}")]
    Fair(String),
    /// A surface or curve the hole filler built could not be evaluated (a built-in example's
    /// surface, the patch at a boundary point).
    #[error("{0}")]
    Evaluation(String),
}

/// How to fill a hole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FillOptions {
    /// Stop when the fitting residual at every boundary edge is within this fraction of the
    /// model size (5.3.3)...
    pub tolerance: f64,
    /// ... and the angle between the patch normal and the given normals is within this many
    /// degrees...
    pub angle_tolerance: f64,
    /// ... or after exactly this many steps, if given.
    pub iterations: Option<usize>,
    /// The most steps when stopping by the tolerance.
    pub max_iterations: usize,
    /// The interior method.
    pub interior: Interior,
}

impl Default for FillOptions {
    fn default() -> Self {
        FillOptions {
            tolerance: 1e-4,
            angle_tolerance: 0.25,
            iterations: None,
            max_iterations: 8,
            interior: Interior::Instant,
        }
    }
}

/// A filled hole: the patch and its quality.
#[derive(Clone, Debug)]
pub struct FilledHole {
    /// The UPS patch.
    pub patch: Ups<Vector3<f64>>,
    /// Its quality.
    pub report: QualityReport,
    /// Whether the fitting met the tolerances (always true for a fixed number of steps).
    pub converged: bool,
}

/// Fills the hole bounded by `boundary` (see the module documentation).
pub fn fill_hole(boundary: HoleBoundary, opts: &FillOptions) -> Result<FilledHole, HoleError> {
    let fill = match opts.iterations {
        Some(n) => {
            if n > MAX_ITERATIONS {
                return Err(HoleError::TooManyIterations { requested: n });
            }
            // A fixed number of steps fits every edge at every step (no tolerance).
            let mut fill = HoleFill::new(boundary, f64::MIN_POSITIVE, f64::MIN_POSITIVE)?;
            for _ in 0..n {
                fill.step()?;
            }
            fill
        }
        None => {
            let mut fill = HoleFill::new(boundary, opts.tolerance, opts.angle_tolerance)?;
            fill.run_to_tolerance(opts.max_iterations.min(MAX_ITERATIONS))?;
            fill
        }
    };
    let patch = fill.patch(opts.interior)?;
    let report = quality(&fill, &patch)?;
    Ok(FilledHole {
        patch,
        report,
        converged: opts.iterations.is_some() || fill.converged(),
    })
}

/// A gap between two curves (thesis 5.5: composite patches) as two triangular holes: the
/// curves a (from P to Q) and b (from Q back to P) are split at their middles, and the gap
/// is cut by `bisector`, a curve from the middle of a to the middle of b with its normals.
/// Returns the boundaries of the two triangles.
pub fn two_curve_gap(
    a: SharedCurve,
    b: SharedCurve,
    bisector: SharedCurve,
) -> Result<[HoleBoundary; 2], HoleError> {
    let half = |c: &SharedCurve, lo: f64| -> DynCurve {
        let (c1, c2, c3) = (c.clone(), c.clone(), c.clone());
        Box::new(CurveFns {
            point: std::sync::Arc::new(move |t| c1.point(lo + 0.5 * t)),
            tangent: std::sync::Arc::new(move |t| c2.tangent(lo + 0.5 * t) * 0.5),
            normal: std::sync::Arc::new(move |t| c3.normal(lo + 0.5 * t)),
        })
    };
    // Triangle 1: second half of a (middle → Q), first half of b (Q → middle), then the
    // bisector back from b's middle to a's middle. Triangle 2: the rest.
    let first = HoleBoundary::new(vec![
        half(&a, 0.5),
        half(&b, 0.0),
        Box::new(Reversed(bisector.clone())),
    ])?;
    let second = HoleBoundary::new(vec![half(&b, 0.5), half(&a, 0.0), Box::new(bisector)])?;
    Ok([first, second])
}

#[cfg(test)]
mod tests;

/// A shared boundary curve.
pub type SharedCurve = std::sync::Arc<dyn BoundaryCurve + Send + Sync>;

/// A gap between two curves joined at both ends, bisected automatically (see
/// [`two_curve_gap`]): the bisector is the cubic Hermite curve from the middle of `a` to the
/// middle of `b`, leaving and arriving across them in their surfaces' tangent planes, with
/// normals blended linearly between theirs and made perpendicular to it.
pub fn gap_between(a: SharedCurve, b: SharedCurve) -> Result<[HoleBoundary; 2], HoleError> {
    let ends = [a.point(0.0), a.point(1.0), b.point(0.0), b.point(1.0)];
    let size = ends
        .iter()
        .flat_map(|p| ends.iter().map(move |q| (p - q).norm()))
        .fold(0.0, f64::max);
    let tolerance = boundary::JOIN_TOLERANCE * size.max(f64::MIN_POSITIVE);
    // b must run from a's end back to a's start.
    let b: SharedCurve = if (ends[2] - ends[1]).norm() <= tolerance {
        b
    } else if (ends[3] - ends[1]).norm() <= tolerance {
        std::sync::Arc::new(Reversed(b))
    } else {
        return Err(HoleError::DoNotJoin {
            curve: 1,
            gap: (ends[2] - ends[1]).norm().min((ends[3] - ends[1]).norm()),
            tolerance,
        });
    };
    let (p0, p1) = (a.point(0.5), b.point(0.5));
    let chord = p1 - p0;
    // The bisector runs between the middles: none when they coincide (two identical arcs),
    // which would otherwise be reported as an internal curve with a vanishing tangent.
    if !(chord.norm() > tolerance) {
        return Err(HoleError::NoGap {
            distance: chord.norm(),
        });
    }
    // Across the curve, in its tangent plane, towards the other middle.
    let across = |c: &SharedCurve, towards: nalgebra::Vector3<f64>| {
        let (g, n) = (c.tangent(0.5), c.normal(0.5));
        let d = boundary::unit(g.cross(&n)).unwrap_or_default();
        if d.dot(&towards) < 0.0 { -d } else { d }
    };
    let length = chord.norm();
    let (t0, t1) = (across(&a, chord) * length, across(&b, chord) * length);
    let (n0, n1) = (a.normal(0.5), b.normal(0.5));
    let n1 = if n0.dot(&n1) < 0.0 { -n1 } else { n1 };
    let point = move |t: f64| {
        let (t2, t3) = (t * t, t * t * t);
        p0 * (2.0 * t3 - 3.0 * t2 + 1.0)
            + t0 * (t3 - 2.0 * t2 + t)
            + p1 * (-2.0 * t3 + 3.0 * t2)
            + t1 * (t3 - t2)
    };
    let tangent = move |t: f64| {
        let t2 = t * t;
        p0 * (6.0 * t2 - 6.0 * t)
            + t0 * (3.0 * t2 - 4.0 * t + 1.0)
            + p1 * (-6.0 * t2 + 6.0 * t)
            + t1 * (3.0 * t2 - 2.0 * t)
    };
    let normal = move |t: f64| {
        let m = n0 * (1.0 - t) + n1 * t;
        let d = boundary::unit(tangent(t)).unwrap_or_default();
        m - d * d.dot(&m)
    };
    let bisector = CurveFns {
        point: std::sync::Arc::new(point),
        tangent: std::sync::Arc::new(tangent),
        normal: std::sync::Arc::new(normal),
    };
    two_curve_gap(a, b, std::sync::Arc::new(bisector))
}
