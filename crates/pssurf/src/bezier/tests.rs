//! Randomized tests of the Bézier machinery against closed forms.
//!
//! A polynomial f = Σ_k c_k ℓ_k^m, with ℓ_k(x, y) = a_k x + b_k y + e_k linear, has the exact
//! Bézier ordinates b_λ = Σ_k c_k Π_i ℓ_k(V_i)^{λ_i} (the blossom of a power of a linear form
//! is a product of its values), and exact derivatives by the chain rule. Such sums span all
//! polynomials of degree m, so they test everything without trusting de Casteljau.

use nalgebra::{Point2, Vector2, Vector3};
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

use super::curve::{ParamCurve, torsion};
use super::index::{bernstein, falling_factorial, index, multi_indices, multinomial};
use super::*;
use crate::geometry::{Triangle2, bary_direction};
use crate::quadrature::TriangleRule;
use crate::test_util::*;

#[derive(Clone, Debug)]
struct PowerSum {
    m: usize,
    terms: Vec<(f64, f64, f64, f64)>,
}

impl PowerSum {
    fn random(rng: &mut rand_chacha::ChaCha8Rng, m: usize) -> Self {
        let terms = (0..4)
            .map(|_| {
                (
                    uniform(rng, -1.0, 1.0),
                    uniform(rng, -1.0, 1.0),
                    uniform(rng, -1.0, 1.0),
                    uniform(rng, -1.0, 1.0),
                )
            })
            .collect();
        PowerSum { m, terms }
    }
    fn ell(t: &(f64, f64, f64, f64), p: Point2<f64>) -> f64 {
        t.1 * p.x + t.2 * p.y + t.3
    }
    fn pow(x: f64, k: i64) -> f64 {
        if k < 0 { 0.0 } else { x.powi(k as i32) }
    }
    fn patch(&self, tri: Triangle2) -> BezierTriangle<f64> {
        let pts = multi_indices(self.m)
            .map(|l| {
                self.terms
                    .iter()
                    .map(|t| {
                        t.0 * (0..3)
                            .map(|i| Self::ell(t, tri.v[i]).powi(l[i] as i32))
                            .product::<f64>()
                    })
                    .sum()
            })
            .collect();
        BezierTriangle::new(tri, self.m, pts)
    }
    /// D_{v_1} ⋯ D_{v_r} f(p) for Cartesian directions.
    fn derivative(&self, p: Point2<f64>, dirs: &[Vector2<f64>]) -> f64 {
        let m = self.m as i64;
        let r = dirs.len();
        self.terms
            .iter()
            .map(|t| {
                let slope: f64 = dirs.iter().map(|v| t.1 * v.x + t.2 * v.y).product();
                t.0 * falling_factorial(self.m, r.min(self.m))
                    * slope
                    * if r > self.m {
                        0.0
                    } else {
                        Self::pow(Self::ell(t, p), m - r as i64)
                    }
            })
            .sum()
    }
    /// The forward-error scale of an order-r derivative computed by de Casteljau on `tri`:
    /// m!/(m−r)! ‖d‖₁^r max|b_λ|, bounding what the algorithm combines (the sum may cancel,
    /// the terms do not). Evaluation points outside the triangle enlarge the bound.
    fn scale_on(&self, tri: &Triangle2, p: Point2<f64>, r: usize) -> f64 {
        if r > self.m {
            return 1.0;
        }
        let map = tri.bary_map().unwrap();
        let d1 = |d: [f64; 3]| d.iter().map(|x| x.abs()).sum::<f64>();
        let g = d1(map.dx()).max(d1(map.dy())).max(1.0);
        let t = map.apply(p);
        let ext = d1(t).max(1.0).powi(self.m as i32);
        let b: f64 = self
            .terms
            .iter()
            .map(|t| {
                let l = (0..3)
                    .map(|i| Self::ell(t, tri.v[i]).abs())
                    .fold(0.0, f64::max);
                t.0.abs() * l.powi(self.m as i32)
            })
            .sum();
        (falling_factorial(self.m, r) * g.powi(r as i32) * b * ext).max(1.0)
    }
    fn jet(&self, p: Point2<f64>) -> Jet<f64> {
        let (ex, ey) = (Vector2::x(), Vector2::y());
        Jet {
            value: self.derivative(p, &[]),
            dx: self.derivative(p, &[ex]),
            dy: self.derivative(p, &[ey]),
            dxx: self.derivative(p, &[ex, ex]),
            dxy: self.derivative(p, &[ex, ey]),
            dyy: self.derivative(p, &[ey, ey]),
        }
    }
}

