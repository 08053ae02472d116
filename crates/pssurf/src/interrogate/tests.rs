//! Curvature against closed forms: graphs of quadratics (reproduced exactly by PS-splines),
//! paraboloids, a rational patch on a sphere, invariance under rigid motions, affine
//! reparametrisation and orientation reversal; sampling and fairness integrals.

use std::sync::Arc;

use nalgebra::{Matrix2, Point2, Rotation3, Vector2, Vector3};

use super::*;
use crate::bezier::index::multi_indices;
use crate::bezier::{BezierTriangle, Jet, RationalBezierTriangle};
use crate::geometry::Triangle2;
use crate::ps::{Hermite, PsBasis, PsSpline};
use crate::surface::{
    ControlId, ControlNet, ControlPoint, ParametricSurface, PieceKind, PiecewiseSurface, Surface,
};
use crate::test_util::*;
use crate::triangulation::Triangulation;

/// A quadratic f(x, y) = a x² + b xy + c y² + d x + e y + g.
#[derive(Clone, Copy, Debug)]
struct Quadratic([f64; 6]);

impl Quadratic {
    fn random(r: &mut rand_chacha::ChaCha8Rng) -> Self {
        Quadratic(std::array::from_fn(|_| uniform(r, -1.5, 1.5)))
    }
    fn hermite(&self, p: Point2<f64>) -> Hermite<f64> {
        let [a, b, c, d, e, g] = self.0;
        let (x, y) = (p.x, p.y);
        Hermite {
            value: a * x * x + b * x * y + c * y * y + d * x + e * y + g,
            dx: 2.0 * a * x + b * y + d,
            dy: b * x + 2.0 * c * y + e,
        }
    }
    /// K, H, κ1, κ2 and the parameter direction of κ1 of the graph, from the classical
    /// formulas for z = f(x, y) — written independently of the code under test.
    fn closed_form(&self, p: Point2<f64>) -> (f64, f64, f64, f64, Vector2<f64>) {
        let [a, b, c, ..] = self.0;
        let h = self.hermite(p);
        let (fx, fy, fxx, fxy, fyy) = (h.dx, h.dy, 2.0 * a, b, 2.0 * c);
        let w2 = 1.0 + fx * fx + fy * fy;
        let w = w2.sqrt();
        let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
        let hm =
            ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy) / (2.0 * w2 * w);
        let disc = (hm * hm - k).max(0.0).sqrt();
        let (k1, k2) = (hm + disc, hm - disc);
        // (L − κE) du + (M − κF) dv = 0 with E = 1 + fx², F = fx fy, L = fxx / w, M = fxy / w.
        let (e, f, g) = (1.0 + fx * fx, fx * fy, 1.0 + fy * fy);
        let (l, m, n) = (fxx / w, fxy / w, fyy / w);
        let cand1 = Vector2::new(m - k1 * f, -(l - k1 * e));
        let cand2 = Vector2::new(n - k1 * g, -(m - k1 * f));
        let d = if cand1.norm() > cand2.norm() {
            cand1
        } else {
            cand2
        };
        (k, hm, k1, k2, d.normalize())
    }
}

/// The degree-2 Bézier form of a quadratic map from its values (exact: vertex ordinates are
/// values, an edge ordinate is 2 f(midpoint) − (f(Va) + f(Vb))/2).
fn quadratic_bezier<V: crate::vector::Vector>(
    t: Triangle2,
    f: impl Fn(Point2<f64>) -> V,
) -> Vec<V> {
    let corner = |k: usize| {
        let mut b = [0.0; 3];
        b[k] = 1.0;
        f(t.point(b))
    };
    multi_indices(2)
        .map(|l| {
            let p = f(t.point(l.map(|x| x as f64 / 2.0)));
            if l.contains(&2) {
                p
            } else {
                let ones: Vec<usize> = (0..3).filter(|&k| l[k] == 1).collect();
                p * 2.0 - (corner(ones[0]) + corner(ones[1])) * 0.5
            }
        })
        .collect()
}

fn parallel(a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    (a.x * b.y - a.y * b.x).abs() / (a.norm() * b.norm())
}

