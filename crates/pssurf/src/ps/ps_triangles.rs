//! PS-points and PS-triangles (Definitions 2.19–2.21).

use nalgebra::Point2;
use rayon::prelude::*;

use super::PsError;
use super::refinement::PsRefinement;
use crate::geometry::{Triangle2, convex_hull, midpoint, min_enclosing_triangle};
use crate::triangulation::Triangulation;

/// How far (in barycentric coordinates) a PS-point may lie outside a *given* PS-triangle:
/// triangles computed in closed form (UPS) or read from a file have PS-points on their edges
/// up to rounding. Triangles built here contain their PS-points exactly, so they pass too.
pub const CONTAINMENT_TOLERANCE: f64 = 1e-9;

/// The margins (relative to its size) by which an optimal PS-triangle is enlarged about its
/// centroid so that it contains its PS-points exactly: the first that works is used. The
/// minimal triangle has sides flush with PS-points, which rounding puts on either side of
/// the line, so even the first margin is always applied: 1e-13 (or 512 ulps of the
/// coordinates relative to the size, when that is more: see `rounding_margin`) is ~500
/// times the rounding error of the construction, changes the triangle invisibly, and lets
/// the exact test decide in its fast stage (measured: 177 → 213 ms for 100k vertices, against 258 ms when the
/// unenlarged triangle was tried first). The larger margins only matter for nearly
/// coincident PS-points.
pub const ENLARGEMENT_MARGINS: [f64; 6] = [1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3];

/// How the PS-triangles t_i are chosen.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum PsTriangleChoice {
    /// Dierckx's optimal triangles: of minimal area among those containing the PS-points, so
    /// that the control triangles lie close to the surface.
    #[default]
    Optimal,
    /// The equilateral triangle around a circle enclosing the PS-points (the optimal one
    /// where that one is not valid in floating point): valid, found in time linear in the
    /// PS-points (about a tenth of the optimal one's), but several times larger. The spline
    /// of given Hermite data does not depend on the PS-triangles (only its B-spline
    /// coefficients do), so this is the choice for Hermite splines made to be evaluated;
    /// build them again on optimal triangles from the same data before showing or saving
    /// control points.
    Circumscribed,
    /// Given triangles, one per vertex, each validated to contain the vertex's PS-points.
    Given(Vec<Triangle2>),
}

/// The PS-points of vertex V_i (Definition 2.19): V_i itself and, on every edge of Δ* at V_i,
/// the Bézier domain point nearest V_i — the midpoints of V_i R for the edge points R of V_i's
/// edges and of V_i Z for the interior points Z of its molecule. Each point is listed once.
pub fn ps_points(tri: &Triangulation, refinement: &PsRefinement, i: usize) -> Vec<Point2<f64>> {
    let mut pts = Vec::with_capacity(1 + 2 * tri.molecule_number(i) + 1);
    ps_points_into(tri, refinement, i, &mut pts);
    pts
}

/// As [`ps_points`], into a reusable buffer (cleared first).
pub fn ps_points_into(
    tri: &Triangulation,
    refinement: &PsRefinement,
    i: usize,
    pts: &mut Vec<Point2<f64>>,
) {
    pts.clear();
    let vi = tri.vertex(i);
    pts.push(vi);
    for &t in tri.molecule(i) {
        let t = t as usize;
        let c = tri
            .corner_of(t, i)
            .expect("molecule triangle has the vertex");
        // The edge to the next vertex; the edge from the previous vertex is some other
        // molecule triangle's next edge, unless it lies on the boundary.
        pts.push(midpoint(vi, refinement.edge_point(tri, t, c)));
        pts.push(midpoint(vi, refinement.z(t)));
        if tri.is_boundary_edge(t, super::refinement::edge_to_local((c + 2) % 3)) {
            pts.push(midpoint(vi, refinement.edge_point(tri, t, (c + 2) % 3)));
        }
    }
}

