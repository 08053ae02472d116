//! Level lines against closed forms: ellipses of constant K on graphs of quadratics, circles
//! of constant height, the straight parabolic line of z = x³/6 + y²/2, plane sections;
//! joining across pieces, gaps where curvature jumps, bounded work on wild surfaces.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::tests::wavy_surface;
use super::*;
use crate::geometry::Triangle2;
use crate::ps::{Hermite, PsBasis, PsSpline};
use crate::surface::Surface;
use crate::test_util::*;
use crate::triangulation::Triangulation;

/// The graph of z = (a x² + b y²)/2 as a PS-spline on a random Delaunay mesh of [-1, 1]²
/// (reproduced exactly, so K and H are the same quadratic's on every piece).
pub(super) fn elliptic_paraboloid(a: f64, b: f64, seed: u64) -> Surface {
    ps_graph_on_square(seed, 40, |p| Hermite {
        value: 0.5 * (a * p.x * p.x + b * p.y * p.y),
        dx: a * p.x,
        dy: b * p.y,
    })
}

/// The PS-spline interpolating `f` (value and gradient) on the corners of [-1, 1]² and `n`
/// random points in it (Delaunay).
pub(super) fn ps_graph_on_square(
    seed: u64,
    n: usize,
    f: impl Fn(Point2<f64>) -> Hermite<f64>,
) -> Surface {
    let mut r = rng(seed);
    let mut pts = vec![
        Point2::new(-1.0, -1.0),
        Point2::new(1.0, -1.0),
        Point2::new(1.0, 1.0),
        Point2::new(-1.0, 1.0),
    ];
    pts.extend((0..n).map(|_| Point2::new(uniform(&mut r, -1.0, 1.0), uniform(&mut r, -1.0, 1.0))));
    let basis = Arc::new(PsBasis::optimal(Triangulation::delaunay(pts).unwrap()).unwrap());
    Surface::Functional(PsSpline::interpolate(basis, f).unwrap())
}

/// K and H of z = (a x² + b y²)/2 by the classical graph formulas.
fn k_and_h(a: f64, b: f64, p: Point2<f64>) -> (f64, f64) {
    let (fx, fy) = (a * p.x, b * p.y);
    let w2 = 1.0 + fx * fx + fy * fy;
    let k = a * b / (w2 * w2);
    let h = ((1.0 + fy * fy) * a + (1.0 + fx * fx) * b) / (2.0 * w2 * w2.sqrt());
    (k, h)
}

fn on_boundary_of_square(p: Point2<f64>) -> bool {
    (p.x.abs() - 1.0).abs() < 1e-12 || (p.y.abs() - 1.0).abs() < 1e-12
}

#[test]
fn level_lines_of_k_on_a_paraboloid_are_closed_ellipses_joined_across_pieces() {
    let opts = ZeroSetOptions::default();
    let mut r = rng(60);
    for seed in 0..6 {
        let (a, b) = (uniform(&mut r, 0.3, 2.0), uniform(&mut r, 0.3, 2.0));
        let s = elliptic_paraboloid(a, b, seed);
        let field = SurfaceField::Curvature(CurvatureQuantity::Gaussian);
        // Levels whose ellipse a²x² + b²y² = √(ab/c) − 1 lies inside the square.
        let c_of = |r2: f64| a * b / ((1.0 + r2) * (1.0 + r2));
        let m = (a * a).min(b * b);
        let levels = [c_of(0.2 * m), c_of(0.5 * m), c_of(0.8 * m)];
        let sets = level_lines(&s, &field, &levels, &opts).unwrap();
        for set in &sets {
            assert_eq!(set.curves.len(), 1, "one ellipse at {}", set.level);
            assert!(
                set.gaps.is_empty(),
                "K is the same on every piece: {:?}",
                set.gaps
            );
            let c = &set.curves[0];
            assert!(c.closed && c.uvs.len() > 20);
            let r2 = (a * b / set.level).sqrt() - 1.0;
            for (uv, p) in c.uvs.iter().zip(&c.points) {
                let on_ellipse = a * a * uv.x * uv.x + b * b * uv.y * uv.y;
                assert!(
                    (on_ellipse - r2).abs() < 1e-9 * (1.0 + r2),
                    "{on_ellipse} vs {r2}"
                );
                // The closed form, within the corrector's tolerance plus the spline's
                // representation error of K (neighbouring pieces differ by rounding).
                let (k, _) = k_and_h(a, b, *uv);
                assert!(
                    (k - set.level).abs() <= set.tolerance + 1e-10 * set.level,
                    "{k} {}",
                    set.level
                );
                assert!(
                    (p - Vector3::new(uv.x, uv.y, 0.5 * (a * uv.x * uv.x + b * uv.y * uv.y)))
                        .norm()
                        < 1e-14
                );
            }
        }
    }
}

