//! Issue 12: both gradient estimators reproduce quadratics exactly and give interpolants of
//! order 3 on Franke's function.

use nalgebra::Point2;
use pssurf::scattered::{GradientMethod, interpolate};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[path = "../benches/common.rs"]
mod common;

const METHODS: [GradientMethod; 2] = [GradientMethod::Local, GradientMethod::Global];

fn franke(x: f64, y: f64) -> f64 {
    common::franke(Point2::new(x, y)).value
}

/// A k × k grid whose interior points are moved by up to δ.
fn jittered_grid(k: usize, delta: f64, seed: u64) -> Vec<Point2<f64>> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut pts = Vec::new();
    for i in 0..k {
        for j in 0..k {
            let inner = i > 0 && j > 0 && i + 1 < k && j + 1 < k;
            let mut p = Point2::new(i as f64 / (k - 1) as f64, j as f64 / (k - 1) as f64);
            if inner && delta > 0.0 {
                p.x += r.random_range(-delta..=delta);
                p.y += r.random_range(-delta..=delta);
            }
            pts.push(p);
        }
    }
    pts
}

/// The largest and the root-mean-square error of the interpolant of f at a 101 × 101 grid
/// of the unit square.
fn errors(pts: &[Point2<f64>], f: impl Fn(f64, f64) -> f64, method: GradientMethod) -> (f64, f64) {
    let z: Vec<f64> = pts.iter().map(|p| f(p.x, p.y)).collect();
    let s = interpolate(pts, &z, method).unwrap().spline;
    let (mut worst, mut sum): (f64, f64) = (0.0, 0.0);
    for i in 0..=100 {
        for j in 0..=100 {
            let (x, y) = (i as f64 / 100.0, j as f64 / 100.0);
            let v = s.eval(Point2::new(x, y)).unwrap();
            worst = worst.max((v - f(x, y)).abs());
            sum += (v - f(x, y)).powi(2);
        }
    }
    (worst, (sum / 101.0 / 101.0).sqrt())
}

#[test]
fn every_gradient_method_reproduces_quadratics() {
    let mut r = ChaCha8Rng::seed_from_u64(120);
    let sets: Vec<(String, Vec<Point2<f64>>)> = vec![
        (
            "random 300".into(),
            common::random_points_with_boundary(300, 1),
        ),
        (
            "random 40".into(),
            common::random_points_with_boundary(40, 2),
        ),
        ("grid 12".into(), jittered_grid(12, 0.0, 3)),
        ("grid 12 δ=1e-9".into(), jittered_grid(12, 1e-9, 4)),
        ("grid 12 δ=1e-3".into(), jittered_grid(12, 1e-3, 5)),
    ];
    for (name, pts) in &sets {
        for method in METHODS {
            for _ in 0..3 {
                let c: [f64; 6] = std::array::from_fn(|_| r.random_range(-1.0..1.0));
                let q = |x: f64, y: f64| {
                    c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y
                };
                let (err, _) = errors(pts, q, method);
                assert!(err < 1e-10, "{name}, {method:?}: {err:e}");
            }
        }
    }
}

#[test]
fn both_estimators_are_of_order_three_on_franke() {
    for method in METHODS {
        let sizes = [1000, 4000, 16000];
        let errors: Vec<f64> = sizes
            .iter()
            .map(|&n| errors(&common::random_points_with_boundary(n, 7), franke, method).1)
            .collect();
        // h ~ n^(-1/2): order p means error ~ n^(-p/2), a factor 4^(p/2) per step. The RMS
        // error at a grid is used: the maximum depends on one unlucky triangle.
        let orders: Vec<f64> = errors
            .windows(2)
            .map(|e| 2.0 * (e[0] / e[1]).log(4.0))
            .collect();
        let shown: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
        eprintln!("{method:?}: errors {shown:?}, observed orders {orders:.2?}");
        let mean = orders.iter().sum::<f64>() / orders.len() as f64;
        assert!(mean > 2.7, "{method:?}: observed order {mean:.2}");
    }
}
