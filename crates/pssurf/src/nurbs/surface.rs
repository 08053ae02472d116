//! Tensor-product NURBS surfaces s(u, v) = Σ N_{i,p}(u) N_{j,q}(v) w_ij P_ij / Σ N N w, with
//! exact first and second derivatives, as a surface kind of the library: one rectangular
//! piece per non-empty knot rectangle (the Bézier extraction without building the Bézier
//! nets: each piece is evaluated on its own span, and extends beyond it as its polynomial).
//!
//! Derivatives of the homogeneous surface A = Σ N N (wP, w) are contracted in v first, then
//! in u; the rational derivatives follow from S = A/w by Leibniz's rule (*The NURBS Book*,
//! eq. 4.20): S_u = (A_u − w_u S)/w, S_uu = (A_uu − 2 w_u S_u − w_uu S)/w,
//! S_uv = (A_uv − w_u S_v − w_v S_u − w_uv S)/w.

use nalgebra::{Point2, Vector3};
use thiserror::Error;

use super::basis::{KnotError, KnotVector, MAX_DEGREE};
use super::curve::NurbsCurve;
use crate::bezier::Jet;
use crate::surface::{
    ControlFreedom, ControlId, ControlNet, ControlPoint, Cursor, EditError, OutsideDomain,
    ParametricSurface, PieceKind, PiecePoint, PieceShape, PiecewiseSurface, Rectangle, SurfaceJet,
};

/// Why a NURBS surface is refused.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum NurbsError {
    /// A knot vector is invalid.
    #[error("{direction} knots: {source}")]
    Knots {
        /// "u" or "v".
        direction: &'static str,
        /// What is wrong.
        source: KnotError,
    },
    /// The number of control points (or weights) is not n_u × n_v.
    #[error("{found} {what} for a {nu} × {nv} net")]
    Count {
        /// "control points" or "weights".
        what: &'static str,
        /// The number given.
        found: usize,
        /// n_u.
        nu: usize,
        /// n_v.
        nv: usize,
    },
    /// A control point is not finite (or beyond ±1e60).
    #[error("control point {0} must have finite coordinates within ±1e60")]
    Point(usize),
    /// A weight is not finite and positive.
    #[error("weight {0} is {1}; weights must lie between 1e-30 and 1e30")]
    Weight(usize, f64),
}

/// A tensor-product NURBS surface.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    knots: [KnotVector; 2],
    points: Vec<Vector3<f64>>,
    weights: Vec<f64>,
    rational: bool,
    /// (w x, w y, w z, w) per control point.
    homogeneous: Vec<[f64; 4]>,
}

