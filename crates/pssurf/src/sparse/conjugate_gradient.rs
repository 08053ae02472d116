//! The preconditioned conjugate gradient method for sparse symmetric positive definite
//! systems over three values per vertex that are well conditioned (a ridge on the diagonal,
//! as in fairing with a positive weight): a product with the matrix per step instead of a
//! factorisation whose fill grows faster than the matrix. The preconditioner inverts the
//! matrix's 3 × 3 diagonal blocks ([`BlockJacobi`]).

use nalgebra::Matrix3;
use rayon::prelude::*;

use super::SymmetricBlocks;
use super::symmetric_blocks::{ROWS_PER_TASK, deinterleave, interleave};

/// The block Jacobi preconditioner: the inverses of the 3 × 3 diagonal blocks.
#[derive(Clone, Debug)]
pub struct BlockJacobi {
    inverses: Vec<Matrix3<f64>>,
}

impl BlockJacobi {
    /// The inverses of the diagonal blocks of `a`; `None` when one is not positive definite
    /// (then neither is `a`).
    pub fn new(a: &SymmetricBlocks) -> Option<Self> {
        let inverses: Option<Vec<Matrix3<f64>>> = (0..a.block_order())
            .into_par_iter()
            .with_min_len(ROWS_PER_TASK)
            .map(|k| {
                let d = a.diagonal(k);
                Matrix3::from_fn(|r, c| d[r][c])
                    .cholesky()
                    .map(|l| l.inverse())
            })
            .collect();
        inverses.map(|inverses| BlockJacobi { inverses })
    }

    /// z = M⁻¹ r for `columns` interleaved columns.
    fn apply(&self, r: &[f64], z: &mut [f64], columns: usize) {
        let w = columns;
        z.par_chunks_mut(3 * w)
            .zip(r.par_chunks(3 * w))
            .zip(self.inverses.par_iter())
            .with_min_len(ROWS_PER_TASK)
            .for_each(|((z, r), inv)| {
                for c in 0..w {
                    for a in 0..3 {
                        z[a * w + c] = inv[(a, 0)] * r[c]
                            + inv[(a, 1)] * r[w + c]
                            + inv[(a, 2)] * r[2 * w + c];
                    }
                }
            });
    }
}

/// When to stop iterating.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stopping {
    /// Stop when ‖b − A x‖ ≤ this × ‖b‖.
    pub relative_residual: f64,
    /// Give up after this many steps.
    pub max_steps: usize,
}

/// The result of [`conjugate_gradient`] for one right-hand side.
#[derive(Clone, Debug)]
pub struct Iterated {
    /// The last iterate.
    pub solution: Vec<f64>,
    /// The steps taken.
    pub steps: usize,
    /// ‖b − A x‖ / ‖b‖ at the last iterate (recomputed from A, not the recurrence).
    pub relative_residual: f64,
}

impl Iterated {
    /// Whether the stopping criterion was met.
    pub fn converged(&self, stop: &Stopping) -> bool {
        self.relative_residual <= stop.relative_residual
    }
}

/// Per column, Σ_k a[k] b[k] over interleaved vectors.
fn dots(a: &[f64], b: &[f64], columns: usize) -> Vec<f64> {
    a.par_chunks(columns * 256)
        .zip(b.par_chunks(columns * 256))
        .with_min_len(64)
        .fold(
            || vec![0.0; columns],
            |mut acc, (x, y)| {
                for (k, (x, y)) in x.iter().zip(y).enumerate() {
                    acc[k % columns] += x * y;
                }
                acc
            },
        )
        .reduce(
            || vec![0.0; columns],
            |mut a, b| {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
                a
            },
        )
}

