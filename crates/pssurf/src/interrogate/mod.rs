//! Surface interrogation: exact curvature at points, curvature sampled over a whole surface
//! piece by piece, and fairness numbers.
//!
//! Everything is written against [`crate::surface::ParametricSurface`] (a point's jet) and
//! [`crate::surface::PiecewiseSurface`] (the smooth pieces), so every kind of
//! [`crate::surface::Surface`] is interrogated by the same code.

pub mod comb;
pub(crate) mod continuation;
pub mod curvature;
pub mod curve;
pub mod curve_shape;
mod edge_lines;
pub mod even_lines;
pub mod fairness;
pub mod field;
pub mod field_lines;
pub mod geodesic;
mod joining;
pub mod level;
#[cfg(test)]
mod level_tests;
#[cfg(test)]
mod lines_tests;
mod ode;
pub mod probe;
pub mod sample;
pub mod section;
#[cfg(test)]
mod tests;
pub mod umbilic;
mod walk;
pub mod zero_set;

pub use curvature::{
    Curvature, CurvatureQuantity, DEFAULT_UMBILIC_TOLERANCE, FundamentalForms, PrincipalCurvatures,
    Singular,
};
pub use even_lines::{EvenLines, even_field_lines};
pub use fairness::{
    DEFAULT_QUADRATURE_DEGREE, Fairness, FairnessIntegrals, QuantityStats, fairness,
    fairness_integrals,
};
pub use field::{FIELD_VARIABLES, FieldError, SurfaceField};
pub use field_lines::{
    FieldLine, FieldLineError, FieldLineOptions, LineEnd, LineFamily, trace_field_line,
};
pub use geodesic::{
    Geodesic, GeodesicEnd, GeodesicError, GeodesicOptions, ShortestGeodesic, geodesic,
    shortest_geodesic,
};
pub use level::{CurvatureRegions, auto_levels, curvature_regions, level_lines, parabolic_lines};
pub use probe::{
    Alignment, Circle, CoordinateCurve, CrossPlane, ProbeError, ProbeOptions, ProbeReport,
    coordinate_curves, probe,
};
pub use sample::{
    SampleCounts, SampledSurface, sample_counts, sample_patches, sample_pieces,
    triangles_per_piece, vertices_per_piece,
};
pub use section::{SectionCurve, SectionError, SectionOptions, plane_section};
pub use umbilic::{Umbilic, Umbilics, find_umbilics, umbilic_near};
pub use zero_set::{
    CONTINUITY_TOLERANCES, FieldOn, LevelGap, PieceFunction, PlaneDistance, SurfaceCurve,
    TraceMethod, ZeroSet, ZeroSetError, ZeroSetOptions, trace_levels, trace_zero_set,
};
