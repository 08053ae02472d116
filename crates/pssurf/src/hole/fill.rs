//! The hole-filling algorithm (thesis 5.3): an initial solution on the coarse polygon,
//! refinement steps on its boundary, and the interior by one of the methods of 5.4.
//!
//! [`HoleFill`] holds the state between steps, so that an application can step the iteration
//! one click at a time and look at the patch with any interior method after each step.

use nalgebra::{Point2, Vector2, Vector3};

use super::HoleError;
use super::boundary::HoleBoundary;
use super::fitting::{
    VertexFrame, alpha_mid, beta_by_subdivision, beta_mid, initial_alphas, q, refit_alphas,
};
use super::interior::{Interior, interior};
use crate::ups::grid::NEIGHBORS;
use crate::ups::{Lattice, LatticePoint, LatticePolygon, Ups, UpsGrid};

/// The most refinement steps (a hexagon then has 3·4⁹ + 3·2⁹ + 1 ≈ 788k vertices).
pub const MAX_ITERATIONS: usize = 9;

/// One side of the coarse domain polygon.
#[derive(Clone, Copy, Debug)]
struct Side {
    /// Its first corner, in lattice coordinates of level 0.
    start: LatticePoint,
    /// Its direction (a [`NEIGHBORS`] index).
    dir: usize,
    /// Lattice steps at level 0 (1, or 2 for the long sides of the pentagon).
    steps: usize,
    /// The boundary curve it fits (loop position).
    curve: usize,
}

/// What one step did, for the residual report.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "io", derive(serde::Serialize))]
pub struct IterationRecord {
    /// The refinement level (0: the initial solution).
    pub level: usize,
    /// Vertices of the patch at this level.
    pub vertices: usize,
    /// The largest distance between the patch's edge curves and the given curves at the
    /// middles (the fitting residual (5.16) / 4) and quarter points of the boundary edges,
    /// model units.
    pub max_deviation: f64,
    /// The largest angle between the patch normal and the given normal at the same points,
    /// degrees, away from singular corners (where the surrounding surface has no tangent
    /// plane: [`HoleBoundary::corner_mismatch`]).
    pub max_angle: f64,
    /// Boundary edges whose new vertex came from the fitting equations.
    pub fitted: usize,
    /// Boundary edges already within the tolerance, whose α and β came from subdivision
    /// (5.3.3).
    pub subdivided: usize,
    /// Vertices where a fitting equation had no usable solution and (5.22) or (5.27) was
    /// used instead.
    pub fallbacks: usize,
}

/// A boundary vertex of the patch at the current level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryVertex {
    /// Its domain point.
    pub domain: Point2<f64>,
    /// The curve (loop position) it lies on.
    pub curve: usize,
    /// Its parameter on that curve.
    pub t: f64,
    /// Whether it is a corner of the domain polygon (the start of `curve`).
    pub corner: bool,
}

/// The state of the hole-filling iteration.
pub struct HoleFill {
    boundary: HoleBoundary,
    sides: Vec<Side>,
    level: usize,
    h: f64,
    /// The frames of the boundary vertices in loop order (side by side, corner first).
    frames: Vec<VertexFrame>,
    /// The deviation of each boundary edge (edge k from vertex k to k + 1).
    deviation: Vec<EdgeDeviation>,
    /// Absolute tolerance of positions for the per-edge stopping criterion (5.3.3).
    tolerance: f64,
    /// Tolerance of normal angles (degrees).
    angle_tolerance: f64,
    /// The instant-update patch (subdivided, boundary overwritten at each step).
    instant: Ups<Vector3<f64>>,
    /// The initial solution subdivided to the current level.
    initial: Ups<Vector3<f64>>,
    history: Vec<IterationRecord>,
}

