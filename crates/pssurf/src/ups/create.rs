//! UPS surfaces over a lattice polygon made from a height function z = f(x, y) by Hermite
//! interpolation of its value and gradient at every vertex (thesis (4.9)): the graph as a
//! functional, parametric or rational (all weights 1) surface. Quadratic f are reproduced
//! exactly, so this also makes the paraboloids and other graph quadrics.

use nalgebra::{Point2, Vector3};

use super::{Ups, UpsGrid};
#[cfg(feature = "expr")]
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
/// finite value or gradient, or where they make a control value larger than ±1e60.
#[cfg(feature = "expr")]
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
    let surface = graph_surface(grid, kind, |p| {
        let d = formula
            .eval(p.x, p.y)
            .expect("checked at every vertex above");
        Hermite {
            value: d.v,
            dx: d.dx,
            dy: d.dy,
        }
    });
    match surface.first_unusable_vertex() {
        Some(p) => Err(ExprError::TooLarge { x: p.x, y: p.y }),
        None => Ok(surface),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{ParametricSurface, Surface};
    use crate::test_util::*;
    use crate::ups::{Lattice, LatticePolygon};

    const KINDS: [GraphKind; 3] = [
        GraphKind::Functional,
        GraphKind::Parametric,
        GraphKind::Rational,
    ];

    fn grid(sides: usize, r: &mut rand_chacha::ChaCha8Rng) -> UpsGrid {
        let lattice = Lattice {
            base: uniform(r, 0.1, 0.4),
            origin: Point2::new(uniform(r, -1.0, 0.0), uniform(r, -1.0, 0.0)),
        };
        UpsGrid::new(lattice, LatticePolygon::standard(sides, 3).unwrap()).unwrap()
    }

    /// max |s(p) − (x, y, q(x, y))| at a random point of every triangle.
    fn error(s: &Surface, q: impl Fn(f64, f64) -> f64, r: &mut rand_chacha::ChaCha8Rng) -> f64 {
        let tri = s.ps_basis().unwrap().triangulation();
        (0..tri.triangle_count())
            .map(|t| {
                let v = tri.triangle(t);
                let b = random_bary(r);
                let c: Point2<f64> = (tri.vertex(v[0]).coords * b[0]
                    + tri.vertex(v[1]).coords * b[1]
                    + tri.vertex(v[2]).coords * b[2])
                    .into();
                (s.point(c).unwrap() - Vector3::new(c.x, c.y, q(c.x, c.y))).norm()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn every_kind_reproduces_random_quadrics_exactly() {
        let mut r = rng(61);
        for sides in 3..=6 {
            for kind in KINDS {
                let a: [f64; 6] = std::array::from_fn(|_| uniform(&mut r, -2.0, 2.0));
                let q = move |x: f64, y: f64| {
                    a[0] * x * x + a[1] * x * y + a[2] * y * y + a[3] * x + a[4] * y + a[5]
                };
                let s = Surface::try_from(graph_surface(grid(sides, &mut r), kind, |p| Hermite {
                    value: q(p.x, p.y),
                    dx: 2.0 * a[0] * p.x + a[1] * p.y + a[3],
                    dy: a[1] * p.x + 2.0 * a[2] * p.y + a[4],
                }))
                .unwrap();
                let e = error(&s, q, &mut r);
                assert!(e < 1e-12, "{kind:?}, {sides} sides: {e}");
            }
        }
    }

    #[cfg(feature = "expr")]
    #[test]
    fn a_formula_gives_the_same_surface_and_bad_formulas_are_errors() {
        let mut r = rng(62);
        for sides in 3..=6 {
            let g = grid(sides, &mut r);
            let f = HeightFunction::parse("0.7*x^2 - 1.2*x*y + 0.3*y^2 + x - 2").unwrap();
            let q = |x: f64, y: f64| 0.7 * x * x - 1.2 * x * y + 0.3 * y * y + x - 2.0;
            for kind in KINDS {
                let s = Surface::try_from(graph_surface_from_formula(g.clone(), kind, &f).unwrap())
                    .unwrap();
                assert!(error(&s, q, &mut r) < 1e-12, "{kind:?} {sides}");
            }
            let bad = HeightFunction::parse("ln(x - 100)").unwrap();
            assert!(matches!(
                graph_surface_from_formula(g.clone(), GraphKind::Parametric, &bad),
                Err(ExprError::NotFinite { .. })
            ));
            // Finite but beyond the control values a surface may hold (±1e60): refused
            // with the first vertex named, for every kind.
            let huge = HeightFunction::parse("10^61 + x").unwrap();
            for kind in KINDS {
                let e = graph_surface_from_formula(g.clone(), kind, &huge).unwrap_err();
                assert!(matches!(e, ExprError::TooLarge { .. }), "{kind:?}: {e}");
            }
        }
    }
}
