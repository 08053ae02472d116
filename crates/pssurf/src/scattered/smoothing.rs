//! Least-squares and smoothing PS-splines for noisy or dense data (the thesis' "fitting"
//! future work; Dierckx's smoothing splines on a triangulation).
//!
//! Given N points (p_k, z_k) and a PS basis on a coarser triangulation, the control values
//! c minimise
//!
//! ```text
//!   Σ_k (s(p_k) − z_k)² + λ E(s)
//! ```
//!
//! with E an [`Energy`] of the spline (a quadratic form cᵀQc, exact). With B the N × 3n
//! matrix of the basis functions' values at the points, the normal equations are
//! (BᵀB + λQ) c = Bᵀz: sparse, symmetric positive definite as soon as the data determine
//! the energy's null space (planes for the thin-plate energy, quadratics for the
//! Hessian-jump energy) — vertices with no data nearby are fixed by the energy. λ is given,
//! or chosen by generalised cross-validation (Craven & Wahba 1979):
//!
//! ```text
//!   GCV(λ) = N · RSS(λ) / (N − tr A(λ))²,   A(λ) = B (BᵀB + λQ)⁻¹ Bᵀ,
//! ```
//!
//! where tr A(λ), the effective degrees of freedom, is computed exactly for small bases and
//! by Hutchinson's estimator (random ±1 probes) otherwise.

use std::sync::Arc;

use nalgebra::Point2;
use rayon::prelude::*;

use crate::ps::net::{NET_LEN, SUB_ORDINATES};
use crate::ps::{Energy, PsBasis, PsError, PsSpline, SubLocation};
use crate::sparse::{Block3Matrix, ElementMatrix, SparseError, SpdPattern};

/// How the smoothing parameter λ is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Smoothing {
    /// This λ (≥ 0; 0 is plain least squares).
    Fixed(f64),
    /// The λ minimising the GCV score.
    Gcv,
}

/// A smoothing fit and its statistics.
#[derive(Clone, Debug)]
pub struct SmoothingFit {
    /// The spline.
    pub spline: PsSpline<f64>,
    /// The smoothing parameter used.
    pub lambda: f64,
    /// √(RSS / N), the root-mean-square residual at the data points.
    pub rms_residual: f64,
    /// tr A(λ), the effective number of parameters.
    pub effective_dof: f64,
    /// Whether the trace was estimated (Hutchinson) rather than computed exactly.
    pub dof_estimated: bool,
    /// The GCV score at λ.
    pub gcv: f64,
}

/// Why a smoothing fit failed.
#[derive(Debug, thiserror::Error)]
pub enum SmoothingError {
    /// A data point lies outside the triangulation.
    #[error("data point {0} lies outside the triangulation")]
    Outside(usize),
    /// A value or λ is not finite, or λ < 0.
    #[error("{0}")]
    Invalid(String),
    /// The normal equations are singular (too few data for the energy's null space).
    #[error(
        "the data do not determine the fit (too few points, or all on a line or conic); give more points or a larger λ"
    )]
    Singular,
    /// The sparse solver failed otherwise.
    #[error(transparent)]
    Solve(SparseError),
    /// The spline could not be built.
    #[error(transparent)]
    Ps(#[from] PsError),
    /// The coarse vertices cannot be triangulated.
    #[error(transparent)]
    Triangulation(#[from] crate::triangulation::TriangulationError),
}

impl From<SparseError> for SmoothingError {
    fn from(e: SparseError) -> Self {
        match e {
            SparseError::NotPositiveDefinite => SmoothingError::Singular,
            e => SmoothingError::Solve(e),
        }
    }
}

/// Bases with at most this many control values get the exact trace of A(λ).
const EXACT_TRACE_MAX: usize = 1500;
/// The number of Hutchinson probes otherwise.
const PROBES: usize = 32;

/// The smoothing PS-spline on `basis` of the data (points[k], values[k]) with energy
/// `energy` and smoothing `smoothing` (module docs).
pub fn smoothing_fit(
    basis: Arc<PsBasis>,
    points: &[Point2<f64>],
    values: &[f64],
    energy: Energy,
    smoothing: Smoothing,
) -> Result<SmoothingFit, SmoothingError> {
    if points.len() != values.len() {
        return Err(SmoothingError::Invalid(format!(
            "{} points but {} values",
            points.len(),
            values.len()
        )));
    }
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        return Err(SmoothingError::Invalid(format!(
            "the value of point {k} is not finite"
        )));
    }
    let rows = DesignRows::new(&basis, points)?;
    let q = basis.energy_matrix(energy);
    let mut btb = q.zeroed();
    let mut btz = vec![0.0; 3 * q.vertex_count()];
    rows.normal_equations(values, &mut btb, &mut btz);
    let system = NormalSystem::new(&btb, &q, btz)?;
    let probes = TraceProbes::new(&rows, &btb);
    let evaluate = |lambda: f64| -> Result<Candidate, SmoothingError> {
        let factor = system.factor(lambda)?;
        let c = factor.solve(&system.rhs);
        let rss = rows.residual_sum_of_squares(values, &c);
        let dof = probes.trace(&factor);
        let n = points.len() as f64;
        let gcv = n * rss / (n - dof).max(f64::MIN_POSITIVE).powi(2);
        Ok(Candidate {
            lambda,
            coeffs: c,
            rss,
            dof,
            gcv,
        })
    };
    let best = match smoothing {
        Smoothing::Fixed(lambda) => {
            if !(lambda >= 0.0 && lambda.is_finite()) {
                return Err(SmoothingError::Invalid(format!(
                    "λ must be finite and ≥ 0, not {lambda}"
                )));
            }
            evaluate(lambda)?
        }
        Smoothing::Gcv => gcv_search(system.lambda_scale(), evaluate)?,
    };
    let coeffs: Vec<[f64; 3]> = best.coeffs.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    Ok(SmoothingFit {
        spline: PsSpline::new(basis, coeffs)?,
        lambda: best.lambda,
        rms_residual: (best.rss / points.len() as f64).sqrt(),
        effective_dof: best.dof,
        dof_estimated: probes.estimated(),
        gcv: best.gcv,
    })
}

