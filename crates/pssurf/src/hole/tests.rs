use std::sync::Arc;

use nalgebra::Vector3;

use super::examples::{EXAMPLES, example};
use super::*;
use crate::ps::Energy;
use crate::ps::fair::{FairOptions, fair};
use crate::surface::{ParametricSurface, Surface, UniformSurface, UpsSurface};

/// Every example's holes, filled to the default tolerances.
fn filled_examples() -> Vec<(&'static str, HoleFill)> {
    let mut out = Vec::new();
    for name in EXAMPLES {
        for hole in example(name).unwrap().unwrap().holes {
            let mut fill = HoleFill::new(hole, 1e-4, 0.25).unwrap();
            fill.run_to_tolerance(MAX_ITERATIONS).unwrap();
            out.push((name, fill));
        }
    }
    out
}

#[test]
fn the_patch_interpolates_position_tangent_and_normal_at_every_boundary_vertex() {
    for (name, fill) in filled_examples() {
        let ps = fill.patch(Interior::Instant).unwrap().to_ps().unwrap();
        let b = fill.boundary();
        let n = b.len();
        let vertices = fill.boundary_vertices();
        assert!(vertices.len() >= 3 * (1 << fill.level()));
        for v in vertices {
            let j = ps.jet(v.domain).unwrap().jet;
            let p = b.curves()[v.curve].point(v.t);
            assert!(
                (j.value - p).norm() < 1e-10 * b.size(),
                "{name}: position at {v:?}"
            );
            let normal = j.dx.cross(&j.dy).normalize();
            // The tangent of the curve lies in the tangent plane, and (away from corners)
            // the normal is the given one.
            let g = b.unit_tangent(v.curve, v.t);
            assert!(g.dot(&normal).abs() < 1e-10, "{name}: tangent at {v:?}");
            if v.corner {
                let g_in = b.unit_tangent((v.curve + n - 1) % n, 1.0);
                assert!(
                    g_in.dot(&normal).abs() < 1e-10,
                    "{name}: incoming tangent at {v:?}"
                );
                assert!(
                    g_in.cross(&g).normalize().dot(&normal) > 1.0 - 1e-10,
                    "{name}"
                );
            } else {
                let given = b.unit_normal(v.curve, v.t);
                assert!(given.dot(&normal) > 1.0 - 1e-12, "{name}: normal at {v:?}");
            }
        }
    }
}

#[test]
fn the_deviation_decreases_with_the_iterations_and_meets_the_tolerances() {
    for (name, fill) in filled_examples() {
        assert!(fill.converged(), "{name}: {:?}", fill.history());
        let h = fill.history();
        let last = h.last().unwrap();
        assert!(
            last.max_deviation <= 1e-4 * fill.boundary().size(),
            "{name}"
        );
        assert!(last.max_angle <= 0.25, "{name}");
        // Every step brings the boundary closer, the first one included.
        for w in h.windows(2) {
            assert!(
                w[1].max_deviation <= w[0].max_deviation && w[1].max_angle <= w[0].max_angle,
                "{name}: {w:?}"
            );
        }
    }
}

/// The octant of the unit sphere: three quarter circles as rational quadratics (middle weight
/// 1/√2, so that t = 1/4 lies at 21.6°, not 22.5°) with radial normals.
fn octant() -> HoleBoundary {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = |a: Vector3<f64>, b: Vector3<f64>| -> DynCurve {
        let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let c =
            crate::nurbs::NurbsCurve::try_new(2, knots, vec![a, a + b, b], Some(vec![1.0, w, 1.0]))
                .unwrap();
        Box::new(NurbsBoundary {
            normals: NormalField::Curve(c.clone()),
            curve: c,
        })
    };
    let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
    HoleBoundary::new(vec![arc(x, y), arc(y, z), arc(z, x)]).unwrap()
}

