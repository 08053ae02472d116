//! [`Surface`]: every surface kind in one enum that forwards the surface traits.

use std::ops::Range;
use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::piece::{PieceKind, PiecePoint, PieceShape};
use super::uniform::{UniformSurface, UpsSurface};
use super::{
    ControlFreedom, ControlId, ControlNet, ControlPoint, Cursor, Domain, EditError, OutsideDomain,
    ParametricSurface, PiecewiseSurface, SurfaceJet,
};
use crate::bezier::{BezierTriangle, Jet, RationalBezierTriangle};
use crate::noise::{NoiseKind, perturb};
use crate::nurbs::NurbsSurface;
use crate::ps::{Nurps, PsBasis, PsSpline};

/// A surface of any kind. Every variant implements [`ParametricSurface`],
/// [`PiecewiseSurface`] and [`ControlNet`], and so does the enum, by forwarding: code
/// written against the traits (sampling, curvature, plots, export, fairness, editing) works
/// for every kind without matching on it.
#[derive(Clone, Debug)]
pub enum Surface {
    /// A functional PS-spline surface z = s(x, y) (2.49).
    Functional(PsSpline<f64>),
    /// A parametric PS-spline surface (2.64).
    Parametric(PsSpline<Vector3<f64>>),
    /// A NURPS surface (3.32).
    Nurps(Nurps<Vector3<f64>>),
    /// A uniform PS-spline (UPS) of any kind, with its general form.
    Uniform(UniformSurface),
    /// A polynomial triangular Bézier patch (2.26).
    Bezier(BezierTriangle<Vector3<f64>>),
    /// A rational triangular Bézier patch (3.1).
    RationalBezier(RationalBezierTriangle<Vector3<f64>>),
    /// A tensor-product NURBS surface (rectangular pieces, one per knot rectangle).
    Nurbs(NurbsSurface),
}

/// Runs `$body` with `$s` bound to the concrete surface of any variant. Adding a kind means
/// adding its line here.
macro_rules! each_kind {
    ($value:expr, $s:ident => $body:expr) => {
        match $value {
            Surface::Functional($s) => $body,
            Surface::Parametric($s) => $body,
            Surface::Nurps($s) => $body,
            Surface::Uniform($s) => $body,
            Surface::Bezier($s) => $body,
            Surface::RationalBezier($s) => $body,
            Surface::Nurbs($s) => $body,
        }
    };
}

/// The kind of a [`Surface`], for messages, file formats and choices that depend on it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SurfaceKind {
    /// A functional PS-spline z = s(x, y).
    Functional,
    /// A parametric PS-spline.
    Parametric,
    /// A NURPS surface.
    Nurps,
    /// A functional UPS-spline.
    UniformFunctional,
    /// A parametric UPS-spline.
    UniformParametric,
    /// A rational UPS-spline.
    UniformRational,
    /// A polynomial Bézier triangle.
    Bezier,
    /// A rational Bézier triangle.
    RationalBezier,
    /// A tensor-product NURBS surface.
    Nurbs,
}

impl SurfaceKind {
    /// The name used in files and messages: "functional", "parametric", "nurps" (also for
    /// the uniform kinds, which files mark by their `uniform` section), "bezier" or
    /// "rational_bezier".
    pub fn name(self) -> &'static str {
        match self {
            SurfaceKind::Functional | SurfaceKind::UniformFunctional => "functional",
            SurfaceKind::Parametric | SurfaceKind::UniformParametric => "parametric",
            SurfaceKind::Nurps | SurfaceKind::UniformRational => "nurps",
            SurfaceKind::Bezier => "bezier",
            SurfaceKind::RationalBezier => "rational_bezier",
            SurfaceKind::Nurbs => "nurbs",
        }
    }

    /// A short description for people, e.g. "parametric UPS".
    pub fn description(self) -> &'static str {
        match self {
            SurfaceKind::Functional => "functional PS",
            SurfaceKind::Parametric => "parametric PS",
            SurfaceKind::Nurps => "NURPS",
            SurfaceKind::UniformFunctional => "functional UPS",
            SurfaceKind::UniformParametric => "parametric UPS",
            SurfaceKind::UniformRational => "rational UPS",
            SurfaceKind::Bezier => "Bézier triangle",
            SurfaceKind::RationalBezier => "rational Bézier triangle",
            SurfaceKind::Nurbs => "NURBS surface",
        }
    }

    /// True for functional surfaces z = s(x, y): parameters are (x, y).
    pub fn is_functional(self) -> bool {
        matches!(
            self,
            SurfaceKind::Functional | SurfaceKind::UniformFunctional
        )
    }

    /// True for rational surfaces (with weights).
    pub fn is_rational(self) -> bool {
        matches!(
            self,
            SurfaceKind::Nurps
                | SurfaceKind::UniformRational
                | SurfaceKind::RationalBezier
                | SurfaceKind::Nurbs
        )
    }

    /// True for UPS surfaces (subdivision and wavelets apply).
    pub fn is_uniform(self) -> bool {
        matches!(
            self,
            SurfaceKind::UniformFunctional
                | SurfaceKind::UniformParametric
                | SurfaceKind::UniformRational
        )
    }
}

