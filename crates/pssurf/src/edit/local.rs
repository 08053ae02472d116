//! Prescribing a curvature at a point by the smallest, smoothest change of the control points
//! near it (issue 16, part 2).
//!
//! The free control points are those of the control groups (PS vertices' control triangles,
//! Bézier or NURBS control points) anchored within the region's radius of the point. Their
//! change y minimises
//!
//!   E(y) = yᵀ (Q + R) y,
//!
//! where Q measures how unevenly the change bends (see `smoothness`: the jumps of its Hessian
//! across the edges of the PS refinement, and the differences of its Hessians over the core of
//! the region; per coordinate, PS kinds) and R a small ridge that grows with the distance from
//! the point (so nearer points move more, and E is positive definite). So the curvature
//! changes evenly around the point and fades out towards the fixed control points, instead of
//! changing on the one piece that holds the point (the thin-plate energy, tried first, did
//! that: a spike in the curvature plot). The constraints are nonlinear: the measure equals the target, and
//! optionally the point and the tangent plane stay. Each iteration linearises them,
//! A (y′ − y) = −r, and takes the minimiser of E under the linearised constraints,
//! y′ = P⁻¹Aᵀ (A P⁻¹ Aᵀ)⁻¹ (A y − r) with P = Q + R (one Cholesky factorisation, k ≤ 6
//! right-hand sides), with a backtracking line search on the residuals. The derivatives of
//! the constraints are central differences in the control coordinates of the few groups that
//! influence the point (three control triangles on a PS surface); the stopping test uses the
//! exact curvature of the surface as edited.
//!
//! Every control point moves along one direction: the surface normal at the point (the
//! height axis for a functional surface), as the paper moves the height of a graph. (Moving
//! all three coordinates was tried first: the cheapest change then reparametrises the surface
//! inside the region, and its curvature plot turns to noise.)
//!
//! An edit is local and keeps the surface's smoothness by construction: only control points
//! move. The surface is left unchanged when the target cannot be reached (the error says how
//! close the iteration came).
//!
//! Torsion is not offered here: the coordinate curves and normal sections of PS surfaces are
//! pieced together from quadratic pieces, so a coordinate curve is a conic piece, planar, with
//! torsion zero wherever it is defined (thesis 2.4); see [`super::graph`] for the paper's
//! twisted curves on polynomial graph surfaces.

use std::collections::HashMap;

use nalgebra::{DMatrix, DVector, Point2, Vector3};
use thiserror::Error;

use crate::bezier::Jet;
use crate::interrogate::Curvature;
use crate::ps::{Energy, PsBasis};
use crate::surface::{
    ControlFreedom, ControlId, ControlNet, ControlPoint, EditError, ParametricSurface, PiecePoint,
    PiecewiseSurface, Surface,
};

/// The weight of the core term of [`smoothness`] against the Hessian jumps, by trace.
const CORE_WEIGHT: f64 = 1.0;

/// The most Gauss–Newton iterations.
const MAX_ITERATIONS: usize = 60;
/// The most free control groups (the dense factorisation grows with their cube).
pub const MAX_FREE_GROUPS: usize = 2000;

/// What to prescribe at the point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Measure {
    /// The normal curvature in the u direction, L / E.
    NormalU,
    /// The normal curvature in the v direction, N / G.
    NormalV,
    /// The larger principal curvature κ1 (the normal curvature in its principal direction).
    K1,
    /// The smaller principal curvature κ2.
    K2,
    /// The Gaussian curvature K = κ1 κ2.
    Gaussian,
    /// The mean curvature H = (κ1 + κ2) / 2.
    Mean,
}

impl Measure {
    /// Every measure.
    pub const ALL: [Measure; 6] = [
        Measure::NormalU,
        Measure::NormalV,
        Measure::K1,
        Measure::K2,
        Measure::Gaussian,
        Measure::Mean,
    ];

