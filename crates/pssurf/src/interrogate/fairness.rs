//! Fairness numbers: integrals of curvature over the surface and the distribution of each
//! curvature quantity, so that two surfaces can be compared with numbers.

use rayon::prelude::*;

use super::curvature::{Curvature, CurvatureQuantity};
use crate::surface::{PieceRule, PiecewiseSurface};

/// The default polynomial degree for which the per-piece quadrature is exact.
///
/// The integrands (H², K, … times the area element) are rational or algebraic functions of
/// the parameters, so no finite rule is exact; degree 12 (49 nodes per piece) gives about
/// 10 correct digits on surfaces whose pieces are not much more curved than they are large.
pub const DEFAULT_QUADRATURE_DEGREE: usize = 12;

/// Integrals over the surface, by Gauss quadrature on every piece (a PS sub-triangle, a
/// Bézier triangle, a rectangle of a tensor-product surface).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct FairnessIntegrals {
    /// The area ∫ dA, with dA = |s_u × s_v| du dv (length²).
    pub area: f64,
    /// ∫ H² dA, the Willmore-type bending energy (dimensionless).
    pub mean_squared: f64,
    /// ∫ K dA, the total Gaussian curvature (dimensionless; by Gauss–Bonnet it depends only
    /// on the boundary and topology).
    pub gaussian: f64,
    /// ∫ |K| dA, the total absolute curvature (dimensionless).
    pub gaussian_abs: f64,
    /// ∫ (κ1² + κ2²) dA = ∫ (4H² − 2K) dA (dimensionless).
    pub principal_squared: f64,
    /// The thin-plate energy ∫∫ (|s_uu|² + 2 |s_uv|² + |s_vv|²) du dv over the parameter
    /// domain (depends on the parametrisation; for a graph it is the usual
    /// ∫∫ f_xx² + 2 f_xy² + f_yy²).
    pub thin_plate: f64,
}

/// The area-weighted distribution of one curvature quantity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct QuantityStats {
    /// The smallest value at a quadrature node.
    pub min: f64,
    /// The largest value at a quadrature node.
    pub max: f64,
    /// The area-weighted mean (∫ q dA / ∫ dA).
    pub mean: f64,
    /// Area-weighted percentiles 1, 5, 50, 95, 99.
    pub percentiles: [f64; 5],
}

/// The percentiles reported in [`QuantityStats::percentiles`].
pub const PERCENTILES: [f64; 5] = [1.0, 5.0, 50.0, 95.0, 99.0];

/// Fairness numbers of a surface.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct Fairness {
    /// The integrals.
    pub integrals: FairnessIntegrals,
    /// The distribution of K, H, κ1, κ2, κabs, in the order of [`CurvatureQuantity::ALL`].
    pub stats: Vec<(String, QuantityStats)>,
    /// Quadrature nodes where the surface is singular (left out of everything).
    pub singular_nodes: usize,
    /// The number of quadrature nodes used.
    pub nodes: usize,
}

/// One quadrature node's contribution.
#[derive(Clone, Copy)]
struct Node {
    weight: f64,
    values: [f64; 5],
}

/// The fairness numbers of `surface`, with a per-piece quadrature rule exact for polynomials
/// of total degree `degree` (see [`DEFAULT_QUADRATURE_DEGREE`]).
pub fn fairness<S: PiecewiseSurface + ?Sized>(surface: &S, degree: usize) -> Fairness {
    let rule = PieceRule::exact_for(degree);
    let per_patch: Vec<(FairnessIntegrals, Vec<Node>, usize)> = (0..surface.piece_count())
        .into_par_iter()
        .map(|k| integrate_patch(surface, k, &rule, true))
        .collect();
    let mut integrals = FairnessIntegrals::default();
    let mut nodes = Vec::with_capacity(per_patch.iter().map(|p| p.1.len()).sum());
    let mut singular_nodes = 0;
    for (i, n, s) in per_patch {
        integrals.add(&i);
        nodes.extend(n);
        singular_nodes += s;
    }
    let count = nodes.len() + singular_nodes;
    let stats = CurvatureQuantity::ALL
        .iter()
        .enumerate()
        .map(|(q, quantity)| {
            (
                quantity.short_name().to_string(),
                distribution(&mut nodes, q),
            )
        })
        .collect();
    Fairness {
        integrals,
        stats,
        singular_nodes,
        nodes: count,
    }
}

