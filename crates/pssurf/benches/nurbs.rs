//! NURBS evaluation (issue 17's goal: ≥ 10 M points per second per core with second
//! derivatives on a bicubic surface): the jet (point, first and second derivatives) of a
//! rational bicubic surface with a 20 × 20 net, at random parameters, on one core.

mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::Vector3;
use pssurf::nurbs::NurbsSurface;
use pssurf::surface::ParametricSurface;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A rational bicubic surface: clamped uniform knots, a wavy net, weights in [0.5, 2].
fn bicubic(n: usize) -> NurbsSurface {
    let knots: Vec<f64> = (0..n + 4)
        .map(|i| (i.saturating_sub(3)).min(n - 3) as f64)
        .collect();
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (i as f64, j as f64);
            points.push(Vector3::new(x, y, (0.7 * x).sin() * (0.5 * y).cos()));
            weights.push(1.25 + 0.75 * ((i * 7 + j * 3) % 5) as f64 / 4.0 - 0.5);
        }
    }
    NurbsSurface::try_new(
        [3, 3],
        [knots.clone(), knots],
        [n, n],
        points,
        Some(weights),
    )
    .unwrap()
}

fn evaluation(c: &mut Criterion) {
    let s = bicubic(20);
    let (lo, hi) = s.domain_bounds();
    // Parameters from a low-discrepancy sequence, in no particular order.
    let pts = common::r2_points(100_000, lo, hi);
    let mut g = c.benchmark_group("nurbs_bicubic_20x20");
    g.throughput(Throughput::Elements(pts.len() as u64));
    g.bench_function("jet (point, 1st and 2nd derivatives), one core", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for p in &pts {
                let j = s.jet(*p).unwrap().jet;
                acc += j.value.z + j.dxx.z + j.dxy.z + j.dyy.z;
            }
            black_box(acc)
        })
    });
    g.finish();
}

criterion_group!(benches, evaluation);
criterion_main!(benches);
