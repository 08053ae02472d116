//! Point location: a walk from a hint for coherent queries; for random queries a bucket grid
//! gives a nearby start ("jump and walk"), with an R-tree as the exact fallback where a walk
//! leaves a non-convex domain.

use nalgebra::Point2;
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};

use super::{NO_NEIGHBOR, Triangulation};
use crate::geometry::{Bary, cross};

/// A point is inside a triangle when all its barycentric coordinates are ≥ −`INSIDE_TOLERANCE`:
/// points on (or within rounding of) an edge belong to the triangles on both sides.
pub const INSIDE_TOLERANCE: f64 = 1e-12;

/// The most walking steps before giving up and asking the R-tree.
const MAX_WALK: usize = 64;

/// Remembers where the previous point location ended (the triangle to start the next walk
/// from), so that nearby points are found by a short walk. Get one near the first point (e.g.
/// from [`Triangulation::start_triangle`] or `ParametricSurface::cursor_near`) and reuse it
/// along a grid or a curve; `Cursor::default()` works too (it starts at triangle 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cursor(pub usize);

/// Where a point lies: a triangle and the point's barycentric coordinates in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Location {
    /// The triangle index.
    pub triangle: usize,
    /// Barycentric coordinates w.r.t. the triangle's (counter-clockwise) vertices.
    pub bary: Bary,
}

/// A uniform grid over the bounding box whose cells name a triangle at (or near) their centre.
#[derive(Debug)]
pub(super) struct Buckets {
    origin: Point2<f64>,
    inv_cell: [f64; 2],
    n: [usize; 2],
    start: Vec<u32>,
}

/// The spatial indexes, built on first use.
#[derive(Debug)]
pub(super) struct Locator {
    buckets: Buckets,
    tree: std::sync::OnceLock<RTree<GeomWithData<Rectangle<[f64; 2]>, u32>>>,
}

impl Buckets {
    fn new(t: &Triangulation) -> Self {
        let (lo, hi) = t.bounds();
        let size = hi - lo;
        // About one cell per triangle, shaped like the bounding box.
        let cells = t.triangle_count().max(1) as f64;
        let aspect = (size.x / size.y.max(f64::MIN_POSITIVE)).clamp(1e-3, 1e3);
        let nx = ((cells * aspect).sqrt().ceil() as usize).clamp(1, 1 << 14);
        let ny = ((cells / nx as f64).ceil() as usize).clamp(1, 1 << 14);
        let cell = [
            size.x.max(f64::MIN_POSITIVE) / nx as f64,
            size.y.max(f64::MIN_POSITIVE) / ny as f64,
        ];
        let mut start = vec![NO_NEIGHBOR; nx * ny];
        // Rasterise: a cell gets a triangle that contains its centre.
        for s in 0..t.triangle_count() {
            let g = t.triangle_geometry(s);
            let (mut x0, mut y0, mut x1, mut y1) = (
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            );
            for v in g.v {
                x0 = x0.min(v.x);
                y0 = y0.min(v.y);
                x1 = x1.max(v.x);
                y1 = y1.max(v.y);
            }
            let ci = |x: f64, k: usize, o: f64| {
                (((x - o) / cell[k] - 0.5).floor().max(0.0) as usize).min([nx, ny][k] - 1)
            };
            let cj = |x: f64, k: usize, o: f64| {
                (((x - o) / cell[k] - 0.5).ceil().max(0.0) as usize).min([nx, ny][k] - 1)
            };
            for j in ci(y0, 1, lo.y)..=cj(y1, 1, lo.y) {
                for i in ci(x0, 0, lo.x)..=cj(x1, 0, lo.x) {
                    let c = Point2::new(
                        lo.x + (i as f64 + 0.5) * cell[0],
                        lo.y + (j as f64 + 0.5) * cell[1],
                    );
                    if t.bary(s, c).iter().all(|&b| b >= -INSIDE_TOLERANCE) {
                        start[j * nx + i] = s as u32;
                    }
                }
            }
        }
        // Cells whose centre is outside the domain take a neighbour's triangle.
        let mut frontier: Vec<usize> = (0..start.len())
            .filter(|&k| start[k] != NO_NEIGHBOR)
            .collect();
        if frontier.is_empty() {
            start.fill(0);
        }
        while !frontier.is_empty() {
            let mut next = Vec::new();
            for k in frontier {
                let (i, j) = (k % nx, k / nx);
                let nbrs = [
                    (i.wrapping_sub(1), j),
                    (i + 1, j),
                    (i, j.wrapping_sub(1)),
                    (i, j + 1),
                ];
                for (a, b) in nbrs {
                    if a < nx && b < ny && start[b * nx + a] == NO_NEIGHBOR {
                        start[b * nx + a] = start[k];
                        next.push(b * nx + a);
                    }
                }
            }
            frontier = next;
        }
        Buckets {
            origin: lo,
            inv_cell: [1.0 / cell[0], 1.0 / cell[1]],
            n: [nx, ny],
            start,
        }
    }