/// |a − b| ≤ tol · scale, with a message.
fn assert_close(a: f64, b: f64, scale: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * scale,
        "{what}: {a:e} vs {b:e} (diff {:e}, scale {scale:e})",
        (a - b).abs()
    );
}

fn assert_jet_close(
    a: &Jet<f64>,
    f: &PowerSum,
    tri: &Triangle2,
    p: Point2<f64>,
    tol: f64,
    what: &str,
) {
    let b = f.jet(p);
    let (s0, s1, s2) = (
        f.scale_on(tri, p, 0),
        f.scale_on(tri, p, 1),
        f.scale_on(tri, p, 2),
    );
    assert_close(a.value, b.value, s0, tol, &format!("value {what}"));
    assert_close(a.dx, b.dx, s1, tol, &format!("dx {what}"));
    assert_close(a.dy, b.dy, s1, tol, &format!("dy {what}"));
    assert_close(a.dxx, b.dxx, s2, tol, &format!("dxx {what}"));
    assert_close(a.dxy, b.dxy, s2, tol, &format!("dxy {what}"));
    assert_close(a.dyy, b.dyy, s2, tol, &format!("dyy {what}"));
}

#[test]
fn de_casteljau_and_jet_match_the_closed_form() {
    let mut r = rng(1);
    for m in 0..=8 {
        for _ in 0..20 {
            let tri = random_triangle(&mut r);
            let f = PowerSum::random(&mut r, m);
            let patch = f.patch(tri);
            for _ in 0..10 {
                // Inside, and (extrapolating) up to one triangle-size outside.
                let t = random_bary(&mut r);
                let s = uniform(&mut r, 0.0, 2.0);
                let t = [
                    s * t[0] + (1.0 - s) / 3.0,
                    s * t[1] + (1.0 - s) / 3.0,
                    s * t[2] + (1.0 - s) / 3.0,
                ];
                let p = tri.point(t);
                // The Bernstein sum (2.9) itself.
                let direct: f64 = multi_indices(m)
                    .map(|l| patch.ordinate(l) * bernstein(l, t))
                    .sum();
                let s = f.scale_on(&tri, p, 0);
                assert_close(
                    patch.eval(p),
                    f.derivative(p, &[]),
                    s,
                    1e-14,
                    &format!("m={m}"),
                );
                assert_close(direct, f.derivative(p, &[]), s, 1e-14, &format!("m={m}"));
                assert_jet_close(&patch.jet(p), &f, &tri, p, 1e-14, &format!("m={m}"));
            }
        }
    }
}

#[test]
fn directional_derivatives_of_any_order_match_theorem_2_3() {
    let mut r = rng(2);
    for m in 0..=7 {
        let tri = random_triangle(&mut r);
        let f = PowerSum::random(&mut r, m);
        let patch = f.patch(tri);
        for order in 0..=m + 1 {
            let t = random_bary(&mut r);
            let p = tri.point(t);
            let v = random_dir(&mut r) * uniform(&mut r, 0.5, 2.0);
            let d = bary_direction(patch.bary_map(), v);
            assert!(d.iter().sum::<f64>().abs() < 1e-14);
            let got = patch.directional_derivative(t, d, order);
            let want = f.derivative(p, &vec![v; order]);
            let s = f.scale_on(&tri, p, order) * 2f64.powi(order as i32);
            assert_close(got, want, s, 1e-14, &format!("m={m} r={order}"));
            // Mixed derivatives with distinct directions.
            let dirs: Vec<_> = (0..order).map(|_| random_dir(&mut r)).collect();
            let bdirs: Vec<_> = dirs
                .iter()
                .map(|v| bary_direction(patch.bary_map(), *v))
                .collect();
            assert_close(
                patch.derivative(t, &bdirs),
                f.derivative(p, &dirs),
                f.scale_on(&tri, p, order),
                1e-14,
                "mixed",
            );
        }
    }
}

