//! # pssurf
//!
//! Powell–Sabin (PS) splines for free-form surface design and interrogation: triangular
//! Bernstein–Bézier patches of any degree (polynomial and rational) and Bézier curves;
//! PS-splines on arbitrary triangulations in their normalized B-spline form (Dierckx), their
//! parametric and rational (NURPS) forms; and the file format.
//!
//! Equation numbers such as (2.45) refer to P. Windmolders, *Powell–Sabin splines for
//! Computer Aided Geometric Design*, PhD thesis, KU Leuven, 2003 (the "thesis").
//!
//! The crate is pure mathematics: no user interface, and file formats only behind the `io`
//! feature.

#[cfg(test)]
#[macro_use]
pub(crate) mod test_util;

pub mod bezier;
pub mod edit;
#[cfg(feature = "expr")]
pub mod expr;
pub mod geometry;
pub mod hole;
pub mod iges;
pub mod interrogate;
#[cfg(feature = "io")]
pub mod io;
pub mod limits;
pub mod mesh;
pub mod noise;
pub mod nurbs;
pub mod ps;
pub mod quadrature;
pub mod scattered;
pub mod sparse;
pub mod subdivision;
pub mod surface;
pub mod text;
pub mod triangulation;
pub mod ups;
pub mod vector;

#[cfg(doctest)]
mod readme_example;

/// The most used types in one import.
pub mod prelude {
    pub use crate::bezier::{
        BezierCurve, BezierTriangle, Jet, RationalBezierCurve, RationalBezierTriangle,
    };
    pub use crate::geometry::{Bary, Triangle2};
    pub use crate::interrogate::{Curvature, CurvatureQuantity};
    pub use crate::ps::{
        Hermite, Nurps, PatchId, PsBasis, PsError, PsSpline, PsTriangleChoice, SplitRule,
    };
    pub use crate::surface::{
        ControlId, ControlNet, ControlPoint, Cursor, Domain, OutsideDomain, ParametricSurface,
        PieceShape, PiecewiseSurface, Surface, SurfaceJet, SurfaceKind, UpsSurface,
    };
    pub use crate::triangulation::{Triangulation, TriangulationError};
    pub use crate::vector::Vector;
    pub use nalgebra::{Point2, Vector2, Vector3};
}
