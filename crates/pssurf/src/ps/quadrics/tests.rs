use super::*;
use crate::geometry::Triangle2;
use crate::interrogate::Curvature;
use crate::ps::from_bezier::equilateral;
use crate::quadrature::TriangleRule;
use crate::surface::ParametricSurface;
use crate::test_util::*;

use std::f64::consts::{PI, SQRT_2};

/// The NURPS equals the Bézier patch at the same barycentric coordinates.
fn same_surface(b: &RationalBezierTriangle<Vector3<f64>>, n: &Nurps<Vector3<f64>>, seed: u64) {
    let mut r = rng(seed);
    let t = equilateral();
    for _ in 0..50 {
        let tau = random_bary(&mut r);
        let ours = ParametricSurface::point(n, t.point(tau)).unwrap();
        let theirs = b.eval_bary(tau).unwrap();
        assert!(
            (ours - theirs).norm() < 1e-12 * theirs.norm().max(1.0),
            "{ours} vs {theirs}"
        );
    }
}

/// The largest distance to the quadric over random points of every NURPS patch, relative to
/// `size`, and the curvature at those points (skipping the cone's apex, where it is infinite).
fn check_on_quadric(q: &Quadric, size: f64, curvature: impl Fn(Vector3<f64>, &Curvature)) {
    let mut r = rng(1760);
    let t = equilateral();
    let patches = q.nurps_patches().unwrap();
    let beziers = q.bezier_patches().unwrap();
    for (k, (n, b)) in patches.iter().zip(&beziers).enumerate() {
        same_surface(b, n, 1761 + k as u64);
        for _ in 0..60 {
            let p = t.point(random_bary(&mut r));
            let j = n.jet(p).unwrap().jet;
            let d = q.distance(j.value);
            assert!(d < 1e-12 * size, "{} patch {k}: {d:e} off at {p}", q.name());
            let c = Curvature::from_jet(&j).unwrap();
            // The outward normal.
            assert!(
                c.normal.dot(&outward(q, j.value)) > 0.0,
                "{} patch {k}",
                q.name()
            );
            curvature(j.value, &c);
        }
    }
}

/// The outward direction of the quadric's surface at `p`.
fn outward(q: &Quadric, p: Vector3<f64>) -> Vector3<f64> {
    match *q {
        Quadric::Cylinder { .. } => Vector3::new(p.x, p.y, 0.0),
        Quadric::Cone { radius, height } => {
            let rho = p.xy().normalize();
            Vector3::new(height * rho.x, height * rho.y, radius)
        }
        Quadric::Sphere { .. } => p,
    }
}

/// ∫ |s_x × s_y| over the equilateral domain, on 64 sub-triangles with a degree-20 rule.
fn area(n: &Nurps<Vector3<f64>>) -> f64 {
    let rule = TriangleRule::exact_for(20);
    let mut tris = vec![equilateral()];
    for _ in 0..3 {
        tris = tris
            .iter()
            .flat_map(|t| {
                let [a, b, c] = t.v;
                let m = |p: nalgebra::Point2<f64>, q: nalgebra::Point2<f64>| {
                    nalgebra::Point2::from((p.coords + q.coords) / 2.0)
                };
                let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
                [
                    Triangle2::new(a, ab, ca),
                    Triangle2::new(ab, b, bc),
                    Triangle2::new(ca, bc, c),
                    Triangle2::new(ab, bc, ca),
                ]
            })
            .collect();
    }
    tris.iter()
        .map(|t| {
            rule.integrate(t, |tau| {
                let j = n.jet(t.point(tau)).unwrap().jet;
                j.dx.cross(&j.dy).norm()
            })
        })
        .sum()
}

