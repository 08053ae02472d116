//! Sparse symmetric matrices over two unknowns per vertex (a gradient), as 2 × 2 blocks in
//! compressed rows with both triangles, and their solution by block-Jacobi preconditioned
//! conjugate gradients for one right-hand side from a given start.
//!
//! (The 3 × 3 solver of [`super::conjugate_gradient`] runs many right-hand sides in
//! lockstep over interleaved vectors. On the global gradient system of 100k vertices, one
//! column of 2-vectors padded to 3, its steps took about 12 ms against about 2 ms here.)

use nalgebra::{Matrix2, Vector2};
use rayon::prelude::*;

/// Block rows per parallel task.
const ROWS_PER_TASK: usize = 2048;

/// A sparse symmetric matrix of 2 × 2 blocks: row i holds its diagonal block and the
/// off-diagonal blocks (i, j) of its coupled vertices (block (j, i) is stored in row j).
#[derive(Clone, Debug, Default)]
pub struct Block2Matrix {
    start: Vec<usize>,
    cols: Vec<u32>,
    blocks: Vec<Matrix2<f64>>,
    diagonal: Vec<Matrix2<f64>>,
}

/// When [`Block2Matrix::conjugate_gradient`] stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block2Stopping {
    /// Stop when ‖b − A x‖ ≤ this × ‖b‖, or at the residual's rounding floor
    /// ([`Block2Matrix::residual_floor`]) when that is higher.
    pub relative_residual: f64,
    /// Give up after this many steps.
    pub max_steps: usize,
}

impl Block2Matrix {
    /// The matrix of `n` rows made by `row(i, off)`, which pushes row i's off-diagonal
    /// blocks (column, block) to `off` and returns its diagonal block with a value of the
    /// caller's (e.g. the right-hand side's row), returned in row order. The caller keeps the
    /// matrix symmetric.
    pub fn from_rows<T: Send>(
        n: usize,
        row: impl Fn(usize, &mut Vec<(u32, Matrix2<f64>)>) -> (Matrix2<f64>, T) + Sync,
    ) -> (Self, Vec<T>) {
        struct Part<T> {
            off: Vec<(u32, Matrix2<f64>)>,
            lens: Vec<usize>,
            diagonal: Vec<Matrix2<f64>>,
            extra: Vec<T>,
        }
        let parts: Vec<Part<T>> = (0..n.div_ceil(ROWS_PER_TASK))
            .into_par_iter()
            .map(|k| {
                let mut part = Part {
                    off: Vec::new(),
                    lens: Vec::new(),
                    diagonal: Vec::new(),
                    extra: Vec::new(),
                };
                for i in k * ROWS_PER_TASK..((k + 1) * ROWS_PER_TASK).min(n) {
                    let first = part.off.len();
                    let (d, extra) = row(i, &mut part.off);
                    part.lens.push(part.off.len() - first);
                    part.diagonal.push(d);
                    part.extra.push(extra);
                }
                part
            })
            .collect();
        let mut m = Block2Matrix {
            start: vec![0],
            ..Default::default()
        };
        let mut extras = Vec::with_capacity(n);
        for part in parts {
            for len in part.lens {
                m.start.push(m.start[m.start.len() - 1] + len);
            }
            m.cols.extend(part.off.iter().map(|&(j, _)| j));
            m.blocks.extend(part.off.iter().map(|&(_, b)| b));
            m.diagonal.extend(part.diagonal);
            extras.extend(part.extra);
        }
        (m, extras)
    }

    /// The number of block rows.
    pub fn order(&self) -> usize {
        self.diagonal.len()
    }

    /// The diagonal block of row i.
    pub fn diagonal(&self, i: usize) -> Matrix2<f64> {
        self.diagonal[i]
    }

    /// y = (A + diag(shift) ⊗ I₂) x: each row's diagonal block plus `shift[i]` times the
    /// identity.
    pub fn multiply(&self, shift: &[f64], x: &[Vector2<f64>], y: &mut [Vector2<f64>]) {
        y.par_iter_mut()
            .enumerate()
            .with_min_len(ROWS_PER_TASK)
            .for_each(|(i, yi)| {
                let mut sum = self.diagonal[i] * x[i] + shift[i] * x[i];
                for k in self.start[i]..self.start[i + 1] {
                    sum += self.blocks[k] * x[self.cols[k] as usize];
                }
                *yi = sum;
            });
    }

