//! Validating a triangulation (exact orientation, adjacency, vertex fans, boundary contacts
//! and loop windings: `Triangulation::try_new`) for growing meshes, and the minimal
//! enclosing triangle of a vertex's PS-points for growing degree (issue 13: validation of
//! 1M triangles under 0.3 s; no cliff at high degree).

mod common;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Point2;
use pssurf::geometry::min_enclosing_triangle;
use pssurf::prelude::*;
use std::hint::black_box;

fn validate(c: &mut Criterion) {
    let mut g = c.benchmark_group("validate");
    g.sample_size(10);
    for n in [10_000usize, 100_000, 500_000] {
        let pts = common::random_points(n, 3);
        let order = pssurf::triangulation::morton_order(&pts);
        let pts: Vec<Point2<f64>> = order.into_iter().map(|i| pts[i as usize]).collect();
        let tri = Triangulation::delaunay(pts).unwrap();
        let vertices = tri.vertices().to_vec();
        let triangles: Vec<[usize; 3]> =
            (0..tri.triangle_count()).map(|t| tri.triangle(t)).collect();
        g.throughput(Throughput::Elements(triangles.len() as u64));
        g.bench_with_input(
            BenchmarkId::new("try_new (triangles)", triangles.len()),
            &(vertices, triangles),
            |b, (v, t)| b.iter(|| black_box(Triangulation::try_new(v.clone(), t.clone()).unwrap())),
        );
    }
    g.finish();
}

fn enclosing(c: &mut Criterion) {
    let mut g = c.benchmark_group("min_enclosing_triangle");
    g.sample_size(10);
    for d in [16usize, 64, 256, 1024, 4096] {
        // Points on a circle: every hull edge is nearly as good as the others, the worst case
        // for pruning.
        let pts: Vec<Point2<f64>> = (0..d)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / d as f64;
                Point2::new(a.cos(), a.sin())
            })
            .collect();
        g.throughput(Throughput::Elements(d as u64));
        g.bench_with_input(BenchmarkId::new("circle (points)", d), &pts, |b, p| {
            b.iter(|| black_box(min_enclosing_triangle(p)))
        });
    }
    g.finish();
}

criterion_group!(benches, validate, enclosing);
criterion_main!(benches);