#[test]
fn graphs_of_quadratics_have_the_closed_form_curvature_on_every_mesh() {
    let mut r = rng(401);
    for (name, tri) in meshes::catalogue(402) {
        let basis = Arc::new(PsBasis::optimal(tri).unwrap());
        for _ in 0..3 {
            let q = Quadratic::random(&mut r);
            let s = Surface::Functional(
                PsSpline::interpolate(basis.clone(), |p| q.hermite(p)).unwrap(),
            );
            let t = basis.triangulation();
            for _ in 0..200 {
                let k = (uniform(&mut r, 0.0, t.triangle_count() as f64) as usize)
                    .min(t.triangle_count() - 1);
                let p = t.triangle_geometry(k).point(random_bary(&mut r));
                let jet = s.jet(p).unwrap();
                let c = Curvature::from_jet(&jet.jet).unwrap();
                let (k_, h, k1, k2, d1) = q.closed_form(p);
                // Second derivatives are second differences of Bézier ordinates divided by
                // the squared height h of the sub-triangle, so rounding is of order ε/h²
                // (measured: below 8 ε/h² on every mesh). Well-shaped pieces meet 1e-10;
                // hull slivers of random Delaunay meshes (h ≈ 4e-4) need ε/h² more.
                let crate::surface::PieceShape::Triangle(piece) = s.piece_shape(jet.piece) else {
                    unreachable!("PS pieces are triangles")
                };
                let height = 2.0 * piece.area() / piece.diameter();
                let tol = 1e-10f64.max(32.0 * f64::EPSILON / (height * height));
                assert_near!(c.gaussian, k_, tol, "{name} at {p:?}");
                assert_near!(c.mean, h, tol, "{name}");
                // κ1,2 = H ± √(H² − K) is ill-conditioned near umbilics, in the reference as
                // much as anywhere: compare the symmetric functions, and κ1, κ2 themselves
                // where they are apart.
                assert_near!(c.k1 + c.k2, 2.0 * h, tol, "{name}");
                assert_near!(c.k1 * c.k2, k_, tol, "{name}");
                if k1 - k2 > 1e-3 {
                    assert_near!(c.k1, k1, 1e2 * tol, "{name}");
                    assert_near!(c.k2, k2, 1e2 * tol, "{name}");
                }
                assert_near!(c.absolute(), k1.abs() + k2.abs(), tol, "{name}");
                if c.k1 - c.k2 > 1e-3 {
                    assert!(
                        parallel(c.dir1_uv, d1) < 1e3 * tol,
                        "{name}: {:?} vs {d1:?}",
                        c.dir1_uv
                    );
                }
            }
        }
    }
}

#[test]
fn principal_directions_are_orthonormal_eigendirections() {
    let mut r = rng(403);
    let mut compared = 0;
    for _ in 0..300 {
        let jet = random_jet(&mut r);
        let Ok(c) = Curvature::from_jet(&jet) else {
            continue;
        };
        compared += 1;
        let f = FundamentalForms::from_jet(&jet).unwrap();
        assert_near!(c.dir1.norm(), 1.0, 1e-13);
        assert_near!(c.dir2.norm(), 1.0, 1e-13);
        assert_near!(c.dir1.dot(&c.dir2), 0.0, 1e-13);
        assert_near!(c.dir1.dot(&c.normal), 0.0, 1e-13);
        assert_near!(c.dir1.cross(&c.dir2).dot(&c.normal), 1.0, 1e-13);
        for (d_uv, d, k) in [(c.dir1_uv, c.dir1, c.k1), (c.dir2_uv, c.dir2, c.k2)] {
            // s maps the parameter direction onto the space direction...
            let t = jet.dx * d_uv.x + jet.dy * d_uv.y;
            assert_near!(t.normalize().dot(&d), 1.0, 1e-10);
            // ...which is an eigendirection: its normal curvature is the principal curvature.
            assert_near!(f.normal_curvature(d_uv), k, 1e-10);
        }
        // Euler's formula against II/I for random directions.
        for _ in 0..5 {
            let d_uv = random_dir(&mut r);
            let t = jet.dx * d_uv.x + jet.dy * d_uv.y;
            let theta = t.dot(&c.dir2).atan2(t.dot(&c.dir1));
            assert_near!(
                c.normal_curvature_at_angle(theta),
                f.normal_curvature(d_uv),
                1e-10
            );
            assert_near!(c.normal_curvature(t), f.normal_curvature(d_uv), 1e-10);
        }
    }
    // Random jets are singular (s_u ∥ s_v) with probability zero; allow a few.
    assert!(compared >= 295, "only {compared} of 300 jets were regular");
}

