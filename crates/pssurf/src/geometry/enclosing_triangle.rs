//! The triangle of minimal area enclosing a point set: Dierckx's optimal PS-triangle
//! (thesis section 2.3.2, "The choice of the PS-triangles").
//!
//! Facts used (for a convex polygon P, after Klee & Laskowski, *Finding the smallest
//! triangles containing a given convex polygon*, J. Algorithms 6, 1985):
//! 1. In a locally minimal enclosing triangle the midpoint of every side touches P.
//! 2. Some minimal triangle has a side flush with an edge of P. If, with side a flush, the
//!    other two sides touched P only at vertices, those vertices would be the midpoints of
//!    their sides and hence lie at the same height over side a; sliding the apex parallel to
//!    side a keeps the area and the containment until a second side becomes flush. So some
//!    minimal triangle has **two** sides flush with edges of P.
//! 3. With two flush sides fixed, they form a wedge with apex A; write each vertex of P as
//!    q = A + s_q u + t_q v (s, t ≥ 0). A third side cutting the wedge at A + X u and A + Y v
//!    encloses P iff s_q/X + t_q/Y ≤ 1 for all q; its area is XY |u × v| / 2. Maximising
//!    (1/X)(1/Y) over this convex region: the optimum either touches a single vertex q at its
//!    midpoint, X = 2 s_q, Y = 2 t_q — then q maximises s_q t_q and the area is the lower
//!    bound 2 max s_q t_q |u × v| — or it is flush with an edge of P.
//!
//! In terms of the distances D_j(q) ≥ 0 of the vertices from the edge lines, with φ the
//! wedge's opening angle, s_q = D_b(q)/sin φ and t_q = D_a(q)/sin φ, so the lower bound of
//! a wedge is 2 max_q D_a(q) D_b(q) / sin φ: n multiplications once the n × n table of
//! distances is known. Wedges are examined in increasing order of their lower bound and the
//! search stops when the bound reaches the best area found, which usually happens after the
//! first wedge. Cost: O(n²) for the table and the bounds, O(n) per examined wedge.

use nalgebra::{Point2, Vector2};

use super::hull::convex_hull_into;
use super::{Triangle2, cross};

/// The minimal-area triangle containing `points` (exact up to rounding), counter-clockwise.
/// `None` when the points are collinear (no triangle of positive area is needed).
///
/// ```
/// use pssurf::geometry::min_enclosing_triangle;
/// use nalgebra::Point2;
/// // A unit square: the minimal enclosing triangle has area 2.
/// let sq = [Point2::new(0., 0.), Point2::new(1., 0.), Point2::new(1., 1.), Point2::new(0., 1.)];
/// let t = min_enclosing_triangle(&sq).unwrap();
/// assert!((t.area() - 2.0).abs() < 1e-12);
/// ```
pub fn min_enclosing_triangle(points: &[Point2<f64>]) -> Option<Triangle2> {
    HULL.with(|h| {
        let (sorted, hull) = &mut *h.borrow_mut();
        sorted.clear();
        sorted.extend_from_slice(points);
        convex_hull_into(sorted, hull);
        min_enclosing_triangle_of_hull(hull)
    })
}

/// Buffers for the hull: a sorted copy of the points, and the hull vertices.
type HullBuffers = (Vec<Point2<f64>>, Vec<Point2<f64>>);

thread_local! {
    static HULL: std::cell::RefCell<HullBuffers> = const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
}

/// The third side of a wedge's best triangle, in distance coordinates: the line
/// A'·D_b + B'·D_a = 1 (A', B' > 0).
#[derive(Clone, Copy, Debug)]
struct Third {
    a: f64,
    b: f64,
}

/// Reused buffers, one set per thread (this runs once per vertex of large meshes).
#[derive(Default)]
struct Scratch {
    dirs: Vec<Vector2<f64>>,
    dist: Vec<f64>,
    wedges: Vec<(f64, u16, u16)>,
    /// The triangles found, (area, first flush edge, second, third side).
    found: Vec<(f64, usize, usize, Third)>,
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch::default());
}