#[test]
fn subdivision_and_restriction_leave_the_polynomial_unchanged() {
    let mut r = rng(3);
    for m in 0..=6 {
        for _ in 0..5 {
            let tri = random_triangle(&mut r);
            let f = PowerSum::random(&mut r, m);
            let patch = f.patch(tri);
            let inner = tri.point(random_bary(&mut r));
            let pieces = patch.subdivide_at(inner).unwrap();
            let quarters = patch.subdivide_mid_edge();
            let far = random_triangle(&mut r);
            let moved = patch.restrict(far).unwrap();
            for piece in pieces.iter().chain(quarters.iter()).chain([&moved]) {
                assert_eq!(piece.degree(), m);
                for _ in 0..5 {
                    let p = piece.domain().point(random_bary(&mut r));
                    // The pieces' nets come from the original one, which bounds the error.
                    let s = f.scale_on(&tri, p, 0).max(f.scale_on(piece.domain(), p, 0));
                    assert_close(piece.eval(p), patch.eval(p), s, 1e-14, &format!("m={m}"));
                    assert_close(piece.eval(p), f.derivative(p, &[]), s, 1e-14, "closed form");
                }
            }
            // Corollary 2.1: the piece over (V̂, V2, V3) has b̂_{0,λ2,λ3} = b_{0,λ2,λ3}.
            for l in multi_indices(m).filter(|l| l[0] == 0) {
                assert_eq!(pieces[0].ordinate(l), patch.ordinate(l));
            }
            let elevated = patch.elevate();
            let p = tri.point(random_bary(&mut r));
            assert_close(
                elevated.eval(p),
                patch.eval(p),
                f.scale_on(&tri, p, 0),
                1e-14,
                "elevated",
            );
        }
    }
    let patch = PowerSum::random(&mut r, 2).patch(random_triangle(&mut r));
    let outside = patch.domain().point([1.5, -0.25, -0.25]);
    assert_eq!(
        patch.subdivide_at(outside).unwrap_err(),
        BezierError::OutsideDomain
    );
}

#[test]
fn integral_2_21_matches_gaussian_quadrature() {
    let mut r = rng(4);
    for m in 0..=9 {
        let tri = random_triangle(&mut r);
        let f = PowerSum::random(&mut r, m);
        let patch = f.patch(tri);
        let q = TriangleRule::exact_for(m).integrate(&tri, |t| f.derivative(tri.point(t), &[]));
        assert_near!(patch.integral(), q, 1e-12, "m={m}");
    }
}

#[test]
fn continuity_test_finds_the_exact_order_corollary_2_2() {
    let mut r = rng(5);
    for m in 1..=6 {
        let tri = random_triangle(&mut r);
        // The neighbour across V2V3: reflect V1 through the edge's midpoint.
        let mid = crate::geometry::midpoint(tri.v[1], tri.v[2]);
        let apex = mid + (mid - tri.v[0]) * uniform(&mut r, 0.5, 1.5);
        let nb = Triangle2::new(tri.v[2], tri.v[1], apex);
        let f = PowerSum::random(&mut r, m);
        let a = f.patch(tri);
        let b = f.patch(nb);
        let c = continuity(&a, &b, 1e-11).unwrap();
        assert_eq!(c.order, Some(m), "same polynomial must be C^m (m={m})");
        for k in 0..=m {
            // Perturb one ordinate whose apex exponent is k: the order drops to k − 1.
            let mut bad = b.clone();
            let l = multi_indices(m).find(|l| l[2] == k).unwrap();
            let size = b.points().iter().fold(1.0, |a: f64, x| a.max(x.abs()));
            bad.points_mut()[index(l)] += 1e-3 * size;
            let c = continuity(&a, &bad, 1e-11).unwrap();
            assert_eq!(c.order, k.checked_sub(1), "m={m} k={k}");
        }
    }
}

