//! The paper's local editing of polynomial graph surfaces X(u, v) = (u, h(u, v), v)
//! (Georgiades and Greenberg, seed 003, "Using the curvature of parametric curves", "Surface
//! from curve", "Using the torsion of parametric curves", "Using the Gaussian curvature" and
//! the sidebars, equations (1)–(6)).
//!
//! A rectangular region [r₀, r₂] × [s₀, s₂] around the point (r₁, s₁) is edited; r is the
//! direction of the chosen coordinate curve (u or v) and s the other one.
//!
//! 1. **The curve** (1)–(2): f(r) of degree μ = 2k_r + 2 meets the old coordinate curve
//!    f_old(r) = h(r, s₁) with C^{k_r} at r₀ and r₂ and has curvature
//!    f''/(1 + f'²)^{3/2} = λ at r₁. The 2k_r + 2 linear conditions (2) leave one degree of
//!    freedom, f = f_old + t φ with φ(r) = (r − r₀)^{k_r+1} (r − r₂)^{k_r+1} (the null space of
//!    (2)), so (1) becomes one equation in t,
//!    g(t) = F₂ + t Φ₂ − λ (1 + (F₁ + t Φ₁)²)^{3/2} = 0 (F, Φ the derivatives of f_old and φ at
//!    r₁), concave in t for λ > 0 and convex for λ < 0: at most two roots, bracketed on either
//!    side of the extremum and refined by bisection to the last bit. The root nearer to t = 0
//!    (the smaller change) is taken; without a root, λ is out of reach and the error gives the
//!    largest (or smallest) curvature this continuity allows.
//! 2. **The interpolating curves** p_i(s), i = 0…μ, at nodes r_i in [r₀, r₂] (Chebyshev–Lobatto,
//!    r_0 = r₀, r_μ = r₂): degree ν = 2k_s + 2, C^{k_s} with the old surface at s₀ and s₂, and
//!    through the new curve at s₁: the sidebar's confluent Vandermonde system, solved by LU with
//!    partial pivoting in the variable scaled to [−1, 1] (never an explicit inverse). The
//!    sidebar gives its determinant for k_s = 2 as 4 (s₀ − s₁)³ (s₀ − s₂)⁹ (s₂ − s₁)³; measured,
//!    it is the negative of that for the row order printed. The magnitude, and so the
//!    solvability for s₀ < s₁ < s₂, is right (tested).
//! 3. **The surface** h(r, s) = Σ_j s^j q_j(r), each q_j the degree-μ interpolant of the
//!    curves' coefficients at the nodes: the Vandermonde system (3) (its first rows are
//!    duplicated in the extracted text), again by LU in the scaled variable.
//!
//! The systems run on the *change* of the surface: the end data are zero and the curves pass
//! through f(r_i) − h_old(r_i, s₁). The systems are linear, so for an old surface of degree at
//! most μ in r and ν in s (the paper's algebraic graphs, e.g. quadrics) this is exactly the
//! paper's computation on the surface itself; for any other polynomial the change still
//! vanishes to order k at the border, so the continuity holds for every polynomial surface.
//! The change is then t φ(r) ψ(s) / ψ(s₁) with ψ(s) = (s − s₀)^{k_s+1} (s − s₂)^{k_s+1}, which the
//! tests confirm.
//!
//! **Torsion** (4)–(5): the curve α(r) = (r, f(r), g(r)) (u curves; (g, f, r) for v curves)
//! with f = f_old + t_f φ and g = s₁ + t_g φ satisfies the end conditions for any (t_f, t_g);
//! (4) (curvature λ) and (5) (torsion σ) are solved by Newton's method in (t_f, t_g) from the
//! planar solution. The interpolating curves then pass through f(r_i) at s = g(r_i), so the
//! surface contains α at the nodes only (as the paper says, α is no longer a coordinate
//! curve). The crossing g(r_i) moves with r_i, so the nodes' data are no longer a multiple of
//! φ(r): (3) with the μ + 1 values alone would be C⁰ across r₀ and r₂ only. The q_j are then
//! the confluent interpolants with zero value and derivatives 1…k_r at r₀ and r₂ and the
//! values at the μ − 1 interior nodes, of degree 4k_r + 2 in r.
//! For a given curvature the torsion reachable this way is bounded: τ is t_g A over
//! B + t_g² C near the point, at most |A| / (2√(BC)); beyond it the error says so. With C⁰ (μ = 2) φ is quadratic and g''' = 0, so σ = 0 is the only torsion possible
//! unless f_old''' ≠ 0: the error says so.
//!
//! **Gaussian, mean and principal curvatures** (6): Euler's formula
//! κ cos θ = k₁ cos² φ + k₂ sin² φ gives the coordinate curve's curvature for the wanted
//! principal curvatures (the other one kept). Changing the curve also turns the principal
//! frame, so one step of (6) does not land on the target exactly: the edit family is
//! f_old + t φ, and t is found from the measure itself (from the curvature code): a root
//! bracketed on a geometric ladder of t on both sides of 0, then bisected to 1e-10. K is
//! quadratic in t, so values beyond its extremum are out of reach; the error gives the
//! closest value.
//!
//! The result, old surface outside the region and edited inside, is a NURBS surface of
//! X(u, v) = (u, h(u, v), v) with the region's borders as knots, so every interrogation tool
//! works on it.

