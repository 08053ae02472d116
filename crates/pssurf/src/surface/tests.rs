//! The surface model against closed forms: every kind through the enum alone (sampling,
//! curvature, fairness), control-net edits that change only their support, rectangular
//! pieces, and the domain on convex, non-convex and holed shapes.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::*;
use crate::bezier::{BezierTriangle, RationalBezierTriangle};
use crate::geometry::Triangle2;
use crate::interrogate::{Curvature, fairness, sample_patches};
use crate::noise::NoiseKind;
use crate::ps::{Hermite, Nurps, PsBasis, PsSpline};
use crate::test_util::*;
use crate::triangulation::Triangulation;
use crate::ups::{GraphKind, Lattice, LatticePolygon, UpsGrid, graph_surface};

/// z = q(x, y) = a x² + b xy + c y² + d x + e y.
#[derive(Clone, Copy)]
struct Quadric([f64; 5]);

impl Quadric {
    fn value(&self, p: Point2<f64>) -> f64 {
        let [a, b, c, d, e] = self.0;
        a * p.x * p.x + b * p.x * p.y + c * p.y * p.y + d * p.x + e * p.y
    }
    fn hermite(&self, p: Point2<f64>) -> Hermite<f64> {
        let [a, b, c, d, e] = self.0;
        Hermite {
            value: self.value(p),
            dx: 2.0 * a * p.x + b * p.y + d,
            dy: b * p.x + 2.0 * c * p.y + e,
        }
    }
    fn lifted(&self, p: Point2<f64>) -> Hermite<Vector3<f64>> {
        let h = self.hermite(p);
        Hermite {
            value: Vector3::new(p.x, p.y, h.value),
            dx: Vector3::new(1.0, 0.0, h.dx),
            dy: Vector3::new(0.0, 1.0, h.dy),
        }
    }
    /// Gaussian and mean curvature of the graph (upward normal).
    fn curvature(&self, p: Point2<f64>) -> (f64, f64) {
        let [a, b, c, ..] = self.0;
        let h = self.hermite(p);
        let (fx, fy, fxx, fxy, fyy) = (h.dx, h.dy, 2.0 * a, b, 2.0 * c);
        let w = 1.0 + fx * fx + fy * fy;
        let k = (fxx * fyy - fxy * fxy) / (w * w);
        let m = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy)
            / (2.0 * w.powf(1.5));
        (k, m)
    }
    /// The thin-plate integrand f_xx² + 2 f_xy² + f_yy² (constant).
    fn thin_plate_density(&self) -> f64 {
        let [a, b, c, ..] = self.0;
        4.0 * a * a + 2.0 * b * b + 4.0 * c * c
    }
    /// The quadratic Bézier ordinates of the graph over `t` (from the polar form: corner
    /// values and 2 q(mid) − (q(a) + q(b))/2 on the edges), in storage order.
    fn bezier(&self, t: &Triangle2) -> Vec<Vector3<f64>> {
        let p = |x: Point2<f64>| Vector3::new(x.x, x.y, self.value(x));
        let mid = |i: usize, j: usize| {
            let m = Point2::from((t.v[i].coords + t.v[j].coords) * 0.5);
            p(m) * 2.0 - (p(t.v[i]) + p(t.v[j])) * 0.5
        };
        // b200, b110, b101, b020, b011, b002.
        vec![
            p(t.v[0]),
            mid(0, 1),
            mid(0, 2),
            p(t.v[1]),
            mid(1, 2),
            p(t.v[2]),
        ]
    }
}

