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

use std::ops::{Add, Div, Sub};

use nalgebra::Point2;

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
/// linked by chains of distances at most
/// [`near_duplicate_distance`](super::near_duplicate_distance); distinct points only (exact
/// duplicates are the caller's to refuse).
///
/// Points are binned in square cells of side tol / 2, whose members are all within tol of
/// each other and are joined at once; two cells at most two apart are joined when any pair
/// between them is within tol. Memory is O(n) and time O(n log n) plus, per pair of
/// neighbouring cells not yet joined, the product of their sizes (a dense cluster costs
/// linear time, unlike a search of every pair).
pub fn near_duplicate_groups(points: &[Point2<f64>], relative: f64) -> Vec<Vec<usize>> {
    let tol = super::near_duplicate_distance(points, relative);
    if !(tol > 0.0 && tol.is_finite()) {
        return Vec::new();
    }
    let lo = points
        .iter()
        .fold(points[0], |a, p| Point2::new(a.x.min(p.x), a.y.min(p.y)));
    let side = tol / 2.0;
    // Cell indices stay below 2 × (extent / tol) ≤ 2e9 × √2 since tol ≥ 1e-9 × the diagonal
    // for the relative tolerances used; saturating casts keep larger ones harmless.
    let cell_of = |p: &Point2<f64>| {
        (
            ((p.x - lo.x) / side).floor() as i64,
            ((p.y - lo.y) / side).floor() as i64,
        )
    };
    let mut keyed: Vec<((i64, i64), usize)> = points
        .iter()
        .enumerate()
        .map(|(k, p)| (cell_of(p), k))
        .collect();
    keyed.sort_unstable();
    // The occupied cells in (cx, cy) order with their members' ranges in `keyed`.
    let mut cells: Vec<((i64, i64), std::ops::Range<usize>)> = Vec::new();
    let mut start = 0;
    for k in 1..=keyed.len() {
        if k == keyed.len() || keyed[k].0 != keyed[start].0 {
            cells.push((keyed[start].0, start..k));
            start = k;
        }
    }
    let mut sets = UnionFind::new(points.len());
    let mut any = false;
    // For the columns cx + 1 and cx + 2, the first cell at or after (cx + dx, cy − 2): it
    // only moves forward as the cells are visited in order.
    let mut ahead = [0usize; 3];
    for (c, (cell, range)) in cells.iter().enumerate() {
        let members = &keyed[range.clone()];
        for w in members.windows(2) {
            sets.join(w[0].1, w[1].1);
            any = true;
        }
        // Neighbouring cells up to two away, each pair of cells visited once: (cx, cy + 1),
        // (cx, cy + 2) follow this cell; columns cx + 1, cx + 2 from cy − 2 to cy + 2.
        for dx in 0..=2usize {
            let lo = if dx == 0 {
                (cell.0, cell.1 + 1)
            } else {
                (cell.0 + dx as i64, cell.1 - 2)
            };
            let hi = (cell.0 + dx as i64, cell.1 + 2);
            let mut first = if dx == 0 { c + 1 } else { ahead[dx] };
            while first < cells.len() && cells[first].0 < lo {
                first += 1;
            }
            ahead[dx] = first;
            for (other_cell, other) in &cells[first..] {
                if *other_cell > hi {
                    break;
                }
                if sets.root(members[0].1) == sets.root(keyed[other.start].1) {
                    continue;
                }
                let close = members.iter().any(|&(_, a)| {
                    keyed[other.clone()]
                        .iter()
                        .any(|&(_, b)| (points[a] - points[b]).norm() <= tol)
                });
                if close {
                    sets.join(members[0].1, keyed[other.start].1);
                    any = true;
                }
            }
        }
    }
    if !any {
        return Vec::new();
    }
    let roots: Vec<usize> = (0..points.len()).map(|k| sets.root(k)).collect();
    let mut size = vec![0u32; points.len()];
    roots.iter().for_each(|&r| size[r] += 1);
    let mut members: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for (k, &r) in roots.iter().enumerate() {
        if size[r] > 1 {
            members.entry(r).or_default().push(k);
        }
    }
    members.into_values().collect()
}

/// Disjoint sets of indices whose representative is the smallest member.
struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    /// n singletons.
    fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    /// The smallest index of i's set (with path halving).
    fn root(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Joins the sets of a and b.
    fn join(&mut self, a: usize, b: usize) {
        let (a, b) = (self.root(a), self.root(b));
        self.parent[a.max(b)] = a.min(b);
    }
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
                out.values.push(group_mean(rows, |k| values[k]));
                out.first_index.push(i);
            }
            _ => {}
        }
    }
    out.merged = merged;
    out
}

