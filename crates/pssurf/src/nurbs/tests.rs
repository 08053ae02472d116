//! The NURBS evaluator against the recursive Cox–de Boor definition (an independent
//! implementation written here), on random rational surfaces with weights from 1e-3 to 1e3,
//! repeated knots and clamped or unclamped ends; exact curvature of a NURBS cylinder.

use nalgebra::{Point2, Vector3};
use rand::RngExt;

use super::*;
use crate::interrogate::Curvature;
use crate::surface::{ParametricSurface, PiecewiseSurface};
use crate::test_util::*;

/// N_{i,p}(t) by the recursion (half-open spans; at the domain's end the last non-empty span
/// is closed), with 0/0 = 0.
fn cox_de_boor(u: &[f64], i: usize, p: usize, t: f64, end: (usize, f64)) -> f64 {
    if p == 0 {
        // The domain's end belongs to the last non-empty span (only).
        if t == end.1 {
            return if i == end.0 { 1.0 } else { 0.0 };
        }
        return if u[i] <= t && t < u[i + 1] { 1.0 } else { 0.0 };
    }
    let a = |num: f64, den: f64| if den == 0.0 { 0.0 } else { num / den };
    a(t - u[i], u[i + p] - u[i]) * cox_de_boor(u, i, p - 1, t, end)
        + a(u[i + p + 1] - t, u[i + p + 1] - u[i + 1]) * cox_de_boor(u, i + 1, p - 1, t, end)
}

/// The k-th derivative of N_{i,p} by recursion on the degree (eq. 2.9 of The NURBS Book).
fn cox_de_boor_d(u: &[f64], i: usize, p: usize, k: usize, t: f64, end: (usize, f64)) -> f64 {
    if k == 0 {
        return cox_de_boor(u, i, p, t, end);
    }
    if p == 0 {
        return 0.0;
    }
    let a = |den: f64| if den == 0.0 { 0.0 } else { p as f64 / den };
    a(u[i + p] - u[i]) * cox_de_boor_d(u, i, p - 1, k - 1, t, end)
        - a(u[i + p + 1] - u[i + 1]) * cox_de_boor_d(u, i + 1, p - 1, k - 1, t, end)
}

/// A random valid knot vector: clamped or not, with repeated interior knots.
fn random_knots(r: &mut rand_chacha::ChaCha8Rng, p: usize, n: usize) -> Vec<f64> {
    loop {
        let clamped = r.random_bool(0.5);
        let mut k: Vec<f64> = Vec::new();
        let mut t = uniform(r, -2.0, 2.0);
        while k.len() < n + p + 1 {
            let times = if clamped && k.is_empty() {
                p + 1
            } else {
                // Interior multiplicity up to p.
                1 + (r.random_range(0..4usize) == 0) as usize * r.random_range(0..p)
            };
            for _ in 0..times.min(n + p + 1 - k.len()) {
                k.push(t);
            }
            t += uniform(r, 0.1, 1.0);
        }
        if clamped {
            let last = k[n];
            for x in &mut k[n..] {
                *x = last;
            }
        }
        if KnotVector::try_new(p, k.clone(), n).is_ok() {
            return k;
        }
    }
}

struct Case {
    s: NurbsSurface,
}

fn random_surface(r: &mut rand_chacha::ChaCha8Rng) -> Case {
    let degree = [r.random_range(1..=5usize), r.random_range(1..=5usize)];
    let counts = [
        degree[0] + 1 + r.random_range(0..6usize),
        degree[1] + 1 + r.random_range(0..6usize),
    ];
    let knots = [
        random_knots(r, degree[0], counts[0]),
        random_knots(r, degree[1], counts[1]),
    ];
    let n = counts[0] * counts[1];
    let points = (0..n).map(|_| random_vec3(r)).collect();
    let weights = (0..n).map(|_| 10f64.powf(uniform(r, -3.0, 3.0))).collect();
    Case {
        s: NurbsSurface::try_new(degree, knots, counts, points, Some(weights)).unwrap(),
    }
}