/// A random jet of a regular surface.
fn random_jet(r: &mut rand_chacha::ChaCha8Rng) -> Jet<Vector3<f64>> {
    let mut v = || {
        Vector3::new(
            uniform(r, -1.0, 1.0),
            uniform(r, -1.0, 1.0),
            uniform(r, -1.0, 1.0),
        )
    };
    Jet {
        value: v(),
        dx: v(),
        dy: v(),
        dxx: v(),
        dxy: v(),
        dyy: v(),
    }
}

#[test]
fn paraboloids_as_parametric_patches() {
    // s(u, v) = (u, v, a(u² ± v²)) as a degree-2 Bézier triangle: at the origin K = ±4a²,
    // H = a(1 ± 1), and elsewhere the graph formulas hold.
    let mut r = rng(404);
    let t = Triangle2::new(
        Point2::new(-1.0, -1.0),
        Point2::new(1.5, -0.5),
        Point2::new(0.0, 1.2),
    );
    for sign in [1.0, -1.0] {
        let a = uniform(&mut r, 0.2, 2.0);
        let f = move |p: Point2<f64>| Vector3::new(p.x, p.y, a * (p.x * p.x + sign * p.y * p.y));
        let patch = BezierTriangle::new(t, 2, quadratic_bezier(t, f));
        let c = Curvature::from_jet(&patch.jet(Point2::origin())).unwrap();
        assert_near!(c.gaussian, sign * 4.0 * a * a, 1e-13);
        assert_near!(c.mean, a * (1.0 + sign), 1e-13);
        assert_near!(c.k1, 2.0 * a, 1e-13);
        assert_near!(c.k2, 2.0 * a * sign, 1e-13);
        let q = Quadratic([a, 0.0, sign * a, 0.0, 0.0, 0.0]);
        for _ in 0..50 {
            let p = t.point(random_bary(&mut r));
            let c = Curvature::from_jet(&patch.jet(p)).unwrap();
            let (k, h, k1, k2, _) = q.closed_form(p);
            assert_near!(c.gaussian, k, 1e-12);
            assert_near!(c.mean, h, 1e-12);
            assert_near!(c.k1, k1, 1e-12);
            assert_near!(c.k2, k2, 1e-12);
        }
    }
}

/// A rational quadratic triangle on the sphere of radius `rad` about `centre`: the inverse
/// stereographic projection (2u, 2v, 1 − u² − v²) / (1 + u² + v²) has quadratic numerator
/// and denominator, so any parameter triangle maps to a rational quadratic patch.
pub(super) fn sphere_patch(
    t: Triangle2,
    rad: f64,
    centre: Vector3<f64>,
) -> RationalBezierTriangle<Vector3<f64>> {
    let hom = |p: Point2<f64>| {
        let (u, v) = (p.x, p.y);
        let w = 1.0 + u * u + v * v;
        nalgebra::Vector4::new(
            rad * 2.0 * u + centre.x * w,
            rad * 2.0 * v + centre.y * w,
            rad * (1.0 - u * u - v * v) + centre.z * w,
            w,
        )
    };
    let ords = quadratic_bezier(t, hom);
    let weights: Vec<f64> = ords.iter().map(|h| h.w).collect();
    let points = ords.iter().map(|h| h.xyz() / h.w).collect();
    RationalBezierTriangle::try_new(t, 2, points, weights).unwrap()
}

#[test]
fn a_rational_patch_on_a_sphere_has_curvature_one_over_r_squared_everywhere() {
    let mut r = rng(405);
    let t = Triangle2::new(
        Point2::new(-0.6, -0.5),
        Point2::new(0.7, -0.3),
        Point2::new(0.1, 0.8),
    );
    for _ in 0..5 {
        let rad = uniform(&mut r, 0.1, 10.0);
        let centre = Vector3::new(uniform(&mut r, -3.0, 3.0), 1.0, -2.0);
        let s = sphere_patch(t, rad, centre);
        for _ in 0..100 {
            let p = t.point(random_bary(&mut r));
            let j = s.jet(p).unwrap();
            assert_near!((j.value - centre).norm(), rad, 1e-13);
            let c = Curvature::from_jet(&j).unwrap();
            // s_u × s_v points outwards (at u = v = 0 it is (0, 0, 4R²)); the sphere bends
            // away from the normal, so H = κ1 = κ2 = −1/R and K = 1/R².
            assert_near!(c.normal.dot(&(j.value - centre)) / rad, 1.0, 1e-12);
            assert_near!(c.gaussian * rad * rad, 1.0, 1e-11);
            assert_near!(c.mean * rad, -1.0, 1e-11);
            assert_near!(c.k1 * rad, -1.0, 1e-11);
            assert_near!(c.k2 * rad, -1.0, 1e-11);
            assert!(c.is_umbilic(1e-9), "{c:?}");
        }
    }
}

