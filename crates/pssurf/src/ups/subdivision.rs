//! Subdivision of UPS-splines (thesis section 4.4): the exact representation of a UPS-spline
//! on the refined triangulation D⁻¹Δ, by convex combinations of the control values.

use rayon::prelude::*;

use super::grid::UpsGrid;
use super::spline::Ups;
use crate::ps::net::Combine;

/// The rule (4.24) at an old vertex: c'_k = 2/3 c_k + 1/6 (c_{k+1} + c_{k+2}).
#[inline]
pub fn old_vertex_rule<T: Combine>(c: [T; 3]) -> [T; 3] {
    const A: f64 = 2.0 / 3.0;
    const B: f64 = 1.0 / 6.0;
    [
        T::combine3([A, B, B], [c[0], c[1], c[2]]),
        T::combine3([A, B, B], [c[1], c[2], c[0]]),
        T::combine3([A, B, B], [c[2], c[0], c[1]]),
    ]
}

/// The rule (4.26)–(4.28) at the new vertex W in the middle of the edge V_i V_j, written for
/// V_j = V_i + (B, 0) and turned by `shift` × 120° for the other edge directions (a turn of
/// 120° maps the corner Q_k of t(6) to Q_{k+1}, so control indices shift cyclically):
/// with σ(k) = k + shift (mod 3),
/// c_W,σ(0) = ½ (c_i,σ(1) + c_i,σ(2)),
/// c_W,σ(1) = ½ c_j,σ(0) + ¼ (c_i,σ(1) + c_j,σ(1)),
/// c_W,σ(2) = ½ c_j,σ(0) + ¼ (c_i,σ(2) + c_j,σ(2)).
#[inline]
pub fn new_vertex_rule<T: Combine>(ci: [T; 3], cj: [T; 3], shift: usize) -> [T; 3] {
    let s = |k: usize| (k + shift) % 3;
    let mut out = [ci[0]; 3];
    out[s(0)] = T::combine2([0.5, 0.5], [ci[s(1)], ci[s(2)]]);
    out[s(1)] = T::combine3([0.5, 0.25, 0.25], [cj[s(0)], ci[s(1)], cj[s(1)]]);
    out[s(2)] = T::combine3([0.5, 0.25, 0.25], [cj[s(0)], ci[s(2)], cj[s(2)]]);
    out
}

/// For the new vertex at odd slot parity (I mod 2, J mod 2) ≠ (0, 0): the old slots (i, j)
/// of the edge's endpoints V_i, V_j in the orientation of [`new_vertex_rule`], and the shift.
/// Horizontal edges (odd, even) run left → right (0°, shift 0); edges (even, odd) are taken
/// from the upper to the lower end (240°, shift 2); edges (odd, odd) from (a+1, b) to
/// (a, b+1) (120°, shift 1).
#[inline]
// (i − 1)/2 and (i + 1)/2 name the two neighbours symmetrically; `div_ceil` would hide that.
#[allow(clippy::manual_div_ceil)]
pub fn edge_of_new_vertex(i: usize, j: usize) -> ((usize, usize), (usize, usize), usize) {
    match (i % 2, j % 2) {
        (1, 0) => (((i - 1) / 2, j / 2), ((i + 1) / 2, j / 2), 0),
        (0, 1) => ((i / 2, (j + 1) / 2), (i / 2, (j - 1) / 2), 2),
        (1, 1) => (((i + 1) / 2, (j - 1) / 2), ((i - 1) / 2, (j + 1) / 2), 1),
        _ => unreachable!("even slots are old vertices"),
    }
}

impl<T: Combine + Default> Ups<T> {
    /// One dyadic subdivision step: the same spline on D⁻¹Δ (base B/2), every new control
    /// value a convex combination of old ones ((4.24), (4.26)–(4.28)). Parallel over rows.
    pub fn subdivide(&self) -> Ups<T> {
        let grid = self.grid().refined();
        let old = self.grid();
        let blocks = self.blocks();
        let [n0, _] = grid.dims();
        let mut out = vec![[T::default(); 3]; grid.slots()];
        out.par_chunks_mut(n0).enumerate().for_each(|(j, row)| {
            for (i, slot) in row.iter_mut().enumerate() {
                if !grid.is_real(grid.slot(i, j)) {
                    continue;
                }
                *slot = if i % 2 == 0 && j % 2 == 0 {
                    old_vertex_rule(blocks[old.slot(i / 2, j / 2)])
                } else {
                    let (a, b, shift) = edge_of_new_vertex(i, j);
                    new_vertex_rule(
                        blocks[old.slot(a.0, a.1)],
                        blocks[old.slot(b.0, b.1)],
                        shift,
                    )
                };
            }
        });
        Ups::from_parts(grid, out)
    }