/// The standard lattice polygon for the number of curves (Figure 5.25) and its sides, the
/// two long sides of the pentagon given to the two consecutive curves of largest length.
fn layout(boundary: &HoleBoundary) -> Result<(UpsGrid, Vec<Side>), HoleError> {
    let n = boundary.len();
    let polygon = LatticePolygon::standard(n, 1).map_err(HoleError::Ups)?;
    let v = polygon.vertices().to_vec();
    let lengths: Vec<f64> = (0..n).map(|k| curve_length(boundary, k)).collect();
    let steps: Vec<usize> = (0..n)
        .map(|k| {
            let d = [v[(k + 1) % n][0] - v[k][0], v[(k + 1) % n][1] - v[k][1]];
            d[0].unsigned_abs().max(d[1].unsigned_abs()) as usize
        })
        .collect();
    // Rotate the curves so that the long sides get the longest consecutive curves.
    let weight = |r: usize| -> f64 {
        (0..n)
            .filter(|&k| steps[k] > 1)
            .map(|k| lengths[(k + r) % n])
            .sum()
    };
    let rotation = (0..n)
        .max_by(|&a, &b| weight(a).total_cmp(&weight(b)))
        .unwrap_or(0);
    let sides = (0..n)
        .map(|k| {
            let d = [v[(k + 1) % n][0] - v[k][0], v[(k + 1) % n][1] - v[k][1]];
            let s = steps[k] as i64;
            let dir = NEIGHBORS
                .iter()
                .position(|&u| u == [d[0] / s, d[1] / s])
                .expect("polygon edges lie on grid lines");
            Side {
                start: v[k],
                dir,
                steps: steps[k],
                curve: (k + rotation) % n,
            }
        })
        .collect();
    let lattice = Lattice {
        base: 1.0,
        origin: Point2::origin(),
    };
    let grid = UpsGrid::new(lattice, polygon).map_err(HoleError::Ups)?;
    Ok((grid, sides))
}

/// The length of curve `k`'s polygon through 64 samples.
fn curve_length(b: &HoleBoundary, k: usize) -> f64 {
    let c = &b.curves()[k];
    (0..64)
        .map(|i| (c.point((i + 1) as f64 / 64.0) - c.point(i as f64 / 64.0)).norm())
        .sum()
}

/// The unit domain vector of a [`NEIGHBORS`] direction.
fn direction(dir: usize) -> Vector2<f64> {
    let a = dir as f64 * std::f64::consts::FRAC_PI_3;
    Vector2::new(a.cos(), a.sin())
}

/// How far a boundary edge of the patch is from the data.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct EdgeDeviation {
    /// The largest distance to the given curve (model units).
    distance: f64,
    /// The largest angle between the patch normal and the given normal (degrees).
    angle: f64,
}

/// The deviation of the patch's edge from vertex i to j (frames `fi`, `fj`, domain length h
/// in direction e) from the given curve on [t_i, t_j], at the middle and the two quarter
/// points, to the closest point of the curve and its normal there. The thesis' residual
/// (5.16) compares the middle with the curve point of the same parameter only, where a
/// planar curve is met exactly by the initial solution however far it is elsewhere, and
/// positions only, which a patch can meet with wrong normals (the prism cap's initial
/// solution: 60° off); at equal parameters it also counts a mere difference of
/// parametrisation (the curve's speed against the patch's) as a deviation. So the quarter
/// points, the geometric distance and the normals are checked. Along the edge the cross-boundary derivative is linear
/// between β_i δ_i and β_j δ_j (5.17), and the patch normal is its cross product with the
/// edge curve's tangent.
fn edge_deviation(
    boundary: &HoleBoundary,
    curve: usize,
    (t_i, t_j): (f64, f64),
    (fi, fj): (VertexFrame, VertexFrame),
    e: Vector2<f64>,
    h: f64,
) -> EdgeDeviation {
    // The Bézier points of the edge curve (Figure 5.2): p_i, u_i, r, u_j, p_j.
    let u_i = fi.point + fi.alpha_gamma(e, h) * 0.5;
    let u_j = fj.point - fj.alpha_gamma(e, h) * 0.5;
    let r = (u_i + u_j) * 0.5;
    let (bd_i, bd_j) = (fi.beta_delta(e, h), fj.beta_delta(e, h));
    // (s, position, tangent) at the quarter points and the middle.
    let samples = [
        (0.25, (fi.point + u_i * 2.0 + r) * 0.25, r - fi.point),
        (0.5, r, u_j - u_i),
        (0.75, (r + u_j * 2.0 + fj.point) * 0.25, fj.point - r),
    ];
    let mut d = EdgeDeviation::default();
    for (s, p, tangent) in samples {
        let (t, distance) = boundary.closest(curve, p, t_i + s * (t_j - t_i));
        d.distance = d.distance.max(distance);
        let normal = (bd_i * (1.0 - s) + bd_j * s).cross(&tangent);
        let given = boundary.unit_normal(curve, t);
        if normal.norm() > 0.0 && given.iter().all(|x| x.is_finite()) {
            d.angle = d.angle.max(super::boundary::angle_degrees(normal, given));
        } else {
            d.angle = 180.0;
        }
    }
    d
}