#[test]
fn rational_derivatives_agree_with_finite_differences() {
    // An independent check of the rational jet: central differences of the values only.
    let mut r = rng(406);
    let t = Triangle2::new(
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.1),
        Point2::new(0.2, 0.9),
    );
    for _ in 0..10 {
        let pts: Vec<Vector3<f64>> = (0..6).map(|_| random_vec3(&mut r)).collect();
        let w: Vec<f64> = (0..6).map(|_| uniform(&mut r, 0.2, 5.0)).collect();
        let s = RationalBezierTriangle::try_new(t, 2, pts, w).unwrap();
        let p = t.point([0.3, 0.35, 0.35]);
        let j = s.jet(p).unwrap();
        let h = 1e-4;
        let f = |dx: f64, dy: f64| s.eval(Point2::new(p.x + dx, p.y + dy)).unwrap();
        let fd_dx = (f(h, 0.0) - f(-h, 0.0)) / (2.0 * h);
        let fd_dy = (f(0.0, h) - f(0.0, -h)) / (2.0 * h);
        let fd_dxx = (f(h, 0.0) - 2.0 * f(0.0, 0.0) + f(-h, 0.0)) / (h * h);
        let fd_dyy = (f(0.0, h) - 2.0 * f(0.0, 0.0) + f(0.0, -h)) / (h * h);
        let fd_dxy = (f(h, h) - f(h, -h) - f(-h, h) + f(-h, -h)) / (4.0 * h * h);
        let scale = 1.0 + j.dxx.norm() + j.dyy.norm();
        assert!((j.dx - fd_dx).norm() < 1e-6 * scale);
        assert!((j.dy - fd_dy).norm() < 1e-6 * scale);
        assert!((j.dxx - fd_dxx).norm() < 1e-4 * scale);
        assert!((j.dyy - fd_dyy).norm() < 1e-4 * scale);
        assert!((j.dxy - fd_dxy).norm() < 1e-4 * scale);
        let fd = Jet {
            value: j.value,
            dx: fd_dx,
            dy: fd_dy,
            dxx: fd_dxx,
            dxy: fd_dxy,
            dyy: fd_dyy,
        };
        if let (Ok(a), Ok(b)) = (Curvature::from_jet(&j), Curvature::from_jet(&fd)) {
            let tol = 1e-4 * (1.0 + a.k1.abs() + a.k2.abs()).powi(2);
            assert!((a.gaussian - b.gaussian).abs() < tol, "{a:?} {b:?}");
            assert!((a.mean - b.mean).abs() < tol);
        }
    }
}

#[test]
fn curvature_is_invariant_under_rigid_motions() {
    let mut r = rng(407);
    let mut compared = 0;
    for _ in 0..200 {
        let j = random_jet(&mut r);
        let Ok(c) = Curvature::from_jet(&j) else {
            continue;
        };
        compared += 1;
        let rot = Rotation3::from_euler_angles(
            uniform(&mut r, 0.0, 6.3),
            uniform(&mut r, 0.0, 6.3),
            uniform(&mut r, 0.0, 6.3),
        );
        let shift = Vector3::new(3.0, -2.0, 7.0);
        let moved = Jet {
            value: rot * j.value + shift,
            dx: rot * j.dx,
            dy: rot * j.dy,
            dxx: rot * j.dxx,
            dxy: rot * j.dxy,
            dyy: rot * j.dyy,
        };
        let m = Curvature::from_jet(&moved).unwrap();
        let scale = 1.0 + c.k1.abs().max(c.k2.abs());
        assert_near!(m.gaussian, c.gaussian, 1e-11 * scale * scale);
        assert_near!(m.mean, c.mean, 1e-11 * scale);
        assert_near!(m.k1, c.k1, 1e-11 * scale);
        assert_near!(m.k2, c.k2, 1e-11 * scale);
        assert!((m.normal - rot * c.normal).norm() < 1e-12);
        if !c.is_umbilic(1e-6) {
            assert!(
                (m.dir1 - rot * c.dir1)
                    .norm()
                    .min((m.dir1 + rot * c.dir1).norm())
                    < 1e-8
            );
        }
    }
    assert!(compared >= 195, "only {compared} of 200 jets were regular");
}

