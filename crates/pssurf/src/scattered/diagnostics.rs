//! Warnings about data that interpolates badly: nearly coincident points and sliver
//! triangles.

use nalgebra::Point2;

use crate::triangulation::{COORDINATE_RESOLUTION, Triangulation};

/// Two data points closer than a given fraction of the data's diameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearDuplicate {
    /// The index of the first point.
    pub first: usize,
    /// The index of the second point (> `first`).
    pub second: usize,
    /// Their distance.
    pub distance: f64,
}

/// The distance below which two of these points count as nearly coincident: `relative` ×
/// the diagonal of their bounding box, but at least [`COORDINATE_RESOLUTION`] × their
/// largest coordinate magnitude (the finest detail the PS refinement can resolve). Zero for
/// no points.
pub fn near_duplicate_distance(points: &[Point2<f64>], relative: f64) -> f64 {
    let Some(first) = points.first() else {
        return 0.0;
    };
    let lo = points.iter().fold(first.coords, |a, p| a.inf(&p.coords));
    let hi = points.iter().fold(first.coords, |a, p| a.sup(&p.coords));
    let magnitude = lo.abs().max().max(hi.abs().max());
    (relative * (hi - lo).norm()).max(COORDINATE_RESOLUTION * magnitude)
}

/// Up to `limit` pairs of distinct points closer than [`near_duplicate_distance`] (with
/// `relative`), found with an R-tree (O(n log n), also when many points share a
/// coordinate). Interpolating values at nearly coincident points makes steep, meaningless
/// slopes; callers warn about them.
pub fn near_duplicates(points: &[Point2<f64>], relative: f64, limit: usize) -> Vec<NearDuplicate> {
    use rstar::RTree;
    use rstar::primitives::GeomWithData;
    let tol = near_duplicate_distance(points, relative);
    if !(tol > 0.0 && tol.is_finite()) || limit == 0 {
        return Vec::new();
    }
    let tree = RTree::bulk_load(
        points
            .iter()
            .enumerate()
            .map(|(k, p)| GeomWithData::new([p.x, p.y], k))
            .collect(),
    );
    let mut found = Vec::new();
    for (a, p) in points.iter().enumerate() {
        for near in tree.locate_within_distance([p.x, p.y], tol * tol) {
            let b = near.data;
            let distance = (points[b] - p).norm();
            if b > a && distance > 0.0 {
                found.push(NearDuplicate {
                    first: a,
                    second: b,
                    distance,
                });
                if found.len() == limit {
                    return found;
                }
            }
        }
    }
    found
}

/// Up to `limit` triangles whose vertices are nearly collinear: twice their area below
/// `relative` × their longest edge squared. Slivers make the split of the PS refinement and
/// the local gradient fits fragile; callers warn about them.
pub fn slivers(tri: &Triangulation, relative: f64, limit: usize) -> Vec<usize> {
    (0..tri.triangle_count())
        .filter(|&t| {
            let g = tri.triangle_geometry(t);
            let h = g.diameter();
            g.det().abs() < relative * h * h
        })
        .take(limit)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_duplicates_and_slivers_are_found_by_hand_computed_cases() {
        let p = Point2::new;
        let pts = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0 + 1e-13, 1e-13),
            p(0.0, 1.0),
            p(0.5, 0.5),
        ];
        let d = near_duplicates(&pts, 1e-10, 10);
        assert_eq!(d.len(), 1);
        assert_eq!((d[0].first, d[0].second), (1, 2));
        assert_eq!(d[0].distance, (pts[2] - pts[1]).norm());
        assert!((d[0].distance - 2f64.sqrt() * 1e-13).abs() < 1e-16);
        assert!(near_duplicates(&pts, 1e-14, 10).is_empty());
        // 200k points on one vertical line, 1 apart: none is near another, and the search
        // does not compare every pair (which would not finish).
        let line: Vec<Point2<f64>> = (0..200_000).map(|k| p(0.0, k as f64)).collect();
        assert!(near_duplicates(&line, 1e-9, 10).is_empty());
        let mut close = line.clone();
        close[7] = p(0.0, 6.0 + 1e-6);
        let d = near_duplicates(&close, 1e-9, 10);
        assert_eq!((d.len(), d[0].first, d[0].second), (1, 6, 7));
        // A triangle with apex 1e-9 above its base of length 2: twice the area 2e-9, longest
        // edge² 4, relative 5e-10.
        let t = Triangulation::try_new(
            vec![p(0.0, 0.0), p(2.0, 0.0), p(1.0, 1e-9), p(1.0, -1.0)],
            vec![[0, 1, 2], [0, 3, 1]],
        )
        .unwrap();
        assert_eq!(slivers(&t, 1e-9, 10), vec![0]);
        assert!(slivers(&t, 4e-10, 10).is_empty());
    }
}
