//! The preconditioned conjugate gradient method for sparse symmetric positive definite
//! systems over three values per vertex that are well conditioned (a ridge on the diagonal,
//! as in fairing with a positive weight): a product with the matrix per step instead of a
//! factorisation whose fill grows faster than the matrix.
//!
//! The matrix is held as 3 × 3 blocks in compressed block rows with both triangles
//! ([`SymmetricBlocks`]), so that its product with vectors runs in parallel over rows
//! without write conflicts and reads one column index per block; the preconditioner
//! inverts the diagonal blocks ([`BlockJacobi`]).

use nalgebra::Matrix3;
use rayon::prelude::*;

use super::Block3Matrix;

/// Block rows per parallel task in the products.
const ROWS_PER_TASK: usize = 1024;

/// A 3 × 3 block.
type Block = [[f64; 3]; 3];

/// A sparse symmetric matrix of 3 × 3 blocks in compressed block rows, both triangles
/// stored: the system over the three control values of each vertex.
#[derive(Clone, Debug)]
pub struct SymmetricBlocks {
    start: Vec<usize>,
    cols: Vec<u32>,
    blocks: Vec<Block>,
}

impl SymmetricBlocks {
    /// The rows and columns of `q` of the vertices with `keep[i] = Some(k)`, renumbered k
    /// (increasing with i), plus `ridge` on the diagonal.
    pub fn restrict(q: &Block3Matrix, keep: &[Option<u32>], ridge: f64) -> Self {
        assert_eq!(keep.len(), q.vertex_count(), "one entry per vertex");
        let order = keep.iter().flatten().count();
        // Each kept lower block (i, j) goes to row i as it is and to row j transposed.
        let mut count = vec![0usize; order + 1];
        for (i, j, _) in q.blocks() {
            if let (Some(a), Some(b)) = (keep[i], keep[j]) {
                count[a as usize + 1] += 1;
                if a != b {
                    count[b as usize + 1] += 1;
                }
            }
        }
        for k in 0..order {
            count[k + 1] += count[k];
        }
        let mut next = count.clone();
        let total = count[order];
        let mut cols = vec![0u32; total];
        let mut blocks = vec![[[0.0; 3]; 3]; total];
        // Blocks come row by row with increasing columns j ≤ i, so each row receives its
        // lower blocks in order and then (from later rows) its upper blocks in order.
        for (i, j, block) in q.blocks() {
            if let (Some(a), Some(b)) = (keep[i], keep[j]) {
                let (a, b) = (a as usize, b as usize);
                cols[next[a]] = b as u32;
                blocks[next[a]] = *block;
                next[a] += 1;
                if a != b {
                    cols[next[b]] = a as u32;
                    blocks[next[b]] = transpose(block);
                    next[b] += 1;
                }
            }
        }
        let mut m = SymmetricBlocks {
            start: count,
            cols,
            blocks,
        };
        for k in 0..order {
            let d = m.diagonal_mut(k);
            for r in 0..3 {
                d[r][r] += ridge;
            }
        }
        m
    }

    /// The number of block rows (vertices).
    pub fn block_order(&self) -> usize {
        self.start.len() - 1
    }

    /// The number of stored blocks (both triangles).
    pub fn stored(&self) -> usize {
        self.cols.len()
    }

    fn row(&self, i: usize) -> (&[u32], &[Block]) {
        let r = self.start[i]..self.start[i + 1];
        (&self.cols[r.clone()], &self.blocks[r])
    }

    fn diagonal_mut(&mut self, i: usize) -> &mut Block {
        let r = self.start[i]..self.start[i + 1];
        let k = self.cols[r.clone()]
            .binary_search(&(i as u32))
            .expect("every vertex couples with itself");
        &mut self.blocks[r.start + k]
    }

    fn diagonal(&self, i: usize) -> &Block {
        let (c, b) = self.row(i);
        &b[c.binary_search(&(i as u32))
            .expect("every vertex couples with itself")]
    }

    /// The scalar lower-triangle entries (3i + r, 3j + c), for a factorisation.
    pub fn lower_entries(&self) -> (Vec<(usize, usize)>, Vec<f64>) {
        let mut pos = Vec::new();
        let mut val = Vec::new();
        for i in 0..self.block_order() {
            let (cols, blocks) = self.row(i);
            for (&j, b) in cols.iter().zip(blocks) {
                let j = j as usize;
                for r in 0..3 {
                    for c in 0..3 {
                        if 3 * j + c <= 3 * i + r {
                            pos.push((3 * i + r, 3 * j + c));
                            val.push(b[r][c]);
                        }
                    }
                }
            }
        }
        (pos, val)
    }

    /// y = A x for `columns` vectors stored interleaved (value 3i + r of column c at
    /// `(3i + r) * columns + c`), in parallel over block rows: one pass over the matrix for
    /// all columns.
    pub fn multiply_interleaved(&self, x: &[f64], y: &mut [f64], columns: usize) {
        let w = columns;
        let n = 3 * self.block_order();
        assert_eq!(x.len(), n * w, "three values per vertex and column");
        assert_eq!(y.len(), n * w, "three values per vertex and column");
        y.par_chunks_mut(3 * w)
            .with_min_len(ROWS_PER_TASK)
            .enumerate()
            .for_each(|(i, yi)| {
                yi.fill(0.0);
                let (cols, blocks) = self.row(i);
                for (&j, b) in cols.iter().zip(blocks) {
                    let xj = &x[3 * w * j as usize..3 * w * (j as usize + 1)];
                    for r in 0..3 {
                        for c in 0..w {
                            yi[r * w + c] +=
                                b[r][0] * xj[c] + b[r][1] * xj[w + c] + b[r][2] * xj[2 * w + c];
                        }
                    }
                }
            });
    }
}