impl std::fmt::Display for SurfaceKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.description())
    }
}

impl Surface {
    /// The kind.
    pub fn kind(&self) -> SurfaceKind {
        match self {
            Surface::Functional(_) => SurfaceKind::Functional,
            Surface::Parametric(_) => SurfaceKind::Parametric,
            Surface::Nurps(_) => SurfaceKind::Nurps,
            Surface::Uniform(u) => match u.ups() {
                UpsSurface::Functional(_) => SurfaceKind::UniformFunctional,
                UpsSurface::Parametric(_) => SurfaceKind::UniformParametric,
                UpsSurface::Rational(_) => SurfaceKind::UniformRational,
            },
            Surface::Bezier(_) => SurfaceKind::Bezier,
            Surface::RationalBezier(_) => SurfaceKind::RationalBezier,
            Surface::Nurbs(_) => SurfaceKind::Nurbs,
        }
    }

    /// The PS basis (triangulation, refinement, PS-triangles) of a PS, NURPS or UPS surface
    /// (for UPS, of its general form); `None` for Bézier triangles.
    pub fn ps_basis(&self) -> Option<&Arc<PsBasis>> {
        match self {
            Surface::Functional(s) => Some(s.basis()),
            Surface::Parametric(s) => Some(s.basis()),
            Surface::Nurps(s) => Some(s.basis()),
            Surface::Uniform(u) => u.general().ps_basis(),
            Surface::Bezier(_) | Surface::RationalBezier(_) | Surface::Nurbs(_) => None,
        }
    }

    /// The total degree of each piece's polynomial (of numerator and denominator for the
    /// rational kinds): 2 for the PS, NURPS and UPS kinds (quadratic Bézier pieces on Δ*), m
    /// for a Bézier triangle of degree m.
    pub fn piece_degree(&self) -> usize {
        match self {
            Surface::Bezier(s) => s.degree(),
            Surface::RationalBezier(s) => s.degree(),
            // A tensor piece of degrees (p, q) has total degree p + q.
            Surface::Nurbs(s) => s.degree()[0] + s.degree()[1],
            _ => 2,
        }
    }

    /// The uniform form of a UPS surface.
    pub fn uniform(&self) -> Option<&UpsSurface> {
        match self {
            Surface::Uniform(u) => Some(u.ups()),
            _ => None,
        }
    }

    /// The parameter domain (built from the triangulation's boundary on each call: keep it
    /// when it is used often).
    pub fn domain(&self) -> Domain {
        match self {
            Surface::Bezier(s) => Domain::triangle(s.domain()),
            Surface::RationalBezier(s) => Domain::triangle(s.domain()),
            Surface::Nurbs(s) => {
                let (lo, hi) = s.domain_bounds();
                Domain::rectangle(&super::Rectangle::new(lo, hi))
            }
            _ => Domain::from_triangulation(
                self.ps_basis()
                    .expect("PS kinds have a basis")
                    .triangulation(),
            ),
        }
    }

