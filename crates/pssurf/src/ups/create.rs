//! UPS surfaces over a lattice polygon made from a height function z = f(x, y) by Hermite
//! interpolation of its value and gradient at every vertex (thesis (4.9)): the graph as a
//! functional, parametric or rational (all weights 1) surface. Quadratic f are reproduced
//! exactly, so this also makes the paraboloids and other graph quadrics.

use nalgebra::{Point2, Vector3};

use super::{Ups, UpsGrid};
use crate::expr::{ExprError, HeightFunction};
use crate::ps::Hermite;
use crate::surface::UpsSurface;

/// Which kind of surface the graph becomes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GraphKind {
    /// z = s(x, y), one value per PS-triangle corner.
    Functional,
    /// (x, y, s(x, y)) with control points in R³.
    #[default]
    Parametric,
    /// The parametric surface as a NURPS with all weights 1 (so that weights can be edited).
    Rational,
}

/// The UPS surface interpolating the graph of f (value and gradient) at every vertex of
/// `grid`.
pub fn graph_surface(
    grid: UpsGrid,
    kind: GraphKind,
    f: impl Fn(Point2<f64>) -> Hermite<f64> + Sync,
) -> UpsSurface {
    let lift = |p: Point2<f64>| {
        let h = f(p);
        Hermite {
            value: Vector3::new(p.x, p.y, h.value),
            dx: Vector3::new(1.0, 0.0, h.dx),
            dy: Vector3::new(0.0, 1.0, h.dy),
        }
    };
    match kind {
        GraphKind::Functional => UpsSurface::Functional(Ups::hermite(grid, f)),
        GraphKind::Parametric => UpsSurface::Parametric(Ups::hermite(grid, lift)),
        GraphKind::Rational => {
            let points = Ups::hermite(grid.clone(), lift).vertex_values();
            let weights = vec![[1.0; 3]; points.len()];
            UpsSurface::Rational(Ups::rational(grid, points, weights).expect("weights are 1"))
        }
    }
}

/// [`graph_surface`] of a formula; an error names the first vertex where the formula has no
/// finite value or gradient.
pub fn graph_surface_from_formula(
    grid: UpsGrid,
    kind: GraphKind,
    formula: &HeightFunction,
) -> Result<UpsSurface, ExprError> {
    let lattice = *grid.lattice();
    for s in grid.real_slots() {
        let p = lattice.point(grid.lattice_point(s));
        formula.eval(p.x, p.y)?;
    }
    Ok(graph_surface(grid, kind, |p| {
        let d = formula
            .eval(p.x, p.y)
            .expect("checked at every vertex above");
        Hermite {
            value: d.v,
            dx: d.dx,
            dy: d.dy,
        }
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{ParametricSurface, Surface};
    use crate::ups::{Lattice, LatticePolygon};

    #[test]
    fn every_kind_reproduces_a_quadric_exactly_and_bad_formulas_are_errors() {
        let lattice = Lattice {
            base: 0.25,
            origin: Point2::new(-0.5, -0.4),
        };
        for sides in 3..=6 {
            let grid = UpsGrid::new(lattice, LatticePolygon::standard(sides, 3).unwrap()).unwrap();
            let q = HeightFunction::parse("0.7*x^2 - 1.2*x*y + 0.3*y^2 + x - 2").unwrap();
            for kind in [
                GraphKind::Functional,
                GraphKind::Parametric,
                GraphKind::Rational,
            ] {
                let s = Surface::from(graph_surface_from_formula(grid.clone(), kind, &q).unwrap());
                let g = s.general();
                let tri = g.basis().triangulation();
                for t in 0..tri.triangle_count() {
                    let v = tri.triangle(t);
                    let c = (tri.vertex(v[0]).coords * 0.2
                        + tri.vertex(v[1]).coords * 0.3
                        + tri.vertex(v[2]).coords * 0.5)
                        .into();
                    let p = g.point(c).unwrap();
                    let (x, y) = (c.x, c.y);
                    let z = 0.7 * x * x - 1.2 * x * y + 0.3 * y * y + x - 2.0;
                    assert!(
                        (p - Vector3::new(x, y, z)).norm() < 1e-12,
                        "{kind:?} {sides}"
                    );
                }
            }
            let bad = HeightFunction::parse("ln(x)").unwrap();
            assert!(matches!(
                graph_surface_from_formula(grid, GraphKind::Parametric, &bad),
                Err(ExprError::NotFinite { .. })
            ));
        }
    }
}
