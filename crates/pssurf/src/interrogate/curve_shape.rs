//! The shape of a NURBS (or Bézier) curve (issue 20, part 1): arc length to a tolerance and
//! the inflection points of a planar curve.

use nalgebra::Vector3;

use crate::nurbs::NurbsCurve;
use crate::quadrature::gauss_legendre;

/// An arc length and how it was found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcLength {
    /// The length.
    pub length: f64,
    /// The estimated absolute error (the sum of the accepted halvings' differences).
    pub error: f64,
    /// Intervals evaluated.
    pub intervals: usize,
}

/// ∫ |c'(t)| dt by adaptive Gauss–Legendre (8 nodes) on every knot span: an interval is split
/// until the rule on it and on its two halves agree to its share of `tolerance` (absolute).
pub fn arc_length(c: &NurbsCurve, tolerance: f64) -> ArcLength {
    let rule = gauss_legendre(8);
    let speed = |t: f64| c.derivatives(t).map_or(0.0, |d| d[1].norm());
    let gauss = |a: f64, b: f64| -> f64 {
        rule.iter()
            .map(|&(x, w)| w * speed(a + x * (b - a)))
            .sum::<f64>()
            * (b - a)
    };
    let (lo, hi) = c.domain();
    let total = hi - lo;
    let mut out = ArcLength {
        length: 0.0,
        error: 0.0,
        intervals: 0,
    };
    let knots = c.knot_vector().knots();
    for w in knots.windows(2) {
        let (a, b) = (w[0].max(lo), w[1].min(hi));
        if b <= a {
            continue;
        }
        // Depth-first with an explicit stack; at most 50 halvings of any span.
        let mut stack = vec![(a, b, gauss(a, b), 0u32)];
        while let Some((a, b, whole, depth)) = stack.pop() {
            out.intervals += 1;
            let m = 0.5 * (a + b);
            let (left, right) = (gauss(a, m), gauss(m, b));
            let diff = (left + right - whole).abs();
            if diff <= tolerance * (b - a) / total || depth >= 50 {
                out.length += left + right;
                out.error += diff;
            } else {
                stack.push((a, m, left, depth + 1));
                stack.push((m, b, right, depth + 1));
            }
        }
    }
    out
}

/// `per_span` equally spaced parameters on every non-empty knot span of `c`, and its end.
pub fn span_samples(c: &NurbsCurve, per_span: usize) -> Vec<f64> {
    let (lo, hi) = c.domain();
    let mut params = Vec::new();
    for w in c.knot_vector().knots().windows(2) {
        let (a, b) = (w[0].max(lo), w[1].min(hi));
        if b <= a {
            continue;
        }
        for k in 0..per_span.max(1) {
            params.push(a + (b - a) * k as f64 / per_span.max(1) as f64);
        }
    }
    params.push(hi);
    params
}