/// Solves A X = B for `columns` right-hand sides stored one after the other in `b`
/// (column-major), from X = 0, by conjugate gradients preconditioned with `m` (Saad,
/// *Iterative methods for sparse linear systems*, Algorithm 9.1): one independent iteration
/// per column, run in lockstep so that each step passes over the matrix once for all of
/// them. A column stops when its residual, recomputed from A (never the drifting
/// recurrence alone), meets the criterion.
pub fn conjugate_gradient(
    a: &SymmetricBlocks,
    m: &BlockJacobi,
    b: &[f64],
    columns: usize,
    stop: &Stopping,
) -> Vec<Iterated> {
    let n = 3 * a.block_order();
    assert_eq!(b.len(), n * columns, "n values per column");
    let w = columns;
    let bi = interleave(b, w);
    let norm_b: Vec<f64> = dots(&bi, &bi, w).into_iter().map(f64::sqrt).collect();
    let target: Vec<f64> = norm_b
        .iter()
        .map(|nb| stop.relative_residual * nb)
        .collect();
    let mut x = vec![0.0; n * w];
    let mut r = bi.clone();
    let mut z = vec![0.0; n * w];
    let mut ap = vec![0.0; n * w];
    m.apply(&r, &mut z, w);
    let mut p = z.clone();
    let mut rz = dots(&r, &z, w);
    // A column is active until it converges or breaks down; a zero column is solved by
    // zero, a non-finite one never.
    let mut active: Vec<bool> = norm_b
        .iter()
        .map(|&nb| nb > 0.0 && nb.is_finite())
        .collect();
    let mut steps = vec![0usize; w];
    let mut step = 0;
    while step < stop.max_steps && active.iter().any(|&a| a) {
        a.multiply_interleaved(&p, &mut ap, w);
        let pap = dots(&p, &ap, w);
        let alpha: Vec<f64> = (0..w)
            .map(|c| {
                if active[c] && pap[c] > 0.0 {
                    rz[c] / pap[c]
                } else {
                    // Converged, or not positive definite along p (or NaN): frozen.
                    active[c] = false;
                    0.0
                }
            })
            .collect();
        update(&mut x, &p, &alpha, 1.0);
        update(&mut r, &ap, &alpha, -1.0);
        step += 1;
        for c in (0..w).filter(|&c| active[c]) {
            steps[c] = step;
        }
        let rr = dots(&r, &r, w);
        if (0..w).any(|c| active[c] && rr[c].sqrt() <= target[c]) {
            // Check against the true residual; where the recurrence drifted, continue from
            // the true residual.
            a.multiply_interleaved(&x, &mut ap, w);
            let true_r: Vec<f64> = bi.iter().zip(&ap).map(|(b, a)| b - a).collect();
            let tr = dots(&true_r, &true_r, w);
            let met: Vec<usize> = (0..w)
                .filter(|&c| active[c] && rr[c].sqrt() <= target[c])
                .collect();
            for c in met {
                if tr[c].sqrt() <= target[c] {
                    active[c] = false;
                } else {
                    for k in 0..n {
                        r[k * w + c] = true_r[k * w + c];
                    }
                }
            }
        }
        m.apply(&r, &mut z, w);
        let rz_next = dots(&r, &z, w);
        let beta: Vec<f64> = (0..w)
            .map(|c| if active[c] { rz_next[c] / rz[c] } else { 0.0 })
            .collect();
        rz = rz_next;
        p.par_chunks_mut(w)
            .zip(z.par_chunks(w))
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(p, z)| {
                for c in 0..w {
                    p[c] = if active[c] {
                        z[c] + beta[c] * p[c]
                    } else {
                        0.0
                    };
                }
            });
    }
    a.multiply_interleaved(&x, &mut ap, w);
    let res: Vec<f64> = {
        let d: Vec<f64> = bi.iter().zip(&ap).map(|(b, a)| b - a).collect();
        dots(&d, &d, w)
    };
    let x = deinterleave(&x, w);
    (0..w)
        .map(|c| Iterated {
            solution: x[c * n..(c + 1) * n].to_vec(),
            steps: steps[c],
            relative_residual: if norm_b[c] == 0.0 {
                0.0
            } else {
                res[c].sqrt() / norm_b[c] // NaN for a non-finite column: not converged
            },
        })
        .collect()
}