fn random_rational(
    r: &mut rand_chacha::ChaCha8Rng,
    m: usize,
    wmax: f64,
) -> RationalBezierTriangle<Vector3<f64>> {
    let tri = random_triangle(r);
    let pts = (0..multi_indices(m).count())
        .map(|_| {
            Vector3::new(
                uniform(r, -1.0, 1.0),
                uniform(r, -1.0, 1.0),
                uniform(r, -1.0, 1.0),
            )
        })
        .collect();
    let w = (0..multi_indices(m).count())
        .map(|_| wmax.powf(uniform(r, 0.0, 1.0)))
        .collect();
    RationalBezierTriangle::new(tri, m, pts, w)
}

#[test]
fn rational_with_equal_weights_is_the_polynomial_patch() {
    let mut r = rng(6);
    for m in 0..=6 {
        let rat = random_rational(&mut r, m, 1.0);
        let scaled = RationalBezierTriangle::new(
            *rat.domain(),
            m,
            rat.points().to_vec(),
            vec![3.7; rat.points().len()],
        );
        let poly = BezierTriangle::new(*rat.domain(), m, rat.points().to_vec());
        for _ in 0..10 {
            let t = random_bary(&mut r);
            let p = rat.domain().point(t);
            assert!((scaled.eval(p).unwrap() - poly.eval(p)).norm() < 1e-14);
            let (a, b) = (scaled.jet(p).unwrap(), poly.jet(p));
            assert!(a.max_diff(&b) < 1e-12 * (1.0 + b.value.norm()), "m={m}");
            let d = bary_direction(&rat.domain().bary_map().unwrap(), random_dir(&mut r));
            for k in 0..=m + 1 {
                let a = scaled.directional_derivative(t, d, k).unwrap();
                let b = poly.directional_derivative(t, d, k);
                let scale: f64 = (0..=k)
                    .map(|j| poly.directional_derivative(t, d, j).norm())
                    .fold(1.0, f64::max);
                assert!((a - b).norm() < 1e-13 * scale, "m={m} k={k} {a:?} {b:?}");
            }
        }
    }
}

/// The quotient rule on the homogeneous numerator p and denominator w, each differentiated as
/// polynomials: an independent route to the rational derivatives.
fn quotient_jet(rat: &RationalBezierTriangle<Vector3<f64>>, p: Point2<f64>) -> Jet<Vector3<f64>> {
    let n = rat.numerator().jet(p);
    let w = rat.denominator().jet(p);
    let b = n.value / w.value;
    let bx = (n.dx - b * w.dx) / w.value;
    let by = (n.dy - b * w.dy) / w.value;
    Jet {
        value: b,
        dx: bx,
        dy: by,
        dxx: (n.dxx - bx * (2.0 * w.dx) - b * w.dxx) / w.value,
        dxy: (n.dxy - bx * w.dy - by * w.dx - b * w.dxy) / w.value,
        dyy: (n.dyy - by * (2.0 * w.dy) - b * w.dyy) / w.value,
    }
}

