//! The network gradient estimator: the gradients whose edge curves bend as little as
//! possible *beyond the curvature the local fits see*. The quadratic analogue of the
//! minimum-norm network that SciPy's `CloughTocher2DInterpolator` solves for (Nielson 1983,
//! cubic edge curves), made exact on quadratics.
//!
//! On the edge from V_i to V_j (d = V_j − V_i, length L, Δf = f_j − f_i) let s(t), t ∈
//! [0, 1], be the C¹ quadratic spline with its knot at t = ½ and the Hermite data of the two
//! ends (values f_i, f_j and slopes d_i = g_i · d, d_j = g_j · d; the PS-spline along an
//! edge is such a spline with its knot at the edge's split point, thesis 2.30). Its second
//! derivatives on the two halves are
//!
//! s''_L = 4Δf − 3d_i − d_j,  s''_R = −4Δf + d_i + 3d_j,
//!
//! and the energy is Σ_edges ½ L⁻³ [(s''_L − c)² + (s''_R − c)²] — the integral over the
//! network of (the second derivative in arc length − its target)² — with the target
//! c = ½ dᵀ(H_i + H_j) d from the Hessians of the local quadratic fits
//! ([`super::estimate_jets`]). With c = 0 this is Nielson's energy for such edges, which does
//! not reproduce quadratics; with the fitted target both terms vanish on quadratic data
//! (the local fits are exact there), so quadratics are reproduced.
//!
//! The two terms of an edge fix both end slopes along it (their coefficients (−3, −1) and
//! (1, 3) are independent), so the system in the gradients is about as well conditioned as a
//! mass matrix, whatever the number of vertices: it is solved by conjugate gradients with
//! the 2 × 2 diagonal blocks as preconditioner, from the local estimate (21 steps on 100k
//! random points), without a factorisation. With the knot at the PS-spline's own split
//! point r instead of ½, the terms' coefficients become (−(1 + r), −(1 − r)) / r, nearly
//! dependent on the thin triangles of a Delaunay triangulation, and the same system took 87
//! steps.
//!
//! As for [`super::estimate_gradients_jumps`], vertices too close to others keep their local
//! estimate, and an anchor to it keeps the system definite ([`super::anchor`]; the stronger
//! anchors are tried when the iteration does not converge).

use nalgebra::{Matrix2, Vector2};
use rayon::prelude::*;

use super::anchor::{ANCHOR, GlobalGradientError, STRONGER_ANCHORS, close_vertices};
use super::local::{LocalJet, estimate_jets};
use crate::ps::PsBasis;
use crate::sparse::{Block2Matrix, Block2Stopping};
use crate::triangulation::Triangulation;

/// The gradients minimising the network energy of these vertex values (module docs).
pub fn estimate_gradients_global(
    basis: &PsBasis,
    values: &[f64],
) -> Result<Vec<Vector2<f64>>, GlobalGradientError> {
    let jets = estimate_jets(basis.triangulation(), values)?;
    Ok(network_gradients(basis, values, &jets).0)
}

/// [`estimate_gradients_global`] with the local fits known; also returns the anchor used
/// ([`ANCHOR`], the first of [`STRONGER_ANCHORS`] with which the iteration converged, or
/// infinity when none did and the result is the local estimate).
pub(super) fn network_gradients(
    basis: &PsBasis,
    values: &[f64],
    jets: &[LocalJet],
) -> (Vec<Vector2<f64>>, f64) {
    let tri = basis.triangulation();
    assert_eq!(values.len(), tri.vertex_count(), "one value per vertex");
    assert_eq!(jets.len(), tri.vertex_count(), "one local fit per vertex");
    let hessians = target_hessians(tri, jets);
    let network = Network {
        tri,
        values,
        hessians: &hessians,
    };
    let local: Vec<Vector2<f64>> = jets.iter().map(|j| j.gradient).collect();
    let system = network.system(&close_vertices(basis), &local);
    for eta in std::iter::once(ANCHOR).chain(STRONGER_ANCHORS) {
        if let Some(g) = system.solve(eta, &local) {
            let (at_local, local_size) = network.energy(&local);
            let (at_solution, size) = network.energy(&g);
            // The local estimate is itself a minimiser when its energy is no larger (to
            // rounding); where the energy leaves gradients free, the solution only carries
            // rounding multiplied by 1 / ANCHOR.
            if at_local <= at_solution + 64.0 * f64::EPSILON * local_size.max(size) {
                return (local, eta);
            }
            return (g, eta);
        }
    }
    (local, f64::INFINITY)
}

