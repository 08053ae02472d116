//! The surface traits for each concrete kind: the three PS kinds (functional, parametric,
//! NURPS) share one set of generic functions through [`PsKind`]; Bézier and rational Bézier
//! triangles are one piece each.

use std::ops::Range;
use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::control::check_point;
use super::piece::{LocalCoords, PieceKind, PiecePoint, PieceShape};
use super::{
    ControlFreedom, ControlId, ControlNet, ControlPoint, Cursor, EditError, OutsideDomain,
    ParametricSurface, PiecewiseSurface, SurfaceJet, graph_jet,
};
use crate::bezier::index::multi_indices;
use crate::bezier::{BezierTriangle, Jet, RationalBezierTriangle};
use crate::geometry::Triangle2;
use crate::ps::{Nurps, PsBasis, PsSpline, SubLocation};
use crate::triangulation::INSIDE_TOLERANCE;

/// What the generic PS code needs from one PS kind.
pub(crate) trait PsKind {
    /// The basis.
    fn ps_basis(&self) -> &Arc<PsBasis>;
    /// The surface jet at a located point with parameters `uv`.
    fn located_jet(&self, loc: &SubLocation, uv: Point2<f64>) -> Jet<Vector3<f64>>;
    /// Control point j of vertex i.
    fn vertex_point(&self, i: usize, j: usize) -> ControlPoint;
    /// True for NURPS.
    const RATIONAL: bool;
    /// Which coordinates may change.
    const FREEDOM: ControlFreedom;
    /// Replaces the control triangles of the given vertices (validated by the caller) and
    /// rebuilds the Bézier nets of their molecules.
    fn write_vertices(&mut self, vertices: &[(usize, [ControlPoint; 3])]);
}

/// The values of a polynomial PS-spline: heights (functional) or points (parametric).
pub(crate) trait PsValue: crate::vector::Vector {
    /// Which coordinates of a control point are free.
    const FREEDOM: ControlFreedom;
    /// The surface jet of the spline's jet at `uv` (the graph for heights).
    fn surface_jet(jet: &Jet<Self>, uv: Point2<f64>) -> Jet<Vector3<f64>>;
    /// The control point of value `v` whose domain point is `xy` (Definition 2.23).
    fn control_point(v: Self, xy: Point2<f64>) -> Vector3<f64>;
    /// The value of a control point.
    fn from_control_point(p: Vector3<f64>) -> Self;
}

impl PsValue for f64 {
    const FREEDOM: ControlFreedom = ControlFreedom::Height;
    #[inline]
    fn surface_jet(jet: &Jet<f64>, uv: Point2<f64>) -> Jet<Vector3<f64>> {
        graph_jet(uv, jet)
    }
    fn control_point(v: f64, xy: Point2<f64>) -> Vector3<f64> {
        Vector3::new(xy.x, xy.y, v)
    }
    fn from_control_point(p: Vector3<f64>) -> f64 {
        p.z
    }
}

impl PsValue for Vector3<f64> {
    const FREEDOM: ControlFreedom = ControlFreedom::Full;
    #[inline]
    fn surface_jet(jet: &Jet<Vector3<f64>>, _: Point2<f64>) -> Jet<Vector3<f64>> {
        *jet
    }
    fn control_point(v: Vector3<f64>, _: Point2<f64>) -> Vector3<f64> {
        v
    }
    fn from_control_point(p: Vector3<f64>) -> Vector3<f64> {
        p
    }
}

impl<V: PsValue> PsKind for PsSpline<V> {
    fn ps_basis(&self) -> &Arc<PsBasis> {
        self.basis()
    }
    #[inline]
    fn located_jet(&self, loc: &SubLocation, uv: Point2<f64>) -> Jet<Vector3<f64>> {
        V::surface_jet(&self.jet_at(loc).jet, uv)
    }
    fn vertex_point(&self, i: usize, j: usize) -> ControlPoint {
        let xy = self.basis().control_xy(i)[j];
        ControlPoint::new(V::control_point(self.coefficients()[i][j], xy))
    }
    const RATIONAL: bool = false;
    const FREEDOM: ControlFreedom = V::FREEDOM;
    fn write_vertices(&mut self, vertices: &[(usize, [ControlPoint; 3])]) {
        let changes: Vec<_> = vertices
            .iter()
            .map(|(i, c)| (*i, c.map(|p| V::from_control_point(p.position))))
            .collect();
        self.set_vertices(&changes);
    }
}