    /// How accurately b − (A + diag(shift)) x can be computed at all: in row i, about ε ×
    /// (the row's terms + 3) × (|b_i| + Σ_j |A_ij| |x_j|), the rounding of the sum of its
    /// terms, as a 2-norm over the rows. (A vertex of degree 20,000 — points on a circle and
    /// their centre, random values — left the residual there above 1e-13 ‖b‖ for good.)
    pub fn residual_floor(&self, shift: &[f64], b: &[Vector2<f64>], x: &[Vector2<f64>]) -> f64 {
        let squares: f64 = (0..b.len())
            .into_par_iter()
            .with_min_len(ROWS_PER_TASK)
            .map(|i| {
                let mut sum =
                    b[i].abs() + self.diagonal[i].abs() * x[i].abs() + shift[i].abs() * x[i].abs();
                for k in self.start[i]..self.start[i + 1] {
                    sum += self.blocks[k].abs() * x[self.cols[k] as usize].abs();
                }
                let terms = (self.start[i + 1] - self.start[i] + 3) as f64;
                (f64::EPSILON * terms * sum).norm_squared()
            })
            .sum();
        squares.sqrt()
    }

    /// The solution of (A + diag(shift)) x = b by conjugate gradients preconditioned with
    /// the inverses of the diagonal blocks (Saad, *Iterative methods for sparse linear
    /// systems*, Algorithm 9.1), from `start`; `None` when a diagonal block or a search
    /// direction shows the matrix not positive definite, a value is not finite, or the
    /// iteration does not converge in `stop.max_steps`. Convergence is checked against the
    /// residual recomputed from A, not the recurrence alone.
    pub fn conjugate_gradient(
        &self,
        shift: &[f64],
        b: &[Vector2<f64>],
        start: Vec<Vector2<f64>>,
        stop: &Block2Stopping,
    ) -> Option<Vec<Vector2<f64>>> {
        let n = self.order();
        assert!(
            shift.len() == n && b.len() == n && start.len() == n,
            "one row each"
        );
        let inverses: Vec<Matrix2<f64>> = (0..n)
            .into_par_iter()
            .with_min_len(ROWS_PER_TASK)
            .map(|i| {
                let d = self.diagonal[i] + Matrix2::identity() * shift[i];
                d.cholesky().map(|l| l.inverse())
            })
            .collect::<Option<_>>()?;
        let norm_b = dot(b, b).sqrt();
        let mut x = start;
        let target = |x: &[Vector2<f64>]| {
            (stop.relative_residual * norm_b).max(self.residual_floor(shift, b, x))
        };
        let mut goal = target(&x);
        let mut q = vec![Vector2::zeros(); n];
        let residual = |x: &[Vector2<f64>], q: &mut [Vector2<f64>]| -> Vec<Vector2<f64>> {
            self.multiply(shift, x, q);
            b.par_iter().zip(q.par_iter()).map(|(b, q)| b - q).collect()
        };
        let mut r = residual(&x, &mut q);
        let rr = dot(&r, &r);
        if !rr.is_finite() {
            return None;
        }
        if rr.sqrt() <= goal {
            return Some(x);
        }
        let precondition = |r: &[Vector2<f64>]| -> Vec<Vector2<f64>> {
            r.par_iter()
                .zip(inverses.par_iter())
                .with_min_len(ROWS_PER_TASK)
                .map(|(r, m)| m * r)
                .collect()
        };
        let mut z = precondition(&r);
        let mut p = z.clone();
        let mut rz = dot(&r, &z);
        for _ in 0..stop.max_steps {
            self.multiply(shift, &p, &mut q);
            let pq = dot(&p, &q);
            if !(pq > 0.0) {
                return None;
            }
            let alpha = rz / pq;
            axpy(&mut x, alpha, &p);
            axpy(&mut r, -alpha, &q);
            if dot(&r, &r).sqrt() <= goal {
                // The recurrence may drift from the true residual: check, and go on from
                // the true one if it is not yet small enough.
                r = residual(&x, &mut q);
                goal = target(&x);
                if dot(&r, &r).sqrt() <= goal {
                    return Some(x);
                }
            }
            z = precondition(&r);
            let rz_next = dot(&r, &z);
            let beta = rz_next / rz;
            rz = rz_next;
            p.par_iter_mut()
                .zip(z.par_iter())
                .with_min_len(ROWS_PER_TASK)
                .for_each(|(p, z)| *p = z + beta * *p);
        }
        None
    }
}

