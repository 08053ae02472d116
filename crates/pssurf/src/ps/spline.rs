//! PS-splines s(u) = Σ_i Σ_j c_ij B_i^j(u) (2.31), functional (values in R) or parametric
//! (values in R³, (2.64)–(2.65)), with cached Bézier nets.

use std::sync::Arc;

use nalgebra::Point2;
use rayon::prelude::*;

use super::basis::{PsBasis, SubLocation};
use super::net::{NET_LEN, SUB_ORDINATES};
use super::{PatchId, PsError};
use crate::bezier::triangle::quadratic_jet;
use crate::bezier::{BezierTriangle, Jet};
use crate::surface::for_each_chunk;
use crate::triangulation::Cursor;
use crate::vector::Vector;

/// Hermite data at a vertex: the value and the two partial derivatives (2.30).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hermite<V> {
    /// s(V_i).
    pub value: V,
    /// ∂s/∂x (V_i).
    pub dx: V,
    /// ∂s/∂y (V_i).
    pub dy: V,
}

/// A value with derivatives and the sub-triangle of Δ* it was computed on. A PS-spline is
/// only C¹: second derivatives jump across the edges of Δ*, so they belong to a patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PsJet<V> {
    /// Value and partial derivatives up to order two.
    pub jet: Jet<V>,
    /// The sub-triangle used.
    pub patch: PatchId,
}

/// A PS-spline with its control values c_i1, c_i2, c_i3 per vertex and the cached Bézier
/// net of every triangle, so that evaluation costs a point location plus one quadratic
/// de Casteljau step (Algorithm 2.2).
#[derive(Clone, Debug)]
pub struct PsSpline<V> {
    basis: Arc<PsBasis>,
    coeffs: Vec<[V; 3]>,
    nets: Vec<[V; NET_LEN]>,
}

impl<V: Vector> PsSpline<V> {
    /// The spline with the given control values (one triple per vertex), validated: the count
    /// must match and every value must be finite.
    pub fn new(basis: Arc<PsBasis>, coeffs: Vec<[V; 3]>) -> Result<Self, PsError> {
        check_coefficients(&basis, &coeffs)?;
        let nets = build_nets(&basis, &coeffs);
        Ok(PsSpline {
            basis,
            coeffs,
            nets,
        })
    }

    /// The Hermite interpolant (2.30): the unique spline with the given value and gradient at
    /// every vertex (coefficients by (2.45), see [`PsBasis::hermite_coefficients`]).
    pub fn hermite(basis: Arc<PsBasis>, data: &[Hermite<V>]) -> Result<Self, PsError> {
        let coeffs = hermite_coefficients(&basis, data)?;
        Self::new(basis, coeffs)
    }

    /// [`hermite`](Self::hermite) with the Bézier nets computed from the data directly
    /// ([`PsBasis::hermite_net`]) instead of from the control values: the same function to
    /// the last bit whatever the PS-triangles (e.g. cheap
    /// [`Circumscribed`](super::PsTriangleChoice::Circumscribed) ones for a spline made to
    /// be evaluated). Its nets differ by rounding from those of `hermite`, which are what a
    /// saved and loaded file has.
    pub fn hermite_direct(basis: Arc<PsBasis>, data: &[Hermite<V>]) -> Result<Self, PsError> {
        let coeffs = hermite_coefficients(&basis, data)?;
        // Coefficients within range make the data finite (the map (2.45) is invertible).
        check_coefficients(&basis, &coeffs)?;
        let nets = (0..basis.triangulation().triangle_count())
            .into_par_iter()
            .with_min_len(1024)
            .map(|t| basis.hermite_net(t, |i| data[i]))
            .collect();
        Ok(PsSpline {
            basis,
            coeffs,
            nets,
        })
    }

