//! Plane sections: the curve in which a plane through a surface point cuts the surface,
//! traced from that point in both directions. With a plane that contains the normal this is
//! a normal section, whose curvature at the point is the normal curvature in the plane's
//! tangent direction (the probe of seed 003, section 3).
//!
//! The curve is the zero set of f(u, v) = (s(u, v) − p₀)·m in the parameter domain (m the
//! plane's normal). It is followed by predictor–corrector continuation: a step along the
//! domain tangent (−f_v, f_u) of the zero set, sized to move `step` in space, then Newton
//! steps along ∇f back onto f = 0 (to 1e-13 of the surface's size), halving the step when
//! the corrector does not converge or leaves the domain.

use nalgebra::{Point2, Vector2, Vector3};
use thiserror::Error;

use crate::surface::{Cursor, ParametricSurface};

/// How far and how finely a section is traced.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionOptions {
    /// The distance in space between successive points.
    pub step: f64,
    /// How far to trace each way from the start (arc length, approximately).
    pub length: f64,
}

/// A traced plane section.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SectionCurve {
    /// The points in space, along the curve.
    pub points: Vec<Vector3<f64>>,
    /// Their parameters.
    pub uvs: Vec<Point2<f64>>,
    /// The index of the start point in `points`.
    pub start: usize,
}

/// Why a section could not be traced.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum SectionError {
    /// The start lies outside the domain.
    #[error("the start point ({0}, {1}) lies outside the domain")]
    Outside(f64, f64),
    /// The plane's normal is zero or not finite, or the options are not positive.
    #[error("the plane normal must be a non-zero finite vector and step, length positive")]
    BadInput,
    /// The plane is tangent to the surface at the start (or the surface is singular there):
    /// the section is not a curve through the point.
    #[error("the plane touches the surface at the start point; the section is not a curve there")]
    Tangent,
}

/// The section of `surface` by the plane through s(`uv0`) with normal `plane_normal`, traced
/// both ways from `uv0` until `length` or the domain's boundary. The points run in the
/// direction m × n at the start (m the plane's normal, n = s_u × s_v the surface's).
pub fn plane_section<S: ParametricSurface + ?Sized>(
    surface: &S,
    uv0: Point2<f64>,
    plane_normal: Vector3<f64>,
    opts: SectionOptions,
) -> Result<SectionCurve, SectionError> {
    let good = |x: f64| x.is_finite() && x > 0.0;
    let m = plane_normal
        .try_normalize(1e-300)
        .filter(|m| m.iter().all(|x| x.is_finite()))
        .ok_or(SectionError::BadInput)?;
    if !good(opts.step) || !good(opts.length) {
        return Err(SectionError::BadInput);
    }
    let mut cursor = surface.cursor_near(uv0);
    let start = surface
        .jet_with(uv0, &mut cursor)
        .map_err(|_| SectionError::Outside(uv0.x, uv0.y))?
        .jet;
    let tracer = Tracer {
        surface,
        origin: start.value,
        m,
        tolerance: 1e-13 * (1.0 + start.value.norm() + opts.length),
    };
    let t = tracer
        .domain_tangent(&start.dx, &start.dy)
        .ok_or(SectionError::Tangent)?;
    // Orient the curve along m × n.
    let along = m.cross(&start.dx.cross(&start.dy));
    let sign = if (start.dx * t.x + start.dy * t.y).dot(&along) >= 0.0 {
        1.0
    } else {
        -1.0
    };
    let mut forward = tracer.trace(uv0, cursor, sign, opts);
    let backward = tracer.trace(uv0, cursor, -sign, opts);
    let mut out = SectionCurve {
        start: backward.len(),
        ..Default::default()
    };
    for (p, uv) in backward.into_iter().rev() {
        out.points.push(p);
        out.uvs.push(uv);
    }
    out.points.push(start.value);
    out.uvs.push(uv0);
    for (p, uv) in forward.drain(..) {
        out.points.push(p);
        out.uvs.push(uv);
    }
    Ok(out)
}

