//! Reproducible noise on control points, for denoising experiments.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use crate::ups::Ups;
use crate::vector::Vector;

/// The distribution of the perturbation of each coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoiseKind {
    /// Uniform on [−A, A] (the thesis' experiment).
    Uniform,
    /// Normal with standard deviation A.
    Gaussian,
}

/// Perturbs every coordinate of every value independently by noise of amplitude `amplitude`,
/// drawn from a generator seeded with `seed` (same seed and order, same noise). Coordinates
/// may overflow to infinity for absurd amplitudes: callers check the result.
pub fn perturb<'a, V: Vector>(
    values: impl Iterator<Item = &'a mut V>,
    amplitude: f64,
    kind: NoiseKind,
    seed: u64,
) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let a = amplitude.abs();
    let normal = Normal::new(0.0, a).expect("finite standard deviation");
    let mut coords = vec![0.0; V::DIM];
    for v in values {
        for (k, x) in coords.iter_mut().enumerate() {
            let delta = match kind {
                // For a width 2A beyond the largest double, scale a draw from [−1, 1].
                NoiseKind::Uniform if (2.0 * a).is_finite() => rng.random_range(-a..=a),
                NoiseKind::Uniform => rng.random_range(-1.0..=1.0) * a,
                NoiseKind::Gaussian => normal.sample(&mut rng),
            };
            *x = v.coord(k) + delta;
        }
        *v = V::from_coords(&coords);
    }
}

impl<V: Vector + Default> Ups<V> {
    /// The spline with every coordinate of every control value of a real vertex perturbed
    /// (see [`perturb`]).
    pub fn with_noise(&self, amplitude: f64, kind: NoiseKind, seed: u64) -> Ups<V> {
        let mut out = self.clone();
        let slots = out.grid().real_slots();
        let blocks = out.blocks_mut();
        let mut values: Vec<V> = slots.iter().flat_map(|&s| blocks[s]).collect();
        perturb(values.iter_mut(), amplitude, kind, seed);
        for (k, &s) in slots.iter().enumerate() {
            blocks[s] = [values[3 * k], values[3 * k + 1], values[3 * k + 2]];
        }
        out
    }
}
