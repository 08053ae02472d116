//! Point location: a walk from a hint for coherent queries, an R-tree for random ones.

use nalgebra::Point2;
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};

use super::{NO_NEIGHBOR, Triangulation};
use crate::geometry::{Bary, cross};

/// A point is inside a triangle when all its barycentric coordinates are ≥ −`INSIDE_TOLERANCE`:
/// points on (or within rounding of) an edge belong to the triangles on both sides.
pub const INSIDE_TOLERANCE: f64 = 1e-12;

/// The most walking steps before giving up and asking the R-tree.
const MAX_WALK: usize = 48;

/// Where a point lies: a triangle and the point's barycentric coordinates in it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Location {
    /// The triangle index.
    pub triangle: usize,
    /// Barycentric coordinates w.r.t. the triangle's (counter-clockwise) vertices.
    pub bary: Bary,
}

/// An R-tree of the triangles' (slightly padded) bounding boxes.
#[derive(Debug)]
pub(super) struct Locator {
    tree: RTree<GeomWithData<Rectangle<[f64; 2]>, u32>>,
}

impl Triangulation {
    fn locator(&self) -> &Locator {
        self.locator.get_or_init(|| {
            let (lo, hi) = self.bounds();
            let pad = 1e-12 * (hi - lo).norm();
            let boxes = (0..self.triangle_count())
                .map(|t| {
                    let g = self.triangle_geometry(t);
                    let xs = g.v.map(|v| v.x);
                    let ys = g.v.map(|v| v.y);
                    let min = [
                        xs.iter().copied().fold(f64::INFINITY, f64::min) - pad,
                        ys.iter().copied().fold(f64::INFINITY, f64::min) - pad,
                    ];
                    let max = [
                        xs.iter().copied().fold(f64::NEG_INFINITY, f64::max) + pad,
                        ys.iter().copied().fold(f64::NEG_INFINITY, f64::max) + pad,
                    ];
                    GeomWithData::new(Rectangle::from_corners(min, max), t as u32)
                })
                .collect();
            Locator {
                tree: RTree::bulk_load(boxes),
            }
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

    /// Builds the spatial index now (it is otherwise built on the first random query).
    pub fn prepare_locator(&self) {
        self.locator();
    }

    /// The triangle containing `p`, or `None` when `p` lies outside the domain.
    /// Uses the R-tree: O(log t) for any query.
    pub fn locate(&self, p: Point2<f64>) -> Option<Location> {
        let mut best: Option<Location> = None;
        let mut best_min = f64::NEG_INFINITY;
        for cand in self.locator().tree.locate_all_at_point([p.x, p.y]) {
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

    /// The triangle containing `p`, walking from triangle `hint` across the edge with the
    /// most negative barycentric coordinate; cheap when `p` is near `hint` (as for
    /// consecutive points of a grid). Falls back to [`Triangulation::locate`] when the walk
    /// reaches the boundary or takes too long.
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
        self.locate(p)
    }
}