/// The jet by the oracle: S = A/w with A, w from recursive basis functions.
fn oracle_jet(s: &NurbsSurface, uv: Point2<f64>) -> [Vector3<f64>; 6] {
    let [kv_u, kv_v] = s.knot_vector_refs();
    let end = |kv: &KnotVector| (*kv.spans().last().unwrap(), kv.domain().1);
    let (eu, ev) = (end(kv_u), end(kv_v));
    let [nu, nv] = s.counts();
    let [p, q] = s.degree();
    let orders = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];
    let mut a = [Vector3::zeros(); 6];
    let mut w = [0.0; 6];
    for i in 0..nu {
        for j in 0..nv {
            let (pt, wt) = (s.points()[i * nv + j], s.weights()[i * nv + j]);
            for (k, (du, dv)) in orders.iter().enumerate() {
                let b = cox_de_boor_d(kv_u.knots(), i, p, *du, uv.x, eu)
                    * cox_de_boor_d(kv_v.knots(), j, q, *dv, uv.y, ev);
                a[k] += pt * (b * wt);
                w[k] += b * wt;
            }
        }
    }
    let s0 = a[0] / w[0];
    let su = (a[1] - s0 * w[1]) / w[0];
    let sv = (a[2] - s0 * w[2]) / w[0];
    let suu = (a[3] - su * 2.0 * w[1] - s0 * w[3]) / w[0];
    let suv = (a[4] - su * w[2] - sv * w[1] - s0 * w[4]) / w[0];
    let svv = (a[5] - sv * 2.0 * w[2] - s0 * w[5]) / w[0];
    [s0, su, sv, suu, suv, svv]
}

impl NurbsSurface {
    fn knot_vector_refs(&self) -> [&KnotVector; 2] {
        let k = self.knot_vectors();
        [&k[0], &k[1]]
    }
}

#[test]
fn evaluation_and_derivatives_match_the_recursive_definition() {
    let mut r = rng(1701);
    let (mut worst, mut points) = (0.0f64, 0);
    for _ in 0..60 {
        let case = random_surface(&mut r);
        let s = &case.s;
        let (lo, hi) = s.domain_bounds();
        // Random parameters, and the knots themselves (span ends), domain ends included.
        let mut uvs: Vec<Point2<f64>> = (0..20)
            .map(|_| Point2::new(uniform(&mut r, lo.x, hi.x), uniform(&mut r, lo.y, hi.y)))
            .collect();
        let ku = s.knot_vectors()[0].knots().to_vec();
        let kv = s.knot_vectors()[1].knots().to_vec();
        for (a, b) in ku.iter().zip(kv.iter().rev()) {
            uvs.push(Point2::new(a.clamp(lo.x, hi.x), b.clamp(lo.y, hi.y)));
        }
        for uv in uvs {
            let j = s.jet(uv).unwrap().jet;
            let ours = [j.value, j.dx, j.dy, j.dxx, j.dxy, j.dyy];
            let oracle = oracle_jet(s, uv);
            for (k, (a, b)) in ours.iter().zip(&oracle).enumerate() {
                // Relative to the size of the quantity (and to 1 for small ones).
                let e = (a - b).norm() / b.norm().max(1.0);
                worst = worst.max(e);
                assert!(e < 1e-12, "order {k} at {uv}: {a} vs {b} ({e:e})");
            }
            points += 1;
        }
    }
    eprintln!("{points} points, worst relative error {worst:e}");
}

#[test]
fn pieces_are_the_knot_rectangles_and_extend_as_their_polynomials() {
    let mut r = rng(1702);
    for _ in 0..20 {
        let s = random_surface(&mut r).s;
        let spans = s.knot_vector_refs().map(|k| k.spans().len());
        assert_eq!(s.piece_count(), spans[0] * spans[1]);
        let mut area = 0.0;
        for k in 0..s.piece_count() {
            let shape = s.piece_shape(k);
            area += shape.area();
            let frame = shape.frame().unwrap();
            // The piece's jet at its centre is the surface's there, from the same piece.
            let c = shape.corners();
            let mid = Point2::from((c[0].coords + c[2].coords) * 0.5);
            let sj = s.jet(mid).unwrap();
            assert_eq!(sj.piece, k);
            assert_eq!(s.piece_jet(k, &frame.at_uv(mid)), sj.jet);
        }
        let (lo, hi) = s.domain_bounds();
        assert_near!(area, (hi.x - lo.x) * (hi.y - lo.y), 1e-12);
        // Outside the domain: an error, not an extrapolation.
        assert!(s.jet(Point2::new(hi.x + 1e-9, lo.y)).is_err());
        assert!(s.jet(Point2::new(f64::NAN, lo.y)).is_err());
    }
}

