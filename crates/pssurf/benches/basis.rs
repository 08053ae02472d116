//! Building the PS basis (optimal PS-triangles by exact minimal enclosing triangles) and the
//! Bézier nets, for growing triangulations; and the Delaunay triangulation for reference.

mod common;

use std::sync::Arc;

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use pssurf::prelude::*;
use std::hint::black_box;

fn basis(c: &mut Criterion) {
    let mut g = c.benchmark_group("basis_and_nets");
    g.sample_size(10);
    for (order, n) in [
        ("random", 10_000usize),
        ("random", 100_000),
        ("random", 1_000_000),
        ("spatial", 1_000_000),
    ] {
        // Vertices numbered as the points came (random), or along a space-filling curve (as
        // `pssurf fit` stores them).
        let mut pts = common::random_points(n, 7);
        if order == "spatial" {
            pts = pssurf::triangulation::morton_order(&pts)
                .into_iter()
                .map(|i| pts[i as usize])
                .collect();
        }
        let tri = Triangulation::delaunay(pts).unwrap();
        g.throughput(Throughput::Elements(n as u64));
        let id = format!("optimal PS-triangles + nets, {order} vertex order");
        g.bench_with_input(BenchmarkId::new(id, n), &tri, |b, tri| {
            b.iter_batched(
                || tri.clone(),
                |t| {
                    let basis = Arc::new(PsBasis::optimal(t).unwrap());
                    let coeffs = vec![[0.5f64; 3]; basis.triangulation().vertex_count()];
                    black_box(PsSpline::new(basis, coeffs).unwrap())
                },
                BatchSize::LargeInput,
            )
        });
    }
    g.finish();

    let mut g = c.benchmark_group("triangulation");
    g.sample_size(10);
    for n in [10_000usize, 100_000] {
        let pts = common::random_points(n, 7);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(
            BenchmarkId::new("delaunay + validation", n),
            &pts,
            |b, pts| {
                b.iter_batched(
                    || pts.clone(),
                    |p| black_box(Triangulation::delaunay(p).unwrap()),
                    BatchSize::LargeInput,
                )
            },
        );
    }
    g.finish();
}

criterion_group!(benches, basis);
criterion_main!(benches);
