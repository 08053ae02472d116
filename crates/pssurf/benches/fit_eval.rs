//! The job of `pssurf fit` + `pssurf eval --grid 1000x1000`, in memory: Delaunay
//! triangulation of 10k scattered points, gradient estimation, the PS basis and Hermite
//! interpolant, then values on a 1000 × 1000 grid — to compare with SciPy's
//! CloughTocher2DInterpolator construction + evaluation (benches/compare_scipy.py).

mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use pssurf::prelude::*;
use pssurf::ps::Energy;
use pssurf::scattered::{
    GradientMethod, Smoothing, estimate_gradients, estimate_gradients_global,
    estimate_gradients_jumps, interpolate, interpolate_with, smooth_scattered,
};
use std::hint::black_box;

fn fit_eval(c: &mut Criterion) {
    let pts = common::random_points(10_000, 2003);
    let z: Vec<f64> = pts.iter().map(|&p| common::franke(p).value).collect();
    let grid = common::grid(1000, 1000);
    let mut g = c.benchmark_group("fit_10k_eval_1M_grid_in_memory");
    g.sample_size(20);
    g.throughput(Throughput::Elements(grid.len() as u64));
    g.bench_function("fit", |b| b.iter(|| black_box(fit(&pts, &z))));
    // As the Python interpolant: circumscribed PS-triangles, nets from the Hermite data.
    g.bench_function("fit for evaluation", |b| {
        b.iter(|| {
            black_box(
                interpolate_with(
                    &pts,
                    &z,
                    GradientMethod::Local,
                    &PsTriangleChoice::Circumscribed,
                )
                .unwrap(),
            )
        })
    });
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

/// The gradient estimators and the global one's parts, and the smoothing fit, by size:
/// `cargo bench -p pssurf --bench fit_eval -- fitting`.
fn fitting(c: &mut Criterion) {
    let mut g = c.benchmark_group("fitting");
    g.sample_size(10);
    for n in [10_000, 100_000] {
        let pts = common::random_points(n, 2004);
        let z: Vec<f64> = pts.iter().map(|&p| common::franke(p).value).collect();
        g.throughput(Throughput::Elements(n as u64));
        let basis = interpolate(&pts, &z, GradientMethod::Local)
            .unwrap()
            .spline
            .basis()
            .clone();
        let zv: Vec<f64> = {
            let fit = interpolate(&pts, &z, GradientMethod::Local).unwrap();
            fit.data_index.iter().map(|&k| z[k]).collect()
        };
        g.bench_function(format!("local gradients/{n}"), |b| {
            b.iter(|| black_box(estimate_gradients(basis.triangulation(), &zv).unwrap()))
        });
        g.bench_function(format!("jump energy matrix/{n}"), |b| {
            b.iter(|| black_box(basis.energy_matrix(Energy::HessianJumps)))
        });
        g.bench_function(format!("global gradients/{n}"), |b| {
            b.iter(|| black_box(estimate_gradients_global(&basis, &zv).unwrap()))
        });
        g.bench_function(format!("least-jump gradients/{n}"), |b| {
            b.iter(|| black_box(estimate_gradients_jumps(&basis, &zv).unwrap()))
        });
        let m = n / 20;
        g.bench_function(format!("smoothing fit, fixed λ, {m} vertices/{n}"), |b| {
            b.iter(|| {
                black_box(
                    smooth_scattered(
                        &pts,
                        &z,
                        m,
                        Energy::HessianJumps,
                        Smoothing::Fixed(1e-6),
                        &mut |_| {},
                    )
                    .unwrap(),
                )
            })
        });
    }
    g.finish();
}

fn fit(pts: &[nalgebra::Point2<f64>], z: &[f64]) -> PsSpline<f64> {
    interpolate(pts, z, GradientMethod::Local).unwrap().spline
}

criterion_group!(benches, fit_eval, fitting);
criterion_main!(benches);