/// max_k a_k b_k (all entries ≥ 0), unrolled for instruction-level parallelism.
#[inline]
fn max_product(a: &[f64], b: &[f64]) -> f64 {
    let mut m = [0.0f64; 4];
    let chunks = a.len() / 4;
    for c in 0..chunks {
        for l in 0..4 {
            let p = a[4 * c + l] * b[4 * c + l];
            m[l] = if p > m[l] { p } else { m[l] };
        }
    }
    for k in 4 * chunks..a.len() {
        let p = a[k] * b[k];
        m[0] = if p > m[0] { p } else { m[0] };
    }
    m[0].max(m[1]).max(m[2].max(m[3]))
}

/// As [`min_enclosing_triangle`] for a convex polygon given counter-clockwise without
/// collinear vertices (as [`convex_hull`] returns it).
pub fn min_enclosing_triangle_of_hull(hull: &[Point2<f64>]) -> Option<Triangle2> {
    let n = hull.len();
    if n < 3 {
        return None;
    }
    if n == 3 {
        return Some(Triangle2::new(hull[0], hull[1], hull[2]));
    }
    if n > SMALL_HULL {
        // Large hulls (vertices of high degree): the linear rotation; the quadratic table
        // below is the fallback only where it stays cheap, then a bounding triangle.
        if let Some(t) = super::enclosing_linear::min_enclosing_triangle_linear(hull) {
            return Some(t);
        }
        if n > MAX_QUADRATIC_HULL {
            return Some(bounding_triangle(hull));
        }
    }
    min_enclosing_triangle_by_wedges(hull)
}

/// Hulls up to this many vertices use the wedge search below (exact, and fastest there:
/// 1.8 µs at 16 vertices); larger ones the linear rotation.
const SMALL_HULL: usize = 24;

/// The largest hull given to the wedge search when the rotation finds nothing (its table
/// is quadratic and its search cubic in the worst case: 2.3 ms at 256 vertices).
const MAX_QUADRATIC_HULL: usize = 256;