/// The Hessians the targets come from: each vertex's local fit's where the data determine
/// it ([`LocalJet::hessian_determined`]), elsewhere the mean of its neighbours' determined
/// ones (exact, like them, on quadratic data), or its own if it has none.
fn target_hessians(tri: &Triangulation, jets: &[LocalJet]) -> Vec<Matrix2<f64>> {
    (0..jets.len())
        .into_par_iter()
        .with_min_len(1024)
        .map(|i| {
            if jets[i].hessian_determined {
                return jets[i].hessian;
            }
            let (mut sum, mut count) = (Matrix2::zeros(), 0usize);
            for &t in tri.molecule(i) {
                for j in tri.triangle(t as usize) {
                    if j != i && jets[j].hessian_determined {
                        sum += jets[j].hessian;
                        count += 1;
                    }
                }
            }
            if count > 0 {
                sum / count as f64
            } else {
                jets[i].hessian
            }
        })
        .collect()
}

/// The data the energy is made of.
struct Network<'a> {
    tri: &'a Triangulation,
    values: &'a [f64],
    /// The Hessians of the targets ([`target_hessians`]).
    hessians: &'a [Matrix2<f64>],
}

/// The two terms w (α_i (g_i · d) + α_j (g_j · d) − β)² of one edge seen from its end i.
struct EdgeTerms {
    d: Vector2<f64>,
    weight: f64,
    /// (α_i, α_j, β) of each term.
    terms: [[f64; 3]; 2],
}

impl EdgeTerms {
    /// Σ w (term)² at these end gradients, and Σ w (|parts|)² (its rounding scale).
    fn energy(&self, gi: Vector2<f64>, gj: Vector2<f64>) -> (f64, f64) {
        let (si, sj) = (gi.dot(&self.d), gj.dot(&self.d));
        self.terms
            .iter()
            .fold((0.0, 0.0), |(e, size), [a, b, beta]| {
                let rho = a * si + b * sj - beta;
                let parts = (a * si).abs() + (b * sj).abs() + beta.abs();
                (
                    e + self.weight * rho * rho,
                    size + self.weight * parts * parts,
                )
            })
    }
}

