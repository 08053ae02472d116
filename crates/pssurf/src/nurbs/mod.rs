//! NURBS curves and tensor-product surfaces (issue 17): knot vectors, B-spline basis
//! functions with derivatives, and a [`NurbsSurface`] that is a surface kind of the library
//! (rectangular pieces, one per non-empty knot rectangle), so that sampling, curvature, zebra,
//! fairness, export and curve tracing work on it unchanged.
//!
//! The evaluator is written here, allocation-free (degrees up to [`MAX_DEGREE`]), for the hot
//! loops; the tests check it against the recursive Cox–de Boor definition and against curvo.

pub mod approx;
mod basis;
mod curve;
mod surface;
#[cfg(test)]
mod tests;

pub use approx::{
    ApproxError, ApproxOptions, Approximation, approximate, default_counts, ups_of_nurbs,
};
pub use basis::{BasisDerivs, KnotError, KnotVector, MAX_DEGREE};
pub use curve::NurbsCurve;
pub use surface::{NurbsError, NurbsSurface};
