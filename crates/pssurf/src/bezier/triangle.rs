//! Polynomial triangular Bernstein–Bézier patches of any degree (thesis section 2.2).

use nalgebra::{Point2, Vector2};

use super::BezierError;
use super::index::{
    de_casteljau_step, de_casteljau_steps, falling_factorial, index, multi_indices, net_len,
};
use super::jet::Jet;
use crate::geometry::{Bary, BaryMap, Triangle2};
use crate::vector::Vector;

/// A triangular Bernstein–Bézier patch b(τ) = Σ_{|λ|=m} b_λ B^m_λ(τ) of degree m over a
/// domain triangle 𝒯 (2.9, 2.26), with values in R^d (`f64` for a function, `Vector3<f64>`
/// for a parametric surface).
///
/// Ordinates are stored in the order of [`super::index`].
#[derive(Clone, Debug, PartialEq)]
pub struct BezierTriangle<V> {
    domain: Triangle2,
    map: BaryMap,
    degree: usize,
    points: Vec<V>,
}

impl<V: Vector> BezierTriangle<V> {
    /// A patch of degree `degree` over `domain` with ordinates `points` in storage order.
    ///
    /// # Panics
    /// On any of the errors of [`BezierTriangle::try_new`].
    pub fn new(domain: Triangle2, degree: usize, points: Vec<V>) -> Self {
        Self::try_new(domain, degree, points).unwrap_or_else(|e| panic!("{e}"))
    }

    /// A patch, validated: the number of ordinates must be (m + 1)(m + 2)/2, every ordinate
    /// finite, and the domain triangle non-degenerate.
    ///
    /// ```
    /// use pssurf::bezier::{BezierError, BezierTriangle};
    /// use pssurf::geometry::Triangle2;
    /// use nalgebra::Point2;
    /// let t = Triangle2::new(Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(0., 1.));
    /// assert!(matches!(BezierTriangle::try_new(t, 2, vec![0.0; 5]),
    ///     Err(BezierError::WrongOrdinateCount { expected: 6, found: 5 })));
    /// ```
    pub fn try_new(domain: Triangle2, degree: usize, points: Vec<V>) -> Result<Self, BezierError> {
        if points.len() != net_len(degree) {
            return Err(BezierError::WrongOrdinateCount {
                expected: net_len(degree),
                found: points.len(),
            });
        }
        if let Some(i) = points.iter().position(|p| !p.in_range()) {
            return Err(BezierError::NonFiniteOrdinate(i));
        }
        let map = domain.bary_map().ok_or(BezierError::DegenerateDomain)?;
        Ok(Self::new_unchecked(domain, map, degree, points))
    }

    /// A patch without validation; `map` must be `domain.bary_map()`.
    pub fn new_unchecked(domain: Triangle2, map: BaryMap, degree: usize, points: Vec<V>) -> Self {
        BezierTriangle {
            domain,
            map,
            degree,
            points,
        }
    }

    /// The patch over `domain` whose ordinates are the values of `f` at the Bézier triangle
    /// points λ/m (Definition 2.8): exact for linear `f` (Property 2.2, linear precision).
    pub fn from_fn(domain: Triangle2, degree: usize, f: impl Fn(Point2<f64>) -> V) -> Self {
        let m = degree.max(1) as f64;
        let points = multi_indices(degree)
            .map(|l| f(domain.point([l[0] as f64 / m, l[1] as f64 / m, l[2] as f64 / m])))
            .collect();
        Self::new(domain, degree, points)
    }

    /// The degree m.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The domain triangle 𝒯.
    pub fn domain(&self) -> &Triangle2 {
        &self.domain
    }

    /// The map from (x, y) to barycentric coordinates w.r.t. the domain.
    pub fn bary_map(&self) -> &BaryMap {
        &self.map
    }

    /// The ordinates b_λ in storage order.
    pub fn points(&self) -> &[V] {
        &self.points
    }