    /// The short name used on the command line: ku, kv, k1, k2, K, H.
    pub fn name(self) -> &'static str {
        match self {
            Measure::NormalU => "ku",
            Measure::NormalV => "kv",
            Measure::K1 => "k1",
            Measure::K2 => "k2",
            Measure::Gaussian => "K",
            Measure::Mean => "H",
        }
    }

    /// A longer name for people.
    pub fn description(self) -> &'static str {
        match self {
            Measure::NormalU => "normal curvature in u",
            Measure::NormalV => "normal curvature in v",
            Measure::K1 => "maximum normal curvature k1",
            Measure::K2 => "minimum normal curvature k2",
            Measure::Gaussian => "Gaussian curvature K",
            Measure::Mean => "mean curvature H",
        }
    }

    /// The measure named `s` (see [`Measure::name`]; case matters for K).
    pub fn parse(s: &str) -> Option<Self> {
        Measure::ALL.into_iter().find(|m| m.name() == s)
    }

    /// The measure's value for a surface jet, `None` where the surface is singular.
    pub fn of(self, j: &Jet<Vector3<f64>>) -> Option<f64> {
        let c = Curvature::from_jet(j).ok()?;
        Some(match self {
            Measure::NormalU => c.normal.dot(&j.dxx) / j.dx.norm_squared(),
            Measure::NormalV => c.normal.dot(&j.dyy) / j.dy.norm_squared(),
            Measure::K1 => c.k1,
            Measure::K2 => c.k2,
            Measure::Gaussian => c.gaussian,
            Measure::Mean => c.mean,
        })
    }

    /// Whether the measure has the units of a curvature squared (K) rather than a curvature.
    fn squared(self) -> bool {
        self == Measure::Gaussian
    }
}

/// An edit to make.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EditRequest {
    /// The parameter point.
    pub at: Point2<f64>,
    /// What to prescribe there.
    pub measure: Measure,
    /// Its value.
    pub target: f64,
    /// The region: control groups anchored within this distance of the point (in parameter
    /// units) may move; a radius beyond the domain's diagonal is taken as that diagonal.
    pub radius: f64,
    /// Keep s(at) where it is.
    pub keep_point: bool,
    /// Keep the tangent plane at s(at).
    pub keep_tangent: bool,
}

/// One control point before and after an edit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlChange {
    /// Which.
    pub id: ControlId,
    /// Before the edit.
    pub before: ControlPoint,
    /// After it.
    pub after: ControlPoint,
}

/// A finished edit, as values: apply `after` to redo it and `before` to undo it.
#[derive(Clone, Debug, PartialEq)]
pub struct LocalEdit {
    /// The control points that moved.
    pub changes: Vec<ControlChange>,
    /// The measure prescribed.
    pub measure: Measure,
    /// The value asked for.
    pub target: f64,
    /// The measure before the edit.
    pub before: f64,
    /// The measure after it, from the exact curvature of the edited surface.
    pub after: f64,
    /// Gauss–Newton iterations.
    pub iterations: usize,
    /// Control groups free to move.
    pub free_groups: usize,
    /// The largest distance a control point moved.
    pub largest_move: f64,
    /// The pieces whose shape changed.
    pub pieces: Vec<usize>,
}

impl LocalEdit {
    /// Puts the control points back as they were before the edit.
    pub fn undo(&self, s: &mut impl ControlNet) -> Result<Vec<usize>, EditError> {
        let back: Vec<_> = self.changes.iter().map(|c| (c.id, c.before)).collect();
        s.set_control_points(&back)
    }

    /// Makes the edit again.
    pub fn redo(&self, s: &mut impl ControlNet) -> Result<Vec<usize>, EditError> {
        let again: Vec<_> = self.changes.iter().map(|c| (c.id, c.after)).collect();
        s.set_control_points(&again)
    }

    /// The free control points' ids in the region (for highlighting).
    pub fn ids(&self) -> impl Iterator<Item = ControlId> + '_ {
        self.changes.iter().map(|c| c.id)
    }
}

/// Why an edit was not made (the surface is unchanged).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum LocalEditError {
    /// A request that means nothing.
    #[error("{0}")]
    BadRequest(String),
    /// The point lies outside the domain.
    #[error("the point ({}, {}) lies outside the domain", crate::text::Short(*.0), crate::text::Short(*.1))]
    Outside(f64, f64),
    /// The surface is singular at the point.
    #[error("the surface is singular at the point: its curvature is undefined there")]
    Singular,
    /// No control point that moves the surface at the point lies in the region.
    #[error(
        "no control point that shapes the surface at the point lies within the radius {radius} (the nearest is {} away): give a larger --region",
        crate::text::Significant(*nearest, 6)
    )]
    EmptyRegion {
        /// The radius given.
        radius: f64,
        /// The distance of the nearest control group that influences the point.
        nearest: f64,
    },
    /// The region holds more control groups than the dense solver takes.
    #[error(
        "the region holds {0} control groups; at most {MAX_FREE_GROUPS} can move in one edit: give a smaller --region"
    )]
    TooLarge(usize),
    /// The iteration did not reach the target.
    #[error(
        "{measure} = {target} is out of reach with the control points of this region{keeps}: the closest was {} (from {}); try a larger region or fewer constraints",
        crate::text::Significant(*reached, 8),
        crate::text::Significant(*before, 8)
    )]
    Unreachable {
        /// The measure's description.
        measure: &'static str,
        /// The target.
        target: f64,
        /// The value before.
        before: f64,
        /// The closest value reached.
        reached: f64,
        /// " with the point and tangent plane kept", or empty.
        keeps: String,
    },
    /// The library refused the new control points (an absurd target drove them beyond ±1e60).
    #[error("the edited control points were refused: {0}")]
    Refused(#[from] EditError),
}

