//! The minimal-area enclosing triangle of a convex polygon in linear time: the rotating
//! algorithm of O'Rourke, Aggarwal, Maddila and Baldwin (*An optimal algorithm for finding
//! minimal enclosing triangles*, J. Algorithms 7, 1986), in the form worked out by Pârvu and
//! Gilbert (*Implementation of linear minimum area enclosing triangle algorithm*, Comp. Appl.
//! Math. 2014), written here with signed heights and orientation tests instead of angles.
//!
//! Each edge of the polygon in turn is the flush side C. Two indices a and b, which only
//! move forward, find the sides A and B of the locally minimal triangle with side C flush:
//! the midpoint of every side touches the polygon (Klee & Laskowski). Three kinds of
//! candidate arise: B flush and A touching at a vertex (its midpoint), A flush and B touching
//! at a vertex, or both flush. The smallest valid candidate that encloses the polygon wins.
//!
//! The decisions compare heights and directions of a polygon normalised to unit size, with
//! tolerances relative to it; the result is checked for containment and the caller falls
//! back to the exact quadratic search when no candidate survives (it never happened in the
//! tests: see `enclosing_triangle::tests`).

use nalgebra::{Point2, Vector2};

use super::{Triangle2, cross};

/// Tolerance for comparisons of heights and coordinates of the normalised polygon (unit
/// size).
const TOL: f64 = 1e-9;

/// What a candidate's sides are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// B flush with an edge, A touching the polygon at vertex a − 1 (its midpoint).
    SideATangent,
    /// A flush with an edge, B touching the polygon at vertex b (its midpoint).
    SideBTangent,
    /// A and B both flush with edges.
    SidesFlush,
}

/// Where the ray from a vertex, in a given direction, enters the polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Crossing {
    /// It enters lower than the vertex (closer to line C).
    Below,
    /// It enters higher.
    Above,
    /// It does not enter (or only grazes the boundary).
    Critical,
}

/// A line through two points.
#[derive(Clone, Copy, Debug)]
struct Line {
    p: Point2<f64>,
    q: Point2<f64>,
}

impl Line {
    fn new(p: Point2<f64>, q: Point2<f64>) -> Line {
        Line { p, q }
    }

    /// The intersection with `other`, `None` if (nearly) parallel.
    fn meet(&self, other: &Line) -> Option<Point2<f64>> {
        let (d, e) = (self.q - self.p, other.q - other.p);
        let s = cross(d, e);
        if s.abs() <= TOL * TOL * d.norm() * e.norm() {
            return None;
        }
        Some(self.p + d * (cross(other.p - self.p, e) / s))
    }
}

/// The polygon (counter-clockwise, normalised) and the current flush edge.
struct State<'a> {
    p: &'a [Point2<f64>],
    n: usize,
    /// Index c: side C is flush with edge (c − 1, c).
    c: usize,
    /// Unit direction of edge (c − 1, c).
    dir_c: Vector2<f64>,
}

impl State<'_> {
    fn succ(&self, i: usize) -> usize {
        if i + 1 == self.n { 0 } else { i + 1 }
    }

    fn pred(&self, i: usize) -> usize {
        if i == 0 { self.n - 1 } else { i - 1 }
    }

    /// The signed height of `x` above line C, positive on the polygon's side.
    fn height_of(&self, x: Point2<f64>) -> f64 {
        cross(self.dir_c, x - self.p[self.c])
    }

    /// The height of vertex i above line C.
    fn h(&self, i: usize) -> f64 {
        self.height_of(self.p[i]).max(0.0)
    }

    /// The point of `line` at height `target` above line C; `None` if the line is parallel
    /// to C (unless it lies at that height: then its first point).
    fn at_height(&self, line: &Line, target: f64) -> Option<Point2<f64>> {
        let (hp, hq) = (self.height_of(line.p), self.height_of(line.q));
        if (hq - hp).abs() <= TOL * TOL {
            return ((hp - target).abs() <= TOL).then_some(line.p);
        }
        let t = (target - hp) / (hq - hp);
        Some(line.p + (line.q - line.p) * t)
    }

    /// γ(i): the point of line A (through vertices a − 1 and a) at twice the height of
    /// vertex i. A side from there through vertex i has vertex i as its midpoint.
    fn gamma(&self, i: usize, a: usize) -> Option<Point2<f64>> {
        let side_a = Line::new(self.p[a], self.p[self.pred(a)]);
        self.at_height(&side_a, 2.0 * self.h(i))
    }

    /// Whether `v` lies strictly inside the cone of directions between `from` and `to`
    /// (the one of angle below π).
    fn in_cone(v: Vector2<f64>, from: Vector2<f64>, to: Vector2<f64>) -> bool {
        let s = cross(from, to);
        s != 0.0 && cross(from, v) * s > 0.0 && cross(v, to) * s > 0.0
    }

    /// Whether two directions agree (up to the tolerance, in radians).
    fn same_direction(v: Vector2<f64>, w: Vector2<f64>) -> bool {
        let (nv, nw) = (v.norm(), w.norm());
        nv > 0.0 && nw > 0.0 && v.dot(&w) > 0.0 && cross(v, w).abs() <= TOL * nv * nw
    }

    /// Where the ray from vertex i in direction −g enters the polygon, relative to vertex
    /// i's height (Pârvu & Gilbert's "intersects below/above", by directions: −g enters
    /// exactly when g lies in the cone between P_i − P_{i−1} and P_i − P_{i+1}).
    fn classify(&self, g: Vector2<f64>, i: usize) -> Crossing {
        let (prev, next) = (self.pred(i), self.succ(i));
        let tp = self.p[i] - self.p[prev];
        let ts = self.p[i] - self.p[next];
        let mut f = self.dir_c;
        let flush_inside = if Self::in_cone(f, tp, ts) {
            true
        } else if Self::in_cone(-f, tp, ts) {
            f = -f;
            true
        } else {
            false
        };
        let above_or_below = |j: usize| {
            if self.h(j) > self.h(i) {
                Crossing::Above
            } else {
                Crossing::Below
            }
        };
        if flush_inside {
            if Self::in_cone(g, tp, f) || Self::same_direction(g, tp) {
                above_or_below(prev)
            } else if Self::in_cone(g, ts, f) || Self::same_direction(g, ts) {
                above_or_below(next)
            } else {
                Crossing::Critical
            }
        } else if Self::in_cone(g, tp, ts)
            || (Self::same_direction(g, tp) && !Self::same_direction(g, f))
            || (Self::same_direction(g, ts) && !Self::same_direction(g, f))
        {
            Crossing::Below
        } else {
            Crossing::Critical
        }
    }

    /// Whether the line through `g` and vertex i enters the polygon below vertex i, on the
    /// far side of vertex i from `g`.
    fn intersects_below(&self, g: Point2<f64>, i: usize) -> bool {
        self.classify(g - self.p[i], i) == Crossing::Below
    }

    /// Whether the line from `g` through vertex i enters the polygon above vertex i, between
    /// `g` and vertex i.
    fn intersects_above(&self, g: Point2<f64>, i: usize) -> bool {
        self.classify(self.p[i] - g, i) == Crossing::Above
    }
}

