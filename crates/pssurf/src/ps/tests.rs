//! Randomized tests of the PS-spline identities over a catalogue of triangulations.

use std::sync::Arc;

use nalgebra::{Point2, SVector, Vector2, Vector3, Vector4};
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use rand_chacha::ChaCha8Rng;

use super::net::{self, NET_LEN, SUB_ORDINATES};
use super::*;
use crate::bezier::{Jet, continuity};
use crate::quadrature::TriangleRule;
use crate::test_util::meshes::catalogue;
use crate::test_util::*;
use crate::triangulation::Triangulation;

/// f = a + b x + c y + d x² + e xy + g y², with exact value, gradient and Hessian.
#[derive(Clone, Copy, Debug)]
struct Quadratic([f64; 6]);

impl Quadratic {
    fn random(r: &mut ChaCha8Rng) -> Self {
        Quadratic(std::array::from_fn(|_| uniform(r, -1.0, 1.0)))
    }
    fn jet(&self, p: Point2<f64>) -> Jet<f64> {
        let [a, b, c, d, e, g] = self.0;
        let (x, y) = (p.x, p.y);
        Jet {
            value: a + b * x + c * y + d * x * x + e * x * y + g * y * y,
            dx: b + 2.0 * d * x + e * y,
            dy: c + e * x + 2.0 * g * y,
            dxx: 2.0 * d,
            dxy: e,
            dyy: 2.0 * g,
        }
    }
    fn hermite(&self, p: Point2<f64>) -> Hermite<f64> {
        let j = self.jet(p);
        Hermite {
            value: j.value,
            dx: j.dx,
            dy: j.dy,
        }
    }
}

/// Random points of the domain: uniform in each triangle, plus vertices, edge points and
/// split points (the places where pieces meet).
fn sample_points(
    t: &Triangulation,
    basis: &PsBasis,
    r: &mut ChaCha8Rng,
    per_triangle: usize,
) -> Vec<Point2<f64>> {
    let mut out = Vec::new();
    for s in 0..t.triangle_count() {
        let g = t.triangle_geometry(s);
        for _ in 0..per_triangle {
            out.push(g.point(random_bary(r)));
        }
        out.push(basis.refinement().z(s));
        for c in 0..3 {
            out.push(basis.refinement().edge_point(t, s, c));
        }
    }
    out.extend_from_slice(t.vertices());
    out
}

/// Random Hermite data (values and gradients in [−1, 1]) for n vertices.
pub(super) fn random_hermite(r: &mut ChaCha8Rng, n: usize) -> Vec<Hermite<f64>> {
    (0..n)
        .map(|_| Hermite {
            value: uniform(r, -1.0, 1.0),
            dx: uniform(r, -1.0, 1.0),
            dy: uniform(r, -1.0, 1.0),
        })
        .collect()
}

/// The Hermite spline with random data (values and gradients in [−1, 1]) on the optimal
/// basis of `tri`.
pub(super) fn random_hermite_spline(tri: Triangulation, seed: u64) -> PsSpline<f64> {
    let data = random_hermite(&mut rng(seed), tri.vertex_count());
    let basis = PsBasis::optimal(tri).expect("a valid triangulation");
    PsSpline::hermite(Arc::new(basis), &data).expect("valid Hermite data")
}

/// Asserts that `grid` (row-major, `xs` along rows) holds `s`'s values to 1e-13 where
/// point-by-point evaluation finds the point, and `outside` (or NaN for NaN) elsewhere;
/// returns how many points were inside and outside.
pub(super) fn assert_grid_agrees(
    s: &PsSpline<f64>,
    xs: &[f64],
    ys: &[f64],
    grid: &[f64],
    outside: f64,
) -> (usize, usize) {
    let mut ev = s.evaluator();
    let (mut inside, mut out) = (0, 0);
    for (i, &x) in xs.iter().enumerate() {
        for (j, &y) in ys.iter().enumerate() {
            let got = grid[i * ys.len() + j];
            match ev.value(Point2::new(x, y)) {
                Some(v) => {
                    inside += 1;
                    let close = (got - v).abs() <= 1e-13 * (1.0 + v.abs());
                    assert!(close, "({x}, {y}): {got} vs {v}");
                }
                None => {
                    out += 1;
                    let same = got == outside || (got.is_nan() && outside.is_nan());
                    assert!(same, "({x}, {y}) is outside, got {got}");
                }
            }
        }
    }
    (inside, out)
}

pub(crate) fn bases(seed: u64) -> Vec<(&'static str, Arc<PsBasis>)> {
    catalogue(seed)
        .into_iter()
        .map(|(name, t)| (name, Arc::new(PsBasis::optimal(t).expect(name))))
        .collect()
}

/// The domain's size, for relative tolerances.
fn scale(t: &Triangulation) -> f64 {
    let (lo, hi) = t.bounds();
    (hi - lo).norm().max(1.0)
}