impl NurbsSurface {
    /// A NURBS surface of degrees `degree` = [p, q] with knot vectors `knots` = [U, V] and an
    /// n_u × n_v control net given row by row (`points[i·n_v + j]` = P_ij, i along u), with
    /// `weights` in the same order (`None`: a polynomial B-spline surface, weights 1).
    pub fn try_new(
        degree: [usize; 2],
        knots: [Vec<f64>; 2],
        counts: [usize; 2],
        points: Vec<Vector3<f64>>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, NurbsError> {
        let [ku, kv] = knots;
        let u =
            KnotVector::try_new(degree[0], ku, counts[0]).map_err(|source| NurbsError::Knots {
                direction: "u",
                source,
            })?;
        let v =
            KnotVector::try_new(degree[1], kv, counts[1]).map_err(|source| NurbsError::Knots {
                direction: "v",
                source,
            })?;
        let n = counts[0] * counts[1];
        let count_error = |what, found| NurbsError::Count {
            what,
            found,
            nu: counts[0],
            nv: counts[1],
        };
        if points.len() != n {
            return Err(count_error("control points", points.len()));
        }
        let rational = weights.is_some();
        let weights = check_net(&points, weights).map_err(|e| match e {
            NurbsError::Count { found, .. } => count_error("weights", found),
            e => e,
        })?;
        let homogeneous = homogeneous(&points, &weights);
        Ok(NurbsSurface {
            knots: [u, v],
            points,
            weights,
            rational,
            homogeneous,
        })
    }

    /// The degrees [p, q].
    pub fn degree(&self) -> [usize; 2] {
        [self.knots[0].degree(), self.knots[1].degree()]
    }

    /// The knot vectors [U, V].
    pub fn knot_vectors(&self) -> &[KnotVector; 2] {
        &self.knots
    }

    /// The net's size [n_u, n_v].
    pub fn counts(&self) -> [usize; 2] {
        [self.knots[0].count(), self.knots[1].count()]
    }

    /// The control points, row by row (P_ij at i·n_v + j).
    pub fn points(&self) -> &[Vector3<f64>] {
        &self.points
    }

    /// The weights, in the order of the points.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Whether the surface was given weights (a rational surface).
    pub fn is_rational(&self) -> bool {
        self.rational
    }

    /// The jet of the piece on knot spans (`iu`, `iv`) at `uv` (the span's polynomial, also
    /// beyond the span).
    #[inline]
    pub fn jet_on(&self, iu: usize, iv: usize, uv: Point2<f64>) -> Jet<Vector3<f64>> {
        // The common degrees with constant loop bounds; the others with arrays of 8 or 16.
        match self.degree() {
            [3, 3] => self.jet_n::<4, 4>([3, 3], iu, iv, uv),
            [2, 2] => self.jet_n::<3, 3>([2, 2], iu, iv, uv),
            [1, 1] => self.jet_n::<2, 2>([1, 1], iu, iv, uv),
            [2, 1] => self.jet_n::<3, 2>([2, 1], iu, iv, uv),
            [1, 2] => self.jet_n::<2, 3>([1, 2], iu, iv, uv),
            [3, 1] => self.jet_n::<4, 2>([3, 1], iu, iv, uv),
            [1, 3] => self.jet_n::<2, 4>([1, 3], iu, iv, uv),
            d if d[0].max(d[1]) < 8 => self.jet_n::<8, 8>(d, iu, iv, uv),
            d => self.jet_n::<{ MAX_DEGREE + 1 }, { MAX_DEGREE + 1 }>(d, iu, iv, uv),
        }
    }

    /// [`NurbsSurface::jet_on`] for degrees `degree` = [p, q] with basis arrays of `NU` > p
    /// and `NV` > q entries.
    #[inline(always)]
    fn jet_n<const NU: usize, const NV: usize>(
        &self,
        degree: [usize; 2],
        iu: usize,
        iv: usize,
        uv: Point2<f64>,
    ) -> Jet<Vector3<f64>> {
        let [p, q] = degree;
        let nv = self.knots[1].count();
        let bu = self.knots[0].basis_of_degree::<NU>(p, iu, uv.x);
        let bv = self.knots[1].basis_of_degree::<NV>(q, iv, uv.y);
        // a[k] for (u, v) derivative orders (0,0), (1,0), (0,1), (2,0), (1,1), (0,2).
        let mut a = [[0.0f64; 4]; 6];
        for r in 0..=p {
            let row = (iu - p + r) * nv + iv - q;
            let net = &self.homogeneous[row..=row + q];
            let mut c = [[0.0f64; 4]; 3];
            for (s, h) in net.iter().enumerate() {
                let (n0, n1, n2) = (bv[0][s], bv[1][s], bv[2][s]);
                for k in 0..4 {
                    c[0][k] += n0 * h[k];
                    c[1][k] += n1 * h[k];
                    c[2][k] += n2 * h[k];
                }
            }
            let (m0, m1, m2) = (bu[0][r], bu[1][r], bu[2][r]);
            for k in 0..4 {
                a[0][k] += m0 * c[0][k];
                a[1][k] += m1 * c[0][k];
                a[2][k] += m0 * c[1][k];
                a[3][k] += m2 * c[0][k];
                a[4][k] += m1 * c[1][k];
                a[5][k] += m0 * c[2][k];
            }
        }
        rational_jet(&a)
    }

    /// The isoparametric curves through `uv`, u ↦ S(u, v) and v ↦ S(u, v), as NURBS curves
    /// (exact: their homogeneous control points are the net's rows or columns contracted
    /// with the other direction's basis functions at `uv`); `None` outside the domain.
    /// Their third derivatives give the coordinate curves' torsion.
    pub fn iso_curves(&self, uv: Point2<f64>) -> Option<[NurbsCurve; 2]> {
        let [nu, nv] = self.counts();
        let contracted = |d: usize, t: f64, lines: usize, at: &dyn Fn(usize, usize) -> usize| {
            let kv = &self.knots[d];
            let (lo, hi) = kv.domain();
            if !(t >= lo && t <= hi) {
                return None;
            }
            let i = kv.spans()[kv.span_rank(t)];
            let b = kv.basis(i, t);
            let p = kv.degree();
            let (mut points, mut weights) = (Vec::with_capacity(lines), Vec::with_capacity(lines));
            for line in 0..lines {
                let mut h = [0.0f64; 4];
                for r in 0..=p {
                    let c = self.homogeneous[at(line, i - p + r)];
                    for k in 0..4 {
                        h[k] += b.d[0][r] * c[k];
                    }
                }
                points.push(Vector3::new(h[0], h[1], h[2]) / h[3]);
                weights.push(h[3]);
            }
            Some((points, weights))
        };
        let curve = |d: usize, (points, weights): (Vec<Vector3<f64>>, Vec<f64>)| {
            let kv = &self.knots[d];
            NurbsCurve::try_new(kv.degree(), kv.knots().to_vec(), points, Some(weights)).ok()
        };
        // u ↦ S(u, v): row i is Σ_j N_j(v) w_ij (P_ij, 1); v ↦ S(u, v) likewise by columns.
        let along_u = contracted(1, uv.y, nu, &|i, j| i * nv + j)?;
        let along_v = contracted(0, uv.x, nv, &|j, i| i * nv + j)?;
        Some([curve(0, along_u)?, curve(1, along_v)?])
    }

    /// The same surface on the rectangle [u₀, u₁] × [v₀, v₁] of its domain, with the same
    /// parametrisation (s′(u, v) = s(u, v) there): each end inside the domain is inserted as a
    /// knot until it has multiplicity p (Boehm's insertion on the homogeneous net, *The NURBS
    /// Book* A5.1), the control points whose basis functions vanish on the rectangle are
    /// dropped and the new ends are clamped. An end within 1e-9 of the domain's width of a
    /// knot is moved onto it: CAD files write about ten digits, and a sliver piece between
    /// the end and the knot would be noise. `None` when the rectangle is empty or not inside
    /// the domain (to that tolerance).
    pub fn restricted(&self, u: [f64; 2], v: [f64; 2]) -> Option<NurbsSurface> {
        let [nu, nv] = self.counts();
        // Lines along u (one per j), clipped; then lines along v (one per i), clipped.
        let lines: Vec<Vec<[f64; 4]>> = (0..nv)
            .map(|j| (0..nu).map(|i| self.homogeneous[i * nv + j]).collect())
            .collect();
        let (ku, lines) = clip(&self.knots[0], u, lines)?;
        let nu = lines[0].len();
        let lines: Vec<Vec<[f64; 4]>> = (0..nu)
            .map(|i| (0..nv).map(|j| lines[j][i]).collect())
            .collect();
        let (kv, lines) = clip(&self.knots[1], v, lines)?;
        let nv = lines[0].len();
        let (mut points, mut weights) = (Vec::with_capacity(nu * nv), Vec::with_capacity(nu * nv));
        for h in lines.iter().flatten() {
            // A polynomial net keeps w = 1 exactly (α + (1 − α) need not round to 1).
            let w = if self.rational { h[3] } else { 1.0 };
            points.push(Vector3::new(h[0], h[1], h[2]) / w);
            weights.push(w);
        }
        let weights = self.rational.then_some(weights);
        NurbsSurface::try_new(self.degree(), [ku, kv], [nu, nv], points, weights).ok()
    }

    /// The spans (i, j) of piece `k`.
    fn piece_spans(&self, k: usize) -> (usize, usize) {
        let sv = self.knots[1].spans();
        (self.knots[0].spans()[k / sv.len()], sv[k % sv.len()])
    }

    /// The rectangle of piece `k`.
    fn rectangle(&self, k: usize) -> Rectangle {
        let (i, j) = self.piece_spans(k);
        let (u, v) = (self.knots[0].knots(), self.knots[1].knots());
        Rectangle::new(Point2::new(u[i], v[j]), Point2::new(u[i + 1], v[j + 1]))
    }

    /// The pieces under basis function (i, j): spans i..=i+p by j..=j+q.
    fn support_of(&self, i: usize, j: usize) -> Vec<usize> {
        let [p, q] = self.degree();
        let (su, sv) = (self.knots[0].spans(), self.knots[1].spans());
        let mut out = Vec::new();
        for (ru, &a) in su.iter().enumerate() {
            if a < i || a > i + p {
                continue;
            }
            for (rv, &b) in sv.iter().enumerate() {
                if b >= j && b <= j + q {
                    out.push(ru * sv.len() + rv);
                }
            }
        }
        out
    }
}

/// Checks control points (finite, within ±1e60) and weights (one per point, 1e-30 … 1e30;
/// all 1 when `None`); the weights.
pub(crate) fn check_net(
    points: &[Vector3<f64>],
    weights: Option<Vec<f64>>,
) -> Result<Vec<f64>, NurbsError> {
    let n = points.len();
    if let Some(i) = points
        .iter()
        .position(|p| !p.iter().all(|&x| crate::limits::value_ok(x)))
    {
        return Err(NurbsError::Point(i));
    }
    let weights = weights.unwrap_or_else(|| vec![1.0; n]);
    if weights.len() != n {
        return Err(NurbsError::Count {
            what: "weights",
            found: weights.len(),
            nu: n,
            nv: 1,
        });
    }
    if let Some(i) = weights.iter().position(|&w| !crate::limits::weight_ok(w)) {
        return Err(NurbsError::Weight(i, weights[i]));
    }
    Ok(weights)
}

/// Lines of homogeneous control points (w P, w), each along one parameter direction.
type HomogeneousLines = Vec<Vec<[f64; 4]>>;

/// The knots and lines of homogeneous control points (each line along this direction) of the
/// same B-spline on [a, b] ⊂ [U_p, U_n]; see [`NurbsSurface::restricted`].
fn clip(
    knots: &KnotVector,
    [a, b]: [f64; 2],
    mut lines: HomogeneousLines,
) -> Option<(Vec<f64>, HomogeneousLines)> {
    let (p, n) = (knots.degree(), knots.count());
    let mut u = knots.knots().to_vec();
    let (lo, hi) = knots.domain();
    let tol = 1e-9 * (hi - lo);
    let snap = |t: f64| {
        u[p..=n]
            .iter()
            .copied()
            .find(|&k| (k - t).abs() <= tol)
            .unwrap_or(t)
    };
    let (a, b) = (snap(a), snap(b));
    if !(a.is_finite() && b.is_finite() && lo <= a && a < b && b <= hi) {
        return None;
    }
    for t in [a, b] {
        if t == lo || t == hi {
            continue;
        }
        let times = u.iter().filter(|&&k| k == t).count();
        for _ in times..p {
            // The span U_k ≤ t < U_{k+1} (p ≤ k < n since U_p < t < U_n).
            let k = u.partition_point(|&x| x <= t) - 1;
            let alpha: Vec<f64> = (k + 1 - p..=k)
                .map(|i| (t - u[i]) / (u[i + p] - u[i]))
                .collect();
            for line in lines.iter_mut() {
                let mut q = Vec::with_capacity(line.len() + 1);
                q.extend_from_slice(&line[..=k - p]);
                for (al, i) in alpha.iter().zip(k + 1 - p..=k) {
                    q.push(std::array::from_fn(|c| {
                        al * line[i][c] + (1.0 - al) * line[i - 1][c]
                    }));
                }
                q.extend_from_slice(&line[k..]);
                *line = q;
            }
            u.insert(k + 1, t);
        }
    }
    // The new U_p is the last knot a, the new U_n the first knot b: the basis functions
    // before and after vanish on [a, b], the kept ones are unchanged.
    let first = u.iter().rposition(|&k| k == a)? - p;
    let end = u.iter().position(|&k| k == b)?;
    let mut kept = u[first..=end + p].to_vec();
    // The outermost knots never enter the basis on the domain: clamping is exact.
    if a > lo {
        kept[0] = a;
    }
    if b < hi {
        *kept.last_mut()? = b;
    }
    let lines = lines
        .into_iter()
        .map(|line| line[first..end].to_vec())
        .collect();
    Some((kept, lines))
}

/// (w x, w y, w z, w) of each control point.
fn homogeneous(points: &[Vector3<f64>], weights: &[f64]) -> Vec<[f64; 4]> {
    points
        .iter()
        .zip(weights)
        .map(|(p, &w)| [w * p.x, w * p.y, w * p.z, w])
        .collect()
}

/// The jet of S = A/w from the homogeneous derivatives (Leibniz's rule).
#[inline]
fn rational_jet(a: &[[f64; 4]; 6]) -> Jet<Vector3<f64>> {
    let xyz = |k: usize| Vector3::new(a[k][0], a[k][1], a[k][2]);
    let w = a[0][3];
    let inv = 1.0 / w;
    let (wu, wv, wuu, wuv, wvv) = (a[1][3], a[2][3], a[3][3], a[4][3], a[5][3]);
    let s = xyz(0) * inv;
    let su = (xyz(1) - s * wu) * inv;
    let sv = (xyz(2) - s * wv) * inv;
    let suu = (xyz(3) - su * (2.0 * wu) - s * wuu) * inv;
    let suv = (xyz(4) - su * wv - sv * wu - s * wuv) * inv;
    let svv = (xyz(5) - sv * (2.0 * wv) - s * wvv) * inv;
    Jet {
        value: s,
        dx: su,
        dy: sv,
        dxx: suu,
        dxy: suv,
        dyy: svv,
    }
}

impl ParametricSurface for NurbsSurface {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        let ((u0, u1), (v0, v1)) = (self.knots[0].domain(), self.knots[1].domain());
        (Point2::new(u0, v0), Point2::new(u1, v1))
    }

