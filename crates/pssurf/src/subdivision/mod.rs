//! The classic subdivision schemes of seed 004 (issue 20): curves (Chaikin, cubic B-spline,
//! the four-point scheme) so far.

pub mod curves;

pub use curves::{CurveScheme, SubdivisionError, limit_points, subdivide_curve};