/// Issue 18 (outside audit): on quarter circles the first step tripled the deviation (the
/// octant 0.00314 → 0.0083, the degenerate NURBS' base arc of radius 35 0.11 → 0.29), because
/// the old α's were kept. With the α's fitted again at every level the deviation falls at
/// every step, by about 8 (it fell by 4 before).
#[test]
fn quarter_circles_come_closer_at_every_step() {
    let cone = || {
        example("degenerate-nurbs")
            .unwrap()
            .unwrap()
            .holes
            .remove(0)
    };
    let cases: [(&str, &dyn Fn() -> HoleBoundary); 2] = [("octant", &octant), ("cone", &cone)];
    for (name, hole) in cases {
        // Six steps fitting every edge (as `--iterations 6`), then to the default tolerances.
        for fixed_steps in [true, false] {
            let tolerance = if fixed_steps { f64::MIN_POSITIVE } else { 1e-4 };
            let mut fill = HoleFill::new(hole(), tolerance, 0.25).unwrap();
            if fixed_steps {
                for _ in 0..6 {
                    fill.step().unwrap();
                }
            } else {
                fill.run_to_tolerance(MAX_ITERATIONS).unwrap();
                assert!(fill.converged(), "{name}");
            }
            let h = fill.history();
            for w in h.windows(2) {
                assert!(
                    w[1].max_deviation <= w[0].max_deviation && w[1].max_angle <= w[0].max_angle,
                    "{name}, fixed steps {fixed_steps}: {w:?}"
                );
            }
            if fixed_steps {
                // 1.07e-5 of the radius after six steps before; a model of the new
                // iteration gives 3.5e-8.
                let radius = if name == "octant" { 1.0 } else { 35.0 };
                assert!(h[6].max_deviation < 1e-6 * radius, "{name}: {h:?}");
            }
        }
    }
}

/// The report's G0 on the octant after eight steps against the deviation measured between
/// the boundary vertices (16 points per edge; the patch lies off the unit sphere by at least
/// ||p| − 1|): the report's samples fell on the vertices, where the patch interpolates, and
/// said 2.3e-12 where the edges were 6.5e-10 off.
#[test]
fn the_quality_report_measures_between_the_boundary_vertices() {
    let mut fill = HoleFill::new(octant(), f64::MIN_POSITIVE, f64::MIN_POSITIVE).unwrap();
    for _ in 0..8 {
        fill.step().unwrap();
    }
    let patch = fill.patch(Interior::Instant).unwrap();
    let q = quality(&fill, &patch).unwrap();
    let ps = patch.to_ps().unwrap();
    let corners = fill.domain_corners();
    let mut off_sphere = 0.0f64;
    for k in 0..corners.len() {
        let (a, c) = (corners[k], corners[(k + 1) % corners.len()]);
        let n = 16 * fill.side_steps(k);
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let p = ps.point(nalgebra::Point2::from(a.coords * (1.0 - t) + c.coords * t));
            off_sphere = off_sphere.max((p.unwrap().norm() - 1.0).abs());
        }
    }
    assert!(off_sphere > 1e-11, "the edges deviate: {off_sphere:e}");
    assert!(
        q.g0_max >= 0.5 * off_sphere,
        "reported {:e}, measured at least {off_sphere:e}",
        q.g0_max
    );
}

#[test]
fn the_quality_report_meets_the_goals_on_every_example() {
    for (name, fill) in filled_examples() {
        for method in Interior::ALL {
            let patch = fill.patch(method).unwrap();
            let q = quality(&fill, &patch).unwrap();
            assert!(
                q.g0_max <= 1e-4 * q.model_size,
                "{name} {}: G0 {}",
                method.name(),
                q.g0_max
            );
            assert!(
                q.g1_max_degrees <= 0.5,
                "{name} {}: G1 {}",
                method.name(),
                q.g1_max_degrees
            );
            assert!(q.g0_rms <= q.g0_max && q.g1_rms_degrees <= q.g1_max_degrees);
        }
    }
}

