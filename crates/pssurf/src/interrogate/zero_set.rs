//! Zero sets and level sets of a function on a piecewise surface, traced as in seed 001:
//!
//! 1. **Seed points** by a hunting mesh on every piece: lines of constant barycentric
//!    coordinate τᵢ = j/n (triangles) or constant s, t = j/n (rectangles), sampled at their
//!    crossings; on every segment with a sign change of f − c a root by the modified regula
//!    falsi (Illinois).
//! 2. **Tracing** from each seed in both directions by the predictor–corrector of
//!    `continuation` (or the seed's derivative-free 4- and 8-point walks,
//!    [`TraceMethod`]), on the piece's own polynomial, until the branch leaves the piece (its
//!    end solved onto the piece's edge), closes, or gets stuck. Seeds whose hunting segment a
//!    branch crosses are used up.
//! 3. **Joining**: branch ends on a shared edge (or corner) of two pieces are joined when
//!    they lie within `join_tolerance` of each other, into polylines over the whole surface;
//!    chains that come back to themselves are closed loops.
//!
//! Functions built from second derivatives (curvature) jump across piece boundaries of a C¹
//! surface (the PS refinement lines): there a level line of one piece generally meets the
//! edge at another point than the continuing line of the next piece, or does not continue at
//! all. Such an end is not bridged: it is reported as a [`LevelGap`] with the value the field
//! takes on the other side.

use std::sync::atomic::{AtomicUsize, Ordering};

use nalgebra::{Point2, Vector2, Vector3};
use rayon::prelude::*;
use thiserror::Error;

use super::continuation::{
    Branch, ConvexPolygon, End, Follow, Sample, correct, distance_to_segment, illinois,
};
pub use super::curve::{CONTINUITY_TOLERANCES, LevelGap, SurfaceCurve, ZeroSet};
use super::edge_lines::{EdgeLineIndex, level_edges};
use super::field::SurfaceField;
use super::joining::{BranchEnds, Edges, Pairing};
use crate::bezier::Jet;
use crate::surface::{PieceFrame, PieceShape, PiecewiseSurface};

/// A function on a piecewise surface, defined piece by piece: on piece k it is a function of
/// that piece's polynomial (extended beyond the piece), so it is smooth on each piece even
/// where it jumps across their boundaries.
pub trait PieceFunction: Sync {
    /// The value on piece `piece` at `uv` and the piece's surface jet there (NaN where the
    /// function is undefined).
    fn eval(&self, piece: usize, frame: &PieceFrame, uv: Point2<f64>) -> (f64, Jet<Vector3<f64>>);

    /// The exact gradient w.r.t. (u, v) from the jet, when it is known; otherwise the tracer
    /// takes central differences on the piece's polynomial.
    fn gradient(&self, _jet: &Jet<Vector3<f64>>) -> Option<Vector2<f64>> {
        None
    }
}

/// A [`SurfaceField`] on a surface, as a [`PieceFunction`].
pub struct FieldOn<'a, S: ?Sized> {
    /// The surface.
    pub surface: &'a S,
    /// The field.
    pub field: &'a SurfaceField,
}

impl<S: PiecewiseSurface + ?Sized> PieceFunction for FieldOn<'_, S> {
    fn eval(&self, piece: usize, frame: &PieceFrame, uv: Point2<f64>) -> (f64, Jet<Vector3<f64>>) {
        let jet = self.surface.piece_jet(piece, &frame.at_uv(uv));
        (self.field.value(uv, &jet), jet)
    }

    fn gradient(&self, jet: &Jet<Vector3<f64>>) -> Option<Vector2<f64>> {
        self.field.gradient(jet)
    }
}

/// The signed distance (s(u, v) − origin)·normal of a surface point from a plane: its zero
/// set is the section of the surface by the plane. Continuous across pieces (the surface is).
pub struct PlaneDistance<'a, S: ?Sized> {
    /// The surface.
    pub surface: &'a S,
    /// A point of the plane.
    pub origin: Vector3<f64>,
    /// The plane's unit normal.
    pub normal: Vector3<f64>,
}