/// The graph of `q` over [0, 1]² (roughly) as a surface of every kind.
fn every_kind(q: Quadric, r: &mut rand_chacha::ChaCha8Rng) -> Vec<Surface> {
    let tri = meshes::uniform_square(r, 12);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let parametric = PsSpline::interpolate(basis.clone(), |p| q.lifted(p)).unwrap();
    let n = basis.triangulation().vertex_count();
    let nurps = Nurps::new(
        basis.clone(),
        parametric.coefficients().to_vec(),
        vec![[1.0; 3]; n],
    )
    .unwrap();
    let grid = UpsGrid::new(
        Lattice {
            base: 0.25,
            origin: Point2::new(0.1, 0.2),
        },
        LatticePolygon::standard(4, 3).unwrap(),
    )
    .unwrap();
    let t = Triangle2::new(
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.1),
        Point2::new(0.2, 0.9),
    );
    let bezier = BezierTriangle::new(t, 2, q.bezier(&t));
    let mut kinds = vec![
        Surface::from(PsSpline::interpolate(basis.clone(), |p| q.hermite(p)).unwrap()),
        Surface::from(parametric),
        Surface::from(nurps),
    ];
    for kind in [
        GraphKind::Functional,
        GraphKind::Parametric,
        GraphKind::Rational,
    ] {
        kinds.push(Surface::try_from(graph_surface(grid.clone(), kind, |p| q.hermite(p))).unwrap());
    }
    kinds.push(Surface::from(RationalBezierTriangle::from_polynomial(
        &bezier,
    )));
    kinds.push(Surface::from(bezier));
    kinds.push(Surface::from(nurbs_graph(&q)));
    kinds
}

/// The graph of `q` over [0, 1]² as a rational biquadratic NURBS surface with an interior knot
/// in each direction (2 × 2 pieces; all weights 2, so the surface is the polynomial one): the
/// control points interpolate (u, v, q) at the Greville points, which reproduces quadratics.
fn nurbs_graph(q: &Quadric) -> crate::nurbs::NurbsSurface {
    use crate::nurbs::KnotVector;
    let knots = vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0];
    let kv = KnotVector::try_new(2, knots.clone(), 4).unwrap();
    let greville = [0.0, 0.25, 0.75, 1.0];
    // A[i][j] = N_j(g_i).
    let a = nalgebra::DMatrix::from_fn(4, 4, |i, j| {
        let t = greville[i];
        let span = kv.spans()[kv.span_rank(t)];
        let b = kv.basis(span, t);
        // N_j is entry j − (span − 2) of the nonzero ones.
        if j + 2 >= span && j <= span {
            b.d[0][j + 2 - span]
        } else {
            0.0
        }
    });
    let inv = a.clone().try_inverse().unwrap();
    let mut points = vec![Vector3::zeros(); 16];
    for c in 0..3 {
        let f = nalgebra::DMatrix::from_fn(4, 4, |i, j| {
            let p = Point2::new(greville[i], greville[j]);
            [p.x, p.y, q.value(p)][c]
        });
        let coef = &inv * f * inv.transpose();
        for i in 0..4 {
            for j in 0..4 {
                points[i * 4 + j][c] = coef[(i, j)];
            }
        }
    }
    crate::nurbs::NurbsSurface::try_new(
        [2, 2],
        [knots.clone(), knots],
        [4, 4],
        points,
        Some(vec![2.0; 16]),
    )
    .unwrap()
}

#[test]
fn every_kind_samples_with_the_closed_form_curvature_through_the_enum() {
    let mut r = rng(1101);
    for _ in 0..4 {
        let q = Quadric(std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0)));
        let kinds = every_kind(q, &mut r);
        let names: std::collections::HashSet<SurfaceKind> =
            kinds.iter().map(Surface::kind).collect();
        assert_eq!(names.len(), 9, "one surface of every kind");
        for s in &kinds {
            graph_of_quadric_through_the_enum(s, q);
        }
    }
}

/// The accuracy of second derivatives on a piece: they are second differences of Bézier
/// ordinates divided by the squared height h of the piece, so rounding is of order ε/h²
/// (the bound of `interrogate::tests`; well-shaped pieces meet 1e-10).
fn curvature_tolerance(piece: &PieceShape) -> f64 {
    let h = match piece {
        PieceShape::Triangle(t) => 2.0 * t.area() / t.diameter(),
        PieceShape::Rectangle(r) => (r.max.x - r.min.x).min(r.max.y - r.min.y),
    };
    1e-10f64.max(32.0 * f64::EPSILON / (h * h))
}