/// The new vertex's α and β on one boundary edge (see [`HoleFill::step`]).
struct NewVertex {
    frame: VertexFrame,
    fallback: bool,
}

impl HoleFill {
    /// The initial solution (5.3.1) for a validated boundary: the α's of every side by
    /// least squares (5.19)–(5.20) (or (5.23) on the pentagon's long sides), with (5.22)
    /// where that fails; corner triangles by (5.11); β's of mid-side vertices by (5.27); the
    /// interior vertex of the pentagon and hexagon by constrained fairing (the general form
    /// of (5.53)). `tolerance` is relative to the model size; `angle_tolerance` is in
    /// degrees.
    pub fn new(
        boundary: HoleBoundary,
        tolerance: f64,
        angle_tolerance: f64,
    ) -> Result<Self, HoleError> {
        if !(tolerance > 0.0 && tolerance < 1.0) {
            return Err(HoleError::BadTolerance(tolerance));
        }
        if !(angle_tolerance > 0.0 && angle_tolerance < 90.0) {
            return Err(HoleError::BadAngleTolerance(angle_tolerance));
        }
        let (grid, sides) = layout(&boundary)?;
        let h = 1.0;
        let n = sides.len();
        let mut alphas: Vec<Vec<f64>> = Vec::with_capacity(n);
        let mut fallbacks = 0;
        for side in &sides {
            let c = side.curve;
            let steps = side.steps;
            let t = |m: f64| m / steps as f64;
            let points: Vec<_> = (0..=steps)
                .map(|m| boundary.curves()[c].point(t(m as f64)))
                .collect();
            let gammas: Vec<_> = (0..=steps)
                .map(|m| boundary.unit_tangent(c, t(m as f64)))
                .collect();
            let qs: Vec<_> = (0..steps)
                .map(|m| {
                    let mid = boundary.curves()[c].point(t(m as f64 + 0.5));
                    q(points[m], mid, points[m + 1])
                })
                .collect();
            let (a, fell_back) = initial_alphas(&points, &gammas, &qs);
            fallbacks += usize::from(fell_back);
            alphas.push(a);
        }
        // Corners first: the mid-side β's need them.
        let corners: Vec<VertexFrame> = (0..n)
            .map(|k| {
                let (side, prev) = (sides[k], sides[(k + n - 1) % n]);
                VertexFrame::corner(
                    boundary.curves()[side.curve].point(0.0),
                    (
                        alphas[k][0],
                        boundary.unit_tangent(side.curve, 0.0),
                        direction(side.dir),
                    ),
                    (
                        *alphas[(k + n - 1) % n].last().expect("α's"),
                        boundary.unit_tangent(prev.curve, 1.0),
                        direction(prev.dir),
                    ),
                    h,
                )
            })
            .collect();
        let mut frames = Vec::new();
        for (k, side) in sides.iter().enumerate() {
            frames.push(corners[k]);
            let e = direction(side.dir);
            for m in 1..side.steps {
                let t = m as f64 / side.steps as f64;
                let c = side.curve;
                let delta = boundary.cross_tangent(c, t);
                let beta = beta_by_subdivision(
                    delta,
                    corners[k].beta_delta(e, h),
                    corners[(k + 1) % n].beta_delta(e, h),
                );
                frames.push(VertexFrame::inner(
                    boundary.curves()[c].point(t),
                    (alphas[k][m], boundary.unit_tangent(c, t)),
                    (beta, delta),
                    e,
                    h,
                ));
            }
        }
        let mut fill = HoleFill {
            sides,
            level: 0,
            h,
            deviation: Vec::new(),
            tolerance: tolerance * boundary.size(),
            angle_tolerance,
            boundary,
            instant: Ups::new(grid.clone(), vec![[Vector3::zeros(); 3]; grid.slots()])
                .map_err(HoleError::Ups)?,
            initial: Ups::new(grid.clone(), vec![[Vector3::zeros(); 3]; grid.slots()])
                .map_err(HoleError::Ups)?,
            frames,
            history: Vec::new(),
        };
        fill.deviation = fill.edge_deviations();
        fill.write_boundary();
        fill.initial = super::interior::fair_interior(&fill.instant)?;
        fill.instant = fill.initial.clone();
        fill.history.push(IterationRecord {
            level: 0,
            vertices: grid.vertex_count(),
            max_deviation: fill.max_deviation(),
            max_angle: fill.max_regular_angle(),
            fitted: fill.deviation.len(),
            subdivided: 0,
            fallbacks,
        });
        Ok(fill)
    }