#[test]
fn every_interior_method_keeps_the_boundary_triangles_bitwise() {
    for (name, fill) in filled_examples().into_iter().step_by(2) {
        let instant = fill.patch(Interior::Instant).unwrap();
        let grid = instant.grid().clone();
        for method in Interior::ALL {
            let p = fill.patch(method).unwrap();
            for s in grid
                .real_slots()
                .into_iter()
                .filter(|&s| grid.is_boundary(s))
            {
                assert_eq!(
                    p.blocks()[s],
                    instant.blocks()[s],
                    "{name} {}",
                    method.name()
                );
            }
        }
    }
}

#[test]
fn constrained_fairing_lowers_the_energy_and_solves_its_normal_equations() {
    for (name, fill) in filled_examples() {
        if fill.level() < 2 {
            continue; // the prism cap is exact at level 0: no interior vertex
        }
        let instant = fill.patch(Interior::Instant).unwrap();
        let surface =
            Surface::Uniform(UniformSurface::new(UpsSurface::Parametric(instant)).unwrap());
        let f = fair(
            &surface,
            &FairOptions {
                weight: 0.0,
                energy: Energy::HessianJumps,
            },
        )
        .unwrap();
        assert!(
            f.energy_after < f.energy_before,
            "{name}: {} -> {}",
            f.energy_before,
            f.energy_after
        );
        assert!(f.normal_residual < 1e-10, "{name}: {}", f.normal_residual);
        // The fair interior method is this solution.
        let faired = fill.patch(Interior::Fair).unwrap();
        let Surface::Uniform(u) = &f.surface else {
            panic!()
        };
        let UpsSurface::Parametric(expected) = u.ups() else {
            panic!()
        };
        assert_eq!(&faired, expected, "{name}");
    }
}

#[test]
fn fairing_a_quadratic_patch_leaves_it_unchanged() {
    let mut r = crate::test_util::rng(182);
    for sides in 3..=6 {
        let a: [f64; 6] = std::array::from_fn(|_| crate::test_util::uniform(&mut r, -2.0, 2.0));
        let p = quadratic_patch(sides, 3, a);
        let f = interior::fair_interior(&p).unwrap();
        let worst = p
            .blocks()
            .iter()
            .zip(f.blocks())
            .flat_map(|(x, y)| (0..3).map(move |k| (x[k] - y[k]).norm()))
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "{sides} sides: {worst}");
    }
}

/// The straight segment a → b with a constant normal.
fn segment(a: Vector3<f64>, b: Vector3<f64>, n: Vector3<f64>) -> CurveFns {
    CurveFns {
        point: Arc::new(move |t| a + (b - a) * t),
        tangent: Arc::new(move |_| b - a),
        normal: Arc::new(move |_| n),
    }
}

