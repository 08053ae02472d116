//! Plane sections: the curve in which a plane through a surface point cuts the surface,
//! traced from that point in both directions. With a plane that contains the normal this is
//! a normal section, whose curvature at the point is the normal curvature in the plane's
//! tangent direction (the probe of seed 003, section 3).
//!
//! The curve is the zero set of f(u, v) = (s(u, v) − p₀)·m in the parameter domain (m the
//! plane's normal). It is followed by the predictor–corrector continuation that traces level
//! lines too (`continuation::Follow`): a step along the domain tangent (−f_v, f_u)
//! of the zero set, sized to move `step` in space, then Newton steps along ∇f back onto f = 0
//! (to 1e-13 of the surface's size), halving the step when the corrector does not converge,
//! the tangent turns too much or the point leaves the domain. A section that comes back to
//! its start is closed.

use nalgebra::{Point2, Vector2, Vector3};
use thiserror::Error;

use std::cell::Cell;

use super::continuation::{Branch, End, Exit, Follow, Region, Sample};
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
    /// Whether the section came back to its start (a closed curve; the start is not
    /// repeated at the end).
    pub closed: bool,
}

/// Why a section could not be traced.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum SectionError {
    /// The start lies outside the domain.
    #[error("the start point ({}, {}) lies outside the domain", crate::text::Short(*.0), crate::text::Short(*.1))]
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
    let cursor = Cell::new(surface.cursor_near(uv0));
    let start = surface
        .jet_with(uv0, &mut cursor.get())
        .map_err(|_| SectionError::Outside(uv0.x, uv0.y))?
        .jet;
    let origin = start.value;
    let mut f = |uv: Point2<f64>| -> Option<Sample> {
        let mut c = cursor.get();
        let j = surface.jet_with(uv, &mut c).ok()?.jet;
        cursor.set(c);
        Some(Sample {
            f: (j.value - origin).dot(&m),
            grad: Vector2::new(j.dx.dot(&m), j.dy.dot(&m)),
            point: j.value,
            su: j.dx,
            sv: j.dy,
        })
    };
    let first = f(uv0).ok_or(SectionError::Outside(uv0.x, uv0.y))?;
    let size = start.dx.norm() + start.dy.norm();
    if first.grad.norm() <= 1e-12 * size {
        return Err(SectionError::Tangent);
    }
    // Orient the curve along m × n.
    let t = Vector2::new(-first.grad.y, first.grad.x).normalize();
    let along = m.cross(&start.dx.cross(&start.dy));
    let t = if (start.dx * t.x + start.dy * t.y).dot(&along) >= 0.0 {
        t
    } else {
        -t
    };
    let follow = Follow {
        step: opts.step,
        in_space: true,
        min_fraction: 1e-9,
        max_turn: 0.2,
        tolerance: 1e-13 * (1.0 + origin.norm() + opts.length),
        singular: 1e-12 * size,
        length: opts.length,
        max_points: MAX_POINTS,
    };
    let region = WholeDomain {
        surface,
        cursor: &cursor,
    };
    let forward = follow.run(&mut f, &region, (uv0, first), t, &mut |_, _| false);
    let backward = if forward.end == End::Closed {
        Branch::empty()
    } else {
        follow.run(&mut f, &region, (uv0, first), -t, &mut |_, _| false)
    };
    let mut out = SectionCurve {
        start: backward.uvs.len(),
        closed: forward.end == End::Closed,
        ..Default::default()
    };
    out.points.extend(backward.points.iter().rev());
    out.uvs.extend(backward.uvs.iter().rev());
    out.points.push(origin);
    out.uvs.push(uv0);
    // A closed section ends on its start: that point is not repeated.
    let n = forward.uvs.len() - usize::from(forward.end == End::Closed);
    out.points.extend(&forward.points[..n]);
    out.uvs.extend(&forward.uvs[..n]);
    Ok(out)
}

/// The most points traced each way (a guard against endless loops).
const MAX_POINTS: usize = 100_000;

/// The surface's whole domain as a region: a point is in it when the surface is defined
/// there (its point location is exact); it has no edges to solve on, so a section ends
/// within the smallest step of the boundary.
struct WholeDomain<'a, S: ?Sized> {
    surface: &'a S,
    cursor: &'a Cell<Cursor>,
}

impl<S: ParametricSurface + ?Sized> Region for WholeDomain<'_, S> {
    fn contains(&self, p: Point2<f64>) -> bool {
        let mut c = self.cursor.get();
        let inside = self.surface.jet_with(p, &mut c).is_ok();
        self.cursor.set(c);
        inside
    }

    fn exits(&self, _: Point2<f64>, _: Point2<f64>) -> Vec<Exit> {
        Vec::new()
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
    fn a_level_section_of_a_paraboloid_is_a_closed_circle() {
        let s = paraboloid(5);
        let uv = Point2::new(0.3, 0.2);
        let opts = SectionOptions {
            step: 0.01,
            length: 100.0,
        };
        let c = plane_section(&s, uv, Vector3::z(), opts).unwrap();
        assert!(c.closed);
        assert_eq!(c.start, 0, "closed going forward: nothing traced backward");
        let r = uv.coords.norm();
        for q in &c.uvs {
            assert!((q.coords.norm() - r).abs() < 1e-12);
        }
        // Once round: about 2πr/step points.
        let n = c.uvs.len() as f64;
        let expected = std::f64::consts::TAU * r / 0.01;
        assert!((n - expected).abs() < 0.05 * expected, "{n} points");
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
