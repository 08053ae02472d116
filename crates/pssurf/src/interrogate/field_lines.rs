//! Lines of curvature and asymptotic lines: integral curves of a line field (a direction
//! without a sign at every point) in the parameter domain.
//!
//! - **Lines of curvature** follow a principal direction (seed 001's "lines of curvature";
//!   the directions are the eigenvectors of the shape operator, [`Curvature`]). The family of
//!   κ1 (the larger curvature) and that of κ2 are orthogonal on the surface; a line never
//!   switches family because the family is chosen by the eigenvalue, not by the direction
//!   nearest the last one. Every slope is oriented like the slope at the start of its step, so
//!   a line never reverses. At an umbilic (κ1 = κ2) the directions are undefined: a line that
//!   reaches one (κ1 − κ2 ≤ `umbilic_tolerance` (|κ1| + |κ2|)) stops there and says so.
//! - **Asymptotic lines** follow the directions of zero normal curvature, which exist where
//!   K < 0: at the angle θ from the first principal direction with tan²θ = −κ1/κ2 (Euler's
//!   formula κ1 cos²θ + κ2 sin²θ = 0, seed 003). The two families are θ and −θ in the frame
//!   (dir1, dir2 = n × dir1), which does not depend on the sign of dir1. A line stops where
//!   the surface stops being hyperbolic (at a parabolic line K = 0 the two families meet).
//!
//! The curves are integrated by the adaptive Dormand–Prince pair of the `ode` module with
//! unit speed in the parameter plane, both ways from the seed, until the domain's boundary,
//! an umbilic, a parabolic line, a length, a point limit, or the start again (a closed line).

use nalgebra::{Point2, Vector2};
use thiserror::Error;

use super::continuation::distance_to_segment;
use super::curvature::Curvature;
use super::curve::SurfaceCurve;
use super::ode::{Flow, Halt, Integrator, State};
use crate::surface::{Cursor, ParametricSurface};

/// Which line field to follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LineFamily {
    /// Lines of curvature along the direction of the larger principal curvature κ1.
    Curvature1,
    /// Lines of curvature along the direction of the smaller principal curvature κ2.
    Curvature2,
    /// Asymptotic lines at the angle +θ from the first principal direction.
    AsymptoticPlus,
    /// Asymptotic lines at the angle −θ from the first principal direction.
    AsymptoticMinus,
}

impl LineFamily {
    /// The two families of lines of curvature.
    pub const CURVATURE: [LineFamily; 2] = [LineFamily::Curvature1, LineFamily::Curvature2];
    /// The two families of asymptotic lines.
    pub const ASYMPTOTIC: [LineFamily; 2] =
        [LineFamily::AsymptoticPlus, LineFamily::AsymptoticMinus];

    /// A short name for reports and files.
    pub fn name(self) -> &'static str {
        match self {
            LineFamily::Curvature1 => "k1-line",
            LineFamily::Curvature2 => "k2-line",
            LineFamily::AsymptoticPlus => "asymptotic+",
            LineFamily::AsymptoticMinus => "asymptotic-",
        }
    }
}

/// How field lines are integrated. Lengths in the parameter plane are relative to the
/// diagonal of the domain's bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldLineOptions {
    /// The integrator's error per step (relative).
    pub tolerance: f64,
    /// The smallest step (relative); steps this small cross curvature jumps.
    pub min_step: f64,
    /// The largest step (relative): how far apart the points of a line may be.
    pub max_step: f64,
    /// The longest line each way from its seed, in space.
    pub length: f64,
    /// The most points each way from the seed.
    pub max_points: usize,
    /// A point with κ1 − κ2 ≤ this × (|κ1| + |κ2|) is treated as an umbilic.
    pub umbilic_tolerance: f64,
}

impl Default for FieldLineOptions {
    fn default() -> Self {
        FieldLineOptions {
            tolerance: 1e-10,
            min_step: 1e-6,
            max_step: 0.02,
            length: f64::INFINITY,
            max_points: 20_000,
            umbilic_tolerance: 1e-3,
        }
    }
}

