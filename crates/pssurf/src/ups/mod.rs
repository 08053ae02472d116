//! Uniform Powell–Sabin (UPS) splines on triangulations of lattice polygons (thesis chapter 4):
//! the fixed PS-triangles, subdivision, display by subdivision, the lifting wavelet transform,
//! thresholding and noise.

pub mod create;
pub mod display;
pub mod grid;
pub mod lattice;
pub mod spline;
pub mod subdivision;
pub mod threshold;
pub mod wavelet;

#[cfg(feature = "expr")]
pub use create::graph_surface_from_formula;
pub use create::{GraphKind, graph_surface};
pub use grid::UpsGrid;
pub use lattice::{Lattice, LatticePoint, LatticePolygon};
pub use spline::{Ups, fixed_ps_triangle};

use thiserror::Error;

/// Errors from building and transforming UPS-splines.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum UpsError {
    /// A lattice polygon needs at least three distinct corners.
    #[error("a lattice polygon needs at least three distinct corners")]
    TooFewCorners,
    /// An edge of the polygon does not follow a grid line.
    #[error(
        "edge {edge} of the polygon does not lie on a grid line (steps must be multiples of (1, 0), (0, 1) or (1, −1) in lattice coordinates)"
    )]
    EdgeOffGrid {
        /// The edge (from corner `edge` to the next).
        edge: usize,
    },
    /// The polygon has no area.
    #[error("the polygon encloses no area")]
    ZeroArea,
    /// Two edges of the polygon cross or touch.
    #[error("edges {} and {} of the polygon cross or touch", edges.0, edges.1)]
    SelfIntersecting {
        /// The two edges.
        edges: (usize, usize),
    },
    /// Only 3-, 4-, 5- and 6-sided standard polygons exist.
    #[error(
        "there is no standard {0}-sided lattice polygon (use 3, 4, 5 or 6, or give the polygon)"
    )]
    UnsupportedSides(usize),
    /// The base must be positive and finite (and the origin finite).
    #[error("the lattice base must be a positive finite number, not {}", crate::text::Short(*.0))]
    InvalidBase(f64),
    /// The block matrix would be too large.
    #[error(
        "the lattice polygon is too large: its bounding box holds {0} lattice points, at most 2^31 are supported"
    )]
    TooLarge(u128),
    /// Too many corners.
    #[error("a lattice polygon may have at most 4096 corners, not {0}")]
    TooManyCorners(usize),
    /// A corner too far from the origin.
    #[error("corner {corner} of the polygon lies beyond ±2^40 in lattice coordinates")]
    CornerOutOfRange {
        /// The corner's index.
        corner: usize,
    },
    /// Lattice points would have coordinates beyond the supported range.
    #[error("the lattice points would reach coordinates of {}, beyond the supported ±1e60 (a smaller base or origin)", crate::text::Short(*extent))]
    OutOfRange {
        /// The largest coordinate magnitude.
        extent: f64,
    },
    /// The base, or a nonzero origin coordinate, is too small to compute with.
    #[error("the lattice base {} or a nonzero origin coordinate ({}, {}) is below 1e-20", crate::text::Short(*base), crate::text::Short(origin[0]), crate::text::Short(origin[1]))]
    TooFine {
        /// The base.
        base: f64,
        /// The origin.
        origin: [f64; 2],
    },
    /// A control value (or weight) is not finite or lies beyond the supported range.
    #[error("the control values at ({}, {}) are not finite or lie beyond ±1e60 (or a weight outside 1e-60 … 1e60)", crate::text::Short(at[0]), crate::text::Short(at[1]))]
    UnusableValues {
        /// The vertex, in the domain.
        at: [f64; 2],
    },
    /// A control array has the wrong length.
    #[error("expected {expected} control triples, found {found}")]
    WrongBlockCount {
        /// Needed.
        expected: usize,
        /// Given.
        found: usize,
    },
    /// The triangulation cannot be coarsened that many times.
    #[error(
        "the triangulation allows only {available} coarsening levels, not {requested}: every corner of the polygon must lie on the lattice of base 2^levels·B"
    )]
    TooManyLevels {
        /// Asked for.
        requested: u32,
        /// Possible.
        available: u32,
    },
    /// The lifting wavelet transform is defined for polynomial UPS surfaces only.
    #[error("wavelets are defined for polynomial UPS surfaces; this one is rational")]
    RationalWavelet,
    /// The general triangulation could not be built.
    #[error("{0}")]
    Triangulation(crate::triangulation::TriangulationError),
    /// The general PS-spline could not be built.
    #[error("{0}")]
    Ps(crate::ps::PsError),
}

#[cfg(test)]
mod tests;
