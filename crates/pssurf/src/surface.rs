//! The one trait every surface kind implements — PS, UPS, NURPS, Bézier patches, and later
//! NURBS — so that interrogation and display are written once.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};
use thiserror::Error;

use crate::bezier::{BezierTriangle, Jet, RationalBezierTriangle};
use crate::geometry::{Bary, BaryMap, Triangle2};
use crate::ps::net::Weighted;
use crate::ps::{Nurps, PatchId, PsJet, PsSpline};
use crate::ups::{Ups, UpsError, UpsGrid};

/// A point of a surface with its first and second partial derivatives w.r.t. the parameters
/// (u, v), and the polynomial piece it was computed on (for piecewise surfaces, whose second
/// derivatives jump across piece boundaries).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceJet {
    /// s, s_u, s_v, s_uu, s_uv, s_vv.
    pub jet: Jet<Vector3<f64>>,
    /// The piece (sub-triangle of Δ*), when the surface is piecewise.
    pub patch: Option<PatchId>,
}

/// The parameter lies outside the surface's domain.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
#[error("the parameter ({u}, {v}) lies outside the domain")]
pub struct OutsideDomain {
    /// u.
    pub u: f64,
    /// v.
    pub v: f64,
}

/// Remembers where the previous evaluation happened (a triangle to start the next walk from),
/// so that nearby points are found by a short walk. Get one from
/// [`ParametricSurface::cursor_near`] for the first point and reuse it along a grid or a curve;
/// `Cursor::default()` works too (it starts at triangle 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cursor(pub usize);

/// A parametric surface s: Ω ⊂ R² → R³ with first and second derivatives.
///
/// Functional surfaces z = f(x, y) are their graphs (x, y, f(x, y)), so (u, v) = (x, y).
pub trait ParametricSurface: Send + Sync {
    /// The bounding box of the parameter domain Ω (min corner, max corner).
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>);

    /// s and its derivatives at `uv`, starting the search at `cursor` (which is updated).
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain>;

    /// A cursor from which the search for `uv` is short (for piecewise surfaces a spatial
    /// index is consulted once; then reuse the cursor for nearby points).
    fn cursor_near(&self, _uv: Point2<f64>) -> Cursor {
        Cursor::default()
    }

    /// s and its derivatives at `uv`.
    fn jet(&self, uv: Point2<f64>) -> Result<SurfaceJet, OutsideDomain> {
        self.jet_with(uv, &mut self.cursor_near(uv))
    }

    /// The point s(u, v).
    fn point(&self, uv: Point2<f64>) -> Result<Vector3<f64>, OutsideDomain> {
        Ok(self.jet(uv)?.jet.value)
    }

    /// The unit normal n = s_u × s_v / |s_u × s_v| (2.67), `None` at a singular point.
    fn normal(&self, uv: Point2<f64>) -> Result<Option<Vector3<f64>>, OutsideDomain> {
        let j = self.jet(uv)?.jet;
        let n = j.dx.cross(&j.dy);
        let size = j.dx.norm() * j.dy.norm();
        Ok((n.norm() > 1e-14 * size && size > 0.0).then(|| n.normalize()))
    }
}

/// Forwards the trait through references and smart pointers.
macro_rules! forward_surface {
    ($($wrapper:ty),*) => {$(
        impl<S: ParametricSurface + ?Sized> ParametricSurface for $wrapper {
            fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
                (**self).domain_bounds()
            }
            fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
                (**self).cursor_near(uv)
            }
            fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
                (**self).jet_with(uv, cursor)
            }
        }
    )*};
}

forward_surface!(&S, Box<S>, Arc<S>);

/// A surface made of smooth (polynomial or rational) pieces, each over a triangle of the
/// parameter domain: the PS sub-triangles of Δ* for PS, UPS and NURPS surfaces, the patch
/// itself for a Bézier triangle. Values and first derivatives are continuous across the
/// pieces; second derivatives, and so curvature, may jump. Sampling piece by piece gives
/// each piece its own values on shared edges, so plots show the jumps.
pub trait PatchwiseSurface: ParametricSurface {
    /// The number of pieces.
    fn patch_count(&self) -> usize;