impl<S: PiecewiseSurface + ?Sized> PieceFunction for PlaneDistance<'_, S> {
    fn eval(&self, piece: usize, frame: &PieceFrame, uv: Point2<f64>) -> (f64, Jet<Vector3<f64>>) {
        let jet = self.surface.piece_jet(piece, &frame.at_uv(uv));
        ((jet.value - self.origin).dot(&self.normal), jet)
    }

    fn gradient(&self, jet: &Jet<Vector3<f64>>) -> Option<Vector2<f64>> {
        Some(Vector2::new(
            jet.dx.dot(&self.normal),
            jet.dy.dot(&self.normal),
        ))
    }
}

/// How branches are followed from their seeds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceMethod {
    /// Euler predictor and Newton corrector with step control (seed 001, 3 b): points on the
    /// curve to the corrector's tolerance. The default.
    PredictorCorrector,
    /// The seed's four-point walk (3 a): from each point the neighbour at (±h, 0), (0, ±h)
    /// with the smallest |f − c| (not going back), h halved until |f − c| ≤ the walk
    /// tolerance. Derivative-free; points are only within the walk tolerance, and the curve
    /// is a staircase at the scale of h. A walk stops (counted in [`ZeroSet::stuck`]) where
    /// no neighbour ahead meets the tolerance even at the smallest h, which happens where the
    /// curve runs at a shallow angle to a step direction; so walks can leave a curve in
    /// pieces. For comparison with the seed; use the predictor–corrector.
    FourPoint,
    /// The seed's eight-point walk: as [`TraceMethod::FourPoint`] with the diagonal
    /// neighbours too.
    EightPoint,
}

/// How a zero set is hunted, traced and joined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZeroSetOptions {
    /// Hunting lines per direction and piece (n ≥ 1): branches that cross no hunting segment
    /// with a sign change (loops smaller than about 1/n of a piece) are missed.
    pub hunting: usize,
    /// The largest step as a fraction of the piece's diameter in the parameter plane.
    pub step: f64,
    /// The corrector's tolerance relative to the field's scale (|c| plus the spread of the
    /// field's values between its 5th and 95th percentiles on the hunting meshes).
    pub tolerance: f64,
    /// The 4-/8-point walks' tolerance, relative to the same scale.
    pub walk_tolerance: f64,
    /// Two branch ends on a shared edge are joined when they are closer than this fraction
    /// of the edge's length.
    pub join_tolerance: f64,
    /// The most points in all curves of all levels together (bounded work).
    pub max_points: usize,
    /// How branches are followed.
    pub method: TraceMethod,
}

impl Default for ZeroSetOptions {
    fn default() -> Self {
        ZeroSetOptions {
            hunting: 4,
            step: 0.125,
            tolerance: 1e-11,
            walk_tolerance: 1e-3,
            join_tolerance: 1e-6,
            max_points: 2_000_000,
            method: TraceMethod::PredictorCorrector,
        }
    }
}

/// The options or levels cannot be used.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum ZeroSetError {
    /// An option is out of range.
    #[error(
        "zero-set options: hunting must be 1..=64, step in (0, 1], tolerances positive and max_points at least 1"
    )]
    BadOptions,
    /// A level is NaN or infinite.
    #[error("the level {0} is not a finite number")]
    BadLevel(f64),
}

/// The zero set f = 0 of `function` on `surface`.
pub fn trace_zero_set<S, F>(
    surface: &S,
    function: &F,
    opts: &ZeroSetOptions,
) -> Result<ZeroSet, ZeroSetError>
where
    S: PiecewiseSurface + ?Sized,
    F: PieceFunction,
{
    Ok(trace_levels(surface, function, &[0.0], opts)?
        .pop()
        .unwrap_or_default())
}