    /// The boundary.
    pub fn boundary(&self) -> &HoleBoundary {
        &self.boundary
    }

    /// The current refinement level.
    pub fn level(&self) -> usize {
        self.level
    }

    /// The lattice base at the current level.
    pub fn base(&self) -> f64 {
        self.h
    }

    /// The residual of every step so far (level 0 first).
    pub fn history(&self) -> &[IterationRecord] {
        &self.history
    }

    /// The largest distance to the curves at the middles and quarter points of the current
    /// boundary edges.
    pub fn max_deviation(&self) -> f64 {
        self.deviation
            .iter()
            .map(|d| d.distance)
            .fold(0.0, f64::max)
    }

    /// The largest normal angle (degrees) at the same points.
    pub fn max_angle(&self) -> f64 {
        self.deviation.iter().map(|d| d.angle).fold(0.0, f64::max)
    }

    /// Whether boundary edge `k` is within both tolerances. The angle is not asked for on
    /// the edges at a singular corner (see [`Self::singular_corner_edge`]).
    fn edge_within(&self, k: usize) -> bool {
        let d = self.deviation[k];
        d.distance <= self.tolerance
            && (d.angle <= self.angle_tolerance || self.singular_corner_edge(k))
    }

    /// Whether boundary edge `k` (current level) touches a singular corner
    /// ([`HoleBoundary::is_singular_corner`]): there the normals cannot be met on that edge
    /// at any level.
    fn singular_corner_edge(&self, k: usize) -> bool {
        let (side, m, steps) = self.loop_vertices()[k];
        let ns = self.sides.len();
        let singular = |s: usize| self.boundary.is_singular_corner(self.sides[s].curve);
        (m == 0 && singular(side)) || (m + 1 == steps && singular((side + 1) % ns))
    }

    /// The largest normal angle (degrees) away from singular corners.
    pub fn max_regular_angle(&self) -> f64 {
        (0..self.deviation.len())
            .filter(|&k| !self.singular_corner_edge(k))
            .map(|k| self.deviation[k].angle)
            .fold(0.0, f64::max)
    }

    /// The absolute tolerance.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Whether every boundary edge is within both tolerances.
    pub fn converged(&self) -> bool {
        (0..self.deviation.len()).all(|k| self.edge_within(k))
    }

    /// The corners of the domain polygon at level 0 (Cartesian), in loop order: side k runs
    /// from corner k to corner k + 1 and fits curve [`Self::side_curve`]`(k)`.
    pub fn domain_corners(&self) -> Vec<Point2<f64>> {
        let lattice = *self.initial_lattice();
        self.sides.iter().map(|s| lattice.point(s.start)).collect()
    }

