//! Exact curvature of a parametric surface at a point, from its first and second partial
//! derivatives (seed 000, section 3.2; the thesis' surfaces give these exactly through their
//! Bézier nets).
//!
//! Conventions (the same for every surface kind):
//!
//! ```text
//! n = s_u × s_v / |s_u × s_v|                              (28)
//! E = s_u·s_u,  F = s_u·s_v,  G = s_v·s_v                  (22)–(24)
//! L = n·s_uu,   M = n·s_uv,   N = n·s_vv                   (25)–(27)
//! K = (LN − M²) / (EG − F²)                                (20)
//! H = (NE − 2MF + LG) / (2 (EG − F²))                      (21)
//! κ1 ≥ κ2 the roots of κ² − 2Hκ + K = 0,   κabs = |κ1| + |κ2|
//! ```
//!
//! For a graph z = f(x, y) (parameters (x, y)) the normal points up, so H > 0 and κ1, κ2 > 0
//! where the surface is convex seen from above (a bowl), and K > 0 at elliptic points, K < 0
//! at hyperbolic (saddle) points. Reversing the orientation (swapping u and v) flips n, H, κ1,
//! κ2 (which also swap) and keeps K. Curvatures have units of 1/length.

use nalgebra::{Vector2, Vector3};
use thiserror::Error;

use crate::bezier::Jet;

/// The default relative tolerance of [`Curvature::is_umbilic`]: |κ1 − κ2| ≤ tol (|κ1| + |κ2|).
pub const DEFAULT_UMBILIC_TOLERANCE: f64 = 1e-8;

/// The surface is singular at the point: s_u × s_v vanishes (relative to |s_u| |s_v|), so
/// the normal and the curvature are undefined there.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
#[error("curvature is undefined: the surface is singular here (|s_u × s_v| = {cross_norm:e})")]
pub struct Singular {
    /// |s_u × s_v|.
    pub cross_norm: f64,
}

/// The first and second fundamental forms at a point, with the unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FundamentalForms {
    /// E = s_u·s_u.
    pub e: f64,
    /// F = s_u·s_v.
    pub f: f64,
    /// G = s_v·s_v.
    pub g: f64,
    /// L = n·s_uu.
    pub l: f64,
    /// M = n·s_uv.
    pub m: f64,
    /// N = n·s_vv.
    pub n: f64,
    /// The unit normal n = s_u × s_v / |s_u × s_v|.
    pub normal: Vector3<f64>,
    /// EG − F², computed as |s_u × s_v|² (Lagrange's identity): the difference EG − F²
    /// itself cancels to nothing on steep graphs (|s_u|, |s_v| ≫ 1 nearly parallel).
    pub det: f64,
}

impl FundamentalForms {
    /// The forms of a surface jet (value, s_u, s_v, s_uu, s_uv, s_vv), or [`Singular`] where
    /// |s_u × s_v| ≤ 1e-14 |s_u| |s_v| (or a derivative is not finite).
    pub fn from_jet(j: &Jet<Vector3<f64>>) -> Result<Self, Singular> {
        let c = j.dx.cross(&j.dy);
        let (e, f, g) = (j.dx.dot(&j.dx), j.dx.dot(&j.dy), j.dy.dot(&j.dy));
        // |c|² = EG − F² (Lagrange); compare squares: |c| > 1e-14 |s_u| |s_v|.
        let c2 = c.norm_squared();
        let size2 = e * g;
        if !(c2 > 1e-28 * size2 && size2 > 0.0 && size2.is_finite()) {
            return Err(Singular {
                cross_norm: c2.sqrt(),
            });
        }
        let normal = c * (1.0 / c2.sqrt());
        Ok(FundamentalForms {
            e,
            f,
            g,
            l: normal.dot(&j.dxx),
            m: normal.dot(&j.dxy),
            n: normal.dot(&j.dyy),
            normal,
            det: c2,
        })
    }

    /// EG − F² = |s_u × s_v|², the area element squared.
    pub fn det_first(&self) -> f64 {
        self.det
    }

    /// The Gaussian curvature K (20).
    pub fn gaussian(&self) -> f64 {
        (self.l * self.n - self.m * self.m) / self.det_first()
    }

    /// The mean curvature H (21).
    pub fn mean(&self) -> f64 {
        0.5 * (self.n * self.e - 2.0 * self.m * self.f + self.l * self.g) / self.det_first()
    }

