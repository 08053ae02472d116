//! Evaluating a PS-spline at many points fast: on a rectilinear grid by runs (the points of a
//! grid line that fall in one sub-triangle share its quadratic, so only the barycentric
//! coordinates move, linearly), and at scattered points in Morton order (neighbouring
//! queries walk short distances and touch the same memory).

use nalgebra::Point2;
use rayon::prelude::*;

use super::basis::SubLocation;
use super::grid_scan::SCAN_POINTS_PER_TRIANGLE;
use super::net::SUB_ORDINATES;
use super::spline::{Evaluator, PsSpline};
use crate::geometry::Bary;
use crate::surface::for_each_chunk;
use crate::triangulation::morton_order;
use crate::vector::Vector;

/// Smallest barycentric coordinate for which a point of a run is taken as inside the run's
/// sub-triangle without locating it. The coordinates are computed to a few units in the last
/// place, so a point accepted with this margin is inside; points nearer the sub-triangle's
/// edges are located as any other point (which also decides the domain's boundary).
const RUN_MARGIN: f64 = 1e-12;

/// The fewest grid rows one parallel task evaluates (fewer tasks for short grids).
const MIN_ROWS_PER_TASK: usize = 4;

/// The points of one grid line inside one sub-triangle: its six ordinates and barycentric
/// coordinates as an affine function of the varying coordinate y.
struct Run<V> {
    /// The sub-triangle's Bézier ordinates in the order of [`SUB_ORDINATES`].
    q: [V; 6],
    /// Barycentric coordinates at y = y0.
    bary: Bary,
    /// Their derivative with respect to y.
    slope: Bary,
    /// Where the run was started.
    y0: f64,
}

impl<V: Vector> Run<V> {
    /// The run through a located point at height `y0`.
    fn new(spline: &PsSpline<V>, loc: &SubLocation, y0: f64) -> Self {
        let n = spline.net(loc.triangle);
        let i = &SUB_ORDINATES[loc.sub];
        Run {
            q: [n[i[0]], n[i[1]], n[i[2]], n[i[3]], n[i[4]], n[i[5]]],
            bary: loc.bary,
            slope: loc.dy,
            y0,
        }
    }

    /// s(x, y) when (x, y) is inside the run's sub-triangle by the margin, else `None`.
    #[inline(always)]
    fn value(&self, y: f64) -> Option<V> {
        let d = y - self.y0;
        let t = [
            self.bary[0] + d * self.slope[0],
            self.bary[1] + d * self.slope[1],
            self.bary[2] + d * self.slope[2],
        ];
        // (A NaN y fails every comparison and is located, i.e. reported outside.)
        if !(t[0] >= RUN_MARGIN && t[1] >= RUN_MARGIN && t[2] >= RUN_MARGIN) {
            return None;
        }
        let q = &self.q;
        // One de Casteljau step on the quadratic net (as PsSpline::value_at).
        let b0 = q[0] * t[0] + q[1] * t[1] + q[2] * t[2];
        let b1 = q[1] * t[0] + q[3] * t[1] + q[4] * t[2];
        let b2 = q[2] * t[0] + q[4] * t[1] + q[5] * t[2];
        Some(b0 * t[0] + b1 * t[1] + b2 * t[2])
    }
}

impl<V: Vector> PsSpline<V> {
    /// The values on the grid `xs` × `ys`, row-major: entry `i · ys.len() + j` is
    /// s(xs\[i\], ys\[j\]), or `outside` where that point lies outside the domain. Agrees with
    /// [`PsSpline::eval`] to rounding. In parallel, by one of two methods:
    /// - sorted axes with several grid points per triangle: a scan conversion of Δ*, which
    ///   finds where each grid line crosses each triangle and its pieces (no point location);
    ///   it decides inside and outside as `eval` does, up to points within rounding of the
    ///   domain's boundary, and also to points beyond the domain's extreme vertices by less
    ///   than the location tolerance, which it leaves outside;
    /// - otherwise each row (a line x = xs\[i\]) is walked once; the points between two
    ///   crossings of the refinement's edges are evaluated from the same quadratic, and
    ///   inside and outside are decided exactly as `eval` does.
    ///
    /// The caller checks the size: `xs.len() · ys.len()` values are allocated.
    pub fn values_on_grid(&self, xs: &[f64], ys: &[f64], outside: V) -> Vec<V> {
        if let Some(values) = self.scan_grid(xs, ys, outside, SCAN_POINTS_PER_TRIANGLE) {
            return values;
        }
        let ny = ys.len();
        let mut out = vec![outside; xs.len() * ny];
        if ny == 0 {
            return out;
        }
        out.par_chunks_mut(ny)
            .zip(xs.par_iter())
            .with_min_len(MIN_ROWS_PER_TASK)
            .for_each(|(row, &x)| self.row_values(x, ys, row));
        out
    }