#[test]
fn rational_derivatives_match_the_quotient_rule() {
    let mut r = rng(7);
    for m in 0..=6 {
        for _ in 0..10 {
            let rat = random_rational(&mut r, m, 10.0);
            let t = random_bary(&mut r);
            let p = rat.domain().point(t);
            let a = rat.jet(p).unwrap();
            let b = quotient_jet(&rat, p);
            let scale = 1.0 + b.dxx.norm() + b.dyy.norm() + b.dxy.norm();
            assert!(a.max_diff(&b) < 1e-11 * scale, "m={m}: {a:?} vs {b:?}");
            // Higher directional derivatives: Leibniz on the homogeneous pair.
            let v = random_dir(&mut r);
            let d = bary_direction(&rat.domain().bary_map().unwrap(), v);
            let num = rat.numerator();
            let den = rat.denominator();
            let mut ders: Vec<Vector3<f64>> = vec![];
            let w0 = den.eval_bary(t);
            for k in 0..=4 {
                let mut v = num.directional_derivative(t, d, k);
                for j in 1..=k {
                    v -= ders[k - j]
                        * (super::index::binomial(k, j) * den.directional_derivative(t, d, j));
                }
                ders.push(v / w0);
                let got = rat.directional_derivative(t, d, k).unwrap();
                assert!(
                    (got - ders[k]).norm() < 1e-10 * (1.0 + ders[k].norm()),
                    "m={m} k={k}"
                );
            }
        }
    }
}

#[test]
fn rational_subdivision_leaves_the_surface_unchanged() {
    let mut r = rng(8);
    for m in 1..=5 {
        let rat = random_rational(&mut r, m, 100.0);
        for piece in rat.subdivide_mid_edge() {
            for _ in 0..5 {
                let p = piece.domain().point(random_bary(&mut r));
                let diff = (piece.eval(p).unwrap() - rat.eval(p).unwrap()).norm();
                assert!(diff < 1e-13, "m={m}: {diff:e}");
            }
        }
    }
}