/// Each boundary edge of each patch, as its rational quadratic curve (end, middle, end) with
/// the weights normalised so that the ends have weight 1 (w₁ / √(w₀ w₂), invariant under
/// reparametrisation), either lies on the quadric's border (`border`) or is the edge of
/// exactly one other patch, traversed the other way. So the patches close up.
fn check_watertight(q: &Quadric, border: impl Fn(&[Vector3<f64>; 3]) -> bool) {
    let patches = q.bezier_patches().unwrap();
    let edges: Vec<Vec<([Vector3<f64>; 3], f64)>> = patches
        .iter()
        .map(|b| {
            [[0, 1, 3], [3, 4, 5], [5, 2, 0]]
                .iter()
                .map(|e| {
                    let (p, w) = (b.points(), b.weights());
                    let pts = e.map(|k| p[k]);
                    (pts, w[e[1]] / (w[e[0]] * w[e[2]]).sqrt())
                })
                .collect()
        })
        .collect();
    let scale = patches[0].points()[0].norm().max(1.0);
    let same = |a: &([Vector3<f64>; 3], f64), b: &([Vector3<f64>; 3], f64)| {
        (a.0[0] - b.0[2]).norm() < 1e-12 * scale
            && (a.0[1] - b.0[1]).norm() < 1e-12 * scale
            && (a.0[2] - b.0[0]).norm() < 1e-12 * scale
            && (a.1 - b.1).abs() < 1e-12
    };
    let mut shared = 0;
    for (k, es) in edges.iter().enumerate() {
        for e in es {
            let partners = edges
                .iter()
                .enumerate()
                .filter(|&(l, _)| l != k)
                .flat_map(|(_, o)| o.iter())
                .filter(|o| same(e, o))
                .count();
            if border(&e.0) {
                assert_eq!(
                    partners,
                    0,
                    "{} patch {k}: a border edge is shared",
                    q.name()
                );
            } else {
                assert_eq!(
                    partners,
                    1,
                    "{} patch {k}: edge {:?} unmatched",
                    q.name(),
                    e.0
                );
                shared += 1;
            }
        }
    }
    assert!(
        shared >= patches.len(),
        "{}: only {shared} shared edges",
        q.name()
    );
}

#[test]
fn the_cylinder_patch_has_the_thesis_weights_and_its_table_points_are_off() {
    let mut r = rng(1721);
    for _ in 0..5 {
        let (rad, h) = (uniform(&mut r, 0.1, 10.0), uniform(&mut r, 0.1, 10.0));
        let n = nurps_optimal(&cylinder_patch(rad, h)).unwrap();
        // The thesis' table of weights: 1, (√2 + 1)/3, 1 / 1, (√2 + 1)/3, (√2 + 1)/3 /
        // 1, 1, (√2 + 1)/3.
        let t = (SQRT_2 + 1.0) / 3.0;
        let w = n.weights();
        for (got, want) in [
            (w[0][1], t),
            (w[0][2], 1.0),
            (w[1][1], t),
            (w[1][2], t),
            (w[2][1], 1.0),
            (w[2][2], t),
        ] {
            assert_near!(got, want, 1e-15);
        }
        // The table's points (plain averages) put the surface off the cylinder.
        let mut pts = n.points().to_vec();
        pts[0][1] = Vector3::new(rad, 2.0 / 3.0 * rad, 0.0);
        let table = Nurps::new(n.basis().clone(), pts, n.weights().to_vec()).unwrap();
        let worst = (0..100)
            .map(|_| {
                let p = equilateral().point(random_bary(&mut r));
                let q = ParametricSurface::point(&table, p).unwrap();
                (q.xy().norm() - rad).abs() / rad
            })
            .fold(0.0f64, f64::max);
        assert!(worst > 1e-3, "the table's c_1,2 is off by only {worst}");
    }
}

#[test]
fn the_complete_cylinder_is_exact_closed_and_has_the_right_area() {
    let mut r = rng(1762);
    for _ in 0..3 {
        let (radius, height) = (uniform(&mut r, 0.1, 10.0), uniform(&mut r, 0.1, 10.0));
        let q = Quadric::Cylinder { radius, height };
        check_on_quadric(&q, radius.max(height), |p, c| {
            assert!(p.z > -1e-12 * height && p.z < height * (1.0 + 1e-12));
            assert!(c.gaussian.abs() < 1e-10 / (radius * radius));
            assert_near!(c.mean.abs(), 0.5 / radius, 1e-10 / radius);
        });
        let on_border = |e: &[Vector3<f64>; 3]| {
            e.iter().all(|p| p.z.abs() < 1e-12) || e.iter().all(|p| (p.z - height).abs() < 1e-12)
        };
        check_watertight(&q, on_border);
        let total: f64 = q.nurps_patches().unwrap().iter().map(area).sum();
        assert_near!(total / (2.0 * PI * radius * height), 1.0, 1e-10);
    }
}