/// A NURBS cylinder of radius `rad` and height 2: the 9-point rational quadratic circle
/// (weights √2/2 at the corners) extruded linearly.
fn cylinder(rad: f64) -> NurbsSurface {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let circle = [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, h),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, h),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, h),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, h),
        (1.0, 0.0, 1.0),
    ];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for (x, y, w) in circle {
        for z in [-1.0, 1.0] {
            points.push(Vector3::new(rad * x, rad * y, z));
            weights.push(w);
        }
    }
    let knots_u = vec![
        0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
    ];
    NurbsSurface::try_new(
        [2, 1],
        [knots_u, vec![0.0, 0.0, 1.0, 1.0]],
        [9, 2],
        points,
        Some(weights),
    )
    .unwrap()
}

#[test]
fn a_nurbs_cylinder_has_the_exact_curvature() {
    let mut r = rng(1703);
    for _ in 0..5 {
        let rad = uniform(&mut r, 0.1, 10.0);
        let s = cylinder(rad);
        for _ in 0..50 {
            let uv = Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0));
            let j = s.jet(uv).unwrap().jet;
            assert_near!(j.value.xy().norm(), rad, 1e-14);
            let c = Curvature::from_jet(&j).unwrap();
            assert!(c.gaussian.abs() < 1e-12 / (rad * rad), "K = {}", c.gaussian);
            assert_near!(c.mean.abs(), 0.5 / rad, 1e-12);
        }
    }
}

#[test]
fn invalid_input_is_refused_with_the_reason() {
    let p = vec![Vector3::zeros(); 4];
    let k = || [vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]];
    let ok = NurbsSurface::try_new([1, 1], k(), [2, 2], p.clone(), None);
    assert!(ok.is_ok());
    let cases: Vec<(Result<NurbsSurface, NurbsError>, &str)> = vec![
        (
            NurbsSurface::try_new([0, 1], k(), [2, 2], p.clone(), None),
            "degree 0",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                [vec![0.0, 1.0, 1.0, 0.5], k()[1].clone()],
                [2, 2],
                p.clone(),
                None,
            ),
            "smaller than the knot before",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                [vec![0.0, 0.0, 1.0], k()[1].clone()],
                [2, 2],
                p.clone(),
                None,
            ),
            "3 knots",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                [vec![0.0, 0.0, 0.0, 0.0], k()[1].clone()],
                [2, 2],
                p.clone(),
                None,
            ),
            "is empty",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                [vec![0.0, f64::NAN, 1.0, 1.0], k()[1].clone()],
                [2, 2],
                p.clone(),
                None,
            ),
            "not a finite",
        ),
        (
            NurbsSurface::try_new([1, 1], k(), [2, 2], p[..3].to_vec(), None),
            "3 control points",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                k(),
                [2, 2],
                p.clone(),
                Some(vec![1.0, 1.0, -1.0, 1.0]),
            ),
            "weight 2",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                k(),
                [2, 2],
                vec![Vector3::new(f64::INFINITY, 0.0, 0.0); 4],
                None,
            ),
            "control point 0",
        ),
        (
            NurbsSurface::try_new(
                [1, 1],
                [vec![0.0, 0.0, 0.5, 0.5, 1.0, 1.0], k()[1].clone()],
                [4, 2],
                vec![Vector3::zeros(); 8],
                None,
            ),
            "repeated 2 times",
        ),
    ];
    for (result, expected) in cases {
        let e = result.unwrap_err().to_string();
        assert!(e.contains(expected), "{e} (expected “{expected}”)");
    }
}