#[test]
fn basis_is_a_convex_partition_of_unity_with_local_support() {
    let mut r = rng(40);
    for seed in 0..3 {
        for (name, basis) in bases(seed) {
            let t = basis.triangulation();
            // All nine basis functions that live on a triangle at once: unit vectors in R⁹ as
            // control values of its three vertices.
            let mut unit = vec![[SVector::<f64, 9>::zeros(); 3]; t.vertex_count()];
            let mut worst_sum: f64 = 0.0;
            let mut worst_neg: f64 = 0.0;
            for s in 0..t.triangle_count() {
                let v = t.triangle(s);
                for c in 0..3 {
                    for j in 0..3 {
                        unit[v[c]][j] = SVector::<f64, 9>::zeros();
                        unit[v[c]][j][3 * c + j] = 1.0;
                    }
                }
                let netv = basis.net(s, &unit);
                for _ in 0..20 {
                    let p = t.triangle_geometry(s).point(random_bary(&mut r));
                    let loc = basis.sub_locate(crate::triangulation::Location {
                        triangle: s,
                        bary: t.bary(s, p),
                    });
                    let idx = SUB_ORDINATES[loc.sub];
                    let q: Vec<_> = idx.iter().map(|&k| netv[k]).collect();
                    let b =
                        crate::bezier::triangle::quadratic_jet(&q, loc.bary, loc.dx, loc.dy, 2.0)
                            .value;
                    worst_sum = worst_sum.max((b.sum() - 1.0).abs());
                    worst_neg = worst_neg.min(b.min());
                }
            }
            assert!(worst_sum < 1e-13, "{name}: Σ B − 1 = {worst_sum:e}");
            assert!(worst_neg > -1e-13, "{name}: min B = {worst_neg:e}");

            // Local support: a single basis function is zero on triangles outside its molecule.
            let i = r_index(&mut r, t.vertex_count());
            for j in 0..3 {
                let mut c = vec![[0.0; 3]; t.vertex_count()];
                c[i][j] = 1.0;
                let b = PsSpline::new(basis.clone(), c).unwrap();
                for s in 0..t.triangle_count() {
                    let inside = t.corner_of(s, i).is_some();
                    let nonzero = b.net(s).iter().any(|&x| x != 0.0);
                    assert_eq!(nonzero, inside, "{name}: B_{i}^{j} on triangle {s}");
                }
            }
        }
    }
}

fn r_index(r: &mut ChaCha8Rng, n: usize) -> usize {
    (uniform(r, 0.0, n as f64) as usize).min(n - 1)
}

#[test]
fn linear_and_quadratic_functions_are_reproduced_exactly() {
    let mut r = rng(41);
    for seed in 0..3 {
        for (name, basis) in bases(seed) {
            let t = basis.triangulation();
            let h = scale(t);
            // Linear precision (2.47)–(2.48): c_ij = X_ij reproduces x.
            let xs: Vec<[f64; 3]> = (0..t.vertex_count())
                .map(|i| basis.control_xy(i).map(|q| q.x))
                .collect();
            let ys: Vec<[f64; 3]> = (0..t.vertex_count())
                .map(|i| basis.control_xy(i).map(|q| q.y))
                .collect();
            let sx = PsSpline::new(basis.clone(), xs).unwrap();
            let sy = PsSpline::new(basis.clone(), ys).unwrap();
            let f = Quadratic::random(&mut r);
            let s = PsSpline::interpolate(basis.clone(), |p| f.hermite(p)).unwrap();
            let fscale = 1.0 + h * h;
            let mut ev = s.evaluator();
            for p in sample_points(t, &basis, &mut r, 5) {
                assert!((sx.eval(p).unwrap() - p.x).abs() < 1e-13 * h, "{name}");
                assert!((sy.eval(p).unwrap() - p.y).abs() < 1e-13 * h, "{name}");
                let loc = ev.locate(p).unwrap();
                let got = s.jet_at(&loc).jet;
                let want = f.jet(p);
                // Derivatives of order k come from ordinates of size ~|f| through k factors
                // |∇σ| ~ 1/(sub-triangle size): the forward-error scale is |f| g^k.
                let g = [loc.dx, loc.dy]
                    .iter()
                    .map(|d| d.iter().map(|x| x.abs()).sum::<f64>())
                    .fold(1.0, f64::max);
                let tol = |k: i32| 4e-15 * fscale * g.powi(k);
                assert!(
                    (got.value - want.value).abs() < tol(0),
                    "{name} value at {p:?}"
                );
                assert!((got.dx - want.dx).abs() < tol(1), "{name} dx");
                assert!((got.dy - want.dy).abs() < tol(1), "{name} dy");
                for (a, b) in [
                    (got.dxx, want.dxx),
                    (got.dxy, want.dxy),
                    (got.dyy, want.dyy),
                ] {
                    assert!(
                        (a - b).abs() < tol(2),
                        "{name} Hessian {a} vs {b}, g = {g:e}"
                    );
                }
            }
        }
    }
}