    /// Mutable access to the ordinates.
    pub fn points_mut(&mut self) -> &mut [V] {
        &mut self.points
    }

    /// The ordinate b_λ.
    pub fn ordinate(&self, l: [usize; 3]) -> V {
        self.points[index(l)]
    }

    /// The value at barycentric coordinates τ by the de Casteljau algorithm (2.13)–(2.15).
    pub fn eval_bary(&self, t: Bary) -> V {
        let mut net = self.points.clone();
        de_casteljau_steps(&mut net, self.degree, t, self.degree);
        net[0]
    }

    /// The value at the domain point `p` (any point of the plane: outside 𝒯 this extrapolates).
    pub fn eval(&self, p: Point2<f64>) -> V {
        self.eval_bary(self.map.apply(p))
    }

    /// The intermediate de Casteljau ordinates b^r_λ(τ), |λ| = m − r (2.15), in storage order.
    pub fn intermediate(&self, t: Bary, r: usize) -> Vec<V> {
        let mut net = self.points.clone();
        de_casteljau_steps(&mut net, self.degree, t, r.min(self.degree));
        net.truncate(net_len(self.degree - r.min(self.degree)));
        net
    }

    /// The r-th directional derivative D^r_d b(τ) of Theorem 2.3: r de Casteljau steps with
    /// the barycentric direction d and m − r with τ, times m!/(m − r)!. Zero for r > m.
    pub fn directional_derivative(&self, t: Bary, d: Bary, r: usize) -> V {
        self.derivative(t, &vec![d; r])
    }

    /// The mixed directional derivative D_{d_1} ⋯ D_{d_r} b(τ) (Theorem 2.3, steps in any order).
    pub fn derivative(&self, t: Bary, dirs: &[Bary]) -> V {
        let m = self.degree;
        let r = dirs.len();
        if r > m {
            return V::zero();
        }
        let mut net = self.points.clone();
        let mut deg = m;
        for d in dirs {
            de_casteljau_step(&mut net, deg, *d);
            deg -= 1;
        }
        de_casteljau_steps(&mut net, deg, t, deg);
        net[0] * falling_factorial(m, r)
    }

    /// The value and the partial derivatives up to order two w.r.t. the domain coordinates
    /// (x, y) at `p` (Algorithm 2.1, extended to second order).
    pub fn jet(&self, p: Point2<f64>) -> Jet<V> {
        let t = self.map.apply(p);
        jet_from_net(&self.points, self.degree, t, self.map.dx(), self.map.dy())
    }

    /// The patch's representation over another triangle `target` (any triangle of the plane):
    /// the ordinates are blossom values b[P1^λ1, P2^λ2, P3^λ3] (Theorem 2.4 applied repeatedly).
    pub fn restrict(&self, target: Triangle2) -> Result<Self, BezierError> {
        let map = target.bary_map().ok_or(BezierError::DegenerateDomain)?;
        let p = target.v.map(|v| self.map.apply(v));
        let points = blossom_net(&self.points, self.degree, p);
        Ok(Self::new_unchecked(target, map, self.degree, points))
    }

    /// Subdivision at an interior point V̂ (Corollary 2.1): the patches over
    /// (V̂, V2, V3), (V1, V̂, V3) and (V1, V2, V̂), from the intermediate de Casteljau ordinates.
    pub fn subdivide_at(&self, p: Point2<f64>) -> Result<[Self; 3], BezierError> {
        let t = self.map.apply(p);
        if t.iter().any(|&ti| ti < 0.0) {
            return Err(BezierError::OutsideDomain);
        }
        let m = self.degree;
        // levels[r] = intermediate net b^r (degree m − r).
        let mut levels = Vec::with_capacity(m + 1);
        let mut net = self.points.clone();
        levels.push(net.clone());
        for r in 0..m {
            de_casteljau_step(&mut net, m - r, t);
            levels.push(net[..net_len(m - r - 1)].to_vec());
        }
        let v = self.domain.v;
        let mut out = Vec::with_capacity(3);
        for corner in 0..3 {
            let mut tri = v;
            tri[corner] = p;
            let tri = Triangle2 { v: tri };
            let map = tri.bary_map().ok_or(BezierError::DegenerateDomain)?;
            // b̂_λ with λ_corner = r is b^r_μ with μ = λ − r e_corner (μ_corner = 0).
            let points = multi_indices(m)
                .map(|l| {
                    let r = l[corner];
                    let mut mu = l;
                    mu[corner] = 0;
                    levels[r][index(mu)]
                })
                .collect();
            out.push(Self::new_unchecked(tri, map, m, points));
        }
        Ok([out[0].clone(), out[1].clone(), out[2].clone()])
    }

