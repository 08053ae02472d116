//! Plane geometry of the domain: points, triangles and barycentric coordinates, convex hulls
//! and minimal enclosing triangles.

mod enclosing_linear;
mod enclosing_triangle;
pub mod hull;

pub use enclosing_triangle::{FIRST_CORNER_DIRECTION, min_enclosing_triangle};
pub use hull::convex_hull;

use nalgebra::{Point2, Vector2};

/// Barycentric coordinates (τ1, τ2, τ3) of a point, or a barycentric direction (d1, d2, d3)
/// with d1 + d2 + d3 = 0 (thesis Definitions 2.1 and 2.3).
pub type Bary = [f64; 3];

/// A triangle in the domain plane, vertices V1, V2, V3.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle2 {
    /// The three vertices.
    pub v: [Point2<f64>; 3],
}

/// The affine map from Cartesian (x, y) to barycentric coordinates of one triangle, written
/// about a local origin o near the triangle for accuracy: τ_i = c_i + g_i · ((x, y) − o).
/// (For a PS-triangle with o = V_i this is (2.37)–(2.39): c = α_i, g = (β_i, γ_i).)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaryMap {
    /// The local origin o.
    pub origin: Point2<f64>,
    /// The barycentric coordinates c_i of the origin.
    pub c: [f64; 3],
    /// Gradients g_i = ∂τ_i/∂(x, y); the x-column is the unit direction d_x of (2.18),
    /// the y-column d_y of (2.19).
    pub g: [Vector2<f64>; 3],
}

impl BaryMap {
    /// Barycentric coordinates of `p`.
    #[inline]
    pub fn apply(&self, p: Point2<f64>) -> Bary {
        let (x, y) = (p.x - self.origin.x, p.y - self.origin.y);
        [
            self.c[0] + self.g[0].x * x + self.g[0].y * y,
            self.c[1] + self.g[1].x * x + self.g[1].y * y,
            self.c[2] + self.g[2].x * x + self.g[2].y * y,
        ]
    }

    /// The same map written about another origin `o` (whose coordinates are computed
    /// accurately by `exact`, e.g. from sub-areas).
    pub fn with_origin(&self, o: Point2<f64>, exact: Bary) -> Self {
        BaryMap {
            origin: o,
            c: exact,
            g: self.g,
        }
    }
    /// The barycentric direction of the x-axis, d_x of (2.18).
    #[inline]
    pub fn dx(&self) -> Bary {
        [self.g[0].x, self.g[1].x, self.g[2].x]
    }
    /// The barycentric direction of the y-axis, d_y of (2.19).
    #[inline]
    pub fn dy(&self) -> Bary {
        [self.g[0].y, self.g[1].y, self.g[2].y]
    }
}