/// The smoothing fit of scattered data on the Delaunay triangulation of about `m` of the
/// data points ([`coarse_vertices`](super::coarse_vertices)), with the incentre split and
/// optimal PS-triangles. With m ≥ N every point is a vertex.
pub fn smooth_scattered(
    points: &[Point2<f64>],
    values: &[f64],
    m: usize,
    energy: Energy,
    smoothing: Smoothing,
) -> Result<SmoothingFit, SmoothingError> {
    if let Some((first, second)) = crate::triangulation::duplicate_points(points) {
        return Err(
            crate::triangulation::TriangulationError::DuplicateVertex { first, second }.into(),
        );
    }
    let chosen = super::coarse_vertices(points, m);
    let vertices: Vec<Point2<f64>> = chosen.iter().map(|&k| points[k]).collect();
    let order = crate::triangulation::morton_order(&vertices);
    let vertices: Vec<Point2<f64>> = order.iter().map(|&k| vertices[k as usize]).collect();
    let tri = crate::triangulation::Triangulation::delaunay(vertices)?;
    let basis = Arc::new(PsBasis::new(
        tri,
        crate::ps::SplitRule::Incenter,
        &crate::ps::PsTriangleChoice::Optimal,
    )?);
    smoothing_fit(basis, points, values, energy, smoothing)
}

/// One λ tried.
struct Candidate {
    lambda: f64,
    coeffs: Vec<f64>,
    rss: f64,
    dof: f64,
    gcv: f64,
}

/// Minimises GCV over λ = scale × 10^k: whole decades k = −8..=8, extended by up to 12
/// more decades while the best is at an end of the range, then quarter decades around the
/// best.
fn gcv_search(
    scale: f64,
    evaluate: impl Fn(f64) -> Result<Candidate, SmoothingError>,
) -> Result<Candidate, SmoothingError> {
    let mut tried: Vec<Candidate> = Vec::new();
    let try_at = |k: f64, tried: &mut Vec<Candidate>| -> Result<(), SmoothingError> {
        tried.push(evaluate(scale * 10f64.powf(k))?);
        Ok(())
    };
    let (mut lo, mut hi) = (-8, 8);
    for k in lo..=hi {
        try_at(k as f64, &mut tried)?;
    }
    let best_k = |tried: &[Candidate]| -> f64 {
        let b = tried.iter().min_by(|a, b| a.gcv.total_cmp(&b.gcv)).unwrap();
        (b.lambda / scale).log10().round()
    };
    for _ in 0..12 {
        let k = best_k(&tried) as i32;
        if k >= hi {
            hi += 1;
            try_at(hi as f64, &mut tried)?;
        } else if k <= lo {
            lo -= 1;
            try_at(lo as f64, &mut tried)?;
        } else {
            break;
        }
    }
    let centre = best_k(&tried);
    for step in [-0.75, -0.5, -0.25, 0.25, 0.5, 0.75] {
        try_at(centre + step, &mut tried)?;
    }
    Ok(tried
        .into_iter()
        .min_by(|a, b| a.gcv.total_cmp(&b.gcv))
        .unwrap())
}