/// The level sets f = c of `function` on `surface` for every c in `levels`, sharing the
/// hunting meshes; in parallel over pieces.
pub fn trace_levels<S, F>(
    surface: &S,
    function: &F,
    levels: &[f64],
    opts: &ZeroSetOptions,
) -> Result<Vec<ZeroSet>, ZeroSetError>
where
    S: PiecewiseSurface + ?Sized,
    F: PieceFunction,
{
    check(opts)?;
    if let Some(&c) = levels.iter().find(|c| !c.is_finite()) {
        return Err(ZeroSetError::BadLevel(c));
    }
    let pieces: Vec<Piece> = (0..surface.piece_count())
        .into_par_iter()
        .filter_map(|k| Piece::new(surface, function, k, opts.hunting))
        .collect();
    let spread = spread(&pieces);
    let budget = AtomicUsize::new(opts.max_points);
    let per_piece: Vec<Vec<PieceLevel>> = pieces
        .par_iter()
        .map(|p| {
            levels
                .iter()
                .map(|&c| p.trace(function, c, tolerance(c, spread, opts), opts, &budget))
                .collect()
        })
        .collect();
    // Level by level: the pieces' branches, then continuing and joining, in parallel.
    let mut per_level: Vec<Vec<(usize, PieceLevel)>> = levels.iter().map(|_| Vec::new()).collect();
    for (pi, piece_levels) in per_piece.into_iter().enumerate() {
        for (li, l) in piece_levels.into_iter().enumerate() {
            if l.flat || l.stuck > 0 || !l.branches.is_empty() {
                per_level[li].push((pi, l));
            }
        }
    }
    let edges = Edges::new(pieces.iter().map(|p| &p.polygon));
    let join_level = |(c, traced): (f64, Vec<(usize, PieceLevel)>)| {
        let mut set = ZeroSet {
            level: c,
            tolerance: tolerance(c, spread, opts),
            ..Default::default()
        };
        let mut branches: Vec<(usize, PieceBranch)> = Vec::new();
        for (pi, l) in traced {
            set.flat_pieces += usize::from(l.flat);
            set.stuck += l.stuck;
            branches.extend(l.branches.into_iter().map(|b| (pi, b)));
        }
        let level = Level {
            pieces: &pieces,
            function,
            c,
            tol: set.tolerance,
            opts,
            budget: &budget,
        };
        level.replace_edge_branches(&mut branches, &edges);
        level.continue_unfinished(&mut branches, &edges, &mut set.stuck);
        let views = views(&branches);
        let pairing = Pairing::new(&views, &edges, opts.join_tolerance);
        let across = |owner: usize, uv: Point2<f64>| {
            let p = &pieces[owner];
            function.eval(p.index, &p.frame, uv).0
        };
        pairing.finish(&mut set, &views, &edges, &across);
        set.truncated = budget.load(Ordering::Relaxed) == 0;
        set
    };
    let out = levels
        .par_iter()
        .copied()
        .zip(per_level)
        .map(join_level)
        .collect();
    Ok(out)
}

/// The joiner's view of the branches.
fn views(branches: &[(usize, PieceBranch)]) -> Vec<BranchEnds<'_>> {
    branches
        .iter()
        .map(|(pi, b)| BranchEnds {
            piece: *pi,
            uvs: &b.uvs,
            points: &b.points,
            closed: b.closed,
            start_edge: b.start_edge,
            end_edge: b.end_edge,
        })
        .collect()
}

/// One level being traced over all pieces.
struct Level<'a, F> {
    pieces: &'a [Piece],
    function: &'a F,
    c: f64,
    tol: f64,
    opts: &'a ZeroSetOptions,
    budget: &'a AtomicUsize,
}

