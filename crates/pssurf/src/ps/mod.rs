//! Powell–Sabin splines on arbitrary triangulations in their normalized B-spline form
//! (thesis chapter 2.3 and 3.3): the PS-refinement, PS-points and PS-triangles, the basis,
//! Bézier nets, evaluation, derivatives, integration, and the rational NURPS form.

pub mod basis;
mod bulk_eval;
pub mod design;
pub mod energy;
pub mod fair;
pub mod from_bezier;
mod grid_scan;
pub mod net;
pub mod nurps;
pub mod ps_triangles;
pub mod quadrics;
pub mod refinement;
pub mod spline;

pub use basis::{PsBasis, SubLocation};
pub use design::Degenerate;
pub use energy::{Energy, PieceHessian};
pub use fair::{FairError, FairOptions, FairSolver, Faired, fair};
pub use nurps::Nurps;
pub use ps_triangles::{PsTriangleChoice, PsTriangleQuality};
pub use refinement::{PsRefinement, SplitRule};
pub use spline::{Evaluator, Hermite, PsJet, PsSpline};

use thiserror::Error;

/// A sub-triangle of Δ*: triangle `triangle()` of Δ and its piece `sub()` in 0..6.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PatchId(u32);

impl PatchId {
    /// The patch `sub` (0..6) of triangle `t`.
    #[inline]
    pub fn new(t: usize, sub: usize) -> Self {
        PatchId((6 * t + sub) as u32)
    }
    /// The triangle of Δ.
    #[inline]
    pub fn triangle(self) -> usize {
        self.0 as usize / 6
    }
    /// The sub-triangle 0..6: (V_c, R_c, Z) is 2c, (R_c, V_{c+1}, Z) is 2c + 1.
    #[inline]
    pub fn sub(self) -> usize {
        self.0 as usize % 6
    }
    /// A single running index, 6 · triangle + sub.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Errors from building or evaluating PS-splines.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PsError {
    /// A per-triangle or per-vertex list has the wrong length.
    #[error("expected {expected} {what}, found {found}")]
    WrongCount {
        /// What was counted.
        what: &'static str,
        /// How many are needed.
        expected: usize,
        /// How many were given.
        found: usize,
    },
    /// A given split point does not lie strictly inside its triangle.
    #[error("the split point of triangle {triangle} is not strictly inside it")]
    SplitPointOutside {
        /// The triangle.
        triangle: usize,
    },
    /// The segment joining the split points of two neighbours does not cross their common edge
    /// strictly between its end points (Definition 2.16); the incentre split never fails so.
    #[error("the split points of triangles {triangle} and {neighbor} are joined by a segment that misses their common edge ({}, {}) — choose other split points, e.g. the incentres", edge.0, edge.1)]
    EdgePointOutside {
        /// One triangle.
        triangle: usize,
        /// Its neighbour.
        neighbor: usize,
        /// The common edge (vertex indices).
        edge: (usize, usize),
    },
    /// One of the six pieces of a triangle in the refinement has (nearly) zero area, so no
    /// polynomial piece can be evaluated on it.
    #[error(
        "a piece of the PS refinement of triangle {triangle} has (nearly) zero area: its split points lie too close to its edges or vertices"
    )]
    DegeneratePiece {
        /// The triangle.
        triangle: usize,
    },
    /// A PS-triangle is degenerate.
    #[error("the PS-triangle of vertex {vertex} is degenerate")]
    DegeneratePsTriangle {
        /// The vertex.
        vertex: usize,
    },
    /// A PS-triangle has a coordinate that is not finite or beyond ±1e60.
    #[error(
        "the PS-triangle of vertex {vertex} has a coordinate that is not a finite number within ±1e60"
    )]
    PsTriangleOutOfRange {
        /// The vertex.
        vertex: usize,
    },
    /// A given PS-triangle does not contain one of its vertex's PS-points (Lemma 2.1), so the
    /// basis would not be a convex partition of unity.
    #[error("the PS-triangle of vertex {vertex} does not contain its PS-point ({}, {})", point[0], point[1])]
    PsPointOutside {
        /// The vertex.
        vertex: usize,
        /// The PS-point outside.
        point: [f64; 2],
    },
    /// A control value is NaN or infinite.
    #[error("control value {index} of vertex {vertex} is not a finite number within ±1e60")]
    NonFiniteCoefficient {
        /// The vertex.
        vertex: usize,
        /// Which of its three control values.
        index: usize,
    },
    /// A NURPS weight is zero, negative or not finite.
    #[error("weight {index} of vertex {vertex} is {}; weights must lie between 1e-30 and 1e30", crate::text::Short(*weight))]
    InvalidWeight {
        /// The vertex.
        vertex: usize,
        /// Which of its three weights.
        index: usize,
        /// The value.
        weight: f64,
    },
    /// The point lies outside the triangulated domain.
    #[error("the point ({}, {}) lies outside the domain", crate::text::Short(*x), crate::text::Short(*y))]
    OutsideDomain {
        /// The first coordinate of the rejected point.
        x: f64,
        /// The second coordinate of the rejected point.
        y: f64,
    },
}

#[cfg(test)]
mod tests;
