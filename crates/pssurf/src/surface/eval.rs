//! The one chunked, parallel evaluation loop: consecutive points in chunks, one cursor per
//! chunk, so grids and curves cost short walks and every core gets work.

use nalgebra::Point2;
use rayon::prelude::*;

use super::{Cursor, OutsideDomain, ParametricSurface, SurfaceJet};

/// Points per chunk: large enough to amortise a chunk's first (bucket-grid) location, small
/// enough to balance the cores.
pub(crate) const CHUNK: usize = 8192;

/// Calls `f(points, out)` on consecutive chunks of `points` and the matching `width`-wide
/// rows of `out`, in parallel. `out.len()` must be `points.len() * width`.
pub(crate) fn for_each_chunk<T: Send>(
    points: &[Point2<f64>],
    out: &mut [T],
    width: usize,
    f: impl Fn(&[Point2<f64>], &mut [T]) + Sync,
) {
    assert_eq!(out.len(), points.len() * width, "one row per point");
    if width == 0 {
        return;
    }
    points
        .par_chunks(CHUNK)
        .zip(out.par_chunks_mut(CHUNK * width))
        .for_each(|(pts, rows)| f(pts, rows));
}

/// Jets at many parameter points, in parallel on all cores (see `for_each_chunk`).
pub fn jets<S: ParametricSurface + ?Sized>(
    surface: &S,
    points: &[Point2<f64>],
) -> Vec<Result<SurfaceJet, OutsideDomain>> {
    let mut out = vec![Err(OutsideDomain::at(Point2::new(f64::NAN, f64::NAN))); points.len()];
    for_each_chunk(points, &mut out, 1, |pts, res| {
        let mut cursor = chunk_cursor(surface, pts);
        for (r, &p) in res.iter_mut().zip(pts) {
            *r = surface.jet_with(p, &mut cursor);
        }
    });
    out
}

/// Evaluates `f(point, jet, row)` at every point in parallel, writing `width` numbers per
/// point into `out` (`out.len() == points.len() * width`); points outside the domain get
/// `f(point, Err, row)`. Nothing is materialised per point, so this is the way to fill large
/// output tables.
pub fn fill_rows<S: ParametricSurface + ?Sized>(
    surface: &S,
    points: &[Point2<f64>],
    width: usize,
    out: &mut [f64],
    f: impl Fn(Point2<f64>, Result<&SurfaceJet, OutsideDomain>, &mut [f64]) + Sync,
) {
    for_each_chunk(points, out, width, |pts, rows| {
        let mut cursor = chunk_cursor(surface, pts);
        for (&p, row) in pts.iter().zip(rows.chunks_mut(width)) {
            match surface.jet_with(p, &mut cursor) {
                Ok(j) => f(p, Ok(&j), row),
                Err(e) => f(p, Err(e), row),
            }
        }
    });
}

/// A cursor near the first point of a chunk.
fn chunk_cursor<S: ParametricSurface + ?Sized>(surface: &S, pts: &[Point2<f64>]) -> Cursor {
    pts.first()
        .map_or_else(Cursor::default, |&p| surface.cursor_near(p))
}