/// Sampling, point evaluation and fairness of `s`, which represents the graph of `q`,
/// against the closed forms.
fn graph_of_quadric_through_the_enum(s: &Surface, q: Quadric) {
    let sampled = sample_patches(s, 1, true);
    assert_eq!(
        sampled.mesh.positions.len(),
        s.piece_count() * crate::interrogate::vertices_per_piece(s.piece_kind(), 1),
        "{}",
        s.kind()
    );
    let mut compared = 0;
    for (v, uv) in sampled.mesh.uvs.iter().enumerate() {
        let p = sampled.mesh.positions[v];
        assert!(
            (p - Vector3::new(uv.x, uv.y, q.value(*uv))).norm() < 1e-12,
            "{}: {p} at {uv}",
            s.kind()
        );
        let (k, h) = q.curvature(*uv);
        let tol = curvature_tolerance(&s.piece_shape(sampled.patch[v] as usize));
        assert_near!(sampled.curvature[v].gaussian, k, tol, "{}", s.kind());
        assert_near!(sampled.curvature[v].mean, h, tol, "{}", s.kind());
        compared += 1;
    }
    assert!(compared >= 6, "{}: only {compared} points", s.kind());
    // Point evaluation agrees with sampling and names the piece.
    let uv = sampled.mesh.uvs[sampled.mesh.uvs.len() / 2];
    let jet = s.jet(uv).unwrap();
    assert!(jet.piece < s.piece_count());
    let c = Curvature::from_jet(&jet.jet).unwrap();
    let tol = curvature_tolerance(&s.piece_shape(jet.piece));
    assert_near!(c.gaussian, q.curvature(uv).0, tol, "{}", s.kind());
    // Fairness through the pieces: the thin-plate energy of a graph of a quadratic is its
    // constant density times the domain's area.
    let f = fairness(s, 6);
    let area = s.domain().area();
    assert_near!(
        f.integrals.thin_plate,
        q.thin_plate_density() * area,
        1e-10,
        "{}",
        s.kind()
    );
    let pieces: f64 = (0..s.piece_count()).map(|k| s.piece_shape(k).area()).sum();
    assert_near!(pieces, area, 1e-12, "{}", s.kind());
}

/// A changed copy of control point `id` (a free coordinate moved; the weight changed for
/// rational kinds).
fn moved(s: &Surface, id: ControlId) -> ControlPoint {
    let mut p = s.control_point(id).unwrap();
    p.position.z += 0.25;
    if s.freedom() == ControlFreedom::Full {
        p.position.x -= 0.05;
    }
    if s.is_rational() {
        p.weight *= 1.7;
    }
    p
}