/// The mean of a merged group's entries, `entry(k)` for its indices k, as
/// [`merge_near_duplicates`] takes the mean of their values: the first entry plus the mean
/// of the differences from it (exact to rounding even far from zero). For other columns
/// given with the points (gradients, further data), so that they merge as the values do.
pub fn group_mean<T>(group: &[usize], entry: impl Fn(usize) -> T) -> T
where
    T: Copy + Add<Output = T> + Sub<Output = T> + Div<f64, Output = T>,
{
    let first = entry(group[0]);
    let shift = group[1..]
        .iter()
        .map(|&k| entry(k) - first)
        .reduce(|s, d| s + d);
    match shift {
        Some(shift) => first + shift / group.len() as f64,
        None => first,
    }
}

impl MergedData {
    /// Another column given with the points (one entry per input point), merged as the
    /// values are: one entry per merged point, the [`group_mean`] of a merged group.
    pub fn mean_of<T>(&self, column: &[T]) -> Vec<T>
    where
        T: Copy + Add<Output = T> + Sub<Output = T> + Div<f64, Output = T>,
    {
        // The groups come in the order of their first indices, as the merged points do.
        let mut groups = self.merged.iter().peekable();
        self.first_index
            .iter()
            .map(|&i| match groups.next_if(|g| g[0] == i) {
                Some(group) => group_mean(group, |k| column[k]),
                None => column[i],
            })
            .collect()
    }
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
        // Other columns merge as the values do: the values themselves, bit for bit, and
        // vectors (their mean, exactly representable here).
        assert_eq!(m.mean_of(&values), m.values);
        let gradients: Vec<nalgebra::Vector2<f64>> = values
            .iter()
            .map(|&v| nalgebra::Vector2::new(v, -2.0 * v))
            .collect();
        let means = m.mean_of(&gradients);
        assert_eq!(means.len(), 4);
        assert_eq!(means[1], nalgebra::Vector2::new(3.0, -6.0));
        assert_eq!(means[3], gradients[5]);
        // Nothing is merged at a tighter tolerance, or when every point is far apart.
        let none = merge_near_duplicates(&pts, &values, 1e-14);
        assert!(none.merged.is_empty());
        assert_eq!(none.points, pts.to_vec());
        assert_eq!(none.first_index, (0..7).collect::<Vec<_>>());
    }

    /// Far from zero the mean of a group is exact to rounding of the result (a plain sum
    /// would lose the offsets' digits): entries 4e15 + k, k = 0 … 4, have the mean
    /// 4e15 + 2 (their plain sum makes it 4e15 + 2.5).
    #[test]
    fn group_means_are_exact_far_from_zero() {
        let column: Vec<f64> = (0..5).map(|k| 4e15 + k as f64).collect();
        assert_eq!(group_mean(&[0, 1, 2, 3, 4], |k| column[k]), 4e15 + 2.0);
        assert_eq!(group_mean(&[4, 0], |k| column[k]), 4e15 + 2.0);
        assert_eq!(group_mean(&[3], |k| column[k]), column[3]);
    }

    /// The groups are the connected components of "within the tolerance", found here by
    /// comparing every pair, on clustered random points.
    #[test]
    fn groups_are_the_components_of_the_closeness_graph() {
        use crate::test_util::*;
        let mut r = rng(5);
        for trial in 0..40 {
            let spread = 10f64.powf(uniform(&mut r, -12.0, -7.0));
            let mut pts = Vec::new();
            for _ in 0..30 {
                let c = Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0));
                for _ in 0..(1 + trial % 5) {
                    pts.push(Point2::new(
                        c.x + uniform(&mut r, -spread, spread),
                        c.y + uniform(&mut r, -spread, spread),
                    ));
                }
            }
            let tol = crate::scattered::near_duplicate_distance(&pts, NEAR_DUPLICATE);
            let mut sets = UnionFind::new(pts.len());
            for a in 0..pts.len() {
                for b in a + 1..pts.len() {
                    if (pts[a] - pts[b]).norm() <= tol {
                        sets.join(a, b);
                    }
                }
            }
            let mut want: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
            for k in 0..pts.len() {
                want.entry(sets.root(k)).or_default().push(k);
            }
            let want: Vec<Vec<usize>> = want.into_values().filter(|g| g.len() > 1).collect();
            assert_eq!(
                near_duplicate_groups(&pts, NEAR_DUPLICATE),
                want,
                "trial {trial}"
            );
        }
    }

    /// A cluster of 200,000 distinct points within the tolerance is one group, found in linear time
    /// (every pair would be 2e10 comparisons).
    #[test]
    fn a_dense_cluster_is_one_group_without_comparing_every_pair() {
        let mut pts: Vec<Point2<f64>> = (0..200_000)
            .map(|k| Point2::new(0.5 + k as f64 * 2.3e-16, 0.5 + (k % 7) as f64 * 2.3e-16))
            .collect();
        pts.push(Point2::new(0.0, 0.0));
        pts.push(Point2::new(1.0, 1.0));
        let groups = near_duplicate_groups(&pts, NEAR_DUPLICATE);
        assert_eq!(groups.len(), 1);
        assert_eq!(groups[0].len(), 200_000);
    }
}
