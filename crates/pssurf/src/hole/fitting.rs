//! The fitting equations of the polygonal hole problem (thesis 5.2–5.3) written for the
//! tangent-plane map of the patch at a boundary vertex.
//!
//! The control triangle of a UPS-spline at a vertex V lies in the tangent plane there:
//! c_k = s(V) + A (Q_k − V) with A = ∂s/∂(x, y) the derivative and Q_k the corners of the
//! fixed PS-triangle t(6) (Property 4.1). A [`VertexFrame`] holds s(V) and A. In the thesis'
//! terms, for a boundary edge of length h in the unit direction e (the hole to its left,
//! e⊥ = e turned by +90°):
//! - α γ = (h/2) A e, the α-factor (5.6) times the unit tangent;
//! - β δ = (√3 h/4) A(−e⊥), the β-factor (5.7) times the unit cross-boundary tangent.
//!
//! These give (5.8) at inner boundary vertices and (5.11) at corners of any angle, and
//! reduce to the thesis' formulas for its horizontal edge.

use nalgebra::{Matrix2, Vector2, Vector3};

use crate::ups::lattice::SQRT3_2;

/// s(V) and the derivative A of the patch at a vertex: A e_x and A e_y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexFrame {
    /// s(V).
    pub point: Vector3<f64>,
    /// ∂s/∂x.
    pub dx: Vector3<f64>,
    /// ∂s/∂y.
    pub dy: Vector3<f64>,
}

/// The offsets Q_k − V of the corners of t(6) for lattice base h (Property 4.1).
pub fn corner_offsets(h: f64) -> [Vector2<f64>; 3] {
    [
        Vector2::new(-0.5 * h, 0.0),
        Vector2::new(0.25 * h, -0.5 * SQRT3_2 * h),
        Vector2::new(0.25 * h, 0.5 * SQRT3_2 * h),
    ]
}

/// e turned by +90° (into the hole when e runs counter-clockwise along its boundary).
pub fn inward(e: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-e.y, e.x)
}

impl VertexFrame {
    /// A v.
    pub fn along(&self, v: Vector2<f64>) -> Vector3<f64> {
        self.dx * v.x + self.dy * v.y
    }

    /// The control triangle for lattice base h: c_k = s(V) + A (Q_k − V).
    pub fn triple(&self, h: f64) -> [Vector3<f64>; 3] {
        corner_offsets(h).map(|o| self.point + self.along(o))
    }

    /// The frame of a control triangle (its centroid and the affine map through its corners).
    pub fn from_triple(c: &[Vector3<f64>; 3], h: f64) -> Self {
        let q = corner_offsets(h);
        let m = Matrix2::from_columns(&[q[1] - q[0], q[2] - q[0]]);
        let inv = m.try_inverse().expect("t(6) is not degenerate");
        let (d1, d2) = (c[1] - c[0], c[2] - c[0]);
        // A = [d1 d2] M⁻¹.
        VertexFrame {
            point: (c[0] + c[1] + c[2]) / 3.0,
            dx: d1 * inv[(0, 0)] + d2 * inv[(1, 0)],
            dy: d1 * inv[(0, 1)] + d2 * inv[(1, 1)],
        }
    }

    /// (5.8) at an inner boundary vertex: A = (2α/h) γ eᵀ − (4β/(√3 h)) δ e⊥ᵀ, so that
    /// (h/2) A e = α γ and (√3h/4) A(−e⊥) = β δ.
    pub fn inner(
        point: Vector3<f64>,
        (alpha, gamma): (f64, Vector3<f64>),
        (beta, delta): (f64, Vector3<f64>),
        e: Vector2<f64>,
        h: f64,
    ) -> Self {
        let along = gamma * (2.0 * alpha / h);
        let across = delta * (-4.0 * beta / (2.0 * SQRT3_2 * h));
        let n = inward(e);
        VertexFrame {
            point,
            dx: along * e.x + across * n.x,
            dy: along * e.y + across * n.y,
        }
    }

    /// (5.11) at a corner of any angle: A e_out = (2α₁/h) γ₁ along the outgoing edge and
    /// A(−e_in) = (2α₂/h)(−γ₂) back along the incoming one, i.e. A e_in = (2α₂/h) γ₂, with γ
    /// the unit tangents in the direction of travel.
    pub fn corner(
        point: Vector3<f64>,
        (alpha_out, gamma_out, e_out): (f64, Vector3<f64>, Vector2<f64>),
        (alpha_in, gamma_in, e_in): (f64, Vector3<f64>, Vector2<f64>),
        h: f64,
    ) -> Self {
        let m = Matrix2::from_columns(&[e_out, e_in]);
        let inv = m
            .try_inverse()
            .expect("the sides of a corner are not parallel");
        let (a, b) = (
            gamma_out * (2.0 * alpha_out / h),
            gamma_in * (2.0 * alpha_in / h),
        );
        VertexFrame {
            point,
            dx: a * inv[(0, 0)] + b * inv[(1, 0)],
            dy: a * inv[(0, 1)] + b * inv[(1, 1)],
        }
    }

