//! The coarse triangulation of a smoothing fit: a regular grid over the data's bounding box.
//!
//! Like Dierckx's smoothing splines (FITPACK `surfit`), the fit lives on the bounding box, so
//! every data point is inside and no triangle is a sliver or a needle, whatever the data:
//! nearly collinear runs on the hull or nearly coincident points would make such triangles
//! if the vertices were data points. Vertices with no data nearby are held by the energy.

use nalgebra::Point2;

use crate::triangulation::{COORDINATE_RESOLUTION, Triangulation, TriangulationError};

/// The shortest side of the box relative to the longest: flatter data get a box this thick.
const MIN_ASPECT: f64 = 1e-3;

/// The smallest grid spacing relative to the largest coordinate magnitude, 2^-32 ≈ 2.3e-10
/// (2^20 units in the last place; 2.3 mm at UTM-sized coordinates of 1e7): far from the
/// origin, finer vertices could not be placed exactly enough.
const MIN_SPACING: f64 = COORDINATE_RESOLUTION * (1u64 << 12) as f64;

/// The bounding box of the data, thickened to an aspect ratio of at least 1 : 1000.
fn data_box(points: &[Point2<f64>]) -> (Point2<f64>, Point2<f64>) {
    let first = points[0];
    let (mut lo, mut hi) = (first, first);
    for p in points {
        lo = Point2::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point2::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    let long = (hi.x - lo.x).max(hi.y - lo.y);
    for axis in 0..2 {
        let short = hi[axis] - lo[axis];
        if short < MIN_ASPECT * long {
            let pad = 0.5 * (MIN_ASPECT * long - short);
            lo[axis] -= pad;
            hi[axis] += pad;
        }
    }
    (lo, hi)
}

/// The number of grid vertices along x and y: about `m` in all, cells about square, at
/// least 2 per side, no finer than the coordinates resolve.
fn grid_size(lo: Point2<f64>, hi: Point2<f64>, m: usize) -> [usize; 2] {
    let extent = hi - lo;
    let magnitude = lo.coords.abs().max().max(hi.coords.abs().max());
    let finest = MIN_SPACING * magnitude;
    let m = m.max(4) as f64;
    let nx = (m * extent.x / extent.y).sqrt().round().max(2.0);
    let ny = (m / nx).round().max(2.0);
    // A flat box has 2 rows: then the columns share m.
    let nx = (m / ny).round().max(2.0).min(nx);
    let fit = |n: f64, length: f64| -> usize {
        let most = if finest > 0.0 {
            (length / finest).floor() + 1.0
        } else {
            n
        };
        n.min(most).max(2.0) as usize
    };
    [fit(nx, extent.x), fit(ny, extent.y)]
}

/// The most vertices a coarse grid gets, whatever `m` asks for (2^24; `smooth_scattered`
/// asks for fewer than the data points, so this bounds direct callers only).
pub const MAX_COARSE_VERTICES: usize = 1 << 24;

/// A grid of about `m` (at most 2²⁴, `MAX_COARSE_VERTICES`) vertices over the data's bounding
/// box, thickened to at least 1 : 1000, each cell split into two triangles along alternating
/// diagonals. The box contains every point (its sides are the data's extremes, or lie beyond
/// them where it was thickened), so every point lies in a triangle. Fails on no points, on
/// coordinates outside the supported range (see
/// [`check_coordinates`](crate::triangulation::check_coordinates)), and on points that all
/// coincide.
pub fn coarse_triangulation(
    points: &[Point2<f64>],
    m: usize,
) -> Result<Triangulation, TriangulationError> {
    crate::triangulation::check_coordinates(points)?;
    if points.is_empty() {
        return Err(TriangulationError::CollinearPoints);
    }
    let (lo, hi) = data_box(points);
    if !(hi.x > lo.x && hi.y > lo.y) {
        return Err(TriangulationError::CollinearPoints);
    }
    let m = m.min(MAX_COARSE_VERTICES);
    let [nx, ny] = grid_size(lo, hi, m);
    let coordinate = |lo: f64, hi: f64, n: usize, i: usize| {
        if i + 1 == n {
            hi
        } else {
            lo + (hi - lo) * (i as f64 / (n - 1) as f64)
        }
    };
    let mut vertices = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            vertices.push(Point2::new(
                coordinate(lo.x, hi.x, nx, i),
                coordinate(lo.y, hi.y, ny, j),
            ));
        }
    }
    let at = |i: usize, j: usize| j * nx + i;
    let mut triangles = Vec::with_capacity(2 * (nx - 1) * (ny - 1));
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if (i + j) % 2 == 0 {
                triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                triangles.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    Triangulation::try_new(vertices, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::*;

    #[test]
    fn the_grid_covers_every_point_with_about_m_vertices() {
        let mut r = rng(142);
        for (n, m, offset, stretch) in [
            (5000, 500, 0.0, 1.0),
            (20000, 300, 1e6, 3.0),
            (3000, 2900, -40.0, 0.01),
            (100, 1000, 0.0, 1e-9),
        ] {
            let pts: Vec<Point2<f64>> = (0..n)
                .map(|_| {
                    Point2::new(
                        offset + uniform(&mut r, 0.0, 1.0),
                        offset + stretch * uniform(&mut r, 0.0, 1.0),
                    )
                })
                .collect();
            let t = coarse_triangulation(&pts, m).unwrap();
            let got = t.vertex_count() as f64;
            assert!(
                got > 0.7 * m as f64 && got < 1.4 * m as f64,
                "n {n}, m {m}: {got}"
            );
            for p in &pts {
                assert!(t.locate(*p).is_some(), "{p} inside");
            }
            // No sliver: every triangle is half a cell of aspect ≤ 1000.
            for k in 0..t.triangle_count() {
                let g = t.triangle_geometry(k);
                assert!(g.det().abs() > 1e-4 * g.diameter().powi(2), "triangle {k}");
            }
        }
    }

    #[test]
    fn far_from_the_origin_the_grid_is_no_finer_than_the_coordinates_resolve() {
        // 30 points spread 1e-3 at 1e9, where doubles are 1.2e-7 apart.
        let mut r = rng(7);
        let pts: Vec<Point2<f64>> = (0..30)
            .map(|_| {
                Point2::new(
                    1e9 + uniform(&mut r, 0.0, 1e-3),
                    1e9 + uniform(&mut r, 0.0, 1e-3),
                )
            })
            .collect();
        let t = coarse_triangulation(&pts, 400).unwrap();
        assert_eq!(t.vertex_count(), 4);
        assert!(pts.iter().all(|p| t.locate(*p).is_some()));
    }
}
