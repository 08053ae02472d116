//! The job of `pssurf fit` + `pssurf eval --grid 1000x1000`, in memory: Delaunay
//! triangulation of 10k scattered points, gradient estimation, the PS basis and Hermite
//! interpolant, then values on a 1000 × 1000 grid — to compare with SciPy's
//! CloughTocher2DInterpolator construction + evaluation (benches/compare_scipy.py).

mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use pssurf::prelude::*;
use pssurf::scattered::{GradientMethod, interpolate};
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
    interpolate(pts, z, GradientMethod::Local).unwrap().spline
}

criterion_group!(benches, fit_eval);
criterion_main!(benches);