/// The integrals of [`fairness`] alone, without the distributions: nothing is kept per
/// quadrature node (the distributions keep 48 bytes per node, about 30 kB per vertex of a PS
/// surface at the default degree; the hole-filling report of a 132k-vertex patch needed 8 GB).
pub fn fairness_integrals<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    degree: usize,
) -> FairnessIntegrals {
    let rule = PieceRule::exact_for(degree);
    let per_patch: Vec<FairnessIntegrals> = (0..surface.piece_count())
        .into_par_iter()
        .map(|k| integrate_patch(surface, k, &rule, false).0)
        .collect();
    let mut integrals = FairnessIntegrals::default();
    for i in &per_patch {
        integrals.add(i);
    }
    integrals
}

impl FairnessIntegrals {
    /// Adds the integrals over another part of the surface.
    fn add(&mut self, other: &FairnessIntegrals) {
        self.area += other.area;
        self.mean_squared += other.mean_squared;
        self.gaussian += other.gaussian;
        self.gaussian_abs += other.gaussian_abs;
        self.principal_squared += other.principal_squared;
        self.thin_plate += other.thin_plate;
    }
}

/// The integrals over piece `k`, its quadrature nodes (when `keep_nodes`) and the number of
/// singular nodes.
fn integrate_patch<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    k: usize,
    rule: &PieceRule,
    keep_nodes: bool,
) -> (FairnessIntegrals, Vec<Node>, usize) {
    let quadrature = surface
        .piece_quadrature(k, rule)
        .expect("pieces of a valid surface are non-degenerate");
    let mut out = FairnessIntegrals::default();
    let mut nodes = Vec::with_capacity(if keep_nodes { quadrature.len() } else { 0 });
    let mut singular = 0;
    for q in &quadrature {
        let j = surface.piece_jet(k, &q.point);
        let w_param = q.weight;
        out.thin_plate +=
            w_param * (j.dxx.norm_squared() + 2.0 * j.dxy.norm_squared() + j.dyy.norm_squared());
        let Ok(c) = Curvature::from_jet(&j) else {
            singular += 1;
            continue;
        };
        let da = w_param * j.dx.cross(&j.dy).norm();
        out.area += da;
        out.mean_squared += da * c.mean * c.mean;
        out.gaussian += da * c.gaussian;
        out.gaussian_abs += da * c.gaussian.abs();
        out.principal_squared += da * (c.k1 * c.k1 + c.k2 * c.k2);
        if keep_nodes {
            nodes.push(Node {
                weight: da,
                values: CurvatureQuantity::ALL.map(|q| c.get(q)),
            });
        }
    }
    (out, nodes, singular)
}

/// Min, max, mean and area-weighted percentiles of quantity `q` over the nodes.
fn distribution(nodes: &mut [Node], q: usize) -> QuantityStats {
    if nodes.is_empty() {
        return QuantityStats {
            min: f64::NAN,
            max: f64::NAN,
            mean: f64::NAN,
            percentiles: [f64::NAN; 5],
        };
    }
    nodes.par_sort_unstable_by(|a, b| a.values[q].total_cmp(&b.values[q]));
    let total: f64 = nodes.iter().map(|n| n.weight).sum();
    let mean = nodes.iter().map(|n| n.weight * n.values[q]).sum::<f64>() / total;
    let mut percentiles = [0.0; 5];
    let mut acc = 0.0;
    let mut next = 0;
    for n in nodes.iter() {
        acc += n.weight;
        while next < 5 && acc >= PERCENTILES[next] / 100.0 * total {
            percentiles[next] = n.values[q];
            next += 1;
        }
    }
    for p in percentiles.iter_mut().skip(next) {
        *p = nodes[nodes.len() - 1].values[q];
    }
    QuantityStats {
        min: nodes[0].values[q],
        max: nodes[nodes.len() - 1].values[q],
        mean,
        percentiles,
    }
}