#[test]
fn curves_match_the_recursive_definition() {
    let mut r = rng(1704);
    for _ in 0..40 {
        let p = r.random_range(1..=6usize);
        let n = p + 1 + r.random_range(0..8usize);
        let knots = random_knots(&mut r, p, n);
        let points: Vec<Vector3<f64>> = (0..n).map(|_| random_vec3(&mut r)).collect();
        let weights: Vec<f64> = (0..n)
            .map(|_| 10f64.powf(uniform(&mut r, -3.0, 3.0)))
            .collect();
        let c =
            NurbsCurve::try_new(p, knots.clone(), points.clone(), Some(weights.clone())).unwrap();
        let (lo, hi) = c.domain();
        let end = (*c.knot_vector().spans().last().unwrap(), hi);
        for _ in 0..20 {
            let t = uniform(&mut r, lo, hi);
            let (mut a, mut w) = ([Vector3::zeros(); 3], [0.0; 3]);
            for i in 0..n {
                for k in 0..3 {
                    let b = cox_de_boor_d(&knots, i, p, k, t, end) * weights[i];
                    a[k] += points[i] * b;
                    w[k] += b;
                }
            }
            let c0 = a[0] / w[0];
            let c1 = (a[1] - c0 * w[1]) / w[0];
            let c2 = (a[2] - c1 * 2.0 * w[1] - c0 * w[2]) / w[0];
            let d = c.derivatives(t).unwrap();
            for (x, y) in d.iter().zip([c0, c1, c2]) {
                assert!((x - y).norm() <= 1e-10 * y.norm().max(1.0), "{x} vs {y}");
            }
        }
        assert!(c.point(hi + 1.0).is_none());
    }
}

/// A smooth rational bicubic surface over [0, 3] × [0, 2] (a wavy net, weights 0.5 … 2).
fn wavy_bicubic() -> NurbsSurface {
    let (nu, nv) = (6, 5);
    let ku = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, y) = (i as f64 * 0.6, j as f64 * 0.5);
            points.push(Vector3::new(x, y, 0.4 * (1.3 * x).sin() * (1.1 * y).cos()));
            weights.push(1.0 + 0.5 * ((i + 2 * j) % 3) as f64 - 0.25);
        }
    }
    NurbsSurface::try_new([3, 3], [ku, kv], [nu, nv], points, Some(weights)).unwrap()
}

#[test]
fn the_ups_approximation_interpolates_values_and_derivatives_at_every_vertex() {
    use crate::surface::{Surface, UpsSurface};
    let s = wavy_bicubic();
    let n = [5, 4];
    let ups = approx::ups_of_nurbs(&s, n).unwrap();
    let UpsSurface::Parametric(u) = &ups else {
        panic!("a parametric UPS surface")
    };
    let grid = u.grid().clone();
    let lattice = *grid.lattice();
    let (lo, hi) = s.domain_bounds();
    let (w, h) = (hi.x - lo.x, hi.y - lo.y);
    let surface = Surface::try_from(ups.clone()).unwrap();
    let mut vertices = 0;
    for slot in grid.real_slots() {
        let [i, j] = grid.lattice_point(slot);
        let v = lattice.point([i, j]);
        // θ(V) = (ū₀ + W i/n_u, v̄₀ + H j/n_v): the corners of Ω go to those of R.
        let q = Point2::new(lo.x + w * i as f64 / 5.0, lo.y + h * j as f64 / 4.0);
        let exact = s.jet(q).unwrap().jet;
        let ours = surface.jet(v).unwrap().jet;
        let scale = exact.value.norm().max(1.0);
        assert!(
            (ours.value - exact.value).norm() < 1e-12 * scale,
            "(6.3) at {i}, {j}"
        );
        // (6.4)–(6.5) by the chain rule through θ (lattice base 1).
        let (a11, a12, a22) = (
            w / 5.0,
            -(3f64.sqrt() / 3.0) * w / 5.0,
            2.0 * 3f64.sqrt() / 3.0 * h / 4.0,
        );
        let du = exact.dx * a11;
        let dv = exact.dx * a12 + exact.dy * a22;
        assert!(
            (ours.dx - du).norm() < 1e-11 * du.norm().max(1.0),
            "(6.4) at {i}, {j}"
        );
        assert!(
            (ours.dy - dv).norm() < 1e-11 * dv.norm().max(1.0),
            "(6.5) at {i}, {j}"
        );
        vertices += 1;
    }
    assert_eq!(vertices, 6 * 5);
}

