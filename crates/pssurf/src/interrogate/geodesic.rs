//! Geodesics: from a point in a direction, and the shortest one between two points.
//!
//! A geodesic s(u(t), v(t)) parametrised by arc length has no tangential acceleration:
//!
//! ```text
//! u″ + Γ¹₁₁ u′² + 2 Γ¹₁₂ u′v′ + Γ¹₂₂ v′² = 0,   v″ + Γ²₁₁ u′² + 2 Γ²₁₂ u′v′ + Γ²₂₂ v′² = 0
//! ```
//!
//! with the Christoffel symbols Γᵏᵢⱼ = gᵏˡ (s_ij · s_l) of the first fundamental form g. In
//! vector form: (u″, v″) = −g⁻¹ (w·s_u, w·s_v) with w = s_uu u′² + 2 s_uv u′v′ + s_vv v′².
//! Only second derivatives enter, so the equations hold across the pieces of a C¹ surface;
//! they are integrated by the adaptive Dormand–Prince pair of the `ode` module, and after every
//! step (u′, v′) is rescaled to unit speed in space (the equations' first integral).
//!
//! The shortest geodesic between two points is found in three stages, because shooting
//! alone fails when the initial guess is poor: a shortest path on a lattice of the domain
//! (Dijkstra, chords in space as weights), relaxed on the exact surface (each interior point
//! moved, by a Gauss–Newton step, to the middle of its neighbours: the discrete geodesic
//! equation), then polished by shooting (Newton on the start direction and the length,
//! central-difference Jacobian) until the geodesic ends at the target. When the polish does
//! not converge (the geodesic would leave the domain, or the points are conjugate), the
//! relaxed polyline is returned and marked as not exact.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use nalgebra::{Matrix2, Point2, Vector2, Vector3};
use thiserror::Error;

use super::curve::SurfaceCurve;
use super::field_lines::domain_diameter;
use super::ode::{Flow, Halt, Integrator, State};
use crate::surface::{Cursor, ParametricSurface};

/// How geodesics are integrated. Tolerances are relative to the domain's diagonal (for the
/// parameters) and to the curve's length (for steps in space).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeodesicOptions {
    /// The integrator's error per step (relative).
    pub tolerance: f64,
    /// The largest step, as a fraction of the length asked for.
    pub max_step: f64,
    /// The most points.
    pub max_points: usize,
}

impl Default for GeodesicOptions {
    fn default() -> Self {
        GeodesicOptions {
            tolerance: 1e-12,
            max_step: 0.01,
            max_points: 100_000,
        }
    }
}

/// Why a geodesic ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeodesicEnd {
    /// It reached the length asked for.
    Length,
    /// It reached the domain's boundary first.
    Boundary,
    /// It reached a singular point of the surface.
    Singular,
    /// The point limit.
    Limit,
}

/// A traced geodesic.
#[derive(Clone, Debug, PartialEq)]
pub struct Geodesic {
    /// The polyline from the start.
    pub curve: SurfaceCurve,
    /// Its arc length (integrated, not the polyline's).
    pub length: f64,
    /// Why it ended.
    pub end: GeodesicEnd,
}

/// The shortest geodesic found between two points.
#[derive(Clone, Debug, PartialEq)]
pub struct ShortestGeodesic {
    /// The curve from the first point to the second.
    pub curve: SurfaceCurve,
    /// Its length: the integrated arc length when `exact`, else the polyline's.
    pub length: f64,
    /// Whether shooting converged: the curve is a geodesic ending at the target to within
    /// 1e-9 of the smaller of the domain's diagonal and the ends' distance in the domain.
    /// Otherwise it is the relaxed polyline (a discrete geodesic).
    pub exact: bool,
    /// The length of the lattice path it started from (for ends within two lattice cells,
    /// the chord between them in space, which shooting starts from instead).
    pub lattice_length: f64,
    /// The length of the relaxed polyline (the chord for ends within two lattice cells).
    pub relaxed_length: f64,
}

/// Why a geodesic could not be traced.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum GeodesicError {
    /// A point lies outside the domain.
    #[error("the point ({}, {}) lies outside the domain", crate::text::Short(*.0), crate::text::Short(*.1))]
    Outside(f64, f64),
    /// The surface is singular at the start.
    #[error("the surface is singular at ({0}, {1})")]
    Singular(f64, f64),
    /// The direction or length is zero, negative or not finite.
    #[error("the direction must be non-zero and the length positive, both finite")]
    BadInput,
    /// The two points are not joined by a path through the domain's lattice.
    #[error("no path through the domain joins the two points")]
    NoPath,
}