/// x ≥ y up to the tolerance.
fn ge(x: f64, y: f64) -> bool {
    x >= y - TOL * (1.0f64).max(x.abs()).max(y.abs())
}

/// |x − y| within the tolerance.
fn almost_equal(x: f64, y: f64) -> bool {
    (x - y).abs() <= TOL * (1.0f64).max(x.abs()).max(y.abs())
}

/// Whether `x` lies on the segment from `s` to `e` (up to the tolerance).
fn on_segment(x: Point2<f64>, s: Point2<f64>, e: Point2<f64>) -> bool {
    let len = (e - s).norm();
    (x - s).norm() + (x - e).norm() <= len + TOL * (1.0 + len)
}

/// Whether two points coincide up to the tolerance.
fn same_point(a: Point2<f64>, b: Point2<f64>) -> bool {
    (a - b).norm() <= TOL
}

/// A candidate triangle: its area (normalised units) and vertices.
type Candidate = (f64, [Point2<f64>; 3]);

/// The candidate of flush edge c with sides found at a and b, if it is valid (every side's
/// midpoint on the polygon as its kind requires).
fn candidate(
    st: &State<'_>,
    a: usize,
    b: usize,
    side_a: Line,
    side_b: Line,
    kind: Kind,
) -> Option<Candidate> {
    let p = st.p;
    let side_c = Line::new(p[st.pred(st.c)], p[st.c]);
    let apex = side_a.meet(&side_b)?; // vertex C, opposite side C
    let on_c_from_a = side_a.meet(&side_c)?; // vertex B
    let on_c_from_b = side_b.meet(&side_c)?; // vertex A
    let mid = |x: Point2<f64>, y: Point2<f64>| Point2::from((x.coords + y.coords) * 0.5);
    let (ma, mb, mc) = (
        mid(on_c_from_a, apex),
        mid(on_c_from_b, apex),
        mid(on_c_from_b, on_c_from_a),
    );
    let valid_a = match kind {
        Kind::SideATangent => same_point(ma, p[st.pred(a)]),
        _ => on_segment(ma, p[st.pred(a)], p[a]),
    };
    let valid_b = match kind {
        Kind::SideBTangent => same_point(mb, p[b]),
        _ => on_segment(mb, p[st.pred(b)], p[b]),
    };
    // As in OpenCV (issue 4992), side C's midpoint is not required when both other sides
    // are flush: this only adds candidates, and the smallest enclosing one is chosen.
    let valid_c = kind == Kind::SidesFlush || on_segment(mc, p[st.pred(st.c)], p[st.c]);
    if !(valid_a && valid_b && valid_c) {
        return None;
    }
    let area = 0.5 * cross(on_c_from_a - on_c_from_b, apex - on_c_from_b).abs();
    Some((area, [on_c_from_b, on_c_from_a, apex]))
}

