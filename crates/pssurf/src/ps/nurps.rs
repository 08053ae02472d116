//! Non-uniform rational PS-spline (NURPS) surfaces (thesis section 3.3).

use std::sync::Arc;

use nalgebra::Point2;

use super::basis::{PsBasis, SubLocation};
use super::net::{NET_LEN, SUB_ORDINATES, Weighted};
use super::spline::{PsJet, build_nets, rebuild_nets};
use super::{PatchId, PsError};
use crate::bezier::rational::rational_quadratic_jet;
use crate::bezier::{Jet, RationalBezierTriangle};
use crate::triangulation::INSIDE_TOLERANCE;
use crate::vector::Vector;

/// A NURPS surface s(u) = Σ c_ij w_ij B_i^j(u) / Σ w_ij B_i^j(u) (3.32) with weights w_ij > 0.
///
/// Its rational Bézier nets are computed with the stable scheme of section 3.3.2: weights
/// first (3.44)–(3.47), then convex combinations of the control points with the normalised
/// coefficients (3.49)–(3.63), never forming the large homogeneous points w c.
#[derive(Clone, Debug)]
pub struct Nurps<V> {
    basis: Arc<PsBasis>,
    points: Vec<[V; 3]>,
    weights: Vec<[f64; 3]>,
    nets: Vec<[Weighted<V>; NET_LEN]>,
}

impl<V: Vector> Nurps<V> {
    /// A NURPS surface from control points and weights (one triple of each per vertex);
    /// every point must be finite and every weight finite and positive.
    pub fn new(
        basis: Arc<PsBasis>,
        points: Vec<[V; 3]>,
        weights: Vec<[f64; 3]>,
    ) -> Result<Self, PsError> {
        let n = basis.triangulation().vertex_count();
        for (what, len) in [
            ("control point triples", points.len()),
            ("weight triples", weights.len()),
        ] {
            if len != n {
                return Err(PsError::WrongCount {
                    what,
                    expected: n,
                    found: len,
                });
            }
        }
        for i in 0..n {
            if let Some(j) = points[i].iter().position(|v| !v.in_range()) {
                return Err(PsError::NonFiniteCoefficient {
                    vertex: i,
                    index: j,
                });
            }
            if let Some(j) = weights[i]
                .iter()
                .position(|&w| !crate::limits::weight_ok(w))
            {
                return Err(PsError::InvalidWeight {
                    vertex: i,
                    index: j,
                    weight: weights[i][j],
                });
            }
        }
        let ctrl = weighted(&points, &weights);
        let nets = build_nets(&basis, &ctrl);
        Ok(Nurps {
            basis,
            points,
            weights,
            nets,
        })
    }

    /// The basis.
    pub fn basis(&self) -> &Arc<PsBasis> {
        &self.basis
    }
    /// The control points c_ij.
    pub fn points(&self) -> &[[V; 3]] {
        &self.points
    }
    /// The weights w_ij.
    pub fn weights(&self) -> &[[f64; 3]] {
        &self.weights
    }

    /// Replaces the control points and weights of vertex i, updating its molecule's nets.
    pub fn set_vertex(
        &mut self,
        i: usize,
        points: [V; 3],
        weights: [f64; 3],
    ) -> Result<(), PsError> {
        if let Some(j) = points.iter().position(|v| !v.in_range()) {
            return Err(PsError::NonFiniteCoefficient {
                vertex: i,
                index: j,
            });
        }
        if let Some(j) = weights.iter().position(|&w| !crate::limits::weight_ok(w)) {
            return Err(PsError::InvalidWeight {
                vertex: i,
                index: j,
                weight: weights[j],
            });
        }
        self.set_vertices(&[(i, points, weights)]);
        Ok(())
    }

    /// The shape parameters of vertex i (thesis 3.4.2): the barycentric coordinates α̃_{i,j} of
    /// the tangent point s(V_i) in its control triangle ([`super::design::shape_parameters`]).
    pub fn shape_parameters(&self, i: usize) -> [f64; 3] {
        super::design::shape_parameters(self.basis.alpha(i), self.weights[i])
    }

    /// Moves the tangent point of vertex i to the barycentric coordinates `target` in its
    /// control triangle, keeping its weight w_{s_i}, by (3.72)
    /// ([`super::design::weights_for_shape`] says which targets are possible).
    pub fn set_shape_parameters(&mut self, i: usize, target: [f64; 3]) -> Result<(), PsError> {
        let weights =
            super::design::weights_for_shape(i, self.basis.alpha(i), self.weights[i], target)?;
        self.set_vertices(&[(i, self.points[i], weights)]);
        Ok(())
    }

