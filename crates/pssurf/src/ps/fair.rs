//! Fairing a PS, UPS or NURPS surface with its boundary fixed (issue 18, part 5): the thesis'
//! constrained fairing (5.4.3) applied to a whole surface, with a weight between fairness and
//! staying close to the original.
//!
//! The control values c of the interior vertices minimise
//!
//!   E(c) + w σ ‖c − c₀‖²,
//!
//! where E is a quadratic energy of the surface (by default the thesis' least squares on the
//! jumps of the second derivatives across the edges of the PS refinement,
//! [`Energy::HessianJumps`]; or the thin-plate energy), c₀ the original control values, σ the
//! mean diagonal of E's matrix on the interior (so that w = 1 weighs both terms about alike)
//! and w ≥ 0 the user's weight. The control triangles of the boundary vertices stay as they
//! are (bitwise), so the boundary curve does not move. The minimiser solves the normal
//! equations (Q_II + w σ I) c_I = w σ c₀_I − Q_IB c_B, written for the change δ = c − c₀ as
//! (Q_II + w σ I) δ_I = −(Q c₀)_I: one sparse Cholesky factorisation for all coordinates. Hessian jumps vanish on quadratics, so a quadratic surface is its own
//! fairest surface and stays unchanged.
//!
//! Each coordinate of a parametric surface is faired alike (the energy of the map (x, y, z));
//! a functional surface changes its heights only; a NURPS surface its control points, with the
//! energy of the polynomial surface of the same control points (the weights stay).

use thiserror::Error;

use super::Energy;
use crate::sparse::{
    Block3Matrix, BlockJacobi, SparseError, Stopping, SymmetricBlocks, conjugate_gradient,
};
use crate::surface::{ControlFreedom, ControlId, ControlNet, ControlPoint, EditError, Surface};
use crate::triangulation::Triangulation;

/// How to fair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FairOptions {
    /// The weight w ≥ 0 of staying close to the original (0: the fairest surface with this
    /// boundary).
    pub weight: f64,
    /// The energy to minimise.
    pub energy: Energy,
}

impl Default for FairOptions {
    fn default() -> Self {
        FairOptions {
            weight: 0.1,
            energy: Energy::HessianJumps,
        }
    }
}

/// A faired surface and what changed.
#[derive(Clone, Debug)]
pub struct Faired {
    /// The faired surface (of the same kind: a UPS surface stays one).
    pub surface: Surface,
    /// E before (≥ 0: a sum of squares, rounding below 0 reported as 0).
    pub energy_before: f64,
    /// E after (≥ 0, likewise).
    pub energy_after: f64,
    /// The control points that moved.
    pub moved: usize,
    /// The largest distance a control point moved.
    pub largest_move: f64,
    /// ‖A c − b‖ / ‖b‖ of the normal equations at the solution.
    pub normal_residual: f64,
    /// How the normal equations were solved.
    pub solver: FairSolver,
}

/// How the fairing's normal equations were solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FairSolver {
    /// Block-Jacobi preconditioned conjugate gradients, with the largest number of steps
    /// that a coordinate took.
    ConjugateGradient {
        /// The steps.
        steps: usize,
    },
    /// A sparse Cholesky factorisation (with iterative refinement).
    Cholesky,
}

impl std::fmt::Display for FairSolver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FairSolver::ConjugateGradient { steps } => {
                write!(f, "conjugate gradients, {steps} steps")
            }
            FairSolver::Cholesky => write!(f, "sparse Cholesky"),
        }
    }
}