/// A triangle enclosing the hull's bounding box [x0, x0 + w] × [y0, y0 + h]: the right
/// triangle (x0, y0), (x0 + 2w, y0), (x0, y0 + 2h), whose hypotenuse touches the box's far
/// corner. Valid, not minimal: the last resort.
fn bounding_triangle(hull: &[Point2<f64>]) -> Triangle2 {
    let (lo, hi) = hull
        .iter()
        .fold((hull[0], hull[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let (w, h) = (hi.x - lo.x, hi.y - lo.y);
    // Slightly larger, so that rounding never puts the far corner outside.
    let grow = 1.0 + 1e-9;
    Triangle2::new(
        lo,
        Point2::new(lo.x + 2.0 * w * grow, lo.y),
        Point2::new(lo.x, lo.y + 2.0 * h * grow),
    )
}

/// The wedge search of the module docs (exact up to rounding; cost O(n²) and more).
fn min_enclosing_triangle_by_wedges(hull: &[Point2<f64>]) -> Option<Triangle2> {
    let n = hull.len();
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        let Scratch {
            dirs,
            dist,
            wedges,
            found,
        } = &mut *s;
        // Unit edge directions; P lies to the left of each (inward normal (−d.y, d.x)).
        dirs.clear();
        dirs.extend((0..n).map(|i| (hull[(i + 1) % n] - hull[i]).normalize()));
        // dist[j * n + k] = D_j(q_k), the distance of vertex k from the line of edge j.
        dist.clear();
        dist.resize(n * n, 0.0);
        for j in 0..n {
            let (d, o) = (dirs[j], hull[j]);
            for k in 0..n {
                dist[j * n + k] = cross(d, hull[k] - o).max(0.0);
            }
        }
        // Lower bounds of all wedges, and the smallest.
        wedges.clear();
        let mut first = (f64::INFINITY, 0usize);
        for a in 0..n {
            for b in a + 1..n {
                let sin = cross(dirs[a], dirs[b]).abs();
                if sin <= 1e-12 {
                    continue; // parallel edges: no wedge
                }
                let lower =
                    2.0 * max_product(&dist[a * n..a * n + n], &dist[b * n..b * n + n]) / sin;
                if lower < first.0 {
                    first = (lower, wedges.len());
                }
                wedges.push((lower, a as u16, b as u16));
            }
        }
        // The most promising wedge first; then only wedges whose bound beats the best (or
        // ties with it). Every triangle within TIE of the best area is kept.
        found.clear();
        let mut best = f64::INFINITY;
        let order = std::iter::once(first.1).chain((0..wedges.len()).filter(|&w| w != first.1));
        for w in order {
            let (lower, a, b) = wedges[w];
            let (a, b) = (a as usize, b as usize);
            if lower > best * (1.0 + TIE) {
                continue;
            }
            let sin = cross(dirs[a], dirs[b]).abs();
            let (da, db) = (&dist[a * n..a * n + n], &dist[b * n..b * n + n]);
            let qs = (0..n)
                .max_by(|&i, &j| (da[i] * db[i]).total_cmp(&(da[j] * db[j])))
                .unwrap_or(0);
            if let Some((area, third)) = best_third_side(da, db, qs, lower, sin)
                && area <= best * (1.0 + TIE)
            {
                best = best.min(area);
                found.push((area, a, b, third));
            }
        }
        let tied = found
            .iter()
            .filter(|(area, ..)| *area <= best * (1.0 + TIE))
            .map(|&(_, a, b, third)| build_triangle(hull, dirs, a, b, third));
        first_of_ties(tied, hull)
    })
}

/// The direction (cos 1, sin 1): one radian is no rational multiple of π, so two corners
/// whose directions from the centroid are (as on grids and symmetric shapes) never lie
/// symmetrically about it.
pub const FIRST_CORNER_DIRECTION: (f64, f64) = (0.5403023058681398, 0.8414709848078965);

/// Areas within this relative difference are a tie: symmetric point sets (a vertex of a
/// grid) have several minimal triangles, mirror images, and rounding picked one or the other
/// as the coordinates were scaled.
const TIE: f64 = 1e-9;

/// Of minimal triangles tied in area, the one whose corners reach farthest along
/// [`FIRST_CORNER_DIRECTION`] from the hull's centroid,
/// relative to the hull's size: a choice that moves and scales with the points (mirror images
/// differ in it unless symmetric about that direction, which grids and axis-aligned shapes
/// are not).
fn first_of_ties(tied: impl Iterator<Item = Triangle2>, hull: &[Point2<f64>]) -> Option<Triangle2> {
    let c = hull.iter().fold(Vector2::zeros(), |s, p| s + p.coords) / hull.len() as f64;
    let (dx, dy) = FIRST_CORNER_DIRECTION;
    let reach = |t: &Triangle2| {
        t.v.iter()
            .map(|p| (p.x - c.x) * dx + (p.y - c.y) * dy)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    tied.max_by(|s, t| reach(s).total_cmp(&reach(t)))
}

/// The best third side in the wedge of edges a and b (distances `da`, `db`): through the
/// vertex q* maximising D_a D_b at its midpoint if that encloses P (area = `lower`), else
/// flush with an edge of P.
fn best_third_side(
    da: &[f64],
    db: &[f64],
    qs: usize,
    lower: f64,
    sin: f64,
) -> Option<(f64, Third)> {
    let n = da.len();
    let (sq, tq) = (db[qs], da[qs]);
    if sq > 0.0 && tq > 0.0 {
        // Midpoint line: D_b / (2 D_b*) + D_a / (2 D_a*) = 1.
        let third = Third {
            a: 0.5 / sq,
            b: 0.5 / tq,
        };
        if (0..n).all(|k| third.a * db[k] + third.b * da[k] <= 1.0 + 1e-12) {
            return Some((lower, third));
        }
    }
    // Flush with edge (k, k+1): the line through (σ_k, τ_k) and (σ_k1, τ_k1) (σ = D_b,
    // τ = D_a) is A' σ + B' τ = 1 with A' = p_a / det, B' = p_b / det, p_a = τ_k1 − τ_k,
    // p_b = σ_k − σ_k1, det = σ_k τ_k1 − σ_k1 τ_k; its area is det² / (2 p_a p_b sin φ).
    // Candidates are compared without dividing.
    let mut best: Option<(usize, f64, f64)> = None; // (k, det², p_a p_b)
    for k in 0..n {
        let k1 = if k + 1 == n { 0 } else { k + 1 };
        let (s1, t1, s2, t2) = (db[k], da[k], db[k1], da[k1]);
        let det = s1 * t2 - s2 * t1;
        let (pa, pb) = (t2 - t1, s1 - s2);
        if !(pa * det > 0.0 && pb * det > 0.0) {
            continue; // A' and B' must be positive
        }
        // P must lie on the apex side: p_a σ + p_b τ ≤ det (for det > 0; reversed otherwise).
        // By convexity one vertex off the line decides it; check two, as one of them may be
        // the apex itself (D = 0) when the two flush edges are adjacent.
        let beyond = |j: usize| (pa * db[j] + pb * da[j] - det) * det.signum() > 1e-12 * det.abs();
        if beyond((k + 2) % n) || beyond((k + n - 1) % n) {
            continue;
        }
        let (num, den) = (det * det, pa * pb);
        if best.is_none_or(|(_, bn, bd)| num * bd < bn * den) {
            best = Some((k, num, den));
        }
    }
    let (k, num, den) = best?;
    let k1 = (k + 1) % n;
    let det = db[k] * da[k1] - db[k1] * da[k];
    let third = Third {
        a: (da[k1] - da[k]) / det,
        b: (db[k] - db[k1]) / det,
    };
    Some((0.5 * num / (den * sin), third))
}

/// The triangle with sides on the lines of edges a and b and the third side `third`.
fn build_triangle(
    hull: &[Point2<f64>],
    dirs: &[Vector2<f64>],
    a: usize,
    b: usize,
    third: Third,
) -> Triangle2 {
    let (da, db) = (dirs[a], dirs[b]);
    let sin_signed = cross(da, db);
    let w = hull[b] - hull[a];
    let apex = hull[a] + da * (cross(w, db) / sin_signed);
    // Rays along each line, pointing into the other's inner half-plane.
    let u = if cross(db, da) > 0.0 { da } else { -da };
    let v = if cross(da, db) > 0.0 { db } else { -db };
    let sin = sin_signed.abs();
    let (x, y) = (1.0 / (third.a * sin), 1.0 / (third.b * sin));
    let (p1, p2) = (apex + u * x, apex + v * y);
    if cross(p1 - apex, p2 - apex) > 0.0 {
        Triangle2::new(apex, p1, p2)
    } else {
        Triangle2::new(apex, p2, p1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::convex_hull;
    use crate::test_util::*;

    /// Brute force over all triples of hull edge lines, plus the lower-bound-free
    /// wedge search with every candidate kept: an independent check for small polygons.
    fn brute_force(points: &[Point2<f64>]) -> f64 {
        let hull = convex_hull(points);
        let n = hull.len();
        let mut best = f64::INFINITY;
        // Any enclosing triangle is at least as large as the hull: this rejects the spurious
        // near-zero "triangles" that rounding lets through the containment test.
        let hull_area: f64 = (1..n - 1)
            .map(|i| Triangle2::new(hull[0], hull[i], hull[i + 1]).area())
            .sum();
        let valid = |t: &Triangle2| {
            t.area() >= hull_area * (1.0 - 1e-9)
                && hull.iter().all(|&q| t.bary(q).iter().all(|&x| x >= -1e-9))
        };
        // All triangles with three flush sides.
        let line = |i: usize| (hull[i], hull[(i + 1) % n] - hull[i]);
        let meet = |(p, d): (Point2<f64>, Vector2<f64>), (q, e): (Point2<f64>, Vector2<f64>)| {
            let s = cross(d, e);
            (s.abs() > 1e-12).then(|| p + d * (cross(q - p, e) / s))
        };
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    if i == j || j == k || i == k {
                        continue;
                    }
                    let (Some(a), Some(b), Some(c)) = (
                        meet(line(i), line(j)),
                        meet(line(j), line(k)),
                        meet(line(k), line(i)),
                    ) else {
                        continue;
                    };
                    let t = Triangle2::new(a, b, c);
                    if valid(&t) {
                        best = best.min(t.area());
                    }
                }
            }
        }
        // Two flush sides and a third touching one vertex at its midpoint, any wedge.
        for i in 0..n {
            for j in 0..n {
                if i == j {
                    continue;
                }
                let Some(apex) = meet(line(i), line(j)) else {
                    continue;
                };
                for &q in &hull {
                    for sgn in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                        let (u, v) = (line(i).1 * sgn.0, line(j).1 * sgn.1);
                        let uv = cross(u, v);
                        let d = q - apex;
                        let (s, t) = (cross(d, v) / uv, cross(u, d) / uv);
                        if s <= 0.0 || t <= 0.0 {
                            continue;
                        }
                        let tri = Triangle2::new(apex, apex + u * (2.0 * s), apex + v * (2.0 * t));
                        if valid(&tri) {
                            best = best.min(tri.area());
                        }
                    }
                }
            }
        }
        best
    }

    #[test]
    fn matches_brute_force_and_contains_the_points() {
        let mut r = rng(30);
        for case in 0..300 {
            let n = 4 + case % 12;
            let pts: Vec<Point2<f64>> = (0..n)
                .map(|_| Point2::new(uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0) * 0.3))
                .collect();
            let t = min_enclosing_triangle(&pts).unwrap();
            assert!(t.det() > 0.0);
            for &p in &pts {
                assert!(
                    t.bary(p).iter().all(|&x| x >= -1e-12),
                    "case {case}: {p:?} outside"
                );
            }
            let bf = brute_force(&pts);
            assert!(
                (t.area() - bf).abs() <= 1e-9 * bf,
                "case {case}: {} vs brute force {}",
                t.area(),
                bf
            );
            // Local minimality: every side's midpoint touches the hull.
            let hull = convex_hull(&pts);
            for i in 0..3 {
                let m = crate::geometry::midpoint(t.v[(i + 1) % 3], t.v[(i + 2) % 3]);
                let inside = crate::geometry::hull::point_in_convex(&hull, m, 1e-9);
                assert!(
                    inside,
                    "case {case}: midpoint of side {i} is not on the hull"
                );
            }
        }
    }

    #[test]
    fn regular_polygons_have_known_minimal_triangles() {
        // For a regular hexagon of side 1 the minimal triangle extends alternate sides: an
        // equilateral triangle of side 3, area 9√3/4 (1.5 times the hexagon's).
        let hex: Vec<_> = (0..6)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 6.0;
                Point2::new(a.cos(), a.sin())
            })
            .collect();
        let t = min_enclosing_triangle(&hex).unwrap();
        assert!(
            (t.area() - 9.0 * 3f64.sqrt() / 4.0).abs() < 1e-12,
            "{}",
            t.area()
        );
        // A triangle encloses itself.
        let tri = [
            Point2::new(0., 0.),
            Point2::new(3., 0.),
            Point2::new(1., 2.),
            Point2::new(1., 0.5),
        ];
        assert!((min_enclosing_triangle(&tri).unwrap().area() - 3.0).abs() < 1e-12);
        assert!(min_enclosing_triangle(&[Point2::new(0., 0.), Point2::new(1., 1.)]).is_none());
    }

    /// The linear rotation (used for hulls above `SMALL_HULL` vertices) against the brute
    /// force and the wedge search, on random convex polygons of 4 … 60 vertices at scales
    /// 1e-6 … 1e6 and offsets to 1e6: it must always find a triangle (no fallback) of the
    /// same area to 1e-9, enclosing every vertex.
    #[test]
    fn the_linear_rotation_matches_the_exact_searches() {
        use crate::geometry::enclosing_linear::min_enclosing_triangle_linear;
        let mut r = rng(31);
        let mut compared_with_brute_force = 0;
        for case in 0..400 {
            // Points on a random ellipse (every one a hull vertex) or in a random box.
            let k = 4 + case % 57;
            let (ax, ay, rot) = (
                uniform(&mut r, 0.2, 1.0),
                uniform(&mut r, 0.2, 1.0),
                uniform(&mut r, 0.0, 3.0),
            );
            let scale = 10f64.powi(case % 13 - 6);
            let offset = if case % 3 == 0 {
                1e6 * scale.sqrt()
            } else {
                0.0
            };
            let pts: Vec<Point2<f64>> = (0..k)
                .map(|_| {
                    let (x, y) = if case % 2 == 0 {
                        let t = uniform(&mut r, 0.0, std::f64::consts::TAU);
                        (ax * t.cos(), ay * t.sin())
                    } else {
                        (uniform(&mut r, -ax, ax), uniform(&mut r, -ay, ay))
                    };
                    let (c, s) = (rot.cos(), rot.sin());
                    Point2::new(
                        offset + scale * (c * x - s * y),
                        offset + scale * (s * x + c * y),
                    )
                })
                .collect();
            let hull = convex_hull(&pts);
            if hull.len() < 4 {
                continue;
            }
            let t = min_enclosing_triangle_linear(&hull).unwrap_or_else(|| {
                panic!(
                    "case {case}: no triangle for {} vertices: {hull:?}",
                    hull.len()
                )
            });
            // Enclosing up to the rounding of the coordinates: a barycentric coordinate is
            // off by about ulp(offset) / (the triangle's height).
            let resolution = 8.0 * f64::EPSILON * (offset + scale);
            let slack = 1e-9 + resolution / t.min_height().min(scale);
            for &p in &hull {
                assert!(
                    t.bary(p).iter().all(|&x| x >= -slack),
                    "case {case}: {p:?} outside: {:?} (slack {slack:e})",
                    t.bary(p)
                );
            }
            let exact = min_enclosing_triangle_by_wedges(&hull).unwrap().area();
            assert!(
                // The wedge search works on the offset coordinates: the same resolution.
                (t.area() - exact).abs() <= slack * exact,
                "case {case} ({} vertices): {} vs {exact}",
                hull.len(),
                t.area()
            );
            // (The brute force's thresholds are absolute: only at unit-like scales.)
            if hull.len() <= 12 && offset == 0.0 && (1e-2..=1e2).contains(&scale) {
                let bf = brute_force(&pts);
                assert!(
                    (t.area() - bf).abs() <= 1e-9 * bf,
                    "case {case}: {} vs {bf}",
                    t.area()
                );
                compared_with_brute_force += 1;
            }
        }
        assert!(
            compared_with_brute_force > 50,
            "{compared_with_brute_force}"
        );
    }

    /// Closed forms at any size: for a regular N-gon of circumradius r with N divisible by 3
    /// the minimal triangle is equilateral with three flush sides, inradius r cos(π/N), area
    /// 3√3 r² cos²(π/N); a rectangle's is twice its area, in any rotation.
    #[test]
    fn large_hulls_meet_closed_forms() {
        for n in [27usize, 99, 300, 3000, 9999] {
            let r = 2.5;
            let pts: Vec<Point2<f64>> = (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64 + 0.1;
                    Point2::new(1.0 + r * a.cos(), -3.0 + r * a.sin())
                })
                .collect();
            let t = min_enclosing_triangle(&pts).unwrap();
            let c = (std::f64::consts::PI / n as f64).cos();
            let want = 3.0 * 3f64.sqrt() * r * r * c * c;
            assert!(
                (t.area() - want).abs() <= 1e-12 * want,
                "{n}: {} vs {want}",
                t.area()
            );
        }
        let mut r = rng(5);
        for _ in 0..50 {
            let (w, h, a) = (
                uniform(&mut r, 0.1, 3.0),
                uniform(&mut r, 0.1, 3.0),
                uniform(&mut r, 0.0, 3.0),
            );
            let (c, s) = (a.cos(), a.sin());
            // A rectangle with extra points on its sides (so that the hull is large enough
            // for the rotation only when they survive; they are collinear and removed).
            let rect: Vec<Point2<f64>> = [(-w, -h), (w, -h), (w, h), (-w, h)]
                .iter()
                .map(|&(x, y)| Point2::new(c * x - s * y, s * x + c * y))
                .collect();
            let t = min_enclosing_triangle(&rect).unwrap();
            assert!(
                (t.area() - 8.0 * w * h).abs() <= 1e-9 * 8.0 * w * h,
                "{} vs {}",
                t.area(),
                8.0 * w * h
            );
        }
    }
}
