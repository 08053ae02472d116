//! The parameter domain of a surface as a polygon with holes: containment decided exactly,
//! the boundary as closed polylines, segments clipped to it, distances to its boundary.

use nalgebra::{Point2, Vector2};
use thiserror::Error;

use super::piece::Rectangle;
use crate::geometry::Triangle2;
use crate::triangulation::Triangulation;

/// A bad description of a domain.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum DomainError {
    /// A boundary loop has fewer than three points.
    #[error("boundary loop {0} has fewer than three points")]
    TooFewPoints(usize),
    /// A boundary point is NaN or infinite.
    #[error("boundary loop {0} has a point that is not finite")]
    NonFinite(usize),
    /// There is no boundary loop.
    #[error("a domain needs at least one boundary loop")]
    Empty,
}

/// A closed region of the parameter plane bounded by closed polylines: outer boundaries
/// counter-clockwise, holes clockwise (so the domain always lies to the left of its
/// boundary). A point belongs to the domain when its winding number is not zero or when it
/// lies on the boundary.
///
/// Containment is decided with exact (adaptive-precision) orientation tests, so a point is
/// never both inside and outside because of rounding.
#[derive(Clone, Debug, PartialEq)]
pub struct Domain {
    loops: Vec<Vec<Point2<f64>>>,
    min: Point2<f64>,
    max: Point2<f64>,
}

/// The part `start..end` (parameters along the segment, 0 at its start and 1 at its end) of a
/// segment that lies in the domain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentPart {
    /// The parameter where the part begins.
    pub start: f64,
    /// The parameter where the part ends.
    pub end: f64,
}

use crate::geometry::orient_exact as orient;

impl Domain {
    /// The domain bounded by `loops` (each a closed polyline without its first point
    /// repeated; outer loops counter-clockwise, holes clockwise).
    ///
    /// ```
    /// use pssurf::surface::{Domain, DomainError};
    /// use nalgebra::Point2;
    /// let two = vec![vec![Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)]];
    /// assert_eq!(Domain::from_loops(two), Err(DomainError::TooFewPoints(0)));
    /// ```
    pub fn from_loops(loops: Vec<Vec<Point2<f64>>>) -> Result<Self, DomainError> {
        if loops.is_empty() {
            return Err(DomainError::Empty);
        }
        let mut min = Point2::new(f64::INFINITY, f64::INFINITY);
        let mut max = Point2::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        for (k, l) in loops.iter().enumerate() {
            if l.len() < 3 {
                return Err(DomainError::TooFewPoints(k));
            }
            for p in l {
                if !(p.x.is_finite() && p.y.is_finite()) {
                    return Err(DomainError::NonFinite(k));
                }
                min = Point2::new(min.x.min(p.x), min.y.min(p.y));
                max = Point2::new(max.x.max(p.x), max.y.max(p.y));
            }
        }
        Ok(Domain { loops, min, max })
    }

    /// A triangle (oriented counter-clockwise whatever the order of its vertices).
    pub fn triangle(t: &Triangle2) -> Self {
        let mut v = t.v.to_vec();
        if orient(v[0], v[1], v[2]) < 0.0 {
            v.swap(1, 2);
        }
        Self::from_loops(vec![v]).expect("three points")
    }

    /// An axis-parallel rectangle.
    pub fn rectangle(r: &Rectangle) -> Self {
        Self::from_loops(vec![r.corners().to_vec()]).expect("four points")
    }

    /// The union of the triangles of a triangulation: its boundary edges chained into loops
    /// (the outer boundary counter-clockwise, each hole clockwise).
    pub fn from_triangulation(tri: &Triangulation) -> Self {
        let n = tri.vertex_count();
        // Boundary edges run counter-clockwise within their triangle, so the domain is on
        // their left; vertices are manifold, so each boundary vertex starts one edge.
        let mut next = vec![usize::MAX; n];
        for (t, i) in tri.boundary_edges() {
            let (a, b) = tri.edge_vertices(t, i);
            next[a] = b;
        }
        let mut seen = vec![false; n];
        let mut loops = Vec::new();
        for start in 0..n {
            if next[start] == usize::MAX || seen[start] {
                continue;
            }
            let mut l = Vec::new();
            let mut v = start;
            while !seen[v] && next[v] != usize::MAX {
                seen[v] = true;
                l.push(tri.vertex(v));
                v = next[v];
            }
            loops.push(l);
        }
        Self::from_loops(loops).expect("a valid triangulation has a closed boundary")
    }

    /// The sides of the outer boundary: the runs between its corners, the vertices where it
    /// turns (decided by the exact orientation test), in the loop's order. A rectangle has
    /// four, a triangle three, a lattice polygon one per side.
    pub fn sides(&self) -> Vec<(Point2<f64>, Point2<f64>)> {
        let Some(outer) = self.boundary().first() else {
            return Vec::new();
        };
        let n = outer.len();
        let turns = |k: usize| {
            crate::geometry::orient_exact(outer[(k + n - 1) % n], outer[k], outer[(k + 1) % n])
                != 0.0
        };
        let corners: Vec<usize> = (0..n).filter(|&k| turns(k)).collect();
        (0..corners.len())
            .map(|c| (outer[corners[c]], outer[corners[(c + 1) % corners.len()]]))
            .collect()
    }

    /// The boundary loops (each closed: its last point joins its first).
    pub fn boundary(&self) -> &[Vec<Point2<f64>>] {
        &self.loops
    }

