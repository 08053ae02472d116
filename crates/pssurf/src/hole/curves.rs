//! The boundary data of a hole (thesis 5.1, Figure 5.1): curves p(t) on [0, 1] with their
//! tangents γ(t) and the normals n(t) of the surrounding surface along them.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use crate::nurbs::NurbsCurve;
use crate::surface::{ParametricSurface, Surface};

/// One boundary curve of a hole, parametrised on [0, 1]. The tangent and the normal need not
/// be unit vectors: the hole filler normalises them.
pub trait BoundaryCurve {
    /// The curve point p(t).
    fn point(&self, t: f64) -> Vector3<f64>;
    /// A tangent vector at t, pointing in the direction of increasing t.
    fn tangent(&self, t: f64) -> Vector3<f64>;
    /// A normal of the surrounding surface at p(t) (needed away from the ends only).
    fn normal(&self, t: f64) -> Vector3<f64>;
}

/// A boundary curve given by closures (used by the built-in examples and by tests).
#[derive(Clone)]
pub struct CurveFns {
    /// p(t).
    pub point: Arc<dyn Fn(f64) -> Vector3<f64> + Send + Sync>,
    /// A tangent at t.
    pub tangent: Arc<dyn Fn(f64) -> Vector3<f64> + Send + Sync>,
    /// A normal at t.
    pub normal: Arc<dyn Fn(f64) -> Vector3<f64> + Send + Sync>,
}

impl BoundaryCurve for CurveFns {
    fn point(&self, t: f64) -> Vector3<f64> {
        (self.point)(t)
    }
    fn tangent(&self, t: f64) -> Vector3<f64> {
        (self.tangent)(t)
    }
    fn normal(&self, t: f64) -> Vector3<f64> {
        (self.normal)(t)
    }
}

/// How the normals along a NURBS boundary curve are given.
#[derive(Clone, Debug)]
pub enum NormalField {
    /// The same normal everywhere (a curve in a planar surrounding surface, or a plane cut).
    Constant(Vector3<f64>),
    /// A vector-valued NURBS curve (its "points" are normal vectors), normalised where used;
    /// its parameter interval is mapped proportionally onto the boundary curve's.
    Curve(NurbsCurve),
}

/// A NURBS (or Bézier) boundary curve with its normals; the curve's parameter interval is
/// mapped onto [0, 1].
#[derive(Clone, Debug)]
pub struct NurbsBoundary {
    /// The curve.
    pub curve: NurbsCurve,
    /// Its normals.
    pub normals: NormalField,
}

impl NurbsBoundary {
    /// The curve's own parameter for t ∈ [0, 1] (clamped into its interval).
    fn parameter(&self, t: f64) -> f64 {
        let (lo, hi) = self.curve.domain();
        (lo + t * (hi - lo)).clamp(lo, hi)
    }

    /// (p, p′) at t; NaN when the curve cannot be evaluated (never for valid curves).
    fn jet(&self, t: f64) -> [Vector3<f64>; 2] {
        let (lo, hi) = self.curve.domain();
        match self.curve.derivatives(self.parameter(t)) {
            Some(d) => [d[0], d[1] * (hi - lo)],
            None => [Vector3::repeat(f64::NAN); 2],
        }
    }
}

impl BoundaryCurve for NurbsBoundary {
    fn point(&self, t: f64) -> Vector3<f64> {
        self.jet(t)[0]
    }
    fn tangent(&self, t: f64) -> Vector3<f64> {
        self.jet(t)[1]
    }
    fn normal(&self, t: f64) -> Vector3<f64> {
        match &self.normals {
            NormalField::Constant(n) => *n,
            NormalField::Curve(c) => {
                let (lo, hi) = c.domain();
                c.point((lo + t * (hi - lo)).clamp(lo, hi))
                    .unwrap_or(Vector3::repeat(f64::NAN))
            }
        }
    }
}

/// A side of a surface's parameter domain as a boundary curve: s(a + t (b − a)), its
/// derivative along the side, and the surface normal there.
#[derive(Clone)]
pub struct SurfaceEdge {
    /// The surface (shared: several edges may come from one surface).
    pub surface: Arc<Surface>,
    /// The start of the side in the parameter domain.
    pub from: Point2<f64>,
    /// Its end.
    pub to: Point2<f64>,
}

impl SurfaceEdge {
    /// The domain point at t (exactly `from` at 0 and `to` at 1).
    fn uv(&self, t: f64) -> Point2<f64> {
        if t <= 0.0 {
            self.from
        } else if t >= 1.0 {
            self.to
        } else {
            self.from + (self.to - self.from) * t
        }
    }
}

impl BoundaryCurve for SurfaceEdge {
    fn point(&self, t: f64) -> Vector3<f64> {
        self.surface
            .point(self.uv(t))
            .unwrap_or(Vector3::repeat(f64::NAN))
    }
    fn tangent(&self, t: f64) -> Vector3<f64> {
        let d = self.to - self.from;
        match self.surface.jet(self.uv(t)) {
            Ok(j) => j.jet.dx * d.x + j.jet.dy * d.y,
            Err(_) => Vector3::repeat(f64::NAN),
        }
    }
    fn normal(&self, t: f64) -> Vector3<f64> {
        match self.surface.normal(self.uv(t)) {
            Ok(Some(n)) => n,
            _ => Vector3::repeat(f64::NAN),
        }
    }
}

/// A curve run backwards: p(1 − t), −p′(1 − t), the same normals.
pub struct Reversed<C>(pub C);

impl<C: BoundaryCurve> BoundaryCurve for Reversed<C> {
    fn point(&self, t: f64) -> Vector3<f64> {
        self.0.point(1.0 - t)
    }
    fn tangent(&self, t: f64) -> Vector3<f64> {
        -self.0.tangent(1.0 - t)
    }
    fn normal(&self, t: f64) -> Vector3<f64> {
        self.0.normal(1.0 - t)
    }
}

/// Curves behind a pointer are curves.
macro_rules! forward_curve {
    ($($pointer:ident),*) => {$(
        impl<C: BoundaryCurve + ?Sized> BoundaryCurve for $pointer<C> {
            fn point(&self, t: f64) -> Vector3<f64> {
                (**self).point(t)
            }
            fn tangent(&self, t: f64) -> Vector3<f64> {
                (**self).tangent(t)
            }
            fn normal(&self, t: f64) -> Vector3<f64> {
                (**self).normal(t)
            }
        }
    )*};
}

forward_curve!(Box, Arc);

impl SurfaceEdge {
    /// The sides of a surface's parameter domain: its outer boundary split at the corners,
    /// the vertices where the boundary turns (decided by the exact orientation test), each
    /// run counter-clockwise (the domain to its left). A tensor-product surface has four
    /// sides, a triangular patch three, a UPS surface one per polygon side.
    pub fn sides(surface: Arc<Surface>) -> Vec<SurfaceEdge> {
        surface
            .domain()
            .sides()
            .into_iter()
            .map(|(from, to)| SurfaceEdge {
                surface: surface.clone(),
                from,
                to,
            })
            .collect()
    }
}
