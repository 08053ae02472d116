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
