use std::sync::Arc;

use nalgebra::{Point2, Vector3};

use super::*;
use crate::ps::{Hermite, Nurps, PsBasis, PsSpline};
use crate::surface::ParametricSurface;
use crate::test_util::*;

/// A wavy graph with noise on its interior control points, as parametric, functional and
/// NURPS surfaces on 400 random points.
fn noisy(seed: u64) -> Vec<(&'static str, Surface)> {
    let mut r = rng(seed);
    let tri = meshes::uniform_square(&mut r, 400);
    let basis = Arc::new(PsBasis::optimal(tri).unwrap());
    let f = |p: Point2<f64>| {
        let (s, c) = (3.0 * p.x).sin_cos();
        (0.2 * s * p.y, 0.6 * c * p.y, 0.2 * s)
    };
    let (functional, parametric) = graph_splines(&basis, f);
    let tri = basis.triangulation();
    let mut out = Vec::new();
    let mut fc = functional.coefficients().to_vec();
    let mut pc = parametric.coefficients().to_vec();
    for i in (0..tri.vertex_count()).filter(|&i| !tri.is_boundary_vertex(i)) {
        for j in 0..3 {
            let e = uniform(&mut r, -0.01, 0.01);
            fc[i][j] += e;
            pc[i][j].z += e;
        }
    }
    let weights = (0..tri.vertex_count())
        .map(|_| std::array::from_fn(|_| uniform(&mut r, 0.8, 1.25)))
        .collect();
    out.push((
        "functional",
        Surface::Functional(PsSpline::new(basis.clone(), fc).unwrap()),
    ));
    out.push((
        "parametric",
        Surface::Parametric(PsSpline::new(basis.clone(), pc.clone()).unwrap()),
    ));
    out.push((
        "nurps",
        Surface::Nurps(Nurps::new(basis, pc, weights).unwrap()),
    ));
    out
}

/// Fairing lowers the energy, keeps the boundary control triangles bitwise, solves its normal
/// equations to 1e-10, and moves less as the weight grows.
#[test]
fn fairing_lowers_the_energy_and_keeps_the_boundary() {
    for (name, s) in noisy(1800) {
        let tri = s.ps_basis().unwrap().triangulation().clone();
        let mut last_move = f64::INFINITY;
        for weight in [0.0, 0.1, 10.0] {
            let opts = FairOptions {
                weight,
                ..FairOptions::default()
            };
            let f = fair(&s, &opts).unwrap_or_else(|e| panic!("{name} w={weight}: {e}"));
            assert!(
                f.energy_after < 0.5 * f.energy_before,
                "{name} w={weight}: {} -> {}",
                f.energy_before,
                f.energy_after
            );
            assert!(f.normal_residual < 1e-10, "{name}: {:e}", f.normal_residual);
            let (a, b) = (s.control_points(), f.surface.control_points());
            for i in (0..tri.vertex_count()).filter(|&i| tri.is_boundary_vertex(i)) {
                for j in 0..3 {
                    assert_eq!(a[3 * i + j], b[3 * i + j], "{name}: boundary vertex {i}");
                }
            }
            assert_eq!(f.surface.kind(), s.kind());
            assert!(
                f.largest_move < last_move,
                "{name}: w={weight} moved {}",
                f.largest_move
            );
            last_move = f.largest_move;
        }
    }
}

/// A surface whose coordinates are quadratic polynomials has no Hessian jumps: fairing leaves
/// it unchanged, whatever the weight. With weight 1 to 1e-12. With weight 0 the energy alone
/// decides, and its matrix is ill-conditioned where triangles are thin: the rounding of its
/// gradient at the surface moves control points by 1.6e-11 on a jittered grid and 1e-7 on a
/// random Delaunay triangulation with slivers (measured), far below anything visible.
#[test]
fn a_quadratic_surface_is_its_own_fairest_surface() {
    let mut r = rng(1801);
    for (mesh, weight, tolerance) in [
        ("grid", 0.0, 1e-10),
        ("grid", 1.0, 1e-12),
        ("random", 0.0, 1e-6),
        ("random", 1.0, 1e-12),
    ] {
        let tri = if mesh == "grid" {
            // The jittered 12 × 12 grid scaled into the unit square.
            let g = meshes::structured(&mut r, 12);
            let v = g
                .vertices()
                .iter()
                .map(|p| Point2::from(p.coords / 12.0))
                .collect();
            let t = g
                .triangles()
                .iter()
                .map(|t| t.map(|i| i as usize))
                .collect();
            crate::triangulation::Triangulation::new(v, t)
        } else {
            meshes::uniform_square(&mut r, 200)
        };
        let basis = Arc::new(PsBasis::optimal(tri).unwrap());
        let s = Surface::Parametric(
            PsSpline::interpolate(basis, |p| Hermite {
                value: Vector3::new(
                    p.x + 0.1 * p.y * p.y,
                    p.y,
                    0.3 * p.x * p.x - 0.2 * p.x * p.y,
                ),
                dx: Vector3::new(1.0, 0.0, 0.6 * p.x - 0.2 * p.y),
                dy: Vector3::new(0.2 * p.y, 1.0, -0.2 * p.x),
            })
            .unwrap(),
        );
        let f = fair(
            &s,
            &FairOptions {
                weight,
                ..FairOptions::default()
            },
        )
        .unwrap();
        assert!(
            f.largest_move < tolerance,
            "{mesh} w={weight}: moved {:e}",
            f.largest_move
        );
        let p = Point2::new(0.4, 0.6);
        assert!((f.surface.point(p).unwrap() - s.point(p).unwrap()).norm() < tolerance);
    }
}

