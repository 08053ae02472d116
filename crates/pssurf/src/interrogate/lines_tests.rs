//! Lines of curvature, asymptotic lines, umbilics and geodesics against closed forms:
//! parallels and meridians of a paraboloid of revolution (apex an umbilic), the rulings of
//! z = xy, great circles on a sphere; orientation and bounded work on wavy surfaces.

use nalgebra::{Point2, Vector2, Vector3};

use super::level_tests::{elliptic_paraboloid, ps_graph_on_square};
use super::tests::{sphere_patch, wavy_surface, wavy_surface_on};
use super::*;
use crate::geometry::Triangle2;
use crate::ps::Hermite;
use crate::surface::{ParametricSurface, PiecewiseSurface, Surface};
use crate::test_util::*;

fn tight() -> FieldLineOptions {
    FieldLineOptions {
        tolerance: 1e-12,
        ..Default::default()
    }
}

/// z = xy as a PS-spline on a random Delaunay mesh of [-1, 1]² (reproduced exactly).
fn saddle(seed: u64) -> Surface {
    ps_graph_on_square(seed, 30, |p| Hermite {
        value: p.x * p.y,
        dx: p.y,
        dy: p.x,
    })
}

#[test]
fn lines_of_curvature_of_a_paraboloid_of_revolution_are_parallels_and_meridians() {
    let mut r = rng(1501);
    // A PS-spline and a quadratic Bézier triangle, both exactly z = (x² + y²)/2.
    let big = Triangle2::new(
        Point2::new(-3.0, -3.0),
        Point2::new(4.0, -2.0),
        Point2::new(0.0, 4.0),
    );
    let surfaces = (0..3)
        .map(|seed| elliptic_paraboloid(1.0, 1.0, 1510 + seed))
        .chain([Surface::Bezier(interpolating_bezier(big, 2, |p| {
            Vector3::new(p.x, p.y, 0.5 * (p.x * p.x + p.y * p.y))
        }))]);
    for s in surfaces {
        let angle = uniform(&mut r, 0.0, std::f64::consts::TAU);
        let radius = uniform(&mut r, 0.2, 0.9);
        let p = Point2::new(radius * angle.cos(), radius * angle.sin());
        // κ1 (the parallel's normal curvature 1/√(1+r²) exceeds the meridian's): a circle.
        let parallel = trace_field_line(&s, LineFamily::Curvature1, p, &tight()).unwrap();
        assert!(parallel.curve.closed, "{:?}", parallel.ends);
        assert_eq!(parallel.ends, [LineEnd::Closed, LineEnd::Closed]);
        for q in &parallel.curve.uvs {
            assert_near!(q.coords.norm(), radius, 1e-8);
        }
        let turned: f64 = parallel
            .curve
            .uvs
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0].coords, w[1].coords);
                (a.x * b.y - a.y * b.x).atan2(a.dot(&b))
            })
            .sum();
        assert_near!(turned.abs(), std::f64::consts::TAU, 0.05);
        // κ2: a meridian, from the apex (an umbilic) to the boundary of the square.
        let meridian = trace_field_line(&s, LineFamily::Curvature2, p, &tight()).unwrap();
        let dir = p.coords / radius;
        for q in &meridian.curve.uvs {
            assert!(
                (dir.x * q.y - dir.y * q.x).abs() <= 1e-8,
                "{q} off the meridian"
            );
        }
        let mut ends = meridian.ends;
        ends.sort_by_key(|e| e.name());
        assert_eq!(
            ends,
            [LineEnd::Boundary, LineEnd::Umbilic],
            "{:?}",
            meridian.ends
        );
        // The end at the apex is near it: |κ1 − κ2| ≤ 1e-3 (κ1 + κ2) there, so r ≲ 0.045.
        let apex_end = if meridian.ends[0] == LineEnd::Umbilic {
            meridian.curve.uvs[0]
        } else {
            *meridian.curve.uvs.last().unwrap()
        };
        assert!(apex_end.coords.norm() < 0.06, "{apex_end}");
        // The umbilic itself, from the line's end and by the global search.
        let u = umbilic_near(&s, apex_end).expect("Newton reaches the apex");
        assert!(u.uv.coords.norm() < 1e-6, "{}", u.uv);
        assert_near!(u.curvature, 1.0, 1e-9);
        let all = find_umbilics(&s);
        assert!(all.umbilic_pieces.is_empty());
        assert_eq!(all.points.len(), 1, "{:?}", all.points);
        assert!(all.points[0].uv.coords.norm() < 1e-6);
    }
}

