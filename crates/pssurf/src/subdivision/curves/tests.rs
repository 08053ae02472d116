use nalgebra::Vector3;

use super::*;
use crate::nurbs::NurbsCurve;
use crate::test_util::*;

fn polygon(r: &mut rand_chacha::ChaCha8Rng, n: usize) -> Vec<Vector3<f64>> {
    (0..n).map(|_| random_vec3(r)).collect()
}

/// The uniform B-spline of degree d with control points `p` and knots a + j h.
fn bspline(p: &[Vector3<f64>], d: usize, a: f64, h: f64) -> NurbsCurve {
    let knots = (0..p.len() + d + 1).map(|j| a + j as f64 * h).collect();
    NurbsCurve::try_new(d, knots, p.to_vec(), None).unwrap()
}

/// Open Chaikin and cubic polygons after k steps describe the original uniform B-spline on
/// the same parameter interval [d, n] (knots a_k + j/2^k with a_k = d − d/2^k), to 1e-12;
/// their closed-form limit points lie on it at the knots.
#[test]
fn chaikin_and_the_cubic_scheme_converge_to_the_uniform_b_splines() {
    let mut r = rng(2000);
    for (scheme, d) in [(CurveScheme::Chaikin, 2), (CurveScheme::CubicBSpline, 3)] {
        for _ in 0..5 {
            let n = 5 + (uniform(&mut r, 0.0, 6.0) as usize);
            let p = polygon(&mut r, n);
            let curve = bspline(&p, d, 0.0, 1.0);
            for k in 1..=5 {
                let q = subdivide_curve(&p, false, scheme, k).unwrap();
                let h = 0.5f64.powi(k as i32);
                let a = d as f64 - d as f64 * h;
                let refined = bspline(&q, d, a, h);
                for _ in 0..50 {
                    let t = uniform(&mut r, d as f64, n as f64);
                    let (x, y) = (curve.point(t).unwrap(), refined.point(t).unwrap());
                    assert!(
                        (x - y).norm() < 1e-12 * (1.0 + x.norm()),
                        "{scheme:?} k={k} t={t}"
                    );
                }
                // The limit points: Chaikin's edge midpoints at a + (j + 2) h, the cubic
                // vertex limits at a + (i + 2) h (vertex i ≥ 1).
                let limits = limit_points(&q, false, scheme).unwrap();
                for (j, l) in limits.iter().enumerate() {
                    let index = if d == 2 { j } else { j + 1 };
                    let t = a + (index + 2) as f64 * h;
                    if t < d as f64 || t > n as f64 {
                        continue;
                    }
                    let c = curve.point(t).unwrap();
                    assert!(
                        (l - c).norm() < 1e-12 * (1.0 + c.norm()),
                        "{scheme:?} limit {j}"
                    );
                }
            }
        }
    }
}

/// A closed polygon is refined as the open polygon wrapped around it: the closed result is a
/// run of the open one, exactly.
#[test]
fn closed_polygons_are_wrapped_open_ones() {
    let mut r = rng(2001);
    for _ in 0..10 {
        let n = 3 + (uniform(&mut r, 0.0, 8.0) as usize);
        let p = polygon(&mut r, n);
        let wrap = |before: usize, after: usize| -> Vec<Vector3<f64>> {
            let mut w: Vec<Vector3<f64>> = (n - before..n).map(|i| p[i]).collect();
            w.extend(&p);
            w.extend((0..after).map(|i| p[i]));
            w
        };
        let four = CurveScheme::FourPoint {
            tension: 1.0 / 16.0,
        };
        for (scheme, before, after, skip) in [
            (CurveScheme::Chaikin, 0, 1, 0),
            (CurveScheme::CubicBSpline, 1, 2, 1),
            (four, 1, 2, 2),
        ] {
            let closed = subdivide_curve(&p, true, scheme, 1).unwrap();
            let open = subdivide_curve(&wrap(before, after), false, scheme, 1).unwrap();
            assert_eq!(closed.len(), 2 * n);
            assert_eq!(closed[..], open[skip..skip + 2 * n], "{scheme:?}");
        }
    }
}

/// The four-point scheme keeps every point, and with w = 1/16 reproduces cubics: after k
/// steps the points of a cubic sampled at t = 0, 1, …, n − 1 are the cubic at t = j / 2^k, to
/// the ends (cubic extrapolation of the missing neighbours).
#[test]
fn the_four_point_scheme_interpolates_and_reproduces_cubics() {
    let mut r = rng(2002);
    let four = CurveScheme::FourPoint {
        tension: 1.0 / 16.0,
    };
    for _ in 0..10 {
        let c: [Vector3<f64>; 4] = std::array::from_fn(|_| random_vec3(&mut r));
        let cubic = |t: f64| c[0] + c[1] * t + c[2] * (t * t) + c[3] * (t * t * t);
        let n = 4 + (uniform(&mut r, 0.0, 6.0) as usize);
        let p: Vec<Vector3<f64>> = (0..n).map(|i| cubic(i as f64)).collect();
        for k in 1..=4 {
            let q = subdivide_curve(&p, false, four, k).unwrap();
            let h = 0.5f64.powi(k as i32);
            assert_eq!(q.len(), (n - 1) * (1 << k) + 1);
            for (j, x) in q.iter().enumerate() {
                let y = cubic(j as f64 * h);
                assert!(
                    (x - y).norm() < 1e-11 * (1.0 + y.norm()),
                    "k={k} j={j}: {x} vs {y}"
                );
            }
            // Interpolation: the original points are kept bitwise.
            for (i, pi) in p.iter().enumerate() {
                assert_eq!(q[i << k], *pi);
            }
        }
        // Another tension still interpolates but no longer reproduces cubics.
        let q = subdivide_curve(&p, true, CurveScheme::FourPoint { tension: 0.1 }, 1).unwrap();
        for (i, pi) in p.iter().enumerate() {
            assert_eq!(q[2 * i], *pi);
        }
    }
}

#[test]
fn counts_and_refusals() {
    let mut r = rng(2003);
    let p = polygon(&mut r, 6);
    let four = CurveScheme::FourPoint {
        tension: 1.0 / 16.0,
    };
    for (scheme, open_len) in [
        (CurveScheme::Chaikin, 10),
        (CurveScheme::CubicBSpline, 9),
        (four, 11),
    ] {
        assert_eq!(
            subdivide_curve(&p, false, scheme, 1).unwrap().len(),
            open_len
        );
        assert_eq!(subdivide_curve(&p, true, scheme, 1).unwrap().len(), 12);
        assert!(matches!(
            subdivide_curve(&p[..2], false, scheme, 1),
            Err(SubdivisionError::TooFewPoints { .. })
        ));
        assert!(matches!(
            subdivide_curve(&p, true, scheme, 40),
            Err(SubdivisionError::TooLarge { .. })
        ));
    }
    let mut bad = p.clone();
    bad[3].y = f64::NAN;
    assert_eq!(
        subdivide_curve(&bad, false, CurveScheme::Chaikin, 1),
        Err(SubdivisionError::NonFinite(3))
    );
    assert!(matches!(
        subdivide_curve(&p, false, CurveScheme::FourPoint { tension: f64::NAN }, 1),
        Err(SubdivisionError::BadTension(_))
    ));
    // A finite tension far outside the convergent range overflows: refused, not written as
    // inf and NaN.
    for (tension, step) in [(1e308, 1), (1e100, 1), (1e25, 3)] {
        assert_eq!(
            subdivide_curve(&p, false, CurveScheme::FourPoint { tension }, 3),
            Err(SubdivisionError::Diverges { step, tension }),
            "tension {tension}"
        );
    }
}