impl PsKind for Nurps<Vector3<f64>> {
    fn ps_basis(&self) -> &Arc<PsBasis> {
        self.basis()
    }
    #[inline]
    fn located_jet(&self, loc: &SubLocation, _: Point2<f64>) -> Jet<Vector3<f64>> {
        self.jet_at(loc).jet
    }
    fn vertex_point(&self, i: usize, j: usize) -> ControlPoint {
        ControlPoint {
            position: self.points()[i][j],
            weight: self.weights()[i][j],
        }
    }
    const RATIONAL: bool = true;
    const FREEDOM: ControlFreedom = ControlFreedom::Full;
    fn write_vertices(&mut self, vertices: &[(usize, [ControlPoint; 3])]) {
        let changes: Vec<_> = vertices
            .iter()
            .map(|(i, c)| (*i, c.map(|p| p.position), c.map(|p| p.weight)))
            .collect();
        self.set_vertices(&changes);
    }
}

/// [`ParametricSurface::jet_with`] for PS kinds: walk from the cursor's triangle.
#[inline]
pub(crate) fn ps_jet_with<T: PsKind>(
    s: &T,
    uv: Point2<f64>,
    cursor: &mut Cursor,
) -> Result<SurfaceJet, OutsideDomain> {
    let loc = s
        .ps_basis()
        .locate(uv, cursor.0)
        .ok_or(OutsideDomain::at(uv))?;
    cursor.0 = loc.triangle;
    Ok(SurfaceJet {
        jet: s.located_jet(&loc, uv),
        piece: 6 * loc.triangle + loc.sub,
    })
}

/// [`PiecewiseSurface::piece_jet`] for PS kinds: piece k is sub-triangle k % 6 of triangle
/// k / 6.
#[inline]
pub(crate) fn ps_piece_jet<T: PsKind>(s: &T, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
    let LocalCoords::Bary { bary, du, dv } = at.local else {
        panic!("PS pieces are triangles");
    };
    let loc = SubLocation {
        triangle: k / 6,
        sub: k % 6,
        bary,
        dx: du,
        dy: dv,
    };
    s.located_jet(&loc, at.uv)
}

/// The pieces of the molecules of `vertices`: the six sub-triangles of each of their
/// triangles, in increasing order.
pub(crate) fn molecule_pieces(
    basis: &PsBasis,
    vertices: impl IntoIterator<Item = usize>,
) -> Vec<usize> {
    basis
        .triangulation()
        .molecules_of(vertices)
        .into_iter()
        .flat_map(|t| 6 * t..6 * t + 6)
        .collect()
}

/// [`ControlNet::set_control_points`] for PS kinds: validate all, then write each touched
/// vertex's control triangle once.
pub(crate) fn ps_set_control_points<T: PsKind>(
    s: &mut T,
    changes: &[(ControlId, ControlPoint)],
) -> Result<Vec<usize>, EditError> {
    let count = 3 * s.ps_basis().triangulation().vertex_count();
    for (id, p) in changes {
        check_point(*id, p, count, T::RATIONAL)?;
    }
    let mut touched: Vec<(usize, [ControlPoint; 3])> = Vec::new();
    let mut slot = std::collections::HashMap::new();
    for &(ControlId(id), p) in changes {
        let (i, j) = (id / 3, id % 3);
        let k = *slot.entry(i).or_insert_with(|| {
            touched.push((i, std::array::from_fn(|j| s.vertex_point(i, j))));
            touched.len() - 1
        });
        touched[k].1[j] = p;
    }
    s.write_vertices(&touched);
    Ok(molecule_pieces(
        s.ps_basis(),
        touched.iter().map(|(i, _)| *i),
    ))
}