#[test]
fn lines_of_curvature_keep_their_family_and_orientation_on_a_wavy_surface() {
    let s = wavy_surface_on(1502, 400);
    let mut r = rng(1503);
    let (mut chords, mut skipped, mut ends, mut jumps) = (0usize, 0usize, 0usize, 0usize);
    for _ in 0..20 {
        let seed = Point2::new(uniform(&mut r, 0.05, 0.95), uniform(&mut r, 0.05, 0.95));
        for family in LineFamily::CURVATURE {
            let Ok(line) = trace_field_line(&s, family, seed, &FieldLineOptions::default()) else {
                continue;
            };
            let uvs = &line.curve.uvs;
            ends += 2;
            for (end, at) in line.ends.iter().zip([uvs[0], *uvs.last().unwrap()]) {
                if *end == LineEnd::Jump {
                    // A jump is where a step meets a piece boundary.
                    jumps += 1;
                    let shape = s.piece_shape(s.jet(at).unwrap().piece);
                    let c = shape.corners();
                    let gap = (0..c.len())
                        .map(|i| {
                            super::continuation::distance_to_segment(at, c[i], c[(i + 1) % c.len()])
                        })
                        .fold(f64::INFINITY, f64::min);
                    assert!(gap < 0.03, "a jump {gap} inside a piece at {at}");
                }
            }
            for w in uvs.windows(3) {
                let (a, b) = (w[1] - w[0], w[2] - w[1]);
                // Never reverses, never switches to the other (orthogonal) family.
                assert!(
                    a.dot(&b) > 0.5 * a.norm() * b.norm(),
                    "turn {} at {} ({:?}, {} points)",
                    a.angle(&b),
                    w[1],
                    line.ends,
                    uvs.len()
                );
            }
            for w in uvs.windows(2) {
                let (j0, j1) = (s.jet(w[0]).unwrap(), s.jet(w[1]).unwrap());
                // Skipped: chords across piece boundaries (the direction jumps) and the
                // smallest steps, taken whatever their error where a step meets a boundary.
                if j0.piece != j1.piece || (w[1] - w[0]).norm() < 1e-5 {
                    skipped += 1;
                    continue;
                }
                chords += 1;
                let mid = Point2::from((w[0].coords + w[1].coords) * 0.5);
                let c = Curvature::from_jet(&s.jet(mid).unwrap().jet).unwrap();
                let d = if family == LineFamily::Curvature1 {
                    c.dir1_uv
                } else {
                    c.dir2_uv
                };
                let t = (w[1] - w[0]).normalize();
                assert!(
                    (t.x * d.y - t.y * d.x).abs() < 2e-2,
                    "chord off the field at {mid} by {} (k {} {}, chord {})",
                    (t.x * d.y - t.y * d.x).abs(),
                    c.k1,
                    c.k2,
                    (w[1] - w[0]).norm()
                );
            }
        }
    }
    assert!(chords > 2000, "{chords} chords checked");
    assert!(
        skipped * 2 < chords,
        "{skipped} of {} chords skipped",
        chords + skipped
    );
    // The PS interpolant's principal directions differ by more than 45° across about 3 % of
    // its piece edges (second derivatives converge only as O(h)); a long line meets one, so
    // most of the 80 ends here are such jumps (each checked above to be at a boundary).
    eprintln!("{jumps} of {ends} ends are jumps");
}

