//! Times the phases of fairing a noisy UPS hexagon (the `fair` bench's surface), for
//! profiling: `cargo run --release -p pssurf --example profile_fair -- SIZE [WEIGHT]` (182:
//! about 100k vertices, 577: about 1M).

use std::time::Instant;

use nalgebra::Point2;
use pssurf::noise::NoiseKind;
use pssurf::ps::{Energy, FairOptions, Hermite, fair};
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface};

fn main() {
    let size: i64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(182);
    let weight: f64 = std::env::args()
        .nth(2)
        .and_then(|a| a.parse().ok())
        .unwrap_or(0.1);
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
    let s = Surface::from(ups.with_noise(0.001, NoiseKind::Uniform, 5));
    let basis = s.ps_basis().unwrap().clone();
    println!("{} vertices", basis.triangulation().vertex_count());
    let t = Instant::now();
    let q = basis.energy_matrix(Energy::HessianJumps);
    println!(
        "energy matrix: {:.3} s, {} blocks",
        t.elapsed().as_secs_f64(),
        q.block_count()
    );
    for _ in 0..2 {
        let t = Instant::now();
        let f = fair(
            &s,
            &FairOptions {
                weight,
                ..FairOptions::default()
            },
        )
        .unwrap();
        println!(
            "fair: {:.3} s ({}), residual {:.2e}, energy {:.4e} -> {:.4e}",
            t.elapsed().as_secs_f64(),
            f.solver,
            f.normal_residual,
            f.energy_before,
            f.energy_after
        );
    }
}
