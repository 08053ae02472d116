//! UPS-splines: subdivision, the wavelet transform (forward + inverse, with the thesis' and the
//! stable update) and tessellation by subdivision, for growing surfaces.

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use nalgebra::{Point2, Vector3};
use pssurf::mesh::TriMesh;
use pssurf::ps::Hermite;
use pssurf::ups::wavelet::Update;
use pssurf::ups::{Lattice, LatticePolygon, Ups, UpsGrid};
use std::hint::black_box;

// The allocator the binaries ship with: it keeps freed memory for reuse, where glibc returns
// large blocks to the OS and every fresh 100 MB output would be page-faulted in again.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn surface(sides: usize, n: i64) -> Ups<Vector3<f64>> {
    let lattice = Lattice {
        base: 1.0 / n as f64,
        origin: Point2::origin(),
    };
    let g = UpsGrid::new(lattice, LatticePolygon::standard(sides, n).unwrap()).unwrap();
    Ups::hermite(g, |p| Hermite {
        value: Vector3::new(p.x, p.y, (3.0 * p.x).sin() * (2.0 * p.y).cos()),
        dx: Vector3::new(1.0, 0.0, 3.0 * (3.0 * p.x).cos() * (2.0 * p.y).cos()),
        dy: Vector3::new(0.0, 1.0, -2.0 * (3.0 * p.x).sin() * (2.0 * p.y).sin()),
    })
}

fn ups(c: &mut Criterion) {
    let mut g = c.benchmark_group("ups_subdivision");
    g.sample_size(10);
    for n in [84i64, 170, 340] {
        let s = surface(6, n);
        let out_points = 3 * s.grid().refined().vertex_count() as u64;
        g.throughput(Throughput::Elements(out_points));
        g.bench_with_input(
            BenchmarkId::new("one step, output control points", out_points),
            &s,
            |b, s| b.iter(|| black_box(s.subdivide())),
        );
    }
    g.finish();

    let mut g = c.benchmark_group("ups_wavelet_forward_inverse");
    g.sample_size(10);
    for n in [128i64, 256, 512] {
        let s = surface(6, n);
        let coeffs = 3 * s.grid().vertex_count() as u64;
        g.throughput(Throughput::Elements(coeffs));
        // The thesis' update (`pssurf wavelet`, hole filling) and the stable one (denoising).
        for (name, update) in [
            ("3 levels, thesis update, control points", Update::Thesis),
            ("3 levels, stable update, control points", Update::Stable),
        ] {
            g.bench_with_input(BenchmarkId::new(name, coeffs), &s, |b, s| {
                b.iter(|| {
                    let d = s.wavelet_transform_with(3, update).unwrap();
                    black_box(d.reconstruct())
                })
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("ups_tessellation");
    g.sample_size(10);
    let s = surface(6, 13);
    let triangles = s.grid().triangle_count() as u64 * 4u64.pow(5);
    g.throughput(Throughput::Elements(triangles));
    g.bench_function(
        BenchmarkId::new("level 5, triangles with normals", triangles),
        |b| {
            b.iter_batched(
                TriMesh::default,
                |mut mesh| {
                    s.tessellate(5, &mut mesh);
                    black_box(mesh)
                },
                BatchSize::LargeInput,
            )
        },
    );
    g.finish();
}

criterion_group!(benches, ups);
criterion_main!(benches);
