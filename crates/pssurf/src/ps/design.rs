//! Designing with NURPS (thesis 3.4): weights as shape parameters (3.67), (3.72), local planar
//! sections by large weights (3.73)–(3.83), cusps and corners by degenerate control triangles
//! (3.84)–(3.86), and replacing a PS-triangle by another valid one without changing the
//! surface.
//!
//! Replacing a PS-triangle keeps the surface because the spline near V_i depends on the
//! control triangle only through the affine map F with F(Q_{i,j}) = c_{i,j} (homogeneous
//! (w c, w) for NURPS): the Bézier ordinates at the PS-points are values of F (2.54)–(2.57).
//! The new control points are F at the new triangle's corners; for NURPS their weights must
//! stay positive.

use std::sync::Arc;

use nalgebra::Vector3;

use super::{Nurps, PsBasis, PsError, PsSpline, PsTriangleChoice};
use crate::geometry::Triangle2;
use crate::vector::Vector;

/// Barycentric coordinates of V_i in its PS-triangle at most this are on the edge.
const ON_EDGE: f64 = 1e-9;

/// The shape parameters (3.67): the barycentric coordinates α̃_j = α_j w_j / Σ_k α_k w_k of the
/// tangent point s(V_i) in the control triangle, for the coordinates `alpha` of V_i in its
/// PS-triangle and the vertex's `weights`.
pub fn shape_parameters(alpha: [f64; 3], weights: [f64; 3]) -> [f64; 3] {
    let ws: f64 = (0..3).map(|j| alpha[j] * weights[j]).sum();
    std::array::from_fn(|j| alpha[j] * weights[j] / ws)
}

/// The weights that put the tangent point at the shape parameters `target` keeping its weight
/// w_s = Σ α_j w_j, by (3.72): w′_j = α̃′_j w_s / α_j. Where V_i lies on an edge of its
/// PS-triangle (α_j ≤ 1e-9, common with the optimal PS-triangles, whose boundary passes through
/// V_i) the tangent point stays on that edge: `target[j]` must be 0 and w_j is kept. The other
/// coordinates must be positive and all must sum to 1 (to 1e-12). `vertex` names the vertex in
/// the error.
pub fn weights_for_shape(
    vertex: usize,
    alpha: [f64; 3],
    weights: [f64; 3],
    target: [f64; 3],
) -> Result<[f64; 3], PsError> {
    let ws: f64 = (0..3).map(|j| alpha[j] * weights[j]).sum();
    let sum: f64 = target.iter().sum();
    let mut out = weights;
    for j in 0..3 {
        // α_j is computed, so V_i exactly on an edge comes out as ~1e-13: below ON_EDGE it is
        // taken as on the edge (a weight of α̃/α would be absurdly large).
        let fits = if alpha[j] > ON_EDGE {
            out[j] = target[j] * ws / alpha[j];
            target[j] > 0.0 && crate::limits::weight_ok(out[j])
        } else {
            target[j] == 0.0
        };
        if !fits || !((sum - 1.0).abs() < 1e-12) {
            return Err(PsError::InvalidWeight {
                vertex,
                index: j,
                weight: out[j],
            });
        }
    }
    Ok(out)
}

/// How a control triangle degenerates (3.4.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Degenerate {
    /// All three control points at one point: a cusp at the vertex (3.84)–(3.85); two such
    /// vertices of an edge make a corner (a crease) along it (3.86).
    Point(Vector3<f64>),
    /// The three control points projected onto the line through `through` along `direction`:
    /// between two point-like neighbours, a curved corner (Figure 3.10).
    Line {
        /// A point of the line.
        through: Vector3<f64>,
        /// Its direction (not zero).
        direction: Vector3<f64>,
    },
}

impl Degenerate {
    /// The degenerate control points made from `points`, or `None` for a line without a
    /// direction.
    pub fn apply(&self, points: [Vector3<f64>; 3]) -> Option<[Vector3<f64>; 3]> {
        match *self {
            Degenerate::Point(c) => Some([c; 3]),
            Degenerate::Line { through, direction } => {
                let d = direction.try_normalize(1e-300)?;
                Some(points.map(|p| through + d * (p - through).dot(&d)))
            }
        }
    }
}

