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
use crate::sparse::{SparseError, SpdPattern};
use crate::surface::{ControlFreedom, ControlId, ControlNet, ControlPoint, EditError, Surface};

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
    /// E before.
    pub energy_before: f64,
    /// E after.
    pub energy_after: f64,
    /// The control points that moved.
    pub moved: usize,
    /// The largest distance a control point moved.
    pub largest_move: f64,
    /// ‖A c − b‖ / ‖b‖ of the normal equations at the solution.
    pub normal_residual: f64,
}

/// Why a surface could not be faired.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum FairError {
    /// Not a PS kind.
    #[error("fairing works on PS, UPS and NURPS surfaces, not on a {0}")]
    NotPs(&'static str),
    /// A weight that is negative, not finite or beyond 1e12.
    #[error("the weight must be a number from 0 to 1e12, not {0}")]
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
    // Interior values: 3 per interior vertex.
    let mut index = vec![usize::MAX; 3 * n];
    let mut value_of = Vec::new();
    for i in (0..n).filter(|&i| !tri.is_boundary_vertex(i)) {
        for j in 0..3 {
            index[3 * i + j] = value_of.len();
            value_of.push(3 * i + j);
        }
    }
    let m = value_of.len();
    if m == 0 {
        return Err(FairError::NoInterior);
    }
    let q = basis.energy_matrix(opts.energy);
    let (positions, values) = q.lower_entries();
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
    let mut ii_pos = Vec::new();
    let mut ii_val = Vec::new();
    let mut diagonal = 0.0;
    for (&(r, c), &v) in positions.iter().zip(&values) {
        let (ir, ic) = (index[r], index[c]);
        if ir != usize::MAX && ic != usize::MAX {
            ii_pos.push((ir.max(ic), ir.min(ic)));
            ii_val.push(v);
            if ir == ic {
                diagonal += v;
            }
        }
    }
    let sigma = diagonal / m as f64;
    let ridge = opts.weight * if sigma > 0.0 { sigma } else { 1.0 };
    for k in 0..m {
        ii_pos.push((k, k));
        ii_val.push(ridge);
    }
    let pattern = SpdPattern::new(m, &ii_pos).map_err(FairError::Singular)?;
    let factor = pattern.factor(&ii_val).map_err(FairError::Singular)?;
    // A x by the stored entries (lower triangle and its mirror).
    let apply = |x: &[f64]| -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        for (&(r, c), &v) in ii_pos.iter().zip(&ii_val) {
            for b in 0..coords.len() {
                y[b * m + r] += v * x[b * m + c];
                if r != c {
                    y[b * m + c] += v * x[b * m + r];
                }
            }
        }
        y
    };
    // With weight 0 the energy alone is ill-conditioned on meshes with slivers (measured: a
    // residual of 5e-9 on a random Delaunay triangulation): iterative refinement with the same
    // factor brings the normal equations to rounding. With a positive weight the first solve
    // is already there, and the refinement is skipped.
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut solution = factor.solve_many(&rhs, coords.len());
    for _ in 0..3 {
        let r: Vec<f64> = rhs
            .iter()
            .zip(apply(&solution))
            .map(|(b, a)| b - a)
            .collect();
        if norm(&r) <= 1e-13 * norm(&rhs) {
            break;
        }
        let correction = factor.solve_many(&r, coords.len());
        for (x, d) in solution.iter_mut().zip(&correction) {
            *x += d;
        }
    }
    let diff: Vec<f64> = apply(&solution)
        .iter()
        .zip(&rhs)
        .map(|(a, b)| a - b)
        .collect();
    let scale = norm(&rhs).max(1e-300);
    let normal_residual = norm(&diff) / scale;
    // The new control points.
    let mut changes = Vec::new();
    let mut largest_move = 0.0f64;
    for v in 0..3 * n {
        let k = index[v];
        if k == usize::MAX {
            continue;
        }
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
            .sum()
    };
    Ok(Faired {
        energy_before: energy_of(&original),
        energy_after: energy_of(&surface.control_points()),
        moved: changes.len(),
        largest_move,
        normal_residual,
        surface,
    })
}

#[cfg(test)]
mod tests;
