//! Rational quadratic Bézier triangles as NURPS (thesis 3.5.2, the optimal representation)
//! and the thesis' quadric patches (3.6): a patch of a cylinder (3.115) and of a sphere
//! (3.118)–(3.122), exact.
//!
//! The optimal representation puts the patch on an equilateral domain triangle V₁V₂V₃ split at
//! its incentre (the angle bisectors), with the PS-triangles of minimal area (3.103)–(3.105):
//! Q_{i,1} = V_i, Q_{i,2} = ⅔ R_{i,i+1} + ⅓ V_i, Q_{i,3} = ⅔ R_{i−1,i} + ⅓ V_i with R the edge
//! midpoints. The homogeneous control points follow from the homogeneous Bézier ordinates by
//! the same combinations, (3.106)–(3.111): w_{i,2} = ⅔ w_{edge} + ⅓ w_{corner} and
//! c_{i,2} = (⅔ w_{edge} b_{edge} + ⅓ w_{corner} b_{corner}) / w_{i,2}.
//!
//! The thesis' tables list c_{i,2} and c_{i,3} as the plain averages ⅔ b_{edge} + ⅓ b_{corner}
//! (e.g. (r, ⅔ r, 0) for the cylinder), which differ from (3.110) wherever the edge weight is
//! not 1; the weights in the tables agree with (3.107)–(3.108). With (3.110) the surface is the
//! Bézier patch exactly (tested); the tables' points put it off the quadric (measured in the
//! tests), so (3.110) is what is implemented.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::{Nurps, PsBasis, PsError, PsTriangleChoice, SplitRule};
use crate::bezier::RationalBezierTriangle;
use crate::geometry::Triangle2;
use crate::triangulation::Triangulation;

/// The equilateral domain triangle of the optimal representation.
pub fn equilateral() -> Triangle2 {
    Triangle2::new(
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.5, 0.75f64.sqrt()),
    )
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

/// The NURPS on [`equilateral`] equal to the rational quadratic Bézier triangle `b` (whose
/// barycentric coordinates become those of the equilateral triangle), by the optimal
/// representation (3.103)–(3.111).
pub fn nurps_from_rational_bezier(
    b: &RationalBezierTriangle<Vector3<f64>>,
) -> Result<Nurps<Vector3<f64>>, PsError> {
    assert_eq!(b.degree(), 2, "the conversion is for quadratic patches");
    let t = equilateral();
    let v = t.v;
    let mut triangles = Vec::new();
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..3 {
        let (next, prev) = ((i + 1) % 3, (i + 2) % 3);
        let unit = |k: usize| {
            let mut l = [0usize; 3];
            l[k] = 1;
            l
        };
        let add = |a: [usize; 3], c: [usize; 3]| [a[0] + c[0], a[1] + c[1], a[2] + c[2]];
        let corner = ordinate(add(unit(i), unit(i)));
        let towards = |k: usize| ordinate(add(unit(i), unit(k)));
        let mid = |a: Point2<f64>, c: Point2<f64>| Point2::from((a.coords + c.coords) * 0.5);
        let q = |k: usize| Point2::from(mid(v[i], v[k]).coords * (2.0 / 3.0) + v[i].coords / 3.0);
        triangles.push(Triangle2::new(v[i], q(next), q(prev)));
        let (pc, wc) = (b.points()[corner], b.weights()[corner]);
        let combine = |e: usize| {
            let (pe, we) = (b.points()[e], b.weights()[e]);
            let w = 2.0 / 3.0 * we + wc / 3.0;
            ((pe * (2.0 / 3.0 * we) + pc * (wc / 3.0)) / w, w)
        };
        let (c2, w2) = combine(towards(next));
        let (c3, w3) = combine(towards(prev));
        points.push([pc, c2, c3]);
        weights.push([wc, w2, w3]);
    }
    let tri =
        Triangulation::try_new(v.to_vec(), vec![[0, 1, 2]]).expect("the equilateral triangle");
    let basis = PsBasis::new(
        tri,
        SplitRule::Incenter,
        &PsTriangleChoice::Given(triangles),
    )?;
    Nurps::new(Arc::new(basis), points, weights)
}