/// Σ aᵢ · bᵢ.
fn dot(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> f64 {
    a.par_iter()
        .zip(b.par_iter())
        .with_min_len(ROWS_PER_TASK)
        .map(|(a, b)| a.dot(b))
        .sum()
}

/// y += α x.
fn axpy(y: &mut [Vector2<f64>], alpha: f64, x: &[Vector2<f64>]) {
    y.par_iter_mut()
        .zip(x.par_iter())
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(y, x)| *y += alpha * x);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{rng, uniform};
    use nalgebra::DMatrix;

    /// A random symmetric system on a random sparse graph: B Bᵀ-like blocks per edge plus a
    /// random positive shift, positive definite by construction; as blocks and dense.
    fn random_system(seed: u64, n: usize) -> (Block2Matrix, DMatrix<f64>, Vec<f64>) {
        let mut r = rng(seed);
        let mut edges: Vec<(usize, usize, Matrix2<f64>, Matrix2<f64>)> = Vec::new();
        for i in 0..n {
            for _ in 0..3 {
                let j = (i + 1 + (uniform(&mut r, 0.0, 1.0) * (n - 1) as f64) as usize) % n;
                if j != i && !edges.iter().any(|e| (e.0, e.1) == (i.min(j), i.max(j))) {
                    // The edge's energy |P xᵢ + Q xⱼ|², P and Q random.
                    let p = Matrix2::from_fn(|_, _| uniform(&mut r, -1.0, 1.0));
                    let q = Matrix2::from_fn(|_, _| uniform(&mut r, -1.0, 1.0));
                    let (a, b) = if i < j { (p, q) } else { (q, p) };
                    edges.push((i.min(j), i.max(j), a, b));
                }
            }
        }
        let mut dense = DMatrix::zeros(2 * n, 2 * n);
        let add = |dense: &mut DMatrix<f64>, i: usize, j: usize, m: Matrix2<f64>| {
            dense
                .view_mut((2 * i, 2 * j), (2, 2))
                .zip_apply(&m, |x, y| *x += y);
        };
        for &(i, j, a, b) in &edges {
            add(&mut dense, i, i, a.transpose() * a);
            add(&mut dense, j, j, b.transpose() * b);
            add(&mut dense, i, j, a.transpose() * b);
            add(&mut dense, j, i, b.transpose() * a);
        }
        let shift: Vec<f64> = (0..n).map(|_| uniform(&mut r, 0.01, 0.1)).collect();
        let (m, _) = Block2Matrix::from_rows(n, |i, off| {
            let mut d = Matrix2::zeros();
            for &(a, b, pa, pb) in &edges {
                if a == i {
                    d += pa.transpose() * pa;
                    off.push((b as u32, pa.transpose() * pb));
                } else if b == i {
                    d += pb.transpose() * pb;
                    off.push((a as u32, pb.transpose() * pa));
                }
            }
            (d, ())
        });
        for (i, s) in shift.iter().enumerate() {
            dense[(2 * i, 2 * i)] += s;
            dense[(2 * i + 1, 2 * i + 1)] += s;
        }
        (m, dense, shift)
    }

    /// Against nalgebra's dense Cholesky solve, from a random start, to 1e-11 relative.
    #[test]
    fn solves_random_spd_block_systems_like_a_dense_factorisation() {
        for seed in 0..6 {
            let n = 50 + 40 * seed as usize;
            let (m, dense, shift) = random_system(400 + seed, n);
            let mut r = rng(500 + seed);
            let b: Vec<Vector2<f64>> = (0..n)
                .map(|_| Vector2::new(uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0)))
                .collect();
            let start: Vec<Vector2<f64>> = (0..n)
                .map(|_| Vector2::new(uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0)))
                .collect();
            let stop = Block2Stopping {
                relative_residual: 1e-14,
                max_steps: 5000,
            };
            let x = m
                .conjugate_gradient(&shift, &b, start, &stop)
                .expect("converges");
            let flat = nalgebra::DVector::from_iterator(2 * n, b.iter().flat_map(|v| [v.x, v.y]));
            let want = dense.clone().cholesky().expect("SPD").solve(&flat);
            let got = nalgebra::DVector::from_iterator(2 * n, x.iter().flat_map(|v| [v.x, v.y]));
            let err = (&got - &want).norm() / want.norm();
            assert!(err < 1e-11, "seed {seed}: {err:e}");
            // The product agrees with the dense one.
            let mut y = vec![Vector2::zeros(); n];
            m.multiply(&shift, &x, &mut y);
            let dense_y = &dense * &got;
            for i in 0..n {
                assert!(
                    (y[i] - Vector2::new(dense_y[2 * i], dense_y[2 * i + 1])).norm()
                        < 1e-12 * (1.0 + y[i].norm())
                );
            }
        }
    }

    /// A negative diagonal block, or NaN in the right-hand side, is reported, not iterated.
    #[test]
    fn indefinite_or_nan_systems_are_refused() {
        let (m, _, mut shift) = random_system(7, 30);
        let b = vec![Vector2::new(1.0, 0.5); 30];
        let stop = Block2Stopping {
            relative_residual: 1e-13,
            max_steps: 100,
        };
        let start = vec![Vector2::zeros(); 30];
        let mut nan = b.clone();
        nan[3].x = f64::NAN;
        assert!(
            m.conjugate_gradient(&shift, &nan, start.clone(), &stop)
                .is_none()
        );
        shift[4] = -1e6;
        assert!(m.conjugate_gradient(&shift, &b, start, &stop).is_none());
    }
}
