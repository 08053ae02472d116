//! Local editing by intrinsic measures (Georgiades and Greenberg, seed 003, the editing half):
//! prescribe a curvature at a point and let the surface follow nearby.
//!
//! - [`local`]: the edit on any surface with control points (PS, UPS, NURPS natively; Bézier
//!   and NURBS too): the smallest, smoothest change of the control points near the point that
//!   gives the measure its value there.
//! - [`graph`]: the paper's own method on polynomial graph surfaces X(u, v) = (u, h(u, v), v):
//!   a constrained coordinate curve, the interpolating curves across it and the surface through
//!   them, with C⁰, C¹ or C² continuity at the border of a rectangular region, and the twisted
//!   curve with prescribed torsion.

pub mod graph;
pub mod local;

pub use local::{
    ControlChange, EditRequest, LocalEdit, LocalEditError, Measure, default_radius, edit_locally,
};
