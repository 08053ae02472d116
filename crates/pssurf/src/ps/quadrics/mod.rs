//! Quadrics as NURPS (thesis 3.6): rational quadratic Bézier patches on the cylinder (3.115),
//! the cone (3.6.2) and the sphere (3.118)–(3.122), and the complete cylinder and cone and the
//! sphere with gaps built from them, each patch converted by the optimal representation
//! ([`super::from_bezier::nurps_optimal`]).
//!
//! The cone's patch was re-derived: the thesis gives only its NURPS table. For the patch to
//! lie on the cone, every point must be a combination of the apex and a point of the base arc,
//! so the ordinates b₁₀₁ and b₀₁₁ must be the apex itself (weight 1); the table's c_{1,3} =
//! (r/3, 0, 2h/3) = ⅔ apex + ⅓ (r, 0, 0) and c_{2,2} confirm it. The control triangle at the
//! apex is degenerate, a cusp in the sense of 3.4.4. The table's c_{2,1} = (r, √3 r/2, 0) is
//! a misprint for (r/2, √3 r/2, 0), the end of the 60° arc (it is not on the base circle).

use nalgebra::{Rotation3, Vector3};

use super::Nurps;
use super::from_bezier::{ConversionError, equilateral, nurps_optimal};
use crate::bezier::RationalBezierTriangle;

/// The largest radius or height accepted.
const MAX_SIZE: f64 = 1e12;
/// The most sectors of the sphere (2 × this many patches).
pub const MAX_SECTORS: usize = 720;

/// The thesis' rational quadratic patch on the cylinder x² + y² = r², 0 ≤ z ≤ h (3.115): corners
/// (r, 0, 0), (0, r, 0), (r, 0, h); weights 1 except w₁₁₀ = w₀₁₁ = √2/2.
pub fn cylinder_patch(r: f64, h: f64) -> RationalBezierTriangle<Vector3<f64>> {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let points = vec![
        Vector3::new(r, 0.0, 0.0),     // 200
        Vector3::new(r, r, 0.0),       // 110
        Vector3::new(r, 0.0, 0.5 * h), // 101
        Vector3::new(0.0, r, 0.0),     // 020
        Vector3::new(r, r, 0.5 * h),   // 011
        Vector3::new(r, 0.0, h),       // 002
    ];
    let weights = vec![1.0, s, 1.0, 1.0, s, 1.0];
    RationalBezierTriangle::try_new(equilateral(), 2, points, weights).expect("a valid patch")
}

/// A rational quadratic patch on the cone x² + y² = ((h − z) r / h)², 0 ≤ z ≤ h (3.116): the
/// 60° base arc from (r, 0, 0) to (r/2, √3 r/2, 0) (middle ordinate (r, r/√3, 0), weight √3/2)
/// and the apex (0, 0, h) as the other three ordinates.
pub fn cone_patch(r: f64, h: f64) -> RationalBezierTriangle<Vector3<f64>> {
    let apex = Vector3::new(0.0, 0.0, h);
    let points = vec![
        Vector3::new(r, 0.0, 0.0),                      // 200
        Vector3::new(r, r / 3f64.sqrt(), 0.0),          // 110
        apex,                                           // 101
        Vector3::new(0.5 * r, 0.75f64.sqrt() * r, 0.0), // 020
        apex,                                           // 011
        apex,                                           // 002
    ];
    let weights = vec![1.0, 0.75f64.sqrt(), 1.0, 1.0, 1.0, 1.0];
    RationalBezierTriangle::try_new(equilateral(), 2, points, weights).expect("a valid patch")
}

