//! Sparse symmetric positive definite systems, assembled from element contributions and
//! solved by faer's sparse Cholesky factorisation (AMD ordering, supernodal when it pays).
//!
//! A [`SpdPattern`] is made once from the positions of the entries; it holds the symbolic
//! factorisation, so systems with the same pattern and new values (the smoothing fit tries
//! many λ) are factorised numerically only.
//!
//! A [`SymmetricBlocks`] matrix (3 × 3 blocks, both triangles, in block rows) is the system
//! restricted to some vertices, e.g. fairing's interior; well-conditioned ones are solved by
//! block-Jacobi preconditioned [`conjugate_gradient`]s, the others by Cholesky.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{Conj, Mat, Side};
use thiserror::Error;

mod block2;
mod conjugate_gradient;
mod symmetric_blocks;
pub use block2::{Block2Matrix, Block2Stopping};
pub use conjugate_gradient::{BlockJacobi, Iterated, Stopping, conjugate_gradient};
pub use symmetric_blocks::SymmetricBlocks;

/// A sparse solve failed.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SparseError {
    /// The matrix is not (numerically) positive definite.
    #[error("the system is not positive definite (singular or indefinite)")]
    NotPositiveDefinite,
    /// The factorisation did not fit in memory.
    #[error("the sparse factorisation ran out of memory")]
    OutOfMemory,
}

/// The sparsity pattern of a symmetric matrix of order `n`, from the positions of its
/// lower-triangle entries (row ≥ column; repeated positions are summed), with its symbolic
/// Cholesky factorisation.
pub struct SpdPattern {
    n: usize,
    entries: usize,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    cholesky: Arc<SymbolicCholesky<usize>>,
}

impl SpdPattern {
    /// The pattern of the entries at `positions` (row, column), row ≥ column, eliminated in
    /// the approximate-minimum-degree order.
    pub fn new(n: usize, positions: &[(usize, usize)]) -> Result<Self, SparseError> {
        Self::with_order(n, positions, None)
    }

    /// [`new`](Self::new), eliminating the unknowns in `order` when given (a permutation
    /// of 0..n, `order[k]` eliminated k-th; e.g. [`Block3Matrix::elimination_order`]).
    pub fn with_order(
        n: usize,
        positions: &[(usize, usize)],
        order: Option<&[usize]>,
    ) -> Result<Self, SparseError> {
        let pairs: Vec<Pair<usize, usize>> = positions
            .iter()
            .map(|&(row, col)| {
                debug_assert!(row >= col && row < n, "lower-triangle position");
                Pair { row, col }
            })
            .collect();
        let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|_| SparseError::OutOfMemory)?;
        let inverse = order.map(|order| inverse_permutation(order, n));
        let ordering = match (order, &inverse) {
            (Some(forward), Some(inverse)) => {
                SymmetricOrdering::Custom(PermRef::new_checked(forward, inverse, n))
            }
            _ => SymmetricOrdering::Amd,
        };
        let cholesky = factorize_symbolic_cholesky(
            symbolic.as_ref(),
            Side::Lower,
            ordering,
            Default::default(),
        )
        .map_err(|_| SparseError::OutOfMemory)?;
        Ok(SpdPattern {
            n,
            entries: positions.len(),
            symbolic,
            argsort,
            cholesky: Arc::new(cholesky),
        })
    }

    /// The order of the matrix.
    pub fn order(&self) -> usize {
        self.n
    }

    /// The number of entries of the Cholesky factor.
    pub fn factor_entries(&self) -> usize {
        self.cholesky.len_val()
    }

    /// Factorises the matrix whose entries at the pattern's positions are `values` (in the
    /// order the positions were given).
    pub fn factor(&self, values: &[f64]) -> Result<Cholesky, SparseError> {
        assert_eq!(values.len(), self.entries, "one value per position");
        let matrix = SparseColMat::new_from_argsort(self.symbolic.clone(), &self.argsort, values)
            .map_err(|_| SparseError::OutOfMemory)?;
        let mut factor = Vec::new();
        factor
            .try_reserve_exact(self.cholesky.len_val())
            .map_err(|_| SparseError::OutOfMemory)?;
        factor.resize(self.cholesky.len_val(), 0.0);
        let par = faer::get_global_parallelism();
        let scratch = self
            .cholesky
            .factorize_numeric_llt_scratch::<f64>(par, Default::default());
        let mut memory = MemBuffer::try_new(scratch).map_err(|_| SparseError::OutOfMemory)?;
        self.cholesky
            .factorize_numeric_llt(
                &mut factor,
                matrix.as_ref(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut memory),
                Default::default(),
            )
            // Its only error is a pivot that is not positive.
            .map_err(|_| SparseError::NotPositiveDefinite)?;
        Ok(Cholesky {
            n: self.n,
            symbolic: Arc::clone(&self.cholesky),
            factor,
        })
    }
}