/// The thesis' rational quadratic patch on the cylinder x² + y² = r², 0 ≤ z ≤ h (3.115): corners
/// (r, 0, 0), (0, r, 0), (r, 0, h); weights 1 except w₁₁₀ = w₀₁₁ = √2/2.
pub fn cylinder_patch(r: f64, h: f64) -> RationalBezierTriangle<Vector3<f64>> {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let points = vec![
        Vector3::new(r, 0.0, 0.0),     // 200
        Vector3::new(r, r, 0.0),       // 110
        Vector3::new(r, 0.0, 0.5 * h), // 101
        Vector3::new(0.0, r, 0.0),     // 020
        Vector3::new(r, r, 0.5 * h),   // 011
        Vector3::new(r, 0.0, h),       // 002
    ];
    let weights = vec![1.0, s, 1.0, 1.0, s, 1.0];
    RationalBezierTriangle::try_new(equilateral(), 2, points, weights).expect("a valid patch")
}

/// The thesis' rational quadratic patch on the sphere of radius `r` with span `b` (3.118),
/// (3.122): corners (cos b, ∓sin b, 0) r and the north pole; w₀₁₁ = w₁₀₁ = √2/2, w₁₁₀ = cos² b.
/// It leaves a gap of height [`sphere_gap`] above the equator.
pub fn sphere_patch(r: f64, b: f64) -> RationalBezierTriangle<Vector3<f64>> {
    let (s, c) = b.sin_cos();
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let points = vec![
        Vector3::new(c, -s, 0.0),                    // 200
        Vector3::new(1.0 / c, 0.0, (s / c).powi(2)), // 110
        Vector3::new(c, -s, 1.0),                    // 101
        Vector3::new(c, s, 0.0),                     // 020
        Vector3::new(c, s, 1.0),                     // 011
        Vector3::new(0.0, 0.0, 1.0),                 // 002
    ]
    .into_iter()
    .map(|p| p * r)
    .collect();
    let weights = vec![1.0, c * c, w, 1.0, w, 1.0];
    RationalBezierTriangle::try_new(equilateral(), 2, points, weights).expect("a valid patch")
}

