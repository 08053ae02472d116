//! The Bézier net of a PS-spline on one triangle of Δ: 19 ordinates on its six sub-triangles
//! (thesis (2.54)–(2.60), stable rational form (3.44)–(3.63)).
//!
//! For a triangle (V_0, V_1, V_2) with edge points R_c on edge c (V_c → V_{c+1}) and interior
//! point Z, the ordinates sit at these domain points (the figure lost in the extraction,
//! re-derived):
//!
//! ```text
//! s_c = S(c)   at V_c                       (2.54)
//! u_c = U(c)   at (V_c + R_c)/2             (2.55)  next to V_c along edge c
//! v_c = V(c)   at (V_c + R_{c−1})/2         (2.56)  next to V_c along edge c − 1
//! w_c = W(c)   at (V_c + Z)/2               (2.57)
//! r_c = R(c)   at R_c                       (2.58)  r = λ_c u_c + (1 − λ_c) v_{c+1}
//! θ_c = TH(c)  at (R_c + Z)/2               (2.59)  θ = λ_c w_c + (1 − λ_c) w_{c+1}
//! ω   = OM     at Z                         (2.60)  ω = a_0 w_0 + a_1 w_1 + a_2 w_2
//! ```
//!
//! The ordinates next to V_c (s, u, v, w) are values of the control triangle's plane at
//! those points: their coefficients are the barycentric coordinates of the point w.r.t. the
//! PS-triangle t_i (Property 2.3 / Theorem 2.5: the control triangle is the tangent plane).
//! The others follow from C¹ continuity across the interior edges of Δ*.

use crate::vector::Vector;

/// Number of ordinates per triangle.
pub const NET_LEN: usize = 19;

/// Index of s_c (at V_c).
pub const fn s(c: usize) -> usize {
    c
}
/// Index of u_c (at (V_c + R_c)/2).
pub const fn u(c: usize) -> usize {
    3 + c
}
/// Index of v_c (at (V_c + R_{c−1})/2).
pub const fn v(c: usize) -> usize {
    6 + c
}
/// Index of w_c (at (V_c + Z)/2).
pub const fn w(c: usize) -> usize {
    9 + c
}
/// Index of r_c (at R_c).
pub const fn r(c: usize) -> usize {
    12 + c
}
/// Index of θ_c (at (R_c + Z)/2).
pub const fn th(c: usize) -> usize {
    15 + c
}
/// Index of ω (at Z).
pub const OM: usize = 18;

/// For each of the six sub-triangles (V_c, R_c, Z), (R_c, V_{c+1}, Z), c = 0, 1, 2, the
/// positions of its six quadratic ordinates in the order b200, b110, b101, b020, b011, b002.
pub const SUB_ORDINATES: [[usize; 6]; 6] = [
    [s(0), u(0), w(0), r(0), th(0), OM],
    [r(0), v(1), th(0), s(1), w(1), OM],
    [s(1), u(1), w(1), r(1), th(1), OM],
    [r(1), v(2), th(1), s(2), w(2), OM],
    [s(2), u(2), w(2), r(2), th(2), OM],
    [r(2), v(0), th(2), s(0), w(0), OM],
];

/// Values that can be combined with convex (or affine) weights: plain vectors, or weighted
/// points combined projectively (the stable rational scheme of section 3.3.2).
pub trait Combine: Copy + Send + Sync + 'static {
    /// Σ c_i p_i for polynomial values; for weighted points, the weight Σ c_i w_i and the
    /// point Σ (c_i w_i / w) p_i (3.49)–(3.54), a convex combination when c ≥ 0.
    fn combine3(c: [f64; 3], p: [Self; 3]) -> Self;
    /// The two-term version, (3.58)–(3.62).
    fn combine2(c: [f64; 2], p: [Self; 2]) -> Self;
    /// Any number of terms (`c` and `p` of equal length, at least one).
    fn combine(c: &[f64], p: &[Self]) -> Self;
}

impl<V: Vector> Combine for V {
    #[inline]
    fn combine3(c: [f64; 3], p: [Self; 3]) -> Self {
        p[0] * c[0] + p[1] * c[1] + p[2] * c[2]
    }
    #[inline]
    fn combine2(c: [f64; 2], p: [Self; 2]) -> Self {
        p[0] * c[0] + p[1] * c[1]
    }
    #[inline]
    fn combine(c: &[f64], p: &[Self]) -> Self {
        crate::vector::combine(c, p)
    }
}

/// A point with a positive weight, combined projectively.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weighted<V> {
    /// The (Euclidean) point.
    pub point: V,
    /// Its weight (> 0).
    pub weight: f64,
}