    #[inline]
    fn jet_with(&self, uv: Point2<f64>, _: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        let (lo, hi) = self.domain_bounds();
        if !(uv.x >= lo.x && uv.x <= hi.x && uv.y >= lo.y && uv.y <= hi.y) {
            return Err(OutsideDomain::at(uv));
        }
        let (ru, rv) = (self.knots[0].span_rank(uv.x), self.knots[1].span_rank(uv.y));
        let (iu, iv) = (self.knots[0].spans()[ru], self.knots[1].spans()[rv]);
        Ok(SurfaceJet {
            jet: self.jet_on(iu, iv, uv),
            piece: ru * self.knots[1].spans().len() + rv,
        })
    }
}

impl PiecewiseSurface for NurbsSurface {
    fn piece_count(&self) -> usize {
        self.knots[0].spans().len() * self.knots[1].spans().len()
    }

    fn piece_kind(&self) -> PieceKind {
        PieceKind::Rectangle
    }

    fn piece_shape(&self, k: usize) -> PieceShape {
        PieceShape::Rectangle(self.rectangle(k))
    }

    #[inline]
    fn piece_jet(&self, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
        let (iu, iv) = self.piece_spans(k);
        self.jet_on(iu, iv, at.uv)
    }
}

impl ControlNet for NurbsSurface {
    fn control_count(&self) -> usize {
        self.points.len()
    }