impl EditRequest {
    fn check(&self) -> Result<(), LocalEditError> {
        let bad = |m: &str| Err(LocalEditError::BadRequest(m.to_string()));
        if !(self.at.x.is_finite() && self.at.y.is_finite()) {
            return bad("the point must have finite coordinates");
        }
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return bad("the region's radius must be a positive number");
        }
        if !(self.target.is_finite() && self.target.abs() <= 1e30) {
            return bad("the target must be a finite number within ±1e30");
        }
        Ok(())
    }
}

/// The free variables: control coordinates of the groups in the region.
struct Region {
    /// Ids of the free control points, in order; point p has values `p` in each coordinate
    /// block.
    ids: Vec<ControlId>,
    /// Indices (into `ids`) of the points that influence the surface at the point.
    relevant: Vec<usize>,
    /// The distance of each free point's group anchor from the point.
    distance: Vec<f64>,
    /// The free groups' first ids and their index among the free groups.
    groups: Vec<(usize, usize)>,
}

impl Region {
    fn around(s: &Surface, req: &EditRequest, piece: usize) -> Result<Self, LocalEditError> {
        let group_len = s.control_group(ControlId(0)).len().max(1);
        let count = s.control_count() / group_len;
        let anchor_distance =
            |g: usize| (s.control_anchor(ControlId(g * group_len)) - req.at).norm();
        let basis = s.ps_basis().cloned();
        let (candidates, influencing): (Vec<usize>, Vec<usize>) = match &basis {
            Some(b) => {
                let t = b.triangulation();
                let near: Vec<usize> = (0..t.vertex_count())
                    .filter(|&i| (t.vertex(i) - req.at).norm() <= req.radius)
                    .collect();
                (near, t.triangle(piece / 6).to_vec())
            }
            None => {
                let near: Vec<usize> = (0..count)
                    .filter(|&g| anchor_distance(g) <= req.radius)
                    .collect();
                let influencing = near
                    .iter()
                    .copied()
                    .filter(|&g| {
                        s.support(ControlId(g * group_len))
                            .binary_search(&piece)
                            .is_ok()
                    })
                    .collect();
                (near, influencing)
            }
        };
        if candidates.len() > MAX_FREE_GROUPS {
            return Err(LocalEditError::TooLarge(candidates.len()));
        }
        let free: Vec<usize> = candidates;
        let mut relevant_groups: Vec<usize> = influencing
            .iter()
            .copied()
            .filter(|g| free.binary_search(g).is_ok())
            .collect();
        relevant_groups.sort_unstable();
        if relevant_groups.is_empty() {
            let nearest = match &basis {
                Some(b) => influencing
                    .iter()
                    .map(|&i| (b.triangulation().vertex(i) - req.at).norm())
                    .fold(f64::INFINITY, f64::min),
                None => (0..count)
                    .filter(|&g| {
                        s.support(ControlId(g * group_len))
                            .binary_search(&piece)
                            .is_ok()
                    })
                    .map(anchor_distance)
                    .fold(f64::INFINITY, f64::min),
            };
            return Err(LocalEditError::EmptyRegion {
                radius: req.radius,
                nearest,
            });
        }
        let mut ids = Vec::new();
        let mut distance = Vec::new();
        let mut relevant = Vec::new();
        let mut groups = Vec::new();
        for (k, &g) in free.iter().enumerate() {
            groups.push((g * group_len, k));
            let d = anchor_distance(g);
            for j in 0..group_len {
                if relevant_groups.binary_search(&g).is_ok() {
                    relevant.push(ids.len());
                }
                ids.push(ControlId(g * group_len + j));
                distance.push(d);
            }
        }
        Ok(Region {
            ids,
            relevant,
            distance,
            groups,
        })
    }