/// The PS-triangles of all vertices.
pub fn ps_triangles(
    tri: &Triangulation,
    refinement: &PsRefinement,
    choice: &PsTriangleChoice,
) -> Result<Vec<Triangle2>, PsError> {
    match choice {
        PsTriangleChoice::Optimal | PsTriangleChoice::Circumscribed => {
            let find = if *choice == PsTriangleChoice::Circumscribed {
                circumscribed_ps_triangle
            } else {
                optimal_ps_triangle
            };
            // In spatial order (neighbouring vertices share triangles, so caches stay warm),
            // then scattered back to vertex order.
            let order = tri.spatial_order();
            let found: Vec<Result<Triangle2, PsError>> = order
                .par_iter()
                .with_min_len(256)
                .map_init(
                    || Vec::with_capacity(32),
                    |pts, &i| {
                        let i = i as usize;
                        ps_points_into(tri, refinement, i, pts);
                        find(i, pts)
                    },
                )
                .collect();
            let mut out = vec![
                Triangle2::new(Point2::origin(), Point2::origin(), Point2::origin());
                order.len()
            ];
            for (&i, t) in order.iter().zip(found) {
                out[i as usize] = t?;
            }
            Ok(out)
        }
        PsTriangleChoice::Given(given) => {
            if given.len() != tri.vertex_count() {
                return Err(PsError::WrongCount {
                    what: "PS-triangles",
                    expected: tri.vertex_count(),
                    found: given.len(),
                });
            }
            given
                .iter()
                .enumerate()
                .map(|(i, t)| validate_ps_triangle(tri, refinement, i, t))
                .collect()
        }
    }
}

/// Dierckx's optimal PS-triangle of vertex `i` with PS-points `pts`, made safe to store: the
/// minimal enclosing triangle enlarged by the first margin that makes it contain every
/// PS-point exactly — the rounding margin (`rounding_margin`, at least 1e-13), then the
/// larger [`ENLARGEMENT_MARGINS`] — so a surface built here always loads again (exact
/// containment implies the load check with [`CONTAINMENT_TOLERANCE`]). When no margin is
/// enough (nearly coincident or nearly collinear PS-points, where the optimum is numerically
/// meaningless) the triangle circumscribing the points' bounding circle is used.
pub fn optimal_ps_triangle(i: usize, pts: &[Point2<f64>]) -> Result<Triangle2, PsError> {
    if let Some(t) = min_enclosing_triangle(pts) {
        let first = ENLARGEMENT_MARGINS[0].max(rounding_margin(&t, pts));
        let larger = ENLARGEMENT_MARGINS.into_iter().filter(|&m| m > first);
        for margin in std::iter::once(first).chain(larger) {
            if let Ok(t) = check_ps_triangle(i, &t.enlarged(margin), pts, Containment::Exact) {
                return Ok(canonical_corners(t));
            }
        }
    }
    circumscribing_triangle(pts)
        .and_then(|t| check_ps_triangle(i, &t, pts, Containment::Exact).ok())
        .map(canonical_corners)
        .ok_or(PsError::DegeneratePsTriangle { vertex: i })
}

/// The counter-clockwise triangle `t` with its corners rotated to start at the one farthest
/// along
/// [`FIRST_CORNER_DIRECTION`](crate::geometry::FIRST_CORNER_DIRECTION) from its centroid. Control values refer to PS-triangle
/// corners by position (`control[i][j]` to corner j), so a computed triangle must list its
/// corners in an order that does not depend on how the search came to them (it followed the
/// scale of the coordinates, and a file without PS-triangles meant another surface when its
/// domain was only rescaled). The rule does not change under translation and scaling, and
/// two corners tie only when they lie symmetrically about that direction, which grids and
/// axis-aligned or symmetric shapes (where a lowest-left rule ties) do not.
fn canonical_corners(t: Triangle2) -> Triangle2 {
    let c = (t.v[0].coords + t.v[1].coords + t.v[2].coords) / 3.0;
    let (dx, dy) = crate::geometry::FIRST_CORNER_DIRECTION;
    let along = |k: usize| (t.v[k].x - c.x) * dx + (t.v[k].y - c.y) * dy;
    let first = (0..3)
        .max_by(|&a, &b| along(a).total_cmp(&along(b)))
        .unwrap_or(0);
    Triangle2::new(t.v[first], t.v[(first + 1) % 3], t.v[(first + 2) % 3])
}