/// v += sign × α_c × d per interleaved column c.
fn update(v: &mut [f64], d: &[f64], alpha: &[f64], sign: f64) {
    let w = alpha.len();
    v.par_chunks_mut(w)
        .zip(d.par_chunks(w))
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(v, d)| {
            for c in 0..w {
                v[c] += sign * alpha[c] * d[c];
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sparse::symmetric_blocks::tests::{random_blocks, restricted};
    use crate::test_util::*;
    use nalgebra::DVector;

    #[test]
    fn solves_random_spd_systems_to_the_requested_residual() {
        let stop = Stopping {
            relative_residual: 1e-13,
            max_steps: 1000,
        };
        for seed in 0..5 {
            let n = 40;
            let (q, dense) = random_blocks(n, 30 + seed);
            let keep: Vec<Option<u32>> = (0..n as u32).map(Some).collect();
            let all: Vec<usize> = (0..n).collect();
            let a = SymmetricBlocks::restrict(&q, &keep, 0.2);
            let d = restricted(&dense, &all, 0.2);
            let m = BlockJacobi::new(&a).unwrap();
            let mut r = rng(seed);
            let len = 3 * n;
            // Three right-hand sides, the second zero.
            let b: Vec<f64> = (0..3 * len)
                .map(|k| {
                    if k / len == 1 {
                        0.0
                    } else {
                        uniform(&mut r, -1.0, 1.0)
                    }
                })
                .collect();
            let out = conjugate_gradient(&a, &m, &b, 3, &stop);
            let eig = d.symmetric_eigenvalues();
            let cond = eig.max() / eig.min();
            let llt = d.clone().cholesky().unwrap();
            for (c, col) in out.iter().enumerate() {
                assert!(
                    col.converged(&stop),
                    "seed {seed}: {}",
                    col.relative_residual
                );
                // Against a dense solve, within the condition number's amplification.
                let bc = DVector::from_column_slice(&b[c * len..(c + 1) * len]);
                let x = DVector::from_column_slice(&col.solution);
                assert!((&d * &x - &bc).norm() <= 1e-13 * bc.norm().max(1e-300));
                let exact = llt.solve(&bc);
                let err = (x - &exact).norm();
                assert!(
                    err <= 10.0 * cond * 1e-13 * exact.norm(),
                    "seed {seed}: {err}"
                );
                if c == 1 {
                    assert_eq!((col.steps, col.relative_residual), (0, 0.0));
                    assert!(col.solution.iter().all(|&v| v == 0.0));
                }
            }
        }
    }

    #[test]
    fn a_non_finite_right_hand_side_never_converges() {
        let (q, _) = random_blocks(6, 4);
        let keep: Vec<Option<u32>> = (0..6).map(Some).collect();
        let a = SymmetricBlocks::restrict(&q, &keep, 0.5);
        let m = BlockJacobi::new(&a).unwrap();
        let stop = Stopping {
            relative_residual: 1e-12,
            max_steps: 50,
        };
        for bad in [f64::NAN, f64::INFINITY, 1e300] {
            let mut b = vec![1.0; 2 * 18];
            b[20] = bad;
            let out = conjugate_gradient(&a, &m, &b, 2, &stop);
            assert!(out[0].converged(&stop), "a finite column still converges");
            // 1e300 squares to infinity in the norm: refused like NaN and infinity.
            assert!(
                !out[1].converged(&stop),
                "{bad}: {}",
                out[1].relative_residual
            );
            assert_eq!(out[1].steps, 0);
        }
    }

    #[test]
    fn an_indefinite_diagonal_block_is_refused() {
        let (q, _) = random_blocks(6, 3);
        let keep: Vec<Option<u32>> = (0..6).map(Some).collect();
        assert!(BlockJacobi::new(&SymmetricBlocks::restrict(&q, &keep, 1e-3)).is_some());
        assert!(BlockJacobi::new(&SymmetricBlocks::restrict(&q, &keep, -1e3)).is_none());
    }
}
