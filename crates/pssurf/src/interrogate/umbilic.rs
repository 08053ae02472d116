//! Umbilics: the points where κ1 = κ2, so that every direction is principal and lines of
//! curvature meet in the patterns of seed 001 (stars, lemons, monstars).
//!
//! In the orthonormal frame e1 = s_u/|s_u|, e2 = n × e1 the shape operator is a symmetric
//! matrix S; its traceless part r = ((S11 − S22)/2, S12) is a smooth function of (u, v) inside
//! a piece and |r| = (κ1 − κ2)/2. Umbilics are the common zeros of r's two components: on
//! every piece, r is sampled on a lattice and Newton's method (central-difference Jacobian)
//! is started from the samples where |r| is smallest. A piece where r vanishes at every
//! sample (a piece of a sphere or of a plane) is reported as umbilic throughout.

use nalgebra::{Matrix2, Point2, Vector2, Vector3};
use rayon::prelude::*;

use super::continuation::{ConvexPolygon, Region, distance_to_segment};
use super::curvature::umbilic_residual;
use crate::surface::{PieceFrame, PieceShape, PiecewiseSurface};

/// An isolated umbilic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Umbilic {
    /// Its parameters.
    pub uv: Point2<f64>,
    /// Its point in space.
    pub point: Vector3<f64>,
    /// The (common) principal curvature κ1 = κ2 = H there.
    pub curvature: f64,
    /// The piece it was found on.
    pub piece: usize,
}

/// The umbilics of a surface.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Umbilics {
    /// Isolated umbilics, each once.
    pub points: Vec<Umbilic>,
    /// Pieces on which every sampled point is an umbilic (spherical or planar pieces).
    pub umbilic_pieces: Vec<usize>,
}

/// Samples per piece edge of the search lattice.
const LATTICE: usize = 6;
/// Roots closer than this (relative to the piece) are one umbilic: at the umbilics of
/// surfaces of revolution r vanishes to second order, and Newton then stalls about √ε away.
const SAME: f64 = 1e-5;
/// Newton starts per piece.
const STARTS: usize = 3;

/// Finds the umbilics of `surface`, piece by piece in parallel.
pub fn find_umbilics<S: PiecewiseSurface + ?Sized>(surface: &S) -> Umbilics {
    let found: Vec<PieceUmbilics> = (0..surface.piece_count())
        .into_par_iter()
        .map(|k| piece_umbilics(surface, k))
        .collect();
    let mut out = Umbilics::default();
    for (k, p) in found.into_iter().enumerate() {
        match p {
            PieceUmbilics::Everywhere => out.umbilic_pieces.push(k),
            PieceUmbilics::Isolated(points) => {
                for u in points {
                    // An umbilic on a shared edge or corner is found from every piece there.
                    let tol = SAME * piece_size(&surface.piece_shape(k));
                    if !out.points.iter().any(|q| (q.uv - u.uv).norm() <= tol) {
                        out.points.push(u);
                    }
                }
            }
        }
    }
    out
}

/// The umbilic that Newton's method reaches from `uv`, if any: started on the piece that
/// contains `uv`, and restarted on the piece where it lands until it lands in its own piece.
pub fn umbilic_near<S: PiecewiseSurface + ?Sized>(surface: &S, uv: Point2<f64>) -> Option<Umbilic> {
    let mut at = uv;
    for _ in 0..8 {
        let piece = surface.jet(at).ok()?.piece;
        let shape = surface.piece_shape(piece);
        let frame = shape.frame()?;
        let scale = residual_scale(surface, piece, &frame, &lattice(&shape));
        let root = newton(surface, piece, &frame, &shape, at, scale)?;
        if inside(&shape, root.uv) {
            return Some(root);
        }
        at = root.uv;
    }
    None
}

enum PieceUmbilics {
    Everywhere,
    Isolated(Vec<Umbilic>),
}

fn piece_size(shape: &PieceShape) -> f64 {
    ConvexPolygon::new(shape.corners()).diameter()
}

/// The lattice of sample points of a piece.
fn lattice(shape: &PieceShape) -> Vec<Point2<f64>> {
    let n = LATTICE as f64;
    match shape {
        PieceShape::Triangle(t) => {
            let mut out = Vec::new();
            for i in 0..=LATTICE {
                for j in 0..=LATTICE - i {
                    let (a, b) = (i as f64 / n, j as f64 / n);
                    out.push(t.point([a, b, 1.0 - a - b]));
                }
            }
            out
        }
        PieceShape::Rectangle(r) => (0..=LATTICE)
            .flat_map(|i| (0..=LATTICE).map(move |j| (i, j)))
            .map(|(i, j)| {
                Point2::new(
                    r.min.x + (r.max.x - r.min.x) * i as f64 / n,
                    r.min.y + (r.max.y - r.min.y) * j as f64 / n,
                )
            })
            .collect(),
    }
}

