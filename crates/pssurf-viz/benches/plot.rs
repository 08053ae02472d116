//! Rendering throughput: a curvature plot of a surface drawn with about a million mesh
//! triangles at 1600 × 1200 (sampling with curvature + rasterising + shading + legend), and
//! the rasteriser alone.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Point2, Vector3};
use pssurf::interrogate::{CurvatureQuantity, sample_patches};
use pssurf::ps::Hermite;
use pssurf::surface::PiecewiseSurface;
use pssurf::ups::{Lattice, LatticePolygon, Ups, UpsGrid};
use pssurf_viz::plot::plot_sampled;
use pssurf_viz::{PlotOptions, Show};
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn plot(c: &mut Criterion) {
    // The hexagon with 27 triangles per side: 6·27² = 4374 triangles, 26 244 PS pieces;
    // level 3 draws 64 mesh triangles per piece, 1 679 616 in all.
    let lattice = Lattice {
        base: 1.0 / 27.0,
        origin: Point2::origin(),
    };
    let grid = UpsGrid::new(lattice, LatticePolygon::standard(6, 27).unwrap()).unwrap();
    let ups = Ups::hermite(grid, |p| Hermite {
        value: Vector3::new(p.x, p.y, (4.0 * p.x).sin() * (3.0 * p.y).cos()),
        dx: Vector3::new(1.0, 0.0, 4.0 * (4.0 * p.x).cos() * (3.0 * p.y).cos()),
        dy: Vector3::new(0.0, 1.0, -3.0 * (4.0 * p.x).sin() * (3.0 * p.y).sin()),
    });
    let surface = ups.to_ps().unwrap();
    let surface = pssurf::surface::Surface::Parametric(surface);
    let level = 3;
    let triangles = (surface.piece_count() << (2 * level)) as u64;
    let opts = PlotOptions {
        show: Show::Quantity(CurvatureQuantity::Mean),
        width: 1600,
        height: 1200,
        level,
        ..PlotOptions::default()
    };
    let mut g = c.benchmark_group("plot_1600x1200");
    g.sample_size(10);
    g.throughput(Throughput::Elements(triangles));
    g.bench_function(
        format!("mean curvature, {triangles} triangles, sample + render"),
        |b| b.iter(|| black_box(pssurf_viz::plot(&surface, &opts))),
    );
    let sampled = sample_patches(&surface, level, true);
    g.bench_function(
        format!("mean curvature, {triangles} triangles, render only"),
        |b| b.iter(|| black_box(plot_sampled(&sampled, &[], &opts))),
    );
    let shaded = PlotOptions {
        show: Show::Shaded,
        ..opts.clone()
    };
    g.bench_function(format!("shaded, {triangles} triangles, render only"), |b| {
        b.iter(|| black_box(plot_sampled(&sampled, &[], &shaded)))
    });
    g.finish();
}

criterion_group!(benches, plot);
criterion_main!(benches);