#[test]
fn asymptotic_lines_of_z_equals_xy_are_its_rulings() {
    let s = saddle(1504);
    let mut r = rng(1505);
    for _ in 0..10 {
        let seed = Point2::new(uniform(&mut r, -0.9, 0.9), uniform(&mut r, -0.9, 0.9));
        let mut constant = Vec::new();
        for family in LineFamily::ASYMPTOTIC {
            let line = trace_field_line(&s, family, seed, &tight()).unwrap();
            assert_eq!(line.ends, [LineEnd::Boundary, LineEnd::Boundary]);
            let u_fixed = line.curve.uvs.iter().all(|q| (q.x - seed.x).abs() <= 1e-9);
            let v_fixed = line.curve.uvs.iter().all(|q| (q.y - seed.y).abs() <= 1e-9);
            assert!(u_fixed != v_fixed, "not a ruling from {seed}");
            // A ruling crosses the whole square.
            assert!(line.curve.length() > 1.9);
            constant.push(u_fixed);
        }
        assert_ne!(
            constant[0], constant[1],
            "both families gave the same ruling"
        );
    }
    // Where K ≥ 0 there are no asymptotic lines: a bowl refuses the seed.
    let bowl = elliptic_paraboloid(1.0, 2.0, 1506);
    let err = trace_field_line(
        &bowl,
        LineFamily::AsymptoticPlus,
        Point2::new(0.3, 0.1),
        &tight(),
    );
    assert!(
        matches!(err, Err(FieldLineError::Undefined { .. })),
        "{err:?}"
    );
}

fn sphere_fixture(
    r: &mut rand_chacha::ChaCha8Rng,
) -> (
    crate::bezier::RationalBezierTriangle<Vector3<f64>>,
    f64,
    Vector3<f64>,
) {
    let t = Triangle2::new(
        Point2::new(-0.6, -0.5),
        Point2::new(0.7, -0.3),
        Point2::new(0.1, 0.8),
    );
    let rad = uniform(r, 0.5, 5.0);
    let centre = random_vec3(r) * 3.0;
    (sphere_patch(t, rad, centre), rad, centre)
}

#[test]
fn geodesics_on_a_sphere_are_great_circles() {
    let mut r = rng(1506);
    for _ in 0..10 {
        let (s, rad, centre) = sphere_fixture(&mut r);
        let start = Point2::new(uniform(&mut r, -0.1, 0.1), uniform(&mut r, -0.1, 0.2));
        let dir = random_dir(&mut r);
        let g = geodesic(&s, start, dir, 0.6 * rad, &GeodesicOptions::default()).unwrap();
        let j = ParametricSurface::jet(&s, start).unwrap().jet;
        let p0 = j.value;
        let t0 = (j.dx * dir.x + j.dy * dir.y).normalize();
        let e = (p0 - centre) / rad;
        let plane = e.cross(&t0);
        for p in &g.curve.points {
            assert!(
                (p - centre).dot(&plane).abs() <= 1e-8 * rad,
                "off the great circle"
            );
        }
        // Only the direction matters, however large its components.
        let huge = geodesic(
            &s,
            start,
            dir * 1e307,
            0.6 * rad,
            &GeodesicOptions::default(),
        )
        .unwrap();
        assert!(
            (huge.curve.points.last().unwrap() - g.curve.points.last().unwrap()).norm()
                < 1e-10 * rad
        );
        if g.end == GeodesicEnd::Length {
            // The end is where the great circle is after the arc length travelled.
            let theta = g.length / rad;
            let expected = centre + (e * theta.cos() + t0 * theta.sin()) * rad;
            let last = g.curve.points.last().unwrap();
            assert!(
                (last - expected).norm() <= 1e-8 * rad,
                "{}",
                (last - expected).norm()
            );
        } else {
            assert_eq!(g.end, GeodesicEnd::Boundary);
        }
        // Asked to run far beyond the patch (a great circle leaves it within π R), it
        // still runs to the boundary: steps are bounded by the surface's size, not by the
        // length asked for (with 1e10 R the smallest step was longer than the way left).
        let to_boundary = geodesic(&s, start, dir, 4.0 * rad, &GeodesicOptions::default());
        let far = geodesic(&s, start, dir, 1e10 * rad, &GeodesicOptions::default());
        let (near, far) = (to_boundary.unwrap(), far.unwrap());
        assert_eq!(
            (near.end, far.end),
            (GeodesicEnd::Boundary, GeodesicEnd::Boundary)
        );
        assert!((near.length - far.length).abs() <= 1e-6 * rad);
        let gap = near.curve.points.last().unwrap() - far.curve.points.last().unwrap();
        assert!(gap.norm() <= 1e-6 * rad, "{}", gap.norm());
        // At most the points asked for.
        let few = GeodesicOptions {
            max_points: 5,
            ..Default::default()
        };
        let short = geodesic(&s, start, dir, 4.0 * rad, &few).unwrap();
        assert_eq!(
            (short.curve.points.len(), short.end),
            (5, GeodesicEnd::Limit)
        );
    }
}