    /// The boundary vertices at the current level, in loop order.
    pub fn boundary_vertices(&self) -> Vec<BoundaryVertex> {
        let lattice = Lattice {
            base: self.h,
            origin: Point2::origin(),
        };
        self.loop_vertices()
            .into_iter()
            .map(|(side, m, steps)| BoundaryVertex {
                domain: lattice.point(self.lattice_point(side, m)),
                curve: self.sides[side].curve,
                t: m as f64 / steps as f64,
                corner: m == 0,
            })
            .collect()
    }

    /// The number of boundary edges of side k at the current level.
    pub fn side_steps(&self, k: usize) -> usize {
        self.sides[k].steps << self.level
    }

    /// The curve (loop position) that side k fits.
    pub fn side_curve(&self, k: usize) -> usize {
        self.sides[k].curve
    }

    fn initial_lattice(&self) -> &Lattice {
        // Level-0 lattice: base 1 at the origin; refinement keeps the origin.
        const LEVEL0: Lattice = Lattice {
            base: 1.0,
            origin: Point2::new(0.0, 0.0),
        };
        &LEVEL0
    }

    /// The boundary vertices at the current level in loop order: (side, step m, steps N).
    fn loop_vertices(&self) -> Vec<(usize, usize, usize)> {
        let scale = 1usize << self.level;
        self.sides
            .iter()
            .enumerate()
            .flat_map(|(k, s)| {
                let steps = s.steps * scale;
                (0..steps).map(move |m| (k, m, steps))
            })
            .collect()
    }

    /// The lattice point (current level) of a loop vertex.
    fn lattice_point(&self, side: usize, m: usize) -> LatticePoint {
        let s = self.sides[side];
        let scale = 1i64 << self.level;
        let d = NEIGHBORS[s.dir];
        [
            s.start[0] * scale + m as i64 * d[0],
            s.start[1] * scale + m as i64 * d[1],
        ]
    }

    /// Deviation (residual / 4) of every current boundary edge.
    fn edge_deviations(&self) -> Vec<EdgeDeviation> {
        let verts = self.loop_vertices();
        let n = verts.len();
        (0..n)
            .map(|i| {
                let (side, m, steps) = verts[i];
                let s = self.sides[side];
                let e = direction(s.dir);
                let (fi, fj) = (self.frames[i], self.frames[(i + 1) % n]);
                edge_deviation(
                    &self.boundary,
                    s.curve,
                    (m as f64 / steps as f64, (m + 1) as f64 / steps as f64),
                    (fi, fj),
                    e,
                    self.h,
                )
            })
            .collect()
    }

    /// Writes the boundary frames' control triangles into the instant-update patch.
    fn write_boundary(&mut self) {
        let verts = self.loop_vertices();
        let h = self.h;
        for (i, &(side, m, _)) in verts.iter().enumerate() {
            let p = self.lattice_point(side, m);
            let slot = self.instant.grid().slot_of(p).expect("boundary vertex");
            self.instant.blocks_mut()[slot] = self.frames[i].triple(h);
        }
    }

