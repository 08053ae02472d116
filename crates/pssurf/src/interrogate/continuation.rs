//! Predictor–corrector continuation of a zero set f(u, v) = 0 in the parameter plane (seed
//! 001, section 3 b): an Euler predictor along the zero set's tangent (−f_v, f_u), Newton
//! steps along ∇f back onto f = 0, step control by the corrector's success and by the turn
//! of the tangent, and the seed's rule at singular points (|∇f| ≈ 0, its (6)): the next point
//! is the linear extrapolation 2 pᵢ − pᵢ₋₁, then corrected.
//!
//! The seed's corrector moves along one coordinate axis (the one with the larger partial
//! derivative); moving along ∇f, as here, is the same Newton step in the best direction and
//! needs no case split. One routine serves plane sections and level lines.

use nalgebra::{Point2, Vector2, Vector3};

use crate::geometry::orient_exact;

/// The value of f and what the tracer needs at one parameter point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sample {
    /// f(u, v) (the level already subtracted).
    pub f: f64,
    /// ∇f w.r.t. (u, v).
    pub grad: Vector2<f64>,
    /// The surface point s(u, v).
    pub point: Vector3<f64>,
    /// s_u and s_v (to measure steps in space).
    pub su: Vector3<f64>,
    /// s_v.
    pub sv: Vector3<f64>,
}

/// Where a followed branch leaves its region: the parameter along the last segment and the
/// boundary edge it crosses.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Exit {
    /// The boundary edge's index in the region.
    pub edge: usize,
    /// Its first end.
    pub from: Point2<f64>,
    /// Its second end.
    pub to: Point2<f64>,
}

/// The region a branch is followed in.
pub(crate) trait Region {
    /// Whether `p` lies in the closed region (exact).
    fn contains(&self, p: Point2<f64>) -> bool;
    /// The boundary edges whose outer side `b` lies on, in the order the segment from `a`
    /// (inside) to `b` (outside) crosses their lines; empty if the region does not know its
    /// edges.
    fn exits(&self, a: Point2<f64>, b: Point2<f64>) -> Vec<Exit>;
}

/// A convex polygon (a piece), corners counter-clockwise.
#[derive(Clone, Debug)]
pub(crate) struct ConvexPolygon {
    pub corners: Vec<Point2<f64>>,
}

impl ConvexPolygon {
    /// The polygon with these corners, reordered counter-clockwise if needed.
    pub fn new(mut corners: Vec<Point2<f64>>) -> Self {
        if corners.len() >= 3 && orient_exact(corners[0], corners[1], corners[2]) < 0.0 {
            corners.reverse();
        }
        ConvexPolygon { corners }
    }

    /// The edges (a, b), counter-clockwise.
    pub fn edges(&self) -> impl Iterator<Item = (Point2<f64>, Point2<f64>)> + '_ {
        let n = self.corners.len();
        (0..n).map(move |i| (self.corners[i], self.corners[(i + 1) % n]))
    }

    /// The largest distance between two corners.
    pub fn diameter(&self) -> f64 {
        let mut d: f64 = 0.0;
        for a in &self.corners {
            for b in &self.corners {
                d = d.max((a - b).norm());
            }
        }
        d
    }
}

impl Region for ConvexPolygon {
    fn contains(&self, p: Point2<f64>) -> bool {
        self.edges().all(|(a, b)| orient_exact(a, b, p) >= 0.0)
    }

    fn exits(&self, a: Point2<f64>, b: Point2<f64>) -> Vec<Exit> {
        let mut out: Vec<(f64, Exit)> = Vec::new();
        for (k, (c, d)) in self.edges().enumerate() {
            let (oa, ob) = (orient_exact(c, d, a), orient_exact(c, d, b));
            if ob >= 0.0 {
                continue;
            }
            // A start a hair outside this edge (a seed on it, rounded) leaves at once.
            let t = if oa <= 0.0 { 0.0 } else { oa / (oa - ob) };
            out.push((
                t,
                Exit {
                    edge: k,
                    from: c,
                    to: d,
                },
            ));
        }
        out.sort_by(|x, y| x.0.total_cmp(&y.0));
        out.into_iter().map(|(_, e)| e).collect()
    }
}