#[test]
fn the_shortest_geodesic_on_a_sphere_has_the_great_circle_arc_length() {
    let mut r = rng(1507);
    for _ in 0..6 {
        let (s, rad, centre) = sphere_fixture(&mut r);
        let a = Point2::new(uniform(&mut r, -0.3, 0.0), uniform(&mut r, -0.25, 0.0));
        let b = Point2::new(uniform(&mut r, 0.0, 0.3), uniform(&mut r, 0.0, 0.3));
        let g = shortest_geodesic(&s, a, b, &GeodesicOptions::default()).unwrap();
        let pa = ParametricSurface::point(&s, a).unwrap() - centre;
        let pb = ParametricSurface::point(&s, b).unwrap() - centre;
        let arc = rad * (pa.cross(&pb).norm()).atan2(pa.dot(&pb));
        assert!(g.exact, "shooting did not converge");
        assert_near!(g.length, arc, 1e-8);
        assert!(g.lattice_length >= arc * (1.0 - 1e-12) && g.relaxed_length <= g.lattice_length);
        assert!((g.curve.uvs.last().unwrap() - b).norm() < 3e-9);
        // From a point to itself: the point, of length 0 (it was "did not converge").
        let same = shortest_geodesic(&s, a, a, &GeodesicOptions::default()).unwrap();
        assert!(same.exact && same.length == 0.0 && same.curve.uvs == vec![a]);
        // Nearby ends: the lattice's detour made 1e-10 apart 3e-6 long, and a tolerance of
        // the domain's size let 1e-8 apart end 1.5 % short (measured now: lengths within
        // 2.7e-7 of the arc at 1e-10 and 1e-8, 2.7e-10 beyond).
        for offset in [1e-10, 1e-8, 1e-6, 1e-4] {
            let b = a + Vector2::new(offset, 0.3 * offset);
            let g = shortest_geodesic(&s, a, b, &GeodesicOptions::default()).unwrap();
            let pb = ParametricSurface::point(&s, b).unwrap() - centre;
            let arc = rad * (pa.cross(&pb).norm()).atan2(pa.dot(&pb));
            assert!(g.exact, "{offset}: shooting did not converge");
            // Within the coordinates' rounding (64 units in the last place) of the arc.
            let rounding = 64.0 * f64::EPSILON * b.coords.amax();
            assert!(
                (g.length - arc).abs() <= 1e-6 * arc + rounding,
                "{offset}: {} for {arc}",
                g.length
            );
            assert!((g.curve.uvs.last().unwrap() - b).norm() <= 1e-9 * offset + rounding);
        }
    }
}

#[test]
fn a_sphere_is_umbilic_everywhere() {
    let mut r = rng(1508);
    let (s, _, _) = sphere_fixture(&mut r);
    let u = find_umbilics(&s);
    assert_eq!(u.umbilic_pieces, vec![0]);
    assert!(u.points.is_empty());
    let err = trace_field_line(&s, LineFamily::Curvature1, Point2::new(0.0, 0.0), &tight());
    assert!(matches!(err, Err(FieldLineError::Undefined { .. })));
    // A largest step below the smallest is refused, not a panic.
    let tiny = FieldLineOptions {
        max_step: 1e-300,
        ..tight()
    };
    let err = trace_field_line(&s, LineFamily::Curvature1, Point2::new(0.1, 0.0), &tiny);
    assert_eq!(err, Err(FieldLineError::BadOptions));
}