fn to_big(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

#[test]
fn rational_de_casteljau_is_accurate_for_weights_up_to_1e6() {
    // Exact rational arithmetic on the same f64 inputs is the reference.
    let mut r = rng(9);
    let mut worst: f64 = 0.0;
    for m in 2..=4 {
        for _ in 0..20 {
            let rat = random_rational(&mut r, m, 1e6);
            let t = random_bary(&mut r);
            let t = [t[0], t[1], 1.0 - t[0] - t[1]];
            let got = rat.eval_bary(t).unwrap();
            let bt: Vec<BigRational> = t.iter().map(|&x| to_big(x)).collect();
            let mut num = [
                BigRational::zero(),
                BigRational::zero(),
                BigRational::zero(),
            ];
            let mut den = BigRational::zero();
            for (l, p, w) in rat.iter() {
                let mut b = to_big(multinomial(m, l)) * to_big(w);
                for i in 0..3 {
                    for _ in 0..l[i] {
                        b *= &bt[i];
                    }
                }
                for c in 0..3 {
                    num[c] += &b * to_big(p[c]);
                }
                den += b;
            }
            for c in 0..3 {
                let exact = (&num[c] / &den).to_f64().unwrap();
                worst = worst.max((got[c] - exact).abs());
            }
        }
    }
    assert!(
        worst < 1e-14,
        "worst absolute error {worst:e} (control points in [-1, 1])"
    );
}

fn quarter_circle() -> RationalBezierCurve<Vector2<f64>> {
    RationalBezierCurve::new(
        vec![
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ],
        vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
    )
}

#[test]
fn curves_match_closed_forms() {
    // The twisted cubic (t, t², t³) in Bézier form: κ and τ in closed form.
    let cubic = BezierCurve::new(vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0 / 3.0, 0.0, 0.0),
        Vector3::new(2.0 / 3.0, 1.0 / 3.0, 0.0),
        Vector3::new(1.0, 1.0, 1.0),
    ]);
    let circle = quarter_circle();
    let mut r = rng(10);
    for _ in 0..50 {
        let t = uniform(&mut r, 0.0, 1.0);
        let d = cubic.derivatives(t, 3);
        let exact = [
            Vector3::new(t, t * t, t * t * t),
            Vector3::new(1.0, 2.0 * t, 3.0 * t * t),
            Vector3::new(0.0, 2.0, 6.0 * t),
            Vector3::new(0.0, 0.0, 6.0),
        ];
        for k in 0..4 {
            assert!((d[k] - exact[k]).norm() < 1e-13);
        }
        let c = exact[1].cross(&exact[2]);
        assert_near!(
            cubic.curvature(t).unwrap(),
            c.norm() / exact[1].norm().powi(3),
            1e-13
        );
        assert_near!(
            torsion(&cubic, t).unwrap(),
            12.0 / (36.0 * t.powi(4) + 36.0 * t * t + 4.0),
            1e-12
        );
        // A quarter of the unit circle: on the circle, curvature 1.
        let p = circle.eval(t);
        assert_near!(p.norm(), 1.0, 1e-15);
        assert_near!(circle.curvature(t).unwrap(), 1.0, 1e-13);
        // Its derivatives agree with the quotient rule on the homogeneous form.
        let dd = circle.derivatives(t, 3);
        let h = |k: usize| {
            let num = BezierCurve::new(
                circle
                    .points()
                    .iter()
                    .zip(circle.weights())
                    .map(|(p, w)| p * *w)
                    .collect(),
            );
            let den = BezierCurve::new(circle.weights().to_vec());
            (num.derivatives(t, 3)[k], den.derivatives(t, 3))
        };
        let (n0, w) = h(0);
        let (n1, _) = h(1);
        let (n2, _) = h(2);
        let c0 = n0 / w[0];
        let c1 = (n1 - c0 * w[1]) / w[0];
        let c2 = (n2 - c1 * (2.0 * w[1]) - c0 * w[2]) / w[0];
        assert!((dd[1] - c1).norm() < 1e-13 && (dd[2] - c2).norm() < 1e-12);
    }
    // A straight line has zero curvature and no torsion.
    let line = BezierCurve::new(vec![
        Vector3::zeros(),
        Vector3::new(1.0, 2.0, 3.0),
        Vector3::new(2.0, 4.0, 6.0),
    ]);
    assert_eq!(line.curvature(0.3), Some(0.0));
    assert_eq!(torsion(&line, 0.3), None);
    // A cusp: p'(t) = 0.
    let cusp = BezierCurve::new(vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 1.0),
        Vector2::new(0.0, 0.0),
    ]);
    assert_eq!(cusp.curvature(0.5), None);
}

#[test]
fn curve_subdivision_leaves_the_curve_unchanged() {
    let mut r = rng(11);
    for d in 0..8 {
        let pts: Vec<Vector3<f64>> = (0..=d).map(|_| random_vec3(&mut r)).collect();
        let w: Vec<f64> = (0..=d).map(|_| uniform(&mut r, 0.1, 10.0)).collect();
        let poly = BezierCurve::new(pts.clone());
        let rat = RationalBezierCurve::new(pts, w);
        let split = uniform(&mut r, 0.05, 0.95);
        let (l, rr) = poly.subdivide(split).unwrap();
        let (rl, rrr) = rat.subdivide(split).unwrap();
        for _ in 0..10 {
            let s = uniform(&mut r, 0.0, 1.0);
            assert!((l.eval(s) - poly.eval(s * split)).norm() < 1e-14);
            assert!((rr.eval(s) - poly.eval(split + s * (1.0 - split))).norm() < 1e-14);
            assert!((rl.eval(s) - rat.eval(s * split)).norm() < 1e-14);
            assert!((rrr.eval(s) - rat.eval(split + s * (1.0 - split))).norm() < 1e-14);
            // The hodograph is the derivative.
            let h = poly.hodograph().eval(s);
            assert!((h - poly.derivatives(s, 1)[1]).norm() < 1e-12);
        }
    }
    assert_eq!(
        BezierCurve::new(vec![0.0, 1.0]).subdivide(1.5).unwrap_err(),
        BezierError::ParameterOutOfRange(1.5)
    );
}