#[test]
fn the_ups_approximation_converges_with_third_order_and_meets_a_tolerance() {
    // A bicubic Bézier patch: doubling n divides the deviation by 8 (third order); with
    // rational weights the ratio approaches 8 from below (higher terms of the quotient).
    let mut points = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            points.push(Vector3::new(i as f64, j as f64, 0.3 * ((i * j) % 3) as f64));
        }
    }
    let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    let rational: Vec<f64> = (0..16).map(|i| 1.0 + 0.3 * (i % 3) as f64).collect();
    for weights in [None, Some(rational)] {
        let is_rational = weights.is_some();
        let b = NurbsSurface::try_new(
            [3, 3],
            [k.clone(), k.clone()],
            [4, 4],
            points.clone(),
            weights,
        )
        .unwrap();
        let dev = |n: usize| {
            let ups = approx::ups_of_nurbs(&b, [n, n]).unwrap();
            approx::deviation(&b, &ups, [n, n], 3).0
        };
        let d: Vec<f64> = [4, 8, 16, 32, 64].iter().map(|&n| dev(n)).collect();
        let ratios: Vec<f64> = d.windows(2).map(|w| w[0] / w[1]).collect();
        if is_rational {
            assert!(ratios.windows(2).all(|w| w[1] > w[0]), "{ratios:?}");
            assert!(ratios[3] > 7.0 && ratios[3] < 8.5, "{ratios:?}");
        } else {
            assert!(ratios.iter().all(|r| (7.5..8.6).contains(r)), "{ratios:?}");
        }
    }
    let s = wavy_bicubic();
    // (6.9): n ≈ (√3/3) k − 1.
    assert_eq!(default_counts(&s), [2, 2]);
    let a = approximate(
        &s,
        &ApproxOptions {
            tolerance: Some(1e-4),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(a.max_deviation <= 1e-4 && a.rms_deviation <= a.max_deviation);
    assert!(a.tried.len() >= 2 && a.tried.windows(2).all(|w| w[1].0[0] > w[0].0[0]));
    // A bilinear patch composed with the affine θ is quadratic: reproduced exactly.
    let bilinear = NurbsSurface::try_new(
        [1, 1],
        [vec![0.0, 0.0, 2.0, 2.0], vec![0.0, 0.0, 1.0, 1.0]],
        [2, 2],
        vec![
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(2.0, 0.0, 0.0),
            Vector3::new(2.0, 1.0, 1.0),
        ],
        None,
    )
    .unwrap();
    let a = approximate(
        &bilinear,
        &ApproxOptions {
            counts: Some([3, 2]),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(a.max_deviation < 1e-14, "{}", a.max_deviation);
    // Bad requests.
    assert!(approx::ups_of_nurbs(&s, [0, 3]).is_err());
    let e = approximate(
        &s,
        &ApproxOptions {
            tolerance: Some(-1.0),
            ..Default::default()
        },
    );
    assert!(matches!(e, Err(ApproxError::Tolerance(_))));
    // A valid surface on a parameter domain of (subnormal) width 1e-320 has derivatives
    // beyond any control value: refused with the domain named, not turned into a UPS
    // surface that cannot be evaluated or saved.
    let thin = NurbsSurface::try_new(
        [1, 1],
        [vec![0.0, 0.0, 1e-320, 1e-320], vec![0.0, 0.0, 1.0, 1.0]],
        [2, 2],
        bilinear.points().to_vec(),
        None,
    )
    .unwrap();
    let e = approx::ups_of_nurbs(&thin, [2, 2]).unwrap_err();
    assert!(matches!(e, ApproxError::TooLarge { .. }), "{e}");
    assert!(e.to_string().contains("[0, 1e-320]"), "{e}");
}

/// The twisted cubic (t, t², t³) on [0, 1] as a cubic Bézier curve, rational with weights c^i
/// (a Möbius reparametrisation t = c s / ((1 − s) + c s) of the same curve) when c ≠ 1.
fn twisted_cubic(c: f64) -> NurbsCurve {
    let p = vec![
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0 / 3.0, 0.0, 0.0),
        Vector3::new(2.0 / 3.0, 1.0 / 3.0, 0.0),
        Vector3::new(1.0, 1.0, 1.0),
    ];
    let w = (c != 1.0).then(|| vec![1.0, c, c * c, c * c * c]);
    NurbsCurve::try_new(3, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], p, w).unwrap()
}

#[test]
fn torsion_and_curvature_of_the_twisted_cubic_are_its_closed_forms() {
    // τ = 3 / (9t⁴ + 9t² + 1), κ = 2 √(9t⁴ + 9t² + 1) / (1 + 4t² + 9t⁴)^{3/2}.
    let tau = |t: f64| 3.0 / (9.0 * t.powi(4) + 9.0 * t * t + 1.0);
    let kappa = |t: f64| {
        2.0 * (9.0 * t.powi(4) + 9.0 * t * t + 1.0).sqrt()
            / (1.0 + 4.0 * t * t + 9.0 * t.powi(4)).powf(1.5)
    };
    for c in [1.0, 0.5, 2.0, 3.7] {
        let curve = twisted_cubic(c);
        for k in 0..=20 {
            let s = k as f64 / 20.0;
            let t = c * s / ((1.0 - s) + c * s);
            let (got_tau, got_kappa) = (curve.torsion(s).unwrap(), curve.curvature(s).unwrap());
            assert!(
                (got_tau - tau(t)).abs() < 1e-12 * tau(t),
                "c {c} s {s}: {got_tau} vs {}",
                tau(t)
            );
            assert!(
                (got_kappa - kappa(t)).abs() < 1e-12 * kappa(t),
                "c {c} s {s}"
            );
        }
    }
}

#[test]
fn torsion_across_an_interior_knot_and_of_planar_curves() {
    // The twisted cubic on [0, 2] as a B-spline with the interior knot 1 of multiplicity 3:
    // Bézier points of (2s, 4s², 8s³) halved by de Casteljau.
    let b = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(2.0 / 3.0, 0.0, 0.0),
        Vector3::new(4.0 / 3.0, 4.0 / 3.0, 0.0),
        Vector3::new(2.0, 4.0, 8.0),
    ];
    let m = |a: Vector3<f64>, b: Vector3<f64>| (a + b) * 0.5;
    let (l1, m1, r1) = (m(b[0], b[1]), m(b[1], b[2]), m(b[2], b[3]));
    let (l2, r2) = (m(l1, m1), m(m1, r1));
    let mid = m(l2, r2);
    // Knots [0,0,0,0,1,1,1,2,2,2,2]: the two Bézier pieces joined (C² by construction).
    let points = vec![b[0], l1, l2, mid, r2, r1, b[3]];
    let curve = NurbsCurve::try_new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0],
        points,
        None,
    )
    .unwrap();
    for k in 0..=40 {
        let t = 2.0 * k as f64 / 40.0;
        let exact = 3.0 / (9.0 * t.powi(4) + 9.0 * t * t + 1.0);
        let got = curve.torsion(t).unwrap();
        assert!(
            (got - exact).abs() < 1e-11 * exact,
            "t {t}: {got} vs {exact}"
        );
    }
    // A planar rational conic has no torsion; a straight line no osculating plane.
    let conic = NurbsCurve::try_new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector3::new(1.0, 0.0, 2.0),
            Vector3::new(1.0, 1.0, 2.0),
            Vector3::new(0.0, 1.0, 2.0),
        ],
        Some(vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]),
    )
    .unwrap();
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        assert!(conic.torsion(t).unwrap().abs() < 1e-12);
        assert!((conic.curvature(t).unwrap() - 1.0).abs() < 1e-12);
    }
    let line = NurbsCurve::try_new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Vector3::zeros(), Vector3::new(1.0, 2.0, 3.0)],
        None,
    )
    .unwrap();
    assert_eq!(line.torsion(0.5), None);
    assert_eq!(line.curvature(0.5), Some(0.0));
    assert_eq!(line.torsion(1.5), None);
}