use nalgebra::{DMatrix, DVector, Vector3};
use thiserror::Error;

use super::local::Measure;
use crate::interrogate::Curvature;
use crate::nurbs::NurbsSurface;
use crate::surface::ParametricSurface;

/// A polynomial in two variables, h(u, v) = Σ c_ij u^i v^j.
#[derive(Clone, Debug, PartialEq)]
pub struct Poly2 {
    /// c_ij at row i (power of u), column j (power of v).
    pub coeffs: DMatrix<f64>,
}

impl Poly2 {
    /// The polynomial with coefficients `c[i][j]` of u^i v^j.
    pub fn new(coeffs: DMatrix<f64>) -> Self {
        Poly2 { coeffs }
    }

    /// The degrees in u and v.
    pub fn degrees(&self) -> [usize; 2] {
        [self.coeffs.nrows() - 1, self.coeffs.ncols() - 1]
    }

    /// ∂^{a+b} h / ∂u^a ∂v^b at (u, v).
    pub fn derivative(&self, a: usize, b: usize, u: f64, v: f64) -> f64 {
        let mut sum = 0.0;
        for i in a..self.coeffs.nrows() {
            for j in b..self.coeffs.ncols() {
                let c = self.coeffs[(i, j)];
                if c != 0.0 {
                    sum += c
                        * falling(i, a)
                        * falling(j, b)
                        * u.powi((i - a) as i32)
                        * v.powi((j - b) as i32);
                }
            }
        }
        sum
    }

    /// h(u, v).
    pub fn value(&self, u: f64, v: f64) -> f64 {
        self.derivative(0, 0, u, v)
    }

    /// h(v, u): the roles of the variables swapped.
    pub fn transposed(&self) -> Self {
        Poly2::new(self.coeffs.transpose())
    }

    /// The sum of two polynomials (padded to the larger degrees).
    pub fn plus(&self, other: &Poly2) -> Poly2 {
        let rows = self.coeffs.nrows().max(other.coeffs.nrows());
        let cols = self.coeffs.ncols().max(other.coeffs.ncols());
        let mut c = DMatrix::zeros(rows, cols);
        for m in [&self.coeffs, &other.coeffs] {
            for i in 0..m.nrows() {
                for j in 0..m.ncols() {
                    c[(i, j)] += m[(i, j)];
                }
            }
        }
        Poly2::new(c)
    }
}

/// n (n − 1) … (n − k + 1).
fn falling(n: usize, k: usize) -> f64 {
    (0..k).map(|i| (n - i) as f64).product()
}

/// A polynomial in one variable, p(x) = Σ c_k x^k.
#[derive(Clone, Debug, PartialEq)]
pub struct Poly1(pub Vec<f64>);

impl Poly1 {
    /// The m-th derivative at x.
    pub fn derivative(&self, m: usize, x: f64) -> f64 {
        (m..self.0.len())
            .map(|k| self.0[k] * falling(k, m) * x.powi((k - m) as i32))
            .sum()
    }
}

/// Which coordinate curve the edit shapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// The u curve v = v₁: r = u, s = v.
    U,
    /// The v curve u = u₁: r = v, s = u.
    V,
}

/// What the edit prescribes at the point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GraphTarget {
    /// The curvature λ of the coordinate curve (1).
    Curvature(f64),
    /// Curvature λ and torsion σ of the twisted curve (4)–(5).
    Torsion {
        /// λ.
        curvature: f64,
        /// σ.
        torsion: f64,
    },
    /// A surface measure (κ1, κ2, K, H; ku and kv are the normal curvatures) through (6).
    Measure(Measure, f64),
}

/// An edit of a graph patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GraphEditRequest {
    /// The point (u₁, v₁).
    pub at: [f64; 2],
    /// The region [u₀, u₂] × [v₀, v₂], strictly around the point and inside the patch.
    pub region: [[f64; 2]; 2],
    /// The coordinate curve to shape.
    pub direction: Direction,
    /// C^k continuity at the region's border across r (k_r) and across s (k_s), each 0–2.
    pub continuity: [usize; 2],
    /// What to prescribe.
    pub target: GraphTarget,
}

/// A polynomial graph surface X(u, v) = (u, h(u, v), v) on a rectangle.
#[derive(Clone, Debug, PartialEq)]
pub struct GraphPatch {
    /// h.
    pub height: Poly2,
    /// [u_min, u_max] and [v_min, v_max].
    pub domain: [[f64; 2]; 2],
}

/// An edited graph patch: the old height outside the region, old + change inside.
#[derive(Clone, Debug, PartialEq)]
pub struct GraphEdit {
    /// The patch before the edit.
    pub base: GraphPatch,
    /// The region.
    pub region: [[f64; 2]; 2],
    /// The change of h inside the region (zero outside).
    pub change: Poly2,
    /// For a torsion edit, the twisted curve α(r) = (r, f(r), g(r)) (u curves) as (f, g).
    pub twisted: Option<(Poly1, Poly1)>,
    /// The nodes r_i of the interpolating curves.
    pub nodes: Vec<f64>,
    /// The edit's direction.
    pub direction: Direction,
}

