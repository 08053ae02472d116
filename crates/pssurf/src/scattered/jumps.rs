//! The least-jump gradient estimator: the gradients whose Hermite PS-spline through the
//! values has the least Hessian-jump energy ([`crate::ps::Energy::HessianJumps`], with the jumps at
//! needle and sliver pieces faded: [`PsBasis::faded_jump_energy_matrix`]), found by one
//! sparse solve.
//!
//! With values f_i fixed and gradients g_i free, the control values are c_ij = f_i +
//! g_i · (Q_ij − V_i) (the Hermite map of [`PsBasis::hermite_coefficients`]), so the energy
//! is a quadratic in g: ½ gᵀ A g − bᵀ g + const, with A sparse and symmetric positive
//! semi-definite (2 unknowns per vertex, coupling vertices that share a triangle or an edge
//! of two triangles). The energy vanishes on quadratics, so their exact gradients are a
//! minimiser and quadratics are reproduced. Because every vertex's gradient is coupled to
//! all others, a boundary vertex uses the data beyond its one-sided neighbourhood — where
//! local fits extrapolate. (That pays on smooth data; on rough real elevation data the local
//! estimator is the more accurate, also near the boundary: docs/performance.md.)
//!
//! Vertices too close to others keep their local estimate, and an anchor to it keeps A
//! definite ([`super::anchor`]'s module docs).

use nalgebra::Vector2;

use super::anchor::{ANCHOR, GlobalGradientError, STRONGER_ANCHORS, close_vertices};
use super::local::estimate_gradients;
use crate::ps::PsBasis;
use crate::sparse::{SparseError, SpdPattern};

/// The gradients minimising the Hessian-jump energy of the Hermite PS-spline with these
/// vertex values (module docs).
pub fn estimate_gradients_jumps(
    basis: &PsBasis,
    values: &[f64],
) -> Result<Vec<Vector2<f64>>, GlobalGradientError> {
    let local: Vec<Vector2<f64>> = estimate_gradients(basis.triangulation(), values)?
        .into_iter()
        .map(|(g, _)| g)
        .collect();
    anchored_jump_gradients(basis, values, &local).map(|(g, _)| g)
}