    fn len(&self) -> usize {
        self.ids.len()
    }
}

/// The energy of the change of the free control values (one coordinate), on the triangles the
/// free vertices influence (zero for surfaces without a PS basis):
///
/// - the jumps of its Hessian across the edges of the PS refinement (`Energy::HessianJumps`),
///   which vanish on quadratics, so the change is smooth where it fades out; and
/// - ten times as much (by trace) of Σ area_k ‖H_k − H_p‖²_F over the pieces k whose centroid
///   lies within half the radius of the point, H_p the Hessian of the change on the point's
///   own piece: the second derivatives change alike over the core of the region.
///
/// A point value of second derivatives is cheap to change by a spike on one piece in any
/// energy of order below three, and the jump energy is only borderline: alone (or the
/// thin-plate energy, tried first) it put the whole change of the curvature on the point's
/// piece. The core term spreads it.
fn smoothness(
    basis: Option<&PsBasis>,
    region: &Region,
    group_len: usize,
    at: Point2<f64>,
    piece: usize,
    radius: f64,
) -> DMatrix<f64> {
    let n = region.len();
    let mut q = DMatrix::zeros(n, n);
    let Some(b) = basis else { return q };
    let tri = b.triangulation();
    let index: HashMap<usize, usize> = region
        .groups
        .iter()
        .map(|&(first, k)| (first / group_len, k))
        .collect();
    let free_value = |vertex: usize, j: usize| index.get(&vertex).map(|&k| k * group_len + j);
    let triangles = tri.molecules_of(index.keys().copied());
    b.local_energy_elements(Energy::HessianJumps, &triangles, |vertices, m| {
        // Element value 3a + j → free value index.
        let local: Vec<Option<usize>> = (0..3 * vertices.len())
            .map(|v| free_value(vertices[v / 3], v % 3))
            .collect();
        for (a, ia) in local.iter().enumerate() {
            let Some(ia) = ia else { continue };
            for (c, ic) in local.iter().enumerate() {
                if let Some(ic) = ic {
                    q[(*ia, *ic)] += m[a][c];
                }
            }
        }
    });
    // The core: Hessians of the pieces near the point against the point's piece.
    let frobenius = [1.0, 2.0, 1.0];
    let hessian_rows = |t: usize, k: usize| -> ([DVector<f64>; 3], f64) {
        let h = b.piece_hessians(t)[k];
        let v = tri.triangle(t);
        let rows = std::array::from_fn(|e| {
            let mut row = DVector::zeros(n);
            for c in 0..3 {
                for j in 0..3 {
                    if let Some(i) = free_value(v[c], j) {
                        row[i] += h.rows[e][3 * c + j];
                    }
                }
            }
            row
        });
        (rows, h.area)
    };
    let (own, _) = hessian_rows(piece / 6, piece % 6);
    let mut core = DMatrix::zeros(n, n);
    for &t in &triangles {
        for (k, sub) in b.refinement().sub_triangles(tri, t).iter().enumerate() {
            let d = (sub.centroid() - at).norm() / radius;
            if d >= 1.0 || 6 * t + k == piece {
                continue;
            }
            // A smooth window: full weight at the point, none at the region's border.
            let window = (1.0 - d * d).powi(2);
            let (rows, area) = hessian_rows(t, k);
            for e in 0..3 {
                let diff = &rows[e] - &own[e];
                core += (&diff * diff.transpose()) * (window * area * frobenius[e]);
            }
        }
    }
    let (tq, tc) = (q.trace(), core.trace());
    if tc > 0.0 {
        q += core * (CORE_WEIGHT * tq.max(tc * 1e-3) / tc);
    }
    q
}

/// The state of one edit.
struct Solver<'a> {
    surface: &'a mut Surface,
    region: Region,
    /// The original control points of the free ids.
    original: Vec<ControlPoint>,
    piece: usize,
    at: PiecePoint,
    req: EditRequest,
    /// The original value, normal and first derivatives at the point.
    start: Jet<Vector3<f64>>,
    normal: Vector3<f64>,
    /// The direction every control point moves in: the normal at the point (the height axis
    /// for a functional surface).
    dir: Vector3<f64>,
    /// Lengths: the free points' extent and the finite-difference step.
    size: f64,
    step: f64,
    /// The Cholesky factor of P (Q + R on control displacements; the identity on bump
    /// coefficients).
    factor: nalgebra::Cholesky<f64, nalgebra::Dyn>,
    /// For PS kinds, the map from the coefficients of the windowed quadratic bump to the free
    /// control points' displacements (see [`bump_shapes`]); `None`: each control point's
    /// displacement is a variable.
    shape: Option<DMatrix<f64>>,
}