/// Why a graph edit failed.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GraphEditError {
    /// A request that means nothing.
    #[error("{0}")]
    BadRequest(String),
    /// The target cannot be reached with this continuity and region.
    #[error("{0}")]
    Unreachable(String),
    /// A linear system was singular (cannot happen for distinct nodes).
    #[error("a linear system of the construction is singular")]
    Singular,
}

/// Solves a small square system by LU with partial pivoting.
fn solve(a: DMatrix<f64>, b: DVector<f64>) -> Result<DVector<f64>, GraphEditError> {
    a.lu().solve(&b).ok_or(GraphEditError::Singular)
}

/// The confluent Vandermonde system of the sidebar ("Deriving interpolating polynomials") in
/// monomials of x: rows are the conditions p^{(m)}(x_c) = value for each (x_c, m).
pub fn confluent_vandermonde(conditions: &[(f64, usize)], degree: usize) -> DMatrix<f64> {
    let n = degree + 1;
    DMatrix::from_fn(conditions.len(), n, |row, k| {
        let (x, m) = conditions[row];
        if k < m {
            0.0
        } else {
            falling(k, m) * x.powi((k - m) as i32)
        }
    })
}

/// The polynomial of degree `conditions.len() − 1` meeting the conditions
/// p^{(m)}(x_c) = values, solved in the variable scaled to [−1, 1] over `interval` and
/// returned in monomials of x.
pub fn interpolate(
    conditions: &[(f64, usize)],
    values: &[f64],
    interval: [f64; 2],
) -> Result<Poly1, GraphEditError> {
    let (mid, half) = (
        0.5 * (interval[0] + interval[1]),
        0.5 * (interval[1] - interval[0]),
    );
    let scaled: Vec<(f64, usize)> = conditions
        .iter()
        .map(|&(x, m)| ((x - mid) / half, m))
        .collect();
    let degree = conditions.len() - 1;
    let a = confluent_vandermonde(&scaled, degree);
    // d^m/dx^m = half^{-m} d^m/dξ^m: the scaled system's right-hand side is value · half^m.
    let b = DVector::from_iterator(
        values.len(),
        conditions
            .iter()
            .zip(values)
            .map(|(&(_, m), &v)| v * half.powi(m as i32)),
    );
    let c = solve(a, b)?;
    Ok(Poly1(expand(c.as_slice(), mid, half)))
}

/// The monomial coefficients in x of Σ c_k ((x − mid)/half)^k.
fn expand(c: &[f64], mid: f64, half: f64) -> Vec<f64> {
    let n = c.len();
    let mut out = vec![0.0; n];
    for (k, &ck) in c.iter().enumerate() {
        // ((x − mid)/half)^k = half^{-k} Σ_i C(k, i) x^i (−mid)^{k−i}.
        let scale = ck / half.powi(k as i32);
        let mut binom = 1.0;
        for i in 0..=k {
            out[i] += scale * binom * (-mid).powi((k - i) as i32);
            binom = binom * (k - i) as f64 / (i + 1) as f64;
        }
    }
    out
}

/// (r − a)^{k+1} (r − b)^{k+1} as monomials.
fn bump(a: f64, b: f64, k: usize) -> Poly1 {
    let mut p = vec![1.0];
    for root in std::iter::repeat_n(a, k + 1).chain(std::iter::repeat_n(b, k + 1)) {
        let mut next = vec![0.0; p.len() + 1];
        for (i, &c) in p.iter().enumerate() {
            next[i + 1] += c;
            next[i] -= root * c;
        }
        p = next;
    }
    Poly1(p)
}

/// Chebyshev–Lobatto nodes on [a, b], a and b included.
fn lobatto(a: f64, b: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| {
            let x = -(std::f64::consts::PI * i as f64 / (count - 1) as f64).cos();
            0.5 * (a + b) + 0.5 * (b - a) * x
        })
        .collect()
}

/// Solves g(t) = F₂ + t Φ₂ − λ (1 + (F₁ + t Φ₁)²)^{3/2} = 0 for the root nearest to 0; `None`
/// when there is none, with the extreme reachable λ.
fn curve_parameter(f1: f64, f2: f64, p1: f64, p2: f64, lambda: f64) -> Result<f64, f64> {
    let g = |t: f64| f2 + t * p2 - lambda * (1.0 + (f1 + t * p1).powi(2)).powf(1.5);
    if lambda == 0.0 || p1 == 0.0 {
        // Linear in t.
        let y = f1;
        if p2 == 0.0 {
            return Err(f2 / (1.0 + y * y).powf(1.5));
        }
        return Ok((lambda * (1.0 + y * y).powf(1.5) - f2) / p2);
    }
    // g is concave (λ > 0) or convex (λ < 0): its extremum is where
    // y √(1 + y²) = Φ₂ / (3 λ Φ₁) with y = F₁ + t Φ₁.
    let c = p2 / (3.0 * lambda * p1);
    let y2 = 0.5 * (-1.0 + (1.0 + 4.0 * c * c).sqrt());
    let ystar = y2.sqrt().copysign(c);
    let tstar = (ystar - f1) / p1;
    let sign = lambda.signum();
    if sign * g(tstar) < 0.0 {
        // The extreme curvature: at the extremum of κ(t) = (F₂ + tΦ₂)/(1 + y²)^{3/2}.
        let kappa = |t: f64| (f2 + t * p2) / (1.0 + (f1 + t * p1).powi(2)).powf(1.5);
        return Err(extreme(kappa, sign));
    }
    let root_on = |dir: f64| {
        let mut step = 1.0f64.max(tstar.abs());
        let mut far = tstar + dir * step;
        let mut n = 0;
        while sign * g(far) > 0.0 && n < 2000 {
            step *= 2.0;
            far = tstar + dir * step;
            n += 1;
        }
        let (mut inside, mut outside) = (tstar, far);
        for _ in 0..200 {
            let mid = 0.5 * (inside + outside);
            if mid == inside || mid == outside {
                break;
            }
            if sign * g(mid) > 0.0 {
                inside = mid;
            } else {
                outside = mid;
            }
        }
        0.5 * (inside + outside)
    };
    let (a, b) = (root_on(-1.0), root_on(1.0));
    Ok(if a.abs() <= b.abs() { a } else { b })
}