    /// One refinement step (5.3.2): the domain is subdivided, each new boundary vertex gets
    /// α_k by (5.24) and β_k by (5.26) — or from subdivision where its edge was already within
    /// the tolerance (5.3.3) — and then the α's of every vertex on the fitted edges are fitted
    /// again together, side by side (`refit_side_alphas`). The β's and the interpolated
    /// data (position, tangent, normal) of the old vertices are kept. The instant-update patch
    /// is subdivided and its boundary overwritten.
    ///
    /// The thesis keeps the old α's, halved: they were fitted to edges twice as long, and
    /// (5.23) then has one unknown left to absorb their error and the unevenness of the
    /// curve's parameter (the rational quarter circle's t = ¼ lies at 21.6°, not 22.5°). It
    /// does so by bulging the edge: the boundary deviation of a quarter circle went
    /// 0.0031 → 0.0083 → 0.0026 (radius 1), and fell only fourfold per step after.
    pub fn step(&mut self) -> Result<(), HoleError> {
        if self.level >= MAX_ITERATIONS {
            return Err(HoleError::TooManyIterations {
                requested: self.level + 1,
            });
        }
        let old = self.loop_vertices();
        let n_old = old.len();
        let h = 0.5 * self.h;
        let mut frames = Vec::with_capacity(2 * n_old);
        // Per new boundary edge: whether it came from subdivision (its ends' α's are kept).
        let mut held = Vec::with_capacity(2 * n_old);
        let (mut fitted, mut subdivided, mut fallbacks) = (0, 0, 0);
        for (i, &(side, m, steps)) in old.iter().enumerate() {
            let converged = self.edge_within(i);
            let new = self.new_vertex(
                (self.frames[i], self.frames[(i + 1) % n_old]),
                (side, m, steps),
                h,
                converged,
            );
            if converged {
                subdivided += 1;
            } else {
                fitted += 1;
            }
            fallbacks += usize::from(new.fallback);
            frames.push(self.frames[i]);
            frames.push(new.frame);
            held.extend([converged, converged]);
        }
        self.level += 1;
        self.h = h;
        self.frames = frames;
        self.refit_side_alphas(&held);
        self.deviation = self.edge_deviations();
        self.instant = self.instant.subdivide();
        self.initial = self.initial.subdivide();
        self.write_boundary();
        self.history.push(IterationRecord {
            level: self.level,
            vertices: self.instant.grid().vertex_count(),
            max_deviation: self.max_deviation(),
            max_angle: self.max_regular_angle(),
            fitted,
            subdivided,
            fallbacks,
        });
        Ok(())
    }

    /// The frame of the vertex in the middle of the old edge from `fi` to `fj` (step m of
    /// `steps` on `side`), at the new base h.
    fn new_vertex(
        &self,
        (fi, fj): (VertexFrame, VertexFrame),
        (side, m, steps): (usize, usize, usize),
        h: f64,
        converged: bool,
    ) -> NewVertex {
        let s = self.sides[side];
        let c = s.curve;
        let curve = &self.boundary.curves()[c];
        let e = direction(s.dir);
        let steps4 = 4.0 * steps as f64;
        let (t_ik, t_k, t_kj) = (
            (4 * m + 1) as f64 / steps4,
            (4 * m + 2) as f64 / steps4,
            (4 * m + 3) as f64 / steps4,
        );
        let p_k = curve.point(t_k);
        let gamma = self.boundary.unit_tangent(c, t_k);
        let delta = self.boundary.cross_tangent(c, t_k);
        let (ag_i, ag_j) = (fi.alpha_gamma(e, h), fj.alpha_gamma(e, h));
        let (bd_i, bd_j) = (fi.beta_delta(e, h), fj.beta_delta(e, h));
        let q_ik = q(fi.point, curve.point(t_ik), p_k);
        let q_kj = q(p_k, curve.point(t_kj), fj.point);
        // α and β that subdivision of the edge would give.
        let alpha_sub = 0.5 * gamma.dot(&((fj.point - ag_j) - (fi.point + ag_i)));
        let beta_sub = beta_by_subdivision(delta, bd_i, bd_j);
        let (mut alpha, mut beta, mut fallback) = if converged {
            (alpha_sub, beta_sub, false)
        } else {
            let (b, flat) = beta_mid(
                delta,
                bd_i,
                bd_j,
                self.boundary.cross_tangent(c, t_ik),
                self.boundary.cross_tangent(c, t_kj),
            );
            (alpha_mid(gamma, ag_i, ag_j, q_ik, q_kj), b, flat)
        };
        if !(alpha > 0.0) {
            alpha = if alpha_sub > 0.0 {
                alpha_sub
            } else {
                0.25 * (fj.point - fi.point).norm()
            };
            fallback = true;
        }
        if !(beta > 0.0) && beta_sub > 0.0 {
            beta = beta_sub;
            fallback = true;
        }
        NewVertex {
            frame: VertexFrame::inner(p_k, (alpha, gamma), (beta, delta), e, h),
            fallback,
        }
    }