/// One row of B: the coefficients of a data point's value in the nine control values of
/// its triangle's vertices.
struct Row {
    triangle: usize,
    vertices: [usize; 3],
    coeffs: [f64; 9],
}

impl Row {
    /// s(p) for control values x (three per vertex, flattened).
    fn dot(&self, x: &[f64]) -> f64 {
        (0..9)
            .map(|r| self.coeffs[r] * x[3 * self.vertices[r / 3] + r % 3])
            .sum()
    }
}

/// The rows of B, grouped by triangle.
struct DesignRows {
    /// The data point of each row.
    point: Vec<usize>,
    rows: Vec<Row>,
}

impl DesignRows {
    fn new(basis: &PsBasis, points: &[Point2<f64>]) -> Result<Self, SmoothingError> {
        // Locate along a space-filling curve: consecutive points are near each other.
        let order = crate::triangulation::morton_order(points);
        let mut located: Vec<(usize, SubLocation)> = order
            .par_chunks(4096)
            .map(|chunk| {
                let first = points[chunk[0] as usize];
                let mut hint = basis.locate_any(first).map_or(0, |l| l.triangle);
                chunk
                    .iter()
                    .map(|&k| {
                        let k = k as usize;
                        let loc = basis
                            .locate(points[k], hint)
                            .or_else(|| basis.locate_any(points[k]))
                            .ok_or(SmoothingError::Outside(k))?;
                        hint = loc.triangle;
                        Ok((k, loc))
                    })
                    .collect::<Result<Vec<_>, SmoothingError>>()
            })
            .collect::<Result<Vec<_>, _>>()?
            .concat();
        located.par_sort_by_key(|(_, l)| l.triangle);
        let tri = basis.triangulation();
        let rows = located
            .par_chunk_by(|a, b| a.1.triangle == b.1.triangle)
            .flat_map_iter(|group| {
                let t = group[0].1.triangle;
                let stencil = basis.stencil(t);
                let vertices = tri.triangle(t);
                group.iter().map(move |(_, loc)| {
                    let k = stencil.transpose(value_weights(loc));
                    let mut coeffs = [0.0; 9];
                    for c in 0..3 {
                        coeffs[3 * c..3 * c + 3].copy_from_slice(&k[c]);
                    }
                    Row {
                        triangle: t,
                        vertices,
                        coeffs,
                    }
                })
            })
            .collect();
        Ok(DesignRows {
            point: located.iter().map(|(k, _)| *k).collect(),
            rows,
        })
    }

    /// Adds BᵀB (one element per triangle with data) and Bᵀz.
    fn normal_equations(&self, values: &[f64], btb: &mut Block3Matrix, btz: &mut [f64]) {
        for group in self.rows.chunk_by(|a, b| a.triangle == b.triangle) {
            let mut m: ElementMatrix = [[0.0; 12]; 12];
            for row in group {
                let a = &row.coeffs;
                for r in 0..9 {
                    for c in 0..9 {
                        m[r][c] += a[r] * a[c];
                    }
                }
            }
            btb.add_element(&group[0].vertices, &m);
        }
        for (row, &k) in self.rows.iter().zip(&self.point) {
            self.scatter(row, values[k], btz);
        }
    }

    /// Adds value × (the row) to y (Bᵀ applied to one entry).
    fn scatter(&self, row: &Row, value: f64, y: &mut [f64]) {
        for r in 0..9 {
            y[3 * row.vertices[r / 3] + r % 3] += row.coeffs[r] * value;
        }
    }

    /// Σ_k (s(p_k) − z_k)² for control values `c`.
    fn residual_sum_of_squares(&self, values: &[f64], c: &[f64]) -> f64 {
        self.rows
            .par_iter()
            .zip(&self.point)
            .map(|(row, &k)| (row.dot(c) - values[k]).powi(2))
            .sum()
    }
}