    /// Mid-edge (4-split) subdivision: the patches over the corner triangles at V1, V2, V3
    /// and the middle triangle, each congruent to a half-size copy of 𝒯 (section 3.2.2).
    pub fn subdivide_mid_edge(&self) -> [Self; 4] {
        mid_edge_triangles(&self.domain).map(|t| self.restrict(t).expect("half-size triangle"))
    }

    /// The integral over 𝒯: 2A / ((m + 1)(m + 2)) · Σ b_λ (2.21).
    pub fn integral(&self) -> V {
        let m = self.degree;
        let mut sum = V::zero();
        for &b in &self.points {
            sum += b;
        }
        sum * (2.0 * self.domain.area() / ((m + 1) * (m + 2)) as f64)
    }

    /// The same polynomial written with degree m + 1:
    /// b'_λ = Σ_i λ_i / (m + 1) · b_{λ − e_i}.
    pub fn elevate(&self) -> Self {
        let points = elevate_net(&self.points, self.degree);
        Self::new_unchecked(self.domain, self.map, self.degree + 1, points)
    }
}

/// The four half-size triangles of the mid-edge split: corners at V1, V2, V3, then the middle.
pub fn mid_edge_triangles(t: &Triangle2) -> [Triangle2; 4] {
    let [a, b, c] = t.v;
    let ab = crate::geometry::midpoint(a, b);
    let bc = crate::geometry::midpoint(b, c);
    let ca = crate::geometry::midpoint(c, a);
    [
        Triangle2::new(a, ab, ca),
        Triangle2::new(ab, b, bc),
        Triangle2::new(ca, bc, c),
        Triangle2::new(bc, ca, ab),
    ]
}

/// Degree elevation of a net.
pub(crate) fn elevate_net<V: Vector>(net: &[V], m: usize) -> Vec<V> {
    let n = (m + 1) as f64;
    multi_indices(m + 1)
        .map(|l| {
            let mut acc = V::zero();
            for i in 0..3 {
                if l[i] > 0 {
                    let mut k = l;
                    k[i] -= 1;
                    acc += net[index(k)] * (l[i] as f64 / n);
                }
            }
            acc
        })
        .collect()
}

/// The ordinates b[P1^λ1, P2^λ2, P3^λ3] for all |λ| = m: the net over the triangle whose
/// vertices have barycentric coordinates `p` w.r.t. the original domain.
pub(crate) fn blossom_net<V: Vector>(net: &[V], m: usize, p: [Bary; 3]) -> Vec<V> {
    blossom_with(
        net.to_vec(),
        m,
        p,
        |n: &mut Vec<V>, deg, t| de_casteljau_step(n, deg, t),
        |n| n[0],
    )
}