/// The map from six bump coefficients to the displacements of the free control values of a PS
/// surface: the change is d(u, v) = w(ρ) Σ_q c_q m_q(x, y) with (x, y) = (uv − at) / radius,
/// ρ = |(x, y)|, the window w = (1 − ρ²)³ (zero with its first two derivatives at the region's
/// border) and m_q ∈ {1, x, y, x², x y, y²}; each vertex's control values are the Hermite
/// coefficients (2.45) of d's value and gradient there, so the PS surface changes by the PS
/// interpolant of d.
fn bump_shapes(basis: &PsBasis, region: &Region, at: Point2<f64>, radius: f64) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(region.len(), 6);
    let tri = basis.triangulation();
    for &(first, k) in &region.groups {
        let i = first / 3;
        let rel = (tri.vertex(i) - at) / radius;
        let (x, y) = (rel.x, rel.y);
        let rho2 = x * x + y * y;
        if rho2 >= 1.0 {
            continue;
        }
        let w = (1.0 - rho2).powi(3);
        // ∂w/∂x, ∂w/∂y in scaled units.
        let wx = -6.0 * x * (1.0 - rho2).powi(2);
        let wy = -6.0 * y * (1.0 - rho2).powi(2);
        let monomials: [(f64, f64, f64); 6] = [
            (1.0, 0.0, 0.0),
            (x, 1.0, 0.0),
            (y, 0.0, 1.0),
            (x * x, 2.0 * x, 0.0),
            (x * y, y, x),
            (y * y, 0.0, 2.0 * y),
        ];
        let map = basis.hermite_map(i);
        for (q, (m, mx, my)) in monomials.into_iter().enumerate() {
            // Value and gradient in (u, v): the scaled derivatives divided by the radius.
            let f = w * m;
            let fu = (wx * m + w * mx) / radius;
            let fv = (wy * m + w * my) / radius;
            for (j, [one, dx, dy]) in map.iter().enumerate() {
                d[(3 * k + j, q)] = one * f + dx * fu + dy * fv;
            }
        }
    }
    d
}

/// What the constraints ask: the measures' targets (one normally; two for the seed of a
/// Gaussian-curvature edit from a flat point).
#[derive(Clone)]
struct Targets(Vec<(Measure, f64)>);

impl<'a> Solver<'a> {
    fn new(surface: &'a mut Surface, req: &EditRequest) -> Result<Self, LocalEditError> {
        let sj = surface
            .jet(req.at)
            .map_err(|_| LocalEditError::Outside(req.at.x, req.at.y))?;
        let piece = sj.piece;
        let at = surface
            .piece_shape(piece)
            .frame()
            .ok_or(LocalEditError::Singular)?
            .at_uv(req.at);
        let start = surface.piece_jet(piece, &at);
        let normal = Curvature::from_jet(&start)
            .map_err(|_| LocalEditError::Singular)?
            .normal;
        let region = Region::around(surface, req, piece)?;
        let original: Vec<ControlPoint> = region
            .ids
            .iter()
            .map(|&id| surface.control_point(id).expect("ids in range"))
            .collect();
        let group_len = surface.control_group(ControlId(0)).len().max(1);
        let basis = surface.ps_basis().cloned();
        let (lo, hi) = original.iter().fold(
            (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(&p.position), hi.sup(&p.position)),
        );
        let size = (hi - lo)
            .norm()
            .max(start.dx.norm() * req.radius)
            .max(1e-300);
        let shape = basis
            .as_deref()
            .filter(|_| group_len == 3)
            .map(|b| bump_shapes(b, &region, req.at, req.radius));
        let p = match &shape {
            Some(d) => DMatrix::identity(d.ncols(), d.ncols()),
            None => {
                let mut p = smoothness(
                    basis.as_deref(),
                    &region,
                    group_len,
                    req.at,
                    piece,
                    req.radius,
                );
                let n = region.len();
                let trace = (0..n).map(|i| p[(i, i)]).sum::<f64>() / n as f64;
                let ridge = if trace > 0.0 { 1e-6 * trace } else { 1.0 };
                for i in 0..n {
                    let d = region.distance[i] / req.radius;
                    p[(i, i)] += ridge * (1.0 + d * d);
                }
                p
            }
        };
        let factor = nalgebra::Cholesky::new(p).ok_or(LocalEditError::Singular)?;
        let dir = match surface.freedom() {
            ControlFreedom::Full => normal,
            ControlFreedom::Height => Vector3::z(),
        };
        Ok(Solver {
            surface,
            region,
            original,
            piece,
            at,
            req: *req,
            start,
            normal,
            dir,
            size,
            step: 1e-6 * size,
            factor,
            shape,
        })
    }