/// The most steps in a row below a thousandth of the largest step before a branch is stopped.
const STALL: usize = 200;

/// Why a branch ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum End {
    /// It reached the region's boundary; its last point lies on edge `edge`.
    Edge(usize),
    /// It reached the region's boundary where the region has no edges to solve on (the
    /// domain of a whole surface): the last point is within the smallest step of it.
    Boundary,
    /// It came back to its start.
    Closed,
    /// The corrector failed even at the smallest step (a singular point it could not pass).
    Stuck,
    /// The length or point limit.
    Limit,
}

/// How a branch is followed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Follow {
    /// The largest step: in space when `in_space`, else in the parameter plane.
    pub step: f64,
    /// Whether `step` and `length` are measured in space.
    pub in_space: bool,
    /// The smallest step, as a fraction of `step`.
    pub min_fraction: f64,
    /// The largest turn of the tangent per step (radians) before the step is halved.
    pub max_turn: f64,
    /// The corrector's tolerance on |f|.
    pub tolerance: f64,
    /// |∇f| at or below this is a singular point (the seed's ε₁).
    pub singular: f64,
    /// The longest branch (same units as `step`).
    pub length: f64,
    /// The most points on the branch.
    pub max_points: usize,
}

/// A followed branch: its points after the start and why it ended.
#[derive(Clone, Debug)]
pub(crate) struct Branch {
    pub uvs: Vec<Point2<f64>>,
    pub points: Vec<Vector3<f64>>,
    pub end: End,
}

impl Branch {
    /// No points yet.
    pub fn empty() -> Self {
        Branch {
            uvs: Vec::new(),
            points: Vec::new(),
            end: End::Limit,
        }
    }
}

/// The unit tangent (−f_v, f_u)/|∇f| of the zero set, `None` at a singular point.
fn tangent(s: &Sample, singular: f64) -> Option<Vector2<f64>> {
    let n = s.grad.norm();
    (n > singular && n.is_finite()).then(|| Vector2::new(-s.grad.y, s.grad.x) / n)
}