/// The geodesic equations as a flow on (u, v, u′, v′).
struct GeodesicFlow<'a, S: ?Sized> {
    surface: &'a S,
}

impl<S: ParametricSurface + ?Sized> Flow<4> for GeodesicFlow<'_, S> {
    fn slope(&self, y: &State<4>, _: &State<4>, cursor: &mut Cursor) -> Result<State<4>, Halt> {
        let j = self
            .surface
            .jet_with(Point2::new(y[0], y[1]), cursor)
            .map_err(|_| Halt::Outside)?
            .jet;
        let (du, dv) = (y[2], y[3]);
        let g = Matrix2::new(
            j.dx.dot(&j.dx),
            j.dx.dot(&j.dy),
            j.dx.dot(&j.dy),
            j.dy.dot(&j.dy),
        );
        let w = j.dxx * (du * du) + j.dxy * (2.0 * du * dv) + j.dyy * (dv * dv);
        let acc = g.try_inverse().ok_or(Halt::Singular)? * Vector2::new(w.dot(&j.dx), w.dot(&j.dy));
        Ok(State::<4>::new(du, dv, -acc.x, -acc.y))
    }

    fn project(&self, y: &mut State<4>, cursor: &mut Cursor) {
        if let Ok(j) = self.surface.jet_with(Point2::new(y[0], y[1]), cursor) {
            let speed = (j.jet.dx * y[2] + j.jet.dy * y[3]).norm();
            if speed > 0.0 && speed.is_finite() {
                y[2] /= speed;
                y[3] /= speed;
            }
        }
    }
}

/// The geodesic from `start` in the parameter direction `direction`, `length` long in space
/// (or until the domain's boundary).
pub fn geodesic<S: ParametricSurface + ?Sized>(
    surface: &S,
    start: Point2<f64>,
    direction: Vector2<f64>,
    length: f64,
    opts: &GeodesicOptions,
) -> Result<Geodesic, GeodesicError> {
    if !(length > 0.0 && length.is_finite() && direction.iter().all(|x| x.is_finite()))
        || direction.norm() == 0.0
    {
        return Err(GeodesicError::BadInput);
    }
    let mut cursor = surface.cursor_near(start);
    let j = surface
        .jet_with(start, &mut cursor)
        .map_err(|_| GeodesicError::Outside(start.x, start.y))?
        .jet;
    // Only the direction matters: scale it first so that huge components cannot overflow.
    let direction = direction / direction.amax();
    let speed = (j.dx * direction.x + j.dy * direction.y).norm();
    if !(speed > 0.0 && speed.is_finite()) {
        return Err(GeodesicError::Singular(start.x, start.y));
    }
    let d = direction / speed;
    let y0 = State::<4>::new(start.x, start.y, d.x, d.y);
    // Steps are bounded by the length asked for, or by the surface's size when that is
    // smaller: a length far beyond the surface (to run to the boundary) must not make the
    // smallest step longer than the way left to the boundary.
    let size = domain_diameter(surface) * j.dx.norm().max(j.dy.norm());
    let scale = if size > 0.0 && size.is_finite() {
        length.min(size)
    } else {
        length
    };
    Ok(integrate(surface, y0, j.value, length, scale, opts, cursor))
}

fn integrate<S: ParametricSurface + ?Sized>(
    surface: &S,
    mut y: State<4>,
    start_point: Vector3<f64>,
    length: f64,
    scale: f64,
    opts: &GeodesicOptions,
    mut cursor: Cursor,
) -> Geodesic {
    let flow = GeodesicFlow { surface };
    let max_step = opts.max_step * scale;
    let ode = Integrator {
        tolerance: opts.tolerance * domain_diameter(surface),
        min_step: 1e-9 * scale,
        max_step,
    };
    let mut curve = SurfaceCurve {
        uvs: vec![Point2::new(y[0], y[1])],
        points: vec![start_point],
        closed: false,
    };
    let (mut s, mut h) = (0.0, 0.25 * max_step);
    let Ok(mut k) = flow.slope(&y, &y, &mut cursor) else {
        return Geodesic {
            curve,
            length: 0.0,
            end: GeodesicEnd::Singular,
        };
    };
    let end = loop {
        if length - s <= 1e-14 * length {
            break GeodesicEnd::Length;
        }
        if curve.uvs.len() >= opts.max_points {
            break GeodesicEnd::Limit;
        }
        // The last step lands exactly on the length.
        let a = match ode.advance(&flow, &y, &k, h.min(length - s), &mut cursor) {
            Ok(a) => a,
            Err(Halt::Outside) => break GeodesicEnd::Boundary,
            Err(_) => break GeodesicEnd::Singular,
        };
        let uv = Point2::new(a.y[0], a.y[1]);
        let Ok(p) = surface.jet_with(uv, &mut cursor) else {
            break GeodesicEnd::Boundary;
        };
        curve.uvs.push(uv);
        curve.points.push(p.jet.value);
        s += a.taken;
        // After a projection the slope is recomputed at the projected state.
        k = flow.slope(&a.y, &a.slope, &mut cursor).unwrap_or(a.slope);
        (y, h) = (a.y, a.next);
    };
    Geodesic {
        curve,
        length: s,
        end,
    }
}

