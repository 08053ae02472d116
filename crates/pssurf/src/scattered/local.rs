//! Scattered data on triangulations: estimating the gradients that Hermite interpolation
//! (2.30) needs when only values are known.

use nalgebra::{Matrix2, Vector2};
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
    /// A plane fitted to the neighbours (too few, or too ill-conditioned, for a quadratic).
    Linear,
}

/// Estimates ∇f at every vertex from values f_i by **local weighted quadratic least squares**:
/// at V_i, the quadratic q(p) = f_i + g·d + ½ dᵀ H d (d = p − V_i) is fitted to the values
/// at the neighbouring vertices with weights 1/|d|, using the first ring of neighbours and
/// widening to the second and third rings when the first does not determine a quadratic
/// well (fewer than five points, or a condition number above [`MAX_CONDITION`]: nearly
/// gridded data puts boundary neighbourhoods on two nearly straight lines). The estimate g
/// is exact for quadratic data, so the Hermite interpolant of a quadratic reproduces it
/// exactly. Where even three rings cannot determine a quadratic, a plane is fitted.
pub fn estimate_gradients(
    tri: &Triangulation,
    values: &[f64],
) -> Result<Vec<(Vector2<f64>, GradientFit)>, GradientError> {
    Ok(estimate_jets(tri, values)?
        .into_iter()
        .map(|jet| (jet.gradient, jet.fit))
        .collect())
}

/// The local fit at a vertex: the gradient of [`estimate_gradients`] and the fitted
/// quadratic's Hessian (zero when a plane was fitted).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalJet {
    /// The estimated ∇f.
    pub gradient: Vector2<f64>,
    /// The estimated ∇²f (exact, like the gradient, on quadratic data).
    pub hessian: Matrix2<f64>,
    /// Whether the data determine the Hessian: a quadratic fit none of whose columns is
    /// below [`HESSIAN_COLUMN_FLOOR`] × the largest. (The condition number is that of the
    /// design with unit columns, so it does not see a column made of rounding-size
    /// offsets.)
    pub hessian_determined: bool,
    /// How they were fitted.
    pub fit: GradientFit,
}

/// The smallest norm of a column of a local fit's design (in coordinates scaled by the
/// neighbourhood's size), relative to the largest, with which the fit's Hessian counts as
/// determined ([`LocalJet::hessian_determined`]). At the corner of a grid whose points were
/// moved by 5e-8, every neighbour of the corner lay on the two boundary lines: the column of
/// d_x d_y was made of the offsets alone (1e-7 of the others), the fit passed the condition
/// test, and its ∂²f/∂x∂y was off by 1.5e5.
pub const HESSIAN_COLUMN_FLOOR: f64 = 1e-3;

/// [`estimate_gradients`] with the fitted Hessians.
pub fn estimate_jets(tri: &Triangulation, values: &[f64]) -> Result<Vec<LocalJet>, GradientError> {
    assert_eq!(values.len(), tri.vertex_count(), "one value per vertex");
    (0..tri.vertex_count())
        .into_par_iter()
        .with_min_len(512)
        .map_init(Workspace::default, |work, i| jet_at(tri, values, i, work))
        .collect()
}

/// Buffers reused from vertex to vertex (one per thread): the neighbourhood and the design
/// matrix, so that estimating a gradient allocates nothing once they have grown.
#[derive(Default)]
struct Workspace {
    /// The vertex and its neighbours found so far, the vertex first.
    seen: Vec<usize>,
    /// The ring last added, and the next one being collected.
    ring: Vec<usize>,
    next: Vec<usize>,
    /// The design matrix of the fit (column-major).
    design: Vec<f64>,
}

fn jet_at(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
    work: &mut Workspace,
) -> Result<LocalJet, GradientError> {
    work.seen.clear();
    work.seen.push(i);
    work.ring.clear();
    work.ring.push(i);
    // The best-conditioned quadratic fit so far, with its rings.
    let mut best: Option<(Fitted, usize)> = None;
    for rings in 1..=3 {
        next_ring(tri, work);
        let nbrs = &work.seen[1..];
        if nbrs.len() < 5 {
            continue;
        }
        if let Some(fitted) = fit(tri, values, i, nbrs, true, &mut work.design) {
            if fitted.condition <= MAX_CONDITION {
                return Ok(fitted.jet(GradientFit::Quadratic { rings }));
            }
            if best.is_none_or(|(b, _)| fitted.condition < b.condition) {
                best = Some((fitted, rings));
            }
        }
    }
    // No neighbourhood is well posed: the best quadratic fit if it is still determined
    // (it keeps quadratics exact), else a plane.
    if let Some((fitted, rings)) = best
        && fitted.condition <= MAX_USABLE_CONDITION
    {
        return Ok(fitted.jet(GradientFit::Quadratic { rings }));
    }
    fit(tri, values, i, &work.seen[1..], false, &mut work.design)
        .filter(|fitted| fitted.condition <= MAX_USABLE_CONDITION)
        .map(|fitted| fitted.jet(GradientFit::Linear))
        .ok_or(GradientError { vertex: i })
}

