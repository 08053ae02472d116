//! The ranges of numbers pssurf accepts. Every constructor and the file loader check them, so
//! that no derived quantity (squared lengths, products in curvature, homogeneous coordinates)
//! can overflow later: the checks are at validation, not deep inside evaluation.

pub use crate::triangulation::{MAX_COORDINATE, MIN_COORDINATE};

/// The largest magnitude of a control value (a coordinate of a control point or ordinate, or
/// a functional coefficient): 1e60, so that products of up to five stay finite.
pub const MAX_VALUE: f64 = 1e60;

/// The smallest weight of a rational surface.
pub const MIN_WEIGHT: f64 = 1e-30;

/// The largest weight of a rational surface: with values up to [`MAX_VALUE`] the homogeneous
/// coordinates w·P stay below 1e90, and products of three weights finite.
pub const MAX_WEIGHT: f64 = 1e30;

/// Whether `x` is a usable control value: finite and within ±[`MAX_VALUE`].
#[inline]
pub fn value_ok(x: f64) -> bool {
    x.is_finite() && x.abs() <= MAX_VALUE
}

/// Whether `w` is a usable weight: within [[`MIN_WEIGHT`], [`MAX_WEIGHT`]].
#[inline]
pub fn weight_ok(w: f64) -> bool {
    (MIN_WEIGHT..=MAX_WEIGHT).contains(&w)
}
