//! Loop subdivision (issue 20's goal: one step of a 1M-triangle mesh in under 0.5 s on 2
//! cores): a closed mesh (the octahedron refined to 2^20 triangles) and an open lattice of
//! about 1M triangles, one step each; √3 and the butterfly on the same closed mesh.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use pssurf::subdivision::{Mesh, SurfaceScheme};
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn octahedron() -> Mesh {
    let p = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    Mesh {
        positions: p.iter().map(|&c| Vector3::from(c)).collect(),
        triangles: vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    }
}

fn lattice(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 + 0.5 * j as f64, 0.866 * j as f64);
            positions.push(Vector3::new(x, y, (0.01 * x).sin() * (0.02 * y).cos()));
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
            triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    Mesh {
        positions,
        triangles,
    }
}

fn one_step(c: &mut Criterion) {
    let mut closed = octahedron();
    for _ in 0..9 {
        closed = SurfaceScheme::Loop.step(&closed).unwrap();
    }
    assert_eq!(closed.triangles.len(), 1 << 21);
    let mut half = octahedron();
    for _ in 0..8 {
        half = SurfaceScheme::Loop.step(&half).unwrap();
    }
    let open = lattice(707); // 999,698 triangles
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