    /// A triangle near `p`.
    #[inline]
    fn start(&self, p: Point2<f64>) -> usize {
        let i = (((p.x - self.origin.x) * self.inv_cell[0]).max(0.0) as usize).min(self.n[0] - 1);
        let j = (((p.y - self.origin.y) * self.inv_cell[1]).max(0.0) as usize).min(self.n[1] - 1);
        self.start[j * self.n[0] + i] as usize
    }
}

impl Triangulation {
    fn locator(&self) -> &Locator {
        self.locator.get_or_init(|| Locator {
            buckets: Buckets::new(self),
            tree: std::sync::OnceLock::new(),
        })
    }

    fn rtree(&self) -> &RTree<GeomWithData<Rectangle<[f64; 2]>, u32>> {
        self.locator().tree.get_or_init(|| {
            let (lo, hi) = self.bounds();
            let pad = 1e-12 * (hi - lo).norm();
            let boxes = (0..self.triangle_count())
                .map(|t| {
                    let g = self.triangle_geometry(t);
                    let (mut min, mut max) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
                    for v in g.v {
                        min = [min[0].min(v.x), min[1].min(v.y)];
                        max = [max[0].max(v.x), max[1].max(v.y)];
                    }
                    let rect = Rectangle::from_corners(
                        [min[0] - pad, min[1] - pad],
                        [max[0] + pad, max[1] + pad],
                    );
                    GeomWithData::new(rect, t as u32)
                })
                .collect();
            RTree::bulk_load(boxes)
        })
    }

    /// Barycentric coordinates of `p` w.r.t. triangle `t`.
    #[inline]
    pub fn bary(&self, t: usize, p: Point2<f64>) -> Bary {
        let [a, b, c] = self.triangles[t];
        let (a, b, c) = (
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        );
        let e = cross(b - a, c - a);
        let t0 = cross(b - p, c - p) / e;
        let t1 = cross(c - p, a - p) / e;
        [t0, t1, 1.0 - t0 - t1]
    }

    /// Builds the spatial indexes now (they are otherwise built on the first random query).
    pub fn prepare_locator(&self) {
        self.locator();
    }

    /// A triangle near `p`, to start a walk from (the bucket grid's guess).
    pub fn start_triangle(&self, p: Point2<f64>) -> usize {
        self.locator().buckets.start(p)
    }

    /// The triangle containing `p`, or `None` when `p` lies outside the domain: a walk from
    /// the bucket grid's guess, with the R-tree as the exact fallback.
    pub fn locate(&self, p: Point2<f64>) -> Option<Location> {
        self.locate_from(p, self.start_triangle(p))
    }

    /// The triangle containing `p` by the R-tree alone (exact; slower than walking).
    pub fn locate_exhaustive(&self, p: Point2<f64>) -> Option<Location> {
        let mut best: Option<Location> = None;
        let mut best_min = f64::NEG_INFINITY;
        for cand in self.rtree().locate_all_at_point([p.x, p.y]) {
            let t = cand.data as usize;
            let b = self.bary(t, p);
            let m = b[0].min(b[1]).min(b[2]);
            if m >= -INSIDE_TOLERANCE && m > best_min {
                best_min = m;
                best = Some(Location {
                    triangle: t,
                    bary: b,
                });
                if m >= 0.0 {
                    break;
                }
            }
        }
        best
    }

    /// The triangle nearest to `p` within `max_distance` (0 when `p` is inside it) and that
    /// distance; `None` when every triangle is farther. For points just outside the domain,
    /// e.g. data beside a boundary sliver that was left out.
    pub fn nearest_triangle(&self, p: Point2<f64>, max_distance: f64) -> Option<(usize, f64)> {
        use rstar::AABB;
        let r = max_distance;
        let window = AABB::from_corners([p.x - r, p.y - r], [p.x + r, p.y + r]);
        self.rtree()
            .locate_in_envelope_intersecting(window)
            .map(|cand| {
                let t = cand.data as usize;
                (t, self.triangle_geometry(t).distance_to(p))
            })
            .filter(|&(_, d)| d <= max_distance)
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The triangle containing `p`, walking from triangle `hint` across the edge with the
    /// most negative barycentric coordinate; cheap when `p` is near `hint` (as for
    /// consecutive points of a grid). Falls back to the R-tree when the walk reaches the
    /// boundary (the point may lie across a notch of a non-convex domain) or takes too long.
    pub fn locate_from(&self, p: Point2<f64>, hint: usize) -> Option<Location> {
        let mut t = hint;
        for _ in 0..MAX_WALK {
            let b = self.bary(t, p);
            let (mut i, mut m) = (0, b[0]);
            if b[1] < m {
                (i, m) = (1, b[1]);
            }
            if b[2] < m {
                (i, m) = (2, b[2]);
            }
            if m >= -INSIDE_TOLERANCE {
                return Some(Location {
                    triangle: t,
                    bary: b,
                });
            }
            let n = self.neighbors[t][i];
            if n == NO_NEIGHBOR {
                break;
            }
            t = n as usize;
        }
        self.locate_exhaustive(p)
    }
}
