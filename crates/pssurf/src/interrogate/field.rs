//! Scalar fields on a surface whose level lines can be traced: a curvature quantity, the
//! height z, or (with the `expr` feature) a formula in u, v, x, y, z, K, H, k1, k2, kabs.

#[cfg(feature = "expr")]
use std::sync::Arc;

use nalgebra::{Point2, Vector2, Vector3};

use super::curvature::{CurvatureQuantity, PrincipalCurvatures};
use crate::bezier::Jet;

/// The variables a field formula may use, in this order.
pub const FIELD_VARIABLES: [&str; 10] = ["u", "v", "x", "y", "z", "K", "H", "k1", "k2", "kabs"];

/// A scalar field on a surface, evaluated from the surface's jet at a parameter point.
#[derive(Clone, Debug)]
pub enum SurfaceField {
    /// A curvature quantity (K, H, κ1, κ2, |κ1| + |κ2|); NaN at singular points.
    Curvature(CurvatureQuantity),
    /// The height z of the surface point.
    Height,
    /// A formula of the variables [`FIELD_VARIABLES`].
    #[cfg(feature = "expr")]
    Formula(Arc<crate::expr::Formula>),
}

/// A field could not be made from its description.
#[derive(Clone, Debug, thiserror::Error, PartialEq)]
pub enum FieldError {
    /// The text is neither a quantity name nor (without the `expr` feature) allowed.
    #[error(
        "`{0}` is not a field: use K, H, k1, k2, kabs, z or a formula of u, v, x, y, z, K, H, k1, k2, kabs"
    )]
    Unknown(String),
    /// The formula does not parse.
    #[cfg(feature = "expr")]
    #[error(transparent)]
    Formula(#[from] crate::expr::ExprError),
}

impl SurfaceField {
    /// The field named by `text`: a curvature name (`K`, `H`, `k1`, `k2`, `kabs`, or their
    /// long names), `z` / `height`, or a formula.
    ///
    /// ```
    /// use pssurf::interrogate::SurfaceField;
    /// assert_eq!(SurfaceField::parse("K").unwrap().name(), "K");
    /// assert_eq!(SurfaceField::parse("height").unwrap().name(), "z");
    /// assert!(SurfaceField::parse("K*").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, FieldError> {
        let t = text.trim();
        if let Some(q) = CurvatureQuantity::parse(t) {
            return Ok(SurfaceField::Curvature(q));
        }
        if t == "z" || t.eq_ignore_ascii_case("height") {
            return Ok(SurfaceField::Height);
        }
        #[cfg(feature = "expr")]
        {
            let f = crate::expr::Formula::parse(t, &FIELD_VARIABLES)?;
            Ok(SurfaceField::Formula(Arc::new(f)))
        }
        #[cfg(not(feature = "expr"))]
        Err(FieldError::Unknown(crate::text::cut(t)))
    }

    /// A short name: `K`, `H`, `k1`, `k2`, `kabs`, `z` or the formula.
    pub fn name(&self) -> String {
        match self {
            SurfaceField::Curvature(q) => q.short_name().to_string(),
            SurfaceField::Height => "z".into(),
            #[cfg(feature = "expr")]
            SurfaceField::Formula(f) => f.text().to_string(),
        }
    }

    /// Whether the value depends on second derivatives (so it jumps across the pieces of a
    /// C¹ surface).
    pub fn uses_curvature(&self) -> bool {
        match self {
            SurfaceField::Curvature(_) => true,
            SurfaceField::Height => false,
            #[cfg(feature = "expr")]
            SurfaceField::Formula(_) => true,
        }
    }

    /// The value at parameter `uv` where the surface's jet is `jet`; NaN where undefined.
    #[cfg_attr(not(feature = "expr"), allow(unused_variables))]
    pub fn value(&self, uv: Point2<f64>, jet: &Jet<Vector3<f64>>) -> f64 {
        match self {
            SurfaceField::Curvature(q) => {
                PrincipalCurvatures::from_jet(jet).map_or(f64::NAN, |(c, _)| c.get(*q))
            }
            SurfaceField::Height => jet.value.z,
            #[cfg(feature = "expr")]
            SurfaceField::Formula(f) => {
                let c = PrincipalCurvatures::from_jet(jet)
                    .map_or(PrincipalCurvatures::UNDEFINED, |(c, _)| c);
                let p = jet.value;
                f.eval(&[
                    uv.x,
                    uv.y,
                    p.x,
                    p.y,
                    p.z,
                    c.gaussian,
                    c.mean,
                    c.k1,
                    c.k2,
                    c.k1.abs() + c.k2.abs(),
                ])
            }
        }
    }

    /// The exact gradient w.r.t. (u, v) where the jet gives it (the height: (z_u, z_v));
    /// `None` when it needs third derivatives (then it is taken by differences).
    pub fn gradient(&self, jet: &Jet<Vector3<f64>>) -> Option<Vector2<f64>> {
        match self {
            SurfaceField::Height => Some(Vector2::new(jet.dx.z, jet.dy.z)),
            _ => None,
        }
    }
}
