//! Delaunay triangulations of scattered points (by the `spade` crate).

use nalgebra::Point2;
use spade::{DelaunayTriangulation, Triangulation as _};

use super::{Triangulation, TriangulationError};

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
    if triangles.is_empty() {
        return Err(TriangulationError::CollinearPoints);
    }
    Triangulation::try_new(points, triangles)
}
