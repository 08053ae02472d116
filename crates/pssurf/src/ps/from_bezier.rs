//! Rational quadratic Bézier triangles as NURPS (thesis 3.5): the identical representation on
//! the given domain triangle (3.5.1) and the optimal one on an equilateral triangle (3.5.2).
//!
//! **Identical** (3.93)–(3.95): the triangle is split at its centroid Z and its edge midpoints
//! R; the PS-triangle of V_i is (V_i, R_{i,j}, R_{k,i}) and its control points and weights are
//! the Bézier ordinates there: c_{i,1} = b at V_i, c_{i,2} = b at R_{i,j}, c_{i,3} = b at
//! R_{k,i}. Proposition 3.1 puts the PS-points inside these triangles.
//!
//! **Optimal** (3.103)–(3.111): an equilateral domain triangle V₁V₂V₃ split at its incentre,
//! with the PS-triangles of minimal area: Q_{i,1} = V_i, Q_{i,2} = ⅔ R_{i,i+1} + ⅓ V_i,
//! Q_{i,3} = ⅔ R_{i−1,i} + ⅓ V_i. The homogeneous control points follow from the homogeneous
//! Bézier ordinates by the same combinations: w_{i,2} = ⅔ w_{edge} + ⅓ w_{corner} and
//! c_{i,2} = (⅔ w_{edge} b_{edge} + ⅓ w_{corner} b_{corner}) / w_{i,2}.
//!
//! The thesis' tables in 3.6 list c_{i,2} and c_{i,3} as the plain averages
//! ⅔ b_{edge} + ⅓ b_{corner} (e.g. (r, ⅔ r, 0) for the cylinder), which differ from (3.110)
//! wherever the edge weight is not 1; the weights in the tables agree with (3.107)–(3.108).
//! With (3.110) the surface is the Bézier patch exactly (tested); the tables' points put it off
//! the quadric (measured in the tests of [`super::quadrics`]), so (3.110) is what is used.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::{Nurps, PsBasis, PsError, PsTriangleChoice, SplitRule};
use crate::bezier::RationalBezierTriangle;
use crate::geometry::Triangle2;
use crate::triangulation::Triangulation;

/// The equilateral domain triangle of the optimal representation: (0, 0), (1, 0), (½, √3/2).
pub fn equilateral() -> Triangle2 {
    Triangle2::new(
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.5, 0.75f64.sqrt()),
    )
}

/// Which quadratic patches the conversions take.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ConversionError {
    /// The patch is not quadratic.
    #[error("only rational quadratic Bézier triangles convert to NURPS; this one has degree {0}")]
    NotQuadratic(usize),
    /// The PS basis or the NURPS could not be built (a degenerate domain triangle).
    #[error(transparent)]
    Ps(#[from] PsError),
}

/// The storage index of the quadratic ordinate with multi-index `l` (order of
/// [`crate::bezier::index::multi_indices`]: 200, 110, 101, 020, 011, 002).
fn ordinate(l: [usize; 3]) -> usize {
    match l {
        [2, 0, 0] => 0,
        [1, 1, 0] => 1,
        [1, 0, 1] => 2,
        [0, 2, 0] => 3,
        [0, 1, 1] => 4,
        _ => 5,
    }
}

/// The ordinates of corner `i` of a quadratic patch: (corner, towards i + 1, towards i − 1).
fn corner_ordinates(i: usize) -> [usize; 3] {
    let unit = |k: usize| {
        let mut l = [0usize; 3];
        l[k] = 1;
        l
    };
    let add = |a: [usize; 3], c: [usize; 3]| [a[0] + c[0], a[1] + c[1], a[2] + c[2]];
    let towards = |k: usize| ordinate(add(unit(i), unit(k)));
    [towards(i), towards((i + 1) % 3), towards((i + 2) % 3)]
}

/// A homogeneous control point (w c, w) kept as the pair (c, w).
#[derive(Clone, Copy, Debug)]
struct Weighted {
    point: Vector3<f64>,
    weight: f64,
}

impl Weighted {
    /// The homogeneous combination Σ a_k (w_k c_k, w_k), back as (c, w).
    fn combine(terms: &[(f64, Weighted)]) -> Weighted {
        let weight: f64 = terms.iter().map(|(a, h)| a * h.weight).sum();
        let point = terms.iter().fold(Vector3::zeros(), |acc, (a, h)| {
            acc + h.point * (a * h.weight)
        });
        Weighted {
            point: point / weight,
            weight,
        }
    }
}

/// The NURPS on `domain` whose control triangle at each vertex interpolates, on the PS-triangle
/// the basis ended with, the homogeneous affine map with values `values[i][k]` at the points
/// `at[i][k]` (the basis may have reordered a clockwise triangle).
fn nurps_on(
    domain: Triangle2,
    rule: SplitRule,
    at: Vec<[Point2<f64>; 3]>,
    values: Vec<[Weighted; 3]>,
) -> Result<Nurps<Vector3<f64>>, PsError> {
    let triangles: Vec<Triangle2> = at
        .iter()
        .map(|q| Triangle2::new(q[0], q[1], q[2]))
        .collect();
    let tri = Triangulation::try_new(domain.v.to_vec(), vec![[0, 1, 2]])
        .map_err(|_| PsError::DegeneratePsTriangle { vertex: 0 })?;
    let basis = PsBasis::new(tri, rule, &PsTriangleChoice::Given(triangles.clone()))?;
    let mut points = Vec::with_capacity(3);
    let mut weights = Vec::with_capacity(3);
    for (i, given) in triangles.iter().enumerate() {
        let used = basis.ps_triangle(i);
        let h: [Weighted; 3] = std::array::from_fn(|k| {
            let tau = given.bary(used.v[k]);
            Weighted::combine(&[
                (tau[0], values[i][0]),
                (tau[1], values[i][1]),
                (tau[2], values[i][2]),
            ])
        });
        points.push(h.map(|w| w.point));
        weights.push(h.map(|w| w.weight));
    }
    Nurps::new(Arc::new(basis), points, weights)
}