/// The largest (sign > 0) or smallest value of a unimodal function of t, by golden section on
/// an expanding bracket.
fn extreme(f: impl Fn(f64) -> f64, sign: f64) -> f64 {
    let h = |t: f64| sign * f(t);
    let (mut a, mut b) = (-1e6, 1e6);
    let phi = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..300 {
        let c = b - phi * (b - a);
        let d = a + phi * (b - a);
        if h(c) > h(d) {
            b = d;
        } else {
            a = c;
        }
    }
    f(0.5 * (a + b))
}

impl GraphPatch {
    /// The built-in demo: h = 0.2 u² + 0.1 u v + 0.3 v² + 0.05 u³ on [−1, 1]² (an elliptic
    /// paraboloid with a cubic term, so that a C⁰ torsion edit is possible).
    pub fn demo() -> Self {
        let mut c = DMatrix::zeros(4, 3);
        c[(2, 0)] = 0.2;
        c[(1, 1)] = 0.1;
        c[(0, 2)] = 0.3;
        c[(3, 0)] = 0.05;
        GraphPatch {
            height: Poly2::new(c),
            domain: [[-1.0, 1.0], [-1.0, 1.0]],
        }
    }

    /// The jet of the patch X(u, v) = (u, h(u, v), v) at (u, v).
    pub fn jet(&self, u: f64, v: f64) -> crate::bezier::Jet<Vector3<f64>> {
        Self::jet_of(&self.height, u, v)
    }

    /// The jet of X(u, v) = (u, h, v) at (u, v) for a height `h`.
    pub(crate) fn jet_of(h: &Poly2, u: f64, v: f64) -> crate::bezier::Jet<Vector3<f64>> {
        let d = |a, b| h.derivative(a, b, u, v);
        crate::bezier::Jet {
            value: Vector3::new(u, d(0, 0), v),
            dx: Vector3::new(1.0, d(1, 0), 0.0),
            dy: Vector3::new(0.0, d(0, 1), 1.0),
            dxx: Vector3::new(0.0, d(2, 0), 0.0),
            dxy: Vector3::new(0.0, d(1, 1), 0.0),
            dyy: Vector3::new(0.0, d(0, 2), 0.0),
        }
    }

    /// Edits the patch (see the module documentation).
    pub fn edit(&self, req: &GraphEditRequest) -> Result<GraphEdit, GraphEditError> {
        self.check(req)?;
        // Work in (r, s): transpose for v curves.
        let (h, at, region) = match req.direction {
            Direction::U => (self.height.clone(), req.at, req.region),
            Direction::V => (
                self.height.transposed(),
                [req.at[1], req.at[0]],
                [req.region[1], req.region[0]],
            ),
        };
        let [kr, ks] = req.continuity;
        let (r1, s1) = (at[0], at[1]);
        let [[r0, r2], [s0, s2]] = region;
        let phi = bump(r0, r2, kr);
        let f_old = |m: usize, r: f64| h.derivative(m, 0, r, s1);
        let (mu, nu) = (2 * kr + 2, 2 * ks + 2);
        let nodes = lobatto(r0, r2, mu + 1);
        // The curve: its parameter t (f = f_old + t φ), or (t_f, t_g) for a torsion edit.
        let (tf, tg) = match req.target {
            GraphTarget::Curvature(lambda) => (self.curve_t(&h, &phi, r1, s1, lambda)?, 0.0),
            GraphTarget::Torsion { curvature, torsion } => {
                torsion_parameters(&f_old, &phi, r1, curvature, torsion)?
            }
            GraphTarget::Measure(m, target) => {
                let t = self.measure_t(req, &h, &phi, [r1, s1], [s0, s2], ks, m, target)?;
                (t, 0.0)
            }
        };
        // The interpolating curves of the change, and the Vandermonde systems (3).
        let change = change_surface(&h, &phi, &nodes, [s0, s1, s2], [kr, ks], nu, tf, tg)?;
        let change = match req.direction {
            Direction::U => change,
            Direction::V => change.transposed(),
        };
        let twisted = matches!(req.target, GraphTarget::Torsion { .. }).then(|| {
            let f = Poly1(pad_add(
                &curve_coeffs(&h, s1, mu.max(h.degrees()[0])),
                &phi.0,
                tf,
            ));
            let g = Poly1(pad_add(&[s1], &phi.0, tg));
            (f, g)
        });
        Ok(GraphEdit {
            base: self.clone(),
            region: req.region,
            change,
            twisted,
            nodes,
            direction: req.direction,
        })
    }