    /// The normal curvature in the parameter direction (du, dv) ≠ 0: II(d) / I(d), the
    /// curvature of the normal section in the tangent direction s_u du + s_v dv.
    pub fn normal_curvature(&self, d: Vector2<f64>) -> f64 {
        let (a, b) = (d.x, d.y);
        let second = self.l * a * a + 2.0 * self.m * a * b + self.n * b * b;
        let first = self.e * a * a + 2.0 * self.f * a * b + self.g * b * b;
        second / first
    }
}

/// Which curvature quantity to show or export.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CurvatureQuantity {
    /// Gaussian curvature K = κ1 κ2 (1/length²).
    Gaussian,
    /// Mean curvature H = (κ1 + κ2)/2 (1/length).
    Mean,
    /// The larger principal curvature κ1 (1/length).
    K1,
    /// The smaller principal curvature κ2 (1/length).
    K2,
    /// Absolute curvature κabs = |κ1| + |κ2| (1/length).
    Absolute,
}

impl CurvatureQuantity {
    /// All quantities, in the order of the CLI's columns.
    pub const ALL: [CurvatureQuantity; 5] = [
        CurvatureQuantity::Gaussian,
        CurvatureQuantity::Mean,
        CurvatureQuantity::K1,
        CurvatureQuantity::K2,
        CurvatureQuantity::Absolute,
    ];

    /// The short name used in files and on the command line: K, H, k1, k2, kabs.
    pub fn short_name(self) -> &'static str {
        match self {
            CurvatureQuantity::Gaussian => "K",
            CurvatureQuantity::Mean => "H",
            CurvatureQuantity::K1 => "k1",
            CurvatureQuantity::K2 => "k2",
            CurvatureQuantity::Absolute => "kabs",
        }
    }

    /// The name for legends: "Gaussian curvature K", …
    pub fn long_name(self) -> &'static str {
        match self {
            CurvatureQuantity::Gaussian => "Gaussian curvature K",
            CurvatureQuantity::Mean => "mean curvature H",
            CurvatureQuantity::K1 => "principal curvature k1",
            CurvatureQuantity::K2 => "principal curvature k2",
            CurvatureQuantity::Absolute => "absolute curvature |k1|+|k2|",
        }
    }

    /// Its unit: Gaussian curvature is a product of two curvatures (1/length²), the others
    /// are curvatures (1/length).
    pub fn unit(self) -> &'static str {
        match self {
            CurvatureQuantity::Gaussian => "1/length²",
            _ => "1/length",
        }
    }

    /// The long name with its unit, for legends: `mean curvature H [1/length]`.
    pub fn titled(self) -> String {
        format!("{} [{}]", self.long_name(), self.unit())
    }

    /// Whether the quantity takes both signs (then colour ranges are symmetric about 0).
    pub fn is_signed(self) -> bool {
        self != CurvatureQuantity::Absolute
    }

    /// Parses a short or long name ("K", "gaussian", "mean", "k1", "abs", …).
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s.to_ascii_lowercase().as_str() {
            "k" | "gaussian" | "gauss" => CurvatureQuantity::Gaussian,
            "h" | "mean" => CurvatureQuantity::Mean,
            "k1" | "kmax" | "max" => CurvatureQuantity::K1,
            "k2" | "kmin" | "min" => CurvatureQuantity::K2,
            "kabs" | "abs" | "absolute" => CurvatureQuantity::Absolute,
            _ => return None,
        })
    }
}

/// The shape operator in the orthonormal tangent frame e1 = s_u/|s_u|, e2 = n × e1:
/// S = A⁻ᵀ [[L, M], [M, N]] A⁻¹ with A = [[a11, a12], [0, a22]] the frame coordinates of s_u
/// and s_v, and A⁻¹ = [[i11, i12], [0, i22]].
struct ShapeOperator {
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    i11: f64,
    i12: f64,
    i22: f64,
    s11: f64,
    s12: f64,
    s22: f64,
}

impl ShapeOperator {
    #[inline]
    fn new(j: &Jet<Vector3<f64>>, forms: &FundamentalForms) -> Self {
        let i11 = 1.0 / forms.e.sqrt();
        let e1 = j.dx * i11;
        let e2 = forms.normal.cross(&e1);
        let a12 = j.dy.dot(&e1);
        let i22 = 1.0 / j.dy.dot(&e2);
        let i12 = -a12 * i11 * i22;
        // C = B A⁻¹, then S = A⁻ᵀ C (symmetric).
        let (l, m, n) = (forms.l, forms.m, forms.n);
        let c11 = l * i11;
        let c12 = l * i12 + m * i22;
        let c22 = m * i12 + n * i22;
        ShapeOperator {
            e1,
            e2,
            i11,
            i12,
            i22,
            s11: i11 * c11,
            s12: i11 * c12,
            s22: i12 * c12 + i22 * c22,
        }
    }