/// The parameters where a planar curve's signed curvature (c' × c'') · `normal` changes
/// sign: sign changes on `per_span` samples of every knot span, refined by bisection to the
/// last bit. Zeros that the curvature touches without crossing are not inflections.
pub fn inflections(c: &NurbsCurve, normal: Vector3<f64>, per_span: usize) -> Vec<f64> {
    let signed = |t: f64| {
        c.derivatives(t)
            .map_or(0.0, |d| d[1].cross(&d[2]).dot(&normal))
    };
    let params = span_samples(c, per_span);
    let mut out = Vec::new();
    let mut previous: Option<(f64, f64)> = None;
    for t in params {
        let s = signed(t);
        if s == 0.0 {
            // Exactly zero at a sample: an inflection if the neighbours' signs differ.
            previous = previous.or(Some((t, s)));
            continue;
        }
        if let Some((tp, sp)) = previous {
            if sp == 0.0 {
                if out.last() != Some(&tp) && t > tp {
                    out.push(tp);
                }
            } else if sp.signum() != s.signum() {
                let (mut a, mut b, fa) = (tp, t, sp);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if m == a || m == b {
                        break;
                    }
                    if signed(m).signum() == fa.signum() {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                out.push(0.5 * (a + b));
            }
        }
        previous = Some((t, s));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::*;

    #[test]
    fn arc_lengths_of_circles_and_lines_are_exact_to_the_tolerance() {
        let mut r = rng(2020);
        for _ in 0..10 {
            let radius = uniform(&mut r, 0.1, 10.0);
            let half = uniform(&mut r, 0.1, 1.4);
            let arc = circular_arc(radius, half);
            let a = arc_length(&arc, 1e-13 * radius);
            assert_near!(a.length, 2.0 * half * radius, 1e-12 * radius);
            assert!(a.error <= 1e-12 * radius);
        }
        let line = NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Vector3::zeros(), Vector3::new(3.0, 4.0, 12.0)],
            None,
        )
        .unwrap();
        assert_near!(arc_length(&line, 1e-14).length, 13.0, 1e-13);
    }

    /// The graph of a polynomial of degree 4 on [−1, 1] as a Bézier curve (Bernstein
    /// coefficients by collocation at five points).
    fn quartic_graph(f: impl Fn(f64) -> f64) -> NurbsCurve {
        let xs: Vec<f64> = (0..5).map(|i| -1.0 + 0.5 * i as f64).collect();
        let bern = |i: usize, u: f64| {
            let binom = [1.0, 4.0, 6.0, 4.0, 1.0][i];
            binom * u.powi(i as i32) * (1.0 - u).powi(4 - i as i32)
        };
        let a = nalgebra::DMatrix::from_fn(5, 5, |r, c| bern(c, (xs[r] + 1.0) / 2.0));
        let y = nalgebra::DVector::from_iterator(5, xs.iter().map(|&x| f(x)));
        let b = a.lu().solve(&y).unwrap();
        NurbsCurve::try_new(
            4,
            vec![-1.0; 5].into_iter().chain(vec![1.0; 5]).collect(),
            (0..5).map(|i| Vector3::new(xs[i], b[i], 0.0)).collect(),
            None,
        )
        .unwrap()
    }

    /// y = x³ − x has one inflection, at x = 0; y = x⁴ + x³ (y'' = 6x (2x + 1)) two, at −½
    /// and 0; y = x⁴ (y'' = 12 x²) none: its curvature touches zero without changing sign.
    #[test]
    fn inflections_of_cubics_and_quartics() {
        let cubic = cubic_graph_curve();
        let found = inflections(&cubic, Vector3::z(), 7);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].abs() < 1e-15, "{found:?}");
        let quartic = quartic_graph(|x| x.powi(4) + x.powi(3));
        for x in [-0.7, 0.0, 0.3, 1.0] {
            let p = quartic.point(x).unwrap();
            assert_near!(p.y, x.powi(4) + x.powi(3), 1e-14);
        }
        let found = inflections(&quartic, Vector3::z(), 9);
        assert_eq!(found.len(), 2, "{found:?}");
        assert_near!(found[0], -0.5, 1e-14);
        assert!(found[1].abs() < 1e-14, "{found:?}");
        let flat = quartic_graph(|x| x.powi(4));
        assert!(inflections(&flat, Vector3::z(), 9).is_empty());
    }
}

/// The ranges of curvature κ and torsion τ at the parameters of [`span_samples`] with
/// `per_span` samples per knot span (seed 004: κ = |c′ × c″|/|c′|³,
/// τ = (c′ × c″) · c‴ / |c′ × c″|²); `None` for τ when it is nowhere defined (a straight
/// line).
pub fn curvature_torsion_ranges(c: &NurbsCurve, per_span: usize) -> CurvatureTorsion {
    let mut out = CurvatureTorsion {
        curvature: [f64::INFINITY, f64::NEG_INFINITY],
        torsion: None,
    };
    for t in span_samples(c, per_span) {
        if let Some(k) = c.curvature(t) {
            out.curvature = [out.curvature[0].min(k), out.curvature[1].max(k)];
        }
        if let Some(tau) = c.torsion(t) {
            let r = out.torsion.get_or_insert([tau, tau]);
            *r = [r[0].min(tau), r[1].max(tau)];
        }
    }
    out
}

/// The ranges found by [`curvature_torsion_ranges`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct CurvatureTorsion {
    /// [min, max] of κ.
    pub curvature: [f64; 2],
    /// [min, max] of τ where the curve has an osculating plane.
    pub torsion: Option<[f64; 2]>,
}