#[test]
fn wild_surfaces_end_every_line_with_bounded_work() {
    for seed in 0..3 {
        let s = wavy_surface(1520 + seed);
        let opts = FieldLineOptions {
            max_points: 300,
            ..Default::default()
        };
        let mut r = rng(1530 + seed);
        for _ in 0..30 {
            let p = Point2::new(uniform(&mut r, 0.0, 1.0), uniform(&mut r, 0.0, 1.0));
            for family in LineFamily::CURVATURE
                .into_iter()
                .chain(LineFamily::ASYMPTOTIC)
            {
                if let Ok(line) = trace_field_line(&s, family, p, &opts) {
                    assert!(line.curve.uvs.len() <= 2 * 300 + 1);
                    assert!(
                        line.curve
                            .points
                            .iter()
                            .all(|q| q.iter().all(|x| x.is_finite()))
                    );
                }
            }
        }
        let u = find_umbilics(&s);
        for um in &u.points {
            let c = Curvature::from_jet(&s.jet(um.uv).unwrap().jet).unwrap();
            assert!(
                c.k1 - c.k2 <= 1e-6 * (c.k1.abs() + c.k2.abs()) + 1e-9,
                "{um:?}"
            );
        }
    }
    let _ = Vector2::<f64>::zeros();
}

#[test]
fn evenly_spaced_lines_keep_their_distance_and_cover_the_domain() {
    let s = elliptic_paraboloid(1.0, 1.0, 1540);
    let spacing = 0.1;
    for family in LineFamily::CURVATURE {
        let even = even_field_lines(&s, family, spacing, &FieldLineOptions::default(), 10_000);
        assert!(!even.truncated);
        assert!(even.lines.len() > 10, "{} lines", even.lines.len());
        let mut earlier: Vec<Point2<f64>> = Vec::new();
        for line in &even.lines {
            for p in &line.curve.uvs {
                let d = earlier
                    .iter()
                    .map(|q| (q - p).norm())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d >= 0.5 * spacing * (1.0 - 1e-9),
                    "{family:?}: {p} is {d} from a line"
                );
            }
            earlier.extend(&line.curve.uvs);
        }
        // Every lattice point of the square away from the apex (an umbilic, whose
        // neighbourhood lines avoid) has a line within twice the spacing.
        let mut far = 0;
        for i in 0..40 {
            for j in 0..40 {
                let p = Point2::new(-0.975 + 0.05 * i as f64, -0.975 + 0.05 * j as f64);
                let d = earlier
                    .iter()
                    .map(|q| (q - p).norm())
                    .fold(f64::INFINITY, f64::min);
                if p.coords.norm() > 0.15 && d > 2.0 * spacing {
                    far += 1;
                }
            }
        }
        assert_eq!(
            far, 0,
            "{family:?}: {far} lattice points far from every line"
        );
    }
}

/// A length limit ends each branch where its length in space reaches it: the last step used
/// to run on, up to a whole step past it (0.1 instead of 0.05 each way); now to 1e-6.
#[test]
fn a_length_limit_ends_each_branch_at_that_length() {
    let mut r = rng(1520);
    for seed in 0..3 {
        let s = elliptic_paraboloid(1.0, uniform(&mut r, 0.5, 2.0), 1521 + seed);
        let seed_point = Point2::new(uniform(&mut r, 0.2, 0.5), uniform(&mut r, 0.2, 0.5));
        for family in [LineFamily::Curvature1, LineFamily::Curvature2] {
            let length = uniform(&mut r, 0.005, 0.3);
            let opts = FieldLineOptions {
                length,
                ..Default::default()
            };
            let line = trace_field_line(&s, family, seed_point, &opts).unwrap();
            assert_eq!(line.ends, [LineEnd::Length, LineEnd::Length]);
            let branch = |pts: &[Vector3<f64>]| -> f64 {
                pts.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
            };
            let pts = &line.curve.points;
            for walked in [branch(&pts[..=line.seed]), branch(&pts[line.seed..])] {
                assert!(
                    (walked - length).abs() <= 1e-6 * length,
                    "{family:?}: {walked} for {length}"
                );
            }
        }
    }
}
