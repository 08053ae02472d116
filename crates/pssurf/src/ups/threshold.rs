//! Wavelet thresholding for noise removal (thesis 4.5.6, seed 000 section 4), with automatic
//! threshold choices beyond the thesis.

use super::wavelet::{Decomposition, Update};
use crate::vector::Vector;

/// What happens to the coefficients above the threshold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shrink {
    /// Kept unchanged.
    Hard,
    /// Moved towards zero by the threshold, keeping their sign.
    Soft,
}

/// How the threshold of one level and coordinate is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ThresholdRule {
    /// A fixed value.
    Absolute(f64),
    /// A percentage of the largest |coefficient| of that level and coordinate (the thesis'
    /// choice, e.g. 5 or 10).
    PercentOfMax(f64),
    /// The universal threshold σ √(2 ln n) (Donoho & Johnstone) with the robust noise
    /// estimate σ = median |d| / 0.6745 of the same coefficients.
    Universal,
    /// The minimiser of Stein's unbiased risk estimate for soft thresholding (SureShrink),
    /// with σ estimated as for [`ThresholdRule::Universal`].
    Sure,
    /// The minimiser of generalized cross validation (Jansen, Malfait & Bultheel 1997):
    /// GCV(t) = (1/n)‖d − η_t(d)‖² / (n₀(t)/n)², n₀ the number of zeroed coefficients;
    /// needs no noise estimate.
    Gcv,
}

impl ThresholdRule {
    /// A short name for reports.
    pub fn name(&self) -> String {
        match self {
            ThresholdRule::Absolute(t) => format!("absolute {t}"),
            ThresholdRule::PercentOfMax(p) => format!("{p}% of max"),
            ThresholdRule::Universal => "universal".into(),
            ThresholdRule::Sure => "SURE".into(),
            ThresholdRule::Gcv => "GCV".into(),
        }
    }

    /// The threshold for a set of coefficients, with the noise level estimated from them.
    pub fn threshold(&self, d: &[f64]) -> f64 {
        self.threshold_with_sigma(d, None)
    }

    /// The threshold for a set of coefficients; `sigma` is the noise level for the universal
    /// and SURE rules (estimated from `d` itself when `None`).
    pub fn threshold_with_sigma(&self, d: &[f64], sigma: Option<f64>) -> f64 {
        let noise = || sigma.unwrap_or_else(|| noise_sigma(d));
        match *self {
            ThresholdRule::Absolute(t) => t,
            ThresholdRule::PercentOfMax(p) => {
                p / 100.0 * d.iter().fold(0.0, |m: f64, x| m.max(x.abs()))
            }
            ThresholdRule::Universal => noise() * (2.0 * (d.len().max(1) as f64).ln()).sqrt(),
            ThresholdRule::Sure => sure_threshold_with_sigma(d, noise()),
            ThresholdRule::Gcv => gcv_threshold(d),
        }
    }
}

/// The robust noise estimate σ = median |d| / 0.6745 (the median absolute deviation of
/// coefficients that are mostly noise).
pub fn noise_sigma(d: &[f64]) -> f64 {
    if d.is_empty() {
        return 0.0;
    }
    let mut a: Vec<f64> = d.iter().map(|x| x.abs()).collect();
    let mid = a.len() / 2;
    let (_, m, _) = a.select_nth_unstable_by(mid, f64::total_cmp);
    *m / 0.6745
}

/// SureShrink: the t ∈ {0} ∪ {|d_i|} minimising
/// SURE(t) = n σ² − 2σ² #{|d_i| ≤ t} + Σ min(d_i², t²).
pub fn sure_threshold(d: &[f64]) -> f64 {
    sure_threshold_with_sigma(d, noise_sigma(d))
}

/// [`sure_threshold`] for a known noise level `sigma`.
pub fn sure_threshold_with_sigma(d: &[f64], sigma: f64) -> f64 {
    if d.is_empty() || !(sigma > 0.0) {
        return 0.0;
    }
    let mut a: Vec<f64> = d.iter().map(|x| x * x).collect();
    a.sort_by(f64::total_cmp);
    let n = a.len() as f64;
    let s2 = sigma * sigma;
    // t = 0: nothing is below, nothing is shrunk: SURE = n σ².
    let mut best = (n * s2, 0.0);
    let mut cum = 0.0;
    for (k, &ak) in a.iter().enumerate() {
        cum += ak;
        let below = (k + 1) as f64;
        let risk = n * s2 - 2.0 * s2 * below + cum + (n - below) * ak;
        if risk < best.0 {
            best = (risk, ak.sqrt());
        }
    }
    best.1
}