    /// The number of variables: the bump's coefficients, or one displacement along `dir`
    /// per free control point.
    fn vars(&self) -> usize {
        self.shape.as_ref().map_or(self.region.len(), |d| d.ncols())
    }

    /// The control points for the variables y.
    fn points(&self, y: &DVector<f64>) -> Vec<(ControlId, ControlPoint)> {
        let disp = match &self.shape {
            Some(d) => d * y,
            None => y.clone(),
        };
        (0..self.region.len())
            .map(|i| {
                let mut p = self.original[i];
                p.position += self.dir * disp[i];
                (self.region.ids[i], p)
            })
            .collect()
    }

    fn set(&mut self, y: &DVector<f64>) -> Result<(), LocalEditError> {
        let pts = self.points(y);
        self.surface.set_control_points(&pts)?;
        Ok(())
    }

    /// The residuals of the constraints at the surface as it is now, or `None` where it is
    /// singular.
    fn residuals(&self, targets: &Targets) -> Option<Vec<f64>> {
        let j = self.surface.piece_jet(self.piece, &self.at);
        let mut r = Vec::with_capacity(6);
        for &(m, t) in &targets.0 {
            r.push(m.of(&j)? - t);
        }
        if self.req.keep_point {
            // Control points move along `dir` only: the point moves along it too (to first
            // order), so one row keeps it.
            r.push(self.dir.dot(&(j.value - self.start.value)));
        }
        if self.req.keep_tangent {
            r.push(self.normal.dot(&j.dx));
            r.push(self.normal.dot(&j.dy));
        }
        Some(r)
    }

    /// How far the residuals are from zero, each in its own scale.
    fn merit(&self, targets: &Targets, r: &[f64]) -> f64 {
        let k = targets.0.len();
        let mut m = 0.0;
        for (i, &(measure, t)) in targets.0.iter().enumerate() {
            m += r[i].abs() / self.measure_scale(measure, t);
        }
        for x in &r[k..] {
            m += x.abs() / self.size;
        }
        m
    }

    /// The size of a measure's values: |target| or the region's natural curvature.
    fn measure_scale(&self, m: Measure, target: f64) -> f64 {
        let natural = 1.0 / self.size;
        let natural = if m.squared() {
            natural * natural
        } else {
            natural
        };
        target.abs().max(natural)
    }

    fn converged(&self, targets: &Targets, r: &[f64]) -> bool {
        let k = targets.0.len();
        targets
            .0
            .iter()
            .enumerate()
            .all(|(i, &(m, t))| r[i].abs() <= 1e-11 * self.measure_scale(m, t))
            && r[k..].iter().all(|x| x.abs() <= 1e-12 * self.size)
    }

    /// The constraints' Jacobian at y by central differences: in the bump's coefficients, or
    /// in the displacements of the control points that influence the point (one at a time).
    fn jacobian(&mut self, targets: &Targets, y: &DVector<f64>) -> Option<DMatrix<f64>> {
        let rows = self.residuals(targets)?.len();
        let mut a = DMatrix::zeros(rows, self.vars());
        if self.shape.is_some() {
            for q in 0..self.vars() {
                let mut diff = [Vec::new(), Vec::new()];
                for (s, sign) in [1.0, -1.0].into_iter().enumerate() {
                    let mut yq = y.clone();
                    yq[q] += sign * self.step;
                    self.set(&yq).ok()?;
                    diff[s] = self.residuals(targets)?;
                }
                for r in 0..rows {
                    a[(r, q)] = (diff[0][r] - diff[1][r]) / (2.0 * self.step);
                }
            }
            self.set(y).ok()?;
            return Some(a);
        }
        let base = self.points(y);
        for &i in &self.region.relevant.clone() {
            let mut diff = [Vec::new(), Vec::new()];
            for (s, sign) in [1.0, -1.0].into_iter().enumerate() {
                let mut p = base[i].1;
                p.position += self.dir * (sign * self.step);
                self.surface.set_control_points(&[(base[i].0, p)]).ok()?;
                diff[s] = self.residuals(targets)?;
            }
            self.surface.set_control_points(&[base[i]]).ok()?;
            for r in 0..rows {
                a[(r, i)] = (diff[0][r] - diff[1][r]) / (2.0 * self.step);
            }
        }
        Some(a)
    }