#[test]
fn level_lines_of_h_satisfy_the_closed_form_and_a_missing_level_gives_nothing() {
    let (a, b) = (1.2, -0.6);
    let s = elliptic_paraboloid(a, b, 7);
    let field = SurfaceField::Curvature(CurvatureQuantity::Mean);
    let levels = auto_levels(&s, &field, 6);
    assert_eq!(levels.len(), 6);
    let sets = level_lines(&s, &field, &levels, &ZeroSetOptions::default()).unwrap();
    let mut points = 0;
    for set in &sets {
        assert!(!set.curves.is_empty(), "level {}", set.level);
        assert!(set.gaps.is_empty());
        for c in &set.curves {
            // Open curves end on the domain's boundary.
            if !c.closed {
                assert!(
                    on_boundary_of_square(c.uvs[0])
                        && on_boundary_of_square(*c.uvs.last().unwrap())
                );
            }
            for uv in &c.uvs {
                let (_, h) = k_and_h(a, b, *uv);
                assert!((h - set.level).abs() <= set.tolerance + 1e-10 * set.level.abs());
                points += 1;
            }
        }
    }
    assert!(points > 100);
    // K = ab/W² < 0 everywhere: a positive level does not occur.
    let k = SurfaceField::Curvature(CurvatureQuantity::Gaussian);
    let none = level_lines(&s, &k, &[0.5], &ZeroSetOptions::default()).unwrap();
    assert!(none[0].curves.is_empty() && none[0].gaps.is_empty());
}

#[test]
fn height_contours_are_circles_and_walks_stay_within_their_tolerance() {
    let s = elliptic_paraboloid(1.0, 1.0, 11);
    for method in [
        TraceMethod::PredictorCorrector,
        TraceMethod::FourPoint,
        TraceMethod::EightPoint,
    ] {
        let opts = ZeroSetOptions {
            method,
            ..Default::default()
        };
        let set = &level_lines(&s, &SurfaceField::Height, &[0.125], &opts).unwrap()[0];
        if method == TraceMethod::PredictorCorrector {
            assert_eq!(set.curves.len(), 1);
            assert!(set.curves[0].closed && set.gaps.is_empty());
            // The circle of radius 1/2 has length π.
            assert!((set.curves[0].length() - std::f64::consts::PI).abs() < 1e-2);
        }
        // The walks only promise points within their tolerance (they can stop where the
        // curve runs at a shallow angle to their step directions, see `TraceMethod`).
        assert!(!set.curves.is_empty());
        let tol = match method {
            TraceMethod::PredictorCorrector => set.tolerance,
            _ => opts.walk_tolerance * set.tolerance / opts.tolerance,
        };
        for uv in set.curves.iter().flat_map(|c| &c.uvs) {
            let z = 0.5 * uv.coords.norm_squared();
            assert!((z - 0.125).abs() <= tol * (1.0 + 1e-9), "{method:?} {z}");
        }
    }
}

#[test]
fn height_contours_of_a_wavy_surface_join_without_gaps() {
    // The height is continuous across pieces, so every end meets its continuation.
    let s = wavy_surface(21);
    let levels: Vec<f64> = (-1..=4).map(|k| 0.2 * k as f64).collect();
    let sets = level_lines(
        &s,
        &SurfaceField::Height,
        &levels,
        &ZeroSetOptions::default(),
    )
    .unwrap();
    let domain = s.domain();
    for set in &sets {
        assert!(
            set.gaps.is_empty(),
            "level {}: {:?} stuck {}",
            set.level,
            set.gaps,
            set.stuck
        );
        assert!(!set.curves.is_empty());
        for c in set.curves.iter().filter(|c| !c.closed) {
            for end in [c.uvs[0], *c.uvs.last().unwrap()] {
                assert!(domain.distance_to_boundary(end) < 1e-9, "{end:?}");
            }
        }
    }
}

