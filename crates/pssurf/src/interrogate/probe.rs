//! The probe (seed 003, "3D cursor"): everything about a surface at one point. Position,
//! normal, the fundamental forms, K, H, κ1, κ2 and the principal directions, the umbilic flag;
//! two cross-planes through the normal (along the principal or the parameter directions) with
//! the normal sections they cut (traced exactly by [`plane_section`]) and their osculating
//! circles; Euler's formula checked against the second fundamental form; and the curvature,
//! torsion and Frenet frame of the two coordinate curves u ↦ s(u, v₀) and v ↦ s(u₀, v) (the
//! seed's torsion coil).
//!
//! Torsion τ = (c′ × c″)·c‴ / |c′ × c″|² needs third derivatives. Bézier triangles (and
//! rational ones) give them exactly at any degree, NURBS surfaces through their coordinate
//! curves, which are NURBS curves ([`crate::nurbs::NurbsSurface::iso_curves`]). PS, UPS and
//! NURPS pieces are quadratic
//! (rational quadratic for NURPS), so their coordinate curves are parabolas (conics), which
//! are planar: their torsion is zero inside every piece, and the probe reports 0.

use nalgebra::{Point2, Vector2, Vector3};
use thiserror::Error;

use super::curvature::{Curvature, FundamentalForms};
use super::section::{SectionCurve, SectionOptions, plane_section};
use crate::geometry::Bary;
use crate::surface::{ParametricSurface, Surface};

/// How the cross-planes are turned about the normal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Alignment {
    /// Along the principal directions: the sections' curvatures are κ1 and κ2.
    #[default]
    Principal,
    /// Along s_u and s_v.
    Parametric,
}

/// What the probe traces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProbeOptions {
    /// The cross-planes' alignment.
    pub alignment: Alignment,
    /// How far each section is traced each way from the point (in space).
    pub extent: f64,
    /// The distance between the sections' points.
    pub step: f64,
}

/// A circle in space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    /// Its centre.
    pub centre: Vector3<f64>,
    /// Its radius.
    pub radius: f64,
    /// The unit normal of its plane.
    pub axis: Vector3<f64>,
}

/// One cross-plane: the plane through the point spanned by a tangent direction and the normal.
#[derive(Clone, Debug, PartialEq)]
pub struct CrossPlane {
    /// The unit tangent direction in the plane.
    pub direction: Vector3<f64>,
    /// The angle from the first principal direction (radians).
    pub angle: f64,
    /// The normal curvature in that direction by Euler's formula κ1 cos²θ + κ2 sin²θ.
    pub normal_curvature: f64,
    /// The same from the fundamental forms, II(d)/I(d) (a check of Euler's formula).
    pub normal_curvature_forms: f64,
    /// The normal section (the curve the plane cuts), traced both ways.
    pub section: SectionCurve,
    /// The section's osculating circle (radius 1/|κ|), `None` where κ = 0.
    pub osculating: Option<Circle>,
}

/// The Frenet apparatus of a coordinate curve at the point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoordinateCurve {
    /// Its curvature |c′ × c″| / |c′|³.
    pub curvature: f64,
    /// Its torsion (c′ × c″)·c‴ / |c′ × c″|²; `None` where the curvature vanishes.
    pub torsion: Option<f64>,
    /// The unit tangent.
    pub tangent: Vector3<f64>,
    /// The unit principal normal (`None` where the curvature vanishes).
    pub normal: Option<Vector3<f64>>,
    /// The unit binormal (`None` where the curvature vanishes).
    pub binormal: Option<Vector3<f64>>,
}

/// Everything the probe knows about a point.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeReport {
    /// The parameters.
    pub uv: Point2<f64>,
    /// The point.
    pub point: Vector3<f64>,
    /// s_u and s_v.
    pub tangents: [Vector3<f64>; 2],
    /// The fundamental forms and the unit normal.
    pub forms: FundamentalForms,
    /// K, H, κ1, κ2 and the principal directions.
    pub curvature: Curvature,
    /// Whether the point is an umbilic (relative tolerance 1e-8).
    pub umbilic: bool,
    /// The two cross-planes.
    pub planes: [CrossPlane; 2],
    /// The u- and v-coordinate curves.
    pub coordinate_curves: [CoordinateCurve; 2],
    /// Why the coordinate curves' torsion is what it is (exact third derivatives, or zero
    /// because the pieces are quadratic).
    pub torsion_source: &'static str,
}

