//! NURBS → UPS approximation (thesis 6.4.2, (6.1)–(6.9)): a NURBS surface S on the rectangle
//! R = [ū₀, ū₀ + W] × [v̄₀, v̄₀ + H] is approximated by the UPS surface s on the lattice
//! parallelogram Ω with n_u × n_v triangles along its sides that interpolates S ∘ θ, value and
//! first derivatives, at every vertex ((6.3)–(6.5), control points by (4.9) = (6.6)–(6.8)).
//!
//! θ : Ω → R is the affine map that sends lattice point (i, j) to
//! (ū₀ + W i/n_u, v̄₀ + H j/n_v). With the lattice's Cartesian coordinates
//! u − u₀ = B (i + j/2), v − v₀ = B (√3/2) j it reads
//!
//! ```text
//! ū = ū₀ + W/(n_u B) (u − u₀) − (√3/3) W/(n_u B) (v − v₀),   v̄ = v̄₀ + (2√3/3) H/(n_v B) (v − v₀)   (6.2)
//! ```
//!
//! (the extracted seed text shows a + before the second term of ū; the − is the one that maps
//! Ω onto R, as the derivation from the lattice coordinates shows and the tests check).
//! The default n_u, n_v follow (6.9): n ≈ (√3/3) k − 1 for k control points in a direction,
//! so that the UPS surface has about as many control points as the NURBS net. Beyond the
//! thesis, the deviation |s(p) − S(θ(p))| is measured densely on every piece (maximum and RMS
//! in model units), and a tolerance refines n_u, n_v until the maximum meets it; the error
//! is of third order, so a refinement by the cube root of the ratio is tried first.

use nalgebra::{Point2, Vector3};
use thiserror::Error;

use super::surface::NurbsSurface;
use rayon::prelude::*;

use crate::ps::Hermite;
use crate::surface::{ParametricSurface, PiecewiseSurface, Surface, UpsSurface};
use crate::ups::{Lattice, LatticePolygon, Ups, UpsGrid};

/// Why an approximation could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ApproxError {
    /// A count is zero or too large.
    #[error("n_u and n_v must be from 1 to {MAX_N} (got {0} × {1})")]
    Counts(usize, usize),
    /// The tolerance is not positive and finite.
    #[error("the tolerance must be a positive finite number (got {0})")]
    Tolerance(f64),
    /// Refinement reached the largest counts without meeting the tolerance.
    #[error(
        "the tolerance {tolerance} is not met with {counts:?} triangles per side (the deviation is still {reached}); give a larger tolerance"
    )]
    NotMet {
        /// The tolerance asked for.
        tolerance: f64,
        /// The largest counts tried.
        counts: [usize; 2],
        /// The deviation they reached.
        reached: f64,
    },
    /// The interpolant's control values would lie beyond ±1e60: the surface's derivatives
    /// are that large (for instance on a parameter domain of almost no width).
    #[error(
        "the NURBS surface's derivatives on its parameter domain [{}, {}] × [{}, {}] are too large: the UPS approximation would have control values beyond ±1e60",
        crate::text::Short(domain[0]), crate::text::Short(domain[1]), crate::text::Short(domain[2]), crate::text::Short(domain[3])
    )]
    TooLarge {
        /// [u0, u1, v0, v1].
        domain: [f64; 4],
    },
}

/// The most triangles along a side of Ω (a UPS surface of 40,000 vertices).
pub const MAX_N: usize = 200;

/// How the approximation is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApproxOptions {
    /// [n_u, n_v], or `None` for the default of (6.9).
    pub counts: Option<[usize; 2]>,
    /// Refine until the maximum deviation is at most this (model units).
    pub tolerance: Option<f64>,
    /// Samples per piece edge for measuring the deviation are 2^level.
    pub level: u32,
}

impl Default for ApproxOptions {
    fn default() -> Self {
        ApproxOptions {
            counts: None,
            tolerance: None,
            level: 3,
        }
    }
}

/// A UPS approximation of a NURBS surface with its measured deviation.
#[derive(Clone, Debug)]
pub struct Approximation {
    /// The UPS surface (parametric).
    pub surface: UpsSurface,
    /// Its [n_u, n_v].
    pub counts: [usize; 2],
    /// The largest |s(p) − S(θ(p))| over the samples.
    pub max_deviation: f64,
    /// The root mean square of the same.
    pub rms_deviation: f64,
    /// Every (counts, max, rms) tried, in order.
    pub tried: Vec<([usize; 2], f64, f64)>,
}

/// The default counts of (6.9): n ≈ (√3/3) k − 1, at least 1.
pub fn default_counts(s: &NurbsSurface) -> [usize; 2] {
    s.counts()
        .map(|k| ((3f64.sqrt() / 3.0 * k as f64 - 1.0).round().max(1.0) as usize).min(MAX_N))
}

/// The affine map θ of (6.2) for counts `n` on a lattice of base 1 at the origin, as
/// (ū, v̄) = A (u, v) + c.
struct Theta {
    a11: f64,
    a12: f64,
    a22: f64,
    c: Point2<f64>,
}

impl Theta {
    fn new(s: &NurbsSurface, n: [usize; 2]) -> Self {
        let (lo, hi) = s.domain_bounds();
        let (w, h) = (hi.x - lo.x, hi.y - lo.y);
        let (nu, nv) = (n[0] as f64, n[1] as f64);
        Theta {
            a11: w / nu,
            a12: -(3f64.sqrt() / 3.0) * w / nu,
            a22: 2.0 * 3f64.sqrt() / 3.0 * h / nv,
            c: lo,
        }
    }

    fn at(&self, p: Point2<f64>) -> Point2<f64> {
        Point2::new(
            self.c.x + self.a11 * p.x + self.a12 * p.y,
            self.c.y + self.a22 * p.y,
        )
    }
}