/// Why a field line ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineEnd {
    /// At the domain's boundary (within the smallest step).
    Boundary,
    /// At an umbilic: the principal directions are undefined there.
    Umbilic,
    /// Where the surface stops being hyperbolic (asymptotic lines).
    Parabolic,
    /// At a singular point of the surface.
    Singular,
    /// It came back to its seed: the line is closed.
    Closed,
    /// The length limit.
    Length,
    /// The point limit.
    Limit,
    /// Too near another line or an earlier turn of itself (evenly spaced seeding).
    Near,
    /// The line field jumps across a piece boundary (curvature is discontinuous there, the
    /// surface being only C¹): the directions on the two sides differ by more than 45°, so
    /// the line has no continuation. Reported rather than bridged.
    Jump,
}

impl LineEnd {
    /// A short name for reports.
    pub fn name(self) -> &'static str {
        match self {
            LineEnd::Boundary => "boundary",
            LineEnd::Umbilic => "umbilic",
            LineEnd::Parabolic => "parabolic line",
            LineEnd::Singular => "singular point",
            LineEnd::Closed => "closed",
            LineEnd::Length => "length",
            LineEnd::Limit => "point limit",
            LineEnd::Near => "too near a line",
            LineEnd::Jump => "direction jump at a piece boundary",
        }
    }

    fn from_halt(h: Halt) -> Self {
        match h {
            Halt::Outside => LineEnd::Boundary,
            Halt::Umbilic => LineEnd::Umbilic,
            Halt::NotHyperbolic => LineEnd::Parabolic,
            Halt::Singular => LineEnd::Singular,
        }
    }
}

/// A traced field line.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldLine {
    /// Its family.
    pub family: LineFamily,
    /// The polyline, from the backward end through the seed to the forward end.
    pub curve: SurfaceCurve,
    /// The index of the seed in the polyline.
    pub seed: usize,
    /// Why the line ended at its first and at its last point (both `Closed` for a loop).
    pub ends: [LineEnd; 2],
}

/// Why a field line could not start.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum FieldLineError {
    /// The seed lies outside the domain.
    #[error("the seed ({}, {}) lies outside the domain", crate::text::Short(*.0), crate::text::Short(*.1))]
    Outside(f64, f64),
    /// The field has no direction at the seed.
    #[error("no {family} passes through ({u}, {v}): the seed is at {why}")]
    Undefined {
        /// The family's name.
        family: &'static str,
        /// The seed's u.
        u: f64,
        /// The seed's v.
        v: f64,
        /// Why (an umbilic, a non-hyperbolic point, a singular point).
        why: &'static str,
    },
    /// An option is not a positive finite number, or the largest step is below the smallest.
    #[error(
        "field-line options must be positive and finite (length may be infinite), the largest step at least the smallest (1e-6 of the domain)"
    )]
    BadOptions,
}

/// The line field of one family on a surface, as a flow in the parameter plane.
pub(crate) struct LineFlow<'a, S: ?Sized> {
    pub surface: &'a S,
    pub family: LineFamily,
    pub umbilic_tolerance: f64,
}

impl<S: ParametricSurface + ?Sized> LineFlow<'_, S> {
    /// The unit parameter direction of the field at `uv` (either sign).
    pub fn direction(&self, uv: Point2<f64>, cursor: &mut Cursor) -> Result<Vector2<f64>, Halt> {
        let jet = self
            .surface
            .jet_with(uv, cursor)
            .map_err(|_| Halt::Outside)?
            .jet;
        let c = Curvature::from_jet(&jet).map_err(|_| Halt::Singular)?;
        let uv_of = |d: Vector2<f64>| d / (jet.dx * d.x + jet.dy * d.y).norm();
        match self.family {
            LineFamily::Curvature1 | LineFamily::Curvature2 => {
                if c.is_umbilic(self.umbilic_tolerance) {
                    return Err(Halt::Umbilic);
                }
                Ok(if self.family == LineFamily::Curvature1 {
                    c.dir1_uv
                } else {
                    c.dir2_uv
                })
            }
            LineFamily::AsymptoticPlus | LineFamily::AsymptoticMinus => {
                let spread = c.k1 - c.k2;
                // Hyperbolic: κ1 > 0 > κ2, by a margin relative to the curvature.
                if !(c.k1 > self.umbilic_tolerance * spread
                    && -c.k2 > self.umbilic_tolerance * spread)
                {
                    return Err(Halt::NotHyperbolic);
                }
                let (cos, sin) = ((-c.k2 / spread).sqrt(), (c.k1 / spread).sqrt());
                let sign = if self.family == LineFamily::AsymptoticPlus {
                    1.0
                } else {
                    -1.0
                };
                let d = uv_of(c.dir1_uv) * cos + uv_of(c.dir2_uv) * (sign * sin);
                Ok(d / d.norm())
            }
        }
    }
}

