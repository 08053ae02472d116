//! Level lines (issue 15's goal: all level lines of K for 20 levels on a 10k-patch surface in
//! under 1 s on 2 cores): hunting, tracing and joining on Franke PS-splines of growing size.

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

criterion_group!(benches, levels);
criterion_main!(benches);
