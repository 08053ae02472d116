//! Evaluation throughput of a PS-spline: value and gradient (and full jets) on a grid, with
//! the walking evaluator on one core and in parallel, and at random points (R-tree).

mod common;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

fn eval(c: &mut Criterion) {
    let spline = common::franke_spline(10_000);
    let pts = common::grid(1000, 1000);
    let mut g = c.benchmark_group("eval_10k_vertices_1M_grid");
    g.throughput(Throughput::Elements(pts.len() as u64));
    g.sample_size(20);
    g.bench_function("value+gradient/1 core", |b| {
        b.iter(|| {
            let mut ev = spline.evaluator();
            let mut acc = 0.0;
            for &p in &pts {
                let (v, gx, gy) = ev.gradient(p).unwrap();
                acc += v + gx + gy;
            }
            black_box(acc)
        })
    });
    g.bench_function("value+gradient/all cores", |b| {
        b.iter(|| black_box(spline.gradients(&pts)))
    });
    g.bench_function("jet (to second order)/1 core", |b| {
        b.iter(|| {
            let mut ev = spline.evaluator();
            let mut acc = 0.0;
            for &p in &pts {
                acc += ev.jet(p).unwrap().jet.dxx;
            }
            black_box(acc)
        })
    });
    g.bench_function("value/1 core", |b| {
        b.iter(|| {
            let mut ev = spline.evaluator();
            let mut acc = 0.0;
            for &p in &pts {
                acc += ev.value(p).unwrap();
            }
            black_box(acc)
        })
    });
    g.finish();

    let mut g = c.benchmark_group("eval_random_points");
    g.sample_size(20);
    for n in [10_000usize, 100_000, 1_000_000] {
        let s = common::franke_spline(n);
        s.basis().triangulation().prepare_locator();
        let q = common::random_points(200_000, 99);
        g.throughput(Throughput::Elements(q.len() as u64));
        g.bench_with_input(BenchmarkId::new("value+gradient/1 core", n), &q, |b, q| {
            b.iter(|| {
                let mut acc = 0.0;
                for &p in q {
                    acc += s.jet(p).unwrap().jet.dx;
                }
                black_box(acc)
            })
        });
    }
    g.finish();
}

/// The fast paths for many points (issue 19): grids by scan conversion and by row runs, and
/// scattered queries sorted along the Morton curve, on 1 core and on all cores:
/// `cargo bench -p pssurf --bench eval -- fast`.
fn fast_paths(c: &mut Criterion) {
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    // The scan conversion (sorted axes) against the row runs, which the same grid with
    // descending axes takes (the same points, rows and columns reversed).
    let mut g = c.benchmark_group("fast_grid_1000x1000");
    g.sample_size(20);
    g.throughput(Throughput::Elements(1_000_000));
    let axis: Vec<f64> = (0..1000).map(|k| k as f64 / 999.0).collect();
    let descending: Vec<f64> = axis.iter().rev().copied().collect();
    for n in [1_000usize, 10_000, 100_000] {
        let s = common::franke_spline(n);
        g.bench_with_input(BenchmarkId::new("scan/all cores", n), &axis, |b, a| {
            b.iter(|| black_box(s.values_on_grid(a, a, f64::NAN)))
        });
        g.bench_with_input(
            BenchmarkId::new("runs/all cores", n),
            &descending,
            |b, a| b.iter(|| black_box(s.values_on_grid(a, a, f64::NAN))),
        );
        if n == 10_000 {
            g.bench_with_input(BenchmarkId::new("scan/1 core", n), &axis, |b, a| {
                b.iter(|| one.install(|| black_box(s.values_on_grid(a, a, f64::NAN))))
            });
            g.bench_with_input(BenchmarkId::new("runs/1 core", n), &descending, |b, a| {
                b.iter(|| one.install(|| black_box(s.values_on_grid(a, a, f64::NAN))))
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("fast_scattered_1M_queries");
    g.sample_size(10);
    let q = common::random_points(1_000_000, 98);
    g.throughput(Throughput::Elements(q.len() as u64));
    for n in [10_000usize, 1_000_000] {
        let s = common::franke_spline(n);
        s.basis().triangulation().prepare_locator();
        g.bench_with_input(BenchmarkId::new("map_scattered/1 core", n), &q, |b, q| {
            b.iter(|| one.install(|| black_box(s.map_scattered(q, |ev, p| ev.value(p)))))
        });
        g.bench_with_input(
            BenchmarkId::new("map_scattered/all cores", n),
            &q,
            |b, q| b.iter(|| black_box(s.map_scattered(q, |ev, p| ev.value(p)))),
        );
        g.bench_with_input(
            BenchmarkId::new("map_points (unsorted)/all cores", n),
            &q,
            |b, q| b.iter(|| black_box(s.map_points(q, |ev, p| ev.value(p)))),
        );
    }
    g.finish();
}

criterion_group!(benches, eval, fast_paths);
criterion_main!(benches);