impl PsSpline<Vector3<f64>> {
    /// Makes the control triangle of vertex i degenerate (3.4.4).
    pub fn degenerate_control_triangle(
        &mut self,
        i: usize,
        how: Degenerate,
    ) -> Result<(), PsError> {
        let c = how
            .apply(self.coefficients()[i])
            .ok_or(PsError::DegeneratePsTriangle { vertex: i })?;
        self.set_coefficients(i, c)
    }
}

impl Nurps<Vector3<f64>> {
    /// Makes the control triangle of vertex i degenerate (3.4.4), keeping its weights.
    pub fn degenerate_control_triangle(
        &mut self,
        i: usize,
        how: Degenerate,
    ) -> Result<(), PsError> {
        let c = how
            .apply(self.points()[i])
            .ok_or(PsError::DegeneratePsTriangle { vertex: i })?;
        self.set_vertex(i, c, self.weights()[i])
    }

    /// A local planar section (3.73)–(3.83): all three weights of vertex i set to `weight`. As
    /// it grows, the six sub-triangles at V_i approach the control plane T_i, at a distance of
    /// order 1/weight: the Bézier ordinates there tend to the points u_i, v_i, w_i of T_i.
    pub fn planar_section(&mut self, i: usize, weight: f64) -> Result<(), PsError> {
        self.set_vertex(i, self.points()[i], [weight; 3])
    }
}

/// The basis with the PS-triangle of vertex `i` replaced (validated to contain its PS-points).
fn basis_with(basis: &PsBasis, i: usize, t: Triangle2) -> Result<PsBasis, PsError> {
    let mut triangles = basis.ps_triangles().to_vec();
    triangles[i] = t;
    PsBasis::with_refinement(
        basis.triangulation().clone(),
        basis.refinement().clone(),
        &PsTriangleChoice::Given(triangles),
    )
}

/// The barycentric coordinates of the new PS-triangle's corners in the old one.
fn corners_in(old: &Triangle2, new: &Triangle2) -> [[f64; 3]; 3] {
    new.v.map(|p| old.bary(p))
}

impl<V: Vector> PsSpline<V> {
    /// The same spline with the PS-triangle of vertex `i` replaced by `t` (any triangle that
    /// contains the vertex's PS-points; Lemma 2.1): the new control values are the old
    /// control triangle's affine map at the new corners.
    pub fn with_ps_triangle(&self, i: usize, t: Triangle2) -> Result<Self, PsError> {
        let basis = basis_with(self.basis(), i, t)?;
        let beta = corners_in(self.basis().ps_triangle(i), basis.ps_triangle(i));
        let old = self.coefficients()[i];
        let mut coeffs = self.coefficients().to_vec();
        coeffs[i] = beta.map(|b| old[0] * b[0] + old[1] * b[1] + old[2] * b[2]);
        PsSpline::new(Arc::new(basis), coeffs)
    }
}

impl<V: Vector> Nurps<V> {
    /// The same surface with the PS-triangle of vertex `i` replaced by `t` (any triangle that
    /// contains the vertex's PS-points): the new homogeneous control points (w c, w) are the
    /// old control triangle's homogeneous affine map at the new corners. Fails when a new
    /// weight is not positive (a corner far outside the old triangle on the side of small
    /// weights).
    pub fn with_ps_triangle(&self, i: usize, t: Triangle2) -> Result<Self, PsError> {
        let basis = basis_with(self.basis(), i, t)?;
        let beta = corners_in(self.basis().ps_triangle(i), basis.ps_triangle(i));
        let (c, w) = (self.points()[i], self.weights()[i]);
        let mut points = self.points().to_vec();
        let mut weights = self.weights().to_vec();
        for (k, b) in beta.iter().enumerate() {
            let wk: f64 = (0..3).map(|j| b[j] * w[j]).sum();
            let hk = (0..3).fold(V::zero(), |acc, j| acc + c[j] * (b[j] * w[j]));
            if !crate::limits::weight_ok(wk) {
                return Err(PsError::InvalidWeight {
                    vertex: i,
                    index: k,
                    weight: wk,
                });
            }
            weights[i][k] = wk;
            points[i][k] = hk * (1.0 / wk);
        }
        Nurps::new(Arc::new(basis), points, weights)
    }
}

#[cfg(test)]
mod tests;
