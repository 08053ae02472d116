//! Bézier curves of any degree, polynomial and rational: de Casteljau evaluation, derivatives
//! (the hodograph), subdivision, curvature and torsion (seed 004, "Bézier curves").

use nalgebra::Vector3;

use super::BezierError;
use super::index::{binomial, falling_factorial};
use crate::vector::Vector;

/// A curve p: [0, 1] → R^d with derivatives of any order.
pub trait ParamCurve<V: Vector> {
    /// The point p(t).
    fn eval(&self, t: f64) -> V;

    /// p(t), p'(t), …, p^(order)(t).
    fn derivatives(&self, t: f64, order: usize) -> Vec<V>;

    /// The curvature κ = |p' × p''| / |p'|³ (seed 004), computed in any dimension as
    /// √(|p'|²|p''|² − (p'·p'')²) / |p'|³. `None` at a singular point (p' = 0).
    fn curvature(&self, t: f64) -> Option<f64> {
        let d = self.derivatives(t, 2);
        let (d1, d2) = (d[1], d[2]);
        let s = dot(&d1, &d1);
        if !(s > 0.0) {
            return None;
        }
        let cross_sq = (s * dot(&d2, &d2) - dot(&d1, &d2).powi(2)).max(0.0);
        Some(cross_sq.sqrt() / (s * s.sqrt()))
    }
}

/// The torsion τ = (p' × p'') · p''' / |p' × p''|² of a space curve; `None` where the
/// curvature vanishes or the curve is singular (the Frenet frame is undefined).
pub fn torsion(curve: &impl ParamCurve<Vector3<f64>>, t: f64) -> Option<f64> {
    let d = curve.derivatives(t, 3);
    let c = d[1].cross(&d[2]);
    let n = c.norm_squared();
    let scale = d[1].norm_squared() * d[2].norm_squared();
    if !(n > 1e-28 * scale) || n == 0.0 {
        return None;
    }
    Some(c.dot(&d[3]) / n)
}

/// The Euclidean inner product of two vectors.
#[inline]
pub fn dot<V: Vector>(a: &V, b: &V) -> f64 {
    (0..V::DIM).map(|i| a.coord(i) * b.coord(i)).sum()
}

/// A polynomial Bézier curve p(t) = Σ p_i B_{i,d}(t), t ∈ [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct BezierCurve<V> {
    points: Vec<V>,
}

impl<V: Vector> BezierCurve<V> {
    /// A curve from its control polygon; panics on the errors of [`BezierCurve::try_new`].
    pub fn new(points: Vec<V>) -> Self {
        Self::try_new(points).unwrap_or_else(|e| panic!("{e}"))
    }

    /// A curve from at least one finite control point.
    ///
    /// ```
    /// use pssurf::bezier::{BezierCurve, BezierError};
    /// assert!(matches!(BezierCurve::<f64>::try_new(vec![]),
    ///     Err(BezierError::WrongOrdinateCount { expected: 1, found: 0 })));
    /// ```
    pub fn try_new(points: Vec<V>) -> Result<Self, BezierError> {
        if points.is_empty() {
            return Err(BezierError::WrongOrdinateCount {
                expected: 1,
                found: 0,
            });
        }
        if let Some(i) = points.iter().position(|p| !p.in_range()) {
            return Err(BezierError::NonFiniteOrdinate(i));
        }
        Ok(BezierCurve { points })
    }

    /// The degree d.
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The control points.
    pub fn points(&self) -> &[V] {
        &self.points
    }

    /// The hodograph p'(t) = d Σ (p_{i+1} − p_i) B_{i,d−1}(t), a curve of degree d − 1
    /// (the zero curve for d = 0).
    pub fn hodograph(&self) -> Self {
        let d = self.degree();
        if d == 0 {
            return BezierCurve {
                points: vec![V::zero()],
            };
        }
        BezierCurve {
            points: self
                .points
                .windows(2)
                .map(|w| (w[1] - w[0]) * d as f64)
                .collect(),
        }
    }

    /// Splits at t into the curves on [0, t] and [t, 1] (both reparametrised to [0, 1]),
    /// from the intermediate de Casteljau points.
    pub fn subdivide(&self, t: f64) -> Result<(Self, Self), BezierError> {
        if !(0.0..=1.0).contains(&t) {
            return Err(BezierError::ParameterOutOfRange(t));
        }
        let n = self.points.len();
        let mut work = self.points.clone();
        let mut left = Vec::with_capacity(n);
        let mut right = Vec::with_capacity(n);
        left.push(work[0]);
        right.push(work[n - 1]);
        for level in 1..n {
            for i in 0..n - level {
                work[i] = work[i] * (1.0 - t) + work[i + 1] * t;
            }
            left.push(work[0]);
            right.push(work[n - 1 - level]);
        }
        right.reverse();
        Ok((BezierCurve { points: left }, BezierCurve { points: right }))
    }
}

impl<V: Vector> ParamCurve<V> for BezierCurve<V> {
    /// De Casteljau evaluation.
    fn eval(&self, t: f64) -> V {
        let mut work = self.points.clone();
        let n = work.len();
        for level in 1..n {
            for i in 0..n - level {
                work[i] = work[i] * (1.0 - t) + work[i + 1] * t;
            }
        }
        work[0]
    }

