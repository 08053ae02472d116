//! Scattered data on triangulations: estimating the gradients that Hermite interpolation
//! (2.30) needs when only values are known.

use nalgebra::{DMatrix, DVector, Vector2};
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
        .map(|i| gradient_at(tri, values, i))
        .collect()
}

fn gradient_at(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
) -> Result<(Vector2<f64>, GradientFit), GradientError> {
    let mut ring = vec![i];
    let mut seen = vec![i];
    for rings in 1..=3 {
        ring = next_ring(tri, &ring, &mut seen);
        let nbrs = &seen[1..];
        if nbrs.len() >= 5
            && let Some(g) = fit(tri, values, i, nbrs, true)
        {
            return Ok((g, GradientFit::Quadratic { rings }));
        }
    }
    fit(tri, values, i, &seen[1..], false)
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
/// neighbourhood's size; `None` when the system is (numerically) rank-deficient.
fn fit(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
    nbrs: &[usize],
    quadratic: bool,
) -> Option<Vector2<f64>> {
    let p = tri.vertex(i);
    let h = nbrs
        .iter()
        .map(|&k| (tri.vertex(k) - p).norm())
        .fold(0.0, f64::max);
    let cols = if quadratic { 5 } else { 2 };
    let mut a = DMatrix::zeros(nbrs.len(), cols);
    let mut b = DVector::zeros(nbrs.len());
    for (r, &k) in nbrs.iter().enumerate() {
        let d = (tri.vertex(k) - p) / h;
        let w = 1.0 / d.norm();
        a[(r, 0)] = w * d.x;
        a[(r, 1)] = w * d.y;
        if quadratic {
            a[(r, 2)] = w * 0.5 * d.x * d.x;
            a[(r, 3)] = w * d.x * d.y;
            a[(r, 4)] = w * 0.5 * d.y * d.y;
        }
        b[r] = w * (values[k] - values[i]);
    }
    let svd = a.svd(true, true);
    let s = &svd.singular_values;
    let (smax, smin) = (s.max(), s.min());
    if !(smin > 1e-9 * smax) {
        return None;
    }
    let x = svd.solve(&b, 0.0).ok()?;
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