/// The height of the gap between the sphere patch's lower boundary and the equator for span
/// `b` (3.124), relative to the radius: sin² b / (cos² b + 1).
pub fn sphere_gap(b: f64) -> f64 {
    let (s, c) = b.sin_cos();
    s * s / (c * c + 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interrogate::Curvature;
    use crate::surface::ParametricSurface;
    use crate::test_util::*;

    /// The NURPS equals the Bézier patch at the same barycentric coordinates.
    fn same_surface(b: &RationalBezierTriangle<Vector3<f64>>, n: &Nurps<Vector3<f64>>, seed: u64) {
        let mut r = rng(seed);
        let t = equilateral();
        for _ in 0..50 {
            let tau = random_bary(&mut r);
            let p = t.point(tau);
            let ours = ParametricSurface::point(n, p).unwrap();
            let theirs = b.eval_bary(tau).unwrap();
            assert!(
                (ours - theirs).norm() < 1e-12 * theirs.norm().max(1.0),
                "{ours} vs {theirs}"
            );
        }
    }

    #[test]
    fn the_optimal_representation_is_the_same_surface() {
        let mut r = rng(1720);
        for k in 0..20 {
            let points = (0..6).map(|_| random_vec3(&mut r)).collect();
            let weights = (0..6).map(|_| uniform(&mut r, 0.2, 5.0)).collect();
            let b = RationalBezierTriangle::try_new(equilateral(), 2, points, weights).unwrap();
            same_surface(&b, &nurps_from_rational_bezier(&b).unwrap(), 1730 + k);
        }
    }

    #[test]
    fn the_cylinder_patch_is_on_the_cylinder_with_the_thesis_weights() {
        let mut r = rng(1721);
        for _ in 0..5 {
            let (rad, h) = (uniform(&mut r, 0.1, 10.0), uniform(&mut r, 0.1, 10.0));
            let b = cylinder_patch(rad, h);
            let n = nurps_from_rational_bezier(&b).unwrap();
            same_surface(&b, &n, 1722);
            // The thesis' table of weights: 1, (√2 + 1)/3, 1 / 1, (√2 + 1)/3, (√2 + 1)/3 /
            // 1, 1, (√2 + 1)/3.
            let t = (2f64.sqrt() + 1.0) / 3.0;
            let w = n.weights();
            assert_near!(w[0][1], t, 1e-15);
            assert_near!(w[0][2], 1.0, 1e-15);
            assert_near!(w[1][1], t, 1e-15);
            assert_near!(w[1][2], t, 1e-15);
            assert_near!(w[2][1], 1.0, 1e-15);
            assert_near!(w[2][2], t, 1e-15);
            let t2 = equilateral();
            let mut worst_table = 0.0f64;
            for _ in 0..100 {
                let p = t2.point(random_bary(&mut r));
                let j = n.jet(p).unwrap().jet;
                assert_near!(j.value.xy().norm(), rad, 1e-12);
                let c = Curvature::from_jet(&j).unwrap();
                assert!(c.gaussian.abs() < 1e-10 / (rad * rad));
                assert_near!(c.mean.abs(), 0.5 / rad, 1e-10);
                // The table's points (plain averages) put the surface off the cylinder.
                let mut pts = n.points().to_vec();
                pts[0][1] = Vector3::new(rad, 2.0 / 3.0 * rad, 0.0);
                let table = Nurps::new(n.basis().clone(), pts, n.weights().to_vec()).unwrap();
                let q = ParametricSurface::point(&table, p).unwrap();
                worst_table = worst_table.max((q.xy().norm() - rad).abs() / rad);
            }
            assert!(
                worst_table > 1e-3,
                "the table's c_1,2 is off by {worst_table}"
            );
        }
    }

    #[test]
    fn the_sphere_patch_is_on_the_sphere_and_its_gap_is_3_124() {
        let mut r = rng(1723);
        for span in [std::f64::consts::PI / 6.0, std::f64::consts::PI / 4.0, 0.3] {
            let rad = uniform(&mut r, 0.5, 5.0);
            let b = sphere_patch(rad, span);
            let n = nurps_from_rational_bezier(&b).unwrap();
            same_surface(&b, &n, 1724);
            let t = equilateral();
            for _ in 0..100 {
                let p = t.point(random_bary(&mut r));
                let j = n.jet(p).unwrap().jet;
                assert_near!(j.value.norm(), rad, 1e-12);
                let c = Curvature::from_jet(&j).unwrap();
                assert_near!(c.gaussian, 1.0 / (rad * rad), 1e-10);
            }
            // The lower boundary (τ₃ = 0) rises at most (3.124) above the equator.
            let top = (0..=1000)
                .map(|k| {
                    let a = k as f64 / 1000.0;
                    b.eval_bary([a, 1.0 - a, 0.0]).unwrap().z
                })
                .fold(0.0f64, f64::max);
            assert_near!(top, rad * sphere_gap(span), 1e-6);
        }
        // b = π/6: the thesis' table of weights, row 1: 1, 5/6, (√2 + 1)/3.
        let n = nurps_from_rational_bezier(&sphere_patch(1.0, std::f64::consts::PI / 6.0)).unwrap();
        assert_near!(n.weights()[0][1], 5.0 / 6.0, 1e-15);
        assert_near!(n.weights()[0][2], (2f64.sqrt() + 1.0) / 3.0, 1e-15);
    }
}