#[test]
fn bad_requests_are_refused() {
    let (_, s) = noisy(1802).remove(0);
    for weight in [-1.0, f64::NAN, f64::INFINITY, 1e308] {
        let opts = FairOptions {
            weight,
            ..FairOptions::default()
        };
        assert!(matches!(fair(&s, &opts), Err(FairError::BadWeight(_))));
    }
    let bezier = Surface::Bezier(
        crate::bezier::BezierTriangle::try_new(
            crate::ps::from_bezier::equilateral(),
            1,
            vec![Vector3::zeros(), Vector3::x(), Vector3::y()],
        )
        .unwrap(),
    );
    assert!(matches!(
        fair(&bezier, &FairOptions::default()),
        Err(FairError::NotPs(_))
    ));
    // One triangle: every vertex is on the boundary.
    let one = crate::triangulation::Triangulation::try_new(
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let b = Arc::new(PsBasis::optimal(one).unwrap());
    let flat = Surface::Functional(PsSpline::new(b, vec![[0.0; 3]; 3]).unwrap());
    assert!(matches!(
        fair(&flat, &FairOptions::default()),
        Err(FairError::NoInterior)
    ));
}

/// The iterative solve (used from [`ITERATIVE_FROM_WEIGHT`] on) and the factorisation agree
/// on the same normal equations to 1e-10 relative, for every kind and several weights; the
/// iteration is the one `fair` chooses there, the factorisation below it and whenever the
/// iteration does not converge.
#[test]
fn conjugate_gradients_agree_with_the_factorisation() {
    for (name, s) in noisy(1802) {
        let basis = s.ps_basis().unwrap();
        let q = basis.energy_matrix(Energy::HessianJumps);
        let interior = interior_numbering(basis.triangulation());
        for weight in [ITERATIVE_FROM_WEIGHT, 0.1, 10.0] {
            let a = interior_system(&q, &interior, weight);
            let m = 3 * a.block_order();
            let mut r = rng(7);
            let rhs: Vec<f64> = (0..2 * m).map(|_| uniform(&mut r, -1.0, 1.0)).collect();
            let (x, steps) = iterate(&a, &rhs, 2, &ITERATIVE_STOP).expect("converges");
            let direct = a.solve_by_cholesky(&rhs, 2).unwrap();
            let norm = |v: &[f64]| v.iter().map(|t| t * t).sum::<f64>().sqrt();
            let diff: Vec<f64> = x.iter().zip(&direct).map(|(a, b)| a - b).collect();
            assert!(
                norm(&diff) <= 1e-10 * norm(&direct),
                "{name} w={weight}: {:e}",
                norm(&diff)
            );
            // (The norms are summed in another order than the iteration's: allow for that.)
            let res = a.relative_residual(&x, &rhs, 2);
            assert!(
                res <= ITERATIVE_RESIDUAL * (1.0 + 1e-9),
                "{name} w={weight}: {res:e}"
            );
            assert!(steps > 0 && steps < ITERATIVE_MAX_STEPS);
            let (_, _, solver) = solve(&a, &rhs, 2, weight, &ITERATIVE_STOP).unwrap();
            assert_eq!(solver, FairSolver::ConjugateGradient { steps }, "{name}");
            // An iteration cut short gives way to the factorisation, with the same answer.
            let short = Stopping {
                max_steps: 2,
                ..ITERATIVE_STOP
            };
            let (y, residual, solver) = solve(&a, &rhs, 2, weight, &short).unwrap();
            assert_eq!(solver, FairSolver::Cholesky, "{name} w={weight}: cut short");
            let diff: Vec<f64> = y.iter().zip(&direct).map(|(a, b)| a - b).collect();
            assert!(
                norm(&diff) <= 1e-13 * norm(&direct),
                "{name} w={weight}: cut short"
            );
            assert!(residual <= 1e-13, "{name} w={weight}: {residual:e}");
        }
        let a = interior_system(&q, &interior, 0.0);
        let ones = vec![1.0; 3 * a.block_order()];
        let (_, _, solver) = solve(&a, &ones, 1, 0.0, &ITERATIVE_STOP).unwrap();
        assert_eq!(solver, FairSolver::Cholesky, "{name}: weight 0");
    }
}