#[test]
fn curvature_level_lines_end_in_reported_gaps_where_curvature_jumps() {
    let s = wavy_surface(22);
    let field = SurfaceField::Curvature(CurvatureQuantity::Mean);
    let levels = auto_levels(&s, &field, 5);
    let sets = level_lines(&s, &field, &levels, &ZeroSetOptions::default()).unwrap();
    let domain = s.domain();
    let mut gaps = 0;
    for set in &sets {
        // Every open end is on the domain's boundary or a reported gap.
        for c in set.curves.iter().filter(|c| !c.closed) {
            for end in [c.uvs[0], *c.uvs.last().unwrap()] {
                let reported = set.gaps.iter().any(|g| g.uv == end);
                assert!(
                    reported || domain.distance_to_boundary(end) < 1e-9,
                    "{end:?}"
                );
            }
        }
        for g in &set.gaps {
            // On the other side the field has another value (else the line would go on).
            assert!(!((g.across - set.level).abs() <= set.tolerance), "{g:?}");
        }
        gaps += set.gaps.len();
    }
    assert!(
        gaps > 0,
        "H of a C¹ PS surface jumps across the refinement lines"
    );
}

#[test]
fn the_parabolic_line_of_a_cubic_is_straight_and_splits_the_area_evenly() {
    // z = x³/6 + y²/2: K = x / W², zero on x = 0, elliptic for x > 0.
    let t = Triangle2::new(
        Point2::new(-1.0, -1.0),
        Point2::new(1.0, -1.0),
        Point2::new(0.0, 1.0),
    );
    let s = Surface::Bezier(interpolating_bezier(t, 3, |p| {
        Vector3::new(p.x, p.y, p.x.powi(3) / 6.0 + 0.5 * p.y * p.y)
    }));
    let (set, regions) = parabolic_lines(&s, &ZeroSetOptions::default()).unwrap();
    assert_eq!(set.curves.len(), 1);
    let c = &set.curves[0];
    // |K| ≤ tolerance with W² ≤ 4 on the triangle.
    assert!(
        c.uvs.iter().all(|p| p.x.abs() <= 4.0 * set.tolerance),
        "{:?}",
        c.uvs
    );
    let ys: Vec<f64> = c.uvs.iter().map(|p| p.y).collect();
    let (lo, hi) = ys
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &y| (a.min(y), b.max(y)));
    assert!(
        (lo + 1.0).abs() < 1e-12 && (hi - 1.0).abs() < 1e-12,
        "{lo} {hi}"
    );
    // The area element √(1 + x⁴/4 + y²) is even in x and the triangle symmetric.
    // The areas are a quadrature estimate of a discontinuous integrand (the sign of K).
    assert!(regions.elliptic > 0.5);
    assert!(
        (regions.elliptic - regions.hyperbolic).abs() < 0.05 * regions.elliptic,
        "{regions:?}"
    );
}

#[test]
fn plane_sections_are_zero_sets_too() {
    let s = elliptic_paraboloid(1.0, 1.0, 31);
    let f = PlaneDistance {
        surface: &s,
        origin: Vector3::new(0.0, 0.2, 0.0),
        normal: Vector3::y(),
    };
    let set = trace_zero_set(&s, &f, &ZeroSetOptions::default()).unwrap();
    assert_eq!(set.curves.len(), 1);
    assert!(set.gaps.is_empty());
    let c = &set.curves[0];
    assert!(!c.closed);
    for p in &c.points {
        assert!((p.y - 0.2).abs() <= set.tolerance);
        assert!((p.z - 0.5 * (p.x * p.x + p.y * p.y)).abs() < 1e-14);
    }
    let xs: Vec<f64> = c.points.iter().map(|p| p.x).collect();
    assert!(
        xs.iter().any(|&x| (x + 1.0).abs() < 1e-12) && xs.iter().any(|&x| (x - 1.0).abs() < 1e-12)
    );
}

