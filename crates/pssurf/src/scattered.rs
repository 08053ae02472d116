//! Scattered data on triangulations: estimating the gradients that Hermite interpolation
//! (2.30) needs when only values are known.

use nalgebra::Vector2;
use rayon::prelude::*;
use thiserror::Error;

use crate::triangulation::Triangulation;

/// The gradient at a vertex could not be estimated (its neighbours are collinear).
#[derive(Clone, Debug, Error, PartialEq)]
#[error("cannot estimate the gradient at vertex {vertex}: its neighbours do not span the plane")]
pub struct GradientError {
    /// The vertex.
    pub vertex: usize,
}

/// How a gradient was estimated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GradientFit {
    /// A quadratic through the vertex value fitted to neighbours up to this ring.
    Quadratic {
        /// The ring of neighbours used (1 = the vertices sharing a triangle).
        rings: usize,
    },
    /// A plane fitted to the neighbours (too few for a quadratic).
    Linear,
}

/// Estimates ∇f at every vertex from values f_i by **local weighted quadratic least squares**:
/// at V_i, the quadratic q(p) = f_i + g·d + ½ dᵀ H d (d = p − V_i) is fitted to the values
/// at the neighbouring vertices with weights 1/|d|, using the first ring of neighbours and
/// widening to the second and third rings when the first does not determine a quadratic
/// (fewer than five points or a singular fit). The estimate g is exact for quadratic data,
/// so the Hermite interpolant of a quadratic reproduces it exactly. Where even three rings
/// cannot determine a quadratic, a plane is fitted.
pub fn estimate_gradients(
    tri: &Triangulation,
    values: &[f64],
) -> Result<Vec<(Vector2<f64>, GradientFit)>, GradientError> {
    assert_eq!(values.len(), tri.vertex_count(), "one value per vertex");
    (0..tri.vertex_count())
        .into_par_iter()
        .with_min_len(512)
        .map_init(Vec::new, |work, i| gradient_at(tri, values, i, work))
        .collect()
}

fn gradient_at(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
    work: &mut Vec<f64>,
) -> Result<(Vector2<f64>, GradientFit), GradientError> {
    let mut ring = vec![i];
    let mut seen = vec![i];
    for rings in 1..=3 {
        ring = next_ring(tri, &ring, &mut seen);
        let nbrs = &seen[1..];
        if nbrs.len() >= 5
            && let Some(g) = fit(tri, values, i, nbrs, true, work)
        {
            return Ok((g, GradientFit::Quadratic { rings }));
        }
    }
    fit(tri, values, i, &seen[1..], false, work)
        .map(|g| (g, GradientFit::Linear))
        .ok_or(GradientError { vertex: i })
}

/// The vertices adjacent to `ring` not yet `seen` (which is extended).
fn next_ring(tri: &Triangulation, ring: &[usize], seen: &mut Vec<usize>) -> Vec<usize> {
    let mut out = Vec::new();
    for &v in ring {
        for &t in tri.molecule(v) {
            for w in tri.triangle(t as usize) {
                if !seen.contains(&w) {
                    seen.push(w);
                    out.push(w);
                }
            }
        }
    }
    out
}

/// Weighted least squares for (g, H) (quadratic) or g (linear), in coordinates scaled by the
/// neighbourhood's size; `None` when the system is (numerically) rank-deficient. Solved by
/// modified Gram–Schmidt on the augmented matrix [A | b] (backward stable for least squares),
/// in the reusable buffer `work` (column-major).
fn fit(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
    nbrs: &[usize],
    quadratic: bool,
    work: &mut Vec<f64>,
) -> Option<Vector2<f64>> {
    let p = tri.vertex(i);
    let h = nbrs
        .iter()
        .map(|&k| (tri.vertex(k) - p).norm())
        .fold(0.0, f64::max);
    let n = if quadratic { 5 } else { 2 };
    let m = nbrs.len();
    work.clear();
    work.resize(m * (n + 1), 0.0);
    for (r, &k) in nbrs.iter().enumerate() {
        let d = (tri.vertex(k) - p) / h;
        let w = 1.0 / d.norm();
        let row = [
            w * d.x,
            w * d.y,
            w * 0.5 * d.x * d.x,
            w * d.x * d.y,
            w * 0.5 * d.y * d.y,
        ];
        for c in 0..n {
            work[c * m + r] = row[c];
        }
        work[n * m + r] = w * (values[k] - values[i]);
    }
    let mut rmat = [[0.0f64; 6]; 5];
    let mut norms = [0.0f64; 5];
    for c in 0..n {
        norms[c] = work[c * m..(c + 1) * m]
            .iter()
            .map(|x| x * x)
            .sum::<f64>()
            .sqrt();
    }
    for j in 0..n {
        let (head, tail) = work.split_at_mut((j + 1) * m);
        let qj = &mut head[j * m..];
        let rjj = qj.iter().map(|x| x * x).sum::<f64>().sqrt();
        // Rank test: the column must keep a fair share of its length after orthogonalising.
        if !(rjj > 1e-9 * norms[j]) {
            return None;
        }
        for x in qj.iter_mut() {
            *x /= rjj;
        }
        rmat[j][j] = rjj;
        for (k, col) in tail.chunks_mut(m).enumerate() {
            let rjk: f64 = qj.iter().zip(col.iter()).map(|(a, b)| a * b).sum();
            for (x, q) in col.iter_mut().zip(qj.iter()) {
                *x -= rjk * q;
            }
            rmat[j][j + 1 + k] = rjk;
        }
    }
    // Back substitution R x = Qᵀ b (the last column of R).
    let mut x = [0.0f64; 5];
    for j in (0..n).rev() {
        let mut s = rmat[j][n];
        for k in j + 1..n {
            s -= rmat[j][k] * x[k];
        }
        x[j] = s / rmat[j][j];
    }
    Some(Vector2::new(x[0], x[1]) / h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::meshes::catalogue;
    use crate::test_util::*;

    #[test]
    fn quadratic_data_gives_exact_gradients() {
        let mut r = rng(70);
        for (name, t) in catalogue(5) {
            let c: [f64; 6] = std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0));
            let f = |x: f64, y: f64| {
                c[0] + c[1] * x + c[2] * y + c[3] * x * x + c[4] * x * y + c[5] * y * y
            };
            let values: Vec<f64> = t.vertices().iter().map(|p| f(p.x, p.y)).collect();
            let g = estimate_gradients(&t, &values).unwrap();
            let (lo, hi) = t.bounds();
            let size = (hi - lo).norm();
            for (i, (gi, kind)) in g.iter().enumerate() {
                let p = t.vertex(i);
                let exact = Vector2::new(
                    c[1] + 2.0 * c[3] * p.x + c[4] * p.y,
                    c[2] + c[4] * p.x + 2.0 * c[5] * p.y,
                );
                assert!(
                    matches!(kind, GradientFit::Quadratic { .. }),
                    "{name}: vertex {i} fell back to {kind:?}"
                );
                assert!(
                    (gi - exact).norm() < 2e-12 * (1.0 + size),
                    "{name}: vertex {i}: {gi:?} vs {exact:?}"
                );
            }
        }
    }
}
