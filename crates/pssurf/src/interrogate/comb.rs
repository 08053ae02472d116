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

/// The comb of a polyline, a curve known only by its points (a subdivided polygon, a traced
/// curve written as points): at each point the curvature of the circle through it and its
/// two neighbours, κ = 2 |a × b| / (|a| |b| |a − b|) with a, b the chords to them (Menger's
/// curvature, exact for points on a circle), the tooth pointing away from that circle's
/// centre. An open polyline's end points take the circle of the first (last) three points;
/// a closed one wraps around. The parameter t is the arc length along the chords. Repeated
/// consecutive points are passed over; fewer than three distinct points give no teeth.
pub fn polyline_comb(points: &[Vector3<f64>], closed: bool, scale: f64) -> Vec<CombTooth> {
    let mut p: Vec<Vector3<f64>> = Vec::with_capacity(points.len());
    for q in points {
        if p.last() != Some(q) {
            p.push(*q);
        }
    }
    if closed && p.len() > 1 && p.first() == p.last() {
        p.pop();
    }
    let n = p.len();
    if n < 3 {
        return Vec::new();
    }
    let mut t = 0.0;
    (0..n)
        .map(|k| {
            if k > 0 {
                t += (p[k] - p[k - 1]).norm();
            }
            // The three points whose circle gives the curvature at k.
            let (prev, here, next) = match (closed, k) {
                (true, _) => ((k + n - 1) % n, k, (k + 1) % n),
                (false, 0) => (0, 1, 2),
                (false, k) if k == n - 1 => (n - 3, n - 2, n - 1),
                (false, k) => (k - 1, k, k + 1),
            };
            let (curvature, outward) = circle_through(p[prev], p[here], p[next], p[k]);
            CombTooth {
                t,
                point: p[k],
                curvature,
                tip: p[k] + outward * (scale * curvature),
            }
        })
        .collect()
}

/// The curvature of the circle through a, b, c (0 when they are collinear) and the unit
/// direction from its centre towards `at` (zero when collinear).
fn circle_through(
    a: Vector3<f64>,
    b: Vector3<f64>,
    c: Vector3<f64>,
    at: Vector3<f64>,
) -> (f64, Vector3<f64>) {
    let (u, v) = (a - b, c - b);
    let w = u.cross(&v);
    let w2 = w.norm_squared();
    if !(w2 > 0.0) {
        return (0.0, Vector3::zeros());
    }
    let curvature = 2.0 * w.norm() / (u.norm() * v.norm() * (u - v).norm());
    // The circumcentre: b + (|u|² v − |v|² u) × w / (2 |w|²).
    let centre = b + (v * u.norm_squared() - u * v.norm_squared()).cross(&w) / (2.0 * w2);
    let outward = (at - centre)
        .try_normalize(0.0)
        .unwrap_or_else(Vector3::zeros);
    (curvature, outward)
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

    /// Points on a circle of random centre, radius, plane and spacing: every tooth has
    /// κ = 1/R to 1e-12 and its tip on the circle of radius R + scale/R (outward), open or
    /// closed; collinear points have none; repeated points are passed over.
    #[test]
    fn polyline_combs_of_circles_are_exact() {
        use crate::test_util::{random_vec3, rng, uniform};
        let mut rng = rng(31);
        for case in 0..200 {
            let r = uniform(&mut rng, 0.01, 100.0);
            let centre = random_vec3(&mut rng) * 10.0;
            let e1 = (random_vec3(&mut rng) + Vector3::new(0.0, 0.0, 2.0)).normalize();
            let e2 = e1.cross(&Vector3::new(0.3, -0.2, 0.9)).normalize();
            let mut angle: f64 = 0.0;
            let mut points = Vec::new();
            while angle < 5.5 {
                points.push(centre + (e1 * angle.cos() + e2 * angle.sin()) * r);
                angle += uniform(&mut rng, 0.05, 0.55);
            }
            points.insert(2, points[2]);
            let scale = 0.5 * r * r;
            for closed in [false, true] {
                let comb = polyline_comb(&points, closed, scale);
                assert_eq!(comb.len(), points.len() - 1, "case {case}");
                for tooth in &comb {
                    let rel = (tooth.curvature * r - 1.0).abs();
                    assert!(rel < 1e-12, "case {case}: κR = {}", tooth.curvature * r);
                    let tip_r = (tooth.tip - centre).norm();
                    assert!((tip_r - (r + scale / r)).abs() < 1e-12 * (r + scale / r));
                }
            }
        }
        let line: Vec<Vector3<f64>> = (0..5).map(|k| Vector3::new(k as f64, 2.0, 0.0)).collect();
        assert!(
            polyline_comb(&line, false, 1.0)
                .iter()
                .all(|t| t.curvature == 0.0 && t.tip == t.point)
        );
        assert!(polyline_comb(&line[..2], false, 1.0).is_empty());
    }
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
