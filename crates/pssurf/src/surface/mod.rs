//! One surface model for every kind.
//!
//! - [`ParametricSurface`]: a point's jet s, s_u, s_v, s_uu, s_uv, s_vv with a [`Cursor`] that
//!   makes nearby queries cheap; [`jets`] and [`fill_rows`] evaluate many points in parallel.
//! - [`PiecewiseSurface`]: the smooth pieces (PS sub-triangles, a Bézier triangle, later the
//!   rectangles of a NURBS surface), each with its parameter [`PieceShape`], its jet and
//!   quadrature on it. Sampling, plots, export and fairness integrals use only this.
//! - [`Domain`]: the parameter domain as a polygon with holes (containment, boundary, segment
//!   clipping, distance to the boundary), exact where it decides.
//! - [`ControlNet`]: control points and weights by a stable [`ControlId`], validated edits,
//!   and the pieces each point influences.
//! - [`Surface`]: every kind in one enum that forwards all of the above; [`SurfaceKind`] names
//!   the kind.
//!
//! Adding a kind is one variant of [`Surface`] (and of the forwarding macro in `model.rs`)
//! plus its impls of the traits; see `docs/architecture.md`.

mod control;
mod domain;
mod eval;
mod kinds;
mod model;
mod piece;
#[cfg(test)]
mod tests;
mod uniform;

pub use crate::triangulation::Cursor;
pub(crate) use control::check_point;
pub use control::{ControlFreedom, ControlId, ControlNet, ControlPoint, EditError};
pub use domain::{Domain, DomainError, SegmentPart};
pub(crate) use eval::for_each_chunk;
pub use eval::{fill_rows, jets};
pub use model::{Surface, SurfaceKind};
pub use piece::{
    LocalCoords, PieceFrame, PieceKind, PiecePoint, PieceRule, PieceShape, PiecewiseSurface,
    QuadratureNode, Rectangle,
};
pub use uniform::{DetailRow, UniformSurface, UpsDecomposition, UpsSurface};

use std::sync::Arc;

use nalgebra::{Point2, Vector3};
use thiserror::Error;

use crate::bezier::Jet;

/// A point of a surface with its first and second partial derivatives w.r.t. the parameters
/// (u, v), and the piece it was computed on (for piecewise surfaces, whose second derivatives
/// jump across piece boundaries).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceJet {
    /// s, s_u, s_v, s_uu, s_uv, s_vv.
    pub jet: Jet<Vector3<f64>>,
    /// The piece (an index of [`PiecewiseSurface`]) whose polynomial gave the values.
    pub piece: usize,
}

/// The parameter lies outside the surface's domain.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
#[error("the parameter ({u}, {v}) lies outside the domain")]
pub struct OutsideDomain {
    /// The first parameter of the rejected point.
    pub u: f64,
    /// The second parameter of the rejected point.
    pub v: f64,
}

impl OutsideDomain {
    /// The error for the parameter point `uv`.
    pub fn at(uv: Point2<f64>) -> Self {
        OutsideDomain { u: uv.x, v: uv.y }
    }
}

/// A parametric surface s: Ω ⊂ R² → R³ with first and second derivatives.
///
/// Functional surfaces z = f(x, y) are their graphs (x, y, f(x, y)), so (u, v) = (x, y).
pub trait ParametricSurface: Send + Sync {
    /// The bounding box of the parameter domain Ω (min corner, max corner).
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>);

    /// s and its derivatives at `uv`, starting the search at `cursor` (which is updated).
    fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain>;

    /// A cursor from which the search for `uv` is short (for piecewise surfaces a spatial
    /// index is consulted once; then reuse the cursor for nearby points).
    fn cursor_near(&self, _uv: Point2<f64>) -> Cursor {
        Cursor::default()
    }

    /// s and its derivatives at `uv`.
    fn jet(&self, uv: Point2<f64>) -> Result<SurfaceJet, OutsideDomain> {
        self.jet_with(uv, &mut self.cursor_near(uv))
    }

    /// The point s(u, v).
    fn point(&self, uv: Point2<f64>) -> Result<Vector3<f64>, OutsideDomain> {
        Ok(self.jet(uv)?.jet.value)
    }

    /// The unit normal n = s_u × s_v / |s_u × s_v| (2.67), `None` at a singular point.
    fn normal(&self, uv: Point2<f64>) -> Result<Option<Vector3<f64>>, OutsideDomain> {
        let j = self.jet(uv)?.jet;
        let n = j.dx.cross(&j.dy);
        let size = j.dx.norm() * j.dy.norm();
        Ok((n.norm() > 1e-14 * size && size > 0.0).then(|| n.normalize()))
    }
}

/// Forwards the surface traits through references and smart pointers.
macro_rules! forward_through_pointers {
    ($($wrapper:ty),*) => {$(
        impl<S: ParametricSurface + ?Sized> ParametricSurface for $wrapper {
            fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
                (**self).domain_bounds()
            }
            fn cursor_near(&self, uv: Point2<f64>) -> Cursor {
                (**self).cursor_near(uv)
            }
            fn jet_with(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
                (**self).jet_with(uv, cursor)
            }
        }

        impl<S: PiecewiseSurface + ?Sized> PiecewiseSurface for $wrapper {
            fn piece_count(&self) -> usize {
                (**self).piece_count()
            }
            fn piece_kind(&self) -> PieceKind {
                (**self).piece_kind()
            }
            fn piece_shape(&self, k: usize) -> PieceShape {
                (**self).piece_shape(k)
            }
            fn piece_jet(&self, k: usize, at: &PiecePoint) -> Jet<Vector3<f64>> {
                (**self).piece_jet(k, at)
            }
        }
    )*};
}

forward_through_pointers!(&S, Box<S>, Arc<S>);

/// The graph (x, y, f(x, y)) of a scalar jet at `p`.
pub fn graph_jet(p: Point2<f64>, j: &Jet<f64>) -> Jet<Vector3<f64>> {
    Jet {
        value: Vector3::new(p.x, p.y, j.value),
        dx: Vector3::new(1.0, 0.0, j.dx),
        dy: Vector3::new(0.0, 1.0, j.dy),
        dxx: Vector3::new(0.0, 0.0, j.dxx),
        dxy: Vector3::new(0.0, 0.0, j.dxy),
        dyy: Vector3::new(0.0, 0.0, j.dyy),
    }
}