#[test]
fn wild_surfaces_never_hang_and_the_point_limit_is_reported() {
    let mut r = rng(41);
    let tri = meshes::uniform_square(&mut r, 200);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let s = Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: (9.0 * p.x).sin() * (7.0 * p.y).cos(),
            dx: 9.0 * (9.0 * p.x).cos() * (7.0 * p.y).cos(),
            dy: -7.0 * (9.0 * p.x).sin() * (7.0 * p.y).sin(),
        })
        .unwrap(),
    );
    for name in ["K", "H", "k1", "k2", "kabs"] {
        let field = SurfaceField::parse(name).unwrap();
        let levels = auto_levels(&s, &field, 8);
        let opts = ZeroSetOptions {
            max_points: 500,
            ..Default::default()
        };
        let sets = level_lines(&s, &field, &levels, &opts).unwrap();
        let total: usize = sets
            .iter()
            .flat_map(|s| &s.curves)
            .map(|c| c.uvs.len())
            .sum();
        // Each branch may finish after the budget runs out, but only one per piece and level.
        assert!(sets.iter().all(|s| s.truncated), "{name}");
        assert!(total < 500 + 100_000, "{total}");
    }
    assert!(
        level_lines(
            &s,
            &SurfaceField::Height,
            &[f64::NAN],
            &ZeroSetOptions::default()
        )
        .is_err()
    );
    let bad = ZeroSetOptions {
        hunting: 0,
        ..Default::default()
    };
    assert_eq!(
        level_lines(&s, &SurfaceField::Height, &[0.0], &bad),
        Err(ZeroSetError::BadOptions)
    );
}

#[cfg(feature = "expr")]
#[test]
fn formulas_of_the_surface_quantities_are_fields() {
    let s = elliptic_paraboloid(1.0, 1.0, 51);
    // x² + y² = 0.25 as a formula: the same circle as z = 0.125.
    let field = SurfaceField::parse("x^2 + y^2").unwrap();
    let set = &level_lines(&s, &field, &[0.25], &ZeroSetOptions::default()).unwrap()[0];
    assert_eq!(set.curves.len(), 1);
    assert!(
        set.curves[0]
            .uvs
            .iter()
            .all(|p| (p.coords.norm() - 0.5).abs() < 1e-10)
    );
    assert!(SurfaceField::parse("K + w").is_err());
}

/// The 6-sided UPS surface of `pssurf new ups --sides 6 --size 4 --height "sin(x)*cos(y)"`.
#[cfg(feature = "expr")]
fn ups_sin_cos() -> Surface {
    use crate::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface_from_formula};
    let lattice = Lattice {
        base: 1.0,
        origin: Point2::origin(),
    };
    let grid = UpsGrid::new(lattice, LatticePolygon::standard(6, 4).unwrap()).unwrap();
    let f = crate::expr::HeightFunction::parse("sin(x)*cos(y)").unwrap();
    Surface::try_from(graph_surface_from_formula(grid, GraphKind::Parametric, &f).unwrap()).unwrap()
}

#[cfg(feature = "expr")]
#[test]
fn a_contour_leaving_a_piece_near_a_corner_is_one_closed_loop_traced_once() {
    // z = 0.3 has a loop that leaves a piece near a corner; the end was once solved on the
    // wrong edge, far from the crossing, and the loop came out open with two gaps, traced
    // twice round.
    let s = ups_sin_cos();
    let sets = level_lines(
        &s,
        &SurfaceField::Height,
        &[0.3],
        &ZeroSetOptions::default(),
    )
    .unwrap();
    let set = &sets[0];
    assert!(set.gaps.is_empty(), "{:?}", set.gaps);
    let domain = s.domain();
    for c in &set.curves {
        if !c.closed {
            for end in [c.uvs[0], *c.uvs.last().unwrap()] {
                assert!(domain.distance_to_boundary(end) < 1e-9, "{end:?}");
            }
        }
        for p in &c.points {
            assert!((p.z - 0.3).abs() <= set.tolerance);
        }
    }
    // No stretch traced twice: no two points of all curves closer than a tenth of a step
    // unless neighbours on one curve.
    let all: Vec<(usize, usize, Point2<f64>)> = set
        .curves
        .iter()
        .enumerate()
        .flat_map(|(k, c)| c.uvs.iter().enumerate().map(move |(i, p)| (k, i, *p)))
        .collect();
    for (x, a) in all.iter().enumerate() {
        for b in &all[x + 1..] {
            let neighbours = a.0 == b.0 && b.1 - a.1 <= 1;
            let wraps = a.0 == b.0 && a.1 == 0 && b.1 + 1 == set.curves[a.0].uvs.len();
            assert!(
                neighbours || wraps || (a.2 - b.2).norm() > 1e-6,
                "{a:?} {b:?}"
            );
        }
    }
    assert!(set.curves.iter().any(|c| c.closed));
}

