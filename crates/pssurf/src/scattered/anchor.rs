//! What the two global gradient estimators ([`super::estimate_gradients_global`] and
//! [`super::estimate_gradients_jumps`]) share.
//!
//! At vertices with a neighbour closer than [`CLOSE`] × the data's extent the gradient is
//! the local estimate, fixed, and the others are solved for around it: there the values
//! cannot fix slopes to 1e-10, and the local fit can ([`close_vertices`]).
//!
//! A small anchor η × (the vertex's own stiffness) × ‖g_i − g_i^local‖² to the local
//! estimate ([`super::estimate_gradients`], itself exact on quadratics) makes the systems
//! positive definite on every triangulation (an energy that vanishes on quadratics cannot
//! fix one that vanishes at all vertices, e.g. when they lie on two lines) without spoiling
//! quadratic reproduction: η = [`ANCHOR`], or the [`STRONGER_ANCHORS`] in turn when
//! rounding defeats it.

use super::local::GradientError;
use crate::ps::PsBasis;
use crate::sparse::SparseError;

/// The anchor's weight relative to each vertex's own stiffness (module docs). Small
/// enough that the estimate is the least-energy interpolant, the limit λ → 0 of the
/// smoothing fit on the data's own triangulation, to about 1e-7 (with 1e-3 they differed by
/// 2.8e-3 on 200 random points, a tenth of the interpolation error); held-out errors on the
/// real data of docs/performance.md moved by 0.2–0.5 % between the two.
pub const ANCHOR: f64 = 1e-7;

/// The stronger anchors tried, in order, when rounding makes the system numerically
/// indefinite: triangulations mixing slivers of relative thickness 1e-7 with triangles 1e6
/// times their size give energy entries whose rounding errors exceed the weakest anchor.
/// Each is still exact on quadratics; the strongest makes the result nearly the local
/// estimate.
pub const STRONGER_ANCHORS: [f64; 3] = [1e-1, 1e1, 1e3];

/// The global estimate failed.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
pub enum GlobalGradientError {
    /// The local estimate that anchors it failed.
    #[error(transparent)]
    Local(#[from] GradientError),
    /// The sparse solve failed.
    #[error("the global gradient system: {0}")]
    Solve(#[from] SparseError),
}

/// Which vertices have a neighbour closer than [`CLOSE`] × the data's extent (their
/// gradients are the local estimate).
pub(super) fn close_vertices(basis: &PsBasis) -> Vec<bool> {
    let tri = basis.triangulation();
    let (lo, hi) = tri.bounds();
    let limit = CLOSE * (hi - lo).norm();
    let mut close = vec![false; tri.vertex_count()];
    for t in 0..tri.triangle_count() {
        let v = tri.triangle(t);
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            if (tri.vertex(a) - tri.vertex(b)).norm() < limit {
                close[a] = true;
                close[b] = true;
            }
        }
    }
    close
}

/// Between points closer than this fraction of the data's extent, values rounded to 1e-16
/// fix the slope only to about 2e-10 of the data's scale over its extent; the least-energy
/// gradients would follow those slopes, and the cluster's jump terms, growing like its
/// spacing⁻⁴, would swamp the others in rounding (quadratics beside 100 points within 1e-7
/// were off by 4.8e-8 to 1.4e-1 depending on the draw). At such vertices the local
/// estimate, whose fit reaches out to farther points, is taken as it is, and the system is
/// solved for the other vertices only.
pub const CLOSE: f64 = 1e-6;