#[test]
fn curvature_is_invariant_under_affine_reparametrisation_and_orientation_flips_h() {
    // A Bézier triangle is affinely invariant: the same ordinates over the image of the
    // domain under an affine map φ describe s ∘ φ⁻¹. Curvature at corresponding points
    // agrees; a map with det < 0 reverses the orientation, which keeps K and flips H.
    let mut r = rng(408);
    let (mut maps, mut compared) = (0, 0);
    for _ in 0..50 {
        let t = random_triangle(&mut r);
        let pts: Vec<Vector3<f64>> = (0..10).map(|_| random_vec3(&mut r)).collect();
        let s = BezierTriangle::new(t, 3, pts.clone());
        let a = Matrix2::new(
            uniform(&mut r, -2.0, 2.0),
            uniform(&mut r, -2.0, 2.0),
            uniform(&mut r, -2.0, 2.0),
            uniform(&mut r, -2.0, 2.0),
        );
        if a.determinant().abs() < 0.3 {
            continue; // nearly singular maps magnify rounding
        }
        maps += 1;
        let b = Vector2::new(0.4, -1.1);
        let phi = |p: Point2<f64>| Point2::from(a * p.coords + b);
        let t2 = Triangle2::new(phi(t.v[0]), phi(t.v[1]), phi(t.v[2]));
        let s2 = BezierTriangle::new(t2, 3, pts);
        let flip = a.determinant() < 0.0;
        for _ in 0..10 {
            let bary = random_bary(&mut r);
            let (Ok(c1), Ok(c2)) = (
                Curvature::from_jet(&s.jet(t.point(bary))),
                Curvature::from_jet(&s2.jet(t2.point(bary))),
            ) else {
                continue;
            };
            compared += 1;
            let scale = 1.0 + c1.k1.abs().max(c1.k2.abs());
            assert_near!(c2.gaussian, c1.gaussian, 1e-9 * scale * scale);
            let sign = if flip { -1.0 } else { 1.0 };
            assert_near!(c2.mean, sign * c1.mean, 1e-9 * scale);
            let (k1, k2) = if flip {
                (-c1.k2, -c1.k1)
            } else {
                (c1.k1, c1.k2)
            };
            assert_near!(c2.k1, k1, 1e-9 * scale);
            assert_near!(c2.k2, k2, 1e-9 * scale);
            assert!((c2.normal - sign * c1.normal).norm() < 1e-9);
        }
    }
    // det(A) is a product of uniform numbers; |det| ≥ 0.3 for most draws.
    assert!(maps >= 30, "only {maps} of 50 affine maps used");
    assert!(
        compared >= 10 * maps - 5,
        "{compared} points for {maps} maps"
    );
}

#[test]
fn singular_points_are_reported_not_nan() {
    let j = Jet {
        value: Vector3::zeros(),
        dx: Vector3::new(1.0, 2.0, 3.0),
        dy: Vector3::new(2.0, 4.0, 6.0),
        dxx: Vector3::new(0.0, 0.0, 1.0),
        dxy: Vector3::zeros(),
        dyy: Vector3::zeros(),
    };
    assert!(Curvature::from_jet(&j).is_err());
    let zero = Jet {
        dx: Vector3::zeros(),
        ..j
    };
    let e = Curvature::from_jet(&zero).unwrap_err();
    assert!(e.to_string().contains("undefined"), "{e}");
    let nan = Jet {
        dx: Vector3::new(f64::NAN, 0.0, 0.0),
        ..j
    };
    assert!(Curvature::from_jet(&nan).is_err());
}

#[test]
fn quantity_names_round_trip() {
    for q in CurvatureQuantity::ALL {
        assert_eq!(CurvatureQuantity::parse(q.short_name()), Some(q));
    }
    assert_eq!(
        CurvatureQuantity::parse("Gaussian"),
        Some(CurvatureQuantity::Gaussian)
    );
    assert_eq!(CurvatureQuantity::parse("nope"), None);
    // Legends carry the unit: K is a product of two curvatures.
    assert_eq!(
        CurvatureQuantity::Gaussian.titled(),
        "Gaussian curvature K [1/length²]"
    );
    assert_eq!(
        CurvatureQuantity::K1.titled(),
        "principal curvature k1 [1/length]"
    );
}