impl<F: PieceFunction> Level<'_, F> {
    /// Replaces the branches traced along piece edges where the function takes the level
    /// by one branch per edge ([`super::edge_lines`]).
    fn replace_edge_branches(&self, branches: &mut Vec<(usize, PieceBranch)>, edges: &Edges) {
        // The corners are points of the hunting mesh: a piece none of whose values there
        // is on the level has no level edge. A flat piece (on the level everywhere) is
        // counted as such, not outlined: between two of them there is no line.
        let near = CONTINUITY_TOLERANCES * self.tol;
        let searched: Vec<bool> = self
            .pieces
            .iter()
            .map(|p| {
                let flat = p.values.iter().all(|&v| v == self.c);
                !flat && p.values.iter().any(|v| (v - self.c).abs() <= near)
            })
            .collect();
        let polygons: Vec<&ConvexPolygon> = self.pieces.iter().map(|p| &p.polygon).collect();
        let on_level = |pi: usize, uv: Point2<f64>| {
            let p = &self.pieces[pi];
            let v = self.function.eval(p.index, &p.frame, uv).0 - self.c;
            v.abs() <= near
        };
        let spacing = |pi: usize| self.opts.step * self.pieces[pi].diameter;
        let lines = level_edges(edges, &polygons, &searched, on_level, spacing);
        if lines.is_empty() {
            return;
        }
        let index = EdgeLineIndex::new(&lines, edges);
        branches.retain(|(pi, b)| !index.covers(*pi, &b.uvs, self.opts.join_tolerance));
        for line in &lines {
            // The points count against the budget as traced ones do; none are left: stop.
            let taken = self
                .budget
                .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |b| {
                    b.checked_sub(line.uvs.len())
                });
            if taken.is_err() {
                self.budget.store(0, Ordering::Relaxed);
                return;
            }
            let p = &self.pieces[line.piece];
            let points = line
                .uvs
                .iter()
                .map(|&uv| self.function.eval(p.index, &p.frame, uv).1.value)
                .collect();
            branches.push((
                line.piece,
                PieceBranch {
                    uvs: line.uvs.clone(),
                    points,
                    closed: false,
                    start_edge: Some(line.edge),
                    end_edge: Some(line.edge),
                },
            ));
        }
    }

    /// Where a branch ends on an edge inside the domain without a partner while the function
    /// on the neighbouring piece takes the level there, the curve goes on through a piece
    /// whose hunting mesh missed it (it enters and leaves by one edge): trace it from there,
    /// and repeat with the new ends.
    fn continue_unfinished(
        &self,
        branches: &mut Vec<(usize, PieceBranch)>,
        edges: &Edges,
        stuck: &mut usize,
    ) {
        // Every start is tried once, so this ends.
        let mut tried: std::collections::HashSet<(usize, [u64; 2])> = Default::default();
        loop {
            let views = views(branches);
            let pairing = Pairing::new(&views, edges, self.opts.join_tolerance);
            let starts: Vec<(usize, Point2<f64>)> = pairing
                .unfinished(edges)
                .into_iter()
                .filter(|&(other, uv)| {
                    if !tried.insert((other, [uv.x.to_bits(), uv.y.to_bits()])) {
                        return false;
                    }
                    let p = &self.pieces[other];
                    let v = self.function.eval(p.index, &p.frame, uv).0 - self.c;
                    v.abs() <= 1e3 * self.tol
                })
                .collect();
            drop(views);
            if starts.is_empty() {
                return;
            }
            let mut added = false;
            let mut by_piece: std::collections::HashMap<usize, Vec<usize>> = Default::default();
            for (i, (piece, _)) in branches.iter().enumerate() {
                by_piece.entry(*piece).or_default().push(i);
            }
            for (other, uv) in starts {
                let p = &self.pieces[other];
                // Skip a piece whose branches already pass there (the curve grazes the edge,
                // or both ends of one missed branch ask for it): never trace a curve twice.
                let near = 1e-3 * p.diameter;
                let traced = by_piece.get(&other).is_some_and(|list| {
                    list.iter().any(|&i| {
                        let uvs = &branches[i].1.uvs;
                        uvs.windows(2)
                            .any(|w| distance_to_segment(uv, w[0], w[1]) <= near)
                            || uvs.iter().any(|q| (q - uv).norm() <= near)
                    })
                });
                if traced {
                    continue;
                }
                let mut seen = |_: Point2<f64>, _: Point2<f64>| false;
                if let Some(b) = p.branch_from(
                    self.function,
                    self.c,
                    uv,
                    self.tol,
                    self.opts,
                    self.budget,
                    &mut seen,
                    stuck,
                ) {
                    by_piece.entry(other).or_default().push(branches.len());
                    branches.push((other, b));
                    added = true;
                }
            }
            if !added {
                return;
            }
        }
    }
}

fn check(o: &ZeroSetOptions) -> Result<(), ZeroSetError> {
    let pos = |x: f64| x > 0.0 && x.is_finite();
    let ok = (1..=64).contains(&o.hunting)
        && pos(o.step)
        && o.step <= 1.0
        && pos(o.tolerance)
        && pos(o.walk_tolerance)
        && pos(o.join_tolerance)
        && o.max_points >= 1;
    ok.then_some(()).ok_or(ZeroSetError::BadOptions)
}

/// The absolute corrector tolerance for level c.
fn tolerance(c: f64, spread: f64, opts: &ZeroSetOptions) -> f64 {
    let scale = c.abs() + spread;
    opts.tolerance * if scale > 0.0 { scale } else { 1.0 }
}