/// The candidates of O'Rourke's rotation over all flush edges (polygon counter-clockwise,
/// strictly convex, normalised, n ≥ 4), or `None` if the rotation did not finish within
/// its bound.
fn rotate(p: &[Point2<f64>]) -> Option<Vec<Candidate>> {
    let n = p.len();
    let mut st = State {
        p,
        n,
        c: 0,
        dir_c: Vector2::zeros(),
    };
    let (mut a, mut b) = (1usize, 2usize);
    let mut steps = 0usize;
    let budget = 20 * n + 20;
    let mut out = Vec::with_capacity(n);
    for c in 0..n {
        st.c = c;
        st.dir_c = (p[c] - p[st.pred(c)]).normalize();
        // (a) b to a local maximum of height.
        while ge(st.h(st.succ(b)), st.h(b)) {
            b = st.succ(b);
            steps += 1;
            if steps > budget {
                return None;
            }
        }
        // (b) a up while it is low, b up while it is high.
        while st.h(b) > st.h(a) && !almost_equal(st.h(b), st.h(a)) {
            match st.gamma(a, a) {
                Some(g) if st.intersects_below(g, b) => b = st.succ(b),
                _ => a = st.succ(a),
            }
            steps += 1;
            if steps > budget {
                return None;
            }
        }
        // (c) b along while the side through γ(b) and b still cuts the polygon below b.
        loop {
            let go = st.gamma(b, a).is_some_and(|g| st.intersects_below(g, b))
                && ge(st.h(b), st.h(st.pred(a)));
            if !go {
                break;
            }
            b = st.succ(b);
            steps += 1;
            if steps > budget {
                return None;
            }
        }
        // (d) sides C and A; (e) whether B is tangent at b.
        let side_a = Line::new(p[st.pred(a)], p[a]);
        let gb = st.gamma(b, a);
        let low = st.h(b) < st.h(st.pred(a)) && !almost_equal(st.h(b), st.h(st.pred(a)));
        let not_tangent = gb.is_some_and(|g| st.intersects_above(g, b)) || low;
        let found = if not_tangent {
            let side_b = Line::new(p[st.pred(b)], p[b]);
            let side_c = Line::new(p[st.pred(c)], p[c]);
            let mid_b = match (side_b.meet(&side_c), side_b.meet(&side_a)) {
                (Some(x), Some(y)) => Some(Point2::from((x.coords + y.coords) * 0.5)),
                _ => None,
            };
            let a_tangent = mid_b.is_some_and(|m| st.height_of(m) < st.h(st.pred(a)));
            if a_tangent {
                // A through vertex a − 1 and the point of B at twice its height.
                st.at_height(&side_b, 2.0 * st.h(st.pred(a)))
                    .filter(|&v| !same_point(v, p[st.pred(a)]))
                    .and_then(|v| {
                        let side_a = Line::new(p[st.pred(a)], v);
                        candidate(&st, a, b, side_a, side_b, Kind::SideATangent)
                    })
            } else {
                candidate(&st, a, b, side_a, side_b, Kind::SidesFlush)
            }
        } else {
            gb.filter(|&g| !same_point(g, p[b]))
                .and_then(|g| candidate(&st, a, b, side_a, Line::new(g, p[b]), Kind::SideBTangent))
        };
        out.extend(found);
    }
    Some(out)
}

/// The minimal-area triangle enclosing the convex polygon `hull` (counter-clockwise, no
/// collinear vertices, at least four), in linear time; `None` if no candidate of the
/// rotation encloses the polygon (the caller then uses the exact quadratic search).
pub(super) fn min_enclosing_triangle_linear(hull: &[Point2<f64>]) -> Option<Triangle2> {
    // Normalise to unit size around the bounding box's centre, so that the tolerances are
    // relative; drop vertices that coincide after it.
    let (lo, hi) = hull
        .iter()
        .fold((hull[0], hull[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let size = (hi - lo).amax();
    if !(size > 0.0 && size.is_finite()) {
        return None;
    }
    let centre = Point2::from((lo.coords + hi.coords) * 0.5);
    let mut p: Vec<Point2<f64>> = Vec::with_capacity(hull.len());
    for q in hull {
        let x = Point2::from((q - centre) / size);
        if p.last().is_none_or(|&l| !same_point(l, x)) {
            p.push(x);
        }
    }
    while p.len() > 1 && same_point(p[0], p[p.len() - 1]) {
        p.pop();
    }
    if p.len() < 4 {
        return None;
    }
    let mut candidates = rotate(&p)?;
    candidates.sort_by(|x, y| x.0.total_cmp(&y.0));
    // Containment is checked on the normalised polygon (its coordinates are exact
    // differences); mapping back rounds each vertex to the input's coordinates.
    let back = |x: Point2<f64>| centre + x.coords * size;
    candidates.into_iter().find_map(|(_, v)| {
        let t = Triangle2::new(v[0], v[1], v[2]);
        let encloses = p.iter().all(|&q| t.bary(q).iter().all(|&x| x >= -TOL));
        let (a, b, c) = (back(v[0]), back(v[1]), back(v[2]));
        let ccw = cross(v[1] - v[0], v[2] - v[0]) > 0.0;
        encloses.then(|| {
            if ccw {
                Triangle2::new(a, b, c)
            } else {
                Triangle2::new(a, c, b)
            }
        })
    })
}