/// The GCV threshold: the t among the |d_i| minimising (1/n) Σ min(d_i², t²) / (n₀/n)².
/// Only thresholds that zero at least 2% of the coefficients (and at least two) are
/// considered: below that, the ratio is dominated by the sampling fluctuation of the very
/// smallest coefficients (GCV(|d|₍₁₎) = n² d²₍₁₎) rather than by the noise level.
pub fn gcv_threshold(d: &[f64]) -> f64 {
    if d.is_empty() {
        return 0.0;
    }
    let mut a: Vec<f64> = d.iter().map(|x| x * x).collect();
    a.sort_by(f64::total_cmp);
    let n = a.len() as f64;
    let mut best = (f64::INFINITY, 0.0);
    let mut cum = 0.0;
    for (k, &ak) in a.iter().enumerate() {
        cum += ak;
        let zeroed = (k + 1) as f64;
        let residual = (cum + (n - zeroed) * ak) / n;
        let gcv = residual / (zeroed / n).powi(2);
        if (k + 1) * 50 >= a.len() && k >= 1 && gcv < best.0 {
            best = (gcv, ak.sqrt());
        }
    }
    best.1
}

/// The shrinkage of one coefficient.
#[inline]
pub fn shrink(x: f64, t: f64, mode: Shrink) -> f64 {
    if x.abs() < t {
        0.0
    } else {
        match mode {
            Shrink::Hard => x,
            Shrink::Soft => x - t * x.signum(),
        }
    }
}

/// Statistics of one level and coordinate (the table after thesis 4.5.6).
#[derive(Clone, Debug, PartialEq)]
pub struct LevelStats {
    /// The level: 1 is the coarsest detail level, as in the thesis' table.
    pub level: usize,
    /// The coordinate (0 = x, 1 = y, 2 = z; 0 for functional splines).
    pub component: usize,
    /// The number of coefficients.
    pub count: usize,
    /// The largest |coefficient|.
    pub max_abs: f64,
    /// The Euclidean norm of the coefficients.
    pub norm: f64,
    /// The threshold applied (0 when none).
    pub threshold: f64,
    /// How many coefficients the threshold set to zero.
    pub zeroed: usize,
}

impl LevelStats {
    /// The share of coefficients zeroed, in percent.
    pub fn zeroed_percent(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            100.0 * self.zeroed as f64 / self.count as f64
        }
    }
}

impl<V: Vector + Default> Decomposition<V> {
    /// The coefficients of one level (0 = coarsest) and coordinate, in slot order.
    pub fn coefficients(&self, level: usize, component: usize) -> Vec<f64> {
        let l = &self.levels[level];
        l.detail_slots()
            .flat_map(|s| l.details[s].iter().map(move |v| v.coord(component)))
            .collect()
    }

    /// The statistics of every level and coordinate, without changing anything.
    pub fn spectrum(&self) -> Vec<LevelStats> {
        (0..self.levels.len())
            .flat_map(|level| (0..V::DIM).map(move |c| (level, c)))
            .map(|(level, component)| {
                let d = self.coefficients(level, component);
                LevelStats {
                    level: level + 1,
                    component,
                    count: d.len(),
                    max_abs: d.iter().fold(0.0, |m: f64, x| m.max(x.abs())),
                    norm: d.iter().map(|x| x * x).sum::<f64>().sqrt(),
                    threshold: 0.0,
                    zeroed: 0,
                }
            })
            .collect()
    }

    /// Thresholds every level and coordinate with the rule `rule(level, component)` (level
    /// 0 = coarsest) and returns what was done.
    ///
    /// The noise level of the universal and SURE rules: with [`Update::Stable`] the detail
    /// coefficients of white noise have the same spread at every level (1.3–1.6 σ), so σ is
    /// estimated once per coordinate from the finest level, where the signal is weakest — a
    /// coarse level's own median is mostly signal. The thesis' transform doubles the noise
    /// per level, so it keeps the estimate per level.
    pub fn threshold(
        &mut self,
        rule: impl Fn(usize, usize) -> ThresholdRule,
        mode: Shrink,
    ) -> Vec<LevelStats> {
        let sigma: Vec<Option<f64>> = (0..V::DIM)
            .map(|c| match (self.update, self.levels.len().checked_sub(1)) {
                (Update::Stable, Some(finest)) => Some(noise_sigma(&self.coefficients(finest, c))),
                _ => None,
            })
            .collect();
        let mut stats = Vec::new();
        for level in 0..self.levels.len() {
            for component in 0..V::DIM {
                let d = self.coefficients(level, component);
                let t = rule(level, component).threshold_with_sigma(&d, sigma[component]);
                let zeroed = d.iter().filter(|x| x.abs() < t).count();
                stats.push(LevelStats {
                    level: level + 1,
                    component,
                    count: d.len(),
                    max_abs: d.iter().fold(0.0, |m: f64, x| m.max(x.abs())),
                    norm: d.iter().map(|x| x * x).sum::<f64>().sqrt(),
                    threshold: t,
                    zeroed,
                });
                let l = &mut self.levels[level];
                let slots: Vec<usize> = l.detail_slots().collect();
                for s in slots {
                    for v in l.details[s].iter_mut() {
                        let mut coords: Vec<f64> = (0..V::DIM).map(|i| v.coord(i)).collect();
                        coords[component] = shrink(coords[component], t, mode);
                        *v = V::from_coords(&coords);
                    }
                }
            }
        }
        stats
    }
}