/// A PS surface interpolating a non-polynomial function on a small Delaunay mesh.
pub(super) fn wavy_surface(seed: u64) -> Surface {
    wavy_surface_on(seed, 30)
}

/// sin(3x) cos(2y) interpolated by a PS-spline on `n` random points of the unit square.
pub(super) fn wavy_surface_on(seed: u64, n: usize) -> Surface {
    let mut r = rng(seed);
    let tri = meshes::uniform_square(&mut r, n);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: (3.0 * p.x).sin() * (2.0 * p.y).cos(),
            dx: 3.0 * (3.0 * p.x).cos() * (2.0 * p.y).cos(),
            dy: -2.0 * (3.0 * p.x).sin() * (2.0 * p.y).sin(),
        })
        .unwrap(),
    )
}

#[test]
fn sampling_gives_surface_points_and_each_pieces_own_curvature() {
    let s = wavy_surface(409);
    for level in [0, 2] {
        let sampled = sample_patches(&s, level, true);
        let n = 1usize << level;
        let pieces = s.piece_count();
        assert_eq!(sampled.mesh.positions.len(), pieces * (n + 1) * (n + 2) / 2);
        assert_eq!(sampled.mesh.triangles.len(), pieces * n * n);
        for v in (0..sampled.mesh.positions.len()).step_by(7) {
            let uv = sampled.mesh.uvs[v];
            let j = s.jet(uv).unwrap().jet;
            assert!((sampled.mesh.positions[v] - j.value).norm() < 1e-13);
            assert!((sampled.mesh.normals[v] - s.normal(uv).unwrap().unwrap()).norm() < 1e-12);
            // The curvature is that of the vertex's own piece.
            let k = sampled.patch[v] as usize;
            let frame = s.piece_shape(k).frame().unwrap();
            let own = s.piece_jet(k, &frame.at_uv(uv));
            let c = Curvature::from_jet(&own).unwrap();
            assert_near!(sampled.curvature[v].gaussian, c.gaussian, 1e-11);
        }
        // Triangles face along the normal: for a graph, upwards.
        for t in &sampled.mesh.triangles {
            let [a, b, c] = t.map(|k| sampled.mesh.positions[k as usize]);
            assert!((b - a).cross(&(c - a)).z > 0.0, "{t:?}");
        }
    }
    // A C¹ surface: the same parameter on two pieces has the same point but, in general,
    // another curvature — the jumps the plots must show.
    let sampled = sample_patches(&s, 0, true);
    let mut jumps = 0;
    let mut by_uv = std::collections::HashMap::new();
    for (v, uv) in sampled.mesh.uvs.iter().enumerate() {
        let key = (uv.x.to_bits(), uv.y.to_bits());
        if let Some(&w) = by_uv.get(&key) {
            let (w, v): (usize, usize) = (w, v);
            assert!((sampled.mesh.positions[w] - sampled.mesh.positions[v]).norm() < 1e-12);
            let (a, b) = (sampled.curvature[w], sampled.curvature[v]);
            if (a.mean - b.mean).abs() > 1e-6 {
                jumps += 1;
            }
        } else {
            by_uv.insert(key, v);
        }
    }
    assert!(
        jumps > 10,
        "curvature should jump across PS edges ({jumps})"
    );
}