    /// Fits the α's of the boundary vertices at the current level again, side by side, by
    /// least squares on (5.16) for all the side's edges at once ([`refit_alphas`]): the
    /// initial solution's system at this level, started from the α's of (5.24). The ends of
    /// edges that came from subdivision (`held`, per edge in loop order) keep theirs. Only the
    /// α-part of each control triangle changes (A e at inner vertices, the two α's of a
    /// corner), so position, tangent direction and normal at every vertex stay interpolated.
    /// A side whose system gives an α ≤ 0 keeps the α's it had.
    fn refit_side_alphas(&mut self, held: &[bool]) {
        let h = self.h;
        let sides = self.sides.clone();
        let ns = sides.len();
        let n = self.frames.len();
        // Per side: (α_out at its first corner, whether refitted), (α_in at its last, whether …).
        let mut ends = Vec::with_capacity(ns);
        let mut first = 0;
        for side in &sides {
            let steps = side.steps << self.level;
            let (c, e) = (side.curve, direction(side.dir));
            let vertex = |m: usize| (first + m) % n;
            let t = |m: f64| m / steps as f64;
            let gammas: Vec<Vector3<f64>> = (0..=steps)
                .map(|m| self.boundary.unit_tangent(c, t(m as f64)))
                .collect();
            let prior: Vec<f64> = (0..=steps)
                .map(|m| gammas[m].dot(&self.frames[vertex(m)].alpha_gamma(e, h)))
                .collect();
            let qs: Vec<Vector3<f64>> = (0..steps)
                .map(|m| {
                    let mid = self.boundary.curves()[c].point(t(m as f64 + 0.5));
                    q(
                        self.frames[vertex(m)].point,
                        mid,
                        self.frames[vertex(m + 1)].point,
                    )
                })
                .collect();
            let fixed: Vec<bool> = (0..=steps)
                .map(|m| (m > 0 && held[first + m - 1]) || (m < steps && held[first + m]))
                .collect();
            let refit = refit_alphas(&gammas, &qs, &prior, &fixed);
            let changed = refit.is_some();
            let alphas = refit.unwrap_or_else(|| prior.clone());
            for m in 1..steps {
                // A e = (2α/h) γ at an inner vertex; A e⊥ (the β δ) is kept.
                let change = gammas[m] * (2.0 * (alphas[m] - prior[m]) / h);
                let frame = &mut self.frames[first + m];
                frame.dx += change * e.x;
                frame.dy += change * e.y;
            }
            ends.push((
                (alphas[0], changed && !fixed[0]),
                (alphas[steps], changed && !fixed[steps]),
            ));
            first += steps;
        }
        let mut first = 0;
        for k in 0..ns {
            let (side, prev) = (sides[k], sides[(k + ns - 1) % ns]);
            let (out, into) = (ends[k].0, ends[(k + ns - 1) % ns].1);
            if out.1 || into.1 {
                let point = self.frames[first].point;
                self.frames[first] = VertexFrame::corner(
                    point,
                    (
                        out.0,
                        self.boundary.unit_tangent(side.curve, 0.0),
                        direction(side.dir),
                    ),
                    (
                        into.0,
                        self.boundary.unit_tangent(prev.curve, 1.0),
                        direction(prev.dir),
                    ),
                    h,
                );
            }
            first += side.steps << self.level;
        }
    }

    /// Steps until the boundary is within the tolerance (or `max_iterations` steps are done).
    pub fn run_to_tolerance(&mut self, max_iterations: usize) -> Result<(), HoleError> {
        while !self.converged() && self.level < max_iterations {
            self.step()?;
        }
        Ok(())
    }

    /// The patch at the current level with its interior control triangles by `method`
    /// (5.4.2–5.4.3). The boundary control triangles are the same for every method.
    pub fn patch(&self, method: Interior) -> Result<Ups<Vector3<f64>>, HoleError> {
        interior(&self.instant, &self.initial, self.level, method)
    }
}