    fn control_point(&self, id: ControlId) -> Option<ControlPoint> {
        Some(ControlPoint {
            position: *self.points.get(id.0)?,
            weight: self.weights[id.0],
        })
    }

    fn is_rational(&self) -> bool {
        self.rational
    }

    fn freedom(&self) -> ControlFreedom {
        ControlFreedom::Full
    }

    fn control_group(&self, id: ControlId) -> std::ops::Range<usize> {
        id.0..id.0 + 1
    }

    /// The Greville abscissae (U_{i+1} + … + U_{i+p})/p, (V_{j+1} + … + V_{j+q})/q.
    fn control_anchor(&self, id: ControlId) -> Point2<f64> {
        let nv = self.knots[1].count();
        let greville = |kv: &KnotVector, i: usize| {
            let p = kv.degree();
            kv.knots()[i + 1..=i + p].iter().sum::<f64>() / p as f64
        };
        Point2::new(
            greville(&self.knots[0], id.0 / nv),
            greville(&self.knots[1], id.0 % nv),
        )
    }

    fn support(&self, id: ControlId) -> Vec<usize> {
        let nv = self.knots[1].count();
        self.support_of(id.0 / nv, id.0 % nv)
    }

    /// The net's rows and columns.
    fn control_polylines(&self) -> Vec<Vec<ControlId>> {
        let [nu, nv] = self.counts();
        let rows = (0..nu).map(|i| (0..nv).map(|j| ControlId(i * nv + j)).collect());
        let columns = (0..nv).map(|j| (0..nu).map(|i| ControlId(i * nv + j)).collect());
        rows.chain(columns).collect()
    }

    fn set_control_points(
        &mut self,
        changes: &[(ControlId, ControlPoint)],
    ) -> Result<Vec<usize>, EditError> {
        let count = self.control_count();
        for (id, p) in changes {
            crate::surface::check_point(*id, p, count, self.rational)?;
        }
        let mut pieces = Vec::new();
        for (id, p) in changes {
            self.points[id.0] = p.position;
            self.weights[id.0] = p.weight;
            let w = p.weight;
            self.homogeneous[id.0] = [w * p.position.x, w * p.position.y, w * p.position.z, w];
            pieces.extend(self.support(*id));
        }
        pieces.sort_unstable();
        pieces.dedup();
        Ok(pieces)
    }
}