    fn check(&self, req: &GraphEditRequest) -> Result<(), GraphEditError> {
        let bad = |m: &str| Err(GraphEditError::BadRequest(m.to_string()));
        for d in 0..2 {
            let [a, b] = req.region[d];
            let [lo, hi] = self.domain[d];
            let p = req.at[d];
            if !(a.is_finite() && b.is_finite() && p.is_finite()) {
                return bad("the point and the region must be finite");
            }
            if !(lo <= a && a < p && p < b && b <= hi) {
                return bad(
                    "the region must lie inside the patch with the point strictly inside it",
                );
            }
        }
        if req.continuity.iter().any(|&k| k > 2) {
            return bad("continuity is C0, C1 or C2");
        }
        let finite = match req.target {
            GraphTarget::Curvature(l) => l.is_finite(),
            GraphTarget::Torsion { curvature, torsion } => {
                curvature.is_finite() && torsion.is_finite()
            }
            GraphTarget::Measure(_, v) => v.is_finite(),
        };
        if !finite {
            return bad("the target must be a finite number");
        }
        Ok(())
    }

    /// The curve parameter t of (1) for curvature λ at r₁.
    fn curve_t(
        &self,
        h: &Poly2,
        phi: &Poly1,
        r1: f64,
        s1: f64,
        lambda: f64,
    ) -> Result<f64, GraphEditError> {
        let (f1, f2) = (h.derivative(1, 0, r1, s1), h.derivative(2, 0, r1, s1));
        let (p1, p2) = (phi.derivative(1, r1), phi.derivative(2, r1));
        curve_parameter(f1, f2, p1, p2, lambda).map_err(|reach| {
            GraphEditError::Unreachable(format!(
                "curvature {lambda} is out of reach for this curve with this continuity and region: the {} curvature possible is {}; widen the region or lower the continuity",
                if lambda > 0.0 { "largest" } else { "smallest" },
                crate::text::Significant(reach, 8)
            ))
        })
    }

    /// The curve parameter that gives the surface measure `m` the value `target` at the point:
    /// the curvature of the coordinate curve from Euler's formula (6) as the first guess, then
    /// the secant method on the measure itself.
    #[allow(clippy::too_many_arguments)]
    fn measure_t(
        &self,
        req: &GraphEditRequest,
        h: &Poly2,
        phi: &Poly1,
        [r1, s1]: [f64; 2],
        [s0, s2]: [f64; 2],
        ks: usize,
        m: Measure,
        target: f64,
    ) -> Result<f64, GraphEditError> {
        let psi = bump(s0, s2, ks);
        let psi1 = psi.derivative(0, s1);
        // The height with the change t φ(r) ψ(s)/ψ(s₁), in (u, v) order.
        let measure_at = |t: f64| -> Option<f64> {
            let mut c = DMatrix::zeros(phi.0.len(), psi.0.len());
            for (i, a) in phi.0.iter().enumerate() {
                for (j, b) in psi.0.iter().enumerate() {
                    c[(i, j)] = t * a * b / psi1;
                }
            }
            let change = Poly2::new(c);
            let (change, hh) = match req.direction {
                Direction::U => (change, h.clone()),
                Direction::V => (change.transposed(), h.transposed()),
            };
            let total = hh.plus(&change);
            m.of(&Self::jet_of(&total, req.at[0], req.at[1]))
        };
        let before = measure_at(0.0).ok_or(GraphEditError::Singular)?;
        // Euler (6): the wanted principal curvatures (the other kept) give the normal
        // curvature along the coordinate direction, κ_n = k₁ cos² φ + k₂ sin² φ, and the curve's
        // curvature κ = κ_n / cos θ with cos θ = N·n. For X = (u, h, v) and the u curve
        // (r, f(r)) this is f''/(1 + f'²)^{3/2} = −κ_n √(1 + h_u² + h_v²) / √(1 + h_u²).
        let j = Self::jet_of(&self.height, req.at[0], req.at[1]);
        let c = Curvature::from_jet(&j).map_err(|_| GraphEditError::Singular)?;
        let (k1, k2) = match m {
            Measure::K1 => (target, c.k2),
            Measure::K2 => (c.k1, target),
            Measure::Gaussian if c.k1.abs() >= c.k2.abs() && c.k1 != 0.0 => (c.k1, target / c.k1),
            Measure::Gaussian if c.k2 != 0.0 => (target / c.k2, c.k2),
            Measure::Mean => (c.k1 + (target - c.mean), c.k2 + (target - c.mean)),
            _ => (c.k1, c.k2),
        };
        let along = match req.direction {
            Direction::U => j.dx,
            Direction::V => j.dy,
        };
        let cos_phi = c.dir1.dot(&along.normalize()).clamp(-1.0, 1.0);
        let kappa_n = k1 * cos_phi * cos_phi + k2 * (1.0 - cos_phi * cos_phi);
        let slope = along.y;
        let grad = 1.0 + j.dx.y * j.dx.y + j.dy.y * j.dy.y;
        let euler = -kappa_n * grad.sqrt() / (1.0 + slope * slope).sqrt();
        let guess = self.curve_t(h, phi, r1, s1, euler).unwrap_or(0.0);
        // The measure along the family t: bracket a root on a geometric ladder of t on both
        // sides of 0 (and around the guess), then bisect; the root of smallest |t| (the
        // smallest change) wins.
        let f = |t: f64| measure_at(t).map(|v| v - target);
        let f0 = before - target;
        if f0 == 0.0 {
            return Ok(0.0);
        }
        let scale = guess.abs().max(1e-3);
        let mut best: Option<f64> = None;
        let mut closest = (f0.abs(), before);
        for dir in [1.0, -1.0] {
            let (mut a, mut fa) = (0.0, f0);
            for k in 0..60 {
                let t = dir * scale * 1.5f64.powi(k - 20);
                let Some(ft) = f(t) else { break };
                if ft.abs() < closest.0 {
                    closest = (ft.abs(), ft + target);
                }
                if ft.signum() != fa.signum() {
                    let (mut lo, mut hi, mut flo) = (a, t, fa);
                    for _ in 0..200 {
                        let mid = 0.5 * (lo + hi);
                        if mid == lo || mid == hi {
                            break;
                        }
                        let Some(fm) = f(mid) else { break };
                        if fm.signum() == flo.signum() {
                            (lo, flo) = (mid, fm);
                        } else {
                            hi = mid;
                        }
                    }
                    let root = 0.5 * (lo + hi);
                    if best.is_none_or(|b| root.abs() < b.abs()) {
                        best = Some(root);
                    }
                    break;
                }
                (a, fa) = (t, ft);
            }
        }
        if let Some(t) = best
            && let Some(ft) = f(t)
            && ft.abs() <= 1e-10 * target.abs().max(1.0)
        {
            return Ok(t);
        }
        Err(GraphEditError::Unreachable(format!(
            "{} = {target} is out of reach by reshaping this coordinate curve with this continuity and region (the closest is {}): try the other direction or a wider region",
            m.description(),
            crate::text::Significant(closest.1, 8)
        )))
    }
}