    /// K and H by (20)–(21), κ1,2 = centre ± √(((S11 − S22)/2)² + S12²).
    #[inline]
    fn principal(&self, forms: &FundamentalForms) -> PrincipalCurvatures {
        let half_diff = 0.5 * (self.s11 - self.s22);
        let d = (half_diff * half_diff + self.s12 * self.s12).sqrt();
        let centre = 0.5 * (self.s11 + self.s22);
        let inv_det = 1.0 / forms.det_first();
        let (e, f, g, l, m, n) = (forms.e, forms.f, forms.g, forms.l, forms.m, forms.n);
        PrincipalCurvatures {
            gaussian: (l * n - m * m) * inv_det,
            mean: 0.5 * (n * e - 2.0 * m * f + l * g) * inv_det,
            k1: centre + d,
            k2: centre - d,
        }
    }
}

/// The traceless part of the shape operator at a point, ((S11 − S22)/2, S12) in the frame
/// e1 = s_u/|s_u|, e2 = n × e1 (smooth in (u, v) inside a piece; both vanish exactly at
/// umbilics, where κ1 = κ2), and the mean curvature H; `None` at a singular point.
pub(crate) fn umbilic_residual(j: &Jet<Vector3<f64>>) -> Option<(Vector2<f64>, f64)> {
    let forms = FundamentalForms::from_jet(j).ok()?;
    let s = ShapeOperator::new(j, &forms);
    Some((
        Vector2::new(0.5 * (s.s11 - s.s22), s.s12),
        0.5 * (s.s11 + s.s22),
    ))
}

/// The curvature values at a point, without directions (cheaper; what plots and exports
/// need). At singular points every value is NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalCurvatures {
    /// Gaussian curvature K (20).
    pub gaussian: f64,
    /// Mean curvature H (21).
    pub mean: f64,
    /// The larger principal curvature κ1.
    pub k1: f64,
    /// The smaller principal curvature κ2.
    pub k2: f64,
}

impl PrincipalCurvatures {
    /// All NaN: the value at a singular point.
    pub const UNDEFINED: PrincipalCurvatures = PrincipalCurvatures {
        gaussian: f64::NAN,
        mean: f64::NAN,
        k1: f64::NAN,
        k2: f64::NAN,
    };

    /// The values from the Gaussian and mean curvature alone (as discrete estimates on
    /// meshes give them): κ1,2 = H ± √(max(H² − K, 0)), the roots of κ² − 2Hκ + K = 0
    /// (seed 000, eqs. 20–21), with a negative discriminant from rounding taken as 0.
    pub fn from_gaussian_mean(gaussian: f64, mean: f64) -> Self {
        let d = (mean * mean - gaussian).max(0.0).sqrt();
        PrincipalCurvatures {
            gaussian,
            mean,
            k1: mean + d,
            k2: mean - d,
        }
    }

    /// The values at a point from the surface's jet there, and the unit normal (as
    /// [`Curvature::from_jet`] without the directions).
    #[inline]
    pub fn from_jet(j: &Jet<Vector3<f64>>) -> Result<(Self, Vector3<f64>), Singular> {
        let forms = FundamentalForms::from_jet(j)?;
        Ok((
            ShapeOperator::new(j, &forms).principal(&forms),
            forms.normal,
        ))
    }

    /// The value of one quantity.
    #[inline]
    pub fn get(&self, q: CurvatureQuantity) -> f64 {
        match q {
            CurvatureQuantity::Gaussian => self.gaussian,
            CurvatureQuantity::Mean => self.mean,
            CurvatureQuantity::K1 => self.k1,
            CurvatureQuantity::K2 => self.k2,
            CurvatureQuantity::Absolute => self.k1.abs() + self.k2.abs(),
        }
    }
}

/// Everything about the curvature of a surface at a regular point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Curvature {
    /// Gaussian curvature K (20).
    pub gaussian: f64,
    /// Mean curvature H (21).
    pub mean: f64,
    /// The larger principal curvature κ1 = H + √(H² − K).
    pub k1: f64,
    /// The smaller principal curvature κ2 = H − √(H² − K).
    pub k2: f64,
    /// The unit normal n.
    pub normal: Vector3<f64>,
    /// The unit principal direction of κ1 in space (tangent to the surface).
    pub dir1: Vector3<f64>,
    /// The unit principal direction of κ2 in space; (dir1, dir2, n) is right-handed.
    pub dir2: Vector3<f64>,
    /// The parameter direction (du, dv), unit length, that s maps onto `dir1`.
    pub dir1_uv: Vector2<f64>,
    /// The parameter direction (du, dv), unit length, that s maps onto `dir2`.
    pub dir2_uv: Vector2<f64>,
}