impl<V: Vector> Combine for Weighted<V> {
    #[inline]
    fn combine3(c: [f64; 3], p: [Self; 3]) -> Self {
        let a = [c[0] * p[0].weight, c[1] * p[1].weight, c[2] * p[2].weight];
        let weight = a[0] + a[1] + a[2];
        let point = p[0].point * (a[0] / weight)
            + p[1].point * (a[1] / weight)
            + p[2].point * (a[2] / weight);
        Weighted { point, weight }
    }
    #[inline]
    fn combine2(c: [f64; 2], p: [Self; 2]) -> Self {
        let a = [c[0] * p[0].weight, c[1] * p[1].weight];
        let weight = a[0] + a[1];
        let point = p[0].point * (a[0] / weight) + p[1].point * (a[1] / weight);
        Weighted { point, weight }
    }
    fn combine(c: &[f64], p: &[Self]) -> Self {
        let weight: f64 = c.iter().zip(p).map(|(c, p)| c * p.weight).sum();
        let mut point = V::zero();
        for (c, q) in c.iter().zip(p) {
            point += q.point * (c * q.weight / weight);
        }
        Weighted { point, weight }
    }
}

/// The coefficients that turn a triangle's control values into its Bézier net: for each
/// corner c, the rows (α, L, L', L'') giving s_c, u_c, v_c, w_c from the three control values
/// of the corner's vertex; λ for the three edges and (a_0, a_1, a_2) for Z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NetStencil {
    /// `rows[c]` = barycentric coordinates w.r.t. t_{V_c} of V_c, (V_c + R_c)/2,
    /// (V_c + R_{c−1})/2 and (V_c + Z)/2.
    pub rows: [[[f64; 3]; 4]; 3],
    /// λ_c of each edge.
    pub lambda: [f64; 3],
    /// Barycentric coordinates of Z.
    pub z: [f64; 3],
}

impl NetStencil {
    /// The 19 ordinates from the control values `ctrl[c]` of the three corners' vertices.
    pub fn apply<T: Combine>(&self, ctrl: [[T; 3]; 3]) -> [T; NET_LEN] {
        let rows = &self.rows;
        let corners = std::array::from_fn(|c| rows[c].map(|weights| T::combine3(weights, ctrl[c])));
        complete_net(corners, self.lambda, self.z)
    }

    /// The transpose of [`apply`](Self::apply): the coefficients `k[c][j]` of the control
    /// values such that Σ_m `weights[m]` × ordinate_m = Σ_{c,j} `k[c][j]` × ctrl\[c\]\[j\]
    /// (for linear functionals of the net: integrals, point values, derivatives).
    pub fn transpose(&self, weights: [f64; NET_LEN]) -> [[f64; 3]; 3] {
        let mut wv = weights;
        // ω, θ and r depend on w, u, v: distribute their weights first.
        for c in 0..3 {
            wv[w(c)] += wv[OM] * self.z[c];
        }
        for c in 0..3 {
            let d = (c + 1) % 3;
            let l = self.lambda[c];
            wv[u(c)] += wv[r(c)] * l;
            wv[v(d)] += wv[r(c)] * (1.0 - l);
            wv[w(c)] += wv[th(c)] * l;
            wv[w(d)] += wv[th(c)] * (1.0 - l);
        }
        let mut out = [[0.0; 3]; 3];
        for c in 0..3 {
            let idx = [s(c), u(c), v(c), w(c)];
            for (row, &k) in self.rows[c].iter().zip(&idx) {
                for j in 0..3 {
                    out[c][j] += wv[k] * row[j];
                }
            }
        }
        out
    }
}

/// The whole net from the four ordinates at each corner c (at V_c and the midpoints of
/// V_c R_c, V_c R_{c−1} and V_c Z, in the order of [`NetStencil::rows`]), λ of the edges and
/// Z's barycentric coordinates: the ordinates at the edge points and around Z follow from
/// C¹ continuity ((2.54)–(2.60)).
pub fn complete_net<T: Combine>(
    corners: [[T; 4]; 3],
    lambda: [f64; 3],
    z: [f64; 3],
) -> [T; NET_LEN] {
    let mut n = [corners[0][0]; NET_LEN];
    for (c, [at_s, at_u, at_v, at_w]) in corners.into_iter().enumerate() {
        n[s(c)] = at_s;
        n[u(c)] = at_u;
        n[v(c)] = at_v;
        n[w(c)] = at_w;
    }
    for c in 0..3 {
        let d = (c + 1) % 3;
        let l = lambda[c];
        n[r(c)] = T::combine2([l, 1.0 - l], [n[u(c)], n[v(d)]]);
        n[th(c)] = T::combine2([l, 1.0 - l], [n[w(c)], n[w(d)]]);
    }
    n[OM] = T::combine3(z, [n[w(0)], n[w(1)], n[w(2)]]);
    n
}