impl Follow {
    /// Follows the zero set of `f` from `start` (on it) in the direction `dir` (the tangent's
    /// orientation), inside `region`. `seen(a, b)` is told of every accepted segment and may
    /// return true to stop (a branch that met its own start).
    pub fn run(
        &self,
        f: &mut dyn FnMut(Point2<f64>) -> Option<Sample>,
        region: &dyn Region,
        start: (Point2<f64>, Sample),
        dir: Vector2<f64>,
        seen: &mut dyn FnMut(Point2<f64>, Point2<f64>) -> bool,
    ) -> Branch {
        let mut out = Branch::empty();
        let (mut uv, mut here) = start;
        let mut previous: Option<Point2<f64>> = None;
        let mut heading = dir;
        // The tangent (−f_v, f_u)/|∇f| keeps its orientation along a regular curve, so the
        // direction of travel is `sense` times it; only across a singular point (where ∇f
        // may flip, as for f = xy on y = 0) is the sense taken again from the chord.
        let mut sense = tangent(&here, self.singular).map_or(1.0, |t| sign(t.dot(&dir)));
        let mut h = self.step;
        let mut travelled = 0.0;
        let origin = start.0;
        let mut crawling = 0usize;
        loop {
            if out.uvs.len() >= self.max_points || travelled >= self.length {
                out.end = End::Limit;
                return out;
            }
            // The predictor's direction: the tangent, or across a singular point the
            // previous chord (the seed's linear extrapolation).
            let t = match tangent(&here, self.singular) {
                Some(t) => t * sense,
                None => match previous {
                    Some(p) => (uv - p).try_normalize(0.0).unwrap_or(heading),
                    None => {
                        out.end = End::Stuck;
                        return out;
                    }
                },
            };
            let scale = if self.in_space {
                (here.su * t.x + here.sv * t.y).norm()
            } else {
                1.0
            };
            if !(scale > 0.0 && scale.is_finite()) {
                out.end = End::Stuck;
                return out;
            }
            let step = h
                .min(self.length - travelled)
                .max(self.step * self.min_fraction);
            let predicted = uv + t * (step / scale);
            let next = correct(f, predicted, self.tolerance)
                .filter(|(_, s)| turn_ok(t, s, sense, self.singular, self.max_turn));
            let Some((next_uv, next_sample)) = next else {
                if h <= self.step * self.min_fraction {
                    out.end = End::Stuck;
                    return out;
                }
                h *= 0.5;
                continue;
            };
            if !region.contains(next_uv) {
                let exits = region.exits(uv, next_uv);
                if exits.is_empty() && h <= self.step * self.min_fraction {
                    out.end = End::Boundary;
                    return out;
                }
                // The edge the chord leaves by first; near a corner the curve itself may
                // leave by the next one.
                for exit in exits {
                    if let Some((e_uv, e_s)) = edge_root(f, exit, uv, next_uv, self.tolerance, 0.0)
                    {
                        push(&mut out, e_uv, e_s.point);
                        seen(uv, e_uv);
                        out.end = End::Edge(exit.edge);
                        return out;
                    }
                }
                if h <= self.step * self.min_fraction {
                    out.end = End::Stuck;
                    return out;
                }
                h *= 0.5;
                continue;
            }
            let chord = next_uv - uv;
            // Near a critical point of f the tangent is ill-conditioned and the step can stay
            // tiny for ever: a branch that crawls for STALL steps in a row is stopped.
            crawling = if h <= 1e-3 * self.step {
                crawling + 1
            } else {
                0
            };
            if crawling > STALL {
                out.end = End::Stuck;
                return out;
            }
            travelled += if self.in_space {
                (next_sample.point - here.point).norm()
            } else {
                chord.norm()
            };
            // Back at the start: the chord passes within a tenth of its length of it.
            let closes = out.uvs.len() >= 3
                && distance_to_segment(origin, uv, next_uv) <= 0.1 * chord.norm();
            if closes {
                push(&mut out, origin, start.1.point);
                out.end = End::Closed;
                return out;
            }
            push(&mut out, next_uv, next_sample.point);
            if seen(uv, next_uv) {
                out.end = End::Closed;
                return out;
            }
            previous = Some(uv);
            heading = chord.try_normalize(0.0).unwrap_or(t);
            uv = next_uv;
            if tangent(&here, self.singular).is_none() {
                // Past a singular point: the sense from the chord.
                if let Some(n) = tangent(&next_sample, self.singular) {
                    sense = sign(n.dot(&chord));
                }
            }
            let turned = tangent(&next_sample, self.singular)
                .map_or(0.0, |n| (n * sense).dot(&t).clamp(-1.0, 1.0).acos());
            here = next_sample;
            if turned < 0.25 * self.max_turn {
                h = (2.0 * h).min(self.step);
            }
        }
    }
}

fn push(out: &mut Branch, uv: Point2<f64>, p: Vector3<f64>) {
    out.uvs.push(uv);
    out.points.push(p);
}

/// Whether the direction of travel at the corrected point (`sense` times its tangent) turned
/// by at most `max_turn` from `t`: a step across a small loop lands where the curve runs the
/// other way and is refused. Singular points pass.
fn turn_ok(t: Vector2<f64>, s: &Sample, sense: f64, singular: f64, max_turn: f64) -> bool {
    tangent(s, singular).is_none_or(|n| (n * sense).dot(&t) >= max_turn.cos())
}

/// ±1 by the sign of `x` (+1 for zero).
fn sign(x: f64) -> f64 {
    if x < 0.0 { -1.0 } else { 1.0 }
}

/// Newton steps along ∇f from `uv` onto |f| ≤ `tolerance`; `None` if they do not converge
/// in 12 steps or f is undefined.
pub(crate) fn correct(
    f: &mut dyn FnMut(Point2<f64>) -> Option<Sample>,
    mut uv: Point2<f64>,
    tolerance: f64,
) -> Option<(Point2<f64>, Sample)> {
    for _ in 0..12 {
        let s = f(uv)?;
        if !s.f.is_finite() {
            return None;
        }
        if s.f.abs() <= tolerance {
            return Some((uv, s));
        }
        let g2 = s.grad.norm_squared();
        if g2 == 0.0 || !g2.is_finite() {
            return None;
        }
        uv -= s.grad * (s.f / g2);
    }
    None
}