/// The lattice parallelogram Ω with `n` = [n_u, n_v] triangles along its sides (base 1).
fn grid(n: [usize; 2]) -> UpsGrid {
    let (nu, nv) = (n[0] as i64, n[1] as i64);
    UpsGrid::new(
        Lattice {
            base: 1.0,
            origin: Point2::origin(),
        },
        LatticePolygon::new(vec![[0, 0], [nu, 0], [nu, nv], [0, nv]]).expect("a parallelogram"),
    )
    .expect("a valid grid")
}

/// The UPS surface interpolating S ∘ θ (values and first derivatives) at every vertex of Ω
/// with `n` = [n_u, n_v].
pub fn ups_of_nurbs(s: &NurbsSurface, n: [usize; 2]) -> Result<UpsSurface, ApproxError> {
    if !(1..=MAX_N).contains(&n[0]) || !(1..=MAX_N).contains(&n[1]) {
        return Err(ApproxError::Counts(n[0], n[1]));
    }
    let theta = Theta::new(s, n);
    let (lo, hi) = s.domain_bounds();
    let ups = Ups::hermite(grid(n), |p| {
        // Lattice points map onto R; clamp rounding just outside it.
        let q = theta.at(p);
        let q = Point2::new(q.x.clamp(lo.x, hi.x), q.y.clamp(lo.y, hi.y));
        let j = s.jet(q).expect("θ maps Ω onto the domain").jet;
        // The chain rule through θ: ∂/∂u = a11 S_ū, ∂/∂v = a12 S_ū + a22 S_v̄.
        Hermite {
            value: j.value,
            dx: j.dx * theta.a11,
            dy: j.dx * theta.a12 + j.dy * theta.a22,
        }
    });
    let ups = UpsSurface::Parametric(ups);
    match ups.first_unusable_vertex() {
        Some(_) => Err(ApproxError::TooLarge {
            domain: [lo.x, hi.x, lo.y, hi.y],
        }),
        None => Ok(ups),
    }
}

/// The most deviation samples (the level is lowered for large surfaces to stay under it).
const MAX_SAMPLES: usize = 4_000_000;

/// The maximum and RMS of |s(p) − S(θ(p))| over the barycentric lattice of 2^level steps per
/// edge on every piece (fewer on large surfaces, at most 4 million (`MAX_SAMPLES`) in all), in parallel
/// and without storing the samples.
pub fn deviation(s: &NurbsSurface, ups: &UpsSurface, n: [usize; 2], level: u32) -> (f64, f64) {
    let Ok(surface) = Surface::try_from(ups.clone()) else {
        // Values beyond the supported range (which `approximate` refuses): no deviation.
        return (f64::INFINITY, f64::INFINITY);
    };
    let pieces = surface.piece_count();
    let mut m = 1usize << level.min(8);
    while m > 1 && pieces * (m + 1) * (m + 2) / 2 > MAX_SAMPLES {
        m /= 2;
    }
    let theta = Theta::new(s, n);
    let (lo, hi) = s.domain_bounds();
    let (max, sum, count) = (0..pieces)
        .into_par_iter()
        .map(|k| {
            let Some(frame) = surface.piece_shape(k).frame() else {
                return (0.0, 0.0, 0usize);
            };
            let (mut max, mut sum, mut count) = (0.0f64, 0.0, 0);
            for i in 0..=m {
                for j in 0..=m - i {
                    let b = [
                        i as f64 / m as f64,
                        j as f64 / m as f64,
                        (m - i - j) as f64 / m as f64,
                    ];
                    let at = frame.at_bary(b);
                    let p = surface.piece_jet(k, &at).value;
                    let q = theta.at(at.uv);
                    let q = Point2::new(q.x.clamp(lo.x, hi.x), q.y.clamp(lo.y, hi.y));
                    let exact: Vector3<f64> = s.point(q).expect("inside");
                    let d = (p - exact).norm();
                    max = max.max(d);
                    sum += d * d;
                    count += 1;
                }
            }
            (max, sum, count)
        })
        .reduce(
            || (0.0, 0.0, 0),
            |a, b| (a.0.max(b.0), a.1 + b.1, a.2 + b.2),
        );
    (max, (sum / count.max(1) as f64).sqrt())
}

/// Approximates `s` by a UPS surface (see the module's notes).
pub fn approximate(s: &NurbsSurface, opts: &ApproxOptions) -> Result<Approximation, ApproxError> {
    if let Some(t) = opts.tolerance
        && !(t > 0.0 && t.is_finite())
    {
        return Err(ApproxError::Tolerance(t));
    }
    let mut n = opts.counts.unwrap_or_else(|| default_counts(s));
    let mut tried = Vec::new();
    loop {
        let surface = ups_of_nurbs(s, n)?;
        let (max, rms) = deviation(s, &surface, n, opts.level);
        tried.push((n, max, rms));
        let done = opts.tolerance.is_none_or(|t| max <= t);
        if done {
            return Ok(Approximation {
                surface,
                counts: n,
                max_deviation: max,
                rms_deviation: rms,
                tried,
            });
        }
        let t = opts.tolerance.expect("not done without a tolerance");
        if n[0] >= MAX_N && n[1] >= MAX_N {
            return Err(ApproxError::NotMet {
                tolerance: t,
                counts: n,
                reached: max,
            });
        }
        // Third order: the deviation falls as n⁻³; aim a little past the tolerance.
        let factor = (1.2 * max / t).cbrt().clamp(1.25, 4.0);
        n = n.map(|k| ((k as f64 * factor).ceil() as usize).max(k + 1).min(MAX_N));
    }
}