    /// α γ = (h/2) A e for an edge of length h in direction e.
    pub fn alpha_gamma(&self, e: Vector2<f64>, h: f64) -> Vector3<f64> {
        self.along(e) * (0.5 * h)
    }

    /// β δ = (√3 h/4) A(−e⊥) for an edge of length h in direction e.
    pub fn beta_delta(&self, e: Vector2<f64>, h: f64) -> Vector3<f64> {
        self.along(-inward(e)) * (0.5 * SQRT3_2 * h)
    }
}

/// q_{i,j} = 4 p_{i,j} − 2 (p_i + p_j) of (5.16).
pub fn q(p_i: Vector3<f64>, p_mid: Vector3<f64>, p_j: Vector3<f64>) -> Vector3<f64> {
    p_mid * 4.0 - (p_i + p_j) * 2.0
}

/// The residual ‖q_{i,j} − α_i γ_i + α_j γ_j‖ of (5.16) (four times the distance between
/// the patch's edge curve and the given point at the middle of the edge).
pub fn residual(q: Vector3<f64>, ag_i: Vector3<f64>, ag_j: Vector3<f64>) -> f64 {
    (q - ag_i + ag_j).norm()
}

/// α_k, the least-squares solution of (5.23): ½ γ_k · (α_i γ_i + α_j γ_j + q_{k,j} − q_{i,k}).
/// (The extracted (5.24) prints −α_j γ_j: minimising the two residuals gives +, and only +
/// reproduces a straight line, where q = 0 and α_k = (α_i + α_j)/2.)
pub fn alpha_mid(
    gamma_k: Vector3<f64>,
    ag_i: Vector3<f64>,
    ag_j: Vector3<f64>,
    q_ik: Vector3<f64>,
    q_kj: Vector3<f64>,
) -> f64 {
    0.5 * gamma_k.dot(&(ag_i + ag_j + q_kj - q_ik))
}

/// Denominators of (5.26) below this (the δ's agree to about 1e-7 rad): use (5.27).
pub const FLAT_DELTA: f64 = 1e-14;

/// β_k from (5.25)–(5.26): the least-squares fit of the cross-boundary directions δ_{i,k}
/// and δ_{k,j} at the quarter points, given β_i δ_i and β_j δ_j (as vectors, so that corner
/// vertices need not have their β's projected by (5.14)–(5.15)). Projections are formed
/// directly, which keeps the small denominator accurate. Falls back to (5.27),
/// ½ δ_k · (β_i δ_i + β_j δ_j), when the δ's all agree (a plane cut) and the fit has no
/// unique solution. Returns β and whether the fall-back was used.
pub fn beta_mid(
    delta_k: Vector3<f64>,
    bd_i: Vector3<f64>,
    bd_j: Vector3<f64>,
    delta_ik: Vector3<f64>,
    delta_kj: Vector3<f64>,
) -> (f64, bool) {
    let perp = |d: Vector3<f64>, v: Vector3<f64>| v - d * d.dot(&v);
    let (pk1, pk2) = (perp(delta_ik, delta_k), perp(delta_kj, delta_k));
    let den = pk1.norm_squared() + pk2.norm_squared();
    let sub = beta_by_subdivision(delta_k, bd_i, bd_j);
    if den < FLAT_DELTA {
        return (sub, true);
    }
    let num = pk1.dot(&perp(delta_ik, bd_i)) + pk2.dot(&perp(delta_kj, bd_j));
    (-num / den, false)
}

/// (5.27): β_k = ½ δ_k · (β_i δ_i + β_j δ_j), the β that subdivision gives.
pub fn beta_by_subdivision(delta_k: Vector3<f64>, bd_i: Vector3<f64>, bd_j: Vector3<f64>) -> f64 {
    0.5 * delta_k.dot(&(bd_i + bd_j))
}

/// The weight of the ridge (α − α_prior)² in [`refit_alphas`], against fitting equations
/// whose coefficients are unit vectors. It only decides what (5.16) leaves open: along a
/// straight run the γ's are parallel and (5.16) fixes the differences of the α's, not their
/// common part.
pub const REFIT_RIDGE: f64 = 1e-9;

