//! Reproducible noise on control points, for denoising experiments.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::spline::Ups;
use crate::vector::Vector;

/// The distribution of the perturbation of each coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoiseKind {
    /// Uniform on [−A, A] (the thesis' experiment).
    Uniform,
    /// Normal with standard deviation A.
    Gaussian,
}

impl<V: Vector + Default> Ups<V> {
    /// The spline with every coordinate of every control value of a real vertex perturbed by
    /// independent noise of amplitude `amplitude`, from the seed `seed` (same seed, same noise).
    pub fn with_noise(&self, amplitude: f64, kind: NoiseKind, seed: u64) -> Ups<V> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, amplitude.abs()).expect("finite standard deviation");
        let mut out = self.clone();
        let slots = out.grid().real_slots();
        let mut coords = vec![0.0; V::DIM];
        for s in slots {
            for c in out.blocks_mut()[s].iter_mut() {
                for (k, x) in coords.iter_mut().enumerate() {
                    let delta = match kind {
                        NoiseKind::Uniform => rng.random_range(-amplitude.abs()..=amplitude.abs()),
                        NoiseKind::Gaussian => normal.sample(&mut rng),
                    };
                    *x = c.coord(k) + delta;
                }
                *c = V::from_coords(&coords);
            }
        }
        out
    }
}
