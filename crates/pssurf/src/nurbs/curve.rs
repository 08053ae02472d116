//! NURBS curves c(t) = Σ N_{i,p}(t) w_i P_i / Σ N_{i,p}(t) w_i with exact first and second
//! derivatives (the trimming curves and space curves of IGES files).

use nalgebra::Vector3;

use super::basis::KnotVector;
use super::surface::{NurbsError, check_net};

/// A NURBS curve in space.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve {
    knots: KnotVector,
    points: Vec<Vector3<f64>>,
    weights: Vec<f64>,
    rational: bool,
}

impl NurbsCurve {
    /// A curve of degree `degree` with `knots` and control points (`weights` `None`: a
    /// polynomial B-spline curve).
    pub fn try_new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Vector3<f64>>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, NurbsError> {
        let n = points.len();
        let knots = KnotVector::try_new(degree, knots, n).map_err(|source| NurbsError::Knots {
            direction: "curve",
            source,
        })?;
        let rational = weights.is_some();
        let weights = check_net(&points, weights)?;
        Ok(NurbsCurve {
            knots,
            points,
            weights,
            rational,
        })
    }

    /// The knot vector (with the degree).
    pub fn knot_vector(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points.
    pub fn points(&self) -> &[Vector3<f64>] {
        &self.points
    }

    /// The weights (1 for a polynomial curve).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Whether the curve was given weights.
    pub fn is_rational(&self) -> bool {
        self.rational
    }

    /// The parameter interval [U_p, U_n].
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// c(t), c′(t), c″(t); `None` outside the domain.
    pub fn derivatives(&self, t: f64) -> Option<[Vector3<f64>; 3]> {
        let (lo, hi) = self.domain();
        if !(t >= lo && t <= hi) {
            return None;
        }
        let p = self.knots.degree();
        let i = self.knots.spans()[self.knots.span_rank(t)];
        let b = self.knots.basis(i, t);
        // Homogeneous derivatives A^(k) = Σ N^(k) w P, w^(k) = Σ N^(k) w.
        let mut a = [Vector3::zeros(); 3];
        let mut w = [0.0; 3];
        for r in 0..=p {
            let (pt, wt) = (self.points[i - p + r], self.weights[i - p + r]);
            for k in 0..3 {
                a[k] += pt * (b.d[k][r] * wt);
                w[k] += b.d[k][r] * wt;
            }
        }
        let c = a[0] / w[0];
        let c1 = (a[1] - c * w[1]) / w[0];
        let c2 = (a[2] - c1 * (2.0 * w[1]) - c * w[2]) / w[0];
        Some([c, c1, c2])
    }

    /// c(t), c′(t), c″(t), c‴(t); `None` outside the domain. From the homogeneous curve
    /// A = Σ N w P, w = Σ N w: c‴ = (A‴ − 3 w′ c″ − 3 w″ c′ − w‴ c)/w.
    pub fn derivatives3(&self, t: f64) -> Option<[Vector3<f64>; 4]> {
        let [c, c1, c2] = self.derivatives(t)?;
        let p = self.knots.degree();
        let i = self.knots.spans()[self.knots.span_rank(t)];
        let b = self.knots.basis(i, t);
        let d3 = self.knots.third_derivatives(i, t);
        let (mut a3, mut w) = (Vector3::zeros(), [0.0; 4]);
        for r in 0..=p {
            let (pt, wt) = (self.points[i - p + r], self.weights[i - p + r]);
            a3 += pt * (d3[r] * wt);
            for k in 0..3 {
                w[k] += b.d[k][r] * wt;
            }
            w[3] += d3[r] * wt;
        }
        let c3 = (a3 - c2 * (3.0 * w[1]) - c1 * (3.0 * w[2]) - c * w[3]) / w[0];
        Some([c, c1, c2, c3])
    }

    /// The torsion τ = (c′ × c″) · c‴ / |c′ × c″|² at t; `None` outside the domain or where
    /// the curvature vanishes (no osculating plane).
    pub fn torsion(&self, t: f64) -> Option<f64> {
        let [_, c1, c2, c3] = self.derivatives3(t)?;
        let b = c1.cross(&c2);
        let n2 = b.norm_squared();
        (n2 > 1e-300 * c1.norm_squared().powi(3).max(f64::MIN_POSITIVE)).then(|| b.dot(&c3) / n2)
    }

    /// The curvature κ = |c′ × c″| / |c′|³ at t; `None` outside the domain or where c′ = 0.
    pub fn curvature(&self, t: f64) -> Option<f64> {
        let [_, c1, c2] = self.derivatives(t)?;
        let s = c1.norm();
        (s > 0.0).then(|| c1.cross(&c2).norm() / (s * s * s))
    }

    /// c(t); `None` outside the domain.
    pub fn point(&self, t: f64) -> Option<Vector3<f64>> {
        self.derivatives(t).map(|d| d[0])
    }
}