#[test]
fn no_branch_crawls_near_critical_points_of_the_field() {
    // Near a critical point of K on a sliver piece the tangent is ill-conditioned and a
    // branch once crept on in steps of 1e-7 until the point budget (2 million) ran out.
    let mut r = rng(41);
    let tri = meshes::uniform_square(&mut r, 5000);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let s = Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: (3.0 * p.x).sin() * (2.0 * p.y).cos(),
            dx: 3.0 * (3.0 * p.x).cos() * (2.0 * p.y).cos(),
            dy: -2.0 * (3.0 * p.x).sin() * (2.0 * p.y).sin(),
        })
        .unwrap(),
    );
    let field = SurfaceField::Curvature(CurvatureQuantity::Gaussian);
    let levels = auto_levels(&s, &field, 20);
    let sets = level_lines(&s, &field, &levels, &ZeroSetOptions::default()).unwrap();
    let points: usize = sets
        .iter()
        .flat_map(|s| &s.curves)
        .map(|c| c.uvs.len())
        .sum();
    let branches_stopped: usize = sets.iter().map(|s| s.stuck).sum();
    assert!(sets.iter().all(|s| !s.truncated));
    // About 54 000 points; a crawling branch alone would add 100 000.
    assert!(points < 100_000, "{points}");
    assert!(branches_stopped < points / 100, "{branches_stopped}");
}

/// z = x²/2 + y²/4 on the hexagon of side 1 on a lattice of side 1/4 (the domain of
/// `pssurf new ups --sides 6 --size 4`, centred), reproduced exactly.
fn quadratic_on_hexagon() -> Surface {
    let h = 0.5 * 3f64.sqrt();
    let mut pts = Vec::new();
    for j in -4i32..=4 {
        for i in -4i32..=4 {
            if (i + j).abs() <= 4 {
                pts.push(Point2::new(
                    0.25 * (i as f64 + 0.5 * j as f64),
                    0.25 * j as f64 * h,
                ));
            }
        }
    }
    let basis = Arc::new(PsBasis::optimal(Triangulation::delaunay(pts).unwrap()).unwrap());
    Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: 0.5 * p.x * p.x + 0.25 * p.y * p.y,
            dx: p.x,
            dy: 0.5 * p.y,
        })
        .unwrap(),
    )
}

#[test]
fn walks_close_level_loops_of_k_on_a_quadratic_graph() {
    // K = ab/W⁴ (a = 1, b = 1/2) is continuous; K = 0.4 is one ellipse inside the hexagon.
    // The curve meets split lines at ~13°, where a walk's step (within the walk tolerance
    // of the curve, not on it) crossed the edge farther from the root than edge_root
    // accepted: the four-point walk stopped there, leaving 8 open curves and 8 "gaps".
    let s = quadratic_on_hexagon();
    let k = SurfaceField::Curvature(CurvatureQuantity::Gaussian);
    for method in [TraceMethod::FourPoint, TraceMethod::EightPoint] {
        let opts = ZeroSetOptions {
            method,
            ..Default::default()
        };
        let set = &level_lines(&s, &k, &[0.4], &opts).unwrap()[0];
        assert!(
            set.gaps.is_empty() && set.stuck == 0,
            "{method:?}: {} gaps, {} stopped",
            set.gaps.len(),
            set.stuck
        );
        assert_eq!(set.curves.len(), 1, "{method:?}");
        assert!(set.curves[0].closed, "{method:?}");
        let tol = opts.walk_tolerance * set.tolerance / opts.tolerance;
        assert!(set.curves[0].uvs.len() > 100);
        for uv in &set.curves[0].uvs {
            let (kk, _) = k_and_h(1.0, 0.5, *uv);
            assert!(
                (kk - 0.4).abs() <= tol * (1.0 + 1e-9),
                "{method:?} {uv:?} {kk}"
            );
        }
    }
}