/// Implements the surface traits for a PS kind through the generic functions above.
macro_rules! impl_ps_kind {
    ($($kind:ty),*) => {$(
        impl ParametricSurface for $kind {
            fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
                self.basis().triangulation().bounds()
            }
            fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
                Cursor(self.basis().triangulation().start_triangle(uv))
            }
            #[inline]
            fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
                ps_jet_with(self, uv, cursor)
            }
        }

        impl PiecewiseSurface for $kind {
            fn piece_count(&self) -> usize {
                6 * self.basis().triangulation().triangle_count()
            }
            fn piece_kind(&self) -> PieceKind {
                PieceKind::Triangle
            }
            fn piece_shape(&self, k: usize) -> PieceShape {
                PieceShape::Triangle(self.basis().sub_triangle(k / 6, k % 6))
            }
            #[inline]
            fn piece_jet(&self, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
                ps_piece_jet(self, k, at)
            }
        }

        impl ControlNet for $kind {
            fn control_count(&self) -> usize {
                3 * self.basis().triangulation().vertex_count()
            }
            fn control_point(&self, id: ControlId) -> Option<ControlPoint> {
                (id.0 < self.control_count()).then(|| self.vertex_point(id.0 / 3, id.0 % 3))
            }
            fn is_rational(&self) -> bool {
                <$kind as PsKind>::RATIONAL
            }
            fn freedom(&self) -> ControlFreedom {
                <$kind as PsKind>::FREEDOM
            }
            fn control_group(&self, id: ControlId) -> Range<usize> {
                3 * (id.0 / 3)..3 * (id.0 / 3) + 3
            }
            fn control_anchor(&self, id: ControlId) -> Point2<f64> {
                self.basis().triangulation().vertex(id.0 / 3)
            }
            fn support(&self, id: ControlId) -> Vec<usize> {
                molecule_pieces(self.basis(), [id.0 / 3])
            }
            fn set_control_points(
                &mut self,
                changes: &[(ControlId, ControlPoint)],
            ) -> Result<Vec<usize>, EditError> {
                ps_set_control_points(self, changes)
            }
        }
    )*};
}

impl_ps_kind!(PsSpline<f64>, PsSpline<Vector3<f64>>, Nurps<Vector3<f64>>);

/// The bounding box of a triangle.
fn triangle_bounds(t: &Triangle2) -> (Point2<f64>, Point2<f64>) {
    let xs = t.v.map(|p| p.x);
    let ys = t.v.map(|p| p.y);
    let min = |a: [f64; 3]| a[0].min(a[1]).min(a[2]);
    let max = |a: [f64; 3]| a[0].max(a[1]).max(a[2]);
    (Point2::new(min(xs), min(ys)), Point2::new(max(xs), max(ys)))
}

/// `Ok` when `uv` lies in the triangle (up to the same tolerance as PS point location).
fn inside(t: &Triangle2, uv: Point2<f64>) -> Result<(), OutsideDomain> {
    if t.bary(uv).iter().all(|&b| b >= -INSIDE_TOLERANCE) {
        Ok(())
    } else {
        Err(OutsideDomain::at(uv))
    }
}

/// The domain point λ/m of ordinate `id` of a degree-m net on `t` (Definition 2.8).
fn ordinate_anchor(t: &Triangle2, degree: usize, id: usize) -> Point2<f64> {
    let m = degree.max(1) as f64;
    let l = multi_indices(degree)
        .nth(id)
        .expect("ordinate index in range");
    t.point([l[0] as f64 / m, l[1] as f64 / m, l[2] as f64 / m])
}

/// The lines of a degree-m Bézier net: for each direction, the ordinates with one index
/// fixed, in storage order (see [`crate::bezier::index`]).
fn bezier_net_lines(m: usize) -> Vec<Vec<ControlId>> {
    let all: Vec<[usize; 3]> = multi_indices(m).collect();
    let mut out = Vec::new();
    for fixed in 0..3 {
        for value in 0..m {
            let line: Vec<ControlId> = (0..all.len())
                .filter(|&k| all[k][fixed] == value)
                .map(ControlId)
                .collect();
            if line.len() >= 2 {
                out.push(line);
            }
        }
    }
    out
}