    /// The parameter triangle of piece `k`.
    fn patch_domain(&self, k: usize) -> Triangle2;

    /// The jet of piece `k` (extended as a polynomial or rational function) at the parameter
    /// `uv` with barycentric coordinates `bary` in `map`, the barycentric map of
    /// `patch_domain(k)`.
    fn patch_jet(&self, k: usize, uv: Point2<f64>, bary: Bary, map: &BaryMap) -> Jet<Vector3<f64>>;
}

impl<S: PatchwiseSurface + ?Sized> PatchwiseSurface for &S {
    fn patch_count(&self) -> usize {
        (**self).patch_count()
    }
    fn patch_domain(&self, k: usize) -> Triangle2 {
        (**self).patch_domain(k)
    }
    fn patch_jet(&self, k: usize, uv: Point2<f64>, bary: Bary, map: &BaryMap) -> Jet<Vector3<f64>> {
        (**self).patch_jet(k, uv, bary, map)
    }
}

/// Jets at many parameter points, in parallel on all cores. Points are processed in
/// consecutive chunks with one cursor each, so grids and curves cost short walks.
pub fn jets<S: ParametricSurface + ?Sized>(
    surface: &S,
    points: &[Point2<f64>],
) -> Vec<Result<SurfaceJet, OutsideDomain>> {
    use rayon::prelude::*;
    let unset = Err(OutsideDomain {
        u: f64::NAN,
        v: f64::NAN,
    });
    let mut out = vec![unset; points.len()];
    points
        .par_chunks(8192)
        .zip(out.par_chunks_mut(8192))
        .for_each(|(pts, res)| {
            let mut cursor = surface.cursor_near(pts[0]);
            for (r, &p) in res.iter_mut().zip(pts) {
                *r = surface.jet_with(p, &mut cursor);
            }
        });
    out
}

/// Evaluates `f(jet, row)` at every point in parallel, writing `width` numbers per point into
/// `out` (`out.len() == points.len() * width`); points outside the domain get `f(Err, row)`.
/// Nothing is materialised per point, so this is the way to fill large output tables.
pub fn fill_rows<S: ParametricSurface + ?Sized>(
    surface: &S,
    points: &[Point2<f64>],
    width: usize,
    out: &mut [f64],
    f: impl Fn(Point2<f64>, Result<&SurfaceJet, OutsideDomain>, &mut [f64]) + Sync,
) {
    use rayon::prelude::*;
    assert_eq!(out.len(), points.len() * width, "one row per point");
    const CHUNK: usize = 8192;
    points
        .par_chunks(CHUNK)
        .zip(out.par_chunks_mut(CHUNK * width))
        .for_each(|(pts, rows)| {
            let mut cursor = surface.cursor_near(pts[0]);
            for (&p, row) in pts.iter().zip(rows.chunks_mut(width)) {
                match surface.jet_with(p, &mut cursor) {
                    Ok(j) => f(p, Ok(&j), row),
                    Err(e) => f(p, Err(e), row),
                }
            }
        });
}

/// The graph (x, y, f(x, y)) of a scalar jet.
pub fn graph_jet(p: Point2<f64>, j: &Jet<f64>) -> Jet<Vector3<f64>> {
    Jet {
        value: Vector3::new(p.x, p.y, j.value),
        dx: Vector3::new(1.0, 0.0, j.dx),
        dy: Vector3::new(0.0, 1.0, j.dy),
        dxx: Vector3::new(0.0, 0.0, j.dxx),
        dxy: Vector3::new(0.0, 0.0, j.dxy),
        dyy: Vector3::new(0.0, 0.0, j.dyy),
    }
}

