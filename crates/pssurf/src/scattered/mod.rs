//! Scattered data on triangulations: the gradients that Hermite interpolation (2.30) needs
//! when only values are known, interpolation, and smoothing fits.

mod anchor;
mod coarse;
mod diagnostics;
mod interpolate;
mod jumps;
mod local;
mod merge;
mod network;
mod smoothing;

pub use anchor::{ANCHOR, CLOSE, GlobalGradientError, STRONGER_ANCHORS};
pub use coarse::coarse_triangulation;
pub use diagnostics::{NearDuplicate, near_duplicate_distance, near_duplicates, slivers};
pub use interpolate::{
    COLLINEAR_HINT, FitError, GradientMethod, GradientReport, Interpolant, PRECISION_HINT,
    check_points, data_basis, data_basis_with, estimate_gradients_by, hermite_data, hermite_spline,
    hermite_spline_with, interpolate, interpolate_with,
};
pub use jumps::estimate_gradients_jumps;
pub use local::{
    GradientError, GradientFit, HESSIAN_COLUMN_FLOOR, LocalJet, MAX_CONDITION,
    MAX_USABLE_CONDITION, estimate_gradients, estimate_jets,
};
pub use merge::{
    MergedData, NEAR_DUPLICATE, group_mean, merge_near_duplicates, near_duplicate_groups,
};
pub use network::estimate_gradients_global;
pub use smoothing::{
    Smoothing, SmoothingError, SmoothingFit, Trial, smooth_scattered, smoothing_fit,
};