/// The inverse of the permutation `order` of 0..n.
fn inverse_permutation(order: &[usize], n: usize) -> Vec<usize> {
    assert_eq!(order.len(), n, "an order of all unknowns");
    let mut inverse = vec![usize::MAX; n];
    for (k, &i) in order.iter().enumerate() {
        assert!(
            i < n && inverse[i] == usize::MAX,
            "the order is a permutation"
        );
        inverse[i] = k;
    }
    inverse
}

/// The Cholesky factorisation L Lᵀ of a sparse SPD matrix.
pub struct Cholesky {
    n: usize,
    symbolic: Arc<SymbolicCholesky<usize>>,
    factor: Vec<f64>,
}

impl Cholesky {
    /// The solution x of A x = b.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        self.solve_many(b, 1)
    }

    /// The solutions of A X = B for `columns` right-hand sides stored one after the other
    /// in `b` (column-major), returned the same way.
    pub fn solve_many(&self, b: &[f64], columns: usize) -> Vec<f64> {
        assert_eq!(b.len(), self.n * columns, "n values per right-hand side");
        let mut x = Mat::from_fn(self.n, columns, |i, j| b[j * self.n + i]);
        let par = faer::get_global_parallelism();
        let scratch = self.symbolic.solve_in_place_scratch::<f64>(columns, par);
        let mut memory = MemBuffer::new(scratch);
        LltRef::new(&self.symbolic, &self.factor).solve_in_place_with_conj(
            Conj::No,
            x.as_mut(),
            par,
            MemStack::new(&mut memory),
        );
        (0..columns)
            .flat_map(|j| (0..self.n).map(move |i| (j, i)))
            .map(|(j, i)| x[(i, j)])
            .collect()
    }
}

/// The largest number of vertices of one element of a [`Block3Matrix`].
pub const MAX_ELEMENT_VERTICES: usize = 4;

/// The local matrix of one element: rows and columns 3k + j for the element's vertex k and
/// control value j (only the leading 3 × vertices rows and columns are used).
pub type ElementMatrix = [[f64; 3 * MAX_ELEMENT_VERTICES]; 3 * MAX_ELEMENT_VERTICES];

/// A symmetric matrix over three values per vertex (the control values of a PS-spline),
/// stored as the 3 × 3 blocks (i, j), i ≥ j, of the vertex pairs that share an element.
#[derive(Clone, Debug)]
pub struct Block3Matrix {
    /// Row i's blocks are `start[i]..start[i + 1]`.
    start: Vec<usize>,
    /// Their columns j ≤ i, increasing.
    cols: Vec<u32>,
    blocks: Vec<[[f64; 3]; 3]>,
}

impl Block3Matrix {
    /// The zero matrix whose row i may couple vertex i with the vertices `coupled(i)` (any
    /// order, repeats allowed; those above i and i itself are handled).
    pub fn with_pattern(n: usize, coupled: impl Fn(usize, &mut Vec<u32>) + Sync) -> Self {
        use rayon::prelude::*;
        const CHUNK: usize = 1024;
        // Per chunk of rows: their columns one after the other, and each row's count.
        let chunks: Vec<(Vec<u32>, Vec<usize>)> = (0..n.div_ceil(CHUNK))
            .into_par_iter()
            .map(|k| {
                let mut work = Vec::new();
                let mut cols = Vec::new();
                let mut lens = Vec::new();
                for i in k * CHUNK..((k + 1) * CHUNK).min(n) {
                    work.clear();
                    coupled(i, &mut work);
                    work.push(i as u32);
                    work.retain(|&j| j as usize <= i);
                    work.sort_unstable();
                    work.dedup();
                    cols.extend_from_slice(&work);
                    lens.push(work.len());
                }
                (cols, lens)
            })
            .collect();
        let mut start = Vec::with_capacity(n + 1);
        start.push(0);
        for len in chunks.iter().flat_map(|(_, lens)| lens) {
            start.push(start.last().unwrap() + len);
        }
        let mut cols = Vec::with_capacity(start[n]);
        for (c, _) in &chunks {
            cols.extend_from_slice(c);
        }
        let blocks = vec![[[0.0; 3]; 3]; cols.len()];
        Block3Matrix {
            start,
            cols,
            blocks,
        }
    }