    /// Replaces the control points and weights of several vertices (unchecked: points must
    /// be finite and weights finite and positive) and rebuilds the nets of the triangles in
    /// their molecules, each once.
    pub(crate) fn set_vertices(&mut self, changes: &[(usize, [V; 3], [f64; 3])]) {
        for &(i, p, w) in changes {
            self.points[i] = p;
            self.weights[i] = w;
        }
        let basis = &self.basis;
        let touched = basis
            .triangulation()
            .molecules_of(changes.iter().map(|c| c.0));
        let (points, weights) = (&self.points, &self.weights);
        let ctrl = |i: usize| -> [Weighted<V>; 3] {
            std::array::from_fn(|j| Weighted {
                point: points[i][j],
                weight: weights[i][j],
            })
        };
        rebuild_nets(&mut self.nets, &touched, |t| basis.net_with(t, ctrl));
    }

    /// The rational quadratic Bézier patch of sub-triangle `sub` of triangle `t`.
    pub fn patch(&self, t: usize, sub: usize) -> RationalBezierTriangle<V> {
        let n = &self.nets[t];
        let idx = &SUB_ORDINATES[sub];
        RationalBezierTriangle::try_new(
            self.basis.sub_triangle(t, sub),
            2,
            idx.iter().map(|&k| n[k].point).collect(),
            idx.iter().map(|&k| n[k].weight).collect(),
        )
        .expect("positive weights")
    }

    /// The value and derivatives at a located point.
    pub fn jet_at(&self, loc: &SubLocation) -> PsJet<V> {
        let n = &self.nets[loc.triangle];
        let idx = &SUB_ORDINATES[loc.sub];
        let q: [V; 6] = std::array::from_fn(|k| n[idx[k]].point);
        let qw: [f64; 6] = std::array::from_fn(|k| n[idx[k]].weight);
        // With non-negative barycentric coordinates and positive weights the denominators
        // are positive. Point location accepts coordinates down to −INSIDE_TOLERANCE, and
        // −1e-17 times a weight of 1e30 outweighs a weight of 1e-30: then the point is taken
        // on the piece (coordinates clamped, a move within the tolerance). Farther outside
        // (a piece's polynomial extended, as level-line tracing does) where the rational
        // patch has no positive denominator, the jet is NaN: undefined there.
        let jet = rational_quadratic_jet(&q, &qw, loc.bary, loc.dx, loc.dy, 2.0)
            .or_else(|e| match clamped(loc.bary) {
                Some(b) => rational_quadratic_jet(&q, &qw, b, loc.dx, loc.dy, 2.0),
                None => Err(e),
            })
            .unwrap_or_else(|_| Jet::zero().map(|v: V| v * f64::NAN));
        PsJet {
            jet,
            patch: PatchId::new(loc.triangle, loc.sub),
        }
    }

    /// s(p) with derivatives up to order two, or an error outside the domain.
    pub fn jet(&self, p: Point2<f64>) -> Result<PsJet<V>, PsError> {
        let loc = self
            .basis
            .locate_any(p)
            .ok_or(PsError::OutsideDomain { x: p.x, y: p.y })?;
        Ok(self.jet_at(&loc))
    }

    /// s(p).
    pub fn eval(&self, p: Point2<f64>) -> Result<V, PsError> {
        Ok(self.jet(p)?.jet.value)
    }
}

/// The barycentric coordinates with their small negative entries (≥ −[`INSIDE_TOLERANCE`])
/// set to zero, summing to one; `None` if one is more negative.
fn clamped(b: [f64; 3]) -> Option<[f64; 3]> {
    if b.iter().any(|&c| !(c >= -INSIDE_TOLERANCE)) {
        return None;
    }
    let b = b.map(|c| c.max(0.0));
    let sum: f64 = b.iter().sum();
    Some(b.map(|c| c / sum))
}

fn weighted<V: Vector>(points: &[[V; 3]], weights: &[[f64; 3]]) -> Vec<[Weighted<V>; 3]> {
    points
        .iter()
        .zip(weights)
        .map(|(p, w)| {
            std::array::from_fn(|j| Weighted {
                point: p[j],
                weight: w[j],
            })
        })
        .collect()
}