/// The triangle of [`PsTriangleChoice::Circumscribed`] for vertex `i` with PS-points `pts`:
/// the [`circumscribing_triangle`] when it contains them exactly, else the optimal one.
fn circumscribed_ps_triangle(i: usize, pts: &[Point2<f64>]) -> Result<Triangle2, PsError> {
    match circumscribing_triangle(pts).map(|t| check_ps_triangle(i, &t, pts, Containment::Exact)) {
        Some(Ok(t)) => Ok(t),
        _ => optimal_ps_triangle(i, pts),
    }
}

/// The smallest margin that outgrows the construction's rounding: 512 ulps of the largest
/// coordinate, relative to the triangle's size (≈ 1e-13 for a triangle at the origin; far
/// from the origin a relative 1e-13 can be less than an ulp of the coordinates).
fn rounding_margin(t: &Triangle2, pts: &[Point2<f64>]) -> f64 {
    let magnitude = pts
        .iter()
        .chain(&t.v)
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(0.0, f64::max);
    512.0 * f64::EPSILON * magnitude / t.diameter()
}

/// The equilateral triangle circumscribing a circle around `pts` (centre: the middle of
/// their bounding box; radius: slightly more than the farthest point's distance), or
/// `None` when the points coincide.
fn circumscribing_triangle(pts: &[Point2<f64>]) -> Option<Triangle2> {
    let lo = pts
        .iter()
        .fold(pts.first()?.coords, |a, p| a.inf(&p.coords));
    let hi = pts.iter().fold(lo, |a, p| a.sup(&p.coords));
    let centre = Point2::from((lo + hi) / 2.0);
    let r = pts.iter().map(|p| (p - centre).norm()).fold(0.0, f64::max);
    if !(r > 0.0 && r.is_finite()) {
        return None;
    }
    // The incircle of an equilateral triangle with circumradius 2R has radius R.
    let big = 2.0 * r * (1.0 + 1e-6);
    let corner = |deg: f64| {
        let a = deg.to_radians();
        centre + nalgebra::Vector2::new(a.cos(), a.sin()) * big
    };
    Some(Triangle2::new(corner(90.0), corner(210.0), corner(330.0)))
}

/// How a PS-triangle must contain the PS-points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Containment {
    /// Exactly (adaptive-precision orientation tests).
    Exact,
    /// Up to [`CONTAINMENT_TOLERANCE`] in barycentric coordinates.
    Tolerant,
}

/// Checks that a given `t` is a proper PS-triangle of vertex `i` and returns it
/// counter-clockwise: finite, not degenerate, and containing every PS-point of the vertex up
/// to [`CONTAINMENT_TOLERANCE`].
pub fn validate_ps_triangle(
    tri: &Triangulation,
    refinement: &PsRefinement,
    i: usize,
    t: &Triangle2,
) -> Result<Triangle2, PsError> {
    check_ps_triangle(i, t, &ps_points(tri, refinement, i), Containment::Tolerant)
}