/// Why a surface could not be faired.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum FairError {
    /// Not a PS kind.
    #[error("fairing works on PS, UPS and NURPS surfaces, not on a {0}")]
    NotPs(&'static str),
    /// A weight that is negative, not finite or beyond 1e12.
    #[error("the weight must be a number from 0 to 1e12, not {}", crate::text::Short(*.0))]
    BadWeight(f64),
    /// Every vertex is on the boundary.
    #[error("every vertex lies on the boundary: there is nothing to fair")]
    NoInterior,
    /// The system could not be factorised: with weight 0, an energy blind to some interior
    /// motion; or too little memory.
    #[error("the fairing system could not be solved ({0}); with weight 0, give a positive weight")]
    Singular(SparseError),
    /// The new control points were refused.
    #[error(transparent)]
    Edit(#[from] EditError),
}

/// The weight from which the normal equations are solved by conjugate gradients (block
/// Jacobi preconditioned) instead of a sparse Cholesky factorisation. The ridge w σ bounds
/// the smallest eigenvalue away from zero, so the number of steps grows like 1/√w:
/// measured on the `fair` bench's 100k-vertex hexagon, 71 steps at w = 0.1 and 203 at 0.01
/// (docs/performance.md). Below it, and whenever the iteration does not reach
/// [`ITERATIVE_RESIDUAL`] within [`ITERATIVE_MAX_STEPS`], the factorisation is used.
pub const ITERATIVE_FROM_WEIGHT: f64 = 1e-2;

/// The relative residual of the normal equations at which the iteration stops.
pub const ITERATIVE_RESIDUAL: f64 = 1e-13;

/// The steps after which the iteration gives way to the factorisation.
pub const ITERATIVE_MAX_STEPS: usize = 2000;

/// When the iteration stops: [`ITERATIVE_RESIDUAL`], [`ITERATIVE_MAX_STEPS`].
const ITERATIVE_STOP: Stopping = Stopping {
    relative_residual: ITERATIVE_RESIDUAL,
    max_steps: ITERATIVE_MAX_STEPS,
};

/// Fairs `s` with its boundary fixed (see the module documentation).
pub fn fair(s: &Surface, opts: &FairOptions) -> Result<Faired, FairError> {
    if !(opts.weight >= 0.0 && opts.weight <= 1e12) {
        return Err(FairError::BadWeight(opts.weight));
    }
    let basis = s
        .ps_basis()
        .ok_or(FairError::NotPs(s.kind().description()))?
        .clone();
    let tri = basis.triangulation();
    let n = tri.vertex_count();
    // Interior values: 3 per interior vertex; value 3i + j of interior vertex k is the
    // unknown 3k + j.
    let interior = interior_numbering(tri);
    let value_of: Vec<usize> = (0..3 * n).filter(|&v| interior[v / 3].is_some()).collect();
    let unknown = |v: usize| interior[v / 3].map(|k| 3 * k as usize + v % 3);
    let m = value_of.len();
    if m == 0 {
        return Err(FairError::NoInterior);
    }
    let q = basis.energy_matrix(opts.energy);
    let coords: Vec<usize> = match s.freedom() {
        ControlFreedom::Full => vec![0, 1, 2],
        ControlFreedom::Height => vec![2],
    };
    // c₀ per coordinate over all 3n values.
    let original: Vec<ControlPoint> = s.control_points();
    let c0: Vec<Vec<f64>> = coords
        .iter()
        .map(|&c| original.iter().map(|p| p.position[c]).collect())
        .collect();
    // The change δ = c − c₀ of the interior values solves (Q_II + w σ I) δ_I = −(Q c₀)_I: the
    // right-hand side is the energy's gradient at the original surface, so a surface that is
    // already fair (Q c₀ = 0, e.g. a quadratic) gets δ = 0 up to rounding of that gradient,
    // not of the whole solution.
    let mut rhs = vec![0.0; m * coords.len()];
    for (b, x) in c0.iter().enumerate() {
        let blocks: Vec<[f64; 3]> = (0..n)
            .map(|i| std::array::from_fn(|j| x[3 * i + j]))
            .collect();
        let g = q.multiply(&blocks);
        for k in 0..m {
            let v = value_of[k];
            rhs[b * m + k] = -g[v / 3][v % 3];
        }
    }
    let system = interior_system(&q, &interior, opts.weight);
    let (solution, normal_residual, solver) =
        solve(&system, &rhs, coords.len(), opts.weight, &ITERATIVE_STOP)?;
    // The new control points.
    let mut changes = Vec::new();
    let mut largest_move = 0.0f64;
    for v in 0..3 * n {
        let Some(k) = unknown(v) else {
            continue;
        };
        let mut p = original[v];
        for (b, &c) in coords.iter().enumerate() {
            p.position[c] += solution[b * m + k];
        }
        if p != original[v] {
            largest_move = largest_move.max((p.position - original[v].position).norm());
            changes.push((ControlId(v), p));
        }
    }
    let mut surface = s.clone();
    surface.set_control_points(&changes)?;
    let energy_of = |pts: &[ControlPoint]| -> f64 {
        coords
            .iter()
            .map(|&c| {
                let x: Vec<[f64; 3]> = (0..n)
                    .map(|i| std::array::from_fn(|j| pts[3 * i + j].position[c]))
                    .collect();
                q.quadratic_form(&x)
            })
            .sum::<f64>()
            // E is a sum of squares; rounding makes it about −1e-10 on surfaces of zero
            // energy (a quadratic under the jump energy), printed as a negative energy.
            .max(0.0)
    };
    Ok(Faired {
        energy_before: energy_of(&original),
        energy_after: energy_of(&surface.control_points()),
        moved: changes.len(),
        largest_move,
        normal_residual,
        solver,
        surface,
    })
}

/// The interior vertices' numbers among the interior vertices (in vertex order), `None` on
/// the boundary.
fn interior_numbering(tri: &Triangulation) -> Vec<Option<u32>> {
    let mut next = 0u32;
    (0..tri.vertex_count())
        .map(|i| {
            (!tri.is_boundary_vertex(i)).then(|| {
                next += 1;
                next - 1
            })
        })
        .collect()
}

/// The normal equations' matrix Q_II + w σ I on the interior vertices' values (`interior`
/// from [`interior_numbering`]), σ the mean diagonal of Q_II.
fn interior_system(q: &Block3Matrix, interior: &[Option<u32>], weight: f64) -> SymmetricBlocks {
    let (mut diagonal, mut count) = (0.0, 0usize);
    for (i, j, b) in q.blocks() {
        if i == j && interior[i].is_some() {
            diagonal += b[0][0] + b[1][1] + b[2][2];
            count += 3;
        }
    }
    let sigma = diagonal / count.max(1) as f64;
    let ridge = weight * if sigma > 0.0 { sigma } else { 1.0 };
    SymmetricBlocks::restrict(q, interior, ridge)
}

/// The solutions for `columns` right-hand sides (one after the other), the relative residual
/// of the normal equations and the solver used: conjugate gradients (stopping at `stop`)
/// from [`ITERATIVE_FROM_WEIGHT`] on, else (or when they do not converge) Cholesky.
fn solve(
    a: &SymmetricBlocks,
    rhs: &[f64],
    columns: usize,
    weight: f64,
    stop: &Stopping,
) -> Result<(Vec<f64>, f64, FairSolver), FairError> {
    let (solution, solver) = match (weight >= ITERATIVE_FROM_WEIGHT)
        .then(|| iterate(a, rhs, columns, stop))
        .flatten()
    {
        Some((x, steps)) => (x, FairSolver::ConjugateGradient { steps }),
        None => (
            a.solve_by_cholesky(rhs, columns)
                .map_err(FairError::Singular)?,
            FairSolver::Cholesky,
        ),
    };
    let residual = a.relative_residual(&solution, rhs, columns);
    Ok((solution, residual, solver))
}

/// Conjugate gradients for all columns, with the most steps a column took; `None` when a
/// diagonal block is not positive definite or a column does not converge.
fn iterate(
    a: &SymmetricBlocks,
    rhs: &[f64],
    columns: usize,
    stop: &Stopping,
) -> Option<(Vec<f64>, usize)> {
    let preconditioner = BlockJacobi::new(a)?;
    let out = conjugate_gradient(a, &preconditioner, rhs, columns, stop);
    let steps = out.iter().map(|c| c.steps).max().unwrap_or(0);
    out.iter()
        .all(|c| c.converged(stop))
        .then(|| (out.into_iter().flat_map(|c| c.solution).collect(), steps))
}

#[cfg(test)]
mod tests;
