//! The C^r continuity test between patches on neighbouring triangles (Corollary 2.2).

use super::BezierError;
use super::index::multi_indices;
use super::triangle::BezierTriangle;
use crate::vector::Vector;

/// The outcome of a continuity test across the common edge of two patches.
#[derive(Clone, Debug, PartialEq)]
pub struct Continuity {
    /// The largest r for which the patches join C^r (`None`: not even continuous).
    pub order: Option<usize>,
    /// `deviation[r]`: the largest difference between the second patch's ordinates with
    /// λ_apex = r and the first patch's polynomial extended onto the second triangle (2.24).
    pub deviation: Vec<f64>,
}

/// Tests how smoothly `a` and `b` join across their common edge: by (2.23)–(2.24), they are
/// C^r iff b̂_λ = b^{λ1}_{0,λ2,λ3}(σ) for λ1 ≤ r, i.e. iff the first r + 1 rows of `b`'s net,
/// counted from the common edge, equal those of `a`'s polynomial written over `b`'s triangle.
///
/// Row r is compared with tolerance `tol · size · (Σ|σ_i|)^r`, where size is the largest
/// ordinate (at least 1) and σ the barycentric coordinates of `b`'s apex w.r.t. `a`'s triangle:
/// extending `a` onto `b` takes r de Casteljau steps with σ, which amplify rounding by that factor.
///
/// ```
/// use pssurf::bezier::{continuity, BezierError, BezierTriangle};
/// use pssurf::geometry::Triangle2;
/// use nalgebra::Point2;
/// let p = |x, y| Point2::new(x, y);
/// let a = BezierTriangle::from_fn(Triangle2::new(p(0., 0.), p(1., 0.), p(0., 1.)), 2, |_| 1.0);
/// let b = BezierTriangle::from_fn(Triangle2::new(p(5., 5.), p(6., 5.), p(5., 6.)), 2, |_| 1.0);
/// assert!(matches!(continuity(&a, &b, 1e-12), Err(BezierError::NoCommonEdge)));
/// ```
pub fn continuity<V: Vector>(
    a: &BezierTriangle<V>,
    b: &BezierTriangle<V>,
    tol: f64,
) -> Result<Continuity, BezierError> {
    if a.degree() != b.degree() {
        return Err(BezierError::DegreeMismatch(a.degree(), b.degree()));
    }
    let scale = a.domain().diameter().max(b.domain().diameter());
    let same = |p: nalgebra::Point2<f64>, q: nalgebra::Point2<f64>| (p - q).norm() <= 1e-12 * scale;
    let shared: Vec<usize> = (0..3)
        .filter(|&i| a.domain().v.iter().any(|&v| same(v, b.domain().v[i])))
        .collect();
    if shared.len() != 2 {
        return Err(BezierError::NoCommonEdge);
    }
    let apex = (0..3).find(|i| !shared.contains(i)).expect("one apex");
    let extended = a.restrict(*b.domain())?;
    let m = a.degree();
    let size = a
        .points()
        .iter()
        .chain(b.points())
        .map(|p| p.max_abs())
        .fold(1.0, f64::max);
    let mut deviation = vec![0.0; m + 1];
    for (l, (&pb, &pe)) in multi_indices(m).zip(b.points().iter().zip(extended.points())) {
        let r = l[apex];
        deviation[r] = f64::max(deviation[r], (pb - pe).max_abs());
    }
    let sigma = a.bary_map().apply(b.domain().v[apex]);
    let amp = sigma.iter().map(|s| s.abs()).sum::<f64>().max(1.0);
    let order = deviation
        .iter()
        .enumerate()
        .take_while(|&(r, &d)| d <= tol * size * amp.powi(r as i32))
        .count()
        .checked_sub(1);
    Ok(Continuity { order, deviation })
}