    /// The Hermite interpolant of a function given with its gradient, `f(p) = (f, f_x, f_y)`.
    pub fn interpolate(
        basis: Arc<PsBasis>,
        f: impl Fn(Point2<f64>) -> Hermite<V>,
    ) -> Result<Self, PsError> {
        let data: Vec<_> = basis
            .triangulation()
            .vertices()
            .iter()
            .map(|&p| f(p))
            .collect();
        Self::hermite(basis, &data)
    }

    /// The basis.
    pub fn basis(&self) -> &Arc<PsBasis> {
        &self.basis
    }

    /// The control values, one triple per vertex.
    pub fn coefficients(&self) -> &[[V; 3]] {
        &self.coeffs
    }

    /// Replaces the control values of vertex i and updates only the nets of its molecule
    /// (local control: B_i^j vanishes outside M_i).
    pub fn set_coefficients(&mut self, i: usize, c: [V; 3]) -> Result<(), PsError> {
        if let Some(j) = c.iter().position(|v| !v.in_range()) {
            return Err(PsError::NonFiniteCoefficient {
                vertex: i,
                index: j,
            });
        }
        self.set_vertices(&[(i, c)]);
        Ok(())
    }

    /// Replaces the control values of several vertices (unchecked: values must be finite)
    /// and rebuilds the nets of the triangles in their molecules, each once.
    pub(crate) fn set_vertices(&mut self, changes: &[(usize, [V; 3])]) {
        for &(i, c) in changes {
            self.coeffs[i] = c;
        }
        let basis = &self.basis;
        let touched = basis
            .triangulation()
            .molecules_of(changes.iter().map(|c| c.0));
        let coeffs = &self.coeffs;
        rebuild_nets(&mut self.nets, &touched, |t| basis.net(t, coeffs));
    }

    /// The 19 Bézier ordinates of triangle `t` (layout in [`super::net`]).
    pub fn net(&self, t: usize) -> &[V; NET_LEN] {
        &self.nets[t]
    }

    /// The quadratic Bézier patch of sub-triangle `sub` of triangle `t`.
    pub fn patch(&self, t: usize, sub: usize) -> BezierTriangle<V> {
        let n = &self.nets[t];
        let pts = SUB_ORDINATES[sub].iter().map(|&k| n[k]).collect();
        let tri = self.basis.sub_triangle(t, sub);
        BezierTriangle::try_new(tri, 2, pts).expect("sub-triangles of a valid refinement")
    }

    /// The value and derivatives at a located point.
    #[inline]
    pub fn jet_at(&self, loc: &SubLocation) -> PsJet<V> {
        let n = &self.nets[loc.triangle];
        let idx = &SUB_ORDINATES[loc.sub];
        let q = [
            n[idx[0]], n[idx[1]], n[idx[2]], n[idx[3]], n[idx[4]], n[idx[5]],
        ];
        PsJet {
            jet: quadratic_jet(&q, loc.bary, loc.dx, loc.dy, 2.0),
            patch: PatchId::new(loc.triangle, loc.sub),
        }
    }

    /// The value and the gradient (∂s/∂x, ∂s/∂y) at a located point (Algorithm 2.2, step 4).
    #[inline]
    pub fn gradient_at(&self, loc: &SubLocation) -> (V, V, V) {
        let n = &self.nets[loc.triangle];
        let i = &SUB_ORDINATES[loc.sub];
        let t = loc.bary;
        let b0 = n[i[0]] * t[0] + n[i[1]] * t[1] + n[i[2]] * t[2];
        let b1 = n[i[1]] * t[0] + n[i[3]] * t[1] + n[i[4]] * t[2];
        let b2 = n[i[2]] * t[0] + n[i[4]] * t[1] + n[i[5]] * t[2];
        let value = b0 * t[0] + b1 * t[1] + b2 * t[2];
        let (e1, e2) = (b1 - b0, b2 - b0);
        let gx = (e1 * loc.dx[1] + e2 * loc.dx[2]) * 2.0;
        let gy = (e1 * loc.dy[1] + e2 * loc.dy[2]) * 2.0;
        (value, gx, gy)
    }