/// A NaN jet: what an extension of a rational piece gives where its denominator vanishes.
fn undefined_jet() -> Jet<Vector3<f64>> {
    let nan = Vector3::repeat(f64::NAN);
    Jet {
        value: nan,
        dx: nan,
        dy: nan,
        dxx: nan,
        dxy: nan,
        dyy: nan,
    }
}

/// Implements the surface traits for a Bézier kind, given how to compute a jet at a domain
/// point and how to read and write an ordinate.
macro_rules! impl_bezier_kind {
    ($kind:ty, rational: $rational:expr, jet: |$s:ident, $uv:ident| $jet:expr) => {
        impl ParametricSurface for $kind {
            fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
                triangle_bounds(self.domain())
            }
            fn jet_with(
                &self,
                uv: Point2<f64>,
                _: &mut Cursor,
            ) -> Result<SurfaceJet, OutsideDomain> {
                inside(self.domain(), uv)?;
                let ($s, $uv) = (self, uv);
                Ok(SurfaceJet {
                    jet: $jet,
                    piece: 0,
                })
            }
        }

        impl PiecewiseSurface for $kind {
            fn piece_count(&self) -> usize {
                1
            }
            fn piece_kind(&self) -> PieceKind {
                PieceKind::Triangle
            }
            fn piece_shape(&self, _: usize) -> PieceShape {
                PieceShape::Triangle(*self.domain())
            }
            fn piece_jet(&self, _: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
                let ($s, $uv) = (self, at.uv);
                $jet
            }
        }

        impl ControlNet for $kind {
            fn control_count(&self) -> usize {
                self.points().len()
            }
            fn control_point(&self, id: ControlId) -> Option<ControlPoint> {
                let position = *self.points().get(id.0)?;
                Some(ControlPoint {
                    position,
                    weight: self.ordinate_weight(id.0),
                })
            }
            fn is_rational(&self) -> bool {
                $rational
            }
            fn freedom(&self) -> ControlFreedom {
                ControlFreedom::Full
            }
            fn control_group(&self, id: ControlId) -> Range<usize> {
                id.0..id.0 + 1
            }
            fn control_anchor(&self, id: ControlId) -> Point2<f64> {
                ordinate_anchor(self.domain(), self.degree(), id.0)
            }
            fn support(&self, _: ControlId) -> Vec<usize> {
                vec![0]
            }
            fn control_polylines(&self) -> Vec<Vec<ControlId>> {
                bezier_net_lines(self.degree())
            }
            fn set_control_points(
                &mut self,
                changes: &[(ControlId, ControlPoint)],
            ) -> Result<Vec<usize>, EditError> {
                let count = self.control_count();
                for (id, p) in changes {
                    check_point(*id, p, count, $rational)?;
                }
                for (id, p) in changes {
                    self.set_ordinate(id.0, p.position, p.weight);
                }
                Ok(if changes.is_empty() { vec![] } else { vec![0] })
            }
        }
    };
}

impl_bezier_kind!(BezierTriangle<Vector3<f64>>, rational: false, jet: |s, uv| s.jet(uv));
impl_bezier_kind!(
    RationalBezierTriangle<Vector3<f64>>,
    rational: true,
    // Weights are positive, so the denominator is positive on the domain triangle; a NaN jet
    // marks an extension beyond it where the denominator vanishes.
    jet: |s, uv| s.jet(uv).unwrap_or_else(|_| undefined_jet())
);

/// Reading and writing one ordinate with its weight, the same way for both Bézier kinds.
trait Ordinates {
    fn ordinate_weight(&self, i: usize) -> f64;
    fn set_ordinate(&mut self, i: usize, p: Vector3<f64>, w: f64);
}

impl Ordinates for BezierTriangle<Vector3<f64>> {
    fn ordinate_weight(&self, _: usize) -> f64 {
        1.0
    }
    fn set_ordinate(&mut self, i: usize, p: Vector3<f64>, _: f64) {
        self.points_mut()[i] = p;
    }
}

impl Ordinates for RationalBezierTriangle<Vector3<f64>> {
    fn ordinate_weight(&self, i: usize) -> f64 {
        self.weights()[i]
    }
    fn set_ordinate(&mut self, i: usize, p: Vector3<f64>, w: f64) {
        self.set_weighted_ordinate(i, p, w);
    }
}