/// One least-squares fit: its derivatives and the condition number of its design matrix.
#[derive(Clone, Copy)]
struct Fitted {
    gradient: Vector2<f64>,
    /// Zero for a plane.
    hessian: Matrix2<f64>,
    hessian_determined: bool,
    condition: f64,
}

impl Fitted {
    fn jet(self, fit: GradientFit) -> LocalJet {
        LocalJet {
            gradient: self.gradient,
            hessian: self.hessian,
            hessian_determined: self.hessian_determined,
            fit,
        }
    }
}

/// Makes the vertices adjacent to `work.ring` not yet `work.seen` the new ring, adding
/// them to `seen`, until `seen` holds [`MAX_NEIGHBOURHOOD`] vertices.
fn next_ring(tri: &Triangulation, work: &mut Workspace) {
    work.next.clear();
    'collect: for &v in &work.ring {
        for &t in tri.molecule(v) {
            for w in tri.triangle(t as usize) {
                if work.seen.len() >= MAX_NEIGHBOURHOOD {
                    break 'collect;
                }
                if !work.seen.contains(&w) {
                    work.seen.push(w);
                    work.next.push(w);
                }
            }
        }
    }
    std::mem::swap(&mut work.ring, &mut work.next);
}

/// The most vertices a local fit uses. Three rings hold about 37 on a Delaunay
/// triangulation of random points; a vertex of high degree (the centre of points on a
/// circle) would otherwise put all its neighbours into the second ring of each of them, and
/// 4000 such points took 105 s (each one's neighbourhood searched and fitted in full).
const MAX_NEIGHBOURHOOD: usize = 128;

/// The largest condition number of a local fit's column-scaled design matrix that counts as
/// well posed. A neighbourhood on two nearly straight grid lines gives ~h/δ for a jitter δ,
/// and the fitted gradient's error grows with it (the O(h³) Taylor remainder of the data is
/// amplified by the condition number), so such fits widen to the next ring instead.
/// Measured: with 1e3 a 20 × 20 grid jittered by 1e-3 still had 70× the error of the plain
/// grid, with 1e2 14× at 3e-3, with 30 at most 1.1× (`tests/fit_robustness.rs`); on the
/// Delaunay triangulations of 250–16000 random points 86–87 % of the first-ring fits pass
/// (88–89 % with 1e3) and the error on Franke's function is unchanged.
pub const MAX_CONDITION: f64 = 30.0;

/// Beyond this condition number a fit is numerically undetermined and not used at all.
pub const MAX_USABLE_CONDITION: f64 = 1e10;

/// Weighted least squares for (g, H) (quadratic) or g (linear), in coordinates scaled by the
/// neighbourhood's size and with unit columns, with the condition number of that design
/// matrix; `None` when a column is zero or exactly dependent. Solved by modified Gram–Schmidt QR on the
/// augmented matrix [A | b] (backward stable for least squares), in the reusable buffer
/// `work` (column-major); the condition number is that of R (A's singular values), from a
/// small SVD.
fn fit(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
    nbrs: &[usize],
    quadratic: bool,
    work: &mut Vec<f64>,
) -> Option<Fitted> {
    let p = tri.vertex(i);
    let h = nbrs
        .iter()
        .map(|&k| (tri.vertex(k) - p).norm())
        .fold(0.0, f64::max);
    let n = if quadratic { 5 } else { 2 };
    let m = nbrs.len();
    if m < n || !(h > 0.0) {
        return None;
    }
    fill_design(tri, values, i, nbrs, h, n, work);
    let norms = unit_columns(work, m, n)?;
    let rmat = gram_schmidt(work, m, n)?;
    let cond = condition(&rmat, n);
    // Back substitution R x = Qᵀ b (the last column of R), then undo the column scaling.
    let mut x = [0.0f64; 5];
    for j in (0..n).rev() {
        let mut s = rmat[j][n];
        for k in j + 1..n {
            s -= rmat[j][k] * x[k];
        }
        x[j] = s / rmat[j][j];
    }
    // Undo the column scaling, then the coordinates' (d = (p − V_i) / h).
    let c: [f64; 5] = std::array::from_fn(|k| x[k] / norms[k]);
    let hessian = if quadratic {
        Matrix2::new(c[2], c[3], c[3], c[4]) / (h * h)
    } else {
        Matrix2::zeros()
    };
    Some(Fitted {
        gradient: Vector2::new(c[0], c[1]) / h,
        hessian,
        hessian_determined: quadratic
            && norms.iter().fold(f64::INFINITY, |a, &b| a.min(b))
                >= HESSIAN_COLUMN_FLOOR * norms.iter().fold(0.0f64, |a, &b| a.max(b)),
        condition: cond,
    })
}