    /// The number of holes (clockwise loops).
    pub fn hole_count(&self) -> usize {
        self.loops.iter().filter(|l| signed_area(l) < 0.0).count()
    }

    /// The bounding box (min corner, max corner).
    pub fn bounds(&self) -> (Point2<f64>, Point2<f64>) {
        (self.min, self.max)
    }

    /// The area: outer loops minus holes.
    pub fn area(&self) -> f64 {
        self.loops.iter().map(|l| signed_area(l)).sum()
    }

    /// The boundary edges (a, b) of every loop.
    fn edges(&self) -> impl Iterator<Item = (Point2<f64>, Point2<f64>)> + '_ {
        self.loops
            .iter()
            .flat_map(|l| (0..l.len()).map(move |i| (l[i], l[(i + 1) % l.len()])))
    }

    /// True when `p` lies on the boundary (exact).
    pub fn on_boundary(&self, p: Point2<f64>) -> bool {
        self.edges().any(|(a, b)| on_segment(a, b, p))
    }

    /// True when `p` lies in the closed domain (exact: interior or boundary).
    pub fn contains(&self, p: Point2<f64>) -> bool {
        if !(p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y) {
            return false;
        }
        let mut winding = 0i64;
        for (a, b) in self.edges() {
            if on_segment(a, b, p) {
                return true;
            }
            if a.y <= p.y {
                if b.y > p.y && orient(a, b, p) > 0.0 {
                    winding += 1;
                }
            } else if b.y <= p.y && orient(a, b, p) < 0.0 {
                winding -= 1;
            }
        }
        winding != 0
    }

    /// The parts of the segment from `a` to `b` that lie in the domain, in order, as
    /// parameter intervals (touching the boundary at a single point gives an empty part
    /// `t..t`, which is dropped).
    pub fn clip_segment(&self, a: Point2<f64>, b: Point2<f64>) -> Vec<SegmentPart> {
        let mut cuts = vec![0.0, 1.0];
        for (c, d) in self.edges() {
            crossing_parameters(a, b, c, d, &mut cuts);
        }
        cuts.retain(|t| (0.0..=1.0).contains(t));
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let at = |t: f64| a + (b - a) * t;
        let mut parts: Vec<SegmentPart> = Vec::new();
        for w in cuts.windows(2) {
            if !self.contains(at(0.5 * (w[0] + w[1]))) {
                continue;
            }
            match parts.last_mut() {
                Some(last) if last.end == w[0] => last.end = w[1],
                _ => parts.push(SegmentPart {
                    start: w[0],
                    end: w[1],
                }),
            }
        }
        if parts.is_empty() && a == b && self.contains(a) {
            parts.push(SegmentPart {
                start: 0.0,
                end: 1.0,
            });
        }
        parts
    }

    /// The nearest point of the boundary to `p`.
    pub fn closest_boundary_point(&self, p: Point2<f64>) -> Point2<f64> {
        let mut best = (f64::INFINITY, p);
        for (a, b) in self.edges() {
            let q = closest_on_segment(a, b, p);
            let d = (q - p).norm_squared();
            if d < best.0 {
                best = (d, q);
            }
        }
        best.1
    }

    /// The distance from `p` to the boundary (whether `p` is inside or not).
    pub fn distance_to_boundary(&self, p: Point2<f64>) -> f64 {
        (self.closest_boundary_point(p) - p).norm()
    }
}

/// The signed area of a closed polyline (positive when counter-clockwise).
fn signed_area(l: &[Point2<f64>]) -> f64 {
    let o = l[0];
    let mut s = 0.0;
    for i in 1..l.len() - 1 {
        s += (l[i] - o).perp(&(l[i + 1] - o));
    }
    0.5 * s
}

/// True when `p` lies on the closed segment [a, b] (exact).
fn on_segment(a: Point2<f64>, b: Point2<f64>, p: Point2<f64>) -> bool {
    p.x >= a.x.min(b.x)
        && p.x <= a.x.max(b.x)
        && p.y >= a.y.min(b.y)
        && p.y <= a.y.max(b.y)
        && orient(a, b, p) == 0.0
}

/// Adds the parameters t along [a, b] where it meets the segment [c, d] (its end points if
/// the two overlap).
fn crossing_parameters(
    a: Point2<f64>,
    b: Point2<f64>,
    c: Point2<f64>,
    d: Point2<f64>,
    out: &mut Vec<f64>,
) {
    let (oc, od) = (orient(a, b, c), orient(a, b, d));
    let (oa, ob) = (orient(c, d, a), orient(c, d, b));
    if oc == 0.0 && od == 0.0 {
        // Collinear: the overlap's ends.
        let r: Vector2<f64> = b - a;
        let len2 = r.norm_squared();
        if len2 > 0.0 {
            out.push((c - a).dot(&r) / len2);
            out.push((d - a).dot(&r) / len2);
        }
        return;
    }
    if oc * od > 0.0 || oa * ob > 0.0 {
        return; // no contact
    }
    // The line through c, d meets [a, b] at t = oa / (oa − ob) (ratios of exact areas).
    let denom = oa - ob;
    if denom != 0.0 {
        out.push(oa / denom);
    }
}

/// The point of [a, b] nearest to p.
fn closest_on_segment(a: Point2<f64>, b: Point2<f64>, p: Point2<f64>) -> Point2<f64> {
    let r = b - a;
    let len2 = r.norm_squared();
    if len2 == 0.0 {
        return a;
    }
    let t = ((p - a).dot(&r) / len2).clamp(0.0, 1.0);
    a + r * t
}
