//! The job of `pssurf fit` + `pssurf eval --grid 1000x1000`, in memory: Delaunay
//! triangulation of 10k scattered points, gradient estimation, the PS basis and Hermite
//! interpolant, then values on a 1000 × 1000 grid — to compare with SciPy's
//! CloughTocher2DInterpolator construction + evaluation (benches/compare_scipy.py).

mod common;

use std::sync::Arc;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use pssurf::prelude::*;
use pssurf::scattered::estimate_gradients;
use std::hint::black_box;

fn fit_eval(c: &mut Criterion) {
    let pts = common::random_points(10_000, 2003);
    let z: Vec<f64> = pts.iter().map(|&p| common::franke(p).value).collect();
    let grid = common::grid(1000, 1000);
    let mut g = c.benchmark_group("fit_10k_eval_1M_grid_in_memory");
    g.sample_size(20);
    g.throughput(Throughput::Elements(grid.len() as u64));
    g.bench_function("fit", |b| b.iter(|| black_box(fit(&pts, &z))));
    let s = fit(&pts, &z);
    g.bench_function("evaluate values", |b| {
        b.iter(|| black_box(s.map_points(&grid, |ev, p| ev.value(p))))
    });
    g.bench_function("fit + evaluate", |b| {
        b.iter(|| {
            let s = fit(&pts, &z);
            black_box(s.map_points(&grid, |ev, p| ev.value(p)))
        })
    });
    g.finish();
}

fn fit(pts: &[nalgebra::Point2<f64>], z: &[f64]) -> PsSpline<f64> {
    let order = pssurf::triangulation::morton_order(pts);
    let pts: Vec<_> = order.iter().map(|&i| pts[i as usize]).collect();
    let z: Vec<f64> = order.iter().map(|&i| z[i as usize]).collect();
    let tri = Triangulation::delaunay(pts).unwrap();
    let grads = estimate_gradients(&tri, &z).unwrap();
    let data: Vec<Hermite<f64>> = z
        .iter()
        .zip(&grads)
        .map(|(&value, (g, _))| Hermite {
            value,
            dx: g.x,
            dy: g.y,
        })
        .collect();
    PsSpline::hermite(Arc::new(PsBasis::optimal(tri).unwrap()), &data).unwrap()
}

criterion_group!(benches, fit_eval);
criterion_main!(benches);