impl<S: ParametricSurface + ?Sized> Flow<2> for LineFlow<'_, S> {
    fn slope(
        &self,
        y: &State<2>,
        reference: &State<2>,
        cursor: &mut Cursor,
    ) -> Result<State<2>, Halt> {
        let d = self.direction(Point2::new(y[0], y[1]), cursor)?;
        Ok(if d.dot(reference) < 0.0 { -d } else { d })
    }
}

/// The diagonal of the domain's bounding box.
pub(crate) fn domain_diameter<S: ParametricSurface + ?Sized>(surface: &S) -> f64 {
    let (lo, hi) = surface.domain_bounds();
    (hi - lo).norm()
}

/// Traces the line of `family` through `seed`, both ways.
pub fn trace_field_line<S: ParametricSurface + ?Sized>(
    surface: &S,
    family: LineFamily,
    seed: Point2<f64>,
    opts: &FieldLineOptions,
) -> Result<FieldLine, FieldLineError> {
    trace_guarded(surface, family, seed, opts, &mut |_, _| false)
}

/// As [`trace_field_line`], stopping a line (with [`LineEnd::Near`]) at the first accepted
/// point for which `near(point, earlier)` says true, `earlier` being the points of the same
/// walk from the seed so far.
pub(crate) fn trace_guarded<S: ParametricSurface + ?Sized>(
    surface: &S,
    family: LineFamily,
    seed: Point2<f64>,
    opts: &FieldLineOptions,
    near: &mut Guard,
) -> Result<FieldLine, FieldLineError> {
    let positive = |x: f64| x > 0.0 && x.is_finite();
    if !(positive(opts.tolerance)
        && positive(opts.min_step)
        && positive(opts.max_step)
        && opts.max_step >= opts.min_step
        && opts.length > 0.0
        && opts.umbilic_tolerance >= 0.0
        && opts.max_points > 0)
    {
        return Err(FieldLineError::BadOptions);
    }
    let flow = LineFlow {
        surface,
        family,
        umbilic_tolerance: opts.umbilic_tolerance,
    };
    let mut cursor = surface.cursor_near(seed);
    let d0 = flow.direction(seed, &mut cursor).map_err(|h| match h {
        Halt::Outside => FieldLineError::Outside(seed.x, seed.y),
        h => FieldLineError::Undefined {
            family: family.name(),
            u: seed.x,
            v: seed.y,
            why: match h {
                Halt::Umbilic => "an umbilic",
                Halt::NotHyperbolic => "a point that is not hyperbolic",
                _ => "a singular point",
            },
        },
    })?;
    let scale = domain_diameter(surface);
    let ode = Integrator {
        tolerance: opts.tolerance * scale,
        min_step: opts.min_step * scale,
        max_step: opts.max_step * scale,
    };
    let walker = Walker {
        flow: &flow,
        ode,
        opts,
        close: 1e-5 * scale,
    };
    let forward = walker.walk(seed, d0, cursor, near);
    let point = |uv: Point2<f64>| surface.point(uv).ok();
    let seed_point = point(seed).ok_or(FieldLineError::Outside(seed.x, seed.y))?;
    let (backward, back_end) = if forward.1 == LineEnd::Closed {
        (Vec::new(), LineEnd::Closed)
    } else {
        walker.walk(seed, -d0, cursor, near)
    };
    let mut curve = SurfaceCurve {
        closed: forward.1 == LineEnd::Closed,
        ..Default::default()
    };
    for (uv, p) in backward
        .iter()
        .rev()
        .chain([(seed, seed_point)].iter())
        .chain(&forward.0)
    {
        curve.uvs.push(*uv);
        curve.points.push(*p);
    }
    Ok(FieldLine {
        family,
        curve,
        seed: backward.len(),
        ends: [back_end, forward.1],
    })
}

/// Says whether a new point (given the walk's earlier points) is too near other lines.
pub(crate) type Guard<'a> = dyn FnMut(Point2<f64>, &[Point2<f64>]) -> bool + 'a;