/// The thesis' rational quadratic patch on the sphere of radius `r` with span `b` (3.118),
/// (3.122): corners (cos b, ∓sin b, 0) r and the north pole; w₀₁₁ = w₁₀₁ = √2/2, w₁₁₀ = cos² b.
/// It leaves a gap of height [`sphere_gap`] above the equator.
pub fn sphere_patch(r: f64, b: f64) -> RationalBezierTriangle<Vector3<f64>> {
    let (s, c) = b.sin_cos();
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let points = vec![
        Vector3::new(c, -s, 0.0),                    // 200
        Vector3::new(1.0 / c, 0.0, (s / c).powi(2)), // 110
        Vector3::new(c, -s, 1.0),                    // 101
        Vector3::new(c, s, 0.0),                     // 020
        Vector3::new(c, s, 1.0),                     // 011
        Vector3::new(0.0, 0.0, 1.0),                 // 002
    ]
    .into_iter()
    .map(|p| p * r)
    .collect();
    let weights = vec![1.0, c * c, w, 1.0, w, 1.0];
    RationalBezierTriangle::try_new(equilateral(), 2, points, weights).expect("a valid patch")
}

/// The height of the gap between the sphere patch's lower boundary and the equator for span
/// `b` (3.124), relative to the radius: sin² b / (cos² b + 1).
pub fn sphere_gap(b: f64) -> f64 {
    let (s, c) = b.sin_cos();
    s * s / (c * c + 1.0)
}

/// Why a quadric cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QuadricError {
    /// A radius or height that is not a positive number up to 1e12.
    #[error("the {what} must be a positive number up to 1e12, not {value}")]
    BadSize {
        /// "radius" or "height".
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A sphere with too few or too many sectors.
    #[error("a sphere needs 3 to {MAX_SECTORS} sectors (2 patches each), not {0}")]
    BadSectors(usize),
    /// A patch did not convert (cannot happen for valid sizes).
    #[error(transparent)]
    Conversion(#[from] ConversionError),
}

/// A complete quadric as rational quadratic patches (3.6), each exactly on the quadric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Quadric {
    /// x² + y² = r², 0 ≤ z ≤ h: eight patches (Figure 3.17), four quarters each cut along a
    /// diagonal; no gaps.
    Cylinder {
        /// r.
        radius: f64,
        /// h.
        height: f64,
    },
    /// x² + y² = ((h − z) r / h)², 0 ≤ z ≤ h: six 60° patches meeting at the apex
    /// (Figure 3.21(a)); no gaps.
    Cone {
        /// The base radius r.
        radius: f64,
        /// h.
        height: f64,
    },
    /// x² + y² + z² = r² by 2n patches of span b = π/n (n around each hemisphere, Figure
    /// 3.21(b)), leaving a band of height 2 r sin² b / (cos² b + 1) around the equator open
    /// (3.124): more sectors, smaller gaps. A whole sphere cannot be made of rational quadratic
    /// triangles.
    Sphere {
        /// r.
        radius: f64,
        /// n ≥ 3.
        sectors: usize,
    },
}