    /// `times` subdivision steps.
    pub fn subdivide_times(&self, times: usize) -> Ups<T> {
        let mut s = self.clone();
        for _ in 0..times {
            s = s.subdivide();
        }
        s
    }
}

/// The refined grid (for callers that only need the triangulation).
pub fn refined_grid(grid: &UpsGrid) -> UpsGrid {
    grid.refined()
}

/// The weights of k-subdivision along a horizontal edge V1 → V2 = V1 + (B, 0) (thesis
/// 4.4.3): the control triple at W_l = ((k − l) V1 + l V2)/k of the spline refined to base
/// B/k is `w[m] · (c1[0], c1[1], c1[2], c2[0], c2[1], c2[2])` for m = 0, 1, 2.
///
/// For l ≤ k/2, (4.37)–(4.39); for l ≥ k/2, (4.40)–(4.42), where the extracted text prints
/// the denominator of the l(l+2) terms as k²: it is 3k² (only then does every row sum to 1
/// and do the two halves agree at l = k/2 and reduce to (4.24) at l = k). All weights are
/// non-negative (convex combinations) for k ≥ 2.
pub fn edge_weights(k: usize, l: usize) -> [[f64; 6]; 3] {
    assert!(k >= 1 && l <= k, "0 ≤ l ≤ k");
    let (k, l) = (k as f64, l as f64);
    let d = 3.0 * k * k;
    if 2.0 * l <= k {
        let a = (k - 2.0 * l) * (k - 2.0 * l + 2.0) / d;
        let b = (k * k + 2.0 * k * l - 5.0 * l * l - k + 5.0 * l) / d;
        let c = 4.0 * l * (l - 1.0) / d;
        let e = l * (l - 1.0) / d;
        let f = (k - 2.0 * l) * (k - 2.0 * l - 1.0) / d;
        let g = (k * k + 2.0 * k * l - 5.0 * l * l + 2.0 * k - 4.0 * l) / d;
        let h = (k * k + 2.0 * k * l - 5.0 * l * l - k - l) / d;
        let i = 2.0 * l * (2.0 * l + 1.0) / d;
        let j = l * (l + 2.0) / d;
        [[a, b, b, c, e, e], [f, g, h, i, j, e], [f, h, g, i, e, j]]
    } else {
        let kk = k * k;
        let a = (l - k - 1.0) * (l - k) / kk;
        let b = (-3.0 * kk - 6.0 * k + 12.0 * k * l + 8.0 * l - 8.0 * l * l) / d;
        let e = l * (l - 1.0) / d;
        let f = (k - l) * (k - l) / kk;
        let g = (k - l) * (k - l - 1.0) / kk;
        let h = (-3.0 * kk + 12.0 * k * l + 3.0 * k - 4.0 * l - 8.0 * l * l) / d;
        let j = l * (l + 2.0) / d;
        [
            [0.0, a, a, b, e, e],
            [0.0, f, g, h, j, e],
            [0.0, g, f, h, e, j],
        ]
    }
}

/// k-subdivision along an edge of Δ: the control triples at the k + 1 points
/// W_l = ((k − l) V1 + l V2)/k of the spline refined to base B/k, from the triples `c1`,
/// `c2` at V1 and V2, where V2 lies in direction `dir` (a [`super::grid::NEIGHBORS`] index)
/// from V1. Convex combinations of the original control values.
pub fn edge_subdivision<T: Combine>(c1: [T; 3], c2: [T; 3], k: usize, dir: usize) -> Vec<[T; 3]> {
    assert!(dir < 6 && k >= 1);
    // Directions 0°, 120°, 240° are the horizontal rule turned by shift × 120°; the others
    // are those edges run backwards.
    if dir % 2 == 1 {
        let mut out = edge_subdivision(c2, c1, k, (dir + 3) % 6);
        out.reverse();
        return out;
    }
    let shift = dir / 2;
    let s = |m: usize| (m + shift) % 3;
    (0..=k)
        .map(|l| {
            let w = edge_weights(k, l);
            let mut out = [c1[0]; 3];
            for m in 0..3 {
                // In the turned frame, value σ(m) of W combines values σ(·) of V1 and V2.
                let pts = [c1[s(0)], c1[s(1)], c1[s(2)], c2[s(0)], c2[s(1)], c2[s(2)]];
                out[s(m)] = T::combine(&w[m], &pts);
            }
            out
        })
        .collect()
}