    /// The zero matrix with the same pattern.
    pub fn zeroed(&self) -> Self {
        Block3Matrix {
            start: self.start.clone(),
            cols: self.cols.clone(),
            blocks: vec![[[0.0; 3]; 3]; self.blocks.len()],
        }
    }

    /// The number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.start.len() - 1
    }

    /// The number of stored blocks.
    pub fn block_count(&self) -> usize {
        self.cols.len()
    }

    fn slot(&self, i: usize, j: usize) -> usize {
        slot_of(&self.start, &self.cols, i, j)
    }

    /// Adds the local matrix `m` of an element with these vertices (distinct, at most
    /// [`MAX_ELEMENT_VERTICES`], pairwise coupled in the pattern).
    pub fn add_element(&mut self, vertices: &[usize], m: &ElementMatrix) {
        for_each_block(vertices, m, |i, j, block| {
            let slot = self.slot(i, j);
            add_block(&mut self.blocks[slot], &block);
        });
    }

    /// Adds elements in parallel, without copies of the matrix: the rows are cut into
    /// consecutive ranges of about `rows_per_range` vertices, and `elements(range, add)`
    /// must pass to `add` the elements of that range of vertices (each element of the
    /// matrix in exactly one range; for locality, those whose smallest vertex is in it).
    /// Each range writes its own rows in place; the blocks an element has in other ranges'
    /// rows are set aside and added afterwards. Element matrices are read like
    /// [`add_element`](Self::add_element)'s.
    pub fn add_elements_by_range<F>(&mut self, rows_per_range: usize, elements: F)
    where
        F: Fn(std::ops::Range<usize>, &mut dyn FnMut(&[usize], &ElementMatrix)) + Sync,
    {
        use rayon::prelude::*;
        let n = self.vertex_count();
        let per = rows_per_range.max(1);
        let Block3Matrix {
            start,
            cols,
            blocks,
        } = self;
        let (start, cols) = (&*start, &*cols);
        // The blocks of each range's rows, as disjoint mutable slices.
        let mut slices = Vec::with_capacity(n.div_ceil(per));
        let mut rest: &mut [[[f64; 3]; 3]] = blocks;
        for first in (0..n).step_by(per) {
            let last = (first + per).min(n);
            let (mine, tail) = rest.split_at_mut(start[last] - start[first]);
            slices.push((first..last, mine));
            rest = tail;
        }
        let foreign: Vec<Vec<(usize, [[f64; 3]; 3])>> = slices
            .into_par_iter()
            .map(|(range, mine)| {
                let offset = start[range.start];
                let mut set_aside = Vec::new();
                let mut add = |vertices: &[usize], m: &ElementMatrix| {
                    for_each_block(vertices, m, |i, j, block| {
                        let slot = slot_of(start, cols, i, j);
                        if range.contains(&i) {
                            add_block(&mut mine[slot - offset], &block);
                        } else {
                            set_aside.push((slot, block));
                        }
                    });
                };
                elements(range.clone(), &mut add);
                set_aside
            })
            .collect();
        for (slot, block) in foreign.into_iter().flatten() {
            add_block(&mut blocks[slot], &block);
        }
    }

    /// A fill-reducing elimination order of a system with `per_vertex` unknowns per vertex
    /// (numbered `per_vertex × i + k`) coupled like this matrix's vertices: the approximate
    /// minimum degree order of the vertex graph, each vertex's unknowns together. Of
    /// essentially the same quality as minimum degree on the scalar system (a vertex's
    /// unknowns are indistinguishable there), found on a graph with `per_vertex` times fewer
    /// nodes and `per_vertex²` times fewer edges.
    pub fn elimination_order(&self, per_vertex: usize) -> Result<Vec<usize>, SparseError> {
        let n = self.vertex_count();
        // Row i's columns j ≤ i, sorted: column i of the upper triangle in CSC.
        let rows: Vec<usize> = self.cols.iter().map(|&j| j as usize).collect();
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &self.start, None, &rows);
        let mut forward = vec![0usize; n];
        let mut inverse = vec![0usize; n];
        let mut memory = MemBuffer::try_new(amd::order_scratch::<usize>(n, self.cols.len()))
            .map_err(|_| SparseError::OutOfMemory)?;
        amd::order(
            &mut forward,
            &mut inverse,
            pattern,
            Default::default(),
            MemStack::new(&mut memory),
        )
        .map_err(|_| SparseError::OutOfMemory)?;
        Ok(forward
            .iter()
            .flat_map(|&v| (0..per_vertex).map(move |k| per_vertex * v + k))
            .collect())
    }

    /// Adds `d` to the diagonal entry of value `j` of vertex `i`.
    pub fn add_diagonal(&mut self, i: usize, j: usize, d: f64) {
        let slot = self.slot(i, i);
        self.blocks[slot][j][j] += d;
    }

    /// The stored blocks as (i, j, block), i ≥ j; the block (j, i) is the transpose.
    pub fn blocks(&self) -> impl Iterator<Item = (usize, usize, &[[f64; 3]; 3])> + '_ {
        (0..self.vertex_count()).flat_map(move |i| {
            (self.start[i]..self.start[i + 1])
                .map(move |k| (i, self.cols[k] as usize, &self.blocks[k]))
        })
    }

    /// The product y = M x, with x and y holding three values per vertex.
    pub fn multiply(&self, x: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut y = vec![[0.0; 3]; self.vertex_count()];
        for (i, j, b) in self.blocks() {
            for r in 0..3 {
                for c in 0..3 {
                    y[i][r] += b[r][c] * x[j][c];
                    if i != j {
                        y[j][c] += b[r][c] * x[i][r];
                    }
                }
            }
        }
        y
    }

    /// The quadratic form xᵀ M x.
    pub fn quadratic_form(&self, x: &[[f64; 3]]) -> f64 {
        let y = self.multiply(x);
        x.iter()
            .zip(&y)
            .map(|(a, b)| a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
            .sum()
    }

    /// Σ |x_i|ᵀ |M_ij| |x_j|: the size of the terms of xᵀ M x, which bounds its rounding.
    pub fn abs_quadratic_form(&self, x: &[[f64; 3]]) -> f64 {
        let mut sum = 0.0;
        for (i, j, b) in self.blocks() {
            let mut term = 0.0;
            for r in 0..3 {
                for c in 0..3 {
                    term += (x[i][r] * b[r][c] * x[j][c]).abs();
                }
            }
            sum += if i == j { term } else { 2.0 * term };
        }
        sum
    }

    /// The matrix's lower-triangle entries in scalar numbering (3i + r, 3j + c), for
    /// [`SpdPattern`].
    pub fn lower_entries(&self) -> (Vec<(usize, usize)>, Vec<f64>) {
        let mut pos = Vec::with_capacity(9 * self.block_count());
        let mut val = Vec::with_capacity(9 * self.block_count());
        for (i, j, b) in self.blocks() {
            for r in 0..3 {
                for c in 0..3 {
                    if i != j || c <= r {
                        pos.push((3 * i + r, 3 * j + c));
                        val.push(b[r][c]);
                    }
                }
            }
        }
        (pos, val)
    }
}

