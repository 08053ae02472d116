//! Convex hulls of small point sets.

use nalgebra::Point2;

use super::orient;

/// The convex hull of `points`, counter-clockwise, without repeated or collinear vertices
/// (Andrew's monotone chain). Fewer than three vertices means the points are collinear.
pub fn convex_hull(points: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let mut pts: Vec<Point2<f64>> = points.to_vec();
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let scale = pts
        .iter()
        .map(|p| (p - pts[0]).norm_squared())
        .fold(0.0, f64::max);
    // A turn counts only when it is clearly positive relative to the set's size.
    let eps = 1e-14 * scale;
    let mut hull: Vec<Point2<f64>> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point2<f64>>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && orient(hull[hull.len() - 2], hull[hull.len() - 1], p) <= eps
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// True when `p` lies in the closed convex polygon `hull` (counter-clockwise), within a
/// tolerance relative to the polygon's size.
pub fn point_in_convex(hull: &[Point2<f64>], p: Point2<f64>, tol: f64) -> bool {
    let n = hull.len();
    let size = hull
        .iter()
        .map(|q| (q - hull[0]).norm_squared())
        .fold(0.0, f64::max);
    (0..n).all(|i| orient(hull[i], hull[(i + 1) % n], p) >= -tol * size)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_square_with_interior_and_edge_points() {
        let p = |x, y| Point2::new(x, y);
        let pts = [
            p(0., 0.),
            p(1., 0.),
            p(0.5, 0.),
            p(1., 1.),
            p(0., 1.),
            p(0.5, 0.5),
            p(0., 0.),
        ];
        let h = convex_hull(&pts);
        assert_eq!(h, vec![p(0., 0.), p(1., 0.), p(1., 1.), p(0., 1.)]);
        assert_eq!(convex_hull(&[p(0., 0.), p(1., 1.), p(2., 2.)]).len(), 2);
    }
}
