//! Fairing (issue 18's goal: a 100k-vertex UPS surface in under 5 s on 2 cores): a noisy UPS
//! hexagon faired with weight 0.1 by the Hessian jumps (the thesis' energy, the default) and by
//! the thin-plate energy, at about 10k and 100k vertices.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Point2;
use pssurf::noise::NoiseKind;
use pssurf::ps::{Energy, FairOptions, Hermite, fair};
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface};
use std::hint::black_box;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A noisy wave on the standard hexagon of side `size`.
fn noisy_wave(size: i64) -> Surface {
    let polygon = LatticePolygon::standard(6, size).unwrap();
    let lattice = Lattice {
        base: 1.0 / size as f64,
        origin: Point2::origin(),
    };
    let grid = UpsGrid::new(lattice, polygon).unwrap();
    let ups = graph_surface(grid, GraphKind::Parametric, |p| {
        let (s, c) = (3.0 * p.x).sin_cos();
        Hermite {
            value: 0.3 * s * (2.0 * p.y).cos(),
            dx: 0.9 * c * (2.0 * p.y).cos(),
            dy: -0.6 * s * (2.0 * p.y).sin(),
        }
    });
    Surface::from(ups.with_noise(0.001, NoiseKind::Uniform, 5))
}

fn fairing(c: &mut Criterion) {
    let mut g = c.benchmark_group("fair");
    g.sample_size(10);
    for size in [58, 182] {
        let s = noisy_wave(size);
        let n = s.ps_basis().unwrap().triangulation().vertex_count();
        for (name, energy) in [
            ("jumps", Energy::HessianJumps),
            ("thin plate", Energy::ThinPlate),
        ] {
            let opts = FairOptions {
                weight: 0.1,
                energy,
            };
            g.bench_function(format!("{n} vertices, {name}"), |b| {
                b.iter(|| black_box(fair(&s, &opts).unwrap().energy_after))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, fairing);
criterion_main!(benches);