/// Where block (i, j), i ≥ j, is stored, given a [`Block3Matrix`]'s row starts and columns.
fn slot_of(start: &[usize], cols: &[u32], i: usize, j: usize) -> usize {
    let row = &cols[start[i]..start[i + 1]];
    let k = row
        .binary_search(&(j as u32))
        .unwrap_or_else(|_| panic!("vertices {i} and {j} are not coupled in the pattern"));
    start[i] + k
}

/// Calls `f(i, j, block)` for the blocks (i, j), i ≥ j, of an element matrix over these
/// vertices.
fn for_each_block(
    vertices: &[usize],
    m: &ElementMatrix,
    mut f: impl FnMut(usize, usize, [[f64; 3]; 3]),
) {
    for (a, &i) in vertices.iter().enumerate() {
        for (b, &j) in vertices.iter().enumerate() {
            if j <= i {
                f(
                    i,
                    j,
                    std::array::from_fn(|r| std::array::from_fn(|c| m[3 * a + r][3 * b + c])),
                );
            }
        }
    }
}

/// `target += block`.
fn add_block(target: &mut [[f64; 3]; 3], block: &[[f64; 3]; 3]) {
    for r in 0..3 {
        for c in 0..3 {
            target[r][c] += block[r][c];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::*;

    /// `count` elements over random sets of up to four of `n` vertices, each with a random
    /// symmetric matrix (entries uniform in [−1, 1]).
    fn random_symmetric_elements(
        r: &mut rand_chacha::ChaCha8Rng,
        n: usize,
        count: usize,
    ) -> Vec<(Vec<usize>, ElementMatrix)> {
        (0..count)
            .map(|_| {
                let mut v: Vec<usize> = (0..4)
                    .map(|_| (uniform(r, 0.0, n as f64) as usize).min(n - 1))
                    .collect();
                v.sort_unstable();
                v.dedup();
                let k = 3 * v.len();
                let mut m: ElementMatrix = [[0.0; 12]; 12];
                for a in 0..k {
                    for b in 0..=a {
                        let x = uniform(r, -1.0, 1.0);
                        m[a][b] = x;
                        m[b][a] = x;
                    }
                }
                (v, m)
            })
            .collect()
    }

    #[test]
    fn solves_a_random_spd_system_to_rounding() {
        let mut r = rng(90);
        let n = 60;
        // A = Σ over random "elements" of vvᵀ on 3 indices, plus the identity.
        let mut dense = nalgebra::DMatrix::<f64>::identity(n, n);
        let mut pos = Vec::new();
        let mut val = Vec::new();
        for i in 0..n {
            pos.push((i, i));
            val.push(1.0);
        }
        for _ in 0..200 {
            let idx: [usize; 3] =
                std::array::from_fn(|_| (uniform(&mut r, 0.0, n as f64) as usize).min(n - 1));
            let v: [f64; 3] = std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0));
            for a in 0..3 {
                for b in 0..3 {
                    let (i, j) = (idx[a], idx[b]);
                    dense[(i, j)] += v[a] * v[b];
                    if i >= j {
                        pos.push((i, j));
                        val.push(v[a] * v[b]);
                    }
                }
            }
        }
        let b: Vec<f64> = (0..2 * n).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
        let pattern = SpdPattern::new(n, &pos).unwrap();
        let x = pattern.factor(&val).unwrap().solve_many(&b, 2);
        for col in 0..2 {
            let xs = nalgebra::DVector::from_column_slice(&x[col * n..(col + 1) * n]);
            let bs = nalgebra::DVector::from_column_slice(&b[col * n..(col + 1) * n]);
            let res = (&dense * &xs - &bs).norm();
            assert!(res < 1e-12 * bs.norm() * 10.0, "residual {res}");
        }
        // Negative definite: refused.
        let neg: Vec<f64> = val.iter().map(|v| -v).collect();
        assert_eq!(
            pattern.factor(&neg).err(),
            Some(SparseError::NotPositiveDefinite)
        );
    }

    #[test]
    fn block_matrices_multiply_and_flatten_like_their_dense_form() {
        let mut r = rng(141);
        let n = 12;
        let elements = random_symmetric_elements(&mut r, n, 30);
        let mut m = Block3Matrix::with_pattern(n, |i, out| {
            for (e, _) in &elements {
                if e.contains(&i) {
                    out.extend(e.iter().map(|&v| v as u32));
                }
            }
        });
        let mut dense = nalgebra::DMatrix::<f64>::zeros(3 * n, 3 * n);
        for (e, local) in &elements {
            m.add_element(e, local);
            let k = 3 * e.len();
            for a in 0..k {
                for b in 0..k {
                    dense[(3 * e[a / 3] + a % 3, 3 * e[b / 3] + b % 3)] += local[a][b];
                }
            }
        }
        let x: Vec<[f64; 3]> = (0..n)
            .map(|_| std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0)))
            .collect();
        let xv = nalgebra::DVector::from_iterator(3 * n, x.iter().flatten().copied());
        let y = m.multiply(&x);
        let yd = &dense * &xv;
        for i in 0..3 * n {
            assert!((y[i / 3][i % 3] - yd[i]).abs() < 1e-13, "{i}");
        }
        assert!((m.quadratic_form(&x) - xv.dot(&yd)).abs() < 1e-12);
        let (pos, val) = m.lower_entries();
        let mut rebuilt = nalgebra::DMatrix::<f64>::zeros(3 * n, 3 * n);
        for (&(i, j), v) in pos.iter().zip(&val) {
            assert!(i >= j);
            rebuilt[(i, j)] += v;
            if i != j {
                rebuilt[(j, i)] += v;
            }
        }
        assert!((rebuilt - dense).abs().max() < 1e-13);
    }

    #[test]
    fn elements_added_by_range_equal_those_added_one_by_one() {
        let mut r = rng(142);
        let n = 40;
        let elements = random_symmetric_elements(&mut r, n, 150);
        let pattern = Block3Matrix::with_pattern(n, |i, out| {
            for (e, _) in &elements {
                if e.contains(&i) {
                    out.extend(e.iter().map(|&v| v as u32));
                }
            }
        });
        let mut one_by_one = pattern.zeroed();
        for (v, m) in &elements {
            one_by_one.add_element(v, m);
        }
        // Ranges of 1, 3 and 7 rows: most elements have blocks in other ranges' rows.
        for per in [1, 3, 7, n] {
            let mut by_range = pattern.zeroed();
            by_range.add_elements_by_range(per, |range, add| {
                for (v, m) in &elements {
                    if range.contains(&v[0]) {
                        add(v, m);
                    }
                }
            });
            for ((i, j, a), (_, _, b)) in one_by_one.blocks().zip(by_range.blocks()) {
                for r in 0..3 {
                    for c in 0..3 {
                        assert!((a[r][c] - b[r][c]).abs() < 1e-13, "{per}: ({i}, {j})");
                    }
                }
            }
        }
    }

    #[test]
    fn block_systems_solve_alike_in_their_vertex_elimination_order() {
        let n = 50;
        let (mut m, mut dense) = symmetric_blocks::tests::random_blocks(n, 143);
        // Plus the identity: positive definite.
        for i in 0..n {
            for j in 0..3 {
                m.add_diagonal(i, j, 1.0);
                dense[(3 * i + j, 3 * i + j)] += 1.0;
            }
        }
        let mut r = rng(144);
        let order = m.elimination_order(3).unwrap();
        // A permutation keeping each vertex's three unknowns together.
        let mut seen = vec![false; 3 * n];
        for chunk in order.chunks(3) {
            assert_eq!(chunk[0] % 3, 0);
            assert_eq!(chunk[1..], [chunk[0] + 1, chunk[0] + 2]);
            for &u in chunk {
                assert!(!std::mem::replace(&mut seen[u], true));
            }
        }
        let (pos, val) = m.lower_entries();
        let b: Vec<f64> = (0..3 * n).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
        let x = SpdPattern::with_order(3 * n, &pos, Some(&order))
            .unwrap()
            .factor(&val)
            .unwrap()
            .solve(&b);
        let bs = nalgebra::DVector::from_column_slice(&b);
        let residual = (&dense * nalgebra::DVector::from_column_slice(&x) - &bs).norm();
        assert!(residual < 1e-12 * bs.norm(), "residual {residual}");
        // The order reduces fill about as well as scalar minimum degree, and below no
        // reordering.
        let with_order = SpdPattern::with_order(3 * n, &pos, Some(&order)).unwrap();
        let scalar = SpdPattern::new(3 * n, &pos).unwrap();
        let identity: Vec<usize> = (0..3 * n).collect();
        let none = SpdPattern::with_order(3 * n, &pos, Some(&identity)).unwrap();
        let (a, b, c) = (
            with_order.factor_entries(),
            scalar.factor_entries(),
            none.factor_entries(),
        );
        assert!(
            a as f64 <= 1.2 * b as f64 && a < c,
            "{a} vs {b} (scalar), {c} (none)"
        );
    }
}
