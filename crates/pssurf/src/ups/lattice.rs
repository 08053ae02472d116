//! The isometrical lattice 𝒦 = Γ B ℤ² and lattice polygons (thesis section 4.2.1).

use nalgebra::Point2;

use super::UpsError;

/// √3 / 2.
pub const SQRT3_2: f64 = 0.866_025_403_784_438_6;

/// A point of the lattice in lattice coordinates (i, j): the Cartesian point
/// origin + B Γ (i, j) with Γ = [[1, 1/2], [0, √3/2]] (4.1).
pub type LatticePoint = [i64; 2];

/// The lattice: its base B (the edge length of its triangles) and the Cartesian position of
/// the lattice point (0, 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice {
    /// The base B > 0.
    pub base: f64,
    /// The Cartesian position of lattice point (0, 0).
    pub origin: Point2<f64>,
}

impl Lattice {
    /// The Cartesian position of lattice point (i, j).
    #[inline]
    pub fn point(&self, p: LatticePoint) -> Point2<f64> {
        let (i, j) = (p[0] as f64, p[1] as f64);
        Point2::new(
            self.origin.x + self.base * (i + 0.5 * j),
            self.origin.y + self.base * SQRT3_2 * j,
        )
    }

    /// The lattice D⁻¹𝒦 with half the base (one subdivision step): lattice point (i, j) of
    /// `self` is (2i, 2j) of the result.
    pub fn refined(&self) -> Lattice {
        Lattice {
            base: 0.5 * self.base,
            origin: self.origin,
        }
    }
}

/// The most corners a lattice polygon may have (the simplicity check is quadratic in them).
pub const MAX_CORNERS: usize = 4096;

/// The largest lattice coordinate |i|, |j| of a polygon corner (2^40): far beyond any
/// triangulation that fits in memory, and small enough that every product of coordinates
/// stays exact in 128-bit integers.
pub const MAX_LATTICE_COORDINATE: i64 = 1 << 40;

/// Twice the signed area of a lattice polygon, in units of the lattice parallelogram.
fn twice_area(v: &[LatticePoint]) -> i128 {
    let n = v.len();
    (0..n)
        .map(|k| {
            let (a, b) = (v[k], v[(k + 1) % n]);
            a[0] as i128 * b[1] as i128 - b[0] as i128 * a[1] as i128
        })
        .sum()
}

/// True when the step `d` runs along one of the three families of grid lines:
/// (1, 0), (0, 1) or (1, −1) (and their opposites).
fn on_grid_line(d: [i64; 2]) -> bool {
    d != [0, 0] && (d[0] == 0 || d[1] == 0 || d[0] == -d[1])
}

/// A simple polygon whose vertices are lattice points and whose edges lie on grid lines
/// (Definition 4.2), counter-clockwise, without repeated or collinear consecutive vertices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LatticePolygon {
    vertices: Vec<LatticePoint>,
}