fn transpose(b: &Block) -> Block {
    std::array::from_fn(|r| std::array::from_fn(|c| b[c][r]))
}

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
    // Interleaved copies: value k of column c at k * w + c.
    let bi: Vec<f64> = (0..n * w).map(|k| b[(k % w) * n + k / w]).collect();
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
    // A column is active until it converges or breaks down.
    let mut active: Vec<bool> = norm_b.iter().map(|&nb| nb > 0.0).collect();
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
            let mut true_r: Vec<f64> = bi.iter().zip(&ap).map(|(b, a)| b - a).collect();
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
            true_r.clear();
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
    (0..w)
        .map(|c| Iterated {
            solution: (0..n).map(|k| x[k * w + c]).collect(),
            steps: steps[c],
            relative_residual: if norm_b[c] > 0.0 {
                res[c].sqrt() / norm_b[c]
            } else {
                0.0
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
    use crate::sparse::ElementMatrix;
    use crate::test_util::*;
    use nalgebra::{DMatrix, DVector};

    /// A random positive semi-definite block matrix over `n` vertices (sums of element
    /// outer products) and its dense form.
    fn random_blocks(n: usize, seed: u64) -> (Block3Matrix, DMatrix<f64>) {
        let mut r = rng(seed);
        let elements: Vec<Vec<usize>> = (0..2 * n)
            .map(|_| {
                let mut v: Vec<usize> = (0..3)
                    .map(|_| (uniform(&mut r, 0.0, n as f64) as usize).min(n - 1))
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            })
            .collect();
        let mut q = Block3Matrix::with_pattern(n, |i, out| {
            for e in elements.iter().filter(|e| e.contains(&i)) {
                out.extend(e.iter().map(|&v| v as u32));
            }
        });
        let mut dense = DMatrix::<f64>::zeros(3 * n, 3 * n);
        for e in &elements {
            let k = 3 * e.len();
            let v: Vec<f64> = (0..k).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
            let mut local: ElementMatrix = [[0.0; 12]; 12];
            for a in 0..k {
                for b in 0..k {
                    local[a][b] = v[a] * v[b];
                    dense[(3 * e[a / 3] + a % 3, 3 * e[b / 3] + b % 3)] += v[a] * v[b];
                }
            }
            q.add_element(e, &local);
        }
        (q, dense)
    }

    /// The dense matrix of the kept vertices plus the ridge.
    fn restricted(dense: &DMatrix<f64>, kept: &[usize], ridge: f64) -> DMatrix<f64> {
        let idx: Vec<usize> = kept
            .iter()
            .flat_map(|&i| (0..3).map(move |r| 3 * i + r))
            .collect();
        DMatrix::from_fn(idx.len(), idx.len(), |a, b| {
            dense[(idx[a], idx[b])] + if a == b { ridge } else { 0.0 }
        })
    }

    #[test]
    fn restricted_blocks_multiply_and_flatten_like_the_dense_matrix() {
        let n = 40;
        let (q, dense) = random_blocks(n, 7);
        // Every third vertex dropped.
        let kept: Vec<usize> = (0..n).filter(|i| i % 3 != 1).collect();
        let mut keep = vec![None; n];
        for (k, &i) in kept.iter().enumerate() {
            keep[i] = Some(k as u32);
        }
        let a = SymmetricBlocks::restrict(&q, &keep, 0.75);
        let d = restricted(&dense, &kept, 0.75);
        let m = d.nrows();
        let mut r = rng(8);
        let x: Vec<f64> = (0..3 * m).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
        let mut y = vec![0.0; 3 * m];
        a.multiply_interleaved(&x, &mut y, 3);
        for c in 0..3 {
            let yd = &d * DVector::from_fn(m, |k, _| x[3 * k + c]);
            for i in 0..m {
                assert!((y[3 * i + c] - yd[i]).abs() < 1e-13, "{c} {i}");
            }
        }
        let (pos, val) = a.lower_entries();
        let mut rebuilt = DMatrix::<f64>::zeros(m, m);
        for (&(i, j), v) in pos.iter().zip(&val) {
            assert!(i >= j);
            rebuilt[(i, j)] += v;
            if i != j {
                rebuilt[(j, i)] += v;
            }
        }
        assert!((rebuilt - d).abs().max() < 1e-13);
    }

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
    fn an_indefinite_diagonal_block_is_refused() {
        let (q, _) = random_blocks(6, 3);
        let keep: Vec<Option<u32>> = (0..6).map(Some).collect();
        assert!(BlockJacobi::new(&SymmetricBlocks::restrict(&q, &keep, 1e-3)).is_some());
        assert!(BlockJacobi::new(&SymmetricBlocks::restrict(&q, &keep, -1e3)).is_none());
    }
}