/// Why a point cannot be probed.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum ProbeError {
    /// Outside the domain.
    #[error("the point ({}, {}) lies outside the domain", crate::text::Short(*.0), crate::text::Short(*.1))]
    Outside(f64, f64),
    /// The surface is singular there.
    #[error("the surface is singular at ({0}, {1}): no normal, no curvature")]
    Singular(f64, f64),
    /// The options are not positive.
    #[error("the probe's extent and step must be positive and finite")]
    BadOptions,
}

/// Probes `surface` at `uv`.
pub fn probe(
    surface: &Surface,
    uv: Point2<f64>,
    opts: &ProbeOptions,
) -> Result<ProbeReport, ProbeError> {
    let good = |x: f64| x > 0.0 && x.is_finite();
    if !good(opts.extent) || !good(opts.step) {
        return Err(ProbeError::BadOptions);
    }
    let j = surface
        .jet(uv)
        .map_err(|_| ProbeError::Outside(uv.x, uv.y))?
        .jet;
    let forms = FundamentalForms::from_jet(&j).map_err(|_| ProbeError::Singular(uv.x, uv.y))?;
    let c = Curvature::from_forms(&j, &forms);
    let directions = match opts.alignment {
        Alignment::Principal => [c.dir1, c.dir2],
        Alignment::Parametric => [j.dx.normalize(), j.dy.normalize()],
    };
    let section_opts = SectionOptions {
        step: opts.step,
        length: opts.extent,
    };
    let planes = directions.map(|d| {
        let angle = d.dot(&c.dir2).atan2(d.dot(&c.dir1));
        let kn = c.normal_curvature_at_angle(angle);
        // II(d)/I(d) with d written in parameters.
        let w = parameter_direction(&j.dx, &j.dy, &d);
        let first = forms.e * w.x * w.x + 2.0 * forms.f * w.x * w.y + forms.g * w.y * w.y;
        let second = forms.l * w.x * w.x + 2.0 * forms.m * w.x * w.y + forms.n * w.y * w.y;
        CrossPlane {
            direction: d,
            angle,
            normal_curvature: kn,
            normal_curvature_forms: second / first,
            section: plane_section(surface, uv, c.normal.cross(&d), section_opts)
                .unwrap_or_default(),
            osculating: (kn != 0.0).then(|| Circle {
                centre: j.value + c.normal / kn,
                radius: 1.0 / kn.abs(),
                axis: c.normal.cross(&d),
            }),
        }
    });
    let (coordinate_curves, torsion_source) = coordinate_curves(surface, uv)?;
    Ok(ProbeReport {
        uv,
        point: j.value,
        tangents: [j.dx, j.dy],
        forms,
        umbilic: c.is_umbilic(super::curvature::DEFAULT_UMBILIC_TOLERANCE),
        curvature: c,
        planes,
        coordinate_curves,
        torsion_source,
    })
}

/// The curvature, torsion and Frenet frame of the coordinate curves u ↦ s(u, v) and
/// v ↦ s(u, v) through `uv`, and why their torsion is what it is (exact third derivatives, or
/// zero because the pieces are quadratic).
pub fn coordinate_curves(
    surface: &Surface,
    uv: Point2<f64>,
) -> Result<([CoordinateCurve; 2], &'static str), ProbeError> {
    let j = surface
        .jet(uv)
        .map_err(|_| ProbeError::Outside(uv.x, uv.y))?
        .jet;
    let (third, source) = third_derivatives(surface, uv);
    Ok((
        [
            frenet(&j.dx, &j.dxx, &third[0]),
            frenet(&j.dy, &j.dyy, &third[1]),
        ],
        source,
    ))
}

/// The parameter direction (du, dv) that s maps onto the tangent vector `d`.
fn parameter_direction(su: &Vector3<f64>, sv: &Vector3<f64>, d: &Vector3<f64>) -> Vector2<f64> {
    let g = nalgebra::Matrix2::new(su.dot(su), su.dot(sv), su.dot(sv), sv.dot(sv));
    g.lu()
        .solve(&Vector2::new(d.dot(su), d.dot(sv)))
        .unwrap_or_else(Vector2::zeros)
}

