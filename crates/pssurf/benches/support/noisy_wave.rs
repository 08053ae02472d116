//! The surface of the fairing bench and its profiling example: a noisy wave on a UPS hexagon.

use nalgebra::Point2;
use pssurf::noise::NoiseKind;
use pssurf::ps::Hermite;
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface};

/// 0.3 sin 3x cos 2y as a parametric UPS surface on the standard hexagon of side `size`
/// (about 3 size² vertices), with uniform noise of amplitude 0.001 (seed 5).
pub fn noisy_wave(size: i64) -> Surface {
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
    Surface::try_from(ups.with_noise(0.001, NoiseKind::Uniform, 5)).unwrap()
}