    /// Values and gradients at many points, in parallel (see [`PsSpline::jets`]).
    pub fn gradients(&self, points: &[Point2<f64>]) -> Vec<Option<(V, V, V)>> {
        self.map_points(points, |ev, p| ev.gradient(p))
    }

    /// The value at a located point.
    #[inline]
    pub fn value_at(&self, loc: &SubLocation) -> V {
        let n = &self.nets[loc.triangle];
        let i = &SUB_ORDINATES[loc.sub];
        let t = loc.bary;
        let b0 = n[i[0]] * t[0] + n[i[1]] * t[1] + n[i[2]] * t[2];
        let b1 = n[i[1]] * t[0] + n[i[3]] * t[1] + n[i[4]] * t[2];
        let b2 = n[i[2]] * t[0] + n[i[4]] * t[1] + n[i[5]] * t[2];
        b0 * t[0] + b1 * t[1] + b2 * t[2]
    }

    /// s(p), or an error when p lies outside the domain.
    pub fn eval(&self, p: Point2<f64>) -> Result<V, PsError> {
        let loc = self
            .basis
            .locate_any(p)
            .ok_or(PsError::OutsideDomain { x: p.x, y: p.y })?;
        Ok(self.value_at(&loc))
    }

    /// s(p) with its partial derivatives up to order two (Algorithm 2.2).
    pub fn jet(&self, p: Point2<f64>) -> Result<PsJet<V>, PsError> {
        let loc = self
            .basis
            .locate_any(p)
            .ok_or(PsError::OutsideDomain { x: p.x, y: p.y })?;
        Ok(self.jet_at(&loc))
    }

    /// The polynomial of a chosen patch at p (p need not lie in it: one-sided limits on
    /// the edges of Δ*, extrapolation elsewhere).
    pub fn jet_on_patch(&self, patch: PatchId, p: Point2<f64>) -> Jet<V> {
        self.patch(patch.triangle(), patch.sub()).jet(p)
    }

    /// An evaluator that remembers where the last point was found: consecutive nearby points
    /// (grids, curves) then cost a short walk instead of a tree search.
    pub fn evaluator(&self) -> Evaluator<'_, V> {
        Evaluator {
            spline: self,
            cursor: Cursor::default(),
        }
    }

    /// An evaluator whose first walk starts near `p` (the bucket grid's guess): use it when
    /// the first point is far from triangle 0.
    pub fn evaluator_near(&self, p: Point2<f64>) -> Evaluator<'_, V> {
        Evaluator {
            spline: self,
            cursor: Cursor(self.basis.triangulation().start_triangle(p)),
        }
    }

    /// Jets at many points, in parallel on all cores (each thread walks through its share of
    /// consecutive points); `None` for points outside the domain.
    pub fn jets(&self, points: &[Point2<f64>]) -> Vec<Option<PsJet<V>>> {
        self.map_points(points, |ev, p| ev.jet(p))
    }

    /// `f(evaluator, p)` for every point, in parallel: consecutive chunks, one walking
    /// evaluator each, results written in place.
    pub fn map_points<T: Send>(
        &self,
        points: &[Point2<f64>],
        f: impl Fn(&mut Evaluator<'_, V>, Point2<f64>) -> T + Sync,
    ) -> Vec<T> {
        let mut out: Vec<Option<T>> = Vec::with_capacity(points.len());
        out.resize_with(points.len(), || None);
        for_each_chunk(points, &mut out, 1, |pts, res| {
            let mut ev = self.evaluator_near(pts[0]);
            for (r, &p) in res.iter_mut().zip(pts) {
                *r = Some(f(&mut ev, p));
            }
        });
        out.into_iter()
            .map(|r| r.expect("every point mapped"))
            .collect()
    }

    /// ∫_Ω s (2.61)–(2.62): Σ over sub-triangles of A(ρ*)/6 · Σ ordinates.
    pub fn integral(&self) -> V {
        (0..self.nets.len())
            .map(|t| {
                let w = self.basis.ordinate_integral_weights(t);
                let mut acc = V::zero();
                for (k, &wk) in w.iter().enumerate() {
                    acc += self.nets[t][k] * wk;
                }
                acc
            })
            .fold(V::zero(), |a, b| a + b)
    }
}