/// Lattice nodes per side of the domain's bounding box for the first stage.
const LATTICE: usize = 96;
/// Points of the relaxed polyline.
const RELAX_POINTS: usize = 48;

/// The shortest geodesic from `a` to `b` (see the module's notes for the method).
pub fn shortest_geodesic<S: ParametricSurface + ?Sized>(
    surface: &S,
    a: Point2<f64>,
    b: Point2<f64>,
    opts: &GeodesicOptions,
) -> Result<ShortestGeodesic, GeodesicError> {
    for p in [a, b] {
        surface
            .jet(p)
            .map_err(|_| GeodesicError::Outside(p.x, p.y))?;
    }
    if a == b {
        // The shortest curve from a point to itself is the point (shooting has no direction
        // to aim at; it reported "did not converge").
        let point = surface
            .point(a)
            .map_err(|_| GeodesicError::Outside(a.x, a.y))?;
        return Ok(ShortestGeodesic {
            curve: SurfaceCurve {
                points: vec![point],
                uvs: vec![a],
                closed: false,
            },
            length: 0.0,
            exact: true,
            lattice_length: 0.0,
            relaxed_length: 0.0,
        });
    }
    // Points within two lattice cells: the lattice's path is a detour of up to a cell (for
    // points 1e-10 apart on a sphere it was 3e-6 long), so aim straight at the target.
    let chord = polyline_length(surface, &[a, b]);
    if (b - a).norm() < 2.0 * domain_diameter(surface) / LATTICE as f64
        && let Some(g) = shoot(surface, a, b, &[a, b], chord, opts)
    {
        return Ok(ShortestGeodesic {
            length: g.length,
            curve: g.curve,
            exact: true,
            lattice_length: chord,
            relaxed_length: chord,
        });
    }
    let lattice = lattice_path(surface, a, b)?;
    let lattice_length = polyline_length(surface, &lattice);
    let relaxed = relax(surface, &resample(surface, &lattice, RELAX_POINTS));
    let relaxed_length = polyline_length(surface, &relaxed);
    let polished = shoot(surface, a, b, &relaxed, relaxed_length, opts);
    Ok(match polished {
        Some(g) => ShortestGeodesic {
            length: g.length,
            curve: g.curve,
            exact: true,
            lattice_length,
            relaxed_length,
        },
        None => ShortestGeodesic {
            curve: SurfaceCurve {
                points: relaxed
                    .iter()
                    .filter_map(|p| surface.point(*p).ok())
                    .collect(),
                uvs: relaxed,
                closed: false,
            },
            length: relaxed_length,
            exact: false,
            lattice_length,
            relaxed_length,
        },
    })
}

