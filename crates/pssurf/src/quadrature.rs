//! Gaussian quadrature on intervals and triangles.

use crate::geometry::{Bary, Triangle2};

/// Gauss–Legendre nodes and weights on [0, 1]: exact for polynomials of degree ≤ 2n − 1.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n > 0, "at least one node");
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        // Newton iteration on P_n from the Chebyshev-like initial guess.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre(n, x);
            dp = d;
            let dx = p / d;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let (_, d) = legendre(n, x);
        dp = if d != 0.0 { d } else { dp };
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((0.5 * (1.0 - x), 0.5 * w));
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    let p = if n == 0 { 1.0 } else { p1 };
    let d = n as f64 * (x * p - p0) / (x * x - 1.0);
    (p, d)
}

/// A quadrature rule on a triangle: barycentric nodes with weights summing to 1 (multiply by
/// the area). Built as a collapsed (Duffy) product of Gauss rules with n nodes per direction,
/// it integrates polynomials of total degree ≤ 2n − 2 exactly.
#[derive(Clone, Debug)]
pub struct TriangleRule {
    /// (barycentric node, weight) pairs; the weights sum to 1.
    pub nodes: Vec<(Bary, f64)>,
}

impl TriangleRule {
    /// The rule that is exact for total degree ≤ `degree`.
    pub fn exact_for(degree: usize) -> Self {
        let n = (degree + 3) / 2;
        let g = gauss_legendre(n);
        let mut nodes = Vec::with_capacity(n * n);
        for &(u, wu) in &g {
            for &(v, wv) in &g {
                let t = [u, (1.0 - u) * v, (1.0 - u) * (1.0 - v)];
                nodes.push((t, 2.0 * wu * wv * (1.0 - u)));
            }
        }
        TriangleRule { nodes }
    }

    /// ∫_T f dA for a function of barycentric coordinates.
    pub fn integrate(&self, tri: &Triangle2, f: impl Fn(Bary) -> f64) -> f64 {
        tri.area() * self.nodes.iter().map(|&(t, w)| w * f(t)).sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point2;

    #[test]
    fn gauss_legendre_integrates_monomials_exactly() {
        for n in 1..12 {
            let g = gauss_legendre(n);
            for k in 0..2 * n {
                let s: f64 = g.iter().map(|&(x, w)| w * x.powi(k as i32)).sum();
                assert!((s - 1.0 / (k + 1) as f64).abs() < 1e-14, "n={n} k={k}");
            }
        }
    }

    #[test]
    fn triangle_rule_matches_the_dirichlet_formula() {
        // ∫_T τ1^a τ2^b τ3^c dA = 2A a! b! c! / (a + b + c + 2)!
        let tri = Triangle2::new(
            Point2::new(0.1, 0.2),
            Point2::new(1.3, 0.1),
            Point2::new(0.4, 2.0),
        );
        let fact = |n: usize| (1..=n).map(|i| i as f64).product::<f64>();
        for deg in 0..10 {
            let rule = TriangleRule::exact_for(deg);
            for a in 0..=deg {
                for b in 0..=deg - a {
                    let c = deg - a - b;
                    let q = rule.integrate(&tri, |t| {
                        t[0].powi(a as i32) * t[1].powi(b as i32) * t[2].powi(c as i32)
                    });
                    let exact = 2.0 * tri.area() * fact(a) * fact(b) * fact(c) / fact(deg + 2);
                    assert!((q - exact).abs() < 1e-14 * exact.max(1e-3), "{a} {b} {c}");
                }
            }
        }
    }
}