/// Evaluates a spline at a sequence of points, walking from the previous one.
#[derive(Clone, Debug)]
pub struct Evaluator<'a, V> {
    spline: &'a PsSpline<V>,
    /// Where the previous point was found (the next walk starts there).
    cursor: Cursor,
}

impl<V: Vector> Evaluator<'_, V> {
    /// Where `p` lies, or `None` outside the domain.
    #[inline]
    pub fn locate(&mut self, p: Point2<f64>) -> Option<SubLocation> {
        let loc = self.spline.basis.locate(p, self.cursor.0)?;
        self.cursor.0 = loc.triangle;
        Some(loc)
    }

    /// The value at `p`.
    #[inline]
    pub fn value(&mut self, p: Point2<f64>) -> Option<V> {
        self.locate(p).map(|l| self.spline.value_at(&l))
    }

    /// The value and gradient at `p`.
    #[inline]
    pub fn gradient(&mut self, p: Point2<f64>) -> Option<(V, V, V)> {
        self.locate(p).map(|l| self.spline.gradient_at(&l))
    }

    /// The jet at `p`.
    #[inline]
    pub fn jet(&mut self, p: Point2<f64>) -> Option<PsJet<V>> {
        self.locate(p).map(|l| self.spline.jet_at(&l))
    }
}

/// Recomputes `nets[t] = net(t)` for the `touched` triangles (sorted): one by one for a local
/// edit, in parallel over all triangles when the edit touches most of them (e.g. noise).
pub(crate) fn rebuild_nets<T: Send>(
    nets: &mut [T],
    touched: &[usize],
    net: impl Fn(usize) -> T + Sync,
) {
    if 2 * touched.len() > nets.len() {
        nets.par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .filter(|(t, _)| touched.binary_search(t).is_ok())
            .for_each(|(t, n)| *n = net(t));
    } else {
        for &t in touched {
            nets[t] = net(t);
        }
    }
}

/// `found` items of `what`, one per vertex of `basis`, or [`PsError::WrongCount`].
fn one_per_vertex(basis: &PsBasis, what: &'static str, found: usize) -> Result<(), PsError> {
    let expected = basis.triangulation().vertex_count();
    if found != expected {
        return Err(PsError::WrongCount {
            what,
            expected,
            found,
        });
    }
    Ok(())
}

/// The control values (2.45) of Hermite data on `basis`, one datum per vertex.
fn hermite_coefficients<V: Vector>(
    basis: &PsBasis,
    data: &[Hermite<V>],
) -> Result<Vec<[V; 3]>, PsError> {
    one_per_vertex(basis, "Hermite data", data.len())?;
    Ok(data
        .iter()
        .enumerate()
        .map(|(i, h)| basis.hermite_coefficients(i, h.value, h.dx, h.dy))
        .collect())
}

/// One triple of control values per vertex of `basis`, every value finite and in range.
fn check_coefficients<V: Vector>(basis: &PsBasis, coeffs: &[[V; 3]]) -> Result<(), PsError> {
    one_per_vertex(basis, "control value triples", coeffs.len())?;
    for (i, c) in coeffs.iter().enumerate() {
        if let Some(j) = c.iter().position(|v| !v.in_range()) {
            return Err(PsError::NonFiniteCoefficient {
                vertex: i,
                index: j,
            });
        }
    }
    Ok(())
}

/// The Bézier nets of all triangles for per-vertex control values (in parallel).
pub(crate) fn build_nets<T: super::net::Combine>(
    basis: &PsBasis,
    ctrl: &[[T; 3]],
) -> Vec<[T; NET_LEN]> {
    (0..basis.triangulation().triangle_count())
        .into_par_iter()
        .with_min_len(1024)
        .map(|t| basis.net(t, ctrl))
        .collect()
}