fn ps_locate<V: crate::vector::Vector>(
    s: &PsSpline<V>,
    uv: Point2<f64>,
    cursor: &mut Cursor,
) -> Result<PsJet<V>, OutsideDomain> {
    let loc = s
        .basis()
        .locate(uv, cursor.0)
        .ok_or(OutsideDomain { u: uv.x, v: uv.y })?;
    cursor.0 = loc.triangle;
    Ok(s.jet_at(&loc))
}

impl ParametricSurface for PsSpline<Vector3<f64>> {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        self.basis().triangulation().bounds()
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        Cursor(self.basis().triangulation().start_triangle(uv))
    }
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        let j = ps_locate(self, uv, cursor)?;
        Ok(SurfaceJet {
            jet: j.jet,
            patch: Some(j.patch),
        })
    }
}

impl ParametricSurface for PsSpline<f64> {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        self.basis().triangulation().bounds()
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        Cursor(self.basis().triangulation().start_triangle(uv))
    }
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        let j = ps_locate(self, uv, cursor)?;
        Ok(SurfaceJet {
            jet: graph_jet(uv, &j.jet),
            patch: Some(j.patch),
        })
    }
}

impl ParametricSurface for Nurps<Vector3<f64>> {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        self.basis().triangulation().bounds()
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        Cursor(self.basis().triangulation().start_triangle(uv))
    }
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        let j = self
            .jet_from(uv, &mut cursor.0)
            .map_err(|_| OutsideDomain { u: uv.x, v: uv.y })?;
        Ok(SurfaceJet {
            jet: j.jet,
            patch: Some(j.patch),
        })
    }
}

fn triangle_bounds(t: &crate::geometry::Triangle2) -> (Point2<f64>, Point2<f64>) {
    let xs = t.v.map(|p| p.x);
    let ys = t.v.map(|p| p.y);
    let min = |a: [f64; 3]| a[0].min(a[1]).min(a[2]);
    let max = |a: [f64; 3]| a[0].max(a[1]).max(a[2]);
    (Point2::new(min(xs), min(ys)), Point2::new(max(xs), max(ys)))
}

fn inside(t: &crate::geometry::Triangle2, uv: Point2<f64>) -> Result<(), OutsideDomain> {
    if t.bary(uv)
        .iter()
        .all(|&b| b >= -crate::triangulation::INSIDE_TOLERANCE)
    {
        Ok(())
    } else {
        Err(OutsideDomain { u: uv.x, v: uv.y })
    }
}

impl ParametricSurface for BezierTriangle<Vector3<f64>> {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        triangle_bounds(self.domain())
    }
    fn jet_with(&self, uv: Point2<f64>, _: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        inside(self.domain(), uv)?;
        Ok(SurfaceJet {
            jet: self.jet(uv),
            patch: None,
        })
    }
}

impl ParametricSurface for RationalBezierTriangle<Vector3<f64>> {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        triangle_bounds(self.domain())
    }
    fn jet_with(&self, uv: Point2<f64>, _: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        inside(self.domain(), uv)?;
        let jet = self
            .jet(uv)
            .map_err(|_| OutsideDomain { u: uv.x, v: uv.y })?;
        Ok(SurfaceJet { jet, patch: None })
    }
}

impl PatchwiseSurface for BezierTriangle<Vector3<f64>> {
    fn patch_count(&self) -> usize {
        1
    }
    fn patch_domain(&self, _: usize) -> Triangle2 {
        *self.domain()
    }
    fn patch_jet(&self, _: usize, uv: Point2<f64>, _: Bary, _: &BaryMap) -> Jet<Vector3<f64>> {
        self.jet(uv)
    }
}

impl PatchwiseSurface for RationalBezierTriangle<Vector3<f64>> {
    fn patch_count(&self) -> usize {
        1
    }
    fn patch_domain(&self, _: usize) -> Triangle2 {
        *self.domain()
    }
    fn patch_jet(&self, _: usize, uv: Point2<f64>, _: Bary, _: &BaryMap) -> Jet<Vector3<f64>> {
        // Weights are positive (checked on construction), so the denominator is positive on
        // the domain triangle.
        self.jet(uv).expect("positive weights")
    }
}