/// The zero of f on the edge `exit` near where the segment a → b crosses it: a bracket on the
/// edge grown from the crossing, then the Illinois regula falsi. `None` if f has no sign
/// change on the edge near the crossing. `slack` widens "near" (in the parameter plane) for
/// segments whose ends are only close to the curve (the 4-/8-point walks); 0 for points on it.
pub(crate) fn edge_root(
    f: &mut dyn FnMut(Point2<f64>) -> Option<Sample>,
    exit: Exit,
    a: Point2<f64>,
    b: Point2<f64>,
    tolerance: f64,
    slack: f64,
) -> Option<(Point2<f64>, Sample)> {
    let (c, d) = (exit.from, exit.to);
    let (oa, ob) = (orient_exact(c, d, a), orient_exact(c, d, b));
    let cross = a + (b - a) * (oa.max(0.0) / (oa.max(0.0) - ob));
    let e = d - c;
    let len2 = e.norm_squared();
    if len2 == 0.0 {
        return None;
    }
    let s0 = ((cross - c).dot(&e) / len2).clamp(0.0, 1.0);
    let at = |s: f64| c + e * s;
    let mut value = |s: f64| f(at(s)).map(|x| x.f).filter(|v| v.is_finite());
    let f0 = value(s0)?;
    if f0.abs() <= tolerance {
        return f(at(s0)).map(|x| (at(s0), x));
    }
    // The curve crosses the edge within about a chord (plus the slack) of where the chord
    // does; a root farther along the edge belongs to another crossing.
    let chord = (b - a).norm() + slack;
    let mut delta = (chord / len2.sqrt()).max(1e-12);
    let widest = 2.0 * delta;
    let bracket = loop {
        let (lo, hi) = ((s0 - delta).max(0.0), (s0 + delta).min(1.0));
        let (flo, fhi) = (value(lo)?, value(hi)?);
        if flo * f0 <= 0.0 {
            break (lo, flo, s0, f0);
        }
        if fhi * f0 <= 0.0 {
            break (s0, f0, hi, fhi);
        }
        if (lo == 0.0 && hi == 1.0) || delta >= widest {
            return None;
        }
        delta *= 2.0;
    };
    let s = illinois(&mut value, bracket, tolerance)?;
    if (at(s) - cross).norm() > 1.5 * chord + 1e-12 * len2.sqrt() {
        return None;
    }
    f(at(s)).map(|x| (at(s), x))
}

/// The Illinois variant of regula falsi (the seed's "modified regula falsi") on a bracket
/// (lo, f(lo), hi, f(hi)) with a sign change: the root where |f| ≤ `tolerance`, or the end of
/// a bracket that has shrunk to nothing.
pub(crate) fn illinois(
    value: &mut dyn FnMut(f64) -> Option<f64>,
    (mut a, mut fa, mut b, mut fb): (f64, f64, f64, f64),
    tolerance: f64,
) -> Option<f64> {
    if fa.abs() <= tolerance {
        return Some(a);
    }
    if fb.abs() <= tolerance {
        return Some(b);
    }
    for _ in 0..100 {
        let c = (a * fb - b * fa) / (fb - fa);
        let c = if c.is_finite() && c > a.min(b) && c < a.max(b) {
            c
        } else {
            0.5 * (a + b)
        };
        let fc = value(c)?;
        if fc.abs() <= tolerance || (b - a).abs() <= 1e-15 * (a.abs() + b.abs()) {
            return Some(c);
        }
        if fc * fb < 0.0 {
            (a, fa) = (b, fb);
        } else {
            fa *= 0.5;
        }
        (b, fb) = (c, fc);
    }
    None
}

/// The distance from `p` to the segment [a, b].
pub(crate) fn distance_to_segment(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let r = b - a;
    let len2 = r.norm_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(&r) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + r * t - p).norm()
}