/// BᵀB and Q on one sparsity pattern, factorised for any λ.
struct NormalSystem {
    pattern: SpdPattern,
    /// Whether each entry is on the diagonal.
    diagonal: Vec<bool>,
    data: Vec<f64>,
    energy: Vec<f64>,
    rhs: Vec<f64>,
}

impl NormalSystem {
    fn new(btb: &Block3Matrix, q: &Block3Matrix, rhs: Vec<f64>) -> Result<Self, SmoothingError> {
        let (positions, data) = btb.lower_entries();
        let (_, energy) = q.lower_entries();
        Ok(NormalSystem {
            pattern: SpdPattern::new(3 * q.vertex_count(), &positions)?,
            diagonal: positions.iter().map(|(r, c)| r == c).collect(),
            data,
            energy,
            rhs,
        })
    }

    fn factor(&self, lambda: f64) -> Result<crate::sparse::Cholesky, SmoothingError> {
        let values: Vec<f64> = self
            .data
            .iter()
            .zip(&self.energy)
            .map(|(a, q)| a + lambda * q)
            .collect();
        Ok(self.pattern.factor(&values)?)
    }

    /// tr(BᵀB) / tr(Q): the λ at which data and energy weigh about the same.
    fn lambda_scale(&self) -> f64 {
        let diagonal = |v: &[f64]| -> f64 {
            v.iter()
                .zip(&self.diagonal)
                .filter(|(_, d)| **d)
                .map(|(x, _)| x)
                .sum()
        };
        let s = diagonal(&self.data) / diagonal(&self.energy);
        if s.is_finite() && s > 0.0 { s } else { 1.0 }
    }
}

/// What tr A(λ) = tr((BᵀB + λQ)⁻¹ BᵀB) is computed from: the columns of BᵀB (exact), or
/// Bᵀu for random ±1 vectors u (Hutchinson: E[uᵀ A u] = tr A).
struct TraceProbes {
    columns: Vec<f64>,
    count: usize,
    exact: bool,
}

impl TraceProbes {
    fn new(rows: &DesignRows, btb: &Block3Matrix) -> Self {
        let n = 3 * btb.vertex_count();
        if n <= EXACT_TRACE_MAX {
            let mut columns = vec![0.0; n * n];
            for (i, j, b) in btb.blocks() {
                for r in 0..3 {
                    for c in 0..3 {
                        let (a, bb) = (3 * i + r, 3 * j + c);
                        columns[bb * n + a] = b[r][c];
                        columns[a * n + bb] = b[r][c];
                    }
                }
            }
            return TraceProbes {
                columns,
                count: n,
                exact: true,
            };
        }
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x5eed);
        let mut columns = vec![0.0; n * PROBES];
        for k in 0..PROBES {
            let col = &mut columns[k * n..(k + 1) * n];
            for row in &rows.rows {
                let u = if rng.random::<bool>() { 1.0 } else { -1.0 };
                rows.scatter(row, u, col);
            }
        }
        TraceProbes {
            columns,
            count: PROBES,
            exact: false,
        }
    }

    fn estimated(&self) -> bool {
        !self.exact
    }

    /// tr A(λ) with the factorisation of BᵀB + λQ.
    fn trace(&self, factor: &crate::sparse::Cholesky) -> f64 {
        let n = self.columns.len() / self.count;
        let x = factor.solve_many(&self.columns, self.count);
        if self.exact {
            (0..n).map(|j| x[j * n + j]).sum()
        } else {
            let total: f64 = (0..self.count)
                .map(|k| {
                    let (b, y) = (&self.columns[k * n..(k + 1) * n], &x[k * n..(k + 1) * n]);
                    b.iter().zip(y).map(|(a, c)| a * c).sum::<f64>()
                })
                .sum();
            total / self.count as f64
        }
    }
}

/// The weights of the 19 ordinates of a triangle's net in the value at a located point:
/// the quadratic Bernstein polynomials of its piece (τ_0², 2τ_0τ_1, …).
fn value_weights(loc: &SubLocation) -> [f64; NET_LEN] {
    let [a, b, c] = loc.bary;
    let bern = [a * a, 2.0 * a * b, 2.0 * a * c, b * b, 2.0 * b * c, c * c];
    let mut w = [0.0; NET_LEN];
    for (slot, &k) in SUB_ORDINATES[loc.sub].iter().enumerate() {
        w[k] += bern[slot];
    }
    w
}
