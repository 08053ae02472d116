//! Fixtures shared by the benchmarks, the integration tests and the profiling examples
//! (`tests/` and `examples/` include this file with `#[path]`).
#![allow(dead_code)]

use std::sync::Arc;

use nalgebra::Point2;
use pssurf::prelude::*;
use rand::{RngExt, SeedableRng};

/// Franke's test function with its gradient.
pub fn franke(p: Point2<f64>) -> Hermite<f64> {
    let (x, y) = (p.x, p.y);
    let e1 = 0.75 * (-((9.0 * x - 2.0).powi(2) + (9.0 * y - 2.0).powi(2)) / 4.0).exp();
    let e2 = 0.75 * (-(9.0 * x + 1.0).powi(2) / 49.0 - (9.0 * y + 1.0) / 10.0).exp();
    let e3 = 0.5 * (-((9.0 * x - 7.0).powi(2) + (9.0 * y - 3.0).powi(2)) / 4.0).exp();
    let e4 = -0.2 * (-(9.0 * x - 4.0).powi(2) - (9.0 * y - 7.0).powi(2)).exp();
    let value = e1 + e2 + e3 + e4;
    let dx = e1 * (-2.0 * 9.0 * (9.0 * x - 2.0) / 4.0)
        + e2 * (-2.0 * 9.0 * (9.0 * x + 1.0) / 49.0)
        + e3 * (-2.0 * 9.0 * (9.0 * x - 7.0) / 4.0)
        + e4 * (-2.0 * 9.0 * (9.0 * x - 4.0));
    let dy = e1 * (-2.0 * 9.0 * (9.0 * y - 2.0) / 4.0)
        + e2 * (-9.0 / 10.0)
        + e3 * (-2.0 * 9.0 * (9.0 * y - 3.0) / 4.0)
        + e4 * (-2.0 * 9.0 * (9.0 * y - 7.0));
    Hermite { value, dx, dy }
}

/// The values of Franke's function at `points`.
pub fn franke_values(points: &[Point2<f64>]) -> Vec<f64> {
    points.iter().map(|&p| franke(p).value).collect()
}

/// The program's first N positional arguments as counts, each `defaults[k]` when absent or
/// not a number (for the profiling examples).
pub fn count_args<const N: usize>(defaults: [usize; N]) -> [usize; N] {
    let args: Vec<Option<usize>> = std::env::args().skip(1).map(|a| a.parse().ok()).collect();
    std::array::from_fn(|k| args.get(k).copied().flatten().unwrap_or(defaults[k]))
}

/// `n` seeded random points in the unit square, with the corners (so the grid is inside).
pub fn random_points(n: usize, seed: u64) -> Vec<Point2<f64>> {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut pts = vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.0, 1.0),
        Point2::new(1.0, 1.0),
    ];
    while pts.len() < n {
        pts.push(Point2::new(r.random::<f64>(), r.random::<f64>()));
    }
    pts
}

/// About n points of the unit square: its corners, √n random ones on each side (so that the
/// boundary is sampled as densely as the inside) and uniform random ones inside.
pub fn random_points_with_boundary(n: usize, seed: u64) -> Vec<Point2<f64>> {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut pts = random_points(4, seed);
    for _ in 0..(n as f64).sqrt() as usize {
        let t: f64 = r.random();
        pts.extend([
            Point2::new(t, 0.0),
            Point2::new(1.0, t),
            Point2::new(1.0 - t, 1.0),
            Point2::new(0.0, 1.0 - t),
        ]);
    }
    while pts.len() < n {
        pts.push(Point2::new(r.random::<f64>(), r.random::<f64>()));
    }
    pts
}

/// The Delaunay triangulation of `n` random points.
pub fn delaunay(n: usize) -> Triangulation {
    Triangulation::delaunay(random_points(n, 7)).expect("random points triangulate")
}

/// Franke's function interpolated on `n` random points.
pub fn franke_spline(n: usize) -> PsSpline<f64> {
    let basis = Arc::new(PsBasis::optimal(delaunay(n)).unwrap());
    PsSpline::interpolate(basis, franke).unwrap()
}

/// An nx × ny grid over the unit square, row by row.
pub fn grid(nx: usize, ny: usize) -> Vec<Point2<f64>> {
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            out.push(Point2::new(
                i as f64 / (nx - 1) as f64,
                j as f64 / (ny - 1) as f64,
            ));
        }
    }
    out
}

/// `n` points of the R2 low-discrepancy sequence in the box [lo, hi] (spread evenly, in no
/// particular order).
pub fn r2_points(n: usize, lo: Point2<f64>, hi: Point2<f64>) -> Vec<Point2<f64>> {
    (0..n)
        .map(|k| {
            let (a, b) = (
                (k as f64 * 0.754_877_666).fract(),
                (k as f64 * 0.569_840_291).fract(),
            );
            Point2::new(lo.x + a * (hi.x - lo.x), lo.y + b * (hi.y - lo.y))
        })
        .collect()
}
