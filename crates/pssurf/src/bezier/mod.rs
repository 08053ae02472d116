//! Triangular Bernstein–Bézier patches (polynomial and rational) of any degree, and Bézier
//! curves (thesis chapter 2.2 and 3.2; course notes seed 004).

pub mod continuity;
pub mod curve;
pub mod index;
pub mod jet;
pub mod rational;
pub mod triangle;

pub use continuity::{Continuity, continuity};
pub use curve::{BezierCurve, RationalBezierCurve};
pub use jet::Jet;
pub use rational::RationalBezierTriangle;
pub use triangle::BezierTriangle;

use thiserror::Error;

/// Errors from constructing or evaluating Bézier patches and curves.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum BezierError {
    /// The number of ordinates (or weights) does not match the degree.
    #[error(
        "the net needs {expected} ordinates for its degree ((m + 1)(m + 2)/2 for a triangle of degree m, m + 1 for a curve), found {found}"
    )]
    WrongOrdinateCount {
        /// (m + 1)(m + 2)/2 for a triangle, m + 1 for a curve.
        expected: usize,
        /// What was given.
        found: usize,
    },
    /// An ordinate has a NaN or infinite coordinate.
    #[error("ordinate {0} is not a finite number within ±1e60")]
    NonFiniteOrdinate(usize),
    /// A weight is zero, negative or not finite.
    #[error("weight {0} must lie between 1e-30 and 1e30")]
    InvalidWeight(usize),
    /// The domain triangle has (numerically) zero area.
    #[error("the domain triangle is degenerate")]
    DegenerateDomain,
    /// A point outside the domain triangle was given where an interior point is needed.
    #[error("the point lies outside the domain triangle")]
    OutsideDomain,
    /// A rational de Casteljau step met a non-positive weight (outside the domain).
    #[error("the rational denominator is not positive there")]
    NonPositiveWeight,
    /// A parameter outside [0, 1] was given to a curve operation that needs one inside.
    #[error("the parameter {0} lies outside [0, 1]")]
    ParameterOutOfRange(f64),
    /// The two patches given to a continuity test share no edge.
    #[error("the two domain triangles share no edge")]
    NoCommonEdge,
    /// The two patches have different degrees.
    #[error("the patches have different degrees ({0} and {1})")]
    DegreeMismatch(usize, usize),
}

#[cfg(test)]
mod tests;
