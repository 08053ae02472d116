//! Merging nearly coincident data points before interpolation.
//!
//! Interpolating different values at points 1e-12 apart asks for slopes of 1e12: the
//! gradient estimates, the PS split of the needle triangles between such points and the
//! validity margins of the refinement all break down. Points closer than
//! [`NEAR_DUPLICATE`] × the data's extent are therefore replaced by their mean (position
//! and value), and the caller warns naming the rows. So are points closer than
//! [`COORDINATE_RESOLUTION`](crate::triangulation::COORDINATE_RESOLUTION) × the largest coordinate, a few
//! units in the last place: far from the origin (1e6 + ε), the triangles between them are
//! finer than the split points can be placed.

use nalgebra::Point2;

use super::diagnostics::near_duplicates;

/// Relative distance (a fraction of the diagonal of the data's bounding box) below which
/// two distinct data points count as nearly duplicate and are merged.
pub const NEAR_DUPLICATE: f64 = 1e-9;

/// Data points after merging nearly coincident ones.
#[derive(Clone, Debug, PartialEq)]
pub struct MergedData {
    /// The points: each is one input point or the mean of a group of merged ones.
    pub points: Vec<Point2<f64>>,
    /// The values, likewise.
    pub values: Vec<f64>,
    /// For each point, the smallest input index it came from.
    pub first_index: Vec<usize>,
    /// The groups of input indices that were merged (each sorted, of two or more).
    pub merged: Vec<Vec<usize>>,
}

/// The groups (sorted, of two or more indices, ordered by their first index) of points
/// linked by chains of distances below
/// [`near_duplicate_distance`](super::near_duplicate_distance);
/// distinct points only (exact duplicates are the caller's to refuse). O(n log n).
pub fn near_duplicate_groups(points: &[Point2<f64>], relative: f64) -> Vec<Vec<usize>> {
    let pairs = near_duplicates(points, relative, usize::MAX);
    if pairs.is_empty() {
        return Vec::new();
    }
    let mut parent: Vec<usize> = (0..points.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for d in &pairs {
        let (a, b) = (root(&mut parent, d.first), root(&mut parent, d.second));
        // The smaller index becomes the root, so a group's root is its first index.
        parent[a.max(b)] = a.min(b);
    }
    let mut members: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for d in &pairs {
        for i in [d.first, d.second] {
            let r = root(&mut parent, i);
            members.entry(r).or_default().push(i);
        }
    }
    members
        .into_values()
        .map(|mut g| {
            g.sort_unstable();
            g.dedup();
            g
        })
        .collect()
}

/// Replaces each group of nearly coincident points (see [`near_duplicate_groups`]) by one point at their mean with the mean value;
/// other points keep their order.
pub fn merge_near_duplicates(points: &[Point2<f64>], values: &[f64], relative: f64) -> MergedData {
    let merged = near_duplicate_groups(points, relative);
    let mut group_of = vec![usize::MAX; points.len()];
    for (g, rows) in merged.iter().enumerate() {
        rows.iter().for_each(|&i| group_of[i] = g);
    }
    let mut out = MergedData {
        points: Vec::with_capacity(points.len()),
        values: Vec::with_capacity(points.len()),
        first_index: Vec::with_capacity(points.len()),
        merged: Vec::new(),
    };
    for (i, (p, &v)) in points.iter().zip(values).enumerate() {
        match group_of[i] {
            usize::MAX => {
                out.points.push(*p);
                out.values.push(v);
                out.first_index.push(i);
            }
            g if merged[g][0] == i => {
                let rows = &merged[g];
                let n = rows.len() as f64;
                // Offsets from the first point keep the mean exact to rounding even far
                // from the origin.
                let shift = rows
                    .iter()
                    .fold(nalgebra::Vector2::zeros(), |s, &k| s + (points[k] - p))
                    / n;
                out.points.push(p + shift);
                out.values
                    .push(v + rows.iter().map(|&k| values[k] - v).sum::<f64>() / n);
                out.first_index.push(i);
            }
            _ => {}
        }
    }
    out.merged = merged;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_of_close_points_merge_into_their_mean() {
        let p = Point2::new;
        let pts = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(0.0, 1.0),
            p(1.0 + 1e-12, 0.0),
            p(1.0 + 2e-12, 0.0),
            p(1.0, 1.0),
            p(1e-13, 1.0),
        ];
        let values = [0.0, 1.0, 2.0, 3.0, 5.0, 6.0, 4.0];
        let m = merge_near_duplicates(&pts, &values, 1e-9);
        assert_eq!(m.merged, vec![vec![1, 3, 4], vec![2, 6]]);
        assert_eq!(m.first_index, vec![0, 1, 2, 5]);
        assert_eq!(m.values, vec![0.0, 3.0, 3.0, 6.0]);
        assert!((m.points[1] - p(1.0 + 1e-12, 0.0)).norm() < 1e-15);
        assert!((m.points[2] - p(0.5e-13, 1.0)).norm() < 1e-15);
        // Nothing is merged at a tighter tolerance, or when every point is far apart.
        let none = merge_near_duplicates(&pts, &values, 1e-14);
        assert!(none.merged.is_empty());
        assert_eq!(none.points, pts.to_vec());
        assert_eq!(none.first_index, (0..7).collect::<Vec<_>>());
    }
}
