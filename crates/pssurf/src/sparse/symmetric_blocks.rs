//! Sparse symmetric matrices over the three control values of each vertex, held as 3 × 3
//! blocks in compressed block rows with both triangles ([`SymmetricBlocks`]): their product
//! with vectors runs in parallel over rows without write conflicts and reads one column index
//! per block. Solved by conjugate gradients (`super::conjugate_gradient`) when well
//! conditioned, or by a sparse Cholesky factorisation.

use rayon::prelude::*;

use super::{Block3Matrix, SparseError, SpdPattern};

/// Block rows per parallel task in the products.
pub(super) const ROWS_PER_TASK: usize = 1024;

/// A 3 × 3 block.
pub(super) type Block = [[f64; 3]; 3];

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

    /// The diagonal block of vertex `i`.
    pub(super) fn diagonal(&self, i: usize) -> &Block {
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

    /// A X for `columns` vectors stored one after the other (column-major).
    pub fn multiply(&self, x: &[f64], columns: usize) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        self.multiply_interleaved(&interleave(x, columns), &mut y, columns);
        deinterleave(&y, columns)
    }

    /// ‖A X − B‖ / ‖B‖ (Frobenius norms) for `columns` vectors stored one after the other.
    pub fn relative_residual(&self, x: &[f64], b: &[f64], columns: usize) -> f64 {
        let norm = |v: &mut dyn Iterator<Item = f64>| v.map(|t| t * t).sum::<f64>().sqrt();
        let ax = self.multiply(x, columns);
        let r = norm(&mut ax.iter().zip(b).map(|(a, b)| a - b));
        r / norm(&mut b.iter().copied()).max(f64::MIN_POSITIVE)
    }

    /// The solutions of A X = B for `columns` right-hand sides stored one after the other,
    /// by a sparse Cholesky factorisation ([`SpdPattern`]) and up to three steps of
    /// iterative refinement with the same factor, until the relative residual is below
    /// 1e-13: an ill-conditioned matrix (an energy without a ridge on a mesh with slivers:
    /// measured 5e-9 after one solve) is brought to rounding.
    pub fn solve_by_cholesky(&self, b: &[f64], columns: usize) -> Result<Vec<f64>, SparseError> {
        let (positions, values) = self.lower_entries();
        let factor = SpdPattern::new(3 * self.block_order(), &positions)?.factor(&values)?;
        let mut x = factor.solve_many(b, columns);
        for _ in 0..3 {
            if self.relative_residual(&x, b, columns) <= 1e-13 {
                break;
            }
            let ax = self.multiply(&x, columns);
            let r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
            for (x, d) in x.iter_mut().zip(factor.solve_many(&r, columns)) {
                *x += d;
            }
        }
        Ok(x)
    }
}

/// Column-major vectors (column c's value k at `c * n + k`) interleaved (at `k * columns + c`).
pub(super) fn interleave(x: &[f64], columns: usize) -> Vec<f64> {
    let n = x.len() / columns;
    (0..x.len())
        .map(|k| x[(k % columns) * n + k / columns])
        .collect()
}

/// The inverse of [`interleave`].
pub(super) fn deinterleave(x: &[f64], columns: usize) -> Vec<f64> {
    let n = x.len() / columns;
    (0..x.len()).map(|k| x[(k % n) * columns + k / n]).collect()
}

fn transpose(b: &Block) -> Block {
    std::array::from_fn(|r| std::array::from_fn(|c| b[c][r]))
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::sparse::ElementMatrix;
    use crate::test_util::*;
    use nalgebra::{DMatrix, DVector};

    /// A random positive semi-definite block matrix over `n` vertices (sums of element
    /// outer products) and its dense form.
    pub(in crate::sparse) fn random_blocks(n: usize, seed: u64) -> (Block3Matrix, DMatrix<f64>) {
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
    pub(in crate::sparse) fn restricted(
        dense: &DMatrix<f64>,
        kept: &[usize],
        ridge: f64,
    ) -> DMatrix<f64> {
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
    fn column_major_products_residuals_and_cholesky_solves_match_the_dense_matrix() {
        let n = 30;
        let (q, dense) = random_blocks(n, 11);
        let keep: Vec<Option<u32>> = (0..n as u32).map(Some).collect();
        let all: Vec<usize> = (0..n).collect();
        let a = SymmetricBlocks::restrict(&q, &keep, 0.3);
        let d = restricted(&dense, &all, 0.3);
        let len = 3 * n;
        let mut r = rng(12);
        let x: Vec<f64> = (0..2 * len).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
        let y = a.multiply(&x, 2);
        for c in 0..2 {
            let yd = &d * DVector::from_column_slice(&x[c * len..(c + 1) * len]);
            for k in 0..len {
                assert!((y[c * len + k] - yd[k]).abs() < 1e-13, "{c} {k}");
            }
        }
        let b = y;
        let solved = a.solve_by_cholesky(&b, 2).unwrap();
        let err = solved
            .iter()
            .zip(&x)
            .map(|(s, t)| (s - t).abs())
            .fold(0.0, f64::max);
        let eig = d.symmetric_eigenvalues();
        assert!(err <= 10.0 * eig.max() / eig.min() * 1e-15, "{err:e}");
        assert!(a.relative_residual(&solved, &b, 2) <= 1e-13);
        // Against a zero right-hand side the residual is relative to the smallest normal.
        assert!(a.relative_residual(&x, &vec![0.0; 2 * len], 2) > 1e300);
        // Interleaving round trips.
        assert_eq!(deinterleave(&interleave(&x, 2), 2), x);
        assert_eq!(interleave(&x, 2)[1], x[len]);
    }
}