/// Follows one way from a seed.
struct Walker<'a, S: ?Sized> {
    flow: &'a LineFlow<'a, S>,
    ode: Integrator,
    opts: &'a FieldLineOptions,
    /// A line passing this near its seed (in the parameter plane), heading the same way, is
    /// closed.
    close: f64,
}

/// The largest turn of the direction over one accepted step: more is a jump of the field.
const MAX_TURN: f64 = std::f64::consts::FRAC_PI_4;

type Points = Vec<(Point2<f64>, nalgebra::Vector3<f64>)>;

impl<S: ParametricSurface + ?Sized> Walker<'_, S> {
    /// The points after the seed, travelling along `dir` first, and why the walk ended.
    fn walk(
        &self,
        seed: Point2<f64>,
        dir: Vector2<f64>,
        mut cursor: Cursor,
        near: &mut Guard,
    ) -> (Points, LineEnd) {
        let mut out: Points = Vec::new();
        let mut walked = vec![seed];
        let mut y = State::<2>::new(seed.x, seed.y);
        let mut k = State::<2>::new(dir.x, dir.y);
        let (mut h, mut length, mut far) = (self.ode.max_step * 0.25, 0.0, 0.0_f64);
        let mut last_chord = None;
        let mut last = match self.flow.surface.point(seed) {
            Ok(p) => p,
            Err(_) => return (out, LineEnd::Boundary),
        };
        loop {
            if out.len() >= self.opts.max_points {
                return (out, LineEnd::Limit);
            }
            let mut a = match self.ode.advance(self.flow, &y, &k, h, &mut cursor) {
                Ok(a) => a,
                Err(halt) => return (out, LineEnd::from_halt(halt)),
            };
            let (from, mut to) = (Point2::new(y[0], y[1]), Point2::new(a.y[0], a.y[1]));
            let Ok(mut p) = self
                .flow
                .surface
                .jet_with(to, &mut cursor)
                .map(|j| j.jet.value)
            else {
                return (out, LineEnd::Boundary);
            };
            let step = (p - last).norm();
            let at_limit = length + step >= self.opts.length;
            if length + step > self.opts.length {
                // The step overshoots the length: take the part of it that ends there (a
                // step's length in space is proportional to its size to first order, so a
                // few rescalings reach it to rounding).
                let want = self.opts.length - length;
                let (mut size, mut got) = (a.taken, step);
                for _ in 0..4 {
                    size *= want / got;
                    let Ok(b) = self.ode.advance(self.flow, &y, &k, size, &mut cursor) else {
                        break;
                    };
                    let Ok(q) = (self.flow.surface)
                        .jet_with(Point2::new(b.y[0], b.y[1]), &mut cursor)
                        .map(|j| j.jet.value)
                    else {
                        break;
                    };
                    (size, got) = (b.taken, (q - last).norm());
                    (a, to, p) = (b, Point2::new(b.y[0], b.y[1]), q);
                    if (got - want).abs() <= 1e-9 * want || got == 0.0 {
                        break;
                    }
                }
            }
            length += (p - last).norm();
            // Closed: back at the seed, heading the same way, after going well away from it.
            // The chord deviates from the arc by up to |chord| φ / 8 (φ the turn of the
            // tangent over the step): allow twice that.
            let turn = Vector2::new(k[0], k[1]).angle(&Vector2::new(a.slope[0], a.slope[1]));
            let sagitta = (to - from).norm() * turn / 4.0;
            let closes = far > 100.0 * self.close
                && distance_to_segment(seed, from, to) <= self.close + sagitta
                && Vector2::new(a.slope[0], a.slope[1]).dot(&dir) > 0.0;
            if closes {
                return (out, LineEnd::Closed);
            }
            far = far.max((to - seed).norm());
            // A kink in the polyline (a step that straddles a piece boundary) is a jump too.
            let chord = to - from;
            if last_chord.is_some_and(|c: Vector2<f64>| c.angle(&chord) > MAX_TURN) {
                return (out, LineEnd::Jump);
            }
            last_chord = Some(chord);
            if near(to, &walked) {
                return (out, LineEnd::Near);
            }
            walked.push(to);
            out.push((to, p));
            if turn > MAX_TURN {
                return (out, LineEnd::Jump);
            }
            if at_limit {
                return (out, LineEnd::Length);
            }
            (y, k, h, last) = (a.y, a.slope, a.next, p);
        }
    }
}