/// The most points traced each way (a guard against endless loops on closed sections).
const MAX_POINTS: usize = 100_000;

struct Tracer<'a, S: ?Sized> {
    surface: &'a S,
    origin: Vector3<f64>,
    m: Vector3<f64>,
    tolerance: f64,
}

impl<S: ParametricSurface + ?Sized> Tracer<'_, S> {
    /// The unit direction of the zero set of f in the domain, from s_u and s_v; None where
    /// ∇f vanishes (plane tangent to the surface, or a singular point).
    fn domain_tangent(&self, su: &Vector3<f64>, sv: &Vector3<f64>) -> Option<Vector2<f64>> {
        let g = Vector2::new(su.dot(&self.m), sv.dot(&self.m));
        let size = su.norm() + sv.norm();
        (g.norm() > 1e-12 * size).then(|| Vector2::new(-g.y, g.x).normalize())
    }

    /// Follows the curve from `uv0` in direction `sign`; the points after the start.
    fn trace(
        &self,
        uv0: Point2<f64>,
        mut cursor: Cursor,
        sign: f64,
        opts: SectionOptions,
    ) -> Vec<(Vector3<f64>, Point2<f64>)> {
        let mut out = Vec::new();
        let (mut uv, mut previous): (Point2<f64>, Option<Vector2<f64>>) = (uv0, None);
        let mut travelled = 0.0;
        while travelled < opts.length && out.len() < MAX_POINTS {
            let Ok(j) = self.surface.jet_with(uv, &mut cursor) else {
                break;
            };
            let Some(mut t) = self.domain_tangent(&j.jet.dx, &j.jet.dy) else {
                break;
            };
            t *= previous.map_or(sign, |p| p.dot(&t).signum());
            let speed = (j.jet.dx * t.x + j.jet.dy * t.y).norm();
            if speed <= 0.0 {
                break;
            }
            let mut h = opts.step.min(opts.length - travelled);
            let next = loop {
                if h < 1e-9 * opts.step {
                    break None;
                }
                match self.correct(uv + t * (h / speed), &mut cursor) {
                    Some(found) => break Some(found),
                    None => h *= 0.5,
                }
            };
            let Some((p, next_uv)) = next else {
                break;
            };
            travelled += (p - j.jet.value).norm();
            previous = Some(t);
            uv = next_uv;
            out.push((p, uv));
        }
        out
    }

    /// Newton steps along ∇f from `uv` onto f = 0; None if they leave the domain or do not
    /// converge.
    fn correct(
        &self,
        mut uv: Point2<f64>,
        cursor: &mut Cursor,
    ) -> Option<(Vector3<f64>, Point2<f64>)> {
        for _ in 0..12 {
            let j = self.surface.jet_with(uv, cursor).ok()?.jet;
            let f = (j.value - self.origin).dot(&self.m);
            if f.abs() <= self.tolerance {
                return Some((j.value, uv));
            }
            let g = Vector2::new(j.dx.dot(&self.m), j.dy.dot(&self.m));
            let g2 = g.norm_squared();
            if g2 == 0.0 || !g2.is_finite() {
                return None;
            }
            uv -= g * (f / g2);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::Surface;
    use crate::test_util::*;

    /// The paraboloid z = (x² + y²)/2 on [-1, 1]² (PS-splines reproduce quadratics exactly).
    fn paraboloid(seed: u64) -> Surface {
        crate::interrogate::level_tests::elliptic_paraboloid(1.0, 1.0, seed)
    }

    fn on_paraboloid(p: &Vector3<f64>) -> f64 {
        (p.z - 0.5 * (p.x * p.x + p.y * p.y)).abs()
    }

    #[test]
    fn a_vertical_section_of_a_paraboloid_is_its_parabola_across_the_whole_domain() {
        let s = paraboloid(1);
        let opts = SectionOptions {
            step: 0.02,
            length: 10.0,
        };
        let c = plane_section(&s, Point2::new(0.3, 0.2), Vector3::y(), opts).unwrap();
        for p in &c.points {
            assert!((p.y - 0.2).abs() < 1e-12, "{p:?}");
            assert!(on_paraboloid(p) < 1e-12, "{p:?}");
        }
        // In order along x, from one side of the square to the other.
        let xs: Vec<f64> = c.points.iter().map(|p| p.x).collect();
        assert!(xs.windows(2).all(|w| w[1] > w[0]));
        assert!(
            xs[0] < -1.0 + 0.021 && *xs.last().unwrap() > 1.0 - 0.021,
            "{xs:?}"
        );
        assert_eq!(c.points[c.start], s.point(Point2::new(0.3, 0.2)).unwrap());
        // The predictor moves one step along the tangent; the corrector changes that by
        // O(step² κ).
        for w in c.points.windows(2) {
            assert!((w[1] - w[0]).norm() <= 0.02 * 1.05);
        }
    }

    #[test]
    fn normal_sections_lie_on_the_surface_and_in_their_plane_and_have_the_normal_curvature() {
        let s = paraboloid(2);
        let mut r = rng(3);
        for _ in 0..20 {
            let uv = Point2::new(uniform(&mut r, -0.5, 0.5), uniform(&mut r, -0.5, 0.5));
            let j = s.jet(uv).unwrap().jet;
            let n = j.dx.cross(&j.dy).normalize();
            let a = uniform(&mut r, 0.0, std::f64::consts::TAU);
            let d = (j.dx * a.cos() + j.dy * a.sin()).normalize();
            let m = n.cross(&d);
            let h = 1e-3;
            let c = plane_section(
                &s,
                uv,
                m,
                SectionOptions {
                    step: h,
                    length: 0.2,
                },
            )
            .unwrap();
            for p in &c.points {
                assert!(on_paraboloid(p) < 1e-12);
                assert!((p - j.value).dot(&m).abs() < 1e-12);
            }
            // The circle through the start and its neighbours: curvature of the section.
            let (p0, p1, p2) = (
                c.points[c.start - 1],
                c.points[c.start],
                c.points[c.start + 1],
            );
            let (a, b, e) = ((p1 - p0).norm(), (p2 - p1).norm(), (p2 - p0).norm());
            let kappa = 2.0 * (p1 - p0).cross(&(p2 - p0)).norm() / (a * b * e);
            // Closed form: for the graph of f, II = Hess f / √(1 + |∇f|²); here Hess f = I,
            // and the unit tangent d has parameter direction (d_x, d_y), so
            // κ_n = (d_x² + d_y²)/√(1 + x² + y²). The three-point circle is within O(h²).
            let w = (1.0 + uv.x * uv.x + uv.y * uv.y).sqrt();
            let expected = (d.x * d.x + d.y * d.y) / w;
            assert!(
                (kappa - expected).abs() < 1e-5 * expected,
                "{kappa} vs {expected}"
            );
        }
    }

    #[test]
    fn bad_input_is_an_error() {
        let s = paraboloid(4);
        let opts = SectionOptions {
            step: 0.1,
            length: 1.0,
        };
        let uv = Point2::new(0.1, 0.1);
        assert_eq!(
            plane_section(&s, Point2::new(3.0, 0.0), Vector3::x(), opts),
            Err(SectionError::Outside(3.0, 0.0))
        );
        assert_eq!(
            plane_section(&s, uv, Vector3::zeros(), opts),
            Err(SectionError::BadInput)
        );
        assert_eq!(
            plane_section(&s, uv, Vector3::new(f64::NAN, 0.0, 1.0), opts),
            Err(SectionError::BadInput)
        );
        let zero_step = SectionOptions { step: 0.0, ..opts };
        assert_eq!(
            plane_section(&s, uv, Vector3::x(), zero_step),
            Err(SectionError::BadInput)
        );
        // The tangent plane at the apex touches the paraboloid there.
        assert_eq!(
            plane_section(&s, Point2::new(0.0, 0.0), Vector3::z(), opts),
            Err(SectionError::Tangent)
        );
    }
}
