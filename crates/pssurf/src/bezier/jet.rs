//! Values with their first and second partial derivatives.

use crate::vector::Vector;

/// A value with its partial derivatives up to order two with respect to the domain
/// coordinates (x, y) — or (u, v) for a parametric surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet<V> {
    /// The value s.
    pub value: V,
    /// ∂s/∂x.
    pub dx: V,
    /// ∂s/∂y.
    pub dy: V,
    /// ∂²s/∂x².
    pub dxx: V,
    /// ∂²s/∂x∂y.
    pub dxy: V,
    /// ∂²s/∂y².
    pub dyy: V,
}

impl<V: Vector> Jet<V> {
    /// A jet with every entry zero.
    pub fn zero() -> Self {
        Jet {
            value: V::zero(),
            dx: V::zero(),
            dy: V::zero(),
            dxx: V::zero(),
            dxy: V::zero(),
            dyy: V::zero(),
        }
    }

    /// Applies `f` to every entry (e.g. to take one coordinate of a 3-D jet).
    pub fn map<W: Vector>(&self, f: impl Fn(V) -> W) -> Jet<W> {
        Jet {
            value: f(self.value),
            dx: f(self.dx),
            dy: f(self.dy),
            dxx: f(self.dxx),
            dxy: f(self.dxy),
            dyy: f(self.dyy),
        }
    }

    /// The largest difference between corresponding entries, in the max-norm.
    pub fn max_diff(&self, other: &Self) -> f64 {
        [
            (self.value - other.value).max_abs(),
            (self.dx - other.dx).max_abs(),
            (self.dy - other.dy).max_abs(),
            (self.dxx - other.dxx).max_abs(),
            (self.dxy - other.dxy).max_abs(),
            (self.dyy - other.dyy).max_abs(),
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}
