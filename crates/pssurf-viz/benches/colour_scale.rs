//! Fitting an automatic colour scale to the values of a plot: the robust percentile range
//! (selection, O(n); what the application refits after every edit) against the sorting
//! one (O(n log n)), and the data range (extremes, clipped counts) the legend shows.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use pssurf_viz::colormap::{ColorScale, DataRange};
use std::hint::black_box;

/// `n` curvature-like values: a smooth bulk in [−1, 1] and a few large outliers.
fn values(n: usize) -> Vec<f64> {
    let mut x = 0.618_033_988_749_895_f64;
    (0..n)
        .map(|k| {
            x = (x * 997.0 + 0.123_456_789).fract();
            if k % 997 == 0 {
                40.0 * x
            } else {
                2.0 * x - 1.0
            }
        })
        .collect()
}

fn colour_scale(c: &mut Criterion) {
    let mut g = c.benchmark_group("colour scale");
    g.sample_size(10);
    for n in [100_000usize, 1_000_000, 4_000_000] {
        let v = values(n);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("robust (select)", n), &v, |b, v| {
            b.iter(|| ColorScale::robust(black_box(v), 1.0, true, 1e-9))
        });
        g.bench_with_input(BenchmarkId::new("auto (sort)", n), &v, |b, v| {
            b.iter(|| ColorScale::auto(black_box(v), true, false, 1e-9))
        });
        let scale = ColorScale::robust(&v, 1.0, true, 1e-9);
        g.bench_with_input(BenchmarkId::new("data range", n), &v, |b, v| {
            b.iter(|| DataRange::of(black_box(v), &scale))
        });
    }
    g.finish();
}

criterion_group!(benches, colour_scale);
criterion_main!(benches);
