//! Rational triangular Bernstein–Bézier patches (thesis section 3.2), evaluated stably with
//! Farin's rational de Casteljau algorithm (Algorithm 3.1).

use nalgebra::Point2;

use super::BezierError;
use super::index::{binomial, de_casteljau_steps, falling_factorial, multi_indices, net_len};
use super::jet::Jet;
use super::triangle::{BezierTriangle, blossom_with, elevate_net, mid_edge_triangles};
use crate::geometry::{Bary, BaryMap, Triangle2};
use crate::vector::Vector;

/// A rational patch b(τ) = Σ w_λ b_λ B^m_λ(τ) / Σ w_λ B^m_λ(τ) (3.1) with weights w_λ > 0.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBezierTriangle<V> {
    domain: Triangle2,
    map: BaryMap,
    degree: usize,
    points: Vec<V>,
    weights: Vec<f64>,
}

/// One projected de Casteljau step (3.8)–(3.12): weights are combined with τ and the points
/// with the normalised coefficients τ̃_i = τ_i w_i / w, a convex combination when τ ≥ 0.
/// Fails when an intermediate weight is not positive (only possible outside the domain).
pub(crate) fn rational_step<V: Vector>(
    pts: &mut [V],
    w: &mut [f64],
    deg: usize,
    t: Bary,
) -> Result<(), BezierError> {
    for r in 0..deg {
        let row = r * (r + 1) / 2;
        let next = row + r + 1;
        for k in 0..=r {
            let (p, q) = (row + k, next + k);
            let a = t[0] * w[p];
            let b = t[1] * w[q];
            let c = t[2] * w[q + 1];
            let wn = a + b + c;
            if !(wn > 0.0) {
                return Err(BezierError::NonPositiveWeight);
            }
            pts[p] = pts[p] * (a / wn) + pts[q] * (b / wn) + pts[q + 1] * (c / wn);
            w[p] = wn;
        }
    }
    Ok(())
}

impl<V: Vector> RationalBezierTriangle<V> {
    /// A rational patch; panics on the errors of [`RationalBezierTriangle::try_new`].
    pub fn new(domain: Triangle2, degree: usize, points: Vec<V>, weights: Vec<f64>) -> Self {
        Self::try_new(domain, degree, points, weights).unwrap_or_else(|e| panic!("{e}"))
    }

    /// A validated rational patch: counts must match, ordinates finite, weights finite and > 0.
    ///
    /// ```
    /// use pssurf::bezier::{BezierError, RationalBezierTriangle};
    /// use pssurf::geometry::Triangle2;
    /// use nalgebra::Point2;
    /// let t = Triangle2::new(Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.));
    /// let w = vec![1.0, 1.0, 0.0];
    /// assert!(matches!(RationalBezierTriangle::try_new(t, 1, vec![0.0; 3], w),
    ///     Err(BezierError::InvalidWeight(2))));
    /// ```
    pub fn try_new(
        domain: Triangle2,
        degree: usize,
        points: Vec<V>,
        weights: Vec<f64>,
    ) -> Result<Self, BezierError> {
        let poly = BezierTriangle::try_new(domain, degree, points)?;
        if weights.len() != net_len(degree) {
            return Err(BezierError::WrongOrdinateCount {
                expected: net_len(degree),
                found: weights.len(),
            });
        }
        if let Some(i) = weights.iter().position(|&w| !crate::limits::weight_ok(w)) {
            return Err(BezierError::InvalidWeight(i));
        }
        let map = *poly.bary_map();
        Ok(RationalBezierTriangle {
            domain,
            map,
            degree,
            points: poly.points().to_vec(),
            weights,
        })
    }

    /// Replaces ordinate `i` and its weight.
    ///
    /// # Panics
    /// If `i` is out of range, the point not finite or the weight not finite and positive.
    pub fn set_weighted_ordinate(&mut self, i: usize, point: V, weight: f64) {
        assert!(point.is_finite(), "ordinates must be finite");
        assert!(
            weight > 0.0 && weight.is_finite(),
            "weights must be positive"
        );
        self.points[i] = point;
        self.weights[i] = weight;
    }

    /// The polynomial patch as a rational one with all weights 1.
    pub fn from_polynomial(p: &BezierTriangle<V>) -> Self {
        RationalBezierTriangle {
            domain: *p.domain(),
            map: *p.bary_map(),
            degree: p.degree(),
            points: p.points().to_vec(),
            weights: vec![1.0; p.points().len()],
        }
    }

    /// The degree m.
    pub fn degree(&self) -> usize {
        self.degree
    }
    /// The domain triangle.
    pub fn domain(&self) -> &Triangle2 {
        &self.domain
    }
    /// The control points b_λ in storage order.
    pub fn points(&self) -> &[V] {
        &self.points
    }
    /// The weights w_λ in storage order.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The denominator w(τ) = Σ w_λ B^m_λ(τ) (3.15) as a polynomial patch.
    pub fn denominator(&self) -> BezierTriangle<f64> {
        BezierTriangle::new_unchecked(self.domain, self.map, self.degree, self.weights.clone())
    }