#[test]
fn a_local_edit_changes_only_the_molecule_pieces_and_sample_pieces_resamples_them() {
    let mut s = wavy_surface(411);
    let level = 1;
    let per = vertices_per_piece(PieceKind::Triangle, level);
    let before = sample_patches(&s, level, true);
    let vertex = 17;
    let changes: Vec<(ControlId, ControlPoint)> = [0.3, -0.2, 0.1]
        .iter()
        .enumerate()
        .map(|(j, dz)| {
            let id = ControlId(3 * vertex + j);
            let mut p = s.control_point(id).unwrap();
            p.position.z += dz;
            (id, p)
        })
        .collect();
    let molecule = s.set_control_points(&changes).unwrap();
    let expected: Vec<usize> = {
        let mut m: Vec<usize> = s
            .ps_basis()
            .unwrap()
            .triangulation()
            .molecule(vertex)
            .iter()
            .flat_map(|&t| (0..6).map(move |sub| 6 * t as usize + sub))
            .collect();
        m.sort_unstable();
        m
    };
    assert_eq!(molecule, expected, "the support is the vertex's molecule");
    let after = sample_patches(&s, level, true);
    let local = sample_pieces(&s, level, true, &molecule);
    assert_eq!(local.mesh.positions.len(), molecule.len() * per);
    for (j, &k) in molecule.iter().enumerate() {
        for v in 0..per {
            let (a, b) = (k * per + v, j * per + v);
            // Bit-identical to sampling the whole surface.
            assert_eq!(after.mesh.positions[a], local.mesh.positions[b]);
            assert_eq!(after.mesh.normals[a], local.mesh.normals[b]);
            assert_eq!(after.mesh.uvs[a], local.mesh.uvs[b]);
            assert_eq!(after.curvature[a], local.curvature[b]);
            assert_eq!(local.patch[b] as usize, k);
        }
    }
    for t in &local.mesh.triangles {
        assert!(t.iter().all(|&i| (i as usize) < local.mesh.positions.len()));
    }
    // Outside the molecule nothing moved (local support, Definition 2.23).
    let mut moved = 0;
    for k in 0..s.piece_count() {
        let inside = molecule.contains(&k);
        for v in k * per..(k + 1) * per {
            let d = (after.mesh.positions[v] - before.mesh.positions[v]).norm();
            if inside {
                moved += usize::from(d > 1e-6);
            } else {
                assert!(d < 1e-14, "piece {k} moved by {d}");
            }
        }
    }
    assert!(moved > 0, "the edit moved nothing");
}

#[test]
fn fairness_integrals_of_a_paraboloid_match_closed_forms() {
    // z = (x² + y²)/2 over the unit square, reproduced exactly. Its Gauss map covers the
    // solid angle of a unit square seen from distance 1 at a corner: ∫ K dA = π/6. The
    // thin-plate energy is ∫∫ 1 + 0 + 1 = 2, the area ∫∫ √(1 + x² + y²) has a closed form.
    let tri = Triangulation::try_new(
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let s = Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: 0.5 * (p.x * p.x + p.y * p.y),
            dx: p.x,
            dy: p.y,
        })
        .unwrap(),
    );
    let f = fairness(&s, 20);
    let i = f.integrals;
    assert_near!(i.gaussian, std::f64::consts::PI / 6.0, 1e-10);
    assert_near!(i.thin_plate, 2.0, 1e-13);
    // ∫∫_[0,1]² √(1 + x² + y²) dx dy = (2/3)·(√3/2)… the known value 1.280789045…
    // (computed independently by 2-D Gauss–Legendre below).
    let g = crate::quadrature::gauss_legendre(40);
    let area: f64 = g
        .iter()
        .flat_map(|&(x, wx)| {
            g.iter()
                .map(move |&(y, wy)| wx * wy * (1.0 + x * x + y * y).sqrt())
        })
        .sum();
    assert_near!(i.area, area, 1e-12);
    // κ1 = κ2 = … and ∫ (κ1² + κ2²) = ∫ 4H² − 2K.
    assert_near!(
        i.principal_squared,
        4.0 * i.mean_squared - 2.0 * i.gaussian,
        1e-12
    );
    assert_near!(i.gaussian_abs, i.gaussian, 1e-12);
    assert_eq!(f.singular_nodes, 0);
    // Distribution: K = (1 + x² + y²)^(−2) lies in [1/9, 1], largest at the origin corner.
    let (name, k) = &f.stats[0];
    assert_eq!(name, "K");
    assert!(k.min >= 1.0 / 9.0 - 1e-12 && k.max <= 1.0 + 1e-12, "{k:?}");
    assert!(k.percentiles.windows(2).all(|w| w[0] <= w[1]));
    assert!(k.min <= k.percentiles[0] && k.percentiles[4] <= k.max);
}

#[test]
fn fairness_of_a_plane_is_zero() {
    let mut r = rng(410);
    let tri = meshes::uniform_square(&mut r, 25);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let s = Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: 0.3 * p.x - 0.2 * p.y + 1.0,
            dx: 0.3,
            dy: -0.2,
        })
        .unwrap(),
    );
    let f = fairness(&s, DEFAULT_QUADRATURE_DEGREE);
    let area = s.ps_basis().unwrap().triangulation().area() * (1.0f64 + 0.09 + 0.04).sqrt();
    assert_near!(f.integrals.area, area, 1e-12);
    for v in [
        f.integrals.mean_squared,
        f.integrals.gaussian,
        f.integrals.gaussian_abs,
        f.integrals.thin_plate,
    ] {
        assert!(v.abs() < 1e-20, "{v:e}");
    }
}