/// s_uuu and s_vvv at `uv`, and where they come from.
fn third_derivatives(surface: &Surface, uv: Point2<f64>) -> ([Vector3<f64>; 2], &'static str) {
    let along = |t: &crate::geometry::Triangle2| -> Option<(Bary, Bary, Bary)> {
        let map = t.bary_map()?;
        Some((t.bary(uv), map.dx(), map.dy()))
    };
    let exact = "exact third derivatives of the Bézier patch";
    match surface {
        Surface::Bezier(b) => match along(b.domain()) {
            Some((t, du, dv)) => (
                [
                    b.directional_derivative(t, du, 3),
                    b.directional_derivative(t, dv, 3),
                ],
                exact,
            ),
            None => ([Vector3::zeros(); 2], "a degenerate domain"),
        },
        Surface::RationalBezier(b) => match along(b.domain()).and_then(|(t, du, dv)| {
            Some([
                b.directional_derivative(t, du, 3).ok()?,
                b.directional_derivative(t, dv, 3).ok()?,
            ])
        }) {
            Some(d) => (d, exact),
            None => ([Vector3::zeros(); 2], "a degenerate domain"),
        },
        Surface::Nurbs(n) => match n
            .iso_curves(uv)
            .and_then(|[cu, cv]| Some([cu.derivatives3(uv.x)?[3], cv.derivatives3(uv.y)?[3]]))
        {
            Some(d) => (d, "exact third derivatives of the NURBS coordinate curves"),
            None => ([Vector3::zeros(); 2], "outside the NURBS domain"),
        },
        _ => (
            [Vector3::zeros(); 2],
            "zero: the pieces are quadratic, so coordinate curves are planar conics",
        ),
    }
}

