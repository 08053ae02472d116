//! Surface interrogation: exact curvature at points, curvature sampled over a whole surface
//! piece by piece, and fairness numbers.
//!
//! Everything is written against [`crate::surface::ParametricSurface`] (a point's jet) and
//! [`crate::surface::PiecewiseSurface`] (the smooth pieces), so every kind of
//! [`crate::surface::Surface`] is interrogated by the same code.

pub(crate) mod continuation;
pub mod curvature;
pub mod fairness;
pub mod field;
mod joining;
pub mod level;
#[cfg(test)]
mod level_tests;
pub mod sample;
pub mod section;
#[cfg(test)]
mod tests;
mod walk;
pub mod zero_set;

pub use curvature::{
    Curvature, CurvatureQuantity, DEFAULT_UMBILIC_TOLERANCE, FundamentalForms, PrincipalCurvatures,
    Singular,
};
pub use fairness::{
    DEFAULT_QUADRATURE_DEGREE, Fairness, FairnessIntegrals, QuantityStats, fairness,
};
pub use field::{FIELD_VARIABLES, FieldError, SurfaceField};
pub use level::{CurvatureRegions, auto_levels, curvature_regions, level_lines, parabolic_lines};
pub use sample::{
    SampleCounts, SampledSurface, sample_counts, sample_patches, sample_pieces,
    triangles_per_piece, vertices_per_piece,
};
pub use section::{SectionCurve, SectionError, SectionOptions, plane_section};
pub use zero_set::{
    FieldOn, LevelGap, PieceFunction, PlaneDistance, SurfaceCurve, TraceMethod, ZeroSet,
    ZeroSetError, ZeroSetOptions, trace_levels, trace_zero_set,
};
