//! Choosing the vertices of a coarse triangulation for a smoothing fit from the data.

use std::collections::HashMap;

use nalgebra::Point2;

use crate::geometry::convex_hull;

/// About `m` of the data points as vertices of a coarse triangulation: every corner of the
/// data's convex hull (so that the triangulation covers all the data), and in each cell of
/// a square grid over the data's bounding box the point nearest the cell's centre, with the
/// cell size chosen (one correction step) so that about `m` cells are occupied. Returns
/// indices into `points`, increasing; all of them when m ≥ the number of points.
pub fn coarse_vertices(points: &[Point2<f64>], m: usize) -> Vec<usize> {
    if m >= points.len() || points.len() < 3 {
        return (0..points.len()).collect();
    }
    let index: HashMap<(u64, u64), usize> = points
        .iter()
        .enumerate()
        .map(|(k, p)| ((p.x.to_bits(), p.y.to_bits()), k))
        .collect();
    let mut chosen: Vec<usize> = convex_hull(points)
        .iter()
        .filter_map(|p| index.get(&(p.x.to_bits(), p.y.to_bits())).copied())
        .collect();
    let lo = points
        .iter()
        .fold(points[0], |a, p| Point2::new(a.x.min(p.x), a.y.min(p.y)));
    let hi = points
        .iter()
        .fold(points[0], |a, p| Point2::new(a.x.max(p.x), a.y.max(p.y)));
    let extent = hi - lo;
    let area = (extent.x.max(extent.norm() * 1e-3)) * (extent.y.max(extent.norm() * 1e-3));
    let target = m.saturating_sub(chosen.len()).max(1);
    let mut cell = (area / target as f64).sqrt();
    let mut sample = grid_sample(points, lo, cell);
    if !sample.is_empty() {
        // Data that fill only part of the box occupy fewer cells: shrink them once.
        cell *= (sample.len() as f64 / target as f64).sqrt();
        sample = grid_sample(points, lo, cell);
    }
    chosen.extend(sample);
    chosen.sort_unstable();
    chosen.dedup();
    chosen
}

/// In each occupied grid cell of size `cell` (origin `lo`), the point nearest its centre.
fn grid_sample(points: &[Point2<f64>], lo: Point2<f64>, cell: f64) -> Vec<usize> {
    if !(cell > 0.0 && cell.is_finite()) {
        return Vec::new();
    }
    let mut best: HashMap<(i64, i64), (f64, usize)> = HashMap::new();
    for (k, p) in points.iter().enumerate() {
        let (fx, fy) = ((p.x - lo.x) / cell, (p.y - lo.y) / cell);
        let key = (fx.floor() as i64, fy.floor() as i64);
        let d = (fx - key.0 as f64 - 0.5).powi(2) + (fy - key.1 as f64 - 0.5).powi(2);
        let e = best.entry(key).or_insert((f64::INFINITY, k));
        if d < e.0 {
            *e = (d, k);
        }
    }
    best.into_values().map(|(_, k)| k).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::*;

    #[test]
    fn coarse_vertices_keep_the_hull_and_come_near_the_requested_count() {
        let mut r = rng(142);
        for (n, m) in [(5000, 500), (20000, 300), (3000, 2900), (100, 1000)] {
            // Points in a disc (a hull with many corners) and a dense cluster.
            let pts: Vec<Point2<f64>> = (0..n)
                .map(|k| {
                    let (a, rad) = (
                        uniform(&mut r, 0.0, std::f64::consts::TAU),
                        uniform(&mut r, 0.0, 1.0).sqrt(),
                    );
                    let s = if k % 5 == 0 { 0.05 } else { 1.0 };
                    Point2::new(5.0 + s * rad * a.cos(), -3.0 + s * rad * a.sin())
                })
                .collect();
            let chosen = coarse_vertices(&pts, m);
            assert!(
                chosen.windows(2).all(|w| w[0] < w[1]),
                "increasing, distinct"
            );
            let hull = convex_hull(&pts);
            for h in &hull {
                assert!(chosen.iter().any(|&k| pts[k] == *h), "hull corner {h} kept");
            }
            if m >= n {
                assert_eq!(chosen.len(), n);
            } else {
                let got = chosen.len() as f64;
                assert!(
                    got > 0.5 * m as f64 && got < 1.5 * m as f64 + hull.len() as f64,
                    "n {n}, m {m}: {got}"
                );
            }
        }
    }
}
