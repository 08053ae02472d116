//! The built-in demo scene: a curvature-coloured UPS patch and a NURPS paraboloid.

use nalgebra::Point2;
use pssurf::ps::Hermite;
use pssurf::surface::Surface;
use pssurf::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface};

use crate::scene::{Scene, SceneObject, Transform};

/// The lattice of base 1/size whose standard hexagon (side 1) is centred at the origin.
fn centred(size: i64) -> Lattice {
    Lattice {
        base: 1.0 / size as f64,
        origin: Point2::new(-1.0, -0.5 * 3f64.sqrt()),
    }
}

/// A hexagonal UPS patch of side 1 with `size` triangles per side, centred at the origin,
/// interpolating a wave.
pub fn wave_patch(size: i64) -> Surface {
    let lattice = centred(size);
    let grid = UpsGrid::new(
        lattice,
        LatticePolygon::standard(6, size).expect("standard hexagon"),
    )
    .expect("a standard hexagon is a valid lattice polygon");
    let ups = graph_surface(grid, GraphKind::Parametric, |p| {
        let (s, c) = ((2.2 * p.x).sin(), (1.7 * p.y).cos());
        Hermite {
            value: 0.35 * s * c + 0.1 * p.x * p.y,
            dx: 0.35 * 2.2 * (2.2 * p.x).cos() * c + 0.1 * p.y,
            dy: -0.35 * 1.7 * s * (1.7 * p.y).sin() + 0.1 * p.x,
        }
    });
    Surface::try_from(ups).expect("the demo's control values are small")
}

/// The paraboloid z = (x² + y²)/2 over a hexagon of radius 1 as a NURPS (all weights 1; PS
/// splines reproduce quadratics exactly, so this is the quadric itself).
pub fn paraboloid(size: i64) -> Surface {
    let lattice = centred(size);
    let grid = UpsGrid::new(
        lattice,
        LatticePolygon::standard(6, size).expect("standard hexagon"),
    )
    .expect("a standard hexagon is a valid lattice polygon");
    let ups = graph_surface(grid, GraphKind::Rational, |p| Hermite {
        value: 0.5 * (p.x * p.x + p.y * p.y),
        dx: p.x,
        dy: p.y,
    });
    Surface::try_from(ups).expect("the demo's control values are small")
}

/// The demo scene.
pub fn scene() -> Scene {
    let mut bowl = SceneObject::new("NURPS paraboloid", paraboloid(3));
    bowl.transform = Transform {
        translate: [2.6, 0.0, -0.3],
        ..Transform::default()
    };
    Scene {
        objects: vec![SceneObject::new("UPS wave patch", wave_patch(4)), bowl],
    }
}