/// Nets straight from Hermite data ([`PsSpline::hermite_direct`]) agree to rounding with the
/// nets computed from the control values (2.45), on circumscribed as on optimal
/// PS-triangles, and reproduce quadratics (against the closed form). Circumscribed
/// triangles contain their PS-points exactly.
#[test]
fn hermite_nets_from_the_data_do_not_depend_on_the_ps_triangles() {
    let mut r = rng(47);
    for seed in 0..3 {
        for (name, optimal) in bases(seed) {
            let t = optimal.triangulation();
            let circumscribed = Arc::new(
                PsBasis::with_refinement(
                    t.clone(),
                    optimal.refinement().clone(),
                    &PsTriangleChoice::Circumscribed,
                )
                .expect(name),
            );
            for i in 0..t.vertex_count() {
                let q = circumscribed.ps_triangle(i);
                for p in ps_triangles::ps_points(t, optimal.refinement(), i) {
                    assert!(q.contains_exact(p), "{name}: vertex {i}");
                }
            }
            let h = scale(t);
            let f = Quadratic::random(&mut r);
            let quadratic: Vec<Hermite<f64>> = t.vertices().iter().map(|&p| f.hermite(p)).collect();
            let data = random_hermite(&mut r, t.vertex_count());
            for d in [&quadratic, &data] {
                let direct = PsSpline::hermite_direct(circumscribed.clone(), d).unwrap();
                for basis in [&circumscribed, &optimal] {
                    let from_values = PsSpline::hermite(basis.clone(), d).unwrap();
                    for tr in 0..t.triangle_count() {
                        for (a, b) in direct.net(tr).iter().zip(from_values.net(tr)) {
                            assert!((a - b).abs() < 1e-14 * (1.0 + h), "{name}: {a} vs {b}");
                        }
                    }
                }
            }
            let s = PsSpline::hermite_direct(circumscribed.clone(), &quadratic).unwrap();
            for p in sample_points(t, &optimal, &mut r, 3) {
                let want = f.jet(p).value;
                assert!(
                    (s.eval(p).unwrap() - want).abs() < 4e-15 * (1.0 + h * h),
                    "{name} at {p:?}"
                );
            }
        }
    }
}

#[test]
fn splines_are_c1_across_every_edge_of_the_refinement() {
    let mut r = rng(42);
    for seed in 0..2 {
        for (name, basis) in bases(seed) {
            let t = basis.triangulation();
            let coeffs: Vec<[Vector3<f64>; 3]> = random_vec3_triples(&mut r, t.vertex_count());
            let s = PsSpline::new(basis.clone(), coeffs).unwrap();
            for tr in 0..t.triangle_count() {
                let p: Vec<_> = (0..6).map(|k| s.patch(tr, k)).collect();
                // Inside the triangle: consecutive sub-triangles share an edge (R_c Z or V_c Z).
                for k in 0..6 {
                    let (a, b) = (&p[k], &p[(k + 1) % 6]);
                    let c = continuity(a, b, 1e-12).unwrap();
                    assert!(
                        c.order >= Some(1),
                        "{name} tri {tr} subs {k},{}: {c:?}",
                        (k + 1) % 6
                    );
                    check_sampled_c1(&s, a, b, &mut r, name);
                }
                // Across the edges of Δ: the sub-triangles on V_c R_c and its mirror image.
                for c in 0..3 {
                    let Some(nb) = t.neighbor(tr, refinement::edge_to_local(c)) else {
                        continue;
                    };
                    let vc = t.triangle(tr)[c];
                    let d = t.corner_of(nb, vc).unwrap();
                    // In the neighbour the edge runs V_{c+1} → V_c, i.e. it is edge d − 1 there,
                    // and the piece at V_c is (R, V_c, Z): sub 2(d − 1) + 1.
                    let other = s.patch(nb, 2 * ((d + 2) % 3) + 1);
                    let cont = continuity(&p[2 * c], &other, 1e-12).unwrap();
                    assert!(
                        cont.order >= Some(1),
                        "{name}: tri {tr} edge {c} vs {nb}: {cont:?}"
                    );
                    check_sampled_c1(&s, &p[2 * c], &other, &mut r, name);
                }
            }
        }
    }
}

/// Values and gradients of two patches agree at random points of their common edge.
fn check_sampled_c1(
    _s: &PsSpline<Vector3<f64>>,
    a: &crate::bezier::BezierTriangle<Vector3<f64>>,
    b: &crate::bezier::BezierTriangle<Vector3<f64>>,
    r: &mut ChaCha8Rng,
    name: &str,
) {
    let same = |p: Point2<f64>| b.domain().v.iter().any(|&q| (q - p).norm() < 1e-12);
    let shared: Vec<_> = a.domain().v.iter().copied().filter(|&p| same(p)).collect();
    assert_eq!(shared.len(), 2, "{name}");
    for _ in 0..3 {
        let t = uniform(r, 0.0, 1.0);
        let p = Point2::from(shared[0].coords * t + shared[1].coords * (1.0 - t));
        let (ja, jb) = (a.jet(p), b.jet(p));
        let size = 1.0 + ja.dx.norm() + ja.dy.norm();
        assert!(
            (ja.value - jb.value).norm() < 1e-13 * size,
            "{name}: values differ"
        );
        assert!(
            (ja.dx - jb.dx).norm() < 1e-11 * size,
            "{name}: x-derivatives differ {:e}",
            (ja.dx - jb.dx).norm()
        );
        assert!(
            (ja.dy - jb.dy).norm() < 1e-11 * size,
            "{name}: y-derivatives differ {:e}",
            (ja.dy - jb.dy).norm()
        );
    }
}

