//! Triangular Bézier patches: de Casteljau evaluation and jets by degree; the minimal
//! enclosing triangle of PS-point sets.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Point2, Vector3};
use pssurf::bezier::BezierTriangle;
use pssurf::geometry::{Triangle2, convex_hull, min_enclosing_triangle};
use std::hint::black_box;

fn bezier(c: &mut Criterion) {
    let tri = Triangle2::new(
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.2, 0.9),
    );
    let mut g = c.benchmark_group("bezier_triangle_jet");
    for m in [2usize, 3, 5, 8] {
        let patch =
            BezierTriangle::from_fn(tri, m, |p| Vector3::new(p.x, p.y, (3.0 * p.x).sin() * p.y));
        g.throughput(Throughput::Elements(1));
        g.bench_with_input(BenchmarkId::new("degree", m), &patch, |b, patch| {
            b.iter(|| black_box(patch.jet(black_box(Point2::new(0.3, 0.2)))))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("min_enclosing_triangle");
    for n in [7usize, 13, 25] {
        let pts: Vec<Point2<f64>> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let r = 1.0 + 0.3 * ((5 * k) as f64).sin();
                Point2::new(r * a.cos(), 0.7 * r * a.sin())
            })
            .collect();
        g.bench_with_input(BenchmarkId::new("points", n), &pts, |b, pts| {
            b.iter(|| black_box(min_enclosing_triangle(pts)))
        });
        g.bench_with_input(BenchmarkId::new("convex hull only", n), &pts, |b, pts| {
            b.iter(|| black_box(convex_hull(pts)))
        });
    }
    g.finish();
}

criterion_group!(benches, bezier);
criterion_main!(benches);