fn polyline_length<S: ParametricSurface + ?Sized>(surface: &S, uvs: &[Point2<f64>]) -> f64 {
    let pts: Vec<Vector3<f64>> = uvs.iter().filter_map(|p| surface.point(*p).ok()).collect();
    pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// A shortest path from `a` to `b` through a lattice of the domain (8 neighbours and the 8
/// knight's moves, so directions are resolved to about 13°), in parameters, ends included.
fn lattice_path<S: ParametricSurface + ?Sized>(
    surface: &S,
    a: Point2<f64>,
    b: Point2<f64>,
) -> Result<Vec<Point2<f64>>, GeodesicError> {
    let (lo, hi) = surface.domain_bounds();
    let n = LATTICE;
    let step = (hi - lo) / (n - 1) as f64;
    let at = |i: usize, j: usize| Point2::new(lo.x + step.x * i as f64, lo.y + step.y * j as f64);
    let mut cursor = surface.cursor_near(a);
    // Node n*n is a, n*n + 1 is b; lattice nodes outside the domain have no point.
    let mut points: Vec<Option<Vector3<f64>>> = (0..n * n)
        .map(|id| {
            let uv = at(id % n, id / n);
            surface.jet_with(uv, &mut cursor).ok().map(|j| j.jet.value)
        })
        .collect();
    points.push(surface.point(a).ok());
    points.push(surface.point(b).ok());
    let uv_of = |id: usize| match id {
        x if x == n * n => a,
        x if x == n * n + 1 => b,
        x => at(x % n, x / n),
    };
    let moves: [(i64, i64); 16] = [
        (1, 0),
        (-1, 0),
        (0, 1),
        (0, -1),
        (1, 1),
        (1, -1),
        (-1, 1),
        (-1, -1),
        (2, 1),
        (2, -1),
        (-2, 1),
        (-2, -1),
        (1, 2),
        (1, -2),
        (-1, 2),
        (-1, -2),
    ];
    // An edge is kept when its midpoint lies in the domain too (non-convex domains).
    let inside = |p: Point2<f64>, c: &mut Cursor| surface.jet_with(p, c).is_ok();
    let cell = |p: Point2<f64>| {
        let f = |x: f64, l: f64, s: f64| (((x - l) / s).floor().max(0.0) as usize).min(n - 2);
        (f(p.x, lo.x, step.x), f(p.y, lo.y, step.y))
    };
    let neighbours = |id: usize, c: &mut Cursor| -> Vec<usize> {
        let mut out = Vec::new();
        let push_cell = |p: Point2<f64>, out: &mut Vec<usize>| {
            let (i, j) = cell(p);
            for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                out.push((j + dj) * n + i + di);
            }
        };
        if id >= n * n {
            push_cell(uv_of(id), &mut out);
            return out;
        }
        let (i, j) = ((id % n) as i64, (id / n) as i64);
        for (di, dj) in moves {
            let (x, y) = (i + di, j + dj);
            if x >= 0 && y >= 0 && x < n as i64 && y < n as i64 {
                out.push(y as usize * n + x as usize);
            }
        }
        let p = uv_of(id);
        for (end, node) in [(a, n * n), (b, n * n + 1)] {
            let (ci, cj) = cell(end);
            if (i - ci as i64).abs() <= 1 && (j - cj as i64).abs() <= 1 {
                out.push(node);
            }
        }
        out.retain(|&q| inside(Point2::from((p.coords + uv_of(q).coords) * 0.5), c));
        out
    };
    let mut dist = vec![f64::INFINITY; n * n + 2];
    let mut prev = vec![usize::MAX; n * n + 2];
    let mut heap = BinaryHeap::new();
    dist[n * n] = 0.0;
    heap.push(Reverse((Ordered(0.0), n * n)));
    while let Some(Reverse((Ordered(d), id))) = heap.pop() {
        if d > dist[id] {
            continue;
        }
        if id == n * n + 1 {
            break;
        }
        let Some(p) = points[id] else { continue };
        for q in neighbours(id, &mut cursor) {
            let Some(pq) = points[q] else { continue };
            let nd = d + (pq - p).norm();
            if nd < dist[q] {
                dist[q] = nd;
                prev[q] = id;
                heap.push(Reverse((Ordered(nd), q)));
            }
        }
    }
    if !dist[n * n + 1].is_finite() {
        return Err(GeodesicError::NoPath);
    }
    let mut path = vec![b];
    let mut id = n * n + 1;
    while prev[id] != usize::MAX {
        id = prev[id];
        path.push(uv_of(id));
    }
    path.reverse();
    Ok(path)
}