/// The coefficients of f_old(r) = h(r, s₁) in monomials of r, padded to `degree`.
fn curve_coeffs(h: &Poly2, s1: f64, degree: usize) -> Vec<f64> {
    let mut out = vec![0.0; degree + 1];
    for i in 0..h.coeffs.nrows() {
        for j in 0..h.coeffs.ncols() {
            out[i] += h.coeffs[(i, j)] * s1.powi(j as i32);
        }
    }
    out
}

/// a + t b, padded.
fn pad_add(a: &[f64], b: &[f64], t: f64) -> Vec<f64> {
    let n = a.len().max(b.len());
    (0..n)
        .map(|k| a.get(k).copied().unwrap_or(0.0) + t * b.get(k).copied().unwrap_or(0.0))
        .collect()
}

/// Solves (4)–(5) for (t_f, t_g) by Newton's method from the planar solution.
fn torsion_parameters(
    f_old: &dyn Fn(usize, f64) -> f64,
    phi: &Poly1,
    r1: f64,
    lambda: f64,
    sigma: f64,
) -> Result<(f64, f64), GraphEditError> {
    let p: [f64; 4] = std::array::from_fn(|m| phi.derivative(m, r1));
    if p[3] == 0.0 && f_old(3, r1) == 0.0 && sigma != 0.0 {
        return Err(GraphEditError::Unreachable(
            "with C0 continuity the twisted curve is quadratic in the region and cannot have torsion: choose C1 or C2".into(),
        ));
    }
    // (κ², τ) of α = (r, f, g) at r₁ as functions of (t_f, t_g).
    let eval = |tf: f64, tg: f64| {
        let f: [f64; 4] = std::array::from_fn(|m| f_old(m, r1) + tf * p[m]);
        let g: [f64; 4] = std::array::from_fn(|m| tg * p[m]);
        let cross = (f[2] * g[1] - f[1] * g[2]).powi(2) + g[2] * g[2] + f[2] * f[2];
        let speed = f[1] * f[1] + g[1] * g[1] + 1.0;
        let kappa2 = cross / speed.powi(3);
        let tau = (f[2] * g[3] - f[3] * g[2]) / cross;
        [kappa2 - lambda * lambda, tau - sigma]
    };
    let newton = |mut t: [f64; 2]| -> Option<[f64; 2]> {
        let norm = |r: [f64; 2]| {
            (r[0] / (lambda * lambda).max(1e-300)).abs() + (r[1] / sigma.abs().max(1e-300)).abs()
        };
        for _ in 0..100 {
            let r = eval(t[0], t[1]);
            if r[0].abs() <= 1e-14 * (lambda * lambda).max(1.0)
                && r[1].abs() <= 1e-13 * sigma.abs().max(1.0)
            {
                return Some(t);
            }
            let h = 1e-7 * (1.0 + t[0].abs().max(t[1].abs()));
            let mut jac = DMatrix::zeros(2, 2);
            for k in 0..2 {
                let (mut a, mut b) = (t, t);
                a[k] += h;
                b[k] -= h;
                let (ra, rb) = (eval(a[0], a[1]), eval(b[0], b[1]));
                jac[(0, k)] = (ra[0] - rb[0]) / (2.0 * h);
                jac[(1, k)] = (ra[1] - rb[1]) / (2.0 * h);
            }
            let step = jac.lu().solve(&DVector::from_vec(vec![-r[0], -r[1]]))?;
            let mut alpha = 1.0;
            loop {
                let trial = [t[0] + alpha * step[0], t[1] + alpha * step[1]];
                let rt = eval(trial[0], trial[1]);
                if rt.iter().all(|x| x.is_finite()) && norm(rt) < norm(r) {
                    t = trial;
                    break;
                }
                alpha *= 0.5;
                if alpha < 1e-10 {
                    return None;
                }
            }
        }
        None
    };
    // Starts: the planar curve with curvature λ (or no change) and twists of either sign and
    // several sizes; the solution with the smallest change wins.
    let (f1, f2) = (f_old(1, r1), f_old(2, r1));
    let planar = curve_parameter(f1, f2, p[1], p[2], lambda).unwrap_or(0.0);
    let mut best: Option<[f64; 2]> = None;
    for tf in [planar, 0.0] {
        for tg in [0.01, -0.01, 0.1, -0.1, 1.0, -1.0, 10.0, -10.0] {
            if let Some(t) = newton([tf, tg / p[2].abs().max(1e-12).sqrt()])
                && best.is_none_or(|b| t[0].abs() + t[1].abs() < b[0].abs() + b[1].abs())
            {
                best = Some(t);
            }
        }
    }
    if let Some(t) = best {
        return Ok((t[0], t[1]));
    }
    Err(GraphEditError::Unreachable(format!(
        "no curve with curvature {lambda} and torsion {sigma} meets the region's border with this continuity (Newton's method on (4)-(5) found no solution from 16 starts)"
    )))
}