    /// The numerator p(τ) = Σ w_λ b_λ B^m_λ(τ) (3.14) as a polynomial patch (the homogeneous
    /// form; evaluating it and dividing is the numerically unstable route the thesis warns of).
    pub fn numerator(&self) -> BezierTriangle<V> {
        let pts = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(&b, &w)| b * w)
            .collect();
        BezierTriangle::new_unchecked(self.domain, self.map, self.degree, pts)
    }

    /// The projected intermediate net after `steps` rational de Casteljau steps at τ.
    fn projected(&self, t: Bary, steps: usize) -> Result<(Vec<V>, Vec<f64>), BezierError> {
        let mut p = self.points.clone();
        let mut w = self.weights.clone();
        for s in 0..steps {
            rational_step(&mut p, &mut w, self.degree - s, t)?;
        }
        let n = net_len(self.degree - steps);
        p.truncate(n);
        w.truncate(n);
        Ok((p, w))
    }

    /// The value and the denominator w(τ) at τ by the rational de Casteljau algorithm (3.5)–(3.12).
    pub fn eval_bary_weighted(&self, t: Bary) -> Result<(V, f64), BezierError> {
        let (p, w) = self.projected(t, self.degree)?;
        Ok((p[0], w[0]))
    }

    /// The value at τ (Algorithm 3.1); inside the domain triangle this cannot fail.
    pub fn eval_bary(&self, t: Bary) -> Result<V, BezierError> {
        Ok(self.eval_bary_weighted(t)?.0)
    }

    /// The value at the domain point `p`.
    pub fn eval(&self, p: Point2<f64>) -> Result<V, BezierError> {
        self.eval_bary(self.map.apply(p))
    }

    /// The value and the (x, y)-partials up to order two at `p`, from the projected degree-2
    /// intermediate net: with w_i, b_i the level-(m−1) and W_ij, P_ij the level-(m−2)
    /// projected weights and points,
    /// D_d b = m Σ d_i (w_i / w)(b_i − b)  (3.17), and
    /// D_d D_e b = m(m−1) Σ d_i e_j (W_ij / w)(P_ij − b) − (D_d w / w) D_e b − (D_e w / w) D_d b
    /// (seed 000 eq. (10)); only differences of points of the convex hull are formed.
    pub fn jet(&self, p: Point2<f64>) -> Result<Jet<V>, BezierError> {
        let t = self.map.apply(p);
        if self.degree < 2 {
            return self.elevated_to_two().jet(p);
        }
        let (q, qw) = self.projected(t, self.degree - 2)?;
        rational_quadratic_jet(&q, &qw, t, self.map.dx(), self.map.dy(), self.degree as f64)
    }

    /// The r-th directional derivative D^r_d b(τ) by Leibniz' rule (3.18), in the stable form
    /// D^k b = A_k − Σ_{j=1}^{k−1} C(k, j) (D^j w / w) D^{k−j} b with
    /// A_k = m!/(m−k)! Σ_{|μ|=k} B^k_μ(d) (W_μ / w)(P_μ − b), where (W_μ, P_μ) is the projected
    /// level-(m−k) net.
    pub fn directional_derivative(&self, t: Bary, d: Bary, r: usize) -> Result<V, BezierError> {
        let m = self.degree;
        let (b, w) = self.eval_bary_weighted(t)?;
        let mut a = vec![V::zero(); r + 1];
        let mut what = vec![0.0; r + 1];
        for k in 1..=r.min(m) {
            let (pts, ws) = self.projected(t, m - k)?;
            let mut h: Vec<V> = pts
                .iter()
                .zip(&ws)
                .map(|(&p, &wk)| (p - b) * (wk / w))
                .collect();
            let mut hw: Vec<f64> = ws.iter().map(|&wk| wk / w).collect();
            de_casteljau_steps(&mut h, k, d, k);
            de_casteljau_steps(&mut hw, k, d, k);
            let f = falling_factorial(m, k);
            a[k] = h[0] * f;
            what[k] = hw[0] * f;
        }
        let mut der = vec![V::zero(); r + 1];
        der[0] = b;
        for k in 1..=r {
            let mut v = a[k];
            for j in 1..k {
                v = v - der[k - j] * (binomial(k, j) * what[j]);
            }
            der[k] = v;
        }
        Ok(der[r])
    }

    /// The same surface over another triangle inside the domain (e.g. a subdivision piece),
    /// by rational blossoming: each ordinate is a projected blossom value.
    pub fn restrict(&self, target: Triangle2) -> Result<Self, BezierError> {
        let map = target.bary_map().ok_or(BezierError::DegenerateDomain)?;
        let p = target.v.map(|v| self.map.apply(v));
        let state = (self.points.clone(), self.weights.clone(), Ok(()));
        let out = blossom_with(
            state,
            self.degree,
            p,
            |s: &mut (Vec<V>, Vec<f64>, Result<(), BezierError>), deg, t| {
                if s.2.is_ok() {
                    s.2 = rational_step(&mut s.0, &mut s.1, deg, t);
                }
            },
            |s| match &s.2 {
                Ok(()) => Ok((s.0[0], s.1[0])),
                Err(e) => Err(e.clone()),
            },
        );
        let mut points = Vec::with_capacity(out.len());
        let mut weights = Vec::with_capacity(out.len());
        for o in out {
            let (p, w) = o?;
            points.push(p);
            weights.push(w);
        }
        Ok(RationalBezierTriangle {
            domain: target,
            map,
            degree: self.degree,
            points,
            weights,
        })
    }

    /// Mid-edge subdivision (3.20)–(3.31) in the stable projected form: corner pieces at
    /// V1, V2, V3, then the middle piece.
    pub fn subdivide_mid_edge(&self) -> [Self; 4] {
        mid_edge_triangles(&self.domain).map(|t| self.restrict(t).expect("inside the domain"))
    }

    /// Degree elevation to at least 2 (exact; used for the derivatives of degrees 0 and 1).
    fn elevated_to_two(&self) -> Self {
        let mut s = self.clone();
        while s.degree < 2 {
            let hw = elevate_net(&s.weights, s.degree);
            let hp: Vec<V> = elevate_net(
                &s.points
                    .iter()
                    .zip(&s.weights)
                    .map(|(&p, &w)| p * w)
                    .collect::<Vec<_>>(),
                s.degree,
            );
            s.points = hp.iter().zip(&hw).map(|(&p, &w)| p * (1.0 / w)).collect();
            s.weights = hw;
            s.degree += 1;
        }
        s
    }

    /// Iterates over multi-indices with their control points and weights.
    pub fn iter(&self) -> impl Iterator<Item = ([usize; 3], V, f64)> + '_ {
        multi_indices(self.degree)
            .zip(self.points.iter().zip(&self.weights))
            .map(|(l, (&p, &w))| (l, p, w))
    }
}