impl Quadric {
    /// "cylinder", "cone" or "sphere".
    pub fn name(&self) -> &'static str {
        match self {
            Quadric::Cylinder { .. } => "cylinder",
            Quadric::Cone { .. } => "cone",
            Quadric::Sphere { .. } => "sphere",
        }
    }

    /// Checks the sizes: positive up to 1e12, 3 to [`MAX_SECTORS`] sectors.
    pub fn validate(&self) -> Result<(), QuadricError> {
        let size = |what, value: f64| {
            if value > 0.0 && value <= MAX_SIZE {
                Ok(())
            } else {
                Err(QuadricError::BadSize { what, value })
            }
        };
        match *self {
            Quadric::Cylinder { radius, height } | Quadric::Cone { radius, height } => {
                size("radius", radius)?;
                size("height", height)
            }
            Quadric::Sphere { radius, sectors } => {
                size("radius", radius)?;
                if (3..=MAX_SECTORS).contains(&sectors) {
                    Ok(())
                } else {
                    Err(QuadricError::BadSectors(sectors))
                }
            }
        }
    }

    /// The rational quadratic Bézier patches, each with its normal pointing outwards.
    pub fn bezier_patches(
        &self,
    ) -> Result<Vec<RationalBezierTriangle<Vector3<f64>>>, QuadricError> {
        self.validate()?;
        let turn = |b: &RationalBezierTriangle<Vector3<f64>>, angle: f64| {
            let rot = Rotation3::from_axis_angle(&Vector3::z_axis(), angle);
            transform(b, |p| rot * p, false)
        };
        let quarter = std::f64::consts::FRAC_PI_2;
        Ok(match *self {
            Quadric::Cylinder { radius, height } => {
                let up = cylinder_patch(radius, height);
                // The other half of the quarter: the turn by π about the line through
                // (r/√2, r/√2, h/2) along (1, −1, 0), (x, y, z) → (y, x, h − z).
                let down = transform(&up, |p| Vector3::new(p.y, p.x, height - p.z), false);
                (0..4)
                    .flat_map(|k| {
                        [
                            turn(&up, k as f64 * quarter),
                            turn(&down, k as f64 * quarter),
                        ]
                    })
                    .collect()
            }
            Quadric::Cone { radius, height } => {
                let p = cone_patch(radius, height);
                (0..6)
                    .map(|k| turn(&p, k as f64 * std::f64::consts::FRAC_PI_3))
                    .collect()
            }
            Quadric::Sphere { radius, sectors } => {
                let b = std::f64::consts::PI / sectors as f64;
                let north = sphere_patch(radius, b);
                // The mirror image in the equator plane, with τ₁ and τ₂ swapped to keep the
                // normal outwards.
                let south = transform(&north, |p| Vector3::new(p.x, p.y, -p.z), true);
                let step = 2.0 * b;
                (0..sectors)
                    .flat_map(|k| [turn(&north, k as f64 * step), turn(&south, k as f64 * step)])
                    .collect()
            }
        })
    }

    /// The patches as NURPS (the optimal representation, 3.103–3.111).
    pub fn nurps_patches(&self) -> Result<Vec<Nurps<Vector3<f64>>>, QuadricError> {
        self.bezier_patches()?
            .iter()
            .map(|b| Ok(nurps_optimal(b)?))
            .collect()
    }

    /// The distance from `p` to the quadric's (unbounded) surface.
    pub fn distance(&self, p: Vector3<f64>) -> f64 {
        match *self {
            Quadric::Cylinder { radius, .. } => (p.xy().norm() - radius).abs(),
            Quadric::Cone { radius, height } => {
                // The generator through (r, 0) and (0, h) in the (ρ, z) half-plane.
                (height * p.xy().norm() + radius * p.z - radius * height).abs()
                    / radius.hypot(height)
            }
            Quadric::Sphere { radius, .. } => (p.norm() - radius).abs(),
        }
    }

    /// The height of each of the two open bands next to the equator of the sphere (3.124),
    /// in model units; 0 for the closed cylinder and cone.
    pub fn gap(&self) -> f64 {
        match *self {
            Quadric::Sphere { radius, sectors } => {
                radius * sphere_gap(std::f64::consts::PI / sectors.max(1) as f64)
            }
            _ => 0.0,
        }
    }
}

/// The patch with every ordinate mapped by the affine map `f` (rational Bézier patches are
/// affine invariant); with `swap` the roles of τ₁ and τ₂ are exchanged, reversing the normal.
fn transform(
    b: &RationalBezierTriangle<Vector3<f64>>,
    f: impl Fn(Vector3<f64>) -> Vector3<f64>,
    swap: bool,
) -> RationalBezierTriangle<Vector3<f64>> {
    // 200 110 101 020 011 002 with τ₁ ↔ τ₂: 020 110 011 200 101 002.
    let order: [usize; 6] = if swap {
        [3, 1, 4, 0, 2, 5]
    } else {
        [0, 1, 2, 3, 4, 5]
    };
    let points = order.iter().map(|&k| f(b.points()[k])).collect();
    let weights = order.iter().map(|&k| b.weights()[k]).collect();
    RationalBezierTriangle::try_new(*b.domain(), 2, points, weights).expect("a valid patch")
}

#[cfg(test)]
mod tests;