#[test]
fn control_net_edits_of_every_kind_change_only_their_support() {
    let mut r = rng(1102);
    let q = Quadric([0.2, 0.1, -0.3, 0.0, 0.5]);
    for mut s in every_kind(q, &mut r) {
        // Build any cached general form first, so the edit must keep it in step.
        let before = sample_patches(&s, 1, false);
        let per = crate::interrogate::vertices_per_piece(s.piece_kind(), 1);
        let count = s.control_count();
        let id = ControlId(count / 2);
        let group = s.control_group(id);
        assert!(group.contains(&id.0));
        let p = moved(&s, id);
        let support = s.set_control_point(id, p).unwrap();
        assert_eq!(support, s.support(id), "{}", s.kind());
        assert!(support.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(s.control_point(id).unwrap(), {
            let mut e = p;
            if s.freedom() == ControlFreedom::Height {
                e.position.x = s.control_point(id).unwrap().position.x;
            }
            e
        });
        let after = sample_patches(&s, 1, false);
        let (mut unchanged, mut changed) = (0, 0);
        for k in 0..s.piece_count() {
            let range = k * per..(k + 1) * per;
            let same = before.mesh.positions[range.clone()] == after.mesh.positions[range];
            if support.contains(&k) {
                changed += usize::from(!same);
            } else {
                assert!(same, "{}: piece {k} outside the support changed", s.kind());
                unchanged += 1;
            }
        }
        assert!(changed > 0, "{}: the edit changed nothing", s.kind());
        if s.piece_count() > 1 {
            assert!(unchanged > 0, "{}: no piece outside the support", s.kind());
        }
        // A UPS surface's uniform and general forms stay in step.
        if let Surface::Uniform(u) = &s {
            let fresh = u.ups().to_general().unwrap();
            assert_eq!(fresh.control_points(), u.general().control_points());
            let uv = after.mesh.uvs[after.mesh.uvs.len() / 3];
            let (a, b) = (fresh.jet(uv).unwrap().jet, s.jet(uv).unwrap().jet);
            assert!(a.max_diff(&b) < 1e-12, "{}", s.kind());
        }
    }
}

#[test]
fn bad_control_points_are_refused_and_leave_the_surface_unchanged() {
    let mut r = rng(1103);
    let q = Quadric([0.2, 0.1, -0.3, 0.0, 0.5]);
    for mut s in every_kind(q, &mut r) {
        let all = s.control_points();
        let id = ControlId(1);
        let good = s.control_point(id).unwrap();
        let mut nan = good;
        nan.position.y = f64::NAN;
        assert_eq!(
            s.set_control_points(&[(ControlId(0), good), (id, nan)]),
            Err(EditError::NonFinite(1))
        );
        let count = s.control_count();
        assert_eq!(
            s.set_control_point(ControlId(count), good),
            Err(EditError::NoSuchPoint { id: count, count })
        );
        let mut w = good;
        w.weight = if s.is_rational() { 0.0 } else { 2.0 };
        let e = s.set_control_point(id, w).unwrap_err();
        assert!(
            matches!(
                e,
                EditError::InvalidWeight { .. } | EditError::NotRational { .. }
            ),
            "{e}"
        );
        assert_eq!(s.control_points(), all, "{}", s.kind());
    }
}

#[test]
fn control_anchors_are_vertices_bezier_points_and_greville_points() {
    let mut r = rng(1104);
    let q = Quadric([0.2, 0.1, -0.3, 0.0, 0.5]);
    for s in every_kind(q, &mut r) {
        let id = ControlId(4);
        let a = s.control_anchor(id);
        match s.ps_basis() {
            Some(b) => {
                assert_eq!(a, b.triangulation().vertex(4 / 3));
                assert!(b.triangulation().molecule(1).len() * 6 == s.support(id).len());
            }
            // NURBS: the Greville point of P_10 (n_v = 4): ((0 + 0.5)/2, (0 + 0)/2).
            None if matches!(s, Surface::Nurbs(_)) => {
                assert_eq!(a, Point2::new(0.25, 0.0));
                // N_1 on u-spans 1..=3 (two pieces) × N_0 on the first v-span.
                assert_eq!(s.support(id), vec![0, 2]);
            }
            // Ordinate 4 of a quadratic is b011: the midpoint of the edge V2 V3.
            None => {
                assert!(matches!(s, Surface::Bezier(_) | Surface::RationalBezier(_)));
                let t = match s.piece_shape(0) {
                    PieceShape::Triangle(t) => t,
                    PieceShape::Rectangle(_) => unreachable!(),
                };
                assert_eq!(a, t.point([0.0, 0.5, 0.5]));
            }
        }
    }
}

#[test]
fn noise_perturbs_every_free_coordinate_reproducibly_and_keeps_weights() {
    let mut r = rng(1105);
    let q = Quadric([0.2, 0.1, -0.3, 0.0, 0.5]);
    for s in every_kind(q, &mut r) {
        let a = s.with_noise(0.01, NoiseKind::Uniform, 7).unwrap();
        let b = s.with_noise(0.01, NoiseKind::Uniform, 7).unwrap();
        assert_eq!(a.control_points(), b.control_points());
        let mut moved_points = 0;
        for (p, n) in s.control_points().iter().zip(a.control_points()) {
            let d = n.position - p.position;
            assert!(d.amax() <= 0.01, "{}", s.kind());
            assert_eq!(n.weight, p.weight);
            if s.freedom() == ControlFreedom::Height {
                assert_eq!((d.x, d.y), (0.0, 0.0));
            }
            moved_points += usize::from(d.z != 0.0);
        }
        assert_eq!(moved_points, s.control_count(), "{}", s.kind());
        for bad in [f64::NAN, f64::INFINITY, -1.0] {
            assert!(matches!(
                s.with_noise(bad, NoiseKind::Gaussian, 3),
                Err(EditError::InvalidAmplitude(_))
            ));
        }
        // Noise that overflows a coordinate is an error for every kind, never a surface with
        // infinite control points. Gaussian noise of deviation MAX overflows a coordinate with
        // probability 0.32; uniform noise in [−MAX, MAX] on coordinates of size 1 almost never
        // does, and must not panic either way.
        assert!(
            matches!(
                s.with_noise(f64::MAX, NoiseKind::Gaussian, 3),
                Err(EditError::NonFinite(_))
            ),
            "{}",
            s.kind()
        );
        match s.with_noise(f64::MAX, NoiseKind::Uniform, 3) {
            Ok(n) => assert!(
                n.control_points()
                    .iter()
                    .all(|p| p.position.iter().all(|x| x.is_finite()))
            ),
            Err(e) => assert!(matches!(e, EditError::NonFinite(_)), "{e}"),
        }
    }
}

/// A test surface with rectangular pieces: the graph of a quadric over an nx × ny grid of
/// rectangles covering [0, 2] × [0, 1].
struct TensorGraph {
    q: Quadric,
    nx: usize,
    ny: usize,
}

impl TensorGraph {
    fn rectangle(&self, k: usize) -> Rectangle {
        let (i, j) = (k % self.nx, k / self.nx);
        let (w, h) = (2.0 / self.nx as f64, 1.0 / self.ny as f64);
        Rectangle::new(
            Point2::new(i as f64 * w, j as f64 * h),
            Point2::new((i + 1) as f64 * w, (j + 1) as f64 * h),
        )
    }
    fn graph(&self, uv: Point2<f64>) -> crate::bezier::Jet<Vector3<f64>> {
        let [a, b, c, ..] = self.q.0;
        let h = self.q.hermite(uv);
        crate::bezier::Jet {
            value: Vector3::new(uv.x, uv.y, h.value),
            dx: Vector3::new(1.0, 0.0, h.dx),
            dy: Vector3::new(0.0, 1.0, h.dy),
            dxx: Vector3::new(0.0, 0.0, 2.0 * a),
            dxy: Vector3::new(0.0, 0.0, b),
            dyy: Vector3::new(0.0, 0.0, 2.0 * c),
        }
    }
}

impl ParametricSurface for TensorGraph {
    fn domain_bounds(&self) -> (Point2<f64>, Point2<f64>) {
        (Point2::new(0.0, 0.0), Point2::new(2.0, 1.0))
    }
    fn jet_with(&self, uv: Point2<f64>, _: &mut Cursor) -> Result<SurfaceJet, OutsideDomain> {
        if !(0.0..=2.0).contains(&uv.x) || !(0.0..=1.0).contains(&uv.y) {
            return Err(OutsideDomain::at(uv));
        }
        let i = ((uv.x / 2.0 * self.nx as f64) as usize).min(self.nx - 1);
        let j = ((uv.y * self.ny as f64) as usize).min(self.ny - 1);
        Ok(SurfaceJet {
            jet: self.graph(uv),
            piece: j * self.nx + i,
        })
    }
}

impl PiecewiseSurface for TensorGraph {
    fn piece_count(&self) -> usize {
        self.nx * self.ny
    }
    fn piece_kind(&self) -> PieceKind {
        PieceKind::Rectangle
    }
    fn piece_shape(&self, k: usize) -> PieceShape {
        PieceShape::Rectangle(self.rectangle(k))
    }
    fn piece_jet(&self, k: usize, at: &PiecePoint) -> crate::bezier::Jet<Vector3<f64>> {
        // Check that the local coordinates are consistent with the parameters.
        let LocalCoords::Rect { st, scale } = at.local else {
            panic!("rectangular pieces get rectangle coordinates");
        };
        let r = self.rectangle(k);
        assert_near!(r.min.x + st[0] / scale[0], at.uv.x, 1e-14);
        assert_near!(r.min.y + st[1] / scale[1], at.uv.y, 1e-14);
        self.graph(at.uv)
    }
}

#[test]
fn rectangular_pieces_are_sampled_and_integrated() {
    let q = Quadric([0.3, -0.2, 0.5, 0.1, 0.0]);
    let s = TensorGraph { q, nx: 3, ny: 2 };
    for level in [0, 2] {
        let n = 1usize << level;
        let sampled = sample_patches(&s, level, true);
        assert_eq!(sampled.mesh.positions.len(), 6 * (n + 1) * (n + 1));
        assert_eq!(sampled.mesh.triangles.len(), 6 * 2 * n * n);
        for (v, uv) in sampled.mesh.uvs.iter().enumerate() {
            assert_near!(sampled.mesh.positions[v].z, q.value(*uv), 1e-14);
            let (k, h) = q.curvature(*uv);
            assert_near!(sampled.curvature[v].gaussian, k, 1e-12);
            assert_near!(sampled.curvature[v].mean, h, 1e-12);
        }
        // Triangles face along the normal (upwards for a graph) and tile each rectangle.
        let mut area = 0.0;
        for t in &sampled.mesh.triangles {
            let [a, b, c] = t.map(|k| sampled.mesh.uvs[k as usize]);
            let det = (b - a).perp(&(c - a));
            assert!(det > 0.0);
            area += 0.5 * det;
            let [pa, pb, pc] = t.map(|k| sampled.mesh.positions[k as usize]);
            assert!((pb - pa).cross(&(pc - pa)).z > 0.0);
        }
        assert_near!(area, 2.0, 1e-13);
    }
    let f = fairness(&s, 4);
    assert_near!(f.integrals.thin_plate, 2.0 * q.thin_plate_density(), 1e-12);
    // The area of a plane's graph is √(1 + d² + e²) times the domain's (exact for a
    // constant integrand).
    let plane = TensorGraph {
        q: Quadric([0.0, 0.0, 0.0, 0.3, -0.4]),
        nx: 2,
        ny: 5,
    };
    assert_near!(
        fairness(&plane, 2).integrals.area,
        2.0 * (1.0f64 + 0.09 + 0.16).sqrt(),
        1e-13
    );
}

#[test]
fn rectangle_quadrature_is_exact_for_its_degree() {
    let mut r = rng(1110);
    for degree in 0..8 {
        let (x0, y0) = (uniform(&mut r, -2.0, 1.0), uniform(&mut r, -2.0, 1.0));
        let (x1, y1) = (
            x0 + uniform(&mut r, 0.1, 3.0),
            y0 + uniform(&mut r, 0.1, 3.0),
        );
        let frame = PieceShape::Rectangle(Rectangle::new(Point2::new(x0, y0), Point2::new(x1, y1)))
            .frame()
            .unwrap();
        let rule = PieceRule::exact_for(degree);
        for a in 0..=degree {
            for b in 0..=degree {
                let q: f64 = rule
                    .nodes(&frame)
                    .iter()
                    .map(|n| n.weight * n.point.uv.x.powi(a as i32) * n.point.uv.y.powi(b as i32))
                    .sum();
                let int =
                    |lo: f64, hi: f64, k: i32| (hi.powi(k + 1) - lo.powi(k + 1)) / (k + 1) as f64;
                let exact = int(x0, x1, a as i32) * int(y0, y1, b as i32);
                assert_near!(q, exact, 1e-12, "degree {degree}: x^{a} y^{b}");
            }
        }
    }
}

fn pts(list: &[(f64, f64)]) -> Vec<Point2<f64>> {
    list.iter().map(|&(x, y)| Point2::new(x, y)).collect()
}

#[test]
fn a_convex_domain_against_hand_computed_answers() {
    let d =
        Domain::from_loops(vec![pts(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])]).unwrap();
    assert_eq!(d.area(), 1.0);
    assert_eq!(d.hole_count(), 0);
    assert!(d.contains(Point2::new(0.5, 0.5)));
    assert!(d.contains(Point2::new(1.0, 0.5)) && d.on_boundary(Point2::new(1.0, 0.5)));
    assert!(d.contains(Point2::new(1.0, 1.0)));
    assert!(!d.contains(Point2::new(1.0 + 1e-15, 0.5)));
    assert!(
        !d.contains(Point2::new(0.5, -1e-300)),
        "exact, not a tolerance"
    );
    let parts = d.clip_segment(Point2::new(-1.0, 0.5), Point2::new(2.0, 0.5));
    assert_eq!(parts.len(), 1);
    assert_near!(parts[0].start, 1.0 / 3.0, 1e-15);
    assert_near!(parts[0].end, 2.0 / 3.0, 1e-15);
    assert!(
        d.clip_segment(Point2::new(2.0, 2.0), Point2::new(3.0, 0.0))
            .is_empty()
    );
    assert_eq!(
        d.clip_segment(Point2::new(0.2, 0.2), Point2::new(0.7, 0.9)),
        vec![SegmentPart {
            start: 0.0,
            end: 1.0
        }]
    );
    assert_near!(d.distance_to_boundary(Point2::new(0.5, 0.25)), 0.25, 1e-15);
    assert_near!(
        d.distance_to_boundary(Point2::new(2.0, 2.0)),
        2f64.sqrt(),
        1e-15
    );
    let c = d.closest_boundary_point(Point2::new(0.3, 5.0));
    assert!((c - Point2::new(0.3, 1.0)).norm() < 1e-15, "{c}");
}

