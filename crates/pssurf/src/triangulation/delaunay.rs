//! Delaunay triangulations of scattered points (by the `spade` crate).

use std::collections::HashMap;

use nalgebra::Point2;
use spade::{DelaunayTriangulation, Triangulation as _};

use super::{Triangulation, TriangulationError};
use crate::geometry::Triangle2;

pub(super) fn delaunay(points: Vec<Point2<f64>>) -> Result<Triangulation, TriangulationError> {
    if let Some(i) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(TriangulationError::NonFiniteVertex(i));
    }
    // Coincident points would be merged silently by spade; report them instead.
    super::validate::check_duplicates(&points)?;
    let sp: Vec<spade::Point2<f64>> = points
        .iter()
        .map(|p| spade::Point2::new(p.x, p.y))
        .collect();
    let dt = DelaunayTriangulation::<spade::Point2<f64>>::bulk_load_stable(sp)
        .map_err(|_| TriangulationError::CollinearPoints)?;
    let triangles: Vec<[usize; 3]> = dt
        .inner_faces()
        .map(|f| f.vertices().map(|v| v.fix().index()))
        .collect();
    let triangles = peel_hull_slivers(&points, triangles);
    if triangles.is_empty() {
        return Err(TriangulationError::CollinearPoints);
    }
    // Triangles in the order of a space-filling curve through their centroids: neighbouring
    // triangles get nearby indices, so per-triangle arrays are traversed cache-friendly.
    let centroids: Vec<Point2<f64>> = triangles
        .iter()
        .map(|t| {
            Point2::from((points[t[0]].coords + points[t[1]].coords + points[t[2]].coords) / 3.0)
        })
        .collect();
    let triangles: Vec<[usize; 3]> = super::morton_order(&centroids)
        .into_iter()
        .map(|k| triangles[k as usize])
        .collect();
    Triangulation::try_new(points, triangles)
}

/// Removes numerically degenerate triangles from the boundary, repeatedly. Nearly collinear
/// points on the convex hull make Delaunay slivers of (almost) zero area; dropping them loses
/// no area, and their vertices stay in the neighbouring triangles.
fn peel_hull_slivers(points: &[Point2<f64>], mut tris: Vec<[usize; 3]>) -> Vec<[usize; 3]> {
    let degenerate =
        |t: &[usize; 3]| Triangle2::new(points[t[0]], points[t[1]], points[t[2]]).is_degenerate();
    loop {
        if !tris.iter().any(degenerate) {
            return tris;
        }
        let mut edge_count: HashMap<(usize, usize), u32> = HashMap::new();
        for t in &tris {
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                *edge_count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let on_boundary = |t: &[usize; 3]| {
            (0..3).any(|i| {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                edge_count[&(a.min(b), a.max(b))] == 1
            })
        };
        let before = tris.len();
        tris.retain(|t| !(degenerate(t) && on_boundary(t)));
        if tris.len() == before {
            return tris; // interior degeneracies are left for validation to report
        }
    }
}