impl Network<'_> {
    /// The terms of edge (i, j) with i's slope first (module docs).
    fn edge(&self, i: usize, j: usize) -> EdgeTerms {
        let d = self.tri.vertex(j) - self.tri.vertex(i);
        let length = d.norm();
        let df4 = 4.0 * (self.values[j] - self.values[i]);
        let c = 0.5 * d.dot(&((self.hessians[i] + self.hessians[j]) * d));
        EdgeTerms {
            d,
            weight: 0.5 / (length * length * length),
            terms: [[-3.0, -1.0, c - df4], [1.0, 3.0, c + df4]],
        }
    }

    /// Calls `f(j)` once for each neighbour j of vertex i.
    fn for_neighbours(&self, i: usize, work: &mut Vec<u32>, mut f: impl FnMut(usize)) {
        work.clear();
        for &t in self.tri.molecule(i) {
            work.extend(self.tri.triangle(t as usize).map(|v| v as u32));
        }
        work.sort_unstable();
        work.dedup();
        for &j in work.iter().filter(|&&j| j as usize != i) {
            f(j as usize);
        }
    }

    /// The energy at gradients `g` (without the constant of the values alone), and the
    /// scale of its rounding.
    fn energy(&self, g: &[Vector2<f64>]) -> (f64, f64) {
        (0..g.len())
            .into_par_iter()
            .with_min_len(1024)
            .map_init(Vec::new, |work, i| {
                let mut sum = (0.0, 0.0);
                self.for_neighbours(i, work, |j| {
                    if j > i {
                        let (e, size) = self.edge(i, j).energy(g[i], g[j]);
                        sum = (sum.0 + e, sum.1 + size);
                    }
                });
                sum
            })
            .reduce(|| (0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
    }

    /// The normal equations in the gradients, fixed vertices holding their `local` estimate.
    fn system(&self, fixed: &[bool], local: &[Vector2<f64>]) -> GradientSystem {
        let (matrix, rows) = Block2Matrix::from_rows(self.tri.vertex_count(), |i, off| {
            self.row(i, fixed, local, off)
        });
        let (rhs, stiffness) = rows.into_iter().unzip();
        GradientSystem {
            matrix,
            rhs,
            stiffness,
        }
    }

    /// Row i of the normal equations: its off-diagonal blocks pushed to `off`, its diagonal
    /// block, right-hand side and stiffness (the anchor's scale; zero where the gradient is
    /// fixed).
    fn row(
        &self,
        i: usize,
        fixed: &[bool],
        local: &[Vector2<f64>],
        off: &mut Vec<(u32, Matrix2<f64>)>,
    ) -> (Matrix2<f64>, (Vector2<f64>, f64)) {
        if fixed[i] {
            return (Matrix2::identity(), (local[i], 0.0));
        }
        let mut diagonal = Matrix2::zeros();
        let mut rhs = Vector2::zeros();
        let mut work = Vec::with_capacity(16);
        self.for_neighbours(i, &mut work, |j| {
            let edge = self.edge(i, j);
            let ddt = edge.d * edge.d.transpose();
            let mut coupling = 0.0;
            for [a, b, beta] in edge.terms {
                diagonal += edge.weight * a * a * ddt;
                coupling += edge.weight * a * b;
                rhs += edge.weight * a * beta * edge.d;
            }
            if fixed[j] {
                rhs -= coupling * ddt * local[j];
            } else {
                off.push((j as u32, coupling * ddt));
            }
        });
        (diagonal, (rhs, 0.5 * diagonal.trace()))
    }
}

/// The normal equations A g = b in the gradients, with each vertex's stiffness (the scale of
/// its anchor; zero where the gradient is fixed).
struct GradientSystem {
    matrix: Block2Matrix,
    rhs: Vec<Vector2<f64>>,
    stiffness: Vec<f64>,
}

/// When the iteration stops: at a relative residual of 1e-13 (or the residual's rounding
/// floor), or, not converged, after 1000 steps (the network energy needs 10–40).
const STOP: Block2Stopping = Block2Stopping {
    relative_residual: 1e-13,
    max_steps: 1000,
};

impl GradientSystem {
    /// The solution with the anchor η: (A + η S) g = b + η S g^local, from the local
    /// estimate; `None` when the iteration shows the system not positive definite or does
    /// not converge.
    fn solve(&self, eta: f64, local: &[Vector2<f64>]) -> Option<Vec<Vector2<f64>>> {
        let shift: Vec<f64> = self.stiffness.iter().map(|s| eta * s).collect();
        let b: Vec<Vector2<f64>> = (0..self.rhs.len())
            .map(|i| self.rhs[i] + shift[i] * local[i])
            .collect();
        self.matrix
            .conjugate_gradient(&shift, &b, local.to_vec(), &STOP)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::meshes::catalogue;
    use crate::test_util::*;
    use nalgebra::Point2;

    /// The terms against the C¹ quadratic spline with its knot at ½ built independently from
    /// its Bézier ordinates: b₀ = f_i, b₁ = f_i + d_i/4, b₃ = f_j − d_j/4, b₄ = f_j and
    /// b₂ = (b₁ + b₃)/2, whose second derivatives in t are 8(b₀ − 2b₁ + b₂) and
    /// 8(b₂ − 2b₃ + b₄).
    #[test]
    fn edge_terms_are_the_midpoint_splines_second_derivatives_less_the_target() {
        let mut r = rng(301);
        for _ in 0..500 {
            let tri = Triangulation::new(
                (0..3)
                    .map(|_| Point2::new(uniform(&mut r, -2.0, 2.0), uniform(&mut r, -2.0, 2.0)))
                    .collect(),
                vec![[0, 1, 2]],
            );
            let values: Vec<f64> = (0..3).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
            let hessians: Vec<Matrix2<f64>> = (0..3)
                .map(|_| {
                    let (a, b, c) = (
                        uniform(&mut r, -1.0, 1.0),
                        uniform(&mut r, -1.0, 1.0),
                        uniform(&mut r, -1.0, 1.0),
                    );
                    Matrix2::new(a, b, b, c)
                })
                .collect();
            let network = Network {
                tri: &tri,
                values: &values,
                hessians: &hessians,
            };
            let (i, j) = (0, 2);
            let (gi, gj) = (random_dir(&mut r) * 3.0, random_dir(&mut r) * 3.0);
            let edge = network.edge(i, j);
            let d = tri.vertex(j) - tri.vertex(i);
            let (di, dj) = (gi.dot(&d), gj.dot(&d));
            let b = [
                values[i],
                values[i] + di / 4.0,
                0.0,
                values[j] - dj / 4.0,
                values[j],
            ];
            let b2 = 0.5 * (b[1] + b[3]);
            let second = [
                8.0 * (b[0] - 2.0 * b[1] + b2),
                8.0 * (b2 - 2.0 * b[3] + b[4]),
            ];
            let target = 0.5 * d.dot(&((hessians[i] + hessians[j]) * d));
            for (k, [a, bb, beta]) in edge.terms.iter().enumerate() {
                let rho = a * di + bb * dj - beta;
                let expected = second[k] - target;
                assert!(
                    near(
                        rho,
                        expected,
                        1e-12 * (1.0 + expected.abs() + di.abs() + dj.abs())
                    ),
                    "{rho} {expected}"
                );
            }
            let length = d.norm();
            assert!(near(edge.weight, 0.5 / length.powi(3), 1e-15 * edge.weight));
        }
    }

    /// The solution is a stationary point of the energy plus the anchor, evaluated edge by
    /// edge ([`Network::energy`]) rather than through the assembled rows: along random
    /// directions the central difference of the (quadratic) objective vanishes to rounding.
    #[test]
    fn the_solution_is_stationary_for_the_energy_plus_anchor() {
        for (name, tri) in catalogue(302) {
            let values: Vec<f64> = tri
                .vertices()
                .iter()
                .map(|p| (3.0 * p.x).sin() * (2.0 * p.y).cos() + p.x * p.x * p.y)
                .collect();
            let basis = PsBasis::optimal(tri.clone()).unwrap();
            let jets = estimate_jets(&tri, &values).unwrap();
            let hessians = target_hessians(&tri, &jets);
            let local: Vec<Vector2<f64>> = jets.iter().map(|j| j.gradient).collect();
            let fixed = close_vertices(&basis);
            let network = Network {
                tri: &tri,
                values: &values,
                hessians: &hessians,
            };
            let system = network.system(&fixed, &local);
            let g = system.solve(ANCHOR, &local).expect("converges");
            let objective = |g: &[Vector2<f64>]| {
                let anchor: f64 = (0..g.len())
                    .map(|i| ANCHOR * system.stiffness[i] * (g[i] - local[i]).norm_squared())
                    .sum();
                network.energy(g).0 + anchor
            };
            let mut r = rng(303);
            for _ in 0..5 {
                let v: Vec<Vector2<f64>> = (0..g.len())
                    .map(|i| {
                        if fixed[i] {
                            Vector2::zeros()
                        } else {
                            random_dir(&mut r)
                        }
                    })
                    .collect();
                let h = 1e-3;
                let shifted = |s: f64| -> Vec<Vector2<f64>> {
                    g.iter().zip(&v).map(|(g, v)| g + s * v).collect()
                };
                let slope = (objective(&shifted(h)) - objective(&shifted(-h))) / (2.0 * h);
                let curvature = (objective(&shifted(h)) - 2.0 * objective(&g)
                    + objective(&shifted(-h)))
                    / (h * h);
                let scale = network.energy(&g).1.max(curvature);
                assert!(
                    slope.abs() <= 1e-9 * scale,
                    "{name}: slope {slope:e}, scale {scale:e}"
                );
                assert!(curvature > 0.0, "{name}: curvature {curvature:e}");
            }
        }
    }
}