/// As [`validate_ps_triangle`] with the PS-points given and the containment rule chosen.
fn check_ps_triangle(
    i: usize,
    t: &Triangle2,
    pts: &[Point2<f64>],
    rule: Containment,
) -> Result<Triangle2, PsError> {
    if t.v
        .iter()
        .any(|p| !(crate::limits::value_ok(p.x) && crate::limits::value_ok(p.y)))
    {
        return Err(PsError::PsTriangleOutOfRange { vertex: i });
    }
    if t.is_degenerate() {
        return Err(PsError::DegeneratePsTriangle { vertex: i });
    }
    let t = if crate::geometry::orient_exact(t.v[0], t.v[1], t.v[2]) < 0.0 {
        Triangle2::new(t.v[0], t.v[2], t.v[1])
    } else {
        *t
    };
    let inside = |p: Point2<f64>| match rule {
        Containment::Exact => t.contains_exact(p),
        Containment::Tolerant => t.bary(p).iter().all(|&x| x >= -CONTAINMENT_TOLERANCE),
    };
    match pts.iter().find(|&&p| !inside(p)) {
        Some(p) => Err(PsError::PsPointOutside {
            vertex: i,
            point: [p.x, p.y],
        }),
        None => Ok(t),
    }
}

/// How good a PS-triangle is: its area relative to the convex hull of the PS-points (≥ 1; the
/// optimal triangle minimises it) and its smallest angle in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PsTriangleQuality {
    /// Area of t_i over the area of the hull of the PS-points.
    pub area_ratio: f64,
    /// The smallest interior angle of t_i, in degrees.
    pub min_angle_deg: f64,
}

/// The quality measures of the PS-triangle `t` of vertex `i`.
pub fn quality(
    tri: &Triangulation,
    refinement: &PsRefinement,
    i: usize,
    t: &Triangle2,
) -> PsTriangleQuality {
    quality_for(&ps_points(tri, refinement, i), t)
}