/// The PS surface kinds of a file, in one type that forwards the traits.
#[derive(Clone, Debug)]
pub enum PsSurface {
    /// A functional PS-spline surface z = s(x, y) (2.49).
    Functional(PsSpline<f64>),
    /// A parametric PS-spline surface (2.64).
    Parametric(PsSpline<Vector3<f64>>),
    /// A NURPS surface (3.32).
    Rational(Nurps<Vector3<f64>>),
}

impl PsSurface {
    /// The kind's name as in the file format: "functional", "parametric" or "nurps".
    pub fn kind_name(&self) -> &'static str {
        match self {
            PsSurface::Functional(_) => "functional",
            PsSurface::Parametric(_) => "parametric",
            PsSurface::Rational(_) => "nurps",
        }
    }

    /// The basis (triangulation, refinement, PS-triangles).
    pub fn basis(&self) -> &Arc<crate::ps::PsBasis> {
        match self {
            PsSurface::Functional(s) => s.basis(),
            PsSurface::Parametric(s) => s.basis(),
            PsSurface::Rational(s) => s.basis(),
        }
    }

    /// The control points in R³ (for a functional surface (X_ij, Y_ij, c_ij), Definition 2.23).
    pub fn control_points(&self) -> Vec<[Vector3<f64>; 3]> {
        (0..self.basis().triangulation().vertex_count())
            .map(|i| self.control_triangle(i))
            .collect()
    }

    /// The control triangle of vertex `i` in R³ (Definition 2.24).
    ///
    /// # Panics
    /// If `i` is not a vertex.
    pub fn control_triangle(&self, i: usize) -> [Vector3<f64>; 3] {
        match self {
            PsSurface::Functional(s) => {
                let q = s.basis().control_xy(i);
                let c = s.coefficients()[i];
                std::array::from_fn(|j| Vector3::new(q[j].x, q[j].y, c[j]))
            }
            PsSurface::Parametric(s) => s.coefficients()[i],
            PsSurface::Rational(s) => s.points()[i],
        }
    }
}

impl ParametricSurface for PsSurface {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        self.basis().triangulation().bounds()
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        Cursor(self.basis().triangulation().start_triangle(uv))
    }
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        match self {
            PsSurface::Functional(s) => s.jet_with(uv, cursor),
            PsSurface::Parametric(s) => s.jet_with(uv, cursor),
            PsSurface::Rational(s) => s.jet_with(uv, cursor),
        }
    }
}

impl PatchwiseSurface for PsSurface {
    fn patch_count(&self) -> usize {
        6 * self.basis().triangulation().triangle_count()
    }
    fn patch_domain(&self, k: usize) -> Triangle2 {
        self.basis().sub_triangle(k / 6, k % 6)
    }
    fn patch_jet(&self, k: usize, uv: Point2<f64>, bary: Bary, map: &BaryMap) -> Jet<Vector3<f64>> {
        let loc = crate::ps::SubLocation {
            triangle: k / 6,
            sub: k % 6,
            bary,
            dx: map.dx(),
            dy: map.dy(),
        };
        match self {
            PsSurface::Functional(s) => graph_jet(uv, &s.jet_at(&loc).jet),
            PsSurface::Parametric(s) => s.jet_at(&loc).jet,
            PsSurface::Rational(s) => s.jet_at(&loc).jet,
        }
    }
}

/// A uniform PS-spline of any kind, in its block-matrix form.
#[derive(Clone, Debug, PartialEq)]
pub enum UpsSurface {
    /// A functional UPS-spline z = s(x, y).
    Functional(Ups<f64>),
    /// A parametric UPS-spline surface.
    Parametric(Ups<Vector3<f64>>),
    /// A rational UPS-spline surface (NURPS on a uniform triangulation).
    Rational(Ups<Weighted<Vector3<f64>>>),
}

impl UpsSurface {
    /// The triangulation.
    pub fn grid(&self) -> &UpsGrid {
        match self {
            UpsSurface::Functional(s) => s.grid(),
            UpsSurface::Parametric(s) => s.grid(),
            UpsSurface::Rational(s) => s.grid(),
        }
    }

