//! Level lines of a field on a surface (seed 001): chosen levels or evenly spread automatic
//! ones, and the parabolic lines K = 0 with the areas of the elliptic (K > 0) and hyperbolic
//! (K < 0) regions they separate.

use rayon::prelude::*;

use super::curvature::{CurvatureQuantity, PrincipalCurvatures};
use super::field::SurfaceField;
use super::zero_set::{FieldOn, ZeroSet, ZeroSetError, ZeroSetOptions, trace_levels};
use crate::surface::{PieceRule, PiecewiseSurface};

/// The level lines f = c of `field` on `surface` for every c in `levels`.
///
/// ```
/// use pssurf::interrogate::{SurfaceField, ZeroSetOptions, level_lines};
/// use pssurf::bezier::BezierTriangle;
/// use pssurf::geometry::Triangle2;
/// use pssurf::surface::Surface;
/// use nalgebra::{Point2, Vector3};
/// // The plane z = x + y over a triangle: its contour z = 0.5 is the segment x + y = 0.5.
/// let t = Triangle2::new(Point2::new(-2.0, -2.0), Point2::new(2.0, -2.0), Point2::new(0.0, 2.0));
/// let s = Surface::Bezier(BezierTriangle::from_fn(t, 1, |p| Vector3::new(p.x, p.y, p.x + p.y)));
/// let sets = level_lines(&s, &SurfaceField::Height, &[0.5], &ZeroSetOptions::default()).unwrap();
/// let segment = &sets[0].curves[0];
/// assert!(!segment.closed && segment.uvs.len() >= 2);
/// assert!(segment.uvs.iter().all(|p| (p.x + p.y - 0.5).abs() < 1e-12));
/// ```
pub fn level_lines<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    field: &SurfaceField,
    levels: &[f64],
    opts: &ZeroSetOptions,
) -> Result<Vec<ZeroSet>, ZeroSetError> {
    trace_levels(surface, &FieldOn { surface, field }, levels, opts)
}

/// `count` levels spread evenly over the bulk of the field's values: the centres of `count`
/// equal bins between its 2nd and 98th percentiles over the pieces (so one spike does not
/// decide them). Empty if the field is undefined everywhere.
pub fn auto_levels<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    field: &SurfaceField,
    count: usize,
) -> Vec<f64> {
    let rule = PieceRule::exact_for(2);
    let mut values: Vec<f64> = (0..surface.piece_count())
        .into_par_iter()
        .flat_map_iter(|k| {
            let nodes = surface.piece_quadrature(k, &rule).unwrap_or_default();
            nodes
                .into_iter()
                .map(move |n| field.value(n.point.uv, &surface.piece_jet(k, &n.point)))
        })
        .filter(|v| v.is_finite())
        .collect();
    if values.is_empty() || count == 0 {
        return Vec::new();
    }
    values.sort_by(f64::total_cmp);
    let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
    let (lo, hi) = (at(0.02), at(0.98));
    if lo == hi {
        return vec![lo];
    }
    let w = (hi - lo) / count as f64;
    (0..count).map(|i| lo + w * (i as f64 + 0.5)).collect()
}

/// The areas (in space) of the regions a surface's parabolic lines separate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CurvatureRegions {
    /// Where K > 0 (elliptic points).
    pub elliptic: f64,
    /// Where K < 0 (hyperbolic points).
    pub hyperbolic: f64,
    /// Where K = 0 exactly at the quadrature points (flat or cylindrical parts).
    pub parabolic: f64,
}

/// The areas of the elliptic, hyperbolic and parabolic regions, by a Gauss rule on every
/// piece (the sign of K at each node, weighted by the area element |s_u × s_v|).
pub fn curvature_regions<S: PiecewiseSurface + ?Sized>(surface: &S) -> CurvatureRegions {
    let rule = PieceRule::exact_for(6);
    (0..surface.piece_count())
        .into_par_iter()
        .map(|k| {
            let mut r = CurvatureRegions::default();
            for n in surface.piece_quadrature(k, &rule).unwrap_or_default() {
                let jet = surface.piece_jet(k, &n.point);
                let area = jet.dx.cross(&jet.dy).norm() * n.weight;
                let Ok((c, _)) = PrincipalCurvatures::from_jet(&jet) else {
                    continue;
                };
                let kk = c.get(CurvatureQuantity::Gaussian);
                if kk > 0.0 {
                    r.elliptic += area;
                } else if kk < 0.0 {
                    r.hyperbolic += area;
                } else {
                    r.parabolic += area;
                }
            }
            r
        })
        .reduce(CurvatureRegions::default, |a, b| CurvatureRegions {
            elliptic: a.elliptic + b.elliptic,
            hyperbolic: a.hyperbolic + b.hyperbolic,
            parabolic: a.parabolic + b.parabolic,
        })
}

/// The parabolic lines K = 0 and the regions they separate.
pub fn parabolic_lines<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    opts: &ZeroSetOptions,
) -> Result<(ZeroSet, CurvatureRegions), ZeroSetError> {
    let field = SurfaceField::Curvature(CurvatureQuantity::Gaussian);
    let set = level_lines(surface, &field, &[0.0], opts)?
        .pop()
        .unwrap_or_default();
    Ok((set, curvature_regions(surface)))
}