impl LatticePolygon {
    /// A validated lattice polygon: at least three distinct corners, every edge on a grid
    /// line, no self-intersection, non-zero area. Clockwise input is reversed; vertices in the
    /// middle of a straight run are dropped.
    ///
    /// ```
    /// use pssurf::ups::{LatticePolygon, UpsError};
    /// // (0,0) → (2,1) is not along a grid line.
    /// assert_eq!(LatticePolygon::new(vec![[0, 0], [2, 1], [0, 2]]).unwrap_err(),
    ///     UpsError::EdgeOffGrid { edge: 0 });
    /// ```
    pub fn new(mut vertices: Vec<LatticePoint>) -> Result<Self, UpsError> {
        if vertices.len() > MAX_CORNERS {
            return Err(UpsError::TooManyCorners(vertices.len()));
        }
        if let Some(corner) = vertices.iter().position(|p| {
            p.iter()
                .any(|c| c.unsigned_abs() > MAX_LATTICE_COORDINATE as u64)
        }) {
            return Err(UpsError::CornerOutOfRange { corner });
        }
        vertices.dedup();
        while vertices.len() > 1 && vertices.first() == vertices.last() {
            vertices.pop();
        }
        if vertices.len() < 3 {
            return Err(UpsError::TooFewCorners);
        }
        let n = vertices.len();
        for k in 0..n {
            let (a, b) = (vertices[k], vertices[(k + 1) % n]);
            if !on_grid_line([b[0] - a[0], b[1] - a[1]]) {
                return Err(UpsError::EdgeOffGrid { edge: k });
            }
        }
        // Drop vertices where the boundary goes straight on.
        let mut v: Vec<LatticePoint> = Vec::with_capacity(n);
        for k in 0..n {
            let (p, c, nx) = (
                vertices[(k + n - 1) % n],
                vertices[k],
                vertices[(k + 1) % n],
            );
            let (d1, d2) = ([c[0] - p[0], c[1] - p[1]], [nx[0] - c[0], nx[1] - c[1]]);
            let cross = d1[0] as i128 * d2[1] as i128 - d1[1] as i128 * d2[0] as i128;
            let dot = d1[0] as i128 * d2[0] as i128 + d1[1] as i128 * d2[1] as i128;
            if cross != 0 || dot < 0 {
                v.push(c);
            }
        }
        if v.len() < 3 || twice_area(&v) == 0 {
            return Err(UpsError::ZeroArea);
        }
        if twice_area(&v) < 0 {
            v.reverse();
        }
        check_simple(&v)?;
        Ok(LatticePolygon { vertices: v })
    }

    /// The corners, counter-clockwise.
    pub fn vertices(&self) -> &[LatticePoint] {
        &self.vertices
    }

    /// The standard polygon with `sides` ∈ {3, 4, 5, 6} sides and `n` triangles along its
    /// (shorter) sides: the equilateral triangle of side n; the rhombus of side n (angles
    /// 60°, 120°); the pentagon cut from the triangle of side 3n by removing two corners of
    /// side n (sides n, n, 2n, 2n, n); the regular hexagon of side n.
    pub fn standard(sides: usize, n: i64) -> Result<Self, UpsError> {
        if n < 1 {
            return Err(UpsError::TooFewCorners);
        }
        let v = match sides {
            3 => vec![[0, 0], [n, 0], [0, n]],
            4 => vec![[0, 0], [n, 0], [n, n], [0, n]],
            5 => vec![[n, 0], [2 * n, 0], [2 * n, n], [0, 3 * n], [0, n]],
            6 => vec![
                [n, 0],
                [2 * n, 0],
                [2 * n, n],
                [n, 2 * n],
                [0, 2 * n],
                [0, n],
            ],
            _ => return Err(UpsError::UnsupportedSides(sides)),
        };
        Self::new(v)
    }

    /// The same polygon on the lattice of half the base (coordinates doubled).
    pub fn refined(&self) -> LatticePolygon {
        LatticePolygon {
            vertices: self.vertices.iter().map(|p| [2 * p[0], 2 * p[1]]).collect(),
        }
    }

    /// The polygon on the lattice of twice the base, if every corner lies on it.
    pub fn coarsened(&self) -> Option<LatticePolygon> {
        if self.vertices.iter().all(|p| p[0] % 2 == 0 && p[1] % 2 == 0) {
            Some(LatticePolygon {
                vertices: self.vertices.iter().map(|p| [p[0] / 2, p[1] / 2]).collect(),
            })
        } else {
            None
        }
    }