/// The change of h in (r, s): the interpolating curves of the change at the nodes (through the
/// curve at s = s₁, or at s = g(r_i) for a twisted curve) and the Vandermonde systems (3)
/// (confluent at r₀ and r₂ for a twisted curve, so that the change is C^{k_r} there).
#[allow(clippy::too_many_arguments)]
fn change_surface(
    h: &Poly2,
    phi: &Poly1,
    nodes: &[f64],
    [s0, s1, s2]: [f64; 3],
    [kr, ks]: [usize; 2],
    nu: usize,
    tf: f64,
    tg: f64,
) -> Result<Poly2, GraphEditError> {
    // Conditions: values at s₀, s_cross, s₂, then derivatives 1..k_s at s₀ and s₂ (the
    // sidebar's row order).
    let mut rows = Vec::new();
    for i in 0..nodes.len() {
        let r = nodes[i];
        let cross = s1 + tg * phi.derivative(0, r);
        if !(s0 < cross && cross < s2) {
            return Err(GraphEditError::Unreachable(
                "the twisted curve leaves the region: lower the torsion or widen the region".into(),
            ));
        }
        let through = h.derivative(0, 0, r, s1) + tf * phi.derivative(0, r) - h.value(r, cross);
        let mut conditions = vec![(s0, 0), (cross, 0), (s2, 0)];
        let mut values = vec![0.0, through, 0.0];
        for m in 1..=ks {
            conditions.push((s0, m));
            conditions.push((s2, m));
            values.extend([0.0, 0.0]);
        }
        let p = interpolate(&conditions, &values, [s0, s2])?;
        debug_assert_eq!(p.0.len(), nu + 1);
        rows.push(p.0);
    }
    // q_j(r_i) = a_ij: one Vandermonde system per power of s. Every p_i is a multiple of
    // ψ(s), so the s borders are C^{k_s} whatever the q_j. Across the r borders the change is
    // C^{k_r} only if every q_j vanishes to order k_r + 1 at r₀ and r₂. For a planar curve the
    // data are t φ(r_i) · (coefficients of ψ/ψ(s₁)), and the degree-μ interpolant reproduces
    // t φ exactly. For a twisted curve the crossing s = g(r_i) moves with r_i, the data are not
    // samples of a multiple of φ, and the interpolant of the μ + 1 values has only zeros at r₀
    // and r₂ (C⁰): its derivatives jump. So the twisted case prescribes q_j^{(m)} = 0 at r₀ and
    // r₂ for m = 0…k_r and q_j(r_i) = a_ij at the μ − 1 interior nodes: degree 4k_r + 2, the
    // "higher degree in r" the paper says the approximation of α costs.
    let mu = nodes.len() - 1;
    let interval = [nodes[0], nodes[mu]];
    let (conditions, rows): (Vec<(f64, usize)>, Vec<Vec<f64>>) = if tg == 0.0 {
        (nodes.iter().map(|&r| (r, 0)).collect(), rows)
    } else {
        let mut conditions = Vec::new();
        let mut data = Vec::new();
        for m in 0..=kr {
            for r in interval {
                conditions.push((r, m));
                data.push(vec![0.0; nu + 1]);
            }
        }
        for (&r, a) in nodes.iter().zip(&rows).take(mu).skip(1) {
            conditions.push((r, 0));
            data.push(a.clone());
        }
        (conditions, data)
    };
    let mut coeffs = DMatrix::zeros(conditions.len(), nu + 1);
    for j in 0..=nu {
        let values: Vec<f64> = rows.iter().map(|a| a[j]).collect();
        let q = interpolate(&conditions, &values, interval)?;
        for (i, c) in q.0.iter().enumerate() {
            coeffs[(i, j)] = *c;
        }
    }
    Ok(Poly2::new(coeffs))
}