/// The weighted design matrix [A | b] of the local fit at vertex `i` (column-major in
/// `work`): rows w·(d_x, d_y, d_x²/2, d_x d_y, d_y²/2 | f_k − f_i) with d = (V_k − V_i)/h and
/// w = 1/|d|, the first `n` columns of A.
fn fill_design(
    tri: &Triangulation,
    values: &[f64],
    i: usize,
    nbrs: &[usize],
    h: f64,
    n: usize,
    work: &mut Vec<f64>,
) {
    let p = tri.vertex(i);
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
}

/// Scales the first `n` columns of the m-row matrix in `work` to unit length; returns their
/// former lengths, or `None` if one is zero (or not finite).
fn unit_columns(work: &mut [f64], m: usize, n: usize) -> Option<[f64; 5]> {
    let mut norms = [1.0f64; 5];
    for (c, norm) in norms.iter_mut().enumerate().take(n) {
        let col = &mut work[c * m..(c + 1) * m];
        *norm = col.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(*norm > 0.0 && norm.is_finite()) {
            return None;
        }
        col.iter_mut().for_each(|x| *x /= *norm);
    }
    Some(norms)
}

/// Modified Gram–Schmidt on the m × (n + 1) matrix in `work`: R (n rows, n + 1 columns, the
/// last one Qᵀ b). `None` when a column is exactly dependent on the previous ones.
fn gram_schmidt(work: &mut [f64], m: usize, n: usize) -> Option<[[f64; 6]; 5]> {
    let mut rmat = [[0.0f64; 6]; 5];
    for j in 0..n {
        let (head, tail) = work.split_at_mut((j + 1) * m);
        let qj = &mut head[j * m..];
        let rjj = qj.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(rjj > 0.0) {
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
    Some(rmat)
}

/// The 2-norm condition number σ_max/σ_min of the leading n × n block of R (n ≤ 5), or the
/// upper bound ‖R‖_F ‖R⁻¹‖_F when that already shows it at most [`MAX_CONDITION`] (the
/// common case, without an SVD; the bound exceeds the exact value by at most a factor n).
fn condition(rmat: &[[f64; 6]; 5], n: usize) -> f64 {
    let upper = |a: usize, b: usize| {
        if b >= a && a < n && b < n {
            rmat[a][b]
        } else {
            0.0
        }
    };
    let r = nalgebra::Matrix5::from_fn(upper);
    let bound = frobenius_of_inverse(&r, n).map(|inv| r.norm() * inv);
    if bound.is_some_and(|b| b <= MAX_CONDITION) {
        return bound.unwrap_or(f64::INFINITY);
    }
    // The zero rows and columns beyond n add zero singular values: skip them.
    let mut sv: Vec<f64> = r.singular_values().iter().copied().collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    let lo = sv[n - 1];
    if lo > 0.0 { sv[0] / lo } else { f64::INFINITY }
}

/// ‖R⁻¹‖_F of the upper-triangular leading n × n block of `r`, by back substitution
/// (`None` when a diagonal entry is zero).
fn frobenius_of_inverse(r: &nalgebra::Matrix5<f64>, n: usize) -> Option<f64> {
    let mut sum = 0.0;
    for col in 0..n {
        // Column `col` of R⁻¹: solve R x = e_col (x is zero below row col).
        let mut x = [0.0f64; 5];
        for row in (0..=col).rev() {
            let mut s = if row == col { 1.0 } else { 0.0 };
            for k in row + 1..=col {
                s -= r[(row, k)] * x[k];
            }
            if r[(row, row)] == 0.0 {
                return None;
            }
            x[row] = s / r[(row, row)];
            sum += x[row] * x[row];
        }
    }
    Some(sum.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::meshes::catalogue;
    use crate::test_util::*;
    use nalgebra::Point2;

    /// A corner all of whose neighbours lie on the two boundary lines, 1e-9 off them (as
    /// at the corner of a grid whose points were moved by 5e-8, where boundary slivers fan
    /// out of the corner): the column of d_x d_y is made of the offsets alone, so the fit's
    /// ∂²f/∂x∂y is not determined, and is marked so; on random triangulations nearly every
    /// fit's Hessian is.
    #[test]
    fn a_hessian_fitted_from_points_on_two_lines_is_marked_undetermined() {
        let v = [
            (0.0, 0.0),
            (0.1, 3e-9),
            (0.2, 1e-9),
            (0.3, -1e-9),
            (3e-9, 0.1),
            (1e-9, 0.2),
            (-1e-9, 0.3),
        ];
        let tri = Triangulation::new(
            v.iter().map(|&(x, y)| Point2::new(x, y)).collect(),
            vec![[0, 3, 2], [0, 2, 1], [0, 1, 4], [0, 4, 5], [0, 5, 6]],
        );
        let values: Vec<f64> = v
            .iter()
            .map(|&(x, y)| (3.0 * x).sin() * (2.0 * y).cos())
            .collect();
        let jets = estimate_jets(&tri, &values).unwrap();
        assert_eq!(jets[0].fit, GradientFit::Quadratic { rings: 1 });
        assert!(!jets[0].hessian_determined, "{:?}", jets[0]);
        let mut r = rng(72);
        let (mut determined, mut fits) = (0, 0);
        for (_, tri) in catalogue(73) {
            let values: Vec<f64> = (0..tri.vertex_count())
                .map(|_| uniform(&mut r, -1.0, 1.0))
                .collect();
            for jet in estimate_jets(&tri, &values).unwrap() {
                fits += 1;
                determined += usize::from(jet.hessian_determined);
            }
        }
        assert!(determined * 100 >= fits * 95, "{determined} of {fits}");
    }

    #[test]
    fn the_condition_number_is_the_svd_ratio_or_a_bound_below_the_limit() {
        let mut r = rng(71);
        let mut exact_checked = 0;
        for case in 0..2000 {
            let n = if case % 3 == 0 { 2 } else { 5 };
            let mut rmat = [[0.0f64; 6]; 5];
            // Diagonals spread over a random number of decades: conditions from ~1 to ~1e6.
            let spread = uniform(&mut r, 0.0, 6.0);
            for a in 0..n {
                rmat[a][a] = 10f64.powf(-spread * uniform(&mut r, 0.0, 1.0));
                for b in a + 1..n {
                    rmat[a][b] = uniform(&mut r, -1.0, 1.0) * 0.3;
                }
            }
            let full =
                nalgebra::DMatrix::from_fn(n, n, |a, b| if b >= a { rmat[a][b] } else { 0.0 });
            let sv = full.singular_values();
            let exact = sv.max() / sv.min();
            let c = condition(&rmat, n);
            if c <= MAX_CONDITION {
                assert!(c >= exact * (1.0 - 1e-12) && c <= n as f64 * exact * (1.0 + 1e-12));
                assert!(exact <= MAX_CONDITION);
            } else {
                // Numerically singular blocks (σ_min rounds to 0) are infinite both ways.
                assert!(
                    c == exact || (c - exact).abs() <= 1e-9 * exact,
                    "{c} vs {exact}"
                );
                exact_checked += 1;
            }
        }
        assert!(
            exact_checked > 300,
            "only {exact_checked} ill-conditioned cases"
        );
    }

    #[test]
    fn quadratics_are_exact_on_jittered_grids_at_every_jitter() {
        let mut r = rng(72);
        for delta in [0.0, 1e-12, 1e-9, 1e-6, 1e-3] {
            let mut pts = Vec::new();
            for i in 0..12 {
                for j in 0..12 {
                    let inner = (1..11).contains(&i) && (1..11).contains(&j);
                    let jitter = |r: &mut _| {
                        if inner && delta > 0.0 {
                            uniform(r, -delta, delta)
                        } else {
                            0.0
                        }
                    };
                    pts.push(Point2::new(
                        i as f64 / 11.0 + jitter(&mut r),
                        j as f64 / 11.0 + jitter(&mut r),
                    ));
                }
            }
            let t = Triangulation::delaunay(pts).unwrap();
            let c: [f64; 6] = std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0));
            let values: Vec<f64> = t
                .vertices()
                .iter()
                .map(|p| {
                    c[0] + c[1] * p.x
                        + c[2] * p.y
                        + c[3] * p.x * p.x
                        + c[4] * p.x * p.y
                        + c[5] * p.y * p.y
                })
                .collect();
            for (i, (g, kind)) in estimate_gradients(&t, &values).unwrap().iter().enumerate() {
                let p = t.vertex(i);
                let exact = Vector2::new(
                    c[1] + 2.0 * c[3] * p.x + c[4] * p.y,
                    c[2] + c[4] * p.x + 2.0 * c[5] * p.y,
                );
                assert!(
                    matches!(kind, GradientFit::Quadratic { .. }),
                    "δ={delta}: {kind:?}"
                );
                assert!(
                    (g - exact).norm() < 1e-10 * (1.0 + exact.norm()),
                    "δ={delta}: {g} vs {exact}"
                );
            }
        }
    }

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
