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
    /// The points cannot fix what the energy leaves free (planes or quadratics).
    #[error(
        "the points do not determine the fit: this energy leaves {0} free, and the points cannot fix them (they need {1})"
    )]
    Undetermined(&'static str, &'static str),
    /// The normal equations are singular in floating point.
    #[error(
        "the fit is not determined: too few points for the vertices near them; give fewer vertices or a larger λ"
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
    /// The coarse triangulation has detail finer than the coordinates resolve
    /// ([`FitError::BeyondPrecision`](super::FitError::BeyondPrecision), with data indices).
    #[error(transparent)]
    BeyondPrecision(super::FitError),
    /// A data point's coordinate is not finite or out of range (the
    /// [`FitError`](super::FitError) of [`check_points`](super::check_points), naming the
    /// point).
    #[error(transparent)]
    Data(super::FitError),
}

impl From<SparseError> for SmoothingError {
    fn from(e: SparseError) -> Self {
        match e {
            SparseError::NotPositiveDefinite => SmoothingError::Singular,
            e => SmoothingError::Solve(e),
        }
    }
}

/// λ beyond this multiple of the balancing scale (tr BᵀB / tr Q) is "too large" when the
/// system cannot be factorised.
const TOO_LARGE: f64 = 1e8;

/// Whether the data determine the null space of `energy` (planes for the thin-plate
/// energy, quadratics for the Hessian-jump energy): then BᵀB + λQ is positive definite for
/// every λ > 0. Checked on the Gram matrix of the monomials in centred, scaled coordinates:
/// its smallest eigenvalue must exceed 1e-13 of its largest (points on one line, or for
/// quadratics on one conic or fewer than six, fail).
fn determines_null_space(points: &[Point2<f64>], energy: Energy) -> bool {
    let k = match energy {
        Energy::ThinPlate => 3,
        Energy::HessianJumps => 6,
    };
    if points.len() < k {
        return false;
    }
    let n = points.len() as f64;
    let centre = points
        .iter()
        .fold(nalgebra::Vector2::zeros(), |a, p| a + p.coords)
        / n;
    let radius = points
        .iter()
        .map(|p| (p.coords - centre).norm())
        .fold(0.0, f64::max);
    if !(radius > 0.0 && radius.is_finite()) {
        return false;
    }
    let mut gram = nalgebra::DMatrix::<f64>::zeros(k, k);
    for p in points {
        let (u, v) = ((p.x - centre.x) / radius, (p.y - centre.y) / radius);
        let m = [1.0, u, v, u * u, u * v, v * v];
        for a in 0..k {
            for b in 0..k {
                gram[(a, b)] += m[a] * m[b];
            }
        }
    }
    let eig = gram.symmetric_eigenvalues();
    eig.min() > 1e-13 * eig.max()
}

/// Bases with at most this many control values get the exact trace of A(λ).
const EXACT_TRACE_MAX: usize = 1500;
/// The number of Hutchinson probes otherwise (relative error of the estimate about
/// √(2/PROBES) × ‖A‖_F / tr A).
const PROBES: usize = 32;
/// The fewest probes, for bases too large for [`PROBES`] within [`PROBE_MEMORY`].
const MIN_PROBES: usize = 4;
/// The memory the probe vectors may take (bytes).
const PROBE_MEMORY: usize = 256 << 20;
/// Right-hand sides solved at once.
const SOLVE_BATCH: usize = 8;

/// One λ tried by the smoothing fit, for progress reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trial {
    /// The smoothing parameter.
    pub lambda: f64,
    /// Its GCV score.
    pub gcv: f64,
    /// Its effective degrees of freedom.
    pub dof: f64,
}