    /// Whether the point with lattice coordinates (x/3, y/3) lies inside (exact; points on
    /// the boundary are not considered — triangle centroids never are).
    pub(crate) fn contains_thirds(&self, x: i64, y: i64) -> bool {
        // Crossing number with exact integer arithmetic on coordinates scaled by 3.
        let n = self.vertices.len();
        let mut inside = false;
        for k in 0..n {
            let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
            let (ax, ay, bx, by) = (3 * a[0], 3 * a[1], 3 * b[0], 3 * b[1]);
            if (ay > y) != (by > y) {
                // x-coordinate of the crossing compared with x, without division.
                let lhs = (x - ax) as i128 * (by - ay) as i128;
                let rhs = (bx - ax) as i128 * (y - ay) as i128;
                let left = if by > ay { lhs < rhs } else { lhs > rhs };
                if left {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// The number of lattice points in the closed polygon, by Pick's theorem (the lattice
    /// coordinates (i, j) are an affine image of ℤ², so Pick applies): A + B/2 + 1 with A the
    /// area in lattice parallelograms and B the lattice points on the boundary. This is the
    /// vertex count of its uniform triangulation; the triangle count is 2A.
    pub fn lattice_point_count(&self) -> u128 {
        let twice = twice_area(&self.vertices).unsigned_abs();
        let n = self.vertices.len();
        let boundary: u128 = (0..n)
            .map(|k| {
                let (a, b) = (self.vertices[k], self.vertices[(k + 1) % n]);
                // Edges lie on grid lines: the lattice points on one are its longest step.
                let d = |c: usize| (b[c] as i128 - a[c] as i128).unsigned_abs();
                d(0).max(d(1))
            })
            .sum();
        (twice + boundary) / 2 + 1
    }

    /// The number of triangles of its uniform triangulation: twice the area in lattice
    /// parallelograms.
    pub fn triangle_count(&self) -> u128 {
        twice_area(&self.vertices).unsigned_abs()
    }

    /// The number of slots of the block matrix that stores its triangulation: the lattice
    /// points of the bounding box.
    pub fn block_slots(&self) -> u128 {
        let (lo, hi) = self.bounds();
        let side = |c: usize| (hi[c] as i128 - lo[c] as i128 + 1).unsigned_abs();
        side(0) * side(1)
    }

    /// The bounding box in lattice coordinates: (min corner, max corner).
    pub fn bounds(&self) -> (LatticePoint, LatticePoint) {
        let mut lo = [i64::MAX; 2];
        let mut hi = [i64::MIN; 2];
        for p in &self.vertices {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        (lo, hi)
    }
}

/// Non-adjacent edges may not touch; adjacent edges may meet only at their common corner.
fn check_simple(v: &[LatticePoint]) -> Result<(), UpsError> {
    let n = v.len();
    let orient = |a: LatticePoint, b: LatticePoint, c: LatticePoint| -> i128 {
        (b[0] - a[0]) as i128 * (c[1] - a[1]) as i128
            - (b[1] - a[1]) as i128 * (c[0] - a[0]) as i128
    };
    let on_seg = |a: LatticePoint, b: LatticePoint, p: LatticePoint| {
        orient(a, b, p) == 0
            && p[0] >= a[0].min(b[0])
            && p[0] <= a[0].max(b[0])
            && p[1] >= a[1].min(b[1])
            && p[1] <= a[1].max(b[1])
    };
    for e in 0..n {
        for f in e + 1..n {
            let adjacent = f == e + 1 || (e == 0 && f == n - 1);
            let (a, b, c, d) = (v[e], v[(e + 1) % n], v[f], v[(f + 1) % n]);
            let (o1, o2, o3, o4) = (
                orient(a, b, c),
                orient(a, b, d),
                orient(c, d, a),
                orient(c, d, b),
            );
            let crossing = o1.signum() * o2.signum() < 0 && o3.signum() * o4.signum() < 0;
            let touching = if adjacent {
                // Only the shared corner; folding back along the same line is not allowed.
                let shared = if f == e + 1 { b } else { a };
                let (p, q) = if f == e + 1 { (a, d) } else { (b, c) };
                (on_seg(c, d, p) && p != shared) || (on_seg(a, b, q) && q != shared)
            } else {
                on_seg(a, b, c) || on_seg(a, b, d) || on_seg(c, d, a) || on_seg(c, d, b)
            };
            if crossing || touching {
                return Err(UpsError::SelfIntersecting { edges: (e, f) });
            }
        }
    }
    Ok(())
}