/// The spread of the function between its 5th and 95th percentiles on the hunting meshes.
fn spread(pieces: &[Piece]) -> f64 {
    let mut v: Vec<f64> = pieces
        .iter()
        .flat_map(|p| p.values.iter().copied())
        .filter(|x| x.is_finite())
        .collect();
    if v.is_empty() {
        return 0.0;
    }
    let at = |v: &mut Vec<f64>, q: f64| {
        let k = ((v.len() - 1) as f64 * q).round() as usize;
        *v.select_nth_unstable_by(k, f64::total_cmp).1
    };
    let hi = at(&mut v, 0.95);
    let lo = at(&mut v, 0.05);
    hi - lo
}

/// One piece with its hunting mesh and the function's values on it.
struct Piece {
    index: usize,
    frame: PieceFrame,
    polygon: ConvexPolygon,
    diameter: f64,
    /// The hunting mesh's points.
    points: Vec<Point2<f64>>,
    /// The function's values there.
    values: Vec<f64>,
    /// Each hunting line as indices into `points`, in order.
    lines: Vec<Vec<usize>>,
}

/// A branch within one piece: its points and how each end is attached.
struct PieceBranch {
    uvs: Vec<Point2<f64>>,
    points: Vec<Vector3<f64>>,
    closed: bool,
    /// The piece edge the first point lies on, if any.
    start_edge: Option<usize>,
    /// The piece edge the last point lies on, if any.
    end_edge: Option<usize>,
}

/// The branches of one level on one piece.
#[derive(Default)]
struct PieceLevel {
    branches: Vec<PieceBranch>,
    flat: bool,
    stuck: usize,
}

/// A seed point: a root of f − c on a hunting segment.
#[derive(Clone, Copy)]
struct Seed {
    uv: Point2<f64>,
}

impl Piece {
    fn new<S, F>(surface: &S, f: &F, index: usize, n: usize) -> Option<Piece>
    where
        S: PiecewiseSurface + ?Sized,
        F: PieceFunction,
    {
        let shape = surface.piece_shape(index);
        let frame = shape.frame()?;
        let polygon = ConvexPolygon::new(shape.corners());
        let diameter = polygon.diameter();
        let (points, lines) = hunting_mesh(&shape, &frame, n);
        let values = points.iter().map(|&p| f.eval(index, &frame, p).0).collect();
        Some(Piece {
            index,
            frame,
            polygon,
            diameter,
            points,
            values,
            lines,
        })
    }

    /// f − c with its gradient on this piece (central differences if not exact).
    fn sample<F: PieceFunction>(&self, f: &F, c: f64, uv: Point2<f64>) -> Option<Sample> {
        let (v, jet) = f.eval(self.index, &self.frame, uv);
        if !v.is_finite() {
            return None;
        }
        let grad = match f.gradient(&jet) {
            Some(g) => g,
            None => {
                let h = 1e-5 * self.diameter;
                let at = |d: Vector2<f64>| f.eval(self.index, &self.frame, uv + d).0;
                let (ex, ey) = (Vector2::new(h, 0.0), Vector2::new(0.0, h));
                Vector2::new(
                    (at(ex) - at(-ex)) / (2.0 * h),
                    (at(ey) - at(-ey)) / (2.0 * h),
                )
            }
        };
        grad.iter().all(|x| x.is_finite()).then_some(Sample {
            f: v - c,
            grad,
            point: jet.value,
            su: jet.dx,
            sv: jet.dy,
        })
    }

    /// The seeds of level c: a root of f − c on every hunting segment with a sign change
    /// (and at mesh points where f = c exactly).
    fn seeds<F: PieceFunction>(&self, f: &F, c: f64, tol: f64) -> Vec<Seed> {
        let mut out = Vec::new();
        for line in &self.lines {
            for w in line.windows(2) {
                let (pa, pb) = (self.points[w[0]], self.points[w[1]]);
                let (fa, fb) = (self.values[w[0]] - c, self.values[w[1]] - c);
                if !(fa.is_finite() && fb.is_finite()) {
                    continue;
                }
                let root = if fa == 0.0 {
                    Some(0.0)
                } else if fa * fb < 0.0 {
                    let mut value = |t: f64| {
                        let v = f.eval(self.index, &self.frame, pa + (pb - pa) * t).0 - c;
                        v.is_finite().then_some(v)
                    };
                    illinois(&mut value, (0.0, fa, 1.0, fb), tol)
                } else {
                    None
                };
                if let Some(t) = root {
                    out.push(Seed {
                        uv: pa + (pb - pa) * t,
                    });
                }
            }
        }
        out
    }