impl GraphEdit {
    /// The edited height at (u, v) with derivatives ∂^{a+b}/∂u^a ∂v^b.
    pub fn derivative(&self, a: usize, b: usize, u: f64, v: f64) -> f64 {
        let base = self.base.height.derivative(a, b, u, v);
        let [[u0, u2], [v0, v2]] = self.region;
        if u0 <= u && u <= u2 && v0 <= v && v <= v2 {
            base + self.change.derivative(a, b, u, v)
        } else {
            base
        }
    }

    /// The edited surface as a NURBS surface of X(u, v) = (u, h(u, v), v): nine polynomial
    /// pieces (the region and its eight neighbours), each an exact tensor Bézier patch, joined
    /// by knots of full multiplicity at the region's border.
    pub fn to_nurbs(&self) -> NurbsSurface {
        let [bu, bv] = self.base.height.degrees();
        let [cu, cv] = self.change.degrees();
        let (du, dv) = (bu.max(cu).max(1), bv.max(cv).max(1));
        let [[u0, u2], [v0, v2]] = self.region;
        let [[ua, ub], [va, vb]] = self.base.domain;
        let ucuts = [ua, u0, u2, ub];
        let vcuts = [va, v0, v2, vb];
        let (nu, nv) = (3 * du + 1, 3 * dv + 1);
        let mut points = vec![Vector3::zeros(); nu * nv];
        for pu in 0..3 {
            for pv in 0..3 {
                let inside = pu == 1 && pv == 1;
                let height = if inside {
                    self.base.height.plus(&self.change)
                } else {
                    self.base.height.clone()
                };
                let ys = bernstein_net(
                    &height,
                    [ucuts[pu], ucuts[pu + 1]],
                    [vcuts[pv], vcuts[pv + 1]],
                    du,
                    dv,
                );
                for i in 0..=du {
                    for j in 0..=dv {
                        let u = ucuts[pu] + (ucuts[pu + 1] - ucuts[pu]) * i as f64 / du as f64;
                        let v = vcuts[pv] + (vcuts[pv + 1] - vcuts[pv]) * j as f64 / dv as f64;
                        points[(pu * du + i) * nv + pv * dv + j] = Vector3::new(u, ys[(i, j)], v);
                    }
                }
            }
        }
        let knots = |cuts: [f64; 4], d: usize| {
            let mut k = vec![cuts[0]; d + 1];
            for c in &cuts[1..3] {
                k.extend(std::iter::repeat_n(*c, d));
            }
            k.extend(std::iter::repeat_n(cuts[3], d + 1));
            k
        };
        NurbsSurface::try_new(
            [du, dv],
            [knots(ucuts, du), knots(vcuts, dv)],
            [nu, nv],
            points,
            None,
        )
        .expect("a valid piecewise Bézier net")
    }
}

/// The tensor Bernstein coefficients of degrees (du, dv) of h on [a, b] × [c, d].
fn bernstein_net(
    h: &Poly2,
    [a, b]: [f64; 2],
    [c, d]: [f64; 2],
    du: usize,
    dv: usize,
) -> DMatrix<f64> {
    // Monomials in the local variables x = (u − a)/(b − a), y = (v − c)/(d − c).
    let local = DMatrix::from_fn(du + 1, dv + 1, |i, j| {
        // ∂^{i+j} h / ∂u^i ∂v^j (a, c) (b − a)^i (d − c)^j / (i! j!) is the coefficient of x^i y^j.
        if i > h.degrees()[0] || j > h.degrees()[1] {
            return 0.0;
        }
        h.derivative(i, j, a, c) * (b - a).powi(i as i32) * (d - c).powi(j as i32)
            / (falling(i, i) * falling(j, j))
    });
    // Monomial → Bernstein in each variable: b_k = Σ_{i ≤ k} C(k, i) / C(n, i) m_i.
    let to_bernstein = |n: usize| {
        DMatrix::from_fn(n + 1, n + 1, |k, i| {
            if i > k {
                0.0
            } else {
                binomial(k, i) / binomial(n, i)
            }
        })
    };
    to_bernstein(du) * local * to_bernstein(dv).transpose()
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The measure's value on the edited surface at the point (for reports and tests), from the
/// NURBS surface and the curvature code.
pub fn measure_on(s: &NurbsSurface, m: Measure, at: [f64; 2]) -> Option<f64> {
    let j = s.jet(nalgebra::Point2::new(at[0], at[1])).ok()?.jet;
    m.of(&j)
}

#[cfg(test)]
mod tests;