/// The smoothing PS-spline on `basis` of the data (points\[k\], values\[k\]) with energy
/// `energy` and smoothing `smoothing` (module docs); `on_trial` hears of every λ tried.
pub fn smoothing_fit(
    basis: Arc<PsBasis>,
    points: &[Point2<f64>],
    values: &[f64],
    energy: Energy,
    smoothing: Smoothing,
    on_trial: &mut dyn FnMut(&Trial),
) -> Result<SmoothingFit, SmoothingError> {
    check_input(points, values, energy, smoothing)?;
    let rows = DesignRows::new(&basis, points)?;
    let q = match energy {
        Energy::HessianJumps => basis.faded_jump_energy_matrix(),
        Energy::ThinPlate => basis.energy_matrix(energy),
    };
    let mut btb = q.zeroed();
    let mut btz = vec![0.0; 3 * q.vertex_count()];
    rows.normal_equations(values, &mut btb, &mut btz);
    let system = NormalSystem::new(&btb, &q, btz)?;
    let probes = TraceProbes::new(&rows, &btb);
    let mut evaluate = |lambda: f64| -> Result<Candidate, SmoothingError> {
        let factor = system.factor(lambda)?;
        let c = factor.solve(&system.rhs);
        let rss = rows.residual_sum_of_squares(values, &c);
        let dof = probes.trace(&factor);
        let n = points.len() as f64;
        let gcv = n * rss / (n - dof).max(f64::MIN_POSITIVE).powi(2);
        on_trial(&Trial { lambda, gcv, dof });
        Ok(Candidate {
            lambda,
            coeffs: c,
            rss,
            dof,
            gcv,
        })
    };
    let scale = system.lambda_scale();
    let best = match smoothing {
        Smoothing::Fixed(lambda) => match evaluate(lambda) {
            // The data determine the energy's null space (checked above), so the system is
            // positive definite for λ > 0 — unless λ is so large that the data's part is
            // lost to rounding next to λQ.
            Err(SmoothingError::Singular) if lambda > TOO_LARGE * scale => {
                return Err(SmoothingError::Invalid(format!(
                    "λ = {lambda:e} is too large for these data: the energy swamps them in floating point (λ ≈ {scale:.1e} weighs both alike)"
                )));
            }
            result => result?,
        },
        Smoothing::Gcv => gcv_search(scale, evaluate)?,
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

/// Refuses data and parameters the fit cannot use, with the reason.
fn check_input(
    points: &[Point2<f64>],
    values: &[f64],
    energy: Energy,
    smoothing: Smoothing,
) -> Result<(), SmoothingError> {
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
    // Not finite, or so large that areas overflow (the data's indices: the input order).
    super::interpolate::check_point_coordinates(points).map_err(SmoothingError::Data)?;
    if let Smoothing::Fixed(lambda) = smoothing
        && !(lambda >= 0.0 && lambda.is_finite())
    {
        return Err(SmoothingError::Invalid(format!(
            "λ must be finite and ≥ 0, not {lambda}"
        )));
    }
    if !determines_null_space(points, energy) {
        return Err(match energy {
            Energy::ThinPlate => SmoothingError::Undetermined("planes", "3 points not on one line"),
            Energy::HessianJumps => SmoothingError::Undetermined(
                "quadratics",
                "6 points not on one line, circle or other conic",
            ),
        });
    }
    Ok(())
}

/// The smoothing fit of scattered data on a grid of about `m` vertices over the data's
/// bounding box ([`coarse_triangulation`](super::coarse_triangulation)), or, when m ≥ N, on
/// the Delaunay triangulation of the data points themselves (of nearly coincident points,
/// see [`NEAR_DUPLICATE`](super::NEAR_DUPLICATE), only the first); with the incentre split
/// and optimal PS-triangles. Points may repeat (repeated measurements).
pub fn smooth_scattered(
    points: &[Point2<f64>],
    values: &[f64],
    m: usize,
    energy: Energy,
    smoothing: Smoothing,
    on_trial: &mut dyn FnMut(&Trial),
) -> Result<SmoothingFit, SmoothingError> {
    // Repeated measurements at one (x, y) are welcome: least squares averages them.
    check_input(points, values, energy, smoothing)?;
    let basis = if m < points.len() {
        let tri = super::coarse_triangulation(points, m)?;
        // The grid is no finer than the coordinates resolve, so this is not expected; its
        // vertices are not data points, so say so rather than name them.
        super::data_basis(tri, crate::ps::SplitRule::Incenter).map_err(|e| match e {
            super::FitError::BeyondPrecision { magnitude, .. } => SmoothingError::Invalid(format!(
                "the coarse grid is finer than coordinates of magnitude {magnitude:.1e} resolve: subtract an origin from the points"
            )),
            e => basis_error(e, |v| v),
        })?
    } else {
        vertices_at_the_data(points)?
    };
    smoothing_fit(Arc::new(basis), points, values, energy, smoothing, on_trial)
}

/// The PS basis on the Delaunay triangulation of the data points (of nearly coincident
/// ones only the first).
fn vertices_at_the_data(points: &[Point2<f64>]) -> Result<PsBasis, SmoothingError> {
    let close = super::near_duplicate_groups(points, super::NEAR_DUPLICATE);
    let mut dropped = vec![false; points.len()];
    close
        .iter()
        .flat_map(|g| g[1..].iter())
        .for_each(|&k| dropped[k] = true);
    let kept: Vec<usize> = (0..points.len()).filter(|&k| !dropped[k]).collect();
    let order =
        crate::triangulation::morton_order(&kept.iter().map(|&k| points[k]).collect::<Vec<_>>());
    let data_index: Vec<usize> = order.iter().map(|&k| kept[k as usize]).collect();
    let vertices: Vec<Point2<f64>> = data_index.iter().map(|&k| points[k]).collect();
    let tri = crate::triangulation::Triangulation::delaunay(vertices)?;
    super::data_basis(tri, crate::ps::SplitRule::Incenter)
        .map_err(|e| basis_error(e, |v| data_index[v]))
}

/// A failure of the PS basis as a smoothing error, with vertices renamed by `index`.
fn basis_error(e: super::FitError, index: impl Fn(usize) -> usize) -> SmoothingError {
    match e {
        super::FitError::Ps(e) => SmoothingError::Ps(e),
        super::FitError::BeyondPrecision {
            vertices,
            height,
            magnitude,
        } => SmoothingError::BeyondPrecision(super::FitError::BeyondPrecision {
            vertices: vertices.map(index),
            height,
            magnitude,
        }),
        e => SmoothingError::Invalid(e.to_string()),
    }
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
    mut evaluate: impl FnMut(f64) -> Result<Candidate, SmoothingError>,
) -> Result<Candidate, SmoothingError> {
    let mut tried: Vec<Candidate> = Vec::new();
    // A λ so large (or small) that the system cannot be factorised in floating point is
    // skipped; the data determine the problem, so moderate λ always work.
    let mut try_at = |k: f64, tried: &mut Vec<Candidate>| -> Result<(), SmoothingError> {
        match evaluate(scale * 10f64.powf(k)) {
            Ok(c) => tried.push(c),
            Err(SmoothingError::Singular) => {}
            Err(e) => return Err(e),
        }
        Ok(())
    };
    let (mut lo, mut hi) = (-8, 8);
    for k in lo..=hi {
        try_at(k as f64, &mut tried)?;
    }
    if tried.is_empty() {
        return Err(SmoothingError::Singular);
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
        // Points beside the domain by no more than a peeled boundary sliver's thickness or a
        // dropped near-duplicate hull vertex's distance are fitted by the nearest piece's
        // polynomial.
        let near =
            2.0 * super::near_duplicate_distance(points, crate::triangulation::PEEL_THICKNESS);
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
                            .or_else(|| basis.locate_near(points[k], near))
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
            pattern: SpdPattern::with_order(
                3 * q.vertex_count(),
                &positions,
                Some(&q.elimination_order(3)?),
            )?,
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

/// What tr A(λ) = tr((BᵀB + λQ)⁻¹ BᵀB) is computed from: the columns of BᵀB, or the rows
/// b_i of B (both exact; whichever are fewer), or Bᵀu for random ±1 vectors u (Hutchinson:
/// E[uᵀ A u] = tr A).
struct TraceProbes {
    columns: Vec<f64>,
    count: usize,
    mode: TraceMode,
}

/// How [`TraceProbes::trace`] combines the solutions y = (BᵀB + λQ)⁻¹ v of its columns v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TraceMode {
    /// v is column k of BᵀB: tr A = Σ_k y_k.
    Diagonal,
    /// v = b_i, row i of B: tr A = tr(B H⁻¹ Bᵀ) = Σ_i b_iᵀ y.
    Rows,
    /// v = Bᵀu: tr A ≈ mean of vᵀ y.
    Hutchinson,
}

impl TraceProbes {
    /// Exact for bases of at most [`EXACT_TRACE_MAX`] values, Hutchinson's otherwise.
    /// Exact from the fewer of the data rows and the columns when there are fewer than
    /// [`EXACT_TRACE_MAX`] data rows or control values.
    fn new(rows: &DesignRows, btb: &Block3Matrix) -> Self {
        let n = 3 * btb.vertex_count();
        let data = rows.rows.len();
        if data < n && data <= EXACT_TRACE_MAX {
            Self::data_rows(rows, n)
        } else if n <= EXACT_TRACE_MAX {
            Self::exact(btb)
        } else {
            Self::hutchinson(rows, n)
        }
    }

    /// The rows of B as vectors, for the exact trace when there are fewer data than values
    /// (a smoothing fit on the data's own triangulation: three values per point).
    fn data_rows(rows: &DesignRows, n: usize) -> Self {
        let count = rows.rows.len();
        let mut columns = vec![0.0; n * count];
        for (k, row) in rows.rows.iter().enumerate() {
            rows.scatter(row, 1.0, &mut columns[k * n..(k + 1) * n]);
        }
        TraceProbes {
            columns,
            count,
            mode: TraceMode::Rows,
        }
    }

    /// The columns of BᵀB, for the exact trace.
    fn exact(btb: &Block3Matrix) -> Self {
        let n = 3 * btb.vertex_count();
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
        TraceProbes {
            columns,
            count: n,
            mode: TraceMode::Diagonal,
        }
    }

    /// Bᵀu for random ±1 vectors u (a fixed seed: results are reproducible).
    fn hutchinson(rows: &DesignRows, n: usize) -> Self {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0x5eed);
        // Fewer probes for very large bases, so that they fit in PROBE_MEMORY.
        let count = (PROBE_MEMORY / (8 * n)).clamp(MIN_PROBES, PROBES);
        let mut columns = vec![0.0; n * count];
        for k in 0..count {
            let col = &mut columns[k * n..(k + 1) * n];
            for row in &rows.rows {
                let u = if rng.random::<bool>() { 1.0 } else { -1.0 };
                rows.scatter(row, u, col);
            }
        }
        TraceProbes {
            columns,
            count,
            mode: TraceMode::Hutchinson,
        }
    }

    fn estimated(&self) -> bool {
        self.mode == TraceMode::Hutchinson
    }

    /// tr A(λ) with the factorisation of BᵀB + λQ.
    /// Solves for the probe columns in batches of [`SOLVE_BATCH`] (bounded memory).
    fn trace(&self, factor: &crate::sparse::Cholesky) -> f64 {
        let n = self.columns.len() / self.count;
        let mut total = 0.0;
        for first in (0..self.count).step_by(SOLVE_BATCH) {
            let last = (first + SOLVE_BATCH).min(self.count);
            let b = &self.columns[first * n..last * n];
            let x = factor.solve_many(b, last - first);
            for (k, col) in (first..last).enumerate() {
                let y = &x[k * n..(k + 1) * n];
                total += match self.mode {
                    TraceMode::Diagonal => y[col],
                    TraceMode::Rows | TraceMode::Hutchinson => b[k * n..(k + 1) * n]
                        .iter()
                        .zip(y)
                        .map(|(a, c)| a * c)
                        .sum::<f64>(),
                };
            }
        }
        match self.mode {
            TraceMode::Hutchinson => total / self.count as f64,
            _ => total,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::*;

    /// A smoothing problem on `n` random points of the unit square (corners included), on a
    /// grid of about `m` vertices over it.
    fn problem(n: usize, m: usize, seed: u64) -> (Arc<PsBasis>, Vec<Point2<f64>>, Vec<f64>) {
        let mut r = rng(seed);
        let mut pts = vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
            Point2::new(1.0, 1.0),
        ];
        while pts.len() < n {
            pts.push(Point2::new(
                uniform(&mut r, 0.0, 1.0),
                uniform(&mut r, 0.0, 1.0),
            ));
        }
        let z: Vec<f64> = pts
            .iter()
            .map(|p| (4.0 * p.x).sin() + p.y * p.y + uniform(&mut r, -0.1, 0.1))
            .collect();
        let tri = super::super::coarse_triangulation(&pts, m).unwrap();
        (Arc::new(PsBasis::optimal(tri).unwrap()), pts, z)
    }

    #[test]
    fn hutchinson_estimates_the_exact_trace() {
        let (basis, pts, z) = problem(600, 80, 91);
        let rows = DesignRows::new(&basis, &pts).unwrap();
        let q = basis.energy_matrix(Energy::HessianJumps);
        let mut btb = q.zeroed();
        let mut btz = vec![0.0; 3 * q.vertex_count()];
        rows.normal_equations(&z, &mut btb, &mut btz);
        let system = NormalSystem::new(&btb, &q, btz).unwrap();
        let exact = TraceProbes::exact(&btb);
        let estimate = TraceProbes::hutchinson(&rows, 3 * q.vertex_count());
        for k in [-4.0, -2.0, 0.0, 2.0] {
            let f = system
                .factor(system.lambda_scale() * 10f64.powf(k))
                .unwrap();
            let (t, e) = (exact.trace(&f), estimate.trace(&f));
            // tr A ≤ rank and A's eigenvalues lie in [0, 1], so ‖A‖_F ≤ √tr A and the
            // estimate's standard deviation is at most √(2 tr A / 32).
            let sd = (2.0 * t / PROBES as f64).sqrt();
            assert!(
                (t - e).abs() <= 4.0 * sd,
                "λ·10^{k}: exact {t}, estimate {e} (sd {sd})"
            );
            assert!(t > 6.0 && t < 3.0 * q.vertex_count() as f64, "{t}");
        }
    }

    #[test]
    fn the_normal_equations_and_the_exact_trace_match_dense_algebra() {
        let (basis, pts, z) = problem(60, 12, 92);
        let rows = DesignRows::new(&basis, &pts).unwrap();
        let q = basis.energy_matrix(Energy::ThinPlate);
        let mut btb = q.zeroed();
        let mut btz = vec![0.0; 3 * q.vertex_count()];
        rows.normal_equations(&z, &mut btb, &mut btz);
        let system = NormalSystem::new(&btb, &q, btz).unwrap();
        let lambda = system.lambda_scale() * 0.1;
        // Dense B and Q from unit control vectors.
        let n = 3 * q.vertex_count();
        let unit = |j: usize| -> Vec<f64> { (0..n).map(|i| f64::from(u8::from(i == j))).collect() };
        let b = nalgebra::DMatrix::from_fn(pts.len(), n, |_, _| 0.0);
        let mut b = b;
        for j in 0..n {
            let e = unit(j);
            for (row, &k) in rows.rows.iter().zip(&rows.point) {
                b[(k, j)] = row.dot(&e);
            }
        }
        let qd = nalgebra::DMatrix::from_fn(n, n, |i, j| {
            let x: Vec<[f64; 3]> = unit(j).chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
            let y = q.multiply(&x);
            y[i / 3][i % 3]
        });
        let m = b.transpose() * &b + qd * lambda;
        let hat = &b * m.clone().try_inverse().unwrap() * b.transpose();
        let factor = system.factor(lambda).unwrap();
        // Both exact forms: from the columns of BᵀB and from the rows of B.
        for t in [
            TraceProbes::exact(&btb).trace(&factor),
            TraceProbes::data_rows(&rows, n).trace(&factor),
        ] {
            assert!(
                (t - hat.trace()).abs() <= 1e-8 * hat.trace(),
                "{t} vs {}",
                hat.trace()
            );
        }
        // The sparse normal equations against the dense ones.
        let zv = nalgebra::DVector::from_column_slice(&z);
        let dense = m.try_inverse().unwrap() * b.transpose() * zv;
        let sparse = factor.solve(&system.rhs);
        for (a, d) in sparse.iter().zip(dense.iter()) {
            assert!((a - d).abs() <= 1e-8 * (1.0 + d.abs()), "{a} vs {d}");
        }
    }

    #[test]
    fn data_that_do_not_determine_the_null_space_are_refused() {
        let p = Point2::new;
        let five = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(0.0, 1.0),
            p(1.0, 1.0),
            p(0.5, 0.3),
        ];
        assert!(!determines_null_space(&five, Energy::HessianJumps));
        assert!(determines_null_space(&five, Energy::ThinPlate));
        // Twelve points on a circle: on one conic.
        let circle: Vec<_> = (0..12)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 12.0;
                p(3.0 + a.cos(), -2.0 + a.sin())
            })
            .collect();
        assert!(!determines_null_space(&circle, Energy::HessianJumps));
        assert!(determines_null_space(&circle, Energy::ThinPlate));
        let mut with_centre = circle.clone();
        with_centre.push(p(3.0, -2.0));
        assert!(determines_null_space(&with_centre, Energy::HessianJumps));
        let line: Vec<_> = (0..10).map(|k| p(k as f64, 2.0 * k as f64 + 1.0)).collect();
        assert!(!determines_null_space(&line, Energy::ThinPlate));
    }
}