    /// The kind's name as in the file format.
    pub fn kind_name(&self) -> &'static str {
        match self {
            UpsSurface::Functional(_) => "functional",
            UpsSurface::Parametric(_) => "parametric",
            UpsSurface::Rational(_) => "nurps",
        }
    }

    /// The same surface as a general PS surface.
    pub fn to_general(&self) -> Result<PsSurface, UpsError> {
        Ok(match self {
            UpsSurface::Functional(s) => PsSurface::Functional(s.to_ps()?),
            UpsSurface::Parametric(s) => PsSurface::Parametric(s.to_ps()?),
            UpsSurface::Rational(s) => PsSurface::Rational(s.to_nurps()?),
        })
    }

    /// `times` subdivision steps.
    pub fn subdivide_times(&self, times: usize) -> UpsSurface {
        match self {
            UpsSurface::Functional(s) => UpsSurface::Functional(s.subdivide_times(times)),
            UpsSurface::Parametric(s) => UpsSurface::Parametric(s.subdivide_times(times)),
            UpsSurface::Rational(s) => UpsSurface::Rational(s.subdivide_times(times)),
        }
    }
}

/// What a surface file holds: a general PS surface, or a uniform one (whose general form is
/// built when first needed, e.g. for evaluation).
#[derive(Debug)]
pub enum Surface {
    /// A PS, parametric PS or NURPS surface on any triangulation.
    General(PsSurface),
    /// A UPS surface, with its general form once built.
    Uniform(UpsSurface, std::sync::OnceLock<PsSurface>),
}

impl Clone for Surface {
    fn clone(&self) -> Self {
        match self {
            Surface::General(s) => Surface::General(s.clone()),
            Surface::Uniform(u, g) => {
                let lock = std::sync::OnceLock::new();
                if let Some(g) = g.get() {
                    let _ = lock.set(g.clone());
                }
                Surface::Uniform(u.clone(), lock)
            }
        }
    }
}

impl From<PsSurface> for Surface {
    fn from(s: PsSurface) -> Self {
        Surface::General(s)
    }
}

impl From<UpsSurface> for Surface {
    fn from(s: UpsSurface) -> Self {
        Surface::Uniform(s, std::sync::OnceLock::new())
    }
}

impl Surface {
    /// The general form (for a uniform surface, built on first use).
    pub fn general(&self) -> &PsSurface {
        match self {
            Surface::General(s) => s,
            Surface::Uniform(u, g) => g.get_or_init(|| {
                u.to_general()
                    .expect("a validated uniform triangulation always has a PS basis with t(6)")
            }),
        }
    }

    /// The uniform form, if any.
    pub fn uniform(&self) -> Option<&UpsSurface> {
        match self {
            Surface::Uniform(u, _) => Some(u),
            Surface::General(_) => None,
        }
    }

    /// "functional", "parametric" or "nurps".
    pub fn kind_name(&self) -> &'static str {
        match self {
            Surface::General(s) => s.kind_name(),
            Surface::Uniform(u, _) => u.kind_name(),
        }
    }

    /// True for a functional surface (evaluation points may be given as x, y).
    pub fn is_functional(&self) -> bool {
        self.kind_name() == "functional"
    }
}

impl PatchwiseSurface for Surface {
    fn patch_count(&self) -> usize {
        self.general().patch_count()
    }
    fn patch_domain(&self, k: usize) -> Triangle2 {
        self.general().patch_domain(k)
    }
    fn patch_jet(&self, k: usize, uv: Point2<f64>, bary: Bary, map: &BaryMap) -> Jet<Vector3<f64>> {
        self.general().patch_jet(k, uv, bary, map)
    }
}

impl ParametricSurface for Surface {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        self.general().domain_bounds()
    }
    fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
        self.general().cursor_near(uv)
    }
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        self.general().jet_with(uv, cursor)
    }
}
