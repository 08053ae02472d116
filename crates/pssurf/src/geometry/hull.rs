//! Convex hulls of small point sets.

use nalgebra::Point2;

use super::orient_exact;

/// The convex hull of `points`, counter-clockwise, without repeated or collinear vertices
/// (Andrew's monotone chain with exact orientation tests: a vertex is dropped only when it
/// is exactly collinear or reflex, so nearly collinear true corners stay). Fewer than three
/// vertices means the points are exactly collinear.
pub fn convex_hull(points: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let mut sorted = points.to_vec();
    let mut hull = Vec::with_capacity(points.len() + 1);
    convex_hull_into(&mut sorted, &mut hull);
    hull
}

/// As [`convex_hull`], reusing buffers: `points` is sorted in place, the hull is written to
/// `hull` (cleared first).
pub fn convex_hull_into(points: &mut [Point2<f64>], hull: &mut Vec<Point2<f64>>) {
    hull.clear();
    points.sort_unstable_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    let n = points.len();
    if n == 0 {
        return;
    }
    // Only a strict left turn keeps a vertex; repeated points make no turn and are dropped
    // with the collinear ones.
    let push = |hull: &mut Vec<Point2<f64>>, start: usize, p: Point2<f64>| {
        while hull.len() >= start + 2
            && orient_exact(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
        {
            hull.pop();
        }
        if hull.len() < start + 1 || hull[hull.len() - 1] != p {
            hull.push(p);
        }
    };
    for &p in points.iter() {
        push(hull, 0, p);
    }
    let lower = hull.len();
    hull.pop();
    for &p in points.iter().rev() {
        push(hull, lower - 1, p);
    }
    hull.pop();
    if hull.len() < 3 {
        // Collinear (or repeated) points: report the distinct extremes only.
        hull.clear();
        hull.push(points[0]);
        if points[n - 1] != points[0] {
            hull.push(points[n - 1]);
        }
    }
}

/// True when `p` lies in the closed convex polygon `hull` (counter-clockwise), within a
/// tolerance relative to the polygon's size (for tests of constructions that round).
pub fn point_in_convex(hull: &[Point2<f64>], p: Point2<f64>, tol: f64) -> bool {
    let n = hull.len();
    let size = hull
        .iter()
        .map(|q| (q - hull[0]).norm_squared())
        .fold(0.0, f64::max);
    (0..n).all(|i| super::orient(hull[i], hull[(i + 1) % n], p) >= -tol * size)
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

    /// Issue 12, defect 1: a tolerance relative to the set's size dropped true corners that
    /// are nearly collinear with their neighbours (here (1, 1e-15) over the segment from
    /// (0, 0) to (2, 0): the old hull reported the three points as collinear).
    #[test]
    fn a_nearly_collinear_true_corner_stays_on_the_hull() {
        let p = |x, y| Point2::new(x, y);
        let corner = p(1.0, 1e-15);
        let pts = [p(0.0, 0.0), corner, p(2.0, 0.0), p(1.0, 0.0)];
        let h = convex_hull(&pts);
        assert_eq!(h, vec![p(0.0, 0.0), p(2.0, 0.0), corner]);
        let far = [
            p(1e6, 1e6),
            p(1e6 + 1.0, 1e6 + 1.0 + 1e-9),
            p(1e6 + 2.0, 1e6 + 2.0),
        ];
        assert_eq!(
            convex_hull(&far).len(),
            3,
            "a corner 1e-9 off a line at 1e6"
        );
    }

    /// Random sets, many of them nearly collinear (points on a line moved by a few ulps):
    /// every point lies in the hull, every hull vertex is a strict left turn and an input
    /// point — all decided exactly.
    #[test]
    fn random_and_nearly_collinear_hulls_are_exact() {
        use crate::test_util::{rng, uniform};
        let mut r = rng(40);
        let mut nearly_collinear = 0;
        for case in 0..3000 {
            let n = 3 + case % 20;
            let pts: Vec<Point2<f64>> = if case % 2 == 0 {
                (0..n)
                    .map(|_| Point2::new(uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0)))
                    .collect()
            } else {
                nearly_collinear += 1;
                let (a, d) = (uniform(&mut r, -1e3, 1e3), uniform(&mut r, -3.0, 3.0));
                (0..n)
                    .map(|_| {
                        let t = uniform(&mut r, -1.0, 1.0);
                        let y = a + d * t;
                        let ulps = uniform(&mut r, -4.0, 4.0).round();
                        Point2::new(t, y + ulps * f64::EPSILON * y.abs().max(1.0))
                    })
                    .collect()
            };
            let h = convex_hull(&pts);
            let m = h.len();
            if m < 3 {
                // Exactly collinear: every triple is.
                assert!(
                    pts.windows(3)
                        .all(|w| orient_exact(w[0], w[1], w[2]) == 0.0)
                );
                continue;
            }
            for k in 0..m {
                assert!(orient_exact(h[k], h[(k + 1) % m], h[(k + 2) % m]) > 0.0);
                assert!(pts.contains(&h[k]));
            }
            for &q in &pts {
                assert!((0..m).all(|k| orient_exact(h[k], h[(k + 1) % m], q) >= 0.0));
            }
        }
        assert_eq!(nearly_collinear, 1500);
    }
}