/// The jet of a rational patch from its projected degree-2 intermediate net (points `q`,
/// weights `qw`, storage order) at τ with unit directions d_x, d_y; `m` is the patch degree.
/// See [`RationalBezierTriangle::jet`] for the formulas.
pub(crate) fn rational_quadratic_jet<V: Vector>(
    q: &[V],
    qw: &[f64],
    t: Bary,
    dx: Bary,
    dy: Bary,
    m: f64,
) -> Result<Jet<V>, BezierError> {
    const PAIR: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];
    let mut b1 = [V::zero(); 3];
    let mut w1 = [0.0; 3];
    for i in 0..3 {
        let ws: [f64; 3] = std::array::from_fn(|j| t[j] * qw[PAIR[i][j]]);
        let wsum: f64 = ws.iter().sum();
        if !(wsum > 0.0) {
            return Err(BezierError::NonPositiveWeight);
        }
        w1[i] = wsum;
        for j in 0..3 {
            b1[i] += q[PAIR[i][j]] * (ws[j] / wsum);
        }
    }
    let ws: [f64; 3] = std::array::from_fn(|i| t[i] * w1[i]);
    let w: f64 = ws.iter().sum();
    if !(w > 0.0) {
        return Err(BezierError::NonPositiveWeight);
    }
    let mut b = V::zero();
    for i in 0..3 {
        b += b1[i] * (ws[i] / w);
    }
    // Directions sum to zero, so contractions may use differences (as in `quadratic_jet`):
    // single differences of Y_i = (w_i / w)(b_i − b) and double differences of
    // X_ij = (W_ij / w)(P_ij − b), which stay small on small or thin triangles.
    let y: [V; 3] = std::array::from_fn(|i| (b1[i] - b) * (w1[i] / w));
    let om: [f64; 3] = std::array::from_fn(|i| w1[i] / w);
    let first = |d: Bary| {
        let acc = (y[1] - y[0]) * d[1] + (y[2] - y[0]) * d[2];
        let dw = (om[1] - om[0]) * d[1] + (om[2] - om[0]) * d[2];
        (acc * m, dw * m)
    };
    let (bx, wx) = first(dx);
    let (by, wy) = first(dy);
    let x = |i: usize, j: usize| (q[PAIR[i][j]] - b) * (qw[PAIR[i][j]] / w);
    let dd = |i: usize, j: usize| x(i, j) - x(i, 0) - x(0, j) + x(0, 0);
    let (d11, d12, d22) = (dd(1, 1), dd(1, 2), dd(2, 2));
    let second = |d: Bary, e: Bary, bd: V, wd: f64, be: V, we: f64| {
        let acc = d11 * (d[1] * e[1]) + d12 * (d[1] * e[2] + d[2] * e[1]) + d22 * (d[2] * e[2]);
        acc * (m * (m - 1.0)) - be * wd - bd * we
    };
    Ok(Jet {
        value: b,
        dx: bx,
        dy: by,
        dxx: second(dx, dx, bx, wx, bx, wx),
        dxy: second(dx, dy, bx, wx, by, wy),
        dyy: second(dy, dy, by, wy, by, wy),
    })
}