    fn trace<F: PieceFunction>(
        &self,
        f: &F,
        c: f64,
        tol: f64,
        opts: &ZeroSetOptions,
        budget: &AtomicUsize,
    ) -> PieceLevel {
        let mut out = PieceLevel::default();
        if self.values.iter().all(|&v| v == c) {
            out.flat = true;
            return out;
        }
        let seeds = self.seeds(f, c, tol);
        if seeds.is_empty() {
            return out;
        }
        let mut used = vec![false; seeds.len()];
        // Seeds near a traced chord are on this branch: the chord is within a tenth of its
        // length of the curve (the turn per step is bounded; a walk's staircase is within a
        // step), so seeds that close to it are used up. A distinct branch that close is
        // below the tracer's resolution.
        let slack = match opts.method {
            TraceMethod::PredictorCorrector => 0.1,
            _ => 1.0,
        };
        for si in 0..seeds.len() {
            if used[si] {
                continue;
            }
            used[si] = true;
            let mut seen = |a: Point2<f64>, b: Point2<f64>| {
                let reach = slack * (b - a).norm() + 1e-9 * self.diameter;
                for (k, sd) in seeds.iter().enumerate() {
                    if !used[k] && distance_to_segment(sd.uv, a, b) <= reach {
                        used[k] = true;
                    }
                }
                false
            };
            let start = seeds[si].uv;
            match self.branch_from(f, c, start, tol, opts, budget, &mut seen, &mut out.stuck) {
                Some(b) => out.branches.push(b),
                None if budget.load(Ordering::Relaxed) == 0 => break,
                None => {}
            }
        }
        out
    }

    /// The branch through the point near `start` (corrected onto f = c), followed both ways;
    /// `None` if the corrector fails there (counted in `stuck`) or the point budget is spent.
    #[allow(clippy::too_many_arguments)]
    fn branch_from<F: PieceFunction>(
        &self,
        f: &F,
        c: f64,
        start: Point2<f64>,
        tol: f64,
        opts: &ZeroSetOptions,
        budget: &AtomicUsize,
        seen: &mut dyn FnMut(Point2<f64>, Point2<f64>) -> bool,
        stuck: &mut usize,
    ) -> Option<PieceBranch> {
        let left = budget.load(Ordering::Relaxed);
        if left == 0 {
            return None;
        }
        let mut sample = |uv: Point2<f64>| self.sample(f, c, uv);
        let corrected = correct(&mut sample, start, tol);
        let Some(((uv0, s0), t0)) = corrected.and_then(|(uv, s)| Some(((uv, s), tangent_at(&s)?)))
        else {
            *stuck += 1;
            return None;
        };
        let forward = self.follow(&mut sample, (uv0, s0), t0, tol, opts, left, seen);
        let (backward, closed) = if forward.end == End::Closed {
            (None, true)
        } else {
            let b = self.follow(&mut sample, (uv0, s0), -t0, tol, opts, left, seen);
            (Some(b), false)
        };
        *stuck += usize::from(forward.end == End::Stuck)
            + usize::from(backward.as_ref().is_some_and(|b| b.end == End::Stuck));
        let branch = assemble(uv0, s0.point, &forward, backward.as_ref(), closed);
        let n = branch.uvs.len();
        budget
            .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |b| {
                Some(b.saturating_sub(n))
            })
            .ok()
            .map(|_| branch)
    }

    /// Follows one direction from the start with the chosen method.
    #[allow(clippy::too_many_arguments)]
    fn follow(
        &self,
        sample: &mut dyn FnMut(Point2<f64>) -> Option<Sample>,
        start: (Point2<f64>, Sample),
        dir: Vector2<f64>,
        tol: f64,
        opts: &ZeroSetOptions,
        left: usize,
        seen: &mut dyn FnMut(Point2<f64>, Point2<f64>) -> bool,
    ) -> Branch {
        let scale = tol / opts.tolerance;
        match opts.method {
            TraceMethod::PredictorCorrector => Follow {
                step: opts.step * self.diameter,
                in_space: false,
                min_fraction: 1e-6,
                max_turn: 0.2,
                tolerance: tol,
                singular: 1e-9 * scale / self.diameter,
                length: f64::INFINITY,
                max_points: left.min(100_000),
            }
            .run(sample, &self.polygon, start, dir, seen),
            TraceMethod::FourPoint | TraceMethod::EightPoint => super::walk::walk(
                sample,
                &self.polygon,
                start,
                dir,
                super::walk::Walk {
                    step: 0.25 * opts.step * self.diameter,
                    tolerance: opts.walk_tolerance * scale,
                    edge_tolerance: tol,
                    eight: opts.method == TraceMethod::EightPoint,
                    max_points: left.min(100_000),
                },
                seen,
            ),
        }
    }
}