/// The PS basis on the Delaunay triangulation of a 15 × 15 grid of [-1, 1]² (with grid lines
/// at x = 0 and y = 0).
fn grid_basis() -> Arc<PsBasis> {
    let pts: Vec<Point2<f64>> = (0..15)
        .flat_map(|j| {
            (0..15).map(move |i| Point2::new(-1.0 + i as f64 / 7.0, -1.0 + j as f64 / 7.0))
        })
        .collect();
    Arc::new(PsBasis::optimal(Triangulation::delaunay(pts).unwrap()).unwrap())
}

/// z = max(x, 0)² on data gridded at x = 0 is flat on the left half: the level z = 0 there is
/// counted in flat pieces, and the only curve is the flat region's edge x = 0 (the pieces on
/// the right take the level along it), not the edges between flat pieces.
#[test]
fn a_flat_region_is_counted_and_only_its_edge_is_a_line() {
    let basis = grid_basis();
    let s = Surface::Functional(
        PsSpline::interpolate(basis, |p| {
            let x = p.x.max(0.0);
            Hermite {
                value: x * x,
                dx: 2.0 * x,
                dy: 0.0,
            }
        })
        .unwrap(),
    );
    let set = &level_lines(
        &s,
        &SurfaceField::Height,
        &[0.0],
        &ZeroSetOptions::default(),
    )
    .unwrap()[0];
    assert!(set.flat_pieces > 0);
    assert_eq!(set.curves.len(), 1, "{} curves", set.curves.len());
    let c = &set.curves[0];
    let (first, last) = (c.uvs[0], *c.uvs.last().unwrap());
    assert!((first.y - last.y).abs() >= 2.0 - 1e-12, "{first} {last}");
    assert!(c.uvs.iter().all(|uv| uv.x.abs() <= 1e-12));
}

/// A level line running along piece edges: z = 0 of z = t + t²/5 with t = x (data gridded
/// on x = 0, the line along edges) or t = x − y (the line through vertices, across pieces or
/// along their edges as the grid's diagonals fall). Each piece on either side traced the edge
/// with rounding, and the joining made 16 curves, 3 of them closed, with 24 ends left
/// unjoined (before that, 55 curves and 49 false jumps); on the diagonal, 21 curves. It is one
/// open curve from boundary to boundary, for every tracing method (the four-point walk only
/// along x = 0: its steps (±h, 0), (0, ±h) leave the diagonal by h/√2 whatever h, so it stops
/// on it, as documented for [`TraceMethod::FourPoint`]).
#[test]
fn a_level_line_along_piece_edges_is_one_curve() {
    let basis = grid_basis();
    for (name, dir) in [("x", [1.0, 0.0]), ("x - y", [1.0, -1.0])] {
        let s = Surface::Functional(
            PsSpline::interpolate(basis.clone(), |p| {
                let t = dir[0] * p.x + dir[1] * p.y;
                Hermite {
                    value: t + 0.2 * t * t,
                    dx: (1.0 + 0.4 * t) * dir[0],
                    dy: (1.0 + 0.4 * t) * dir[1],
                }
            })
            .unwrap(),
        );
        for method in [
            TraceMethod::PredictorCorrector,
            TraceMethod::FourPoint,
            TraceMethod::EightPoint,
        ] {
            if method == TraceMethod::FourPoint && dir[1] != 0.0 {
                continue;
            }
            let opts = ZeroSetOptions {
                method,
                ..Default::default()
            };
            let set = &level_lines(&s, &SurfaceField::Height, &[0.0], &opts).unwrap()[0];
            let case = format!("t = {name}, {method:?}");
            assert!(set.gaps.is_empty(), "{case}: {:?}", set.gaps);
            assert_eq!(set.unjoined, 0, "{case}");
            assert_eq!(set.curves.len(), 1, "{case}");
            let c = &set.curves[0];
            assert!(!c.closed, "{case}");
            let (first, last) = (c.uvs[0], *c.uvs.last().unwrap());
            // From one end of the line x = 0 (or the diagonal x = y) to the other.
            let ends = [first, last].map(|p| p.y.abs());
            assert!(
                ends.iter().all(|e| (e - 1.0).abs() <= 1e-12),
                "{case}: {first} {last}"
            );
            assert!(
                (first.y - last.y).abs() >= 2.0 - 1e-12,
                "{case}: {first} {last}"
            );
            for uv in &c.uvs {
                let t = dir[0] * uv.x + dir[1] * uv.y;
                assert!(t.abs() <= 1e-12, "{case}: {uv}");
            }
        }
    }
}