/// r and H on piece `k` at `uv` (the piece's polynomial, extended beyond it).
fn residual<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    k: usize,
    frame: &PieceFrame,
    uv: Point2<f64>,
) -> Option<(Vector2<f64>, f64)> {
    let (r, h) = umbilic_residual(&surface.piece_jet(k, &frame.at_uv(uv)))?;
    (r.iter().all(|x| x.is_finite()) && h.is_finite()).then_some((r, h))
}

/// The size of curvature on the piece: the largest |H| + |r| over its samples.
fn residual_scale<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    k: usize,
    frame: &PieceFrame,
    samples: &[Point2<f64>],
) -> f64 {
    samples
        .iter()
        .filter_map(|&p| residual(surface, k, frame, p))
        .map(|(r, h)| h.abs() + r.norm())
        .fold(0.0, f64::max)
}

fn piece_umbilics<S: PiecewiseSurface + ?Sized>(surface: &S, k: usize) -> PieceUmbilics {
    let shape = surface.piece_shape(k);
    let Some(frame) = shape.frame() else {
        return PieceUmbilics::Isolated(Vec::new());
    };
    let samples = lattice(&shape);
    let mut values: Vec<(f64, Point2<f64>)> = samples
        .iter()
        .filter_map(|&p| residual(surface, k, &frame, p).map(|(r, _)| (r.norm(), p)))
        .collect();
    let scale = residual_scale(surface, k, &frame, &samples);
    let size = piece_size(&shape);
    let worst = values.iter().map(|v| v.0).fold(0.0, f64::max);
    // Umbilic throughout: r vanishes at every sample, relative to the curvature there, or
    // the piece is flat to rounding (no curvature at all on the scale of its size).
    if !values.is_empty() && (worst <= 1e-9 * scale || scale * size <= 1e-13) {
        return PieceUmbilics::Everywhere;
    }
    values.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut found: Vec<Umbilic> = Vec::new();
    for (_, start) in values.iter().take(STARTS) {
        if let Some(u) = newton(surface, k, &frame, &shape, *start, scale)
            && inside(&shape, u.uv)
            && !found.iter().any(|q| (q.uv - u.uv).norm() <= SAME * size)
        {
            found.push(u);
        }
    }
    PieceUmbilics::Isolated(found)
}

/// Newton's method on r = 0 from `start` on piece `k` (its polynomial extended beyond it);
/// the root if it converges.
fn newton<S: PiecewiseSurface + ?Sized>(
    surface: &S,
    k: usize,
    frame: &PieceFrame,
    shape: &PieceShape,
    start: Point2<f64>,
    scale: f64,
) -> Option<Umbilic> {
    let size = piece_size(shape);
    let h = 1e-6 * size;
    let mut uv = start;
    for _ in 0..40 {
        let (r, _) = residual(surface, k, frame, uv)?;
        let d = |e: Vector2<f64>| -> Option<Vector2<f64>> {
            let (a, _) = residual(surface, k, frame, uv + e)?;
            let (b, _) = residual(surface, k, frame, uv - e)?;
            Some((a - b) / (2.0 * h))
        };
        let (du, dv) = (d(Vector2::new(h, 0.0))?, d(Vector2::new(0.0, h))?);
        let step = Matrix2::from_columns(&[du, dv]).lu().solve(&-r)?;
        // Keep Newton near the piece: a step longer than the piece is a divergence.
        if !step.iter().all(|x| x.is_finite()) || step.norm() > 2.0 * size {
            return None;
        }
        uv += step;
        if step.norm() <= 1e-13 * size {
            break;
        }
    }
    let (r, mean) = residual(surface, k, frame, uv)?;
    (r.norm() <= 1e-8 * scale.max(f64::MIN_POSITIVE)).then(|| Umbilic {
        uv,
        point: surface.piece_jet(k, &frame.at_uv(uv)).value,
        curvature: mean,
        piece: k,
    })
}

/// Whether `uv` lies in the piece, or within rounding of its boundary.
fn inside(shape: &PieceShape, uv: Point2<f64>) -> bool {
    let polygon = ConvexPolygon::new(shape.corners());
    let size = polygon.diameter();
    polygon.contains(uv)
        || polygon
            .edges()
            .any(|(a, b)| distance_to_segment(uv, a, b) <= 1e-9 * size)
}