/// The regular polygon with `k` corners on the paraboloid z = (x² + y²)/2 (edges lifted
/// straight lines of the plane), its normals those of the paraboloid.
fn paraboloid_polygon(k: usize) -> Vec<DynCurve> {
    let corner = |i: usize| {
        let a = 2.0 * std::f64::consts::PI * i as f64 / k as f64;
        (a.cos(), a.sin())
    };
    (0..k)
        .map(|i| {
            let ((x0, y0), (x1, y1)) = (corner(i), corner((i + 1) % k));
            let xy = move |t: f64| (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
            Box::new(CurveFns {
                point: Arc::new(move |t| {
                    let (x, y) = xy(t);
                    Vector3::new(x, y, 0.5 * (x * x + y * y))
                }),
                tangent: Arc::new(move |t| {
                    let (x, y) = xy(t);
                    let (dx, dy) = (x1 - x0, y1 - y0);
                    Vector3::new(dx, dy, x * dx + y * dy)
                }),
                normal: Arc::new(move |t| {
                    let (x, y) = xy(t);
                    Vector3::new(-x, -y, 1.0)
                }),
            }) as DynCurve
        })
        .collect()
}

#[test]
fn holes_with_three_to_six_sides_are_filled_within_the_goals() {
    for k in 3..=6 {
        let filled = fill_hole(
            HoleBoundary::new(paraboloid_polygon(k)).unwrap(),
            &FillOptions::default(),
        )
        .unwrap();
        let q = &filled.report;
        assert!(filled.converged, "{k} sides");
        assert!(
            q.g0_max <= 1e-4 * q.model_size && q.g1_max_degrees <= 0.5,
            "{k} sides: {q:?}"
        );
        let ps = filled.patch.to_ps().unwrap();
        let tri = ps.basis().triangulation();
        let worst = (0..tri.vertex_count())
            .map(|i| {
                let p = ps.point(tri.vertex(i)).unwrap();
                (p.z - 0.5 * (p.x * p.x + p.y * p.y)).abs()
            })
            .fold(0.0, f64::max);
        // The triangle, rhombus and hexagon are affine images of the regular polygons, so the
        // lifted boundary is a quadratic of the domain and the patch is the paraboloid
        // itself. The standard pentagon (sides 1, 1, 2, 2, 1) is not: measured 3.1% of the
        // size.
        let bound = if k == 5 { 0.05 } else { 1e-12 };
        assert!(worst < bound * q.model_size, "{k} sides: {worst}");
    }
}

#[test]
fn bad_boundaries_are_refused_naming_the_curve() {
    let z = Vector3::z();
    let (a, b, c) = (Vector3::zeros(), Vector3::x(), Vector3::y());
    let tri = |n2: Vector3<f64>, cc: Vector3<f64>| -> Vec<DynCurve> {
        vec![
            Box::new(segment(a, b, z)),
            Box::new(segment(b, cc, n2)),
            Box::new(segment(cc, a, z)),
        ]
    };
    assert!(HoleBoundary::new(tri(z, c)).is_ok());
    let err = |curves: Vec<DynCurve>| HoleBoundary::new(curves).err().unwrap();
    // Not closed: curve 2 ends away from every other curve.
    let open: Vec<DynCurve> = vec![
        Box::new(segment(a, b, z)),
        Box::new(segment(b, c, z)),
        Box::new(segment(c * 1.1, a, z)),
    ];
    let e = err(open);
    assert!(matches!(e, HoleError::DoNotJoin { curve: 2, .. }), "{e}");
    assert!(e.to_string().contains("curve 2"), "{e}");
    // 2 and 7 curves.
    assert_eq!(
        err(tri(z, c).into_iter().take(2).collect()),
        HoleError::Sides(2)
    );
    assert_eq!(err(paraboloid_polygon(7)), HoleError::Sides(7));
    // A normal along the tangent of curve 2.
    let e = err(tri(c - b, c));
    assert!(
        matches!(e, HoleError::NormalAlongTangent { curve: 2, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("curve 2"), "{e}");
    // NaN.
    let e = err(tri(z, Vector3::new(f64::NAN, 1.0, 0.0)));
    assert!(matches!(e, HoleError::NotFinite { .. }), "{e}");
    assert!(e.to_string().contains("not a finite number"), "{e}");
    // Normals of curve 2 flipped.
    let e = err(tri(-z, c));
    assert!(matches!(e, HoleError::Orientation { .. }), "{e}");
    assert!(
        e.to_string().contains("curves 1 and 2") || e.to_string().contains("curves 2 and 3"),
        "{e}"
    );
    // A joint without a corner: the side a → b split in two.
    let m = (a + b) * 0.5;
    let e = err(vec![
        Box::new(segment(a, m, z)),
        Box::new(segment(m, b, z)),
        Box::new(segment(b, c, z)),
        Box::new(segment(c, a, z)),
    ]);
    assert_eq!(e, HoleError::NoCorner { curves: (1, 2) });
    // Curves given backwards and out of order are chained and oriented.
    let shuffled: Vec<DynCurve> = vec![
        Box::new(segment(a, b, z)),
        Box::new(segment(a, c, z)),
        Box::new(segment(c, b, z)),
    ];
    let hole = HoleBoundary::new(shuffled).unwrap();
    assert_eq!(
        (0..3).map(|k| hole.number(k)).collect::<Vec<_>>(),
        vec![1, 3, 2]
    );
    // Bad tolerances and too many steps.
    let fill = |t: f64, a: f64| HoleFill::new(HoleBoundary::new(tri(z, c)).unwrap(), t, a).err();
    assert_eq!(fill(0.0, 0.1), Some(HoleError::BadTolerance(0.0)));
    assert_eq!(
        fill(f64::NAN, 0.1).map(|e| e.to_string().contains("tolerance")),
        Some(true)
    );
    assert_eq!(fill(1e-4, 90.0), Some(HoleError::BadAngleTolerance(90.0)));
    let opts = FillOptions {
        iterations: Some(MAX_ITERATIONS + 1),
        ..FillOptions::default()
    };
    assert!(matches!(
        fill_hole(HoleBoundary::new(tri(z, c)).unwrap(), &opts),
        Err(HoleError::TooManyIterations { .. })
    ));
}

#[test]
fn a_planar_triangle_is_filled_by_a_planar_patch() {
    let z = Vector3::z();
    let (a, b, c) = (
        Vector3::new(0.0, 0.0, 1.0),
        Vector3::new(2.0, 0.0, 1.0),
        Vector3::new(0.5, 1.5, 1.0),
    );
    let hole = HoleBoundary::new(vec![
        Box::new(segment(a, b, z)),
        Box::new(segment(b, c, z)),
        Box::new(segment(c, a, z)),
    ])
    .unwrap();
    let f = fill_hole(
        hole,
        &FillOptions {
            iterations: Some(3),
            ..FillOptions::default()
        },
    )
    .unwrap();
    for t in f
        .patch
        .blocks()
        .iter()
        .enumerate()
        .filter(|(s, _)| f.patch.grid().is_real(*s))
    {
        for p in t.1 {
            assert!((p.z - 1.0).abs() < 1e-14);
        }
    }
    assert!(f.report.g0_max < 1e-14 && f.report.mean_curvature_squared < 1e-20);
}

#[test]
fn the_sphere_gap_is_two_triangles_meeting_along_the_meridian() {
    let ex = example("hole-sphere").unwrap().unwrap();
    assert_eq!(ex.holes.len(), 2);
    assert_eq!(ex.surroundings.len(), 2);
    // Every boundary curve lies on the unit sphere with radial normals.
    for hole in &ex.holes {
        for k in 0..3 {
            for i in 0..=8 {
                let t = i as f64 / 8.0;
                let p = hole.curves()[k].point(t);
                assert!((p.norm() - 1.0).abs() < 1e-12);
                assert!(hole.unit_normal(k, t).dot(&p) > 1.0 - 1e-12);
            }
        }
    }
}

#[test]
fn gap_between_bisects_automatically() {
    let ex = example("two-curve-gap").unwrap().unwrap();
    let [a, b] = &ex.holes[..] else { panic!() };
    // The automatic bisector joins the same middles as the example's.
    let spec = |h: &HoleBoundary| (0..3).map(|k| h.curves()[k].point(0.0)).collect::<Vec<_>>();
    let (sa, sb) = (spec(a), spec(b));
    let lift = |sign: f64| -> SharedCurve {
        let h = |x: f64, y: f64| 0.25 * (x * x - y * y);
        Arc::new(CurveFns {
            point: Arc::new(move |t| {
                let (x, y) = (
                    sign * (2.0 * t - 1.0),
                    sign * 0.5 * (std::f64::consts::PI * t).sin(),
                );
                Vector3::new(x, y, h(x, y))
            }),
            tangent: Arc::new(move |t| {
                let (x, y) = (
                    sign * (2.0 * t - 1.0),
                    sign * 0.5 * (std::f64::consts::PI * t).sin(),
                );
                let (dx, dy) = (
                    2.0 * sign,
                    sign * 0.5 * std::f64::consts::PI * (std::f64::consts::PI * t).cos(),
                );
                Vector3::new(dx, dy, 0.5 * (x * dx - y * dy))
            }),
            normal: Arc::new(move |t| {
                let (x, y) = (
                    sign * (2.0 * t - 1.0),
                    sign * 0.5 * (std::f64::consts::PI * t).sin(),
                );
                Vector3::new(-0.5 * x, 0.5 * y, 1.0)
            }),
        })
    };
    let [c, d] = gap_between(lift(1.0), lift(-1.0)).unwrap();
    let (sc, sd) = (spec(&c), spec(&d));
    for (x, y) in sa.iter().chain(&sb).zip(sc.iter().chain(&sd)) {
        assert!((x - y).norm() < 1e-12);
    }
    for h in [c, d] {
        let f = fill_hole(h, &FillOptions::default()).unwrap();
        assert!(f.converged && f.report.g1_max_degrees <= 0.5);
    }
    // Two identical arcs enclose nothing: said so, not reported as a vanishing tangent of
    // the internal bisector ("curve 3", which the user never gave).
    let e = gap_between(lift(1.0), lift(1.0)).err().expect("no gap");
    assert!(matches!(e, HoleError::NoGap { .. }), "{e}");
}

/// A UPS patch whose every control triangle is the Hermite data of the quadratic map
/// (x, y) ↦ (x, y, q(x, y)) on the standard polygon with `sides` at `level`.
fn quadratic_patch(sides: usize, level: usize, a: [f64; 6]) -> Ups<Vector3<f64>> {
    use crate::ps::Hermite;
    use crate::ups::{Lattice, LatticePolygon, UpsGrid};
    let mut grid = UpsGrid::new(
        Lattice {
            base: 1.0,
            origin: nalgebra::Point2::origin(),
        },
        LatticePolygon::standard(sides, 1).unwrap(),
    )
    .unwrap();
    for _ in 0..level {
        grid = grid.refined();
    }
    Ups::hermite(grid, |p| {
        let (x, y) = (p.x, p.y);
        Hermite {
            value: Vector3::new(
                x,
                y,
                a[0] * x * x + a[1] * x * y + a[2] * y * y + a[3] * x + a[4] * y + a[5],
            ),
            dx: Vector3::new(1.0, 0.0, 2.0 * a[0] * x + a[1] * y + a[3]),
            dy: Vector3::new(0.0, 1.0, a[1] * x + 2.0 * a[2] * y + a[4]),
        }
    })
}

#[test]
fn bridging_reproduces_quadratics() {
    let mut r = crate::test_util::rng(181);
    for sides in 3..=6 {
        let a: [f64; 6] = std::array::from_fn(|_| crate::test_util::uniform(&mut r, -2.0, 2.0));
        let p = quadratic_patch(sides, 3, a);
        let b = interior::bridged_for_tests(&p);
        let worst = p
            .blocks()
            .iter()
            .zip(b.blocks())
            .flat_map(|(x, y)| (0..3).map(move |k| (x[k] - y[k]).norm()))
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "{sides} sides: {worst}");
    }
}

#[test]
fn the_degenerate_nurbs_patch_is_replaced_with_its_apex_a_singular_corner() {
    let ex = example("degenerate-nurbs").unwrap().unwrap();
    let hole = ex.holes.into_iter().next().unwrap();
    let n = hole.len();
    // Only the apex is singular: the cone has no tangent plane there. Along the ruling at
    // angle θ the cone's normal is (h cos θ, r, h sin θ); the rulings at 0 and 90° span the
    // plane with normal (h, r, h): the mismatch is acos(√(h² + r²) / √(2h² + r²)).
    let singular: Vec<usize> = (0..n).filter(|&k| hole.is_singular_corner(k)).collect();
    assert_eq!(singular.len(), 1);
    let apex = hole.curves()[singular[0]].point(0.0);
    assert!(
        (apex - Vector3::new(0.0, 100.0, 0.0)).norm() < 1e-9,
        "{apex}"
    );
    let (h, r) = (100.0f64, 35.0f64);
    let exact = ((h * h + r * r).sqrt() / (2.0 * h * h + r * r).sqrt())
        .acos()
        .to_degrees();
    let got = hole.corner_mismatch(singular[0]);
    // The normals are taken 1e-6 from the apex, where the NURBS normal is the cross product
    // of a derivative 1e-6 long: 10 digits (measured 2.7e-9°).
    assert!((got - exact).abs() < 1e-7, "{got} against {exact}");
    let filled = fill_hole(hole, &FillOptions::default()).unwrap();
    assert!(filled.converged);
    assert_eq!(filled.report.singular_corners.len(), 1);
    // The patch follows the cone: every boundary sample within G0, and a point in the middle
    // of the patch within 1% of the size of the cone x² + z² = (35 (1 − y/100))².
    let q = &filled.report;
    assert!(
        q.g0_max <= 1e-4 * q.model_size && q.g1_max_degrees <= 0.5,
        "{q:?}"
    );
    let ps = filled.patch.to_ps().unwrap();
    let tri = ps.basis().triangulation();
    let worst = (0..tri.vertex_count())
        .map(|i| {
            let p = ps.point(tri.vertex(i)).unwrap();
            ((p.x * p.x + p.z * p.z).sqrt() - 35.0 * (1.0 - p.y / 100.0)).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst < 0.01 * q.model_size, "{worst}");
}

/// A random unit vector.
fn random_unit(r: &mut rand_chacha::ChaCha8Rng) -> Vector3<f64> {
    loop {
        let v = Vector3::from_fn(|_, _| crate::test_util::uniform(r, -1.0, 1.0));
        if v.norm() > 0.1 && v.norm() < 1.0 {
            return v.normalize();
        }
    }
}

#[test]
fn the_fitting_formulas_are_the_least_squares_solutions() {
    use super::fitting::{alpha_mid, beta_mid};
    use nalgebra::{DMatrix, DVector};
    let mut r = crate::test_util::rng(183);
    for _ in 0..200 {
        let u = |r: &mut _| crate::test_util::uniform(r, -2.0, 2.0);
        // (5.23): min over α_k of |α_iγ_i − α_kγ_k − q_ik|² + |α_kγ_k − α_jγ_j − q_kj|².
        let gk = random_unit(&mut r);
        let (ag_i, ag_j) = (
            random_unit(&mut r) * u(&mut r),
            random_unit(&mut r) * u(&mut r),
        );
        let (q_ik, q_kj) = (
            random_unit(&mut r) * u(&mut r),
            random_unit(&mut r) * u(&mut r),
        );
        let a = DMatrix::from_fn(6, 1, |i, _| if i < 3 { -gk[i] } else { gk[i - 3] });
        let b = DVector::from_fn(6, |i, _| {
            if i < 3 {
                q_ik[i] - ag_i[i]
            } else {
                q_kj[i - 3] + ag_j[i - 3]
            }
        });
        let ls = a.clone().svd(true, true).solve(&b, 1e-15).unwrap()[0];
        let got = alpha_mid(gk, ag_i, ag_j, q_ik, q_kj);
        assert!(
            (got - ls).abs() < 1e-12 * ls.abs().max(1.0),
            "{got} vs {ls}"
        );
        // (5.25): min over β_k, β_ik, β_kj of |β_ik δ_ik − ½(w_i + β_k δ_k)|² +
        // |β_kj δ_kj − ½(β_k δ_k + w_j)|².
        let (dk, dik, dkj) = (
            random_unit(&mut r),
            random_unit(&mut r),
            random_unit(&mut r),
        );
        let (w_i, w_j) = (
            random_unit(&mut r) * u(&mut r),
            random_unit(&mut r) * u(&mut r),
        );
        let a = DMatrix::from_fn(6, 3, |i, c| match (i < 3, c) {
            (true, 0) | (false, 0) => -0.5 * dk[i % 3],
            (true, 1) => dik[i],
            (false, 2) => dkj[i - 3],
            _ => 0.0,
        });
        let b = DVector::from_fn(6, |i, _| {
            if i < 3 {
                0.5 * w_i[i]
            } else {
                0.5 * w_j[i - 3]
            }
        });
        let ls = a.svd(true, true).solve(&b, 1e-15).unwrap()[0];
        let (got, flat) = beta_mid(dk, w_i, w_j, dik, dkj);
        assert!(!flat);
        assert!(
            (got - ls).abs() < 1e-10 * ls.abs().max(1.0),
            "{got} vs {ls}"
        );
    }
}

#[test]
fn random_quadratic_graphs_over_regular_polygons_are_reproduced_by_the_initial_solution() {
    // The triangle, rhombus and hexagon are affine images of the regular 3-, 4- and 6-gon, so
    // the lift of a regular polygon's edges to the graph of a quadratic is a quadratic of the
    // domain along every side, and the initial solution is the quadratic itself.
    let mut r = crate::test_util::rng(184);
    for round in 0..12 {
        let k = [3, 4, 6][round % 3];
        let u = |r: &mut _, lo, hi| crate::test_util::uniform(r, lo, hi);
        let a: [f64; 5] = std::array::from_fn(|_| u(&mut r, -0.5, 0.5));
        let (cx, cy, radius, turn) = (
            u(&mut r, -3.0, 3.0),
            u(&mut r, -3.0, 3.0),
            u(&mut r, 0.2, 5.0),
            u(&mut r, 0.0, 6.3),
        );
        let q =
            move |x: f64, y: f64| a[0] * x * x + a[1] * x * y + a[2] * y * y + a[3] * x + a[4] * y;
        let grad = move |x: f64, y: f64| {
            (
                2.0 * a[0] * x + a[1] * y + a[3],
                a[1] * x + 2.0 * a[2] * y + a[4],
            )
        };
        let corner = move |i: usize| {
            let t = turn + 2.0 * std::f64::consts::PI * i as f64 / k as f64;
            (cx + radius * t.cos(), cy + radius * t.sin())
        };
        let curves: Vec<DynCurve> = (0..k)
            .map(|i| {
                let ((x0, y0), (x1, y1)) = (corner(i), corner((i + 1) % k));
                let xy = move |t: f64| (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
                Box::new(CurveFns {
                    point: Arc::new(move |t| {
                        let (x, y) = xy(t);
                        Vector3::new(x, y, q(x, y))
                    }),
                    tangent: Arc::new(move |t| {
                        let (x, y) = xy(t);
                        let (gx, gy) = grad(x, y);
                        let (dx, dy) = (x1 - x0, y1 - y0);
                        Vector3::new(dx, dy, gx * dx + gy * dy)
                    }),
                    normal: Arc::new(move |t| {
                        let (x, y) = xy(t);
                        let (gx, gy) = grad(x, y);
                        Vector3::new(-gx, -gy, 1.0)
                    }),
                }) as DynCurve
            })
            .collect();
        let hole = HoleBoundary::new(curves).unwrap();
        let mut fill = HoleFill::new(hole, 1e-4, 0.25).unwrap();
        let size = fill.boundary().size();
        let error = |fill: &HoleFill, boundary_only: bool| {
            let ps = fill.patch(Interior::Fair).unwrap().to_ps().unwrap();
            let tri = ps.basis().triangulation();
            (0..tri.vertex_count())
                .filter(|&i| !boundary_only || tri.is_boundary_vertex(i))
                .map(|i| {
                    let p = ps.point(tri.vertex(i)).unwrap();
                    (p.z - q(p.x, p.y)).abs()
                })
                .fold(0.0, f64::max)
        };
        // The initial solution (and its faired interior vertex) is the quadratic.
        let e0 = error(&fill, false);
        assert!(e0 < 1e-12 * size, "{k}-gon at level 0: {e0}");
        // Refinement keeps the boundary vertices on it. Inside it does not: (5.7) makes the
        // new vertices' cross-boundary derivative perpendicular to the edge, which the graph's
        // is not unless its gradient runs along or across the edge (measured up to 0.6 at
        // level 2 on these steep graphs; docs/holes.md).
        fill.step().unwrap();
        fill.step().unwrap();
        let e2 = error(&fill, true);
        assert!(e2 < 1e-12 * size, "{k}-gon at level 2, boundary: {e2}");
    }
}