#[test]
fn a_non_convex_domain_against_hand_computed_answers() {
    // The L-shape [0, 2] × [0, 1] ∪ [0, 1] × [0, 2], reflex corner at (1, 1).
    let d = Domain::from_loops(vec![pts(&[
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ])])
    .unwrap();
    assert_eq!(d.area(), 3.0);
    assert!(!d.contains(Point2::new(1.5, 1.5)));
    assert!(d.contains(Point2::new(0.5, 1.5)) && d.contains(Point2::new(1.5, 0.5)));
    assert!(d.on_boundary(Point2::new(1.0, 1.0)));
    // From (0.5, 1.5) to (2.5, 1.5): inside up to x = 1.
    let parts = d.clip_segment(Point2::new(0.5, 1.5), Point2::new(2.5, 1.5));
    assert_eq!(
        parts,
        vec![SegmentPart {
            start: 0.0,
            end: 0.25
        }]
    );
    // The diagonal through the reflex corner leaves there.
    let parts = d.clip_segment(Point2::new(0.5, 0.5), Point2::new(1.5, 1.5));
    assert_eq!(
        parts,
        vec![SegmentPart {
            start: 0.0,
            end: 0.5
        }]
    );
    // A segment leaving and re-entering: y = 1.5 from x = 0.5 to x = 0.8 stays in; y = 0.5
    // across the whole shape is one part; x = 1.5 from y = −1 to y = 3 is inside on [0, 1].
    let parts = d.clip_segment(Point2::new(1.5, -1.0), Point2::new(1.5, 3.0));
    assert_eq!(
        parts,
        vec![SegmentPart {
            start: 0.25,
            end: 0.5
        }]
    );
    assert_near!(d.distance_to_boundary(Point2::new(1.5, 1.5)), 0.5, 1e-15);
}

