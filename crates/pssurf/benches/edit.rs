//! Local editing (issue 16's goal: one edit on a 100k-vertex PS surface with a region of about
//! 50 control triangles in under 5 ms, so that the application can follow a dragged slider):
//! a parametric PS interpolant of a wave on a jittered 317 × 317 grid, the mean curvature at
//! one point raised by 0.2, with the point and tangent plane kept; each iteration undoes the
//! edit (not timed separately: undo is one `set_control_points`).

use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{Point2, Vector3};
use pssurf::edit::{EditRequest, Measure, edit_locally};
use pssurf::ps::{Hermite, PsBasis, PsSpline};
use pssurf::surface::Surface;
use pssurf::triangulation::Triangulation;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A k × k grid of the unit square, jittered, Delaunay-triangulated.
fn grid(k: usize) -> Triangulation {
    let mut pts = Vec::with_capacity(k * k);
    for j in 0..k {
        for i in 0..k {
            let jitter = |a: usize, b: usize| {
                0.2 * (((a * 7919 + b * 104_729) % 1000) as f64 / 1000.0 - 0.5)
            };
            let x = (i as f64
                + if i > 0 && i + 1 < k {
                    jitter(i, j)
                } else {
                    0.0
                })
                / (k - 1) as f64;
            let y = (j as f64
                + if j > 0 && j + 1 < k {
                    jitter(j, i)
                } else {
                    0.0
                })
                / (k - 1) as f64;
            pts.push(Point2::new(x, y));
        }
    }
    Triangulation::delaunay(pts).unwrap()
}

fn one_edit(c: &mut Criterion) {
    let mut g = c.benchmark_group("local_edit");
    for k in [100, 317] {
        edit_on_grid(&mut g, k);
    }
    g.finish();
}

/// One edit on a k × k grid with a region of about 50 control triangles.
fn edit_on_grid(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>, k: usize) {
    let tri = grid(k);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let spline = PsSpline::interpolate(basis, |p| {
        let (s, co) = (3.0 * p.x).sin_cos();
        let z = 0.2 * s * (2.0 * p.y).cos();
        Hermite {
            value: Vector3::new(p.x, p.y, z),
            dx: Vector3::new(1.0, 0.0, 0.6 * co * (2.0 * p.y).cos()),
            dy: Vector3::new(0.0, 1.0, -0.4 * s * (2.0 * p.y).sin()),
        }
    })
    .unwrap();
    let mut surface = Surface::Parametric(spline);
    // About 50 vertices within 4 grid spacings.
    let at = Point2::new(0.4123, 0.5871);
    let h = Measure::Mean
        .of(&pssurf::surface::ParametricSurface::jet(&surface, at)
            .unwrap()
            .jet)
        .unwrap();
    let req = EditRequest {
        at,
        measure: Measure::Mean,
        target: h + 0.2,
        radius: 4.0 / (k - 1) as f64,
        keep_point: true,
        keep_tangent: true,
    };
    let probe = edit_locally(&mut surface, &req).unwrap();
    eprintln!(
        "{} free control triangles, {} iterations, H {} -> {}",
        probe.free_groups, probe.iterations, probe.before, probe.after
    );
    probe.undo(&mut surface).unwrap();
    let name = format!("{} vertices, H + 0.2, point and tangent kept", k * k);
    g.bench_function(name, |b| {
        b.iter(|| {
            let e = edit_locally(&mut surface, &req).unwrap();
            e.undo(&mut surface).unwrap();
            black_box(e.after)
        })
    });
}

criterion_group!(benches, one_edit);
criterion_main!(benches);