/// An f64 ordered for the heap (the distances are finite).
#[derive(Clone, Copy, PartialEq)]
struct Ordered(f64);
impl Eq for Ordered {}
impl PartialOrd for Ordered {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Ordered {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// `m` points along the polyline, evenly spaced in space.
fn resample<S: ParametricSurface + ?Sized>(
    surface: &S,
    uvs: &[Point2<f64>],
    m: usize,
) -> Vec<Point2<f64>> {
    let pts: Vec<Vector3<f64>> = uvs.iter().filter_map(|p| surface.point(*p).ok()).collect();
    let mut acc = vec![0.0];
    for w in pts.windows(2) {
        acc.push(acc.last().unwrap() + (w[1] - w[0]).norm());
    }
    let total = *acc.last().unwrap();
    if uvs.len() < 2 || total <= 0.0 || pts.len() != uvs.len() {
        return uvs.to_vec();
    }
    let mut out = Vec::with_capacity(m);
    let mut seg = 0;
    for i in 0..m {
        let s = total * i as f64 / (m - 1) as f64;
        while seg + 2 < acc.len() && acc[seg + 1] < s {
            seg += 1;
        }
        let len = acc[seg + 1] - acc[seg];
        let t = if len > 0.0 {
            ((s - acc[seg]) / len).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(uvs[seg] + (uvs[seg + 1] - uvs[seg]) * t);
    }
    out
}

/// Relaxes a polyline with fixed ends towards a discrete geodesic: every interior point is
/// moved, by a Gauss–Newton step, to where its image is the midpoint of its neighbours'
/// images (which minimises the sum of squared chords), until the points stop moving.
fn relax<S: ParametricSurface + ?Sized>(surface: &S, uvs: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let mut p = uvs.to_vec();
    let scale = domain_diameter(surface);
    let mut cursor = surface.cursor_near(p[0]);
    for _ in 0..2000 {
        let mut moved: f64 = 0.0;
        for i in 1..p.len().saturating_sub(1) {
            let (Ok(a), Ok(b), Ok(here)) = (
                surface.jet_with(p[i - 1], &mut cursor),
                surface.jet_with(p[i + 1], &mut cursor),
                surface.jet_with(p[i], &mut cursor),
            ) else {
                continue;
            };
            let j = here.jet;
            let target = (a.jet.value + b.jet.value) * 0.5 - j.value;
            let g = Matrix2::new(
                j.dx.dot(&j.dx),
                j.dx.dot(&j.dy),
                j.dx.dot(&j.dy),
                j.dy.dot(&j.dy),
            );
            let Some(step) = g
                .lu()
                .solve(&Vector2::new(target.dot(&j.dx), target.dot(&j.dy)))
            else {
                continue;
            };
            // A step that leaves the domain is halved until it does not.
            let mut t = 1.0;
            while t > 1e-3 && surface.jet_with(p[i] + step * t, &mut cursor).is_err() {
                t *= 0.5;
            }
            if t > 1e-3 {
                p[i] += step * t;
                moved = moved.max((step * t).norm());
            }
        }
        if moved <= 1e-13 * scale {
            break;
        }
    }
    p
}

/// How near the target a shot geodesic must end, relative to the domain's diagonal or to
/// the distance of its ends in the domain, whichever is smaller (a tolerance of the diagonal
/// alone let a geodesic 1e-8 long end 1.5 % short of its target).
const SHOOTING_TOLERANCE: f64 = 1e-9;

/// The distance within which shooting from `a` to `b` counts as reaching `b`:
/// [`SHOOTING_TOLERANCE`] of the smaller of the domain's diagonal `scale` and |b − a|, but
/// not below the rounding of an integrated end point (64 units in the last place of the
/// coordinates: 11 were measured for a geodesic 1e-10 long).
fn shooting_tolerance(a: Point2<f64>, b: Point2<f64>, scale: f64) -> f64 {
    let rounding = 64.0 * f64::EPSILON * a.coords.amax().max(b.coords.amax());
    (SHOOTING_TOLERANCE * scale.min((b - a).norm())).max(rounding)
}

/// Shooting from `a` towards `b`: Newton on (start angle, length) so that the geodesic ends
/// at `b`, from the relaxed polyline's start direction and length.
fn shoot<S: ParametricSurface + ?Sized>(
    surface: &S,
    a: Point2<f64>,
    b: Point2<f64>,
    guide: &[Point2<f64>],
    guess: f64,
    opts: &GeodesicOptions,
) -> Option<Geodesic> {
    let first = *guide.get(1)?;
    let d = first - a;
    let (mut angle, mut length) = (d.y.atan2(d.x), guess);
    let tolerance = shooting_tolerance(a, b, domain_diameter(surface));
    let end = |angle: f64, length: f64| -> Option<(Point2<f64>, Geodesic)> {
        let g = geodesic(
            surface,
            a,
            Vector2::new(angle.cos(), angle.sin()),
            length,
            opts,
        )
        .ok()?;
        (g.end == GeodesicEnd::Length).then(|| (*g.curve.uvs.last().unwrap(), g))
    };
    for _ in 0..30 {
        let (here, g) = end(angle, length)?;
        let miss = here - b;
        // Steps across piece boundaries leave the end noisy at about 1e-10 of the domain.
        if miss.norm() <= tolerance {
            return Some(g);
        }
        let (ha, hl) = (1e-6, 1e-6 * length);
        let da = (end(angle + ha, length)?.0 - end(angle - ha, length)?.0) / (2.0 * ha);
        let dl = (end(angle, length + hl)?.0 - end(angle, length - hl)?.0) / (2.0 * hl);
        let step = Matrix2::from_columns(&[da, dl]).lu().solve(&-miss)?;
        angle += step.x;
        length += step.y;
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
    }
    None
}