    /// P⁻¹ x.
    fn solve_p(&self, x: &DVector<f64>) -> DVector<f64> {
        self.factor.solve(x)
    }

    /// The minimiser of yᵀPy under A y = rhs, or `None` when the constraints are dependent
    /// (a measure that does not change with these control points).
    fn constrained_minimum(&self, a: &DMatrix<f64>, rhs: &DVector<f64>) -> Option<DVector<f64>> {
        let k = a.nrows();
        let pa: Vec<DVector<f64>> = (0..k)
            .map(|r| self.solve_p(&a.row(r).transpose()))
            .collect();
        let mut g = DMatrix::zeros(k, k);
        for r in 0..k {
            for c in 0..k {
                g[(r, c)] = a.row(r).transpose().dot(&pa[c]);
            }
        }
        let diag_max = (0..k).map(|i| g[(i, i)]).fold(0.0f64, f64::max);
        let svd = g.clone().svd(true, true);
        if svd.singular_values.min() <= 1e-13 * diag_max || diag_max <= 0.0 {
            return None;
        }
        let lambda = svd.solve(rhs, 0.0).ok()?;
        Some(
            pa.iter()
                .enumerate()
                .fold(DVector::zeros(self.vars()), |acc, (r, v)| {
                    acc + v * lambda[r]
                }),
        )
    }

    /// Gauss–Newton from y to the targets; returns the last y, whether it converged, and the
    /// iterations used.
    fn iterate(
        &mut self,
        targets: &Targets,
        mut y: DVector<f64>,
    ) -> Result<(DVector<f64>, bool, usize), LocalEditError> {
        self.set(&y)?;
        let mut r = self.residuals(targets).ok_or(LocalEditError::Singular)?;
        for it in 0..MAX_ITERATIONS {
            if self.converged(targets, &r) {
                return Ok((y, true, it));
            }
            let Some(a) = self.jacobian(targets, &y) else {
                return Ok((y, false, it));
            };
            let residual = DVector::from_column_slice(&r);
            // The minimiser of E on the linearised constraints, and the smallest correction
            // from y that satisfies them (Newton on the constraints alone). The first is
            // taken when it reduces the residuals; where the constraints curve too much for
            // it, the second, with backtracking, still converges.
            let rhs = &a * &y - &residual;
            let Some(best) = self.constrained_minimum(&a, &rhs) else {
                return Ok((y, false, it));
            };
            let Some(correction) = self.constrained_minimum(&a, &(-&residual)) else {
                return Ok((y, false, it));
            };
            // The minimiser is taken when it at least halves the residuals. Taking it on any
            // decrease converged linearly where the constraint curves (ku = 1 on z = xy:
            // residuals shrinking by a quarter per step, 1e-9 after the 60 iterations, and
            // the edit reported out of reach); the Newton correction converges
            // quadratically, and the minimiser with a smaller decrease is the last resort.
            let merit = self.merit(targets, &r);
            let mut accepted = false;
            let candidates = std::iter::once((best.clone(), 0.5 * merit))
                .chain(
                    std::iter::successors(Some(1.0), |a| (*a > 1e-6).then_some(a * 0.5))
                        .map(|alpha| (&y + &correction * alpha, merit)),
                )
                .chain(std::iter::once((best, merit)));
            for (trial, below) in candidates {
                self.set(&trial)?;
                if let Some(rt) = self.residuals(targets)
                    && self.merit(targets, &rt) < below
                {
                    y = trial;
                    r = rt;
                    accepted = true;
                    break;
                }
            }
            if !accepted {
                self.set(&y)?;
                return Ok((y, false, it + 1));
            }
        }
        let done = self.converged(targets, &r);
        Ok((y, done, MAX_ITERATIONS))
    }
}