/// The square [0, 3]² with the hole [1, 2]², triangulated.
fn annulus() -> Triangulation {
    let v = pts(&[
        (0.0, 0.0),
        (3.0, 0.0),
        (3.0, 3.0),
        (0.0, 3.0),
        (1.0, 1.0),
        (2.0, 1.0),
        (2.0, 2.0),
        (1.0, 2.0),
    ]);
    let t = vec![
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ];
    Triangulation::try_new(v, t).unwrap()
}

#[test]
fn a_holed_domain_against_hand_computed_answers() {
    let from_loops = Domain::from_loops(vec![
        pts(&[(0.0, 0.0), (3.0, 0.0), (3.0, 3.0), (0.0, 3.0)]),
        pts(&[(1.0, 1.0), (1.0, 2.0), (2.0, 2.0), (2.0, 1.0)]),
    ])
    .unwrap();
    let from_mesh = Domain::from_triangulation(&annulus());
    for d in [from_loops, from_mesh] {
        assert_eq!(d.boundary().len(), 2);
        assert_eq!(d.hole_count(), 1);
        assert_eq!(d.area(), 8.0);
        assert!(!d.contains(Point2::new(1.5, 1.5)));
        assert!(d.contains(Point2::new(0.5, 0.5)));
        assert!(
            d.contains(Point2::new(1.0, 1.5)),
            "hole boundary belongs to the domain"
        );
        let parts = d.clip_segment(Point2::new(-1.0, 1.5), Point2::new(4.0, 1.5));
        assert_eq!(parts.len(), 2);
        for (p, (a, b)) in parts.iter().zip([(0.2, 0.4), (0.6, 0.8)]) {
            assert_near!(p.start, a, 1e-15);
            assert_near!(p.end, b, 1e-15);
        }
        assert_near!(d.distance_to_boundary(Point2::new(0.5, 1.5)), 0.5, 1e-15);
        assert_near!(d.distance_to_boundary(Point2::new(1.5, 1.6)), 0.4, 1e-15);
    }
    // The surface on the annulus reports the same domain.
    let basis = Arc::new(PsBasis::optimal(annulus()).unwrap());
    let s = Surface::from(PsSpline::new(basis, vec![[0.0; 3]; 8]).unwrap());
    assert_eq!(s.domain().hole_count(), 1);
}