/// The unit tangent of the zero set at a sample, `None` where ∇f = 0.
fn tangent_at(s: &Sample) -> Option<Vector2<f64>> {
    let n = s.grad.norm();
    (n > 0.0).then(|| Vector2::new(-s.grad.y, s.grad.x) / n)
}

/// The branch: backward points reversed, the start, the forward points.
fn assemble(
    uv0: Point2<f64>,
    p0: Vector3<f64>,
    forward: &Branch,
    backward: Option<&Branch>,
    closed: bool,
) -> PieceBranch {
    let edge = |b: &Branch| match b.end {
        End::Edge(e) => Some(e),
        _ => None,
    };
    let mut uvs = Vec::new();
    let mut points = Vec::new();
    if let Some(b) = backward {
        uvs.extend(b.uvs.iter().rev());
        points.extend(b.points.iter().rev());
    }
    uvs.push(uv0);
    points.push(p0);
    uvs.extend(&forward.uvs);
    points.extend(&forward.points);
    if closed {
        // The forward branch ends on its start again.
        uvs.pop();
        points.pop();
    }
    dedup(&mut uvs, &mut points);
    PieceBranch {
        uvs,
        points,
        closed,
        start_edge: backward.and_then(edge),
        end_edge: if closed { None } else { edge(forward) },
    }
}

/// Drops consecutive repeated points.
fn dedup(uvs: &mut Vec<Point2<f64>>, points: &mut Vec<Vector3<f64>>) {
    let mut k = 0;
    for i in 0..uvs.len() {
        if k == 0 || uvs[i] != uvs[k - 1] {
            uvs[k] = uvs[i];
            points[k] = points[i];
            k += 1;
        }
    }
    uvs.truncate(k);
    points.truncate(k);
}

/// The hunting mesh of a piece: its points and its lines (as indices, in order).
fn hunting_mesh(
    shape: &PieceShape,
    frame: &PieceFrame,
    n: usize,
) -> (Vec<Point2<f64>>, Vec<Vec<usize>>) {
    let nf = n as f64;
    match shape {
        PieceShape::Triangle(tri) => {
            // Points (a, b) with a + b ≤ n: τ = (a/n, b/n, (n − a − b)/n).
            let index = |a: usize, b: usize| a * (n + 1) - a * (a.saturating_sub(1)) / 2 + b;
            let mut points = Vec::new();
            for a in 0..=n {
                for b in 0..=n - a {
                    let t = [a as f64 / nf, b as f64 / nf, (n - a - b) as f64 / nf];
                    points.push(tri.point(t));
                }
            }
            // `index` must agree with the push order: rows a of length n − a + 1.
            debug_assert_eq!(index(n, 0), points.len() - 1);
            let mut lines = Vec::new();
            for j in 0..n {
                // τ1 = j/n, τ2 = j/n, τ3 = j/n.
                lines.push((0..=n - j).map(|b| index(j, b)).collect());
                lines.push((0..=n - j).map(|a| index(a, j)).collect());
                lines.push((0..=n - j).map(|a| index(a, n - j - a)).collect());
            }
            (points, lines)
        }
        PieceShape::Rectangle(_) => {
            let index = |a: usize, b: usize| a * (n + 1) + b;
            let mut points = Vec::new();
            for a in 0..=n {
                for b in 0..=n {
                    points.push(frame.at_st(a as f64 / nf, b as f64 / nf).uv);
                }
            }
            let mut lines = Vec::new();
            for j in 0..=n {
                lines.push((0..=n).map(|b| index(j, b)).collect());
                lines.push((0..=n).map(|a| index(a, j)).collect());
            }
            (points, lines)
        }
    }
}