    /// p^(r)(t) = d!/(d−r)! Σ Δ^r p_i B_{i,d−r}(t) (seed 004).
    fn derivatives(&self, t: f64, order: usize) -> Vec<V> {
        let mut out = Vec::with_capacity(order + 1);
        let mut c = self.clone();
        for _ in 0..=order {
            out.push(c.eval(t));
            c = c.hodograph();
        }
        out
    }
}

/// A rational Bézier curve p(t) = Σ w_i p_i B_{i,d}(t) / Σ w_i B_{i,d}(t) with w_i > 0.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBezierCurve<V> {
    points: Vec<V>,
    weights: Vec<f64>,
}

impl<V: Vector> RationalBezierCurve<V> {
    /// A rational curve; panics on the errors of [`RationalBezierCurve::try_new`].
    pub fn new(points: Vec<V>, weights: Vec<f64>) -> Self {
        Self::try_new(points, weights).unwrap_or_else(|e| panic!("{e}"))
    }

    /// A validated rational curve: as many finite positive weights as control points.
    ///
    /// ```
    /// use pssurf::bezier::{BezierError, RationalBezierCurve};
    /// assert!(matches!(RationalBezierCurve::try_new(vec![0.0, 1.0], vec![1.0, -2.0]),
    ///     Err(BezierError::InvalidWeight(1))));
    /// ```
    pub fn try_new(points: Vec<V>, weights: Vec<f64>) -> Result<Self, BezierError> {
        let poly = BezierCurve::try_new(points)?;
        if weights.len() != poly.points.len() {
            return Err(BezierError::WrongOrdinateCount {
                expected: poly.points.len(),
                found: weights.len(),
            });
        }
        if let Some(i) = weights.iter().position(|&w| !crate::limits::weight_ok(w)) {
            return Err(BezierError::InvalidWeight(i));
        }
        Ok(RationalBezierCurve {
            points: poly.points,
            weights,
        })
    }

    /// The degree d.
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }
    /// The control points.
    pub fn points(&self) -> &[V] {
        &self.points
    }
    /// The weights.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The projected de Casteljau levels at t: `levels[k]` holds the (points, weights) of
    /// level k (d + 1 − k entries). Each step forms convex combinations with coefficients
    /// (1 − t) w_i / w and t w_{i+1} / w, so no point leaves the convex hull.
    fn levels(&self, t: f64) -> Vec<(Vec<V>, Vec<f64>)> {
        let mut levels = vec![(self.points.clone(), self.weights.clone())];
        for _ in 0..self.degree() {
            let (p, w) = levels.last().expect("non-empty");
            let mut np = Vec::with_capacity(p.len() - 1);
            let mut nw = Vec::with_capacity(p.len() - 1);
            for i in 0..p.len() - 1 {
                let a = (1.0 - t) * w[i];
                let b = t * w[i + 1];
                let wn = a + b;
                np.push(p[i] * (a / wn) + p[i + 1] * (b / wn));
                nw.push(wn);
            }
            levels.push((np, nw));
        }
        levels
    }

    /// Splits at t ∈ [0, 1] into two rational curves (projected de Casteljau).
    pub fn subdivide(&self, t: f64) -> Result<(Self, Self), BezierError> {
        if !(0.0..=1.0).contains(&t) {
            return Err(BezierError::ParameterOutOfRange(t));
        }
        let levels = self.levels(t);
        let n = self.points.len();
        let left = RationalBezierCurve {
            points: levels.iter().map(|(p, _)| p[0]).collect(),
            weights: levels.iter().map(|(_, w)| w[0]).collect(),
        };
        let mut rp: Vec<V> = (0..n).map(|k| levels[k].0[n - 1 - k]).collect();
        let mut rw: Vec<f64> = (0..n).map(|k| levels[k].1[n - 1 - k]).collect();
        rp.reverse();
        rw.reverse();
        Ok((
            left,
            RationalBezierCurve {
                points: rp,
                weights: rw,
            },
        ))
    }
}

impl<V: Vector> ParamCurve<V> for RationalBezierCurve<V> {
    /// The rational de Casteljau algorithm (projected intermediate points).
    fn eval(&self, t: f64) -> V {
        self.levels(t).last().expect("non-empty").0[0]
    }

    /// Derivatives by Leibniz' rule in the stable form used for patches (3.18):
    /// with the level-(d−k) projected points P_j, weights W_j and the value p, w,
    /// A_k = d!/(d−k)! Σ_j (−1)^{k−j} C(k, j) (W_j / w)(P_j − p) and
    /// p^(k) = A_k − Σ_{j=1}^{k−1} C(k, j) (w^(j) / w) p^(k−j).
    fn derivatives(&self, t: f64, order: usize) -> Vec<V> {
        let d = self.degree();
        let levels = self.levels(t);
        let (p, w) = (levels[d].0[0], levels[d].1[0]);
        let mut a = vec![V::zero(); order + 1];
        let mut what = vec![0.0; order + 1];
        for k in 1..=order.min(d) {
            let (pts, ws) = &levels[d - k];
            let f = falling_factorial(d, k);
            for j in 0..=k {
                let sign = if (k - j) % 2 == 0 { 1.0 } else { -1.0 };
                let c = sign * binomial(k, j) * ws[j] / w;
                a[k] += (pts[j] - p) * (c * f);
                what[k] += c * f;
            }
        }
        let mut out = vec![V::zero(); order + 1];
        out[0] = p;
        for k in 1..=order {
            let mut v = a[k];
            for j in 1..k {
                v = v - out[k - j] * (binomial(k, j) * what[j]);
            }
            out[k] = v;
        }
        out
    }
}