impl Triangle2 {
    /// The triangle with vertices `a`, `b`, `c`.
    pub fn new(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> Self {
        Triangle2 { v: [a, b, c] }
    }

    /// The determinant e of (2.20): twice the signed area, positive for counter-clockwise.
    #[inline]
    pub fn det(&self) -> f64 {
        cross(self.v[1] - self.v[0], self.v[2] - self.v[0])
    }

    /// The (unsigned) area A = |e| / 2 of (2.22).
    pub fn area(&self) -> f64 {
        self.det().abs() * 0.5
    }

    /// The smallest height: twice the area over the longest edge.
    pub fn min_height(&self) -> f64 {
        self.det().abs() / self.diameter()
    }

    /// The longest edge length.
    pub fn diameter(&self) -> f64 {
        (0..3)
            .map(|i| (self.v[(i + 1) % 3] - self.v[i]).norm())
            .fold(0.0, f64::max)
    }

    /// True when the area is tiny relative to the squared longest edge
    /// (the triangle is numerically a segment or a point).
    pub fn is_degenerate(&self) -> bool {
        // The longest edge squared, without square roots.
        let h2 = (0..3)
            .map(|i| (self.v[(i + 1) % 3] - self.v[i]).norm_squared())
            .fold(0.0, f64::max);
        !(self.det().abs() > 1e-12 * h2) || !h2.is_finite()
    }

    /// The affine map to barycentric coordinates, solving (2.1). `None` if degenerate.
    pub fn bary_map(&self) -> Option<BaryMap> {
        let e = self.det();
        if self.is_degenerate() {
            return None;
        }
        let [a, b, c] = self.v;
        // ∂τ1/∂(x, y) = (y2 − y3, x3 − x2) / e, and cyclically (2.18)–(2.20); about V1,
        // whose coordinates are (1, 0, 0).
        let g = [
            Vector2::new(b.y - c.y, c.x - b.x) / e,
            Vector2::new(c.y - a.y, a.x - c.x) / e,
            Vector2::new(a.y - b.y, b.x - a.x) / e,
        ];
        Some(BaryMap {
            origin: a,
            c: [1.0, 0.0, 0.0],
            g,
        })
    }

    /// Barycentric coordinates of `p` (2.1), computed from sub-areas for accuracy.
    /// Returns NaNs for a degenerate triangle.
    pub fn bary(&self, p: Point2<f64>) -> Bary {
        let e = self.det();
        let [a, b, c] = self.v;
        let t0 = cross(b - p, c - p) / e;
        let t1 = cross(c - p, a - p) / e;
        [t0, t1, 1.0 - t0 - t1]
    }

    /// The point with barycentric coordinates `t`.
    #[inline]
    pub fn point(&self, t: Bary) -> Point2<f64> {
        let [a, b, c] = self.v;
        Point2::new(
            t[0] * a.x + t[1] * b.x + t[2] * c.x,
            t[0] * a.y + t[1] * b.y + t[2] * c.y,
        )
    }

    /// The incentre: the vertices weighted by the lengths of the opposite edges.
    pub fn incenter(&self) -> Point2<f64> {
        let [a, b, c] = self.v;
        let la = (c - b).norm();
        let lb = (a - c).norm();
        let lc = (b - a).norm();
        let s = la + lb + lc;
        self.point([la / s, lb / s, lc / s])
    }

    /// The Euclidean distance from `p` to the closed triangle (0 inside).
    pub fn distance_to(&self, p: Point2<f64>) -> f64 {
        if self.contains_exact(p) {
            return 0.0;
        }
        let [a, b, c] = self.v;
        [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(u, v)| {
                let e = v - u;
                let t = ((p - u).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
                (p - (u + e * t)).norm()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The centroid.
    pub fn centroid(&self) -> Point2<f64> {
        self.point([1.0 / 3.0; 3])
    }

    /// Whether `p` lies in the closed triangle, decided exactly (adaptive-precision
    /// orientation tests, [`orient_exact`]); false for a triangle of zero area.
    pub fn contains_exact(&self, p: Point2<f64>) -> bool {
        let [a, b, c] = self.v;
        let turn = orient_exact(a, b, c);
        if turn == 0.0 || turn.is_nan() {
            return false;
        }
        [(a, b), (b, c), (c, a)]
            .iter()
            .all(|&(u, v)| orient_exact(u, v, p) * turn.signum() >= 0.0)
    }

    /// The triangle scaled about its centroid by 1 + `margin`.
    pub fn enlarged(&self, margin: f64) -> Triangle2 {
        let c = self.centroid();
        Triangle2 {
            v: self.v.map(|p| c + (p - c) * (1.0 + margin)),
        }
    }
}

/// The 2-D cross product (z-component of the 3-D cross product).
#[inline]
pub fn cross(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Twice the signed area of the triangle (a, b, c): positive when counter-clockwise.
/// Rounded: use [`orient_exact`] for decisions.
#[inline]
pub fn orient(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> f64 {
    cross(b - a, c - a)
}

/// The orientation of (a, b, c) with the exact sign: > 0 counter-clockwise, < 0 clockwise,
/// 0 exactly collinear (Shewchuk's adaptive-precision predicate, `robust::orient2d`; the
/// value approximates twice the signed area).
#[inline]
pub fn orient_exact(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> f64 {
    robust::orient2d(
        robust::Coord { x: a.x, y: a.y },
        robust::Coord { x: b.x, y: b.y },
        robust::Coord { x: c.x, y: c.y },
    )
}

/// The midpoint of a and b.
#[inline]
pub fn midpoint(a: Point2<f64>, b: Point2<f64>) -> Point2<f64> {
    Point2::new(0.5 * (a.x + b.x), 0.5 * (a.y + b.y))
}

/// The barycentric direction from point `from` to point `to`, w.r.t. a triangle's map.
pub fn bary_direction(map: &BaryMap, v: Vector2<f64>) -> Bary {
    [map.g[0].dot(&v), map.g[1].dot(&v), map.g[2].dot(&v)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle2 {
        Triangle2::new(
            Point2::new(0.3, -0.2),
            Point2::new(2.1, 0.4),
            Point2::new(0.7, 1.9),
        )
    }

    #[test]
    fn bary_map_agrees_with_sub_areas_and_reproduces_points() {
        let t = tri();
        let m = t.bary_map().unwrap();
        for p in [
            Point2::new(0.9, 0.5),
            Point2::new(-3.0, 7.0),
            Point2::new(0.3, -0.2),
        ] {
            let a = m.apply(p);
            let b = t.bary(p);
            for i in 0..3 {
                assert!((a[i] - b[i]).abs() < 1e-14);
            }
            assert!((a.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let q = t.point(a);
            assert!((q - p).norm() < 1e-13);
        }
        // The directions sum to zero and map the unit x-vector (Definition 2.3, (2.18)).
        let dx = m.dx();
        assert!(dx.iter().sum::<f64>().abs() < 1e-15);
        let moved = t.point([
            m.apply(Point2::origin())[0] + dx[0],
            m.apply(Point2::origin())[1] + dx[1],
            m.apply(Point2::origin())[2] + dx[2],
        ]);
        assert!((moved - Point2::new(1.0, 0.0)).norm() < 1e-13);
    }

    /// A right triangle with legs a, b, turned and moved at random: its smallest height is
    /// the one onto the hypotenuse, ab / √(a² + b²); points at distance d beyond a leg, the
    /// hypotenuse or the right-angle corner are d from it.
    #[test]
    fn min_height_and_distance_match_closed_forms_on_right_triangles() {
        use crate::test_util::*;
        let mut r = rng(31);
        for _ in 0..1000 {
            let (a, b) = (uniform(&mut r, 0.01, 10.0), uniform(&mut r, 0.01, 10.0));
            let angle = uniform(&mut r, 0.0, std::f64::consts::TAU);
            let shift = Vector2::new(uniform(&mut r, -5.0, 5.0), uniform(&mut r, -5.0, 5.0));
            let (c, s) = (angle.cos(), angle.sin());
            let place = |x: f64, y: f64| Point2::new(c * x - s * y, s * x + c * y) + shift;
            let t = Triangle2::new(place(0.0, 0.0), place(a, 0.0), place(0.0, b));
            let h = a * b / a.hypot(b);
            assert!((t.min_height() - h).abs() <= 1e-13 * h.max(1.0), "{a} {b}");
            let d = uniform(&mut r, 1e-3, 3.0);
            let u = uniform(&mut r, 0.05, 0.95);
            // Below the leg along x, left of the leg along y, beyond the corner.
            assert!((t.distance_to(place(u * a, -d)) - d).abs() <= 1e-12 * (1.0 + d));
            assert!((t.distance_to(place(-d, u * b)) - d).abs() <= 1e-12 * (1.0 + d));
            let corner = d / 2f64.sqrt();
            assert!((t.distance_to(place(-corner, -corner)) - d).abs() <= 1e-12 * (1.0 + d));
            // Beyond the hypotenuse along its outward normal (b, a) / √(a² + b²).
            let foot = (u * a, (1.0 - u) * b);
            let n = (b / a.hypot(b), a / a.hypot(b));
            let out = place(foot.0 + d * n.0, foot.1 + d * n.1);
            assert!(
                (t.distance_to(out) - d).abs() <= 1e-12 * (1.0 + d),
                "{a} {b} {d}"
            );
            // Inside: zero.
            assert_eq!(t.distance_to(place(0.25 * a, 0.25 * b)), 0.0);
        }
    }

    #[test]
    fn incenter_is_equidistant_from_the_edges() {
        let t = tri();
        let z = t.incenter();
        let dist = |a: Point2<f64>, b: Point2<f64>| orient(a, b, z).abs() / (b - a).norm();
        let d0 = dist(t.v[0], t.v[1]);
        let d1 = dist(t.v[1], t.v[2]);
        let d2 = dist(t.v[2], t.v[0]);
        assert!((d0 - d1).abs() < 1e-14 && (d1 - d2).abs() < 1e-14);
    }

    #[test]
    fn degenerate_triangles_are_detected() {
        let t = Triangle2::new(
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 2.0 + 1e-15),
        );
        assert!(t.is_degenerate());
        assert!(t.bary_map().is_none());
        assert!(!tri().is_degenerate());
    }
}
