//! Curves on surfaces (issue 15's goals): all level lines of K for 20 levels on a 10k-patch
//! surface in under 1 s on 2 cores (hunting, tracing and joining on Franke PS-splines of
//! growing size); 1000 lines of curvature of 200 steps each in under 0.5 s.

mod common;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use pssurf::interrogate::{
    CurvatureQuantity, SurfaceField, ZeroSetOptions, auto_levels, level_lines,
};
use pssurf::prelude::*;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn levels(c: &mut Criterion) {
    let mut g = c.benchmark_group("level_lines_20_levels");
    g.sample_size(10);
    for vertices in [1_250, 5_000, 20_000] {
        let surface = Surface::Functional(common::franke_spline(vertices));
        let patches = surface
            .ps_basis()
            .map_or(0, |b| b.triangulation().triangle_count());
        g.throughput(Throughput::Elements(patches as u64));
        for (name, q) in [
            ("K", CurvatureQuantity::Gaussian),
            ("H", CurvatureQuantity::Mean),
        ] {
            let field = SurfaceField::Curvature(q);
            let lv = auto_levels(&surface, &field, 20);
            let opts = ZeroSetOptions::default();
            g.bench_with_input(
                BenchmarkId::new(format!("{name}, patches"), patches),
                &lv,
                |b, lv| b.iter(|| black_box(level_lines(&surface, &field, lv, &opts).unwrap())),
            );
        }
    }
    g.finish();
}

/// 1000 lines of curvature from random seeds, at most 100 steps each way (200 in all), traced
/// in parallel on a 10k-patch Franke spline.
fn curvature_lines(c: &mut Criterion) {
    use pssurf::interrogate::{FieldLineOptions, LineFamily, trace_field_line};
    use rayon::prelude::*;
    let surface = Surface::Functional(common::franke_spline(5_000));
    let (lo, hi) = surface.domain_bounds();
    let seeds = common::r2_points(1000, lo, hi);
    let opts = FieldLineOptions {
        max_points: 100,
        ..FieldLineOptions::default()
    };
    let trace = || -> usize {
        seeds
            .par_iter()
            .enumerate()
            .filter_map(|(k, p)| {
                let family = LineFamily::CURVATURE[k % 2];
                trace_field_line(&surface, family, *p, &opts).ok()
            })
            .map(|l| l.curve.uvs.len() - 1)
            .sum()
    };
    eprintln!("curvature lines: {} steps in 1000 lines", trace());
    let mut g = c.benchmark_group("curvature_lines");
    g.sample_size(10);
    g.throughput(Throughput::Elements(1000));
    g.bench_function("1000 lines of up to 200 steps, 10k patches", |b| {
        b.iter(|| black_box(trace()))
    });
    g.finish();
}

criterion_group!(benches, levels, curvature_lines);
criterion_main!(benches);
