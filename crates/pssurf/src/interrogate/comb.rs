//! Curvature combs of curves (issue 20, part 1; seed 004, "curve curvature"): at samples along
//! a NURBS (or Bézier) curve, the curvature κ = |c' × c''| / |c'|³ and a tooth of length
//! `scale` · κ along the principal normal, pointing away from the centre of curvature as CAD
//! systems draw it. The tips' polyline is the comb's envelope: where it is smooth, so is the
//! curvature.

use nalgebra::Vector3;

use crate::nurbs::NurbsCurve;

/// One tooth of a comb.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CombTooth {
    /// The curve parameter.
    pub t: f64,
    /// The curve point c(t).
    pub point: Vector3<f64>,
    /// κ(t) (0 where the curve is straight; NaN where c' = 0).
    pub curvature: f64,
    /// The tooth's tip: c(t) − scale · κ · n with n the principal normal (towards the centre
    /// of curvature), so the tooth points outward; the point itself where κ = 0.
    pub tip: Vector3<f64>,
}

/// The comb of `c` with `per_span` samples on every non-empty knot span (ends included) and
/// tooth length `scale` · κ.
pub fn curvature_comb(c: &NurbsCurve, per_span: usize, scale: f64) -> Vec<CombTooth> {
    super::curve_shape::span_samples(c, per_span)
        .into_iter()
        .filter_map(|t| c.derivatives(t).map(|d| tooth(t, d, scale)))
        .collect()
}

/// The combs of the sides of a surface's boundary ([`crate::surface::Domain::sides`]):
/// along each side u(t) = a + t (b − a), `per_side` + 1 teeth of the curve s(u(t)) with
/// c′ = s_x d_x + s_y d_y and c″ = s_xx d_x² + 2 s_xy d_x d_y + s_yy d_y², d = b − a. Teeth
/// where the surface cannot be evaluated are left out.
pub fn boundary_combs(
    surface: &crate::surface::Surface,
    per_side: usize,
    scale: f64,
) -> Vec<Vec<CombTooth>> {
    use crate::surface::ParametricSurface;
    let n = per_side.max(1);
    surface
        .domain()
        .sides()
        .into_iter()
        .map(|(a, b)| {
            let d = b - a;
            (0..=n)
                .filter_map(|k| {
                    let t = k as f64 / n as f64;
                    let uv = if k == n { b } else { a + d * t };
                    let j = surface.jet(uv).ok()?.jet;
                    let d1 = j.dx * d.x + j.dy * d.y;
                    let d2 = j.dxx * (d.x * d.x) + j.dxy * (2.0 * d.x * d.y) + j.dyy * (d.y * d.y);
                    Some(tooth(t, [j.value, d1, d2], scale))
                })
                .collect()
        })
        .collect()
}

/// The tooth length factor that makes the longest tooth `length` long (1 when every curve
/// is straight).
pub fn comb_scale_for(combs: &[Vec<CombTooth>], length: f64) -> f64 {
    let max = combs
        .iter()
        .flatten()
        .map(|t| t.curvature)
        .filter(|k| k.is_finite())
        .fold(0.0, f64::max);
    if max > 0.0 { length / max } else { 1.0 }
}

