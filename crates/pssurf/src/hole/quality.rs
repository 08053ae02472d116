//! The quality report of a filling patch in the terms CAD users know: boundary deviation
//! (G0), normal angle (G1), fairness numbers and the residual per iteration.

use nalgebra::{Point2, Vector3};

use super::HoleError;
use super::boundary::unit;
use super::fill::{HoleFill, IterationRecord};
use crate::interrogate::fairness::{DEFAULT_QUADRATURE_DEGREE, fairness_integrals};
use crate::ups::Ups;

/// The fewest samples per boundary curve for G0 and G1, at the parameters (i + ½)/N (the
/// curves' ends are corners, where the normals of two surrounding surfaces may differ).
pub const SAMPLES_PER_CURVE: usize = 256;

/// The fewest samples per boundary edge of the patch, at (m + ½)/4 of the edge: the patch
/// meets the curves at its boundary vertices, so samples that fell on them (256 per curve
/// after 9 steps, 512 edges) reported G0 2e-16 and G1 5e-11° where the edges deviated by
/// 8e-11 and 0.02°.
pub const SAMPLES_PER_EDGE: usize = 4;

/// How well a filling patch meets its boundary data, and how fair it is.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct QualityReport {
    /// The model size (bounding-box diagonal of the boundary curves).
    pub model_size: f64,
    /// The largest distance from the patch's boundary to the given curves (model units; from
    /// each sample point to the closest point of its curve).
    pub g0_max: f64,
    /// The root mean square of the same distances.
    pub g0_rms: f64,
    /// The largest angle between the patch normal and the given normal at the closest curve
    /// point, degrees; away from singular corners (the boundary edges touching them are left
    /// out, a length that halves with every step).
    pub g1_max_degrees: f64,
    /// The root mean square of the same angles, degrees.
    pub g1_rms_degrees: f64,
    /// ∫ H² dA of the patch.
    pub mean_curvature_squared: f64,
    /// The thin-plate energy ∫∫ |s_uu|² + 2|s_uv|² + |s_vv|² of the patch.
    pub thin_plate: f64,
    /// The singular corners: the numbers of the two curves meeting there and the angle
    /// between their surrounding normals and the corner's tangent plane, degrees.
    pub singular_corners: Vec<SingularCorner>,
    /// The residual of every iteration.
    pub iterations: Vec<IterationRecord>,
}

/// A corner where the surrounding surface has no tangent plane the patch could share.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct SingularCorner {
    /// The curve arriving (numbered as given).
    pub curve_in: usize,
    /// The curve leaving.
    pub curve_out: usize,
    /// The mismatch in degrees.
    pub degrees: f64,
}

/// Measures `patch` (the current patch of `fill`, with any interior method).
pub fn quality(fill: &HoleFill, patch: &Ups<Vector3<f64>>) -> Result<QualityReport, HoleError> {
    let ps = patch.to_ps().map_err(HoleError::Ups)?;
    let corners = fill.domain_corners();
    let n = corners.len();
    let b = fill.boundary();
    let (mut g0, mut g1) = (Vec::new(), Vec::new());
    for k in 0..n {
        let (a, c) = (corners[k], corners[(k + 1) % n]);
        let curve = fill.side_curve(k);
        let next = fill.side_curve((k + 1) % n);
        let singular = |c: usize| b.is_singular_corner(c);
        // The first and last boundary edges of the side, if they touch a singular corner.
        let edge = 1.0 / fill.side_steps(k) as f64;
        let lo = if singular(curve) { edge } else { 0.0 };
        let hi = if singular(next) { 1.0 - edge } else { 1.0 };
        let samples = SAMPLES_PER_CURVE.max(SAMPLES_PER_EDGE * fill.side_steps(k));
        for i in 0..samples {
            let t = (i as f64 + 0.5) / samples as f64;
            let measure_g1 = t >= lo && t <= hi;
            let uv = Point2::from(a.coords * (1.0 - t) + c.coords * t);
            let jet = ps
                .jet(uv)
                .map_err(|e| HoleError::Evaluation(e.to_string()))?
                .jet;
            let (t, distance) = b.closest(curve, jet.value, t);
            g0.push(distance);
            let given = b.unit_normal(curve, t);
            if let Some(normal) = unit(jet.dx.cross(&jet.dy))
                && given.iter().all(|x| x.is_finite())
                && measure_g1
            {
                g1.push(super::boundary::angle_degrees(normal, given));
            }
        }
    }
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt();
    let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
    let f = fairness_integrals(&ps, DEFAULT_QUADRATURE_DEGREE);
    Ok(QualityReport {
        model_size: b.size(),
        g0_max: max(&g0),
        g0_rms: rms(&g0),
        g1_max_degrees: max(&g1),
        g1_rms_degrees: rms(&g1),
        mean_curvature_squared: f.mean_squared,
        thin_plate: f.thin_plate,
        singular_corners: (0..n)
            .filter(|&c| b.is_singular_corner(c))
            .map(|c| SingularCorner {
                curve_in: b.number((c + n - 1) % n),
                curve_out: b.number(c),
                degrees: b.corner_mismatch(c),
            })
            .collect(),
        iterations: fill.history().to_vec(),
    })
}
