//! Multi-indices λ = (λ1, λ2, λ3), |λ| = m, of a triangular Bézier net and their storage order.
//!
//! The (m + 1)(m + 2)/2 ordinates of a degree-m net are stored row by row, where row
//! r = λ2 + λ3 = m − λ1 runs from 0 (the vertex V1) to m (the edge V2V3), and within a row
//! λ3 increases: `index(λ) = r (r + 1) / 2 + λ3`. For m = 2 the order is
//! b200, b110, b101, b020, b011, b002.

use crate::geometry::Bary;
use crate::vector::Vector;

/// The number of ordinates of a degree-m triangular net, (m + 1)(m + 2) / 2.
#[inline]
pub const fn net_len(m: usize) -> usize {
    (m + 1) * (m + 2) / 2
}

/// The storage position of the multi-index λ (its degree is implied).
#[inline]
pub const fn index(l: [usize; 3]) -> usize {
    let r = l[1] + l[2];
    r * (r + 1) / 2 + l[2]
}

/// All multi-indices of degree m, in storage order.
pub fn multi_indices(m: usize) -> impl Iterator<Item = [usize; 3]> {
    (0..=m).flat_map(move |r| (0..=r).map(move |l3| [m - r, r - l3, l3]))
}

/// One de Casteljau step (2.15) in place: the degree-`deg` net in `net[..net_len(deg)]`
/// becomes the degree-(deg − 1) net of intermediate ordinates in `net[..net_len(deg − 1)]`.
///
/// `t` may be a point (τ) or a direction (d): Theorem 2.3 uses both.
#[inline]
pub fn de_casteljau_step<V: Vector>(net: &mut [V], deg: usize, t: Bary) {
    for r in 0..deg {
        let row = r * (r + 1) / 2;
        let next = row + r + 1;
        for k in 0..=r {
            net[row + k] = net[row + k] * t[0] + net[next + k] * t[1] + net[next + k + 1] * t[2];
        }
    }
}

/// `steps` de Casteljau steps with the same `t`, reducing the degree from `deg` to `deg − steps`.
pub fn de_casteljau_steps<V: Vector>(net: &mut [V], deg: usize, t: Bary, steps: usize) {
    for s in 0..steps {
        de_casteljau_step(net, deg - s, t);
    }
}

/// The Bernstein polynomial B^m_λ(τ) of (2.5) (m = |λ|).
pub fn bernstein(l: [usize; 3], t: Bary) -> f64 {
    let m = l[0] + l[1] + l[2];
    multinomial(m, l) * t[0].powi(l[0] as i32) * t[1].powi(l[1] as i32) * t[2].powi(l[2] as i32)
}

/// The multinomial coefficient m! / (λ1! λ2! λ3!).
pub fn multinomial(m: usize, l: [usize; 3]) -> f64 {
    binomial(m, l[0]) * binomial(m - l[0], l[1])
}

/// The binomial coefficient C(n, k) as a float (exact for the sizes used here).
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut c = 1.0;
    for i in 0..k {
        c = c * (n - i) as f64 / (i + 1) as f64;
    }
    c.round()
}

/// The falling factorial m! / (m − r)!.
pub fn falling_factorial(m: usize, r: usize) -> f64 {
    (0..r).map(|i| (m - i) as f64).product()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_order_is_a_bijection() {
        for m in 0..8 {
            let all: Vec<_> = multi_indices(m).collect();
            assert_eq!(all.len(), net_len(m));
            for (pos, l) in all.iter().enumerate() {
                assert_eq!(l.iter().sum::<usize>(), m);
                assert_eq!(index(*l), pos);
            }
        }
    }

    #[test]
    fn bernstein_polynomials_partition_unity_and_linear_precision() {
        let t = [0.2, 0.45, 0.35];
        for m in 1..9 {
            let sum: f64 = multi_indices(m).map(|l| bernstein(l, t)).sum();
            assert!((sum - 1.0).abs() < 1e-14);
            // (2.10): τ1 = Σ λ1/m B_λ.
            let t1: f64 = multi_indices(m)
                .map(|l| l[0] as f64 / m as f64 * bernstein(l, t))
                .sum();
            assert!((t1 - t[0]).abs() < 1e-14);
        }
    }
}