/// A region radius that suits the surface at `at`: 2.5 times the longest edge of the
/// triangle (PS kinds) or piece that holds the point, so that the region holds the control
/// groups of the point's triangle and a ring or two around it. `None` outside the domain.
pub fn default_radius(s: &Surface, at: Point2<f64>) -> Option<f64> {
    let piece = s.jet(at).ok()?.piece;
    let corners = match s.ps_basis() {
        Some(b) => b.triangulation().triangle_geometry(piece / 6).v.to_vec(),
        None => s.piece_shape(piece).corners(),
    };
    let longest = corners
        .iter()
        .flat_map(|a| corners.iter().map(move |b| (a - b).norm()))
        .fold(0.0, f64::max);
    Some(2.5 * longest)
}

/// Prescribes `req.measure = req.target` at `req.at` by moving the control points anchored
/// within `req.radius` (see the module documentation). On success the surface is edited and
/// the edit returned as values; on an error the surface is unchanged.
pub fn edit_locally(surface: &mut Surface, req: &EditRequest) -> Result<LocalEdit, LocalEditError> {
    req.check()?;
    // A radius beyond the domain's extent means the whole domain: the bump's window is
    // scaled to the region, so a radius of 1e308 would flatten its quadratic terms to zero.
    let (lo, hi) = surface.domain_bounds();
    let req = &EditRequest {
        radius: req.radius.min((hi - lo).norm()),
        ..*req
    };
    let mut solver = Solver::new(surface, req)?;
    let before = req
        .measure
        .of(&solver.start)
        .ok_or(LocalEditError::Singular)?;
    let zero = DVector::zeros(solver.vars());
    let main = Targets(vec![(req.measure, req.target)]);
    let mut outcome = solver.iterate(&main, zero.clone());
    let mut iterations = 0;
    let reached_now =
        |solver: &Solver| (req.measure).of(&solver.surface.piece_jet(solver.piece, &solver.at));
    // The value closest to the target over every attempt (the start included), for the
    // message when none reaches it.
    let mut closest = before;
    let note = |closest: &mut f64, v: Option<f64>| {
        if let Some(v) = v.filter(|v| (v - req.target).abs() < (*closest - req.target).abs()) {
            *closest = v;
        }
    };
    // K is quadratic in the second derivatives: at a flat point its gradient vanishes. Seed
    // with normal curvatures in u and v whose product is the target, then go on.
    if req.measure == Measure::Gaussian
        && let Ok((_, false, it)) = &outcome
    {
        iterations += it;
        note(&mut closest, reached_now(&solver));
        let root = req.target.abs().sqrt();
        let seed = Targets(vec![
            (Measure::NormalU, root),
            (Measure::NormalV, root * req.target.signum()),
        ]);
        outcome = match solver.iterate(&seed, zero.clone()) {
            Ok((y, _, it)) => {
                iterations += it;
                solver.iterate(&main, y)
            }
            Err(e) => Err(e),
        };
    }
    let result = outcome.and_then(|(y, done, it)| {
        iterations += it;
        let reached = reached_now(&solver).unwrap_or(f64::NAN);
        note(&mut closest, Some(reached));
        if done {
            Ok((y, reached))
        } else {
            let keeps = match (req.keep_point, req.keep_tangent) {
                (true, true) => " with the point and its tangent plane kept",
                (true, false) => " with the point kept",
                (false, true) => " with the tangent plane kept",
                (false, false) => "",
            };
            Err(LocalEditError::Unreachable {
                measure: req.measure.description(),
                target: req.target,
                before,
                reached: closest,
                keeps: keeps.to_string(),
            })
        }
    });
    match result {
        Ok((y, after)) => {
            let pts = solver.points(&y);
            let pieces = solver.surface.set_control_points(&pts)?;
            let changes: Vec<ControlChange> = pts
                .iter()
                .zip(&solver.original)
                .filter(|((_, a), b)| a != *b)
                .map(|(&(id, after), &before)| ControlChange { id, before, after })
                .collect();
            let largest_move = changes
                .iter()
                .map(|c| (c.after.position - c.before.position).norm())
                .fold(0.0, f64::max);
            Ok(LocalEdit {
                changes,
                measure: req.measure,
                target: req.target,
                before,
                after,
                iterations,
                free_groups: solver.region.groups.len(),
                largest_move,
                pieces,
            })
        }
        Err(e) => {
            let back: Vec<_> = solver
                .region
                .ids
                .iter()
                .copied()
                .zip(solver.original.iter().copied())
                .collect();
            solver
                .surface
                .set_control_points(&back)
                .expect("the original control points are valid");
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests;