/// The Frenet apparatus of a curve from its first three derivatives.
fn frenet(d1: &Vector3<f64>, d2: &Vector3<f64>, d3: &Vector3<f64>) -> CoordinateCurve {
    let b = d1.cross(d2);
    let speed = d1.norm();
    let bn = b.norm();
    let curved = bn > 1e-14 * speed * d2.norm().max(speed) && bn > 0.0;
    let tangent = d1 / speed;
    CoordinateCurve {
        curvature: bn / (speed * speed * speed),
        torsion: curved.then(|| b.dot(d3) / (bn * bn)),
        tangent,
        normal: curved.then(|| (b / bn).cross(&tangent)),
        binormal: curved.then(|| b / bn),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Triangle2;
    use crate::test_util::*;

    fn opts(alignment: Alignment) -> ProbeOptions {
        ProbeOptions {
            alignment,
            extent: 0.05,
            step: 1e-4,
        }
    }

    /// A bicubic-by-linear NURBS surface S(u, v) = c(u) + v e whose u-curves are the
    /// twisted cubic c(u) = (u, u², u³) (Bernstein points (0,0,0), (1/3,0,0), (2/3,1/3,0),
    /// (1,1,1)): their torsion is 3/(9u⁴ + 9u² + 1) from the curves' exact third
    /// derivatives (it was reported as 0, "the pieces are quadratic"); the v-curves are
    /// straight (no osculating plane, no torsion).
    #[test]
    fn nurbs_coordinate_curves_have_their_torsion() {
        let e = Vector3::new(0.2, -0.1, 0.3);
        let c = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0 / 3.0, 0.0, 0.0),
            Vector3::new(2.0 / 3.0, 1.0 / 3.0, 0.0),
            Vector3::new(1.0, 1.0, 1.0),
        ];
        let points = c.iter().flat_map(|&p| [p, p + e]).collect();
        let s = Surface::Nurbs(
            crate::nurbs::NurbsSurface::try_new(
                [3, 1],
                [
                    vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
                    vec![0.0, 0.0, 1.0, 1.0],
                ],
                [4, 2],
                points,
                None,
            )
            .unwrap(),
        );
        let mut r = rng(1551);
        for _ in 0..20 {
            let uv = Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0));
            let p = probe(&s, uv, &opts(Alignment::Parametric)).unwrap();
            let u = uv.x;
            let tau = 3.0 / (9.0 * u.powi(4) + 9.0 * u * u + 1.0);
            assert_near!(p.coordinate_curves[0].torsion.unwrap(), tau, 1e-12);
            assert_eq!(p.coordinate_curves[1].torsion, None);
            assert!(p.torsion_source.contains("NURBS"));
        }
    }

    #[test]
    fn the_torsion_of_a_twisted_cubics_coordinate_curve_matches_the_closed_form() {
        let t = Triangle2::new(
            Point2::new(-1.0, -1.0),
            Point2::new(1.5, -0.8),
            Point2::new(0.1, 1.2),
        );
        let s = Surface::Bezier(interpolating_bezier(t, 3, |p| {
            Vector3::new(p.x, p.x * p.x + p.y, p.x.powi(3) + p.y * p.y)
        }));
        let mut r = rng(1550);
        for _ in 0..20 {
            let uv = t.point(random_bary(&mut r));
            let p = probe(&s, uv, &opts(Alignment::Parametric)).unwrap();
            let u = uv.x;
            let tau = 12.0 / (36.0 * u.powi(4) + 36.0 * u * u + 4.0);
            assert_near!(p.coordinate_curves[0].torsion.unwrap(), tau, 1e-10);
            // v ↦ (u, u² + v, u³ + v²) lies in the plane x = u.
            assert!(p.coordinate_curves[1].torsion.unwrap().abs() < 1e-10);
            // The Frenet frame is orthonormal and the binormal is c′ × c″ normalised.
            let c = &p.coordinate_curves[0];
            let (n, b) = (c.normal.unwrap(), c.binormal.unwrap());
            assert!(c.tangent.dot(&n).abs() < 1e-12 && n.dot(&b).abs() < 1e-12);
            let k = Vector3::new(6.0 * u * u, -6.0 * u, 2.0);
            assert!((b - k.normalize()).norm() < 1e-12);
            assert_near!(
                c.curvature,
                k.norm() / (1.0 + 4.0 * u * u + 9.0 * u.powi(4)).powf(1.5),
                1e-12
            );
        }
    }

    #[test]
    fn normal_sections_have_the_curvature_of_eulers_formula() {
        let mut r = rng(1551);
        let t = Triangle2::new(
            Point2::new(-1.0, -1.0),
            Point2::new(1.5, -0.8),
            Point2::new(0.1, 1.2),
        );
        for _ in 0..10 {
            let (a, b, c) = (
                uniform(&mut r, -1.0, 1.0),
                uniform(&mut r, -1.0, 1.0),
                uniform(&mut r, -1.0, 1.0),
            );
            let s = Surface::Bezier(interpolating_bezier(t, 3, |p| {
                Vector3::new(
                    p.x + 0.1 * p.y,
                    p.y,
                    a * p.x * p.x + b * p.x * p.y * p.y + c * p.y.powi(3),
                )
            }));
            let uv = t.point([0.3, 0.3, 0.4]);
            for alignment in [Alignment::Principal, Alignment::Parametric] {
                let p = probe(&s, uv, &opts(alignment)).unwrap();
                for plane in &p.planes {
                    assert_near!(plane.normal_curvature, plane.normal_curvature_forms, 1e-10);
                    // The traced section's curvature at the point: the circle through the
                    // point and its two neighbours (spacing h: error O(h²)).
                    let sec = &plane.section;
                    let (p0, p1, p2) = (
                        sec.points[sec.start - 1],
                        sec.points[sec.start],
                        sec.points[sec.start + 1],
                    );
                    let (x, y) = (p0 - p1, p2 - p1);
                    let kappa = 2.0 * x.cross(&y).norm() / (x.norm() * y.norm() * (p2 - p0).norm());
                    assert_near!(kappa, plane.normal_curvature.abs(), 1e-5);
                    if let Some(circle) = plane.osculating {
                        assert_near!(circle.radius, 1.0 / plane.normal_curvature.abs(), 1e-14);
                        assert_near!((circle.centre - p.point).norm(), circle.radius, 1e-12);
                        assert!(circle.axis.dot(&p.forms.normal).abs() < 1e-12);
                    }
                }
                if alignment == Alignment::Principal {
                    assert_near!(p.planes[0].normal_curvature, p.curvature.k1, 1e-12);
                    assert_near!(p.planes[1].normal_curvature, p.curvature.k2, 1e-12);
                }
            }
        }
    }

    #[test]
    fn ps_pieces_report_zero_torsion_and_bad_points_are_errors() {
        let s = super::super::level_tests::elliptic_paraboloid(1.0, 2.0, 1552);
        let p = probe(&s, Point2::new(0.2, 0.1), &opts(Alignment::Principal)).unwrap();
        assert!(p.torsion_source.starts_with("zero"));
        assert_eq!(p.coordinate_curves[0].torsion, Some(0.0));
        assert!(matches!(
            probe(&s, Point2::new(5.0, 0.0), &opts(Alignment::Principal)),
            Err(ProbeError::Outside(..))
        ));
        let bad = ProbeOptions {
            extent: f64::NAN,
            ..opts(Alignment::Principal)
        };
        assert_eq!(
            probe(&s, Point2::new(0.0, 0.0), &bad),
            Err(ProbeError::BadOptions)
        );
    }
}
