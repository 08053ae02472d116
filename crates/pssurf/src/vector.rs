//! The values a patch or spline can take: scalars (functional surfaces) or points in R^d.

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Mul, Neg, Sub};

use nalgebra::SVector;

/// An element of a real vector space R^d, the range of Bézier patches and splines.
///
/// Implemented for `f64` (functional surfaces, d = 1) and for nalgebra's
/// `SVector<f64, D>` (parametric surfaces, e.g. `Vector3<f64>`, and homogeneous points).
/// Control "points" are treated as vectors: every algorithm forms affine combinations only.
pub trait Vector:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
    + Neg<Output = Self>
    + AddAssign
{
    /// The dimension d of the space.
    const DIM: usize;
    /// The zero vector.
    fn zero() -> Self;
    /// The i-th coordinate, `i < DIM`.
    fn coord(&self, i: usize) -> f64;
    /// Builds a vector from its coordinates; `coords.len()` must be `DIM`.
    fn from_coords(coords: &[f64]) -> Self;
    /// The Euclidean norm.
    fn norm(&self) -> f64 {
        (0..Self::DIM)
            .map(|i| self.coord(i) * self.coord(i))
            .sum::<f64>()
            .sqrt()
    }
    /// The largest absolute coordinate (the max-norm), used for relative tolerances.
    fn max_abs(&self) -> f64 {
        (0..Self::DIM)
            .map(|i| self.coord(i).abs())
            .fold(0.0, f64::max)
    }
    /// True when every coordinate is finite (no NaN or infinity).
    fn is_finite(&self) -> bool {
        (0..Self::DIM).all(|i| self.coord(i).is_finite())
    }
    /// True when every coordinate is a usable control value: finite and within
    /// ±[`MAX_VALUE`](crate::limits::MAX_VALUE).
    fn in_range(&self) -> bool {
        (0..Self::DIM).all(|i| crate::limits::value_ok(self.coord(i)))
    }
}

impl Vector for f64 {
    const DIM: usize = 1;
    fn zero() -> Self {
        0.0
    }
    fn coord(&self, _i: usize) -> f64 {
        *self
    }
    fn from_coords(coords: &[f64]) -> Self {
        coords[0]
    }
}

impl<const D: usize> Vector for SVector<f64, D> {
    const DIM: usize = D;
    fn zero() -> Self {
        SVector::zeros()
    }
    fn coord(&self, i: usize) -> f64 {
        self[i]
    }
    fn from_coords(coords: &[f64]) -> Self {
        SVector::from_column_slice(coords)
    }
}

/// The affine combination `Σ c_i p_i` of equally many coefficients and vectors.
#[inline]
pub fn combine<V: Vector>(coeffs: &[f64], points: &[V]) -> V {
    debug_assert_eq!(coeffs.len(), points.len());
    let mut acc = V::zero();
    for (&c, &p) in coeffs.iter().zip(points) {
        acc += p * c;
    }
    acc
}