/// The α's of the vertices 0..=N of a run of N boundary edges, fitted together: the
/// least-squares solution of α_m γ_m − α_{m+1} γ_{m+1} = q_m (5.16) for every edge m, the
/// system (5.19)–(5.20) and (5.23) of the initial solution, at the current level, plus
/// [`REFIT_RIDGE`] (α_m − prior_m)². Vertices marked `fixed` keep their prior. The normal
/// equations are tridiagonal and strictly diagonally dominant (|γ_m · γ_{m+1}| ≤ 1), solved
/// by the Thomas algorithm in O(N). `None` when an α is not positive or not finite.
pub fn refit_alphas(
    gammas: &[Vector3<f64>],
    qs: &[Vector3<f64>],
    prior: &[f64],
    fixed: &[bool],
) -> Option<Vec<f64>> {
    let n = gammas.len();
    debug_assert!(n >= 2 && qs.len() + 1 == n && prior.len() == n && fixed.len() == n);
    // Row m: off[m − 1] α_{m−1} + diag[m] α_m + off[m] α_{m+1} = rhs[m].
    let mut diag = vec![REFIT_RIDGE; n];
    let mut off = vec![0.0; n - 1];
    let mut rhs: Vec<f64> = prior.iter().map(|a| REFIT_RIDGE * a).collect();
    for m in 0..n - 1 {
        diag[m] += 1.0;
        diag[m + 1] += 1.0;
        off[m] = -gammas[m].dot(&gammas[m + 1]);
        rhs[m] += gammas[m].dot(&qs[m]);
        rhs[m + 1] -= gammas[m + 1].dot(&qs[m]);
    }
    for m in 0..n {
        if fixed[m] {
            diag[m] = 1.0;
            rhs[m] = prior[m];
            if m > 0 {
                rhs[m - 1] -= off[m - 1] * prior[m];
                off[m - 1] = 0.0;
            }
            if m + 1 < n {
                rhs[m + 1] -= off[m] * prior[m];
                off[m] = 0.0;
            }
        }
    }
    let (mut c, mut d) = (vec![0.0; n], vec![0.0; n]);
    for m in 0..n {
        let (lower, c_prev, d_prev) = if m > 0 {
            (off[m - 1], c[m - 1], d[m - 1])
        } else {
            (0.0, 0.0, 0.0)
        };
        let pivot = diag[m] - lower * c_prev;
        if !(pivot > 0.0) {
            return None;
        }
        c[m] = if m + 1 < n { off[m] / pivot } else { 0.0 };
        d[m] = (rhs[m] - lower * d_prev) / pivot;
    }
    let mut alphas = d;
    for m in (0..n - 1).rev() {
        alphas[m] -= c[m] * alphas[m + 1];
    }
    alphas
        .iter()
        .all(|a| a.is_finite() && *a > 0.0)
        .then_some(alphas)
}

/// The initial α's along one side of the coarse domain, split into `gammas.len() − 1` steps
/// (1, or 2 for the long sides of the pentagon): the least-squares solution of
/// α_m γ_m − α_{m+1} γ_{m+1} = q_m (5.16), (5.19)–(5.20), or of (5.23) for two steps.
/// When the system is singular (γ's parallel, D = 1 − (γ_i·γ_j)² ≈ 0) or gives an α ≤ 0,
/// every step gets α = ½ ‖p_{m+1} − p_m‖ (5.22) instead. Returns the α's and whether the
/// fall-back was used.
pub fn initial_alphas(
    points: &[Vector3<f64>],
    gammas: &[Vector3<f64>],
    qs: &[Vector3<f64>],
) -> (Vec<f64>, bool) {
    let n = gammas.len();
    debug_assert!(points.len() == n && qs.len() == n - 1);
    let mut m = nalgebra::DMatrix::<f64>::zeros(n, n);
    let mut rhs = nalgebra::DVector::<f64>::zeros(n);
    for k in 0..n - 1 {
        let g = gammas[k].dot(&gammas[k + 1]);
        m[(k, k)] += 1.0;
        m[(k + 1, k + 1)] += 1.0;
        m[(k, k + 1)] -= g;
        m[(k + 1, k)] -= g;
        rhs[k] += gammas[k].dot(&qs[k]);
        rhs[k + 1] -= gammas[k + 1].dot(&qs[k]);
    }
    // For one step det = D of (5.19); the same bound for two steps.
    let solved = (m.determinant() > 1e-8)
        .then(|| m.lu().solve(&rhs))
        .flatten()
        .map(|a| a.iter().copied().collect::<Vec<f64>>())
        .filter(|a| a.iter().all(|&x| x > 0.0 && x.is_finite()));
    match solved {
        Some(a) => (a, false),
        None => {
            let chord: Vec<f64> = (0..n - 1)
                .map(|k| 0.5 * (points[k + 1] - points[k]).norm())
                .collect();
            let a = (0..n)
                .map(|k| match (k.checked_sub(1), chord.get(k)) {
                    (Some(l), Some(&r)) => 0.5 * (chord[l] + r),
                    (Some(l), None) => chord[l],
                    (None, Some(&r)) => r,
                    (None, None) => 0.0,
                })
                .collect();
            (a, true)
        }
    }
}