/// The tooth at t from the curve's point and first two derivatives.
fn tooth(t: f64, [p, d1, d2]: [Vector3<f64>; 3], scale: f64) -> CombTooth {
    let speed2 = d1.norm_squared();
    if !(speed2 > 0.0) {
        return CombTooth {
            t,
            point: p,
            curvature: f64::NAN,
            tip: p,
        };
    }
    let cross = d1.cross(&d2);
    let kappa = cross.norm() / (speed2 * speed2.sqrt());
    // The principal normal: the part of c'' across the tangent.
    let across = d2 - d1 * (d2.dot(&d1) / speed2);
    let tip = match across.try_normalize(1e-300) {
        Some(n) if kappa > 0.0 => p - n * (scale * kappa),
        _ => p,
    };
    CombTooth {
        t,
        point: p,
        curvature: kappa,
        tip,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::*;

    /// The cylinder patch's sides: the base arc has κ = 1/r, the ruling κ = 0, and the
    /// teeth of the arc point away from the axis.
    #[test]
    fn boundary_combs_of_a_cylinder_patch_are_its_arcs_and_rulings() {
        use crate::ps::quadrics::cylinder_patch;
        use crate::surface::Surface;
        let (r, h) = (2.0, 3.0);
        let s = Surface::RationalBezier(cylinder_patch(r, h));
        let combs = boundary_combs(&s, 16, 0.5);
        assert_eq!(combs.len(), 3);
        let mut arcs = 0;
        for side in &combs {
            assert_eq!(side.len(), 17);
            let on_base = side.iter().all(|t| t.point.z.abs() < 1e-12);
            let straight = side.iter().all(|t| t.curvature.abs() < 1e-12);
            if on_base {
                arcs += 1;
                for t in side {
                    assert_near!(t.curvature * r, 1.0, 1e-12);
                    let tip = t.tip.xy().norm();
                    assert_near!(tip, r + 0.5 / r, 1e-12);
                }
            } else if !straight {
                // The diagonal side is an ellipse arc on the cylinder: curved, and every tooth
                // points away from the axis.
                for t in side {
                    assert!(t.tip.xy().norm() >= t.point.xy().norm() - 1e-12);
                }
            }
        }
        assert_eq!(arcs, 1);
        // The auto scale makes the longest tooth the asked length.
        let scale = comb_scale_for(&combs, 0.7);
        let longest = boundary_combs(&s, 16, scale)
            .iter()
            .flatten()
            .map(|t| (t.tip - t.point).norm())
            .fold(0.0, f64::max);
        assert_near!(longest, 0.7, 1e-12);
    }

    /// A circular arc as a rational quadratic NURBS: every tooth has κ = 1/R to 1e-12 and its
    /// tip lies on the circle of radius R + scale/R (outward).
    #[test]
    fn the_comb_of_a_circular_arc_is_constant() {
        let mut r = rng(2010);
        for _ in 0..10 {
            let radius = uniform(&mut r, 0.1, 10.0);
            let half = uniform(&mut r, 0.1, 1.4); // half the arc's angle
            let curve = circular_arc(radius, half);
            let scale = uniform(&mut r, 0.1, 2.0);
            let comb = curvature_comb(&curve, 40, scale);
            assert_eq!(comb.len(), 41);
            for t in &comb {
                assert_near!(t.curvature * radius, 1.0, 1e-12);
                assert_near!(t.point.norm(), radius, 1e-12 * radius);
                assert_near!(t.tip.norm(), radius + scale / radius, 1e-12 * radius);
            }
        }
    }

    /// A straight segment has κ = 0 and tips on the curve; a cubic's comb changes side at its
    /// inflection, where κ = 0.
    #[test]
    fn straight_lines_have_no_teeth_and_inflections_flip_the_comb() {
        let line = NurbsCurve::try_new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Vector3::zeros(), Vector3::new(2.0, 1.0, 0.0)],
            None,
        )
        .unwrap();
        for t in curvature_comb(&line, 5, 1.0) {
            assert_eq!(t.curvature, 0.0);
            assert_eq!(t.tip, t.point);
        }
        // y = x³ − x on [−1, 1] as a Bézier cubic (control points of the polynomial).
        let cubic = cubic_graph_curve();
        let comb = curvature_comb(&cubic, 20, 0.1);
        for t in &comb {
            // Closed form for y = x³ − x at x = t: κ = |6x| / (1 + (3x² − 1)²)^{3/2}.
            let x = t.t;
            let want = (6.0 * x).abs() / (1.0 + (3.0 * x * x - 1.0).powi(2)).powf(1.5);
            assert_near!(t.curvature, want, 1e-12 * want.max(1.0));
            // Outward: below the curve where it bends up (x > 0), above where it bends down.
            let side = t.tip.y - t.point.y;
            if x > 1e-9 {
                assert!(side < 0.0, "x = {x}");
            } else if x < -1e-9 {
                assert!(side > 0.0, "x = {x}");
            }
        }
    }
}