/// Blossom values for every multi-index of degree m, in storage order, for any de Casteljau
/// `step` (polynomial or projected rational) acting on a `state` holding a net of degree m:
/// the value for λ is read after λ1 steps with P1, λ2 with P2 and λ3 with P3.
pub(crate) fn blossom_with<S: Clone, T>(
    state: S,
    m: usize,
    p: [Bary; 3],
    step: impl Fn(&mut S, usize, Bary),
    read: impl Fn(&S) -> T,
) -> Vec<T> {
    let mut out: Vec<Option<T>> = (0..net_len(m)).map(|_| None).collect();
    let mut n1 = state;
    for i in 0..=m {
        let mut n2 = n1.clone();
        for j in 0..=(m - i) {
            let k = m - i - j;
            let mut n3 = n2.clone();
            for s in 0..k {
                step(&mut n3, k - s, p[2]);
            }
            out[index([i, j, k])] = Some(read(&n3));
            if k > 0 {
                step(&mut n2, k, p[1]);
            }
        }
        if i < m {
            step(&mut n1, m - i, p[0]);
        }
    }
    out.into_iter()
        .map(|o| o.expect("every index visited"))
        .collect()
}

/// Value and (x, y)-partials up to order two from a degree-m net at τ, given the unit
/// barycentric directions d_x, d_y (2.18)–(2.19).
pub(crate) fn jet_from_net<V: Vector>(
    points: &[V],
    m: usize,
    t: Bary,
    dx: Bary,
    dy: Bary,
) -> Jet<V> {
    if m < 2 {
        let elevated = if m == 0 {
            elevate_net(&elevate_net(points, 0), 1)
        } else {
            elevate_net(points, 1)
        };
        return jet_from_net(&elevated, 2, t, dx, dy);
    }
    let mut net = points.to_vec();
    de_casteljau_steps(&mut net, m, t, m - 2);
    quadratic_jet(&net[..6], t, dx, dy, m as f64)
}

/// Jet from the degree-2 intermediate net `q` (b^{m−2}) of a degree-m patch:
/// D_d b = m Σ d_i b^{m−1}_{e_i}, D_d D_e b = m (m − 1) Σ d_i e_j b^{m−2}_{e_i + e_j}.
///
/// Since Σ d_i = Σ e_i = 0, constants may be subtracted before contracting: the first
/// derivative uses b^{m−1}_i − b^{m−1}_1 and the second the double differences
/// B_ij − B_i1 − B_1j + B_11 of B_ij = b^{m−2}_{e_i + e_j}. This is algebraically identical and
/// avoids the cancellation of large terms on small or thin triangles (|d| ~ 1/size).
#[inline]
pub(crate) fn quadratic_jet<V: Vector>(q: &[V], t: Bary, dx: Bary, dy: Bary, m: f64) -> Jet<V> {
    // q order: 200, 110, 101, 020, 011, 002.
    let [q200, q110, q101, q020, q011, q002] = [q[0], q[1], q[2], q[3], q[4], q[5]];
    let b1 = [
        q200 * t[0] + q110 * t[1] + q101 * t[2],
        q110 * t[0] + q020 * t[1] + q011 * t[2],
        q101 * t[0] + q011 * t[1] + q002 * t[2],
    ];
    let value = b1[0] * t[0] + b1[1] * t[1] + b1[2] * t[2];
    let (e1, e2) = (b1[1] - b1[0], b1[2] - b1[0]);
    let first = |d: Bary| (e1 * d[1] + e2 * d[2]) * m;
    // Double differences: D11, D12, D22 (row and column 0 vanish).
    let d11 = q020 - q110 - q110 + q200;
    let d12 = q011 - q110 - q101 + q200;
    let d22 = q002 - q101 - q101 + q200;
    let second = |d: Bary, e: Bary| {
        (d11 * (d[1] * e[1]) + d12 * (d[1] * e[2] + d[2] * e[1]) + d22 * (d[2] * e[2]))
            * (m * (m - 1.0))
    };
    Jet {
        value,
        dx: first(dx),
        dy: first(dy),
        dxx: second(dx, dx),
        dxy: second(dx, dy),
        dyy: second(dy, dy),
    }
}

/// The barycentric direction of a domain vector v w.r.t. a triangle's map.
pub fn direction(map: &BaryMap, v: Vector2<f64>) -> Bary {
    crate::geometry::bary_direction(map, v)
}