#[test]
fn bad_domains_are_refused() {
    assert_eq!(Domain::from_loops(vec![]), Err(DomainError::Empty));
    assert_eq!(
        Domain::from_loops(vec![pts(&[(0.0, 0.0), (1.0, f64::NAN), (0.0, 1.0)])]),
        Err(DomainError::NonFinite(0))
    );
}

#[test]
fn domain_containment_agrees_with_point_location_on_random_meshes() {
    let mut r = rng(1106);
    let (mut compared, mut total) = (0, 0);
    for (name, tri) in meshes::catalogue(1107) {
        let d = Domain::from_triangulation(&tri);
        assert_near!(d.area(), tri.area(), 1e-12, "{name}");
        let (lo, hi) = tri.bounds();
        for _ in 0..400 {
            total += 1;
            let p = Point2::new(uniform(&mut r, lo.x, hi.x), uniform(&mut r, lo.y, hi.y));
            // Skip points within rounding of the boundary, where the triangulation's locator
            // uses a tolerance and the domain decides exactly.
            if d.distance_to_boundary(p) < 1e-9 {
                continue;
            }
            assert_eq!(d.contains(p), tri.locate(p).is_some(), "{name} at {p}");
            compared += 1;
        }
    }
    assert!(
        compared >= total * 95 / 100,
        "only {compared} of {total} points compared"
    );
}