#[test]
fn control_triangles_are_tangent_at_their_vertex() {
    let mut r = rng(43);
    for (name, basis) in bases(7) {
        let t = basis.triangulation();
        let coeffs: Vec<[Vector3<f64>; 3]> = random_vec3_triples(&mut r, t.vertex_count());
        let s = PsSpline::new(basis.clone(), coeffs.clone()).unwrap();
        for i in 0..t.vertex_count() {
            let alpha = basis.alpha(i);
            let at_vertex: Vector3<f64> = (0..3).map(|j| coeffs[i][j] * alpha[j]).sum();
            for &tr in t.molecule(i) {
                let tr = tr as usize;
                let c = t.corner_of(tr, i).unwrap();
                for sub in [2 * c, 2 * ((c + 2) % 3) + 1] {
                    let j = s.jet_on_patch(PatchId::new(tr, sub), t.vertex(i));
                    // The tangent point is s(V_i) = Σ α_ij c_ij ...
                    assert!((j.value - at_vertex).norm() < 1e-13, "{name}");
                    // ... the derivatives are Σ β c and Σ γ c ...
                    let (b, g) = (basis.beta(i), basis.gamma(i));
                    let sx: Vector3<f64> = (0..3).map(|k| coeffs[i][k] * b[k]).sum();
                    let sy: Vector3<f64> = (0..3).map(|k| coeffs[i][k] * g[k]).sum();
                    let size = 1.0 + sx.norm() + sy.norm();
                    assert!(
                        (j.dx - sx).norm() < 1e-11 * size && (j.dy - sy).norm() < 1e-11 * size,
                        "{name}"
                    );
                    // ... and the control triangle lies in the tangent plane (Theorem 2.5).
                    let n = j.dx.cross(&j.dy);
                    if n.norm() > 1e-8 {
                        let n = n.normalize();
                        for k in 0..3 {
                            let off = (coeffs[i][k] - j.value).dot(&n);
                            assert!(
                                off.abs() < 1e-11 * (1.0 + (coeffs[i][k] - j.value).norm()),
                                "{name}: off-plane {off:e}"
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn ordinates_next_to_a_vertex_lie_on_its_control_plane() {
    // The derivation of (2.54)–(2.57): the ordinates s, u, v, w next to V_c are values of the
    // tangent plane at V_c at their domain points.
    let mut r = rng(44);
    for (name, basis) in bases(8) {
        let t = basis.triangulation();
        let data = random_hermite(&mut r, t.vertex_count());
        let s = PsSpline::hermite(basis.clone(), &data).unwrap();
        for tr in 0..t.triangle_count() {
            let v = t.triangle(tr);
            let n = s.net(tr);
            let z = basis.refinement().z(tr);
            for c in 0..3 {
                let h = data[v[c]];
                let vc = t.vertex(v[c]);
                let plane = |p: Point2<f64>| h.value + h.dx * (p.x - vc.x) + h.dy * (p.y - vc.y);
                let rn = basis.refinement().edge_point(t, tr, c);
                let rp = basis.refinement().edge_point(t, tr, (c + 2) % 3);
                let mid = crate::geometry::midpoint;
                let pts = [
                    (net::s(c), vc),
                    (net::u(c), mid(vc, rn)),
                    (net::v(c), mid(vc, rp)),
                    (net::w(c), mid(vc, z)),
                ];
                for (k, p) in pts {
                    assert!(
                        (n[k] - plane(p)).abs() < 1e-13 * (1.0 + scale(t)),
                        "{name}: ordinate {k}"
                    );
                }
            }
        }
    }
}

#[test]
fn hermite_data_is_interpolated_and_2_45_agrees() {
    let mut r = rng(45);
    for (name, basis) in bases(9) {
        let t = basis.triangulation();
        let data = random_hermite(&mut r, t.vertex_count());
        let s = PsSpline::hermite(basis.clone(), &data).unwrap();
        for i in 0..t.vertex_count() {
            let j = s.jet(t.vertex(i)).unwrap().jet;
            assert!((j.value - data[i].value).abs() < 1e-13, "{name}");
            assert!(
                (j.dx - data[i].dx).abs() < 1e-11 && (j.dy - data[i].dy).abs() < 1e-11,
                "{name}"
            );
            // (2.45) literally, with d_i = β1 γ2 − γ1 β2 (2.46).
            let (a, b, g) = (basis.alpha(i), basis.beta(i), basis.gamma(i));
            let d = b[0] * g[1] - g[0] * b[1];
            let (f, fx, fy) = (data[i].value, data[i].dx, data[i].dy);
            let c = [
                f + fx * (a[1] * g[0] + g[1] * (1.0 - a[0])) / d
                    + fy * (-a[1] * b[0] - b[1] * (1.0 - a[0])) / d,
                f + fx * (-a[0] * g[1] - g[0] * (1.0 - a[1])) / d
                    + fy * (a[0] * b[1] + b[0] * (1.0 - a[1])) / d,
                f + fx * (-a[0] * g[1] + g[0] * a[1]) / d + fy * (a[0] * b[1] - b[0] * a[1]) / d,
            ];
            for k in 0..3 {
                let want = s.coefficients()[i][k];
                assert!(
                    (c[k] - want).abs() < 1e-11 * (1.0 + want.abs()),
                    "{name}: (2.45) c_{i}{k} = {} vs {want}",
                    c[k]
                );
            }
            // Corollary 2.4: |α| = 1, |β| = |γ| = 0, and d_i = 1/e_i (2.46).
            assert!((a.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(b.iter().sum::<f64>().abs() < 1e-12 * b.iter().map(|x| x.abs()).sum::<f64>());
            assert!((d * basis.ps_triangle(i).det() - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn integrals_are_exact() {
    let mut r = rng(46);
    for (name, basis) in bases(10) {
        let t = basis.triangulation();
        let f = Quadratic::random(&mut r);
        let s = PsSpline::interpolate(basis.clone(), |p| f.hermite(p)).unwrap();
        let rule = TriangleRule::exact_for(2);
        let exact: f64 = (0..t.triangle_count())
            .map(|k| {
                let g = t.triangle_geometry(k);
                rule.integrate(&g, |b| f.jet(g.point(b)).value)
            })
            .sum();
        assert!(
            (s.integral() - exact).abs() < 1e-12 * (1.0 + exact.abs()),
            "{name}: {} vs {exact}",
            s.integral()
        );
        // Σ ∫ B_i^j = area, and ∫ s = Σ c_ij ∫ B_ij.
        let bi = basis.basis_integrals();
        let total: f64 = bi.iter().flatten().sum();
        assert!((total - t.area()).abs() < 1e-13 * t.area(), "{name}");
        let via_basis: f64 = bi
            .iter()
            .zip(s.coefficients())
            .map(|(b, c)| (0..3).map(|j| b[j] * c[j]).sum::<f64>())
            .sum();
        assert!(
            (via_basis - s.integral()).abs() < 1e-12 * (1.0 + exact.abs()),
            "{name}"
        );
        assert!(bi.iter().flatten().all(|&x| x > 0.0));
    }
}

#[test]
fn nurps_with_equal_weights_is_the_ps_surface_and_matches_the_homogeneous_form() {
    let mut r = rng(47);
    for (name, basis) in bases(11) {
        let t = basis.triangulation();
        let pts = random_vec3_triples(&mut r, t.vertex_count());
        let poly = PsSpline::new(basis.clone(), pts.clone()).unwrap();
        let equal =
            Nurps::new(basis.clone(), pts.clone(), vec![[2.5; 3]; t.vertex_count()]).unwrap();
        let weights: Vec<[f64; 3]> = (0..t.vertex_count())
            .map(|_| std::array::from_fn(|_| 10f64.powf(uniform(&mut r, -1.0, 1.0))))
            .collect();
        let rat = Nurps::new(basis.clone(), pts.clone(), weights.clone()).unwrap();
        // The homogeneous 4-D PS-spline (3.33)–(3.34), evaluated and divided: independent.
        let hom: Vec<[Vector4<f64>; 3]> = pts
            .iter()
            .zip(&weights)
            .map(|(p, w)| {
                std::array::from_fn(|j| {
                    Vector4::new(p[j].x * w[j], p[j].y * w[j], p[j].z * w[j], w[j])
                })
            })
            .collect();
        let hom = PsSpline::new(basis.clone(), hom).unwrap();
        for p in sample_points(t, &basis, &mut r, 3) {
            // On the same patch: at vertices and edges of Δ* neighbouring patches differ in
            // their second derivatives.
            let loc = basis.locate_any(p).unwrap();
            let a = equal.jet_at(&loc).jet;
            let b = poly.jet_at(&loc).jet;
            assert!(
                a.max_diff(&b) < 1e-11 * (1.0 + b.dxx.norm() + b.dyy.norm()),
                "{name}: {:e} at {p:?}\n{a:?}\n{b:?}",
                a.max_diff(&b)
            );
            let got = rat.jet_at(&loc).jet;
            let h = hom.jet_at(&loc).jet;
            let w = h.value.w;
            let v3 = |v: Vector4<f64>| Vector3::new(v.x, v.y, v.z);
            let b = v3(h.value) / w;
            let bx = (v3(h.dx) - b * h.dx.w) / w;
            let by = (v3(h.dy) - b * h.dy.w) / w;
            let bxx = (v3(h.dxx) - bx * (2.0 * h.dx.w) - b * h.dxx.w) / w;
            let bxy = (v3(h.dxy) - bx * h.dy.w - by * h.dx.w - b * h.dxy.w) / w;
            let byy = (v3(h.dyy) - by * (2.0 * h.dy.w) - b * h.dyy.w) / w;
            let want = Jet {
                value: b,
                dx: bx,
                dy: by,
                dxx: bxx,
                dxy: bxy,
                dyy: byy,
            };
            let size = 1.0
                + want.dx.norm()
                + want.dy.norm()
                + want.dxx.norm()
                + want.dxy.norm()
                + want.dyy.norm();
            assert!(
                got.max_diff(&want) < 1e-11 * size,
                "{name}: {:e}",
                got.max_diff(&want)
            );
        }
    }
}

/// Weights 1e30 and 1e-30 at two vertices in three (inside the documented range): on the edges of the
/// pieces point location gives barycentric coordinates like −1e-17, and −1e-17 × 1e30
/// outweighed 1e-30, so evaluation panicked ("positive weights inside the domain") on files
/// that load as valid. Every point of the domain, on the pieces' edges too, now evaluates.
#[test]
fn nurps_with_extreme_weights_evaluates_everywhere_in_its_domain() {
    let mut r = rng(49);
    let mut on_edges = 0;
    for (name, basis) in bases(13) {
        let t = basis.triangulation();
        let pts = random_vec3_triples(&mut r, t.vertex_count());
        let weights: Vec<[f64; 3]> = (0..t.vertex_count())
            .map(|i| match i % 3 {
                0 => [1e30, 1e-30, 1e30],
                1 => [1e-30, 1e30, 1e-30],
                _ => [1.0; 3],
            })
            .collect();
        let rat = Nurps::new(basis.clone(), pts, weights).unwrap();
        let mut points = sample_points(t, &basis, &mut r, 3);
        // Points on the rays Z P and the edges P P' of every triangle's pieces.
        for s in 0..t.triangle_count() {
            let ref_ = basis.refinement();
            let p: Vec<Point2<f64>> = (0..3)
                .flat_map(|c| [t.vertex(t.triangle(s)[c]), ref_.edge_point(t, s, c)])
                .collect();
            let z = ref_.z(s);
            for k in 0..6 {
                for (a, b) in [(z, p[k]), (p[k], p[(k + 1) % 6])] {
                    points.push(a + (b - a) * uniform(&mut r, 0.0, 1.0));
                    on_edges += 1;
                }
            }
        }
        for p in points {
            let j = rat.jet(p).expect("inside the domain").jet;
            let finite = [j.value, j.dx, j.dy]
                .iter()
                .all(|v| v.iter().all(|x| x.is_finite()));
            assert!(finite, "{name} at {p:?}: {j:?}");
        }
    }
    assert!(on_edges > 1000, "{on_edges} points on edges");
}

fn big(x: f64) -> BigRational {
    BigRational::from_float(x).unwrap()
}

#[test]
fn nurps_stays_accurate_with_weights_up_to_1e6() {
    // Reference: exact rational arithmetic on the same basis-function coefficients
    // (Σ c w B / Σ w B with the stencil and the sub-triangle coordinates as exact numbers).
    let mut r = rng(48);
    let mut worst: f64 = 0.0;
    for (name, basis) in bases(12).into_iter().take(3) {
        let t = basis.triangulation();
        let pts = random_vec3_triples(&mut r, t.vertex_count());
        let weights: Vec<[f64; 3]> = (0..t.vertex_count())
            .map(|_| std::array::from_fn(|_| 1e6f64.powf(uniform(&mut r, 0.0, 1.0))))
            .collect();
        let rat = Nurps::new(basis.clone(), pts.clone(), weights.clone()).unwrap();
        for k in 0..60 {
            let tr = k % t.triangle_count();
            let p = t.triangle_geometry(tr).point(random_bary(&mut r));
            let loc = basis.locate(p, tr).unwrap();
            let got = rat.jet_at(&loc).jet.value;
            let st = basis.stencil(loc.triangle);
            let v = t.triangle(loc.triangle);
            // Exact homogeneous net (numerator and denominator) from the stencil.
            let hom = |c: usize, j: usize| -> [BigRational; 4] {
                let (p, w) = (pts[v[c]][j], big(weights[v[c]][j]));
                [big(p.x) * &w, big(p.y) * &w, big(p.z) * &w, w]
            };
            let comb = |coef: &[f64], vals: &[[BigRational; 4]]| -> [BigRational; 4] {
                std::array::from_fn(|d| {
                    coef.iter()
                        .zip(vals)
                        .fold(BigRational::zero(), |acc, (c, x)| acc + big(*c) * &x[d])
                })
            };
            let mut n: Vec<[BigRational; 4]> =
                vec![std::array::from_fn(|_| BigRational::zero()); NET_LEN];
            for c in 0..3 {
                let ctrl: Vec<_> = (0..3).map(|j| hom(c, j)).collect();
                for (row, k) in st.rows[c]
                    .iter()
                    .zip([net::s(c), net::u(c), net::v(c), net::w(c)])
                {
                    n[k] = comb(row, &ctrl);
                }
            }
            for c in 0..3 {
                let d = (c + 1) % 3;
                let l = st.lambda[c];
                n[net::r(c)] = comb(&[l, 1.0 - l], &[n[net::u(c)].clone(), n[net::v(d)].clone()]);
                n[net::th(c)] = comb(&[l, 1.0 - l], &[n[net::w(c)].clone(), n[net::w(d)].clone()]);
            }
            n[net::OM] = comb(
                &st.z,
                &[
                    n[net::w(0)].clone(),
                    n[net::w(1)].clone(),
                    n[net::w(2)].clone(),
                ],
            );
            let q: Vec<_> = SUB_ORDINATES[loc.sub]
                .iter()
                .map(|&k| n[k].clone())
                .collect();
            let tb: Vec<BigRational> = loc.bary.iter().map(|&x| big(x)).collect();
            // Quadratic Bernstein sum.
            let bern = [
                &tb[0] * &tb[0],
                big(2.0) * &tb[0] * &tb[1],
                big(2.0) * &tb[0] * &tb[2],
                &tb[1] * &tb[1],
                big(2.0) * &tb[1] * &tb[2],
                &tb[2] * &tb[2],
            ];
            let val: [BigRational; 4] = std::array::from_fn(|d| {
                (0..6).fold(BigRational::zero(), |acc, k| acc + &bern[k] * &q[k][d])
            });
            for d in 0..3 {
                let exact = (&val[d] / &val[3]).to_f64().unwrap();
                worst = worst.max((got[d] - exact).abs());
            }
        }
        assert!(
            worst < 1e-14,
            "{name}: worst error {worst:e} for control points in [-1, 1]"
        );
    }
}

#[test]
fn bad_inputs_are_rejected() {
    let p = |x, y| Point2::new(x, y);
    // Centroids whose joining segment misses the common edge.
    let t = Triangulation::new(
        vec![p(0., 0.), p(1., 0.), p(-5., 0.1), p(-5., -0.1)],
        vec![[0, 1, 2], [1, 0, 3]],
    );
    let e = PsRefinement::new(&t, SplitRule::Centroid).unwrap_err();
    assert!(
        matches!(
            e,
            PsError::EdgePointOutside {
                edge: (0, 1) | (1, 0),
                ..
            }
        ),
        "{e}"
    );
    assert!(PsRefinement::new(&t, SplitRule::Incenter).is_ok());
    assert_eq!(
        PsRefinement::with_points(&t, vec![p(-1.0, 0.025), p(5.0, 5.0)]).unwrap_err(),
        PsError::SplitPointOutside { triangle: 1 }
    );
    // A user PS-triangle that misses the PS-points.
    let refn = PsRefinement::new(&t, SplitRule::Incenter).unwrap();
    let mut given: Vec<_> = (0..4)
        .map(|i| *PsBasis::optimal(t.clone()).unwrap().ps_triangle(i))
        .collect();
    given[2] = crate::geometry::Triangle2::new(p(-5., 0.1), p(-4.9, 0.1), p(-5., 0.2));
    let e = PsBasis::with_refinement(t.clone(), refn, &PsTriangleChoice::Given(given)).unwrap_err();
    assert!(
        matches!(e, PsError::PsPointOutside { vertex: 2, .. }),
        "{e}"
    );
    // Coefficients: wrong count, NaN; weights: zero, negative; points outside.
    let basis = Arc::new(PsBasis::optimal(t.clone()).unwrap());
    assert!(matches!(
        PsSpline::new(basis.clone(), vec![[0.0; 3]; 3]),
        Err(PsError::WrongCount {
            expected: 4,
            found: 3,
            ..
        })
    ));
    let mut c = vec![[0.0; 3]; 4];
    c[3][1] = f64::NAN;
    assert_eq!(
        PsSpline::new(basis.clone(), c).unwrap_err(),
        PsError::NonFiniteCoefficient {
            vertex: 3,
            index: 1
        }
    );
    let pts = vec![[Vector3::zeros(); 3]; 4];
    for bad in [0.0, -1.0, f64::INFINITY, f64::NAN] {
        let mut w = vec![[1.0; 3]; 4];
        w[1][2] = bad;
        assert!(matches!(
            Nurps::new(basis.clone(), pts.clone(), w),
            Err(PsError::InvalidWeight {
                vertex: 1,
                index: 2,
                ..
            })
        ));
    }
    let s = PsSpline::new(basis, vec![[1.0; 3]; 4]).unwrap();
    assert_eq!(
        s.eval(p(0.5, 5.0)).unwrap_err(),
        PsError::OutsideDomain { x: 0.5, y: 5.0 }
    );
    assert!((s.eval(p(0.5, 0.0)).unwrap() - 1.0).abs() < 1e-15);
}

#[test]
fn local_updates_match_a_full_rebuild() {
    let mut r = rng(49);
    for (name, basis) in bases(13) {
        let t = basis.triangulation();
        let mut pts = random_vec3_triples(&mut r, t.vertex_count());
        let mut s = PsSpline::new(basis.clone(), pts.clone()).unwrap();
        for _ in 0..5 {
            let i = r_index(&mut r, t.vertex_count());
            let new = random_vec3_triples(&mut r, 1)[0];
            pts[i] = new;
            s.set_coefficients(i, new).unwrap();
        }
        let full = PsSpline::new(basis.clone(), pts).unwrap();
        for k in 0..t.triangle_count() {
            assert_eq!(s.net(k), full.net(k), "{name}");
        }
        let _ = Vector2::<f64>::zeros();
    }
}

#[test]
fn fast_paths_agree_with_the_full_jet() {
    let mut r = rng(50);
    for (name, basis) in bases(14) {
        let t = basis.triangulation();
        let f = Quadratic::random(&mut r);
        let s = PsSpline::interpolate(basis.clone(), |p| f.hermite(p)).unwrap();
        let pts = sample_points(t, &basis, &mut r, 2);
        let grads = s.gradients(&pts);
        let jets = s.jets(&pts);
        let mut ev = s.evaluator();
        for ((p, g), j) in pts.iter().zip(&grads).zip(&jets) {
            let (g, j) = (g.unwrap(), j.unwrap().jet);
            assert_eq!((g.0, g.1, g.2), (j.value, j.dx, j.dy), "{name}");
            // A fresh walk may land on the other side of an edge: equal up to rounding.
            assert!(
                (ev.value(*p).unwrap() - j.value).abs() < 1e-14 * (1.0 + j.value.abs()),
                "{name}"
            );
        }
    }
}

/// The stencil's transpose is its adjoint: Σ_m w_m (S c)_m = Σ_{c,j} (Sᵀ w)_{c,j} c_{c,j} for
/// random weights and control values on every triangle of the catalogue.
#[test]
fn the_net_stencil_transpose_is_its_adjoint() {
    let mut r = rng(140);
    let mut checked = 0;
    for (name, t) in catalogue(3) {
        let b = PsBasis::optimal(t).unwrap();
        for tri in 0..b.triangulation().triangle_count() {
            let st = b.stencil(tri);
            let ctrl: [[f64; 3]; 3] =
                std::array::from_fn(|_| std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0)));
            let w: [f64; NET_LEN] = std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0));
            let net = st.apply(ctrl);
            let lhs: f64 = w.iter().zip(&net).map(|(a, b)| a * b).sum();
            let k = st.transpose(w);
            let rhs: f64 = (0..3)
                .flat_map(|c| (0..3).map(move |j| (c, j)))
                .map(|(c, j)| k[c][j] * ctrl[c][j])
                .sum();
            let size: f64 = w.iter().zip(&net).map(|(a, b)| (a * b).abs()).sum();
            assert!(
                (lhs - rhs).abs() <= 1e-14 * size.max(1.0),
                "{name}, triangle {tri}: {lhs} vs {rhs}"
            );
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}

/// Thesis 3.4.1–3.4.2: the tangent point s(V_i) is the combination of the control points with
/// the shape parameters α̃, the control triangle is tangent there (Theorem 3.2), and moving
/// the tangent point by (3.72) puts it where asked, keeps w_{s_i} and the tangency, and
/// changes nothing outside the vertex's molecule.
#[test]
fn shape_parameters_move_the_tangent_point_inside_the_control_triangle() {
    use crate::surface::ParametricSurface;
    let mut r = rng(48);
    let (mut checked, mut skipped) = (0, 0);
    for (name, basis) in bases(12) {
        let t = basis.triangulation();
        let n = t.vertex_count();
        let pts = random_vec3_triples(&mut r, n);
        let weights: Vec<[f64; 3]> = (0..n)
            .map(|_| std::array::from_fn(|_| uniform(&mut r, 0.3, 3.0)))
            .collect();
        let mut s = Nurps::new(basis.clone(), pts, weights).unwrap();
        for _ in 0..5 {
            let i = (uniform(&mut r, 0.0, 1.0) * n as f64) as usize % n;
            // V_i on an edge of its PS-triangle: the tangent point stays on that edge.
            let on_edge = basis.alpha(i).map(|a| a <= 1e-9);
            if on_edge.iter().filter(|&&e| e).count() > 1 {
                skipped += 1; // V_i is a corner of its PS-triangle: the point cannot move
                continue;
            }
            checked += 1;
            let combine = |s: &Nurps<Vector3<f64>>, a: [f64; 3]| -> Vector3<f64> {
                (0..3).map(|j| s.points()[i][j] * a[j]).sum()
            };
            let at = t.vertex(i);
            let here = ParametricSurface::jet(&s, at).unwrap().jet;
            assert!(
                (here.value - combine(&s, s.shape_parameters(i))).norm() < 1e-12,
                "{name}"
            );
            let ws = |s: &Nurps<Vector3<f64>>| -> f64 {
                (0..3).map(|j| basis.alpha(i)[j] * s.weights()[i][j]).sum()
            };
            let before_ws = ws(&s);
            let far = t.vertex((i + n / 2) % n);
            let far_point = ParametricSurface::point(&s, far).unwrap();
            // A random target strictly inside.
            let mut b = random_bary(&mut r).map(|x| 0.1 + 0.7 * x);
            for (x, e) in b.iter_mut().zip(on_edge) {
                if e {
                    *x = 0.0;
                }
            }
            let target = b.map(|x| x / b.iter().sum::<f64>());
            s.set_shape_parameters(i, target).unwrap();
            let moved = ParametricSurface::jet(&s, at).unwrap().jet;
            // V_i lies on an edge of its PS-triangle only up to the triangle's enlargement
            // margin (α_j ≈ 2e-13 measured): a zero parameter there is out of reach by α_j
            // times the control triangle's size (1.3e-12 measured on the l-shape).
            let size = (0..3)
                .map(|j| (s.points()[i][j] - s.points()[i][(j + 1) % 3]).norm())
                .fold(0.0, f64::max);
            let unreachable: f64 = (0..3)
                .filter(|&j| on_edge[j])
                .map(|j| basis.alpha(i)[j])
                .sum();
            let err = (moved.value - combine(&s, target)).norm();
            assert!(err < 1e-12 + 4.0 * unreachable * size, "{name}: {err:e}");
            assert_near!(ws(&s), before_ws, 1e-12);
            for (k, got) in s.shape_parameters(i).iter().enumerate() {
                assert_near!(*got, target[k], 1e-12);
            }
            // Theorem 3.2: the control points lie in the tangent plane at s(V_i).
            let normal = moved.dx.cross(&moved.dy).normalize();
            for c in &s.points()[i] {
                let off = (c - moved.value).dot(&normal).abs();
                assert!(
                    off < 1e-10 * (1.0 + (c - moved.value).norm()),
                    "{name}: {off:e}, alpha {:?}, target {target:?}",
                    basis.alpha(i)
                );
            }
            // Outside the molecule nothing changed.
            if !t
                .molecule(i)
                .iter()
                .any(|&tr| t.triangle(tr as usize).contains(&((i + n / 2) % n)))
            {
                assert_eq!(
                    ParametricSurface::point(&s, far).unwrap(),
                    far_point,
                    "{name}"
                );
            }
        }
        // A target on the boundary or not summing to 1 is refused.
        if let Some(i) = (0..n).find(|&i| basis.alpha(i).iter().all(|&a| a > 1e-9)) {
            assert!(s.set_shape_parameters(i, [0.0, 0.5, 0.5]).is_err());
        }
        assert!(s.set_shape_parameters(0, [0.4, 0.4, 0.4]).is_err());
    }
    assert!(
        checked >= 20 && skipped * 2 < checked,
        "{checked} checked, {skipped} skipped"
    );
}