#[test]
fn the_cone_patch_reproduces_the_thesis_table_and_the_cone_is_exact_and_closed() {
    let mut r = rng(1763);
    for _ in 0..3 {
        let (radius, height) = (uniform(&mut r, 0.1, 10.0), uniform(&mut r, 0.1, 10.0));
        let n = nurps_optimal(&cone_patch(radius, height)).unwrap();
        // The table: w_{1,2} = w_{2,3} = (√3 + 1)/3, the rest 1; c_{1,3} = (r/3, 0, 2h/3),
        // c_{2,2} = (r/6, √3 r/6, 2h/3); the apex's control triangle is the apex (a cusp).
        let t = (3f64.sqrt() + 1.0) / 3.0;
        let w = n.weights();
        assert_near!(w[0][1], t, 1e-15);
        assert_near!(w[1][2], t, 1e-15);
        for (i, j) in [(0, 0), (0, 2), (1, 0), (1, 1), (2, 0), (2, 1), (2, 2)] {
            assert_near!(w[i][j], 1.0, 1e-15);
        }
        let c = n.points();
        let close = |a: Vector3<f64>, b: Vector3<f64>| (a - b).norm() < 1e-14 * (radius + height);
        assert!(close(
            c[0][2],
            Vector3::new(radius / 3.0, 0.0, 2.0 * height / 3.0)
        ));
        let c22 = Vector3::new(radius / 6.0, 3f64.sqrt() / 6.0 * radius, 2.0 * height / 3.0);
        assert!(close(c[1][1], c22));
        assert!((0..3).all(|j| close(c[2][j], Vector3::new(0.0, 0.0, height))));

        let q = Quadric::Cone { radius, height };
        let slant = radius.hypot(height);
        check_on_quadric(&q, radius.max(height), |p, c| {
            // K = 0; the circle direction has κ = h / (ρ √(r² + h²)), the generators κ = 0.
            let rho = p.xy().norm();
            if rho > 1e-3 * radius {
                let k = height / (rho * slant);
                assert!(c.gaussian.abs() < 1e-9 * k * k);
                assert_near!(c.mean.abs(), 0.5 * k, 1e-9 * k);
            }
        });
        check_watertight(&q, |e| e.iter().all(|p| p.z.abs() < 1e-12));
        let total: f64 = q.nurps_patches().unwrap().iter().map(area).sum();
        assert_near!(total / (PI * radius * slant), 1.0, 1e-9);
    }
}

#[test]
fn the_sphere_patch_is_on_the_sphere_and_its_gap_is_3_124() {
    let mut r = rng(1723);
    for span in [PI / 6.0, PI / 4.0, 0.3] {
        let rad = uniform(&mut r, 0.5, 5.0);
        let b = sphere_patch(rad, span);
        // The lower boundary (τ₃ = 0) rises at most (3.124) above the equator.
        let top = (0..=1000)
            .map(|k| {
                let a = k as f64 / 1000.0;
                b.eval_bary([a, 1.0 - a, 0.0]).unwrap().z
            })
            .fold(0.0f64, f64::max);
        assert_near!(top, rad * sphere_gap(span), 1e-6);
    }
    // b = π/6: the thesis' table of weights, row 1: 1, 5/6, (√2 + 1)/3.
    let n = nurps_optimal(&sphere_patch(1.0, PI / 6.0)).unwrap();
    assert_near!(n.weights()[0][1], 5.0 / 6.0, 1e-15);
    assert_near!(n.weights()[0][2], (SQRT_2 + 1.0) / 3.0, 1e-15);
}

#[test]
fn the_sphere_is_exact_closed_but_for_its_equator_band_which_shrinks_with_more_sectors() {
    let mut r = rng(1764);
    let mut gaps = Vec::new();
    for sectors in [3, 4, 6, 12, 24] {
        let radius = uniform(&mut r, 0.5, 5.0);
        let q = Quadric::Sphere { radius, sectors };
        check_on_quadric(&q, radius, |_, c| {
            assert_near!(c.gaussian * radius * radius, 1.0, 1e-10);
            assert_near!(c.mean.abs() * radius, 1.0, 1e-10);
        });
        // The lower edges (τ₃ = 0) of the northern patches and the upper ones of the southern
        // patches border the open band.
        let band = |e: &[Vector3<f64>; 3]| e[0].z.abs() < 1e-12 && e[2].z.abs() < 1e-12;
        check_watertight(&q, band);
        assert_eq!(q.bezier_patches().unwrap().len(), 2 * sectors);
        gaps.push(q.gap() / radius);
    }
    assert!(gaps.windows(2).all(|g| g[1] < g[0]), "{gaps:?}");
    assert!(gaps[4] < 0.01, "24 sectors leave {:.4} r", gaps[4]);
}

#[test]
fn bad_sizes_are_refused() {
    for q in [
        Quadric::Cylinder {
            radius: 0.0,
            height: 1.0,
        },
        Quadric::Cylinder {
            radius: 1.0,
            height: f64::NAN,
        },
        Quadric::Cone {
            radius: 1.0,
            height: -1.0,
        },
        Quadric::Cone {
            radius: f64::INFINITY,
            height: 1.0,
        },
        Quadric::Sphere {
            radius: 1e300,
            sectors: 6,
        },
    ] {
        assert!(
            matches!(q.nurps_patches(), Err(QuadricError::BadSize { .. })),
            "{q:?}"
        );
    }
    for sectors in [0, 2, MAX_SECTORS + 1] {
        let q = Quadric::Sphere {
            radius: 1.0,
            sectors,
        };
        assert_eq!(q.validate(), Err(QuadricError::BadSectors(sectors)));
    }
}