/// κ1, κ2 from K = κ1κ2 and H = (κ1 + κ2)/2 alone give random principal curvatures back
/// (the roots of κ² − 2Hκ + K), to 1e-13 of their size when they are apart by a tenth of it.
#[test]
fn principal_curvatures_from_gaussian_and_mean_are_the_roots() {
    let mut r = crate::test_util::rng(71);
    let mut close = 0;
    for _ in 0..10_000 {
        let scale = 10f64.powf(crate::test_util::uniform(&mut r, -6.0, 6.0));
        let a = crate::test_util::uniform(&mut r, -1.0, 1.0) * scale;
        let b = crate::test_util::uniform(&mut r, -1.0, 1.0) * scale;
        let (k1, k2) = (a.max(b), a.min(b));
        let size = k1.abs().max(k2.abs());
        if k1 - k2 < 0.1 * size {
            close += 1; // near an umbilic the root is ill-conditioned: counted, skipped
            continue;
        }
        let p = PrincipalCurvatures::from_gaussian_mean(k1 * k2, 0.5 * (k1 + k2));
        assert!((p.k1 - k1).abs() <= 1e-13 * size, "{} vs {k1}", p.k1);
        assert!((p.k2 - k2).abs() <= 1e-13 * size, "{} vs {k2}", p.k2);
    }
    assert!(close < 1_500, "{close} of 10000 skipped");
    // At an umbilic a rounding-negative discriminant gives κ1 = κ2 = H, never NaN.
    let p = PrincipalCurvatures::from_gaussian_mean(0.1 * 0.1 + 1e-18, 0.1);
    assert_eq!((p.k1, p.k2), (0.1, 0.1));
}

/// Steep graphs: on z = s (a x² + b xy + c y²) with s up to 1e12 the tangents s_u, s_v are
/// nearly parallel, and EG − F² computed as a difference cancels to nothing (K and H came
/// out infinite at s = 1e9). With EG − F² = |s_u × s_v|² they match the graph's closed forms
/// K = (f_xx f_yy − f_xy²)/W⁴, H = ((1 + f_y²) f_xx − 2 f_x f_y f_xy + (1 + f_x²) f_yy)/(2W³),
/// W² = 1 + f_x² + f_y², to 1e-12 relative (|H| relative to the largest term).
#[test]
fn curvature_of_steep_graphs_matches_the_closed_forms() {
    let mut r = rng(93);
    for scale in [1.0, 1e3, 1e6, 1e9, 1e12] {
        for _ in 0..50 {
            let [a, b, c] = [0; 3].map(|_| uniform(&mut r, 0.2, 1.5));
            let (x, y) = (uniform(&mut r, 0.1, 1.0), uniform(&mut r, 0.1, 1.0));
            let (fx, fy) = (scale * (2.0 * a * x + b * y), scale * (b * x + 2.0 * c * y));
            let (fxx, fxy, fyy) = (2.0 * a * scale, b * scale, 2.0 * c * scale);
            let jet = Jet {
                value: Vector3::new(x, y, scale * (a * x * x + b * x * y + c * y * y)),
                dx: Vector3::new(1.0, 0.0, fx),
                dy: Vector3::new(0.0, 1.0, fy),
                dxx: Vector3::new(0.0, 0.0, fxx),
                dxy: Vector3::new(0.0, 0.0, fxy),
                dyy: Vector3::new(0.0, 0.0, fyy),
            };
            let w2 = 1.0 + fx * fx + fy * fy;
            let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
            let terms = [
                (1.0 + fy * fy) * fxx,
                2.0 * fx * fy * fxy,
                (1.0 + fx * fx) * fyy,
            ];
            let h = (terms[0] - terms[1] + terms[2]) / (2.0 * w2 * w2.sqrt());
            let h_size = terms.iter().map(|t| t.abs()).sum::<f64>() / (2.0 * w2 * w2.sqrt());
            let c = Curvature::from_jet(&jet).expect("a graph is regular");
            assert!(
                (c.gaussian - k).abs() <= 1e-12 * k.abs(),
                "s = {scale}: K {} vs {k}",
                c.gaussian
            );
            assert!(
                (c.mean - h).abs() <= 1e-12 * h_size,
                "s = {scale}: H {} vs {h}",
                c.mean
            );
        }
    }
}