#[test]
fn clipped_segments_are_inside_and_their_gaps_outside_on_random_meshes() {
    let mut r = rng(1108);
    let (mut checked, mut total) = (0, 0);
    for (name, tri) in meshes::catalogue(1109) {
        let d = Domain::from_triangulation(&tri);
        let (lo, hi) = tri.bounds();
        let pad = 0.2 * (hi - lo).norm();
        let mut point = || {
            Point2::new(
                uniform(&mut r, lo.x - pad, hi.x + pad),
                uniform(&mut r, lo.y - pad, hi.y + pad),
            )
        };
        for _ in 0..100 {
            let (a, b) = (point(), point());
            let parts = d.clip_segment(a, b);
            assert!(parts.windows(2).all(|w| w[0].end < w[1].start), "{name}");
            for k in 0..=40 {
                let t = k as f64 / 40.0;
                let p = a + (b - a) * t;
                total += 1;
                // Within rounding of the boundary, rounding decides: skip and count.
                if d.distance_to_boundary(p) < 1e-9 {
                    continue;
                }
                let covered = parts.iter().any(|s| s.start <= t && t <= s.end);
                assert_eq!(covered, d.contains(p), "{name}: t = {t} on {a} → {b}");
                checked += 1;
            }
        }
    }
    assert!(
        checked >= total * 95 / 100,
        "only {checked} of {total} compared"
    );
}

/// A uniform form whose control values are beyond ±1e60 (reachable through the library's
/// `Ups::hermite`) is refused when it becomes a surface, naming the vertex; its general
/// form could not hold those values, and building it on first use panicked.
#[test]
fn a_uniform_form_with_unusable_values_is_refused_not_a_panic() {
    let grid = UpsGrid::new(
        Lattice {
            base: 1.0,
            origin: Point2::origin(),
        },
        LatticePolygon::standard(6, 2).unwrap(),
    )
    .unwrap();
    for height in [1e61, f64::INFINITY, f64::NAN] {
        let ups = crate::ups::Ups::hermite(grid.clone(), |p| Hermite {
            value: if p.x > 2.5 { height } else { 0.0 },
            dx: 0.0,
            dy: 0.0,
        });
        let e = Surface::try_from(UpsSurface::Functional(ups)).unwrap_err();
        assert!(
            matches!(e, crate::ups::UpsError::UnusableValues { at } if at[0] > 2.5),
            "{height}: {e}"
        );
    }
}
