//! Loop subdivision (issue 20's goal: one step of a 1M-triangle mesh in under 0.5 s on 2
//! cores): a closed mesh (the octahedron refined to 2^20 triangles) and an open lattice of
//! about 1M triangles, one step each; √3 and the butterfly on the same closed mesh.

use criterion::{Criterion, criterion_group, criterion_main};
use pssurf::subdivision::{Mesh, SurfaceScheme};
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn one_step(c: &mut Criterion) {
    let mut closed = Mesh::octahedron();
    for _ in 0..9 {
        closed = SurfaceScheme::Loop.step(&closed).unwrap();
    }
    assert_eq!(closed.triangles.len(), 1 << 21);
    let mut half = Mesh::octahedron();
    for _ in 0..8 {
        half = SurfaceScheme::Loop.step(&half).unwrap();
    }
    let open = Mesh::lattice(707, |x, y| (0.01 * x).sin() * (0.02 * y).cos()); // 999,698 triangles
    let mut g = c.benchmark_group("mesh_one_step");
    g.sample_size(10);
    g.bench_function("loop_524k_closed", |b| {
        b.iter(|| black_box(SurfaceScheme::Loop.step(&half).unwrap()))
    });
    g.bench_function("loop_1m_open", |b| {
        b.iter(|| black_box(SurfaceScheme::Loop.step(&open).unwrap()))
    });
    g.bench_function("loop_2m_closed", |b| {
        b.iter(|| black_box(SurfaceScheme::Loop.step(&closed).unwrap()))
    });
    g.bench_function("sqrt3_1m_open", |b| {
        b.iter(|| black_box(SurfaceScheme::Sqrt3.step(&open).unwrap()))
    });
    g.bench_function("butterfly_1m_open", |b| {
        b.iter(|| black_box(SurfaceScheme::Butterfly.step(&open).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, one_step);
criterion_main!(benches);
