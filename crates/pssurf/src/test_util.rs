//! Helpers shared by the unit tests: seeded randomness, random geometry, relative comparison.

use nalgebra::{Point2, Vector2};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::geometry::{Bary, Triangle2};

/// A seeded generator, so failures reproduce.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A uniform number in [lo, hi).
pub fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    rng.random_range(lo..hi)
}

/// A random counter-clockwise triangle with minimum angle not too small.
pub fn random_triangle(rng: &mut ChaCha8Rng) -> Triangle2 {
    loop {
        let p = |r: &mut ChaCha8Rng| Point2::new(uniform(r, -2.0, 2.0), uniform(r, -2.0, 2.0));
        let t = Triangle2::new(p(rng), p(rng), p(rng));
        if t.det() > 0.5 {
            return t;
        }
    }
}

/// A random point of the closed triangle, as barycentric coordinates.
pub fn random_bary(rng: &mut ChaCha8Rng) -> Bary {
    let (mut a, mut b) = (uniform(rng, 0.0, 1.0), uniform(rng, 0.0, 1.0));
    if a + b > 1.0 {
        a = 1.0 - a;
        b = 1.0 - b;
    }
    [a, b, 1.0 - a - b]
}

/// A random unit vector of the plane.
pub fn random_dir(rng: &mut ChaCha8Rng) -> Vector2<f64> {
    let a = uniform(rng, 0.0, std::f64::consts::TAU);
    Vector2::new(a.cos(), a.sin())
}

/// A random point of [−1, 1]³.
pub fn random_vec3(r: &mut ChaCha8Rng) -> nalgebra::Vector3<f64> {
    nalgebra::Vector3::new(
        uniform(r, -1.0, 1.0),
        uniform(r, -1.0, 1.0),
        uniform(r, -1.0, 1.0),
    )
}

/// `n` triples of random points of [−1, 1]³ (control points of random surfaces).
pub fn random_vec3_triples(r: &mut ChaCha8Rng, n: usize) -> Vec<[nalgebra::Vector3<f64>; 3]> {
    (0..n)
        .map(|_| std::array::from_fn(|_| random_vec3(r)))
        .collect()
}

/// |a − b| ≤ tol · max(1, |a|, |b|): a relative comparison that is absolute near zero.
pub fn near(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * a.abs().max(b.abs()).max(1.0)
}

/// Asserts [`near`] with a readable message.
#[macro_export]
macro_rules! assert_near {
    ($a:expr, $b:expr, $tol:expr) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        assert!(
            $crate::test_util::near(a, b, tol),
            "{} = {a:e} differs from {} = {b:e} by {:e} (tol {tol:e})",
            stringify!($a),
            stringify!($b),
            (a - b).abs()
        );
    }};
    ($a:expr, $b:expr, $tol:expr, $($msg:tt)+) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        assert!(
            $crate::test_util::near(a, b, tol),
            "{} = {a:e} differs from {} = {b:e} by {:e} (tol {tol:e}): {}",
            stringify!($a),
            stringify!($b),
            (a - b).abs(),
            format!($($msg)+)
        );
    }};
}

/// A catalogue of test triangulations grouped by the property they stress.
pub mod meshes {
    use super::*;
    use crate::triangulation::Triangulation;

    /// Delaunay triangulation of uniform random points in the unit square (slivers at the hull).
    pub fn uniform_square(r: &mut ChaCha8Rng, n: usize) -> Triangulation {
        let pts = (0..n)
            .map(|_| Point2::new(uniform(r, 0.0, 1.0), uniform(r, 0.0, 1.0)))
            .collect();
        Triangulation::delaunay(pts).unwrap()
    }

    /// Points stretched 50:1 in x: many thin triangles.
    pub fn thin(r: &mut ChaCha8Rng, n: usize) -> Triangulation {
        let pts = (0..n)
            .map(|_| Point2::new(uniform(r, 0.0, 5.0), uniform(r, 0.0, 0.1)))
            .collect();
        Triangulation::delaunay(pts).unwrap()
    }