/// The identical representation (3.93)–(3.95): the NURPS on the patch's own domain triangle,
/// split at its centroid, whose control points and weights are the Bézier ordinates.
pub fn nurps_identical(
    b: &RationalBezierTriangle<Vector3<f64>>,
) -> Result<Nurps<Vector3<f64>>, ConversionError> {
    if b.degree() != 2 {
        return Err(ConversionError::NotQuadratic(b.degree()));
    }
    let v = b.domain().v;
    let mid = |a: Point2<f64>, c: Point2<f64>| Point2::from((a.coords + c.coords) * 0.5);
    let mut at = Vec::new();
    let mut values = Vec::new();
    for i in 0..3 {
        let (next, prev) = ((i + 1) % 3, (i + 2) % 3);
        at.push([v[i], mid(v[i], v[next]), mid(v[i], v[prev])]);
        values.push(corner_ordinates(i).map(|k| Weighted {
            point: b.points()[k],
            weight: b.weights()[k],
        }));
    }
    Ok(nurps_on(*b.domain(), SplitRule::Centroid, at, values)?)
}

/// The optimal representation (3.103)–(3.111): the NURPS on [`equilateral`] equal to `b` (whose
/// barycentric coordinates become those of the equilateral triangle).
pub fn nurps_optimal(
    b: &RationalBezierTriangle<Vector3<f64>>,
) -> Result<Nurps<Vector3<f64>>, ConversionError> {
    if b.degree() != 2 {
        return Err(ConversionError::NotQuadratic(b.degree()));
    }
    let t = equilateral();
    let v = t.v;
    let mut at = Vec::new();
    let mut values = Vec::new();
    for i in 0..3 {
        let (next, prev) = ((i + 1) % 3, (i + 2) % 3);
        let mid = |a: Point2<f64>, c: Point2<f64>| Point2::from((a.coords + c.coords) * 0.5);
        let q = |k: usize| Point2::from(mid(v[i], v[k]).coords * (2.0 / 3.0) + v[i].coords / 3.0);
        at.push([v[i], q(next), q(prev)]);
        let [corner, towards_next, towards_prev] = corner_ordinates(i).map(|k| Weighted {
            point: b.points()[k],
            weight: b.weights()[k],
        });
        let third = |edge: Weighted| Weighted::combine(&[(2.0 / 3.0, edge), (1.0 / 3.0, corner)]);
        values.push([corner, third(towards_next), third(towards_prev)]);
    }
    Ok(nurps_on(t, SplitRule::Incenter, at, values)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::ParametricSurface;
    use crate::test_util::*;

    /// The NURPS equals the Bézier patch at the same barycentric coordinates of `on`.
    pub(crate) fn same_surface(
        b: &RationalBezierTriangle<Vector3<f64>>,
        n: &Nurps<Vector3<f64>>,
        on: &Triangle2,
        seed: u64,
    ) {
        let mut r = rng(seed);
        for _ in 0..50 {
            let tau = random_bary(&mut r);
            let ours = ParametricSurface::point(n, on.point(tau)).unwrap();
            let theirs = b.eval_bary(tau).unwrap();
            assert!(
                (ours - theirs).norm() < 1e-12 * theirs.norm().max(1.0),
                "{ours} vs {theirs}"
            );
        }
    }

    fn random_patch(
        r: &mut rand_chacha::ChaCha8Rng,
        domain: Triangle2,
    ) -> RationalBezierTriangle<Vector3<f64>> {
        let points = (0..6).map(|_| random_vec3(r)).collect();
        let weights = (0..6).map(|_| uniform(r, 0.2, 5.0)).collect();
        RationalBezierTriangle::try_new(domain, 2, points, weights).unwrap()
    }

    #[test]
    fn the_optimal_representation_is_the_same_surface() {
        let mut r = rng(1720);
        for k in 0..20 {
            let b = random_patch(&mut r, equilateral());
            same_surface(&b, &nurps_optimal(&b).unwrap(), &equilateral(), 1730 + k);
        }
    }

    /// On random domain triangles of both orientations: the same surface, and the control
    /// points and weights are the Bézier ordinates (3.94)–(3.95).
    #[test]
    fn the_identical_representation_is_the_same_surface_with_the_same_ordinates() {
        let mut r = rng(1740);
        for k in 0..40 {
            let mut domain = random_triangle(&mut r);
            if k % 2 == 1 {
                domain = Triangle2::new(domain.v[0], domain.v[2], domain.v[1]);
            }
            let b = random_patch(&mut r, domain);
            let n = nurps_identical(&b).unwrap();
            same_surface(&b, &n, &domain, 1750 + k);
            for i in 0..3 {
                let (c, w) = (n.points()[i], n.weights()[i]);
                for k in corner_ordinates(i) {
                    let j = (0..3)
                        .find(|&j| (c[j] - b.points()[k]).norm() < 1e-12)
                        .expect("every ordinate at V_i is a control point of V_i");
                    assert_near!(w[j], b.weights()[k], 1e-12);
                }
            }
        }
        assert!(matches!(
            nurps_identical(&RationalBezierTriangle::from_polynomial(
                &crate::bezier::BezierTriangle::try_new(
                    equilateral(),
                    3,
                    vec![Vector3::zeros(); 10]
                )
                .unwrap()
            )),
            Err(ConversionError::NotQuadratic(3))
        ));
    }
}