impl Curvature {
    /// The curvature at a point from the surface's jet there.
    ///
    /// The principal curvatures and directions are the eigenpairs of the shape operator
    /// written in the orthonormal tangent frame e1 = s_u/|s_u|, e2 = n × e1, where it is a
    /// symmetric 2×2 matrix S = A⁻ᵀ [[L, M], [M, N]] A⁻¹ (A maps (du, dv) to frame
    /// coordinates). Its eigenvalues H ± √(((S11 − S22)/2)² + S12²) have no cancellation, so
    /// κ1 − κ2 is accurate even near umbilics; K and H themselves are (20)–(21).
    pub fn from_jet(j: &Jet<Vector3<f64>>) -> Result<Self, Singular> {
        let forms = FundamentalForms::from_jet(j)?;
        Ok(Self::from_forms(j, &forms))
    }

    /// As [`Curvature::from_jet`], with the forms already computed.
    pub fn from_forms(j: &Jet<Vector3<f64>>, forms: &FundamentalForms) -> Self {
        let s = ShapeOperator::new(j, forms);
        let p = s.principal(forms);
        // The eigenvector (x, y) of the larger eigenvalue κ1 of [[s11, s12], [s12, s22]]:
        // (s12, κ1 − s11) or (κ1 − s22, s12), whichever is longer (both are unless S is a
        // multiple of the identity, an umbilic, where any direction will do).
        let (a, b) = ((s.s12, p.k1 - s.s11), (p.k1 - s.s22, s.s12));
        let (na, nb) = (a.0 * a.0 + a.1 * a.1, b.0 * b.0 + b.1 * b.1);
        let (x, y, n2) = if na >= nb {
            (a.0, a.1, na)
        } else {
            (b.0, b.1, nb)
        };
        let (cs, sn) = if n2 > 0.0 {
            let r = 1.0 / n2.sqrt();
            (x * r, y * r)
        } else {
            (1.0, 0.0)
        };
        let dir1 = s.e1 * cs + s.e2 * sn;
        let dir2 = forms.normal.cross(&dir1);
        let to_uv = |x: f64, y: f64| {
            let w = Vector2::new(s.i11 * x + s.i12 * y, s.i22 * y);
            w / w.norm()
        };
        Curvature {
            gaussian: p.gaussian,
            mean: p.mean,
            k1: p.k1,
            k2: p.k2,
            normal: forms.normal,
            dir1,
            dir2,
            dir1_uv: to_uv(cs, sn),
            dir2_uv: to_uv(-sn, cs),
        }
    }

    /// The curvature values without the directions.
    pub fn principal(&self) -> PrincipalCurvatures {
        PrincipalCurvatures {
            gaussian: self.gaussian,
            mean: self.mean,
            k1: self.k1,
            k2: self.k2,
        }
    }

    /// κabs = |κ1| + |κ2|.
    pub fn absolute(&self) -> f64 {
        self.k1.abs() + self.k2.abs()
    }

    /// The value of one quantity.
    pub fn get(&self, q: CurvatureQuantity) -> f64 {
        match q {
            CurvatureQuantity::Gaussian => self.gaussian,
            CurvatureQuantity::Mean => self.mean,
            CurvatureQuantity::K1 => self.k1,
            CurvatureQuantity::K2 => self.k2,
            CurvatureQuantity::Absolute => self.absolute(),
        }
    }

    /// Euler's formula: the normal curvature in the tangent direction at angle θ from the
    /// first principal direction, κ(θ) = κ1 cos²θ + κ2 sin²θ (seed 003).
    pub fn normal_curvature_at_angle(&self, theta: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        self.k1 * c * c + self.k2 * s * s
    }

    /// The normal curvature in a tangent direction given in space (its component along the
    /// normal is ignored), by Euler's formula.
    pub fn normal_curvature(&self, direction: Vector3<f64>) -> f64 {
        let (x, y) = (direction.dot(&self.dir1), direction.dot(&self.dir2));
        let r2 = x * x + y * y;
        (self.k1 * x * x + self.k2 * y * y) / r2
    }

    /// Whether the point is an umbilic (κ1 = κ2, every direction principal; planar points
    /// included) up to the relative tolerance: κ1 − κ2 ≤ tol (|κ1| + |κ2|). The principal
    /// directions reported at an umbilic are arbitrary.
    pub fn is_umbilic(&self, tolerance: f64) -> bool {
        self.k1 - self.k2 <= tolerance * (self.k1.abs() + self.k2.abs())
    }
}