    /// The values along the line x = `x` at heights `ys` (points outside keep `row`'s value).
    fn row_values(&self, x: f64, ys: &[f64], row: &mut [V]) {
        let mut ev = self.evaluator_near(Point2::new(x, ys[0]));
        let mut run: Option<Run<V>> = None;
        for (o, &y) in row.iter_mut().zip(ys) {
            if let Some(v) = run.as_ref().and_then(|r| r.value(y)) {
                *o = v;
                continue;
            }
            match ev.locate(Point2::new(x, y)) {
                Some(loc) => {
                    *o = self.value_at(&loc);
                    run = Some(Run::new(self, &loc, y));
                }
                None => run = None,
            }
        }
    }

    /// `f(evaluator, p)` for scattered points: they are visited in Morton (Z-curve) order
    /// ([`morton_order`]), in parallel chunks, so that each walk from the previous point is
    /// short and touches nearby memory; the results come back in the caller's order. (A
    /// coarser order, by cells of about four queries, sorts in 70 % of the time but doubled
    /// the walks: inside a cell the queries come in random order.) For coherent points (already ordered along a path)
    /// [`PsSpline::map_points`] saves the sort.
    pub fn map_scattered<T: Send + Copy + Default>(
        &self,
        points: &[Point2<f64>],
        f: impl Fn(&mut Evaluator<'_, V>, Point2<f64>) -> T + Sync,
    ) -> Vec<T> {
        let order = morton_order(points);
        // Gathered first: the loads are independent there, while inside the walk each
        // would stall it.
        let sorted: Vec<Point2<f64>> = order.par_iter().map(|&k| points[k as usize]).collect();
        let mut in_order = vec![T::default(); points.len()];
        for_each_chunk(&sorted, &mut in_order, 1, |pts, values| {
            let mut ev = self.evaluator_near(pts[0]);
            for (v, &p) in values.iter_mut().zip(pts) {
                *v = f(&mut ev, p);
            }
        });
        let mut out = vec![T::default(); points.len()];
        for (&k, v) in order.iter().zip(in_order) {
            out[k as usize] = v;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use nalgebra::Point2;

    use crate::ps::tests::{assert_grid_agrees, random_hermite_spline};
    use crate::ps::{Hermite, PsBasis, PsSpline};
    use crate::test_util::{rng, uniform};
    use crate::triangulation::Triangulation;

    /// A spline with random Hermite data on the Delaunay triangulation of random points.
    fn random_spline(seed: u64, n: usize) -> PsSpline<f64> {
        let mut r = rng(seed);
        let pts: Vec<Point2<f64>> = (0..n)
            .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
            .collect();
        random_hermite_spline(Triangulation::delaunay(pts).unwrap(), seed)
    }

    /// The grid path agrees with point-by-point evaluation: the same points are outside
    /// (both decide by the same point location), values agree to rounding; on unsorted,
    /// repeated and NaN coordinates and lines outside the domain too.
    #[test]
    fn grid_values_agree_with_pointwise_evaluation() {
        for seed in 0..4 {
            let s = random_spline(seed, 300);
            let mut r = rng(100 + seed);
            let mut xs: Vec<f64> = (0..60).map(|_| uniform(&mut r, -0.1, 1.1)).collect();
            let mut ys: Vec<f64> = (0..50).map(|k| -0.1 + 1.2 * k as f64 / 49.0).collect();
            if seed % 2 == 1 {
                ys.reverse();
                ys.swap(3, 30);
                ys[7] = ys[8];
            }
            xs[5] = f64::NAN;
            ys[9] = f64::NAN;
            let grid = s.values_on_grid(&xs, &ys, f64::INFINITY);
            let (inside, outside) = assert_grid_agrees(&s, &xs, &ys, &grid, f64::INFINITY);
            assert!(
                inside > 1500 && outside > 300,
                "{inside} inside, {outside} outside"
            );
        }
    }

    /// A spline interpolating a quadratic (value and gradient) is that quadratic (the PS
    /// space contains the quadratics): the grid paths (runs and scan) and the scattered path
    /// give its closed form to 1e-13 relative at every point inside.
    #[test]
    fn grid_and_scattered_values_reproduce_quadratics() {
        let q = |p: Point2<f64>| {
            0.4 - 1.3 * p.x + 0.8 * p.y + 2.1 * p.x * p.x - 0.9 * p.x * p.y - 1.7 * p.y * p.y
        };
        let dq = |p: Point2<f64>| (-1.3 + 4.2 * p.x - 0.9 * p.y, 0.8 - 0.9 * p.x - 3.4 * p.y);
        for seed in 0..3 {
            let mut r = rng(200 + seed);
            let pts: Vec<Point2<f64>> = (0..400)
                .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
                .collect();
            let data: Vec<Hermite<f64>> = pts
                .iter()
                .map(|&p| Hermite {
                    value: q(p),
                    dx: dq(p).0,
                    dy: dq(p).1,
                })
                .collect();
            let basis = PsBasis::optimal(Triangulation::delaunay(pts).unwrap()).unwrap();
            let s = PsSpline::hermite(Arc::new(basis), &data).unwrap();
            // Unsorted rows take the runs; sorted ones the scan.
            let xs: Vec<f64> = (0..80).map(|_| uniform(&mut r, 0.0, 1.0)).collect();
            let mut sorted = xs.clone();
            sorted.sort_by(f64::total_cmp);
            let ys: Vec<f64> = (0..90).map(|k| k as f64 / 89.0).collect();
            let runs = s.values_on_grid(&xs, &ys, f64::NAN);
            let scan = s
                .scan_grid(&sorted, &ys, f64::NAN, 0.0)
                .expect("sorted axes");
            for (xs, grid) in [(&xs, runs), (&sorted, scan)] {
                let mut inside = 0;
                for (i, &x) in xs.iter().enumerate() {
                    for (j, &y) in ys.iter().enumerate() {
                        let v = grid[i * ys.len() + j];
                        if !v.is_nan() {
                            inside += 1;
                            let want = q(Point2::new(x, y));
                            let close = (v - want).abs() <= 1e-13 * (1.0 + want.abs());
                            assert!(close, "{v} vs {want}");
                        }
                    }
                }
                assert!(inside > 5000, "{inside}");
            }
            let scattered: Vec<Point2<f64>> = (0..20_000)
                .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
                .collect();
            let values = s.map_scattered(&scattered, |ev, p| ev.value(p));
            let found = values.iter().flatten().count();
            assert!(found > 18_000, "{found}");
            for (p, v) in scattered.iter().zip(&values) {
                if let Some(v) = v {
                    let want = q(*p);
                    assert!((v - want).abs() <= 1e-13 * (1.0 + want.abs()));
                }
            }
        }
    }

    #[test]
    fn empty_grids() {
        let s = random_spline(9, 20);
        assert!(s.values_on_grid(&[], &[0.5], 0.0).is_empty());
        assert!(s.values_on_grid(&[0.5], &[], 0.0).is_empty());
    }

    /// Morton-ordered evaluation returns each point's own value in the caller's order.
    #[test]
    fn scattered_values_come_back_in_order() {
        let s = random_spline(5, 500);
        let mut r = rng(6);
        let pts: Vec<Point2<f64>> = (0..20_000)
            .map(|_| Point2::new(uniform(&mut r, -0.2, 1.2), uniform(&mut r, -0.2, 1.2)))
            .collect();
        let got = s.map_scattered(&pts, |ev, p| ev.value(p));
        let mut ev = s.evaluator();
        let mut outside = 0;
        for (p, g) in pts.iter().zip(&got) {
            match (ev.value(*p), g) {
                (Some(a), Some(b)) => assert!((a - b).abs() <= 1e-13 * (1.0 + a.abs())),
                (None, None) => outside += 1,
                (a, b) => panic!("{p:?}: {a:?} vs {b:?}"),
            }
        }
        assert!(outside > 3000);
    }
}