    /// The surface with every free coordinate of every control point perturbed reproducibly
    /// (uniform or Gaussian noise of amplitude `amplitude` from a generator seeded with
    /// `seed`, in control-point id order; see [`crate::noise::perturb`]). Weights are kept.
    ///
    /// ```
    /// use pssurf::prelude::*;
    /// use pssurf::noise::NoiseKind;
    /// use pssurf::surface::EditError;
    /// use std::sync::Arc;
    /// let t = Triangulation::try_new(
    ///     vec![Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)],
    ///     vec![[0, 1, 2]],
    /// )?;
    /// let s = Surface::from(PsSpline::new(Arc::new(PsBasis::optimal(t)?), vec![[0.0; 3]; 3])?);
    /// // Noise so large that a coordinate overflows is refused, not returned.
    /// let e = s.with_noise(f64::MAX, NoiseKind::Gaussian, 1).unwrap_err();
    /// assert!(matches!(e, EditError::NonFinite(_)));
    /// let e = s.with_noise(f64::NAN, NoiseKind::Uniform, 1).unwrap_err();
    /// assert!(matches!(e, EditError::InvalidAmplitude(_)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_noise(
        &self,
        amplitude: f64,
        kind: NoiseKind,
        seed: u64,
    ) -> Result<Surface, EditError> {
        if !(amplitude.is_finite() && amplitude >= 0.0) {
            return Err(EditError::InvalidAmplitude(amplitude));
        }
        if let Surface::Uniform(u) = self {
            let noisy = u.ups().with_noise(amplitude, kind, seed);
            let unusable = noisy
                .grid()
                .real_slots()
                .into_iter()
                .flat_map(|s| noisy.vertex_points(s))
                .position(|p| !p.position.iter().all(|&x| crate::limits::value_ok(x)));
            return match unusable {
                Some(id) => Err(EditError::NonFinite(id)),
                // Noise moves points only: the weights were usable and still are.
                None => Surface::try_from(noisy).map_err(|_| EditError::NonFinite(0)),
            };
        }
        let mut out = self.clone();
        let points = self.control_points();
        let changes: Vec<(ControlId, ControlPoint)> = match self.freedom() {
            ControlFreedom::Height => {
                let mut z: Vec<f64> = points.iter().map(|p| p.position.z).collect();
                perturb(z.iter_mut(), amplitude, kind, seed);
                points
                    .iter()
                    .zip(z)
                    .enumerate()
                    .map(|(i, (p, z))| {
                        let mut q = *p;
                        q.position.z = z;
                        (ControlId(i), q)
                    })
                    .collect()
            }
            ControlFreedom::Full => {
                let mut pos: Vec<Vector3<f64>> = points.iter().map(|p| p.position).collect();
                perturb(pos.iter_mut(), amplitude, kind, seed);
                points
                    .iter()
                    .zip(pos)
                    .enumerate()
                    .map(|(i, (p, position))| (ControlId(i), ControlPoint { position, ..*p }))
                    .collect()
            }
        };
        out.set_control_points(&changes)?;
        Ok(out)
    }
}

impl TryFrom<UpsSurface> for Surface {
    type Error = crate::ups::UpsError;
    /// The surface of a uniform form, unless a control value is unusable
    /// ([`UniformSurface::new`]).
    fn try_from(s: UpsSurface) -> Result<Self, Self::Error> {
        UniformSurface::new(s).map(Surface::Uniform)
    }
}

/// `From` for each concrete kind.
macro_rules! from_kind {
    ($($variant:ident($kind:ty)),*) => {$(
        impl From<$kind> for Surface {
            fn from(s: $kind) -> Self {
                Surface::$variant(s)
            }
        }
    )*};
}

from_kind!(
    Functional(PsSpline<f64>),
    Parametric(PsSpline<Vector3<f64>>),
    Nurps(Nurps<Vector3<f64>>),
    Uniform(UniformSurface),
    Bezier(BezierTriangle<Vector3<f64>>),
    RationalBezier(RationalBezierTriangle<Vector3<f64>>),
    Nurbs(NurbsSurface)
);

impl ParametricSurface for Surface {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        each_kind!(self, s => s.domain_bounds())
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        each_kind!(self, s => s.cursor_near(uv))
    }
    #[inline]
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        each_kind!(self, s => s.jet_with(uv, cursor))
    }
}

impl PiecewiseSurface for Surface {
    fn piece_count(&self) -> usize {
        each_kind!(self, s => s.piece_count())
    }
    fn piece_kind(&self) -> PieceKind {
        each_kind!(self, s => s.piece_kind())
    }
    fn piece_shape(&self, k: usize) -> PieceShape {
        each_kind!(self, s => s.piece_shape(k))
    }
    #[inline]
    fn piece_jet(&self, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
        each_kind!(self, s => s.piece_jet(k, at))
    }
}

impl ControlNet for Surface {
    fn control_count(&self) -> usize {
        each_kind!(self, s => s.control_count())
    }
    fn control_point(&self, id: ControlId) -> Option<ControlPoint> {
        each_kind!(self, s => s.control_point(id))
    }
    fn is_rational(&self) -> bool {
        each_kind!(self, s => s.is_rational())
    }
    fn freedom(&self) -> ControlFreedom {
        each_kind!(self, s => s.freedom())
    }
    fn control_group(&self, id: ControlId) -> Range<usize> {
        each_kind!(self, s => s.control_group(id))
    }
    fn control_anchor(&self, id: ControlId) -> Point2<f64> {
        each_kind!(self, s => s.control_anchor(id))
    }
    fn support(&self, id: ControlId) -> Vec<usize> {
        each_kind!(self, s => s.support(id))
    }
    fn set_control_points(
        &mut self,
        changes: &[(ControlId, ControlPoint)],
    ) -> Result<Vec<usize>, EditError> {
        each_kind!(self, s => s.set_control_points(changes))
    }
}
