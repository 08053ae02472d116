//! Helpers shared by the unit tests: seeded randomness, random geometry, relative comparison.

use nalgebra::{Point2, Vector2};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::geometry::{Bary, Triangle2};

/// A seeded generator, so failures reproduce.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A uniform number in [lo, hi).
pub fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    rng.random_range(lo..hi)
}

/// A random counter-clockwise triangle with minimum angle not too small.
pub fn random_triangle(rng: &mut ChaCha8Rng) -> Triangle2 {
    loop {
        let p = |r: &mut ChaCha8Rng| Point2::new(uniform(r, -2.0, 2.0), uniform(r, -2.0, 2.0));
        let t = Triangle2::new(p(rng), p(rng), p(rng));
        if t.det() > 0.5 {
            return t;
        }
    }
}

/// A random point of the closed triangle, as barycentric coordinates.
pub fn random_bary(rng: &mut ChaCha8Rng) -> Bary {
    let (mut a, mut b) = (uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0));
    if a + b > 1.0 {
        a = 1.0 - a;
        b = 1.0 - b;
    }
    [a, b, 1.0 - a - b]
}

/// A random unit vector of the plane.
pub fn random_dir(rng: &mut ChaCha8Rng) -> Vector2<f64> {
    let a = uniform(rng, 0.0, std::f64::consts::TAU);
    Vector2::new(a.cos(), a.sin())
}

/// |a − b| ≤ tol · max(1, |a|, |b|): a relative comparison that is absolute near zero.
pub fn near(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}

/// Asserts [`near`] with a readable message.
#[macro_export]
macro_rules! assert_near {
    ($a:expr, $b:expr, $tol:expr) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        assert!(
            $crate::test_util::near(a, b, tol),
            "{} = {a:e} differs from {} = {b:e} by {:e} (tol {tol:e})",
            stringify!($a),
            stringify!($b),
            (a - b).abs()
        );
    }};
    ($a:expr, $b:expr, $tol:expr, $($msg:tt)+) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        assert!(
            $crate::test_util::near(a, b, tol),
            "{} = {a:e} differs from {} = {b:e} by {:e} (tol {tol:e}): {}",
            stringify!($a),
            stringify!($b),
            (a - b).abs(),
            format!($($msg)+)
        );
    }};
}