/// The quality of PS-triangle `t` for these PS-points (see [`quality`]).
pub fn quality_for(ps_points: &[Point2<f64>], t: &Triangle2) -> PsTriangleQuality {
    let hull = convex_hull(ps_points);
    let hull_area: f64 = (1..hull.len().saturating_sub(1))
        .map(|k| Triangle2::new(hull[0], hull[k], hull[k + 1]).area())
        .sum();
    let angle = |a: Point2<f64>, b: Point2<f64>, c: Point2<f64>| {
        let (u, v) = (b - a, c - a);
        (u.dot(&v) / (u.norm() * v.norm()))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let [a, b, c] = t.v;
    PsTriangleQuality {
        area_ratio: t.area() / hull_area,
        min_angle_deg: angle(a, b, c).min(angle(b, c, a)).min(angle(c, a, b)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{rng, uniform};

    /// The computed PS-triangles of a domain moved and scaled are the same triangles moved and
    /// scaled, corner for corner (control values refer to corners by position). On the unit
    /// square split in two, the corners of vertex 0's triangle came out rotated at scale 7
    /// against scale 1, and the same control values gave z = 1.025 instead of 1.05 at the
    /// centre. Grids (ties for a lowest-left rule) and random Delaunay sets, at scales from
    /// 1e-38 to 1e30.
    #[test]
    fn computed_ps_triangles_list_their_corners_whatever_the_scale() {
        let mut r = rng(51);
        let grid: Vec<Point2<f64>> = (0..36)
            .map(|k| Point2::new((k % 6) as f64, (k / 6) as f64))
            .collect();
        let square = vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ];
        for (case, pts) in [("square", square), ("grid", grid)]
            .into_iter()
            .chain((0..4).map(|k| {
                let pts = (0..30)
                    .map(|_| Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0)))
                    .collect();
                (["random 0", "random 1", "random 2", "random 3"][k], pts)
            }))
        {
            // One triangulation, moved and scaled (Delaunay's choice between co-circular
            // points on a grid may change with the scale).
            let triangles: Vec<[usize; 3]> = Triangulation::delaunay(pts.clone())
                .unwrap()
                .triangles()
                .iter()
                .map(|t| t.map(|v| v as usize))
                .collect();
            let basis = |scale: f64, shift: f64| {
                let moved: Vec<Point2<f64>> = pts
                    .iter()
                    .map(|p| Point2::new(p.x * scale + shift, p.y * scale - shift))
                    .collect();
                let tri = Triangulation::try_new(moved, triangles.clone()).unwrap();
                crate::ps::PsBasis::optimal(tri).unwrap()
            };
            let reference = basis(1.0, 0.0);
            for (scale, shift) in [
                (3.0, 0.0),
                (7.0, 0.0),
                (0.1, 0.0),
                (1e30, 0.0),
                (1e-38, 0.0),
                (1.0, 0.37),
            ] {
                let other = basis(scale, shift * scale);
                for i in 0..pts.len() {
                    let (a, b) = (reference.ps_triangle(i), other.ps_triangle(i));
                    for k in 0..3 {
                        let back = Point2::new(
                            (b.v[k].x - shift * scale) / scale,
                            (b.v[k].y + shift * scale) / scale,
                        );
                        assert!(
                            (back - a.v[k]).norm() <= 1e-9 * a.diameter(),
                            "{case}, scale {scale}, shift {shift}: vertex {i} corner {k}: {back} against {}; {:?} (area {}) against {:?} (area {})",
                            a.v[k],
                            b.v,
                            b.area() / scale / scale,
                            a.v,
                            a.area()
                        );
                    }
                }
            }
        }
    }

    /// Random point sets (a quarter squashed to nearly collinear, offsets up to 1e12 times
    /// the spread): the stored triangle contains every point exactly; every well-scaled set
    /// gets the minimal triangle up to the first margin (measured: 3049 of 4000 sets); the
    /// squashed or far-offset ones may need the circumscribing triangle (measured: 364).
    #[test]
    fn optimal_ps_triangles_contain_their_points_exactly_and_stay_minimal() {
        let mut r = rng(41);
        // `enlarged` counts the well-scaled sets (not squashed, offset at most 1e3 × the
        // spread) that needed more than the first margin.
        let (mut minimal, mut enlarged, mut fallback, mut refused) = (0, 0, 0, 0);
        for case in 0..4000 {
            let n = 3 + case % 12;
            let scale = 10f64.powf(uniform(&mut r, -6.0, 6.0));
            let offset = 10f64.powf(uniform(&mut r, -3.0, 6.0));
            let squash = if case % 4 == 0 { 1e-9 } else { 1.0 };
            let pts: Vec<Point2<f64>> = (0..n)
                .map(|_| {
                    Point2::new(
                        offset + scale * uniform(&mut r, -1.0, 1.0),
                        offset + squash * scale * uniform(&mut r, -1.0, 1.0),
                    )
                })
                .collect();
            let Ok(t) = optimal_ps_triangle(0, &pts) else {
                // Only when the rounded points coincide (no triangle can be built).
                assert!(pts.iter().all(|p| *p == pts[0]), "case {case}");
                refused += 1;
                continue;
            };
            assert!(pts.iter().all(|&p| t.contains_exact(p)), "case {case}");
            let Some(best) = min_enclosing_triangle(&pts) else {
                // Rounded onto one line: the circumscribing triangle.
                fallback += 1;
                continue;
            };
            // Sets that are not squashed mostly need only the first margin (at least 1e-13,
            // and 512 ulps of the coordinates relative to the size); near-parallel sides put
            // a vertex far away and may need the next one. Squashed sets may need more.
            let first = ENLARGEMENT_MARGINS[0].max(rounding_margin(&best, &pts));
            if t.area() > best.area() * 1.0021 {
                // No margin was enough: the circumscribing triangle.
                fallback += 1;
            } else if t.area() <= best.area() * (1.0 + 3.0 * first) {
                minimal += 1;
            } else if squash == 1.0 && offset <= 1e3 * scale {
                enlarged += 1;
            }
        }
        let counts = format!(
            "{minimal} minimal, {enlarged} enlarged, {fallback} fallback, {refused} refused"
        );
        assert!(
            minimal >= 3000 && enlarged == 0 && refused + fallback <= 450,
            "{counts}"
        );
    }
}