    /// Many points on a circle and few inside: most vertices on the boundary.
    pub fn boundary_heavy(r: &mut ChaCha8Rng, n: usize) -> Triangulation {
        let mut pts: Vec<Point2<f64>> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * (k as f64 + uniform(r, 0.0, 0.5)) / n as f64;
                Point2::new(a.cos(), a.sin())
            })
            .collect();
        for _ in 0..n / 8 {
            let (a, rad) = (uniform(r, 0.0, std::f64::consts::TAU), uniform(r, 0.0, 0.8));
            pts.push(Point2::new(rad * a.cos(), rad * a.sin()));
        }
        Triangulation::delaunay(pts).unwrap()
    }

    /// A jittered k × k grid with random diagonals: a valid, generally non-Delaunay
    /// triangulation given explicitly.
    pub fn structured(r: &mut ChaCha8Rng, k: usize) -> Triangulation {
        let mut pts = Vec::new();
        for j in 0..=k {
            for i in 0..=k {
                let jit = |r: &mut ChaCha8Rng, on_edge: bool| {
                    if on_edge {
                        0.0
                    } else {
                        uniform(r, -0.25, 0.25)
                    }
                };
                let (ei, ej) = (i == 0 || i == k, j == 0 || j == k);
                pts.push(Point2::new(i as f64 + jit(r, ei), j as f64 + jit(r, ej)));
            }
        }
        let id = |i: usize, j: usize| j * (k + 1) + i;
        let mut tris = Vec::new();
        for j in 0..k {
            for i in 0..k {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if uniform(r, 0.0, 1.0) < 0.5 {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        Triangulation::new(pts, tris)
    }

    /// A non-convex L-shaped domain with a jittered interior (walks may hit the boundary).
    pub fn l_shape(r: &mut ChaCha8Rng, k: usize) -> Triangulation {
        let half = k as f64 / 2.0;
        without(&structured(r, k), |c| c.x > half && c.y > half)
    }

    /// A square domain with a square hole (the middle ninth) and a jittered interior: two
    /// boundary loops.
    pub fn holed(r: &mut ChaCha8Rng, k: usize) -> Triangulation {
        let (lo, hi) = (k as f64, 2.0 * k as f64);
        without(&structured(r, 3 * k), |c| {
            c.x > lo && c.x < hi && c.y > lo && c.y < hi
        })
    }

    /// `full` without the triangles whose centroid satisfies `drop`.
    fn without(full: &Triangulation, drop: impl Fn(Point2<f64>) -> bool) -> Triangulation {
        let keep: Vec<[usize; 3]> = full
            .triangles()
            .iter()
            .filter(|t| {
                let c = t.iter().fold(Point2::origin(), |acc: Point2<f64>, &v| {
                    acc + full.vertex(v as usize).coords / 3.0
                });
                !drop(c)
            })
            .map(|t| t.map(|v| v as usize))
            .collect();
        compact(full.vertices(), &keep)
    }

    /// Drops unused vertices and renumbers.
    pub fn compact(vertices: &[Point2<f64>], tris: &[[usize; 3]]) -> Triangulation {
        let mut map = vec![usize::MAX; vertices.len()];
        let mut verts = Vec::new();
        let tris = tris
            .iter()
            .map(|t| {
                t.map(|v| {
                    if map[v] == usize::MAX {
                        map[v] = verts.len();
                        verts.push(vertices[v]);
                    }
                    map[v]
                })
            })
            .collect();
        Triangulation::new(verts, tris)
    }

    /// One of each kind, for sweeping a property over the whole catalogue.
    pub fn catalogue(seed: u64) -> Vec<(&'static str, Triangulation)> {
        let mut r = rng(seed);
        vec![
            ("uniform", uniform_square(&mut r, 60)),
            ("thin", thin(&mut r, 50)),
            ("boundary-heavy", boundary_heavy(&mut r, 40)),
            ("structured", structured(&mut r, 6)),
            ("l-shape", l_shape(&mut r, 6)),
            ("holed", holed(&mut r, 2)),
        ]
    }
}

/// The Bézier triangle of degree `m` over `t` that interpolates `f` at the domain points λ/m
/// (exact for polynomials of degree ≤ m): the collocation system solved by LU.
pub fn interpolating_bezier(
    t: Triangle2,
    m: usize,
    f: impl Fn(Point2<f64>) -> nalgebra::Vector3<f64>,
) -> crate::bezier::BezierTriangle<nalgebra::Vector3<f64>> {
    use crate::bezier::index::{bernstein, multi_indices};
    let idx: Vec<[usize; 3]> = multi_indices(m).collect();
    let n = idx.len();
    let at = |l: &[usize; 3]| l.map(|x| x as f64 / m as f64);
    let a = nalgebra::DMatrix::from_fn(n, n, |i, j| bernstein(idx[j], at(&idx[i])));
    let rhs = nalgebra::DMatrix::from_fn(n, 3, |i, k| f(t.point(at(&idx[i])))[k]);
    let x = a
        .lu()
        .solve(&rhs)
        .expect("the collocation matrix is regular");
    let points = (0..n)
        .map(|i| nalgebra::Vector3::new(x[(i, 0)], x[(i, 1)], x[(i, 2)]))
        .collect();
    crate::bezier::BezierTriangle::new(t, m, points)
}

/// The functional and parametric PS interpolants of the graph of a height function `f`, which
/// returns (value, ∂/∂x, ∂/∂y), on `basis`.
pub fn graph_splines(
    basis: &std::sync::Arc<crate::ps::PsBasis>,
    f: impl Fn(Point2<f64>) -> (f64, f64, f64) + Sync,
) -> (
    crate::ps::PsSpline<f64>,
    crate::ps::PsSpline<nalgebra::Vector3<f64>>,
) {
    use crate::ps::{Hermite, PsSpline};
    use nalgebra::Vector3;
    let functional = PsSpline::interpolate(basis.clone(), |p| {
        let (value, dx, dy) = f(p);
        Hermite { value, dx, dy }
    })
    .unwrap();
    let parametric = PsSpline::interpolate(basis.clone(), |p| {
        let (v, dx, dy) = f(p);
        Hermite {
            value: Vector3::new(p.x, p.y, v),
            dx: Vector3::new(1.0, 0.0, dx),
            dy: Vector3::new(0.0, 1.0, dy),
        }
    })
    .unwrap();
    (functional, parametric)
}

/// The circular arc of `radius` about the origin in the (x, y) plane from angle −`half` to
/// `half` (< π/2), as a rational quadratic NURBS curve (middle weight cos `half`).
pub fn circular_arc(radius: f64, half: f64) -> crate::nurbs::NurbsCurve {
    use nalgebra::Vector3;
    let (s, c) = half.sin_cos();
    crate::nurbs::NurbsCurve::try_new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Vector3::new(c, -s, 0.0) * radius,
            Vector3::new(1.0 / c, 0.0, 0.0) * radius,
            Vector3::new(c, s, 0.0) * radius,
        ],
        Some(vec![1.0, c, 1.0]),
    )
    .unwrap()
}

/// y = x³ − x on [−1, 1] as a cubic Bézier curve in the plane z = 0 (the control points of the
/// polynomial): one inflection, at x = 0.
pub fn cubic_graph_curve() -> crate::nurbs::NurbsCurve {
    use nalgebra::Vector3;
    crate::nurbs::NurbsCurve::try_new(
        3,
        vec![-1.0, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 1.0],
        vec![
            Vector3::new(-1.0, 0.0, 0.0),
            Vector3::new(-1.0 / 3.0, 4.0 / 3.0, 0.0),
            Vector3::new(1.0 / 3.0, -4.0 / 3.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
        ],
        None,
    )
    .expect("a valid cubic")
}
