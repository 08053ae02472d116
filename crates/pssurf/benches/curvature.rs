//! Curvature throughput: every quantity (K, H, κ1, κ2, κabs, principal directions) at many
//! points — on a 1000 × 1000 grid located by walking, and piece by piece as the plots and
//! exporters sample a surface.

mod common;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use pssurf::interrogate::{Curvature, sample_patches};
use pssurf::prelude::*;
use pssurf::surface::fill_rows;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn curvature(c: &mut Criterion) {
    let surface = Surface::Functional(common::franke_spline(10_000));
    let pts = common::grid(1000, 1000);
    let mut g = c.benchmark_group("curvature_10k_vertices");
    g.sample_size(10);
    g.throughput(Throughput::Elements(pts.len() as u64));
    g.bench_function("1M grid points, all quantities, all cores", |b| {
        let mut out = vec![0.0; pts.len() * 11];
        b.iter(|| {
            fill_rows(&surface, &pts, 11, &mut out, |_, j, row| {
                if let Ok(j) = j
                    && let Ok(c) = Curvature::from_jet(&j.jet)
                {
                    row[0] = c.gaussian;
                    row[1] = c.mean;
                    row[2] = c.k1;
                    row[3] = c.k2;
                    row[4] = c.absolute();
                    row[5..8].copy_from_slice(c.dir1.as_slice());
                    row[8..11].copy_from_slice(c.dir2.as_slice());
                }
            });
            black_box(&out);
        })
    });
    // The curvature computation alone, from precomputed jets, one core.
    let jets: Vec<_> = pssurf::surface::jets(&surface, &pts)
        .into_iter()
        .map(|j| j.unwrap().jet)
        .collect();
    g.bench_function("from jets: K, H, κ1, κ2 and directions, 1 core", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for j in &jets {
                let c = Curvature::from_jet(j).unwrap();
                acc += c.mean + c.dir1.x + c.dir2_uv.y;
            }
            black_box(acc)
        })
    });
    g.bench_function("from jets: K, H, κ1, κ2 only, 1 core", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for j in &jets {
                acc += pssurf::interrogate::PrincipalCurvatures::from_jet(j)
                    .unwrap()
                    .0
                    .k1;
            }
            black_box(acc)
        })
    });
    g.bench_function("jets only, all cores", |b| {
        b.iter(|| black_box(pssurf::surface::jets(&surface, &pts)))
    });
    // Level 2: 16 mesh triangles and 15 vertices per PS sub-triangle.
    let vertices = (surface.piece_count() * 15) as u64;
    g.throughput(Throughput::Elements(vertices));
    g.bench_function("sampled piece by piece (level 2), all cores", |b| {
        b.iter(|| black_box(sample_patches(&surface, 2, true)))
    });
    g.finish();
}

criterion_group!(benches, curvature);
criterion_main!(benches);
