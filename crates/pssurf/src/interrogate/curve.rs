//! The results of tracing curves on a surface: polylines ([`SurfaceCurve`]), the level sets
//! of a field ([`ZeroSet`]) with the gaps where the field jumps ([`LevelGap`]). Shared by the
//! tracer (`zero_set`), the joiner (`joining`) and the integral curves.

use nalgebra::{Point2, Vector3};

/// A polyline on a surface: parameters and points, in order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SurfaceCurve {
    /// The parameter points.
    pub uvs: Vec<Point2<f64>>,
    /// The surface points s(u, v).
    pub points: Vec<Vector3<f64>>,
    /// Whether the last point joins the first (a closed loop; the first point is not
    /// repeated).
    pub closed: bool,
}

impl SurfaceCurve {
    /// The length of the polyline in space.
    pub fn length(&self) -> f64 {
        let open: f64 = self.points.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        match (self.closed, self.points.first(), self.points.last()) {
            (true, Some(a), Some(b)) => open + (a - b).norm(),
            _ => open,
        }
    }
}

/// How far apart, in units of a level's corrector tolerance, the field's values on the two
/// sides of a piece edge must be for an unpaired end there to count as a jump of the field
/// ([`LevelGap`]) rather than an end left unjoined. A continuous field agrees across an edge
/// to rounding (about 1e-5 of the tolerance); the curvature of a PS-spline jumps by far more.
pub const CONTINUITY_TOLERANCES: f64 = 100.0;

/// An end of a level line on a piece boundary where the line does not continue at the same
/// point on the other side (the field jumps there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelGap {
    /// Where the line ends.
    pub uv: Point2<f64>,
    /// The surface point there.
    pub point: Vector3<f64>,
    /// The field's value on the neighbouring piece at that point (the level is the value on
    /// this side); NaN at a corner shared by several pieces.
    pub across: f64,
}

/// The traced zero set f = c of one level.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ZeroSet {
    /// The level c.
    pub level: f64,
    /// The curves, joined across pieces.
    pub curves: Vec<SurfaceCurve>,
    /// Ends on interior piece boundaries that do not continue because the field jumps there
    /// (see [`LevelGap`]).
    pub gaps: Vec<LevelGap>,
    /// Ends on interior piece boundaries left unpaired although the field is continuous
    /// there (it agrees across the edge to within [`CONTINUITY_TOLERANCES`] times
    /// `tolerance`): a line the joining could not continue, such as one running along piece
    /// edges, or a walk that stopped at a shallow angle.
    pub unjoined: usize,
    /// The corrector's absolute tolerance: every point of the predictor–corrector has
    /// |f − c| ≤ this (on its piece).
    pub tolerance: f64,
    /// Pieces on which the function equals c everywhere on the hunting mesh (a whole region
    /// at the level, not a curve: skipped).
    pub flat_pieces: usize,
    /// Branches that stopped because the corrector failed at the smallest step (a singular
    /// point it could not pass) or whose end could not be solved onto an edge.
    pub stuck: usize,
    /// Whether the point limit cut the tracing short.
    pub truncated: bool,
}
