//! Loading surface files (issue 19, part 3): the same parametric UPS surface from its binary
//! (`.psb`) and JSON forms, validated as every load is, for growing surfaces.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Point2, Vector3};
use pssurf::ps::Hermite;
use pssurf::surface::{ControlNet, Surface, UpsSurface};
use pssurf::ups::{Lattice, LatticePolygon, Ups, UpsGrid};
use std::hint::black_box;

// The allocator the binaries ship with.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A parametric UPS hexagon of side `n` (3n² + 3n + 1 vertices, three control points each).
fn surface(n: i64) -> Surface {
    let lattice = Lattice {
        base: 1.0 / n as f64,
        origin: Point2::origin(),
    };
    let g = UpsGrid::new(lattice, LatticePolygon::standard(6, n).unwrap()).unwrap();
    let ups = Ups::hermite(g, |p| Hermite {
        value: Vector3::new(p.x, p.y, (3.0 * p.x).sin() * (2.0 * p.y).cos()),
        dx: Vector3::new(1.0, 0.0, 3.0 * (3.0 * p.x).cos() * (2.0 * p.y).cos()),
        dy: Vector3::new(0.0, 1.0, -2.0 * (3.0 * p.x).sin() * (2.0 * p.y).sin()),
    });
    Surface::try_from(UpsSurface::Parametric(ups)).unwrap()
}

fn load(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let mut g = c.benchmark_group("load_surface_file");
    g.sample_size(10);
    for n in [64i64, 256] {
        let s = surface(n);
        let points = s.control_count() as u64;
        for ext in ["psb", "json"] {
            let path = dir.path().join(format!("s{n}.{ext}"));
            pssurf::io::save(&s, &path).unwrap();
            g.throughput(Throughput::Elements(points));
            g.bench_with_input(
                BenchmarkId::new(format!("{ext}, control points"), points),
                &path,
                |b, p| b.iter(|| black_box(pssurf::io::load(p).unwrap())),
            );
        }
    }
    g.finish();
}

criterion_group!(benches, load);
criterion_main!(benches);