/// [`estimate_gradients_jumps`] with the local estimates that anchor it already known; also
/// returns the anchor used ([`ANCHOR`], or the first of [`STRONGER_ANCHORS`] with which the
/// system could be factorised, or infinity when none could and the result is the local
/// estimate).
pub(super) fn anchored_jump_gradients(
    basis: &PsBasis,
    values: &[f64],
    local: &[Vector2<f64>],
) -> Result<(Vec<Vector2<f64>>, f64), GlobalGradientError> {
    let n = basis.triangulation().vertex_count();
    assert_eq!(values.len(), n, "one value per vertex");
    assert_eq!(local.len(), n, "one local gradient per vertex");
    let q = basis.faded_jump_energy_matrix();
    let hermite: Vec<[[f64; 3]; 3]> = (0..n).map(|i| basis.hermite_map(i)).collect();
    let mut positions = Vec::with_capacity(4 * q.block_count());
    let mut entries = Vec::with_capacity(4 * q.block_count());
    let mut rhs = vec![0.0; 2 * n];
    // For each vertex: where its two diagonal entries are, and its stiffness.
    let mut diagonal = vec![(0, 0, 0.0); n];
    // Vertices whose gradient is the local estimate (a neighbour closer than `CLOSE`): an
    // identity row, and their couplings to the others moved to the right-hand side.
    let fixed = close_vertices(basis);
    for (i, j, block) in q.blocks() {
        // The block in Hermite unknowns (f, g_x, g_y): Tᵢᵀ B Tⱼ.
        let h = congruence(&hermite[i], block, &hermite[j]);
        for a in 0..2 {
            for b in 0..2 {
                if i != j || b <= a {
                    positions.push((2 * i + a, 2 * j + b));
                    let free = !fixed[i] && !fixed[j];
                    entries.push(if free { h[1 + a][1 + b] } else { 0.0 });
                }
                if i != j && fixed[j] && !fixed[i] {
                    rhs[2 * i + a] -= h[1 + a][1 + b] * local[j][b];
                }
                if i != j && fixed[i] && !fixed[j] {
                    rhs[2 * j + b] -= h[1 + a][1 + b] * local[i][a];
                }
            }
            // The value terms move to the right-hand side (both halves of a symmetric pair).
            if !fixed[i] {
                rhs[2 * i + a] -= h[1 + a][0] * values[j];
            }
            if i != j && !fixed[j] {
                rhs[2 * j + a] -= h[0][1 + a] * values[i];
            }
        }
        if i == j {
            // The diagonal entries of this block are at k − 3 (aa) and k − 1 (bb).
            let k = entries.len();
            diagonal[i] = (k - 3, k - 1, 0.5 * (h[1][1] + h[2][2]));
            if fixed[i] {
                (entries[k - 3], entries[k - 1]) = (1.0, 1.0);
                rhs[2 * i] = local[i].x;
                rhs[2 * i + 1] = local[i].y;
                diagonal[i].2 = 0.0;
            }
        }
    }
    // Minimum degree on the vertex graph: an order as good as on the scalar system, found on
    // a graph with half the nodes and a quarter of the edges.
    let pattern = SpdPattern::with_order(2 * n, &positions, Some(&q.elimination_order(2)?))?;
    for eta in std::iter::once(ANCHOR).chain(STRONGER_ANCHORS) {
        let (mut a, mut b) = (entries.clone(), rhs.clone());
        for (i, &(xx, yy, stiffness)) in diagonal.iter().enumerate() {
            let mu = eta * stiffness;
            a[xx] += mu;
            a[yy] += mu;
            b[2 * i] += mu * local[i].x;
            b[2 * i + 1] += mu * local[i].y;
        }
        match pattern.factor(&a) {
            Ok(llt) => {
                let g = llt.solve(&b);
                let g: Vec<Vector2<f64>> = (0..n)
                    .map(|i| Vector2::new(g[2 * i], g[2 * i + 1]))
                    .collect();
                if local_is_least_energy(&q, &hermite, values, local, &g) {
                    return Ok((local.to_vec(), eta));
                }
                return Ok((g, eta));
            }
            Err(SparseError::NotPositiveDefinite) => continue,
            Err(e) => return Err(e.into()),
        }
    }
    // Rounding swamps even the strongest anchor (measured on clusters of points 1e-8 apart
    // among others 1e4 away): the anchor's limit, the local estimate itself.
    Ok((local.to_vec(), f64::INFINITY))
}

/// Whether the local estimate has no more energy than the solution `global`, to rounding:
/// then it is itself a minimiser (the global solution minimises the energy plus the anchor,
/// which vanishes at the local estimate, so its energy is never larger in exact arithmetic),
/// and the one the anchor selects. Where the energy leaves gradients free (a single
/// triangle: quadratics through three values), the solve only multiplies rounding by
/// 1 / [`ANCHOR`]: linear data on 3 points came out 2.7e-9 off, quadratics on 6 points 1.5e-10,
/// where the local estimate is exact.
fn local_is_least_energy(
    q: &crate::sparse::Block3Matrix,
    hermite: &[[[f64; 3]; 3]],
    values: &[f64],
    local: &[Vector2<f64>],
    global: &[Vector2<f64>],
) -> bool {
    let control = |g: &[Vector2<f64>]| -> Vec<[f64; 3]> {
        (0..values.len())
            .map(|i| {
                let h = &hermite[i];
                std::array::from_fn(|j| h[j][0] * values[i] + h[j][1] * g[i].x + h[j][2] * g[i].y)
            })
            .collect()
    };
    let (at_local, at_global) = (control(local), control(global));
    let rounding = 64.0
        * f64::EPSILON
        * q.abs_quadratic_form(&at_local)
            .max(q.abs_quadratic_form(&at_global));
    q.quadratic_form(&at_local) <= q.quadratic_form(&at_global) + rounding
}

/// Tᵢᵀ B Tⱼ.
fn congruence(ti: &[[f64; 3]; 3], b: &[[f64; 3]; 3], tj: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut bt = [[0.0; 3]; 3];
    for r in 0..3 {
        for c in 0..3 {
            bt[r][c] = (0..3).map(|k| b[r][k] * tj[k][c]).sum();
        }
    }
    std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| ti[k][r] * bt[k][c]).sum()))
}