/// A sub-interval of a knot vector's domain: its ends random, knots or the domain's ends.
fn sub_range(r: &mut rand_chacha::ChaCha8Rng, kv: &KnotVector) -> [f64; 2] {
    let (lo, hi) = kv.domain();
    let inside: Vec<f64> = kv
        .knots()
        .iter()
        .copied()
        .filter(|&k| k >= lo && k <= hi)
        .collect();
    let pick = |r: &mut rand_chacha::ChaCha8Rng| match r.random_range(0..3) {
        0 => uniform(r, lo, hi),
        1 => inside[r.random_range(0..inside.len())],
        _ => [lo, hi][r.random_range(0..2usize)],
    };
    loop {
        let (a, b) = (pick(&mut *r), pick(&mut *r));
        if a != b {
            return [a.min(b), a.max(b)];
        }
    }
}

#[test]
fn a_restricted_surface_is_the_same_surface_on_the_sub_rectangle() {
    let mut r = rng(1707);
    let mut worst = 0.0f64;
    for _ in 0..60 {
        let case = random_surface(&mut r);
        let s = &case.s;
        let (u, v) = (
            sub_range(&mut r, &s.knot_vectors()[0]),
            sub_range(&mut r, &s.knot_vectors()[1]),
        );
        let t = s.restricted(u, v).unwrap();
        let (lo, hi) = t.domain_bounds();
        assert_eq!([lo.x, hi.x, lo.y, hi.y], [u[0], u[1], v[0], v[1]]);
        assert!(t.degree() == s.degree() && t.is_rational());
        // The same parametrisation: equal jets (relative to the quantity, and to 1).
        for _ in 0..20 {
            let uv = Point2::new(uniform(&mut r, lo.x, hi.x), uniform(&mut r, lo.y, hi.y));
            let (a, b) = (t.jet(uv).unwrap().jet, s.jet(uv).unwrap().jet);
            let pairs = [
                (a.value, b.value),
                (a.dx, b.dx),
                (a.dy, b.dy),
                (a.dxx, b.dxx),
                (a.dxy, b.dxy),
                (a.dyy, b.dyy),
            ];
            for (k, (x, y)) in pairs.iter().enumerate() {
                let e = (x - y).norm() / y.norm().max(1.0);
                worst = worst.max(e);
                assert!(e < 1e-10, "order {k} at {uv}: {x} vs {y} ({e:e})");
            }
        }
        // Clamped at new ends: the corner is the first control point.
        let (slo, _) = s.domain_bounds();
        if u[0] > slo.x && v[0] > slo.y {
            let corner = s.point(Point2::new(u[0], v[0])).unwrap();
            assert!((t.points()[0] - corner).norm() <= 1e-12 * corner.norm().max(1.0));
        }
    }
    eprintln!("worst relative difference {worst:e}");
    // A polynomial surface stays polynomial, with weights exactly 1.
    let wavy = wavy_bicubic();
    let poly = NurbsSurface::try_new(
        wavy.degree(),
        [
            wavy.knot_vectors()[0].knots().to_vec(),
            wavy.knot_vectors()[1].knots().to_vec(),
        ],
        wavy.counts(),
        wavy.points().to_vec(),
        None,
    )
    .unwrap();
    let t = poly.restricted([0.3, 2.2], [0.5, 1.0]).unwrap();
    assert!(!t.is_rational() && t.weights().iter().all(|&w| w == 1.0));
    // An empty rectangle, or one reaching outside the domain, is refused.
    assert!(poly.restricted([1.0, 1.0], [0.0, 2.0]).is_none());
    assert!(poly.restricted([-0.5, 1.0], [0.0, 2.0]).is_none());
    assert!(poly.restricted([0.5, 1.0], [0.0, f64::NAN]).is_none());
}
