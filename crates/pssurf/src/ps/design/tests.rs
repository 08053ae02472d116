use super::*;
use crate::ps::PatchId;
use crate::ps::tests::bases;
use crate::test_util::*;

use nalgebra::{Point2, Rotation2};

/// The sub-triangles of Δ* at V_i: (triangle, sub) with V_i as a corner.
fn subs_at(basis: &PsBasis, i: usize) -> Vec<(usize, usize)> {
    let t = basis.triangulation();
    t.molecule(i)
        .iter()
        .flat_map(|&tr| {
            let tr = tr as usize;
            let c = t.triangle(tr).iter().position(|&v| v == i).unwrap();
            [(tr, 2 * c), (tr, (2 * c + 5) % 6)]
        })
        .collect()
}

/// (3.73)–(3.83): with all three weights of V_i equal to W, the sub-triangles at V_i approach
/// the control plane T_i like 1/W.
#[test]
fn large_weights_make_the_surface_planar_around_the_vertex() {
    let mut r = rng(1770);
    let mut checked = 0;
    for (name, basis) in bases(17) {
        let n = basis.triangulation().vertex_count();
        let pts = random_vec3_triples(&mut r, n);
        let weights = (0..n)
            .map(|_| std::array::from_fn(|_| uniform(&mut r, 0.3, 3.0)))
            .collect();
        let original = Nurps::new(basis.clone(), pts, weights).unwrap();
        for _ in 0..4 {
            // One vertex at a time: a flattened neighbour would compete for the same pieces.
            let mut s = original.clone();
            let i = (uniform(&mut r, 0.0, 1.0) * n as f64) as usize % n;
            let c = s.points()[i];
            let normal = (c[1] - c[0]).cross(&(c[2] - c[0])).normalize();
            let samples: Vec<_> = subs_at(&basis, i)
                .into_iter()
                .flat_map(|sub| (0..10).map(move |_| sub))
                .map(|sub| (sub, random_bary(&mut r)))
                .collect();
            let off_plane = |s: &Nurps<Vector3<f64>>| {
                samples
                    .iter()
                    .map(|&((t, sub), tau)| {
                        let p = s.patch(t, sub).eval_bary(tau).unwrap();
                        (p - c[0]).dot(&normal).abs()
                    })
                    .fold(0.0f64, f64::max)
            };
            let before = off_plane(&s);
            s.planar_section(i, 1e3).unwrap();
            let at_1e3 = off_plane(&s);
            s.planar_section(i, 1e6).unwrap();
            let at_1e6 = off_plane(&s);
            // The distance is C / W with C of the order of the initial distance.
            assert!(at_1e6 < 1e-4 * before.max(1.0), "{name}: {at_1e6:e}");
            let ratio = at_1e3 / at_1e6;
            assert!((300.0..3000.0).contains(&ratio), "{name}: ratio {ratio}");
            checked += 1;
        }
    }
    assert!(checked >= 20, "{checked}");
}

/// (3.84)–(3.85): a control triangle collapsed to a point C puts s(V_i) = C with all first
/// derivatives zero there (a cusp), and not in the sub-triangles' interiors; collapsed to a
/// line, the tangent plane at V_i degenerates to that line.
#[test]
fn degenerate_control_triangles_make_cusps() {
    let mut r = rng(1771);
    let mut checked = 0;
    for (name, basis) in bases(18) {
        let t = basis.triangulation();
        let n = t.vertex_count();
        let mut s = PsSpline::new(basis.clone(), random_vec3_triples(&mut r, n)).unwrap();
        let size = 10.0;
        for _ in 0..4 {
            let i = (uniform(&mut r, 0.0, 1.0) * n as f64) as usize % n;
            let cusp = random_vec3(&mut r);
            s.degenerate_control_triangle(i, Degenerate::Point(cusp))
                .unwrap();
            for (tr, sub) in subs_at(&basis, i) {
                let j = s.jet_on_patch(PatchId::new(tr, sub), t.vertex(i));
                assert!((j.value - cusp).norm() < 1e-12 * size, "{name}");
                assert!(
                    j.dx.norm() + j.dy.norm() < 1e-11 * size,
                    "{name}: {:e}",
                    j.dx.norm()
                );
                let inside = basis.sub_triangle(tr, sub).point([0.2, 0.4, 0.4]);
                let k = s.jet_on_patch(PatchId::new(tr, sub), inside);
                assert!(k.dx.cross(&k.dy).norm() > 1e-9, "{name}: flat inside");
            }
            let (through, direction) = (random_vec3(&mut r), random_vec3(&mut r));
            s.degenerate_control_triangle(i, Degenerate::Line { through, direction })
                .unwrap();
            for c in &s.coefficients()[i] {
                assert!((c - through).cross(&direction).norm() < 1e-12 * size * size);
            }
            for (tr, sub) in subs_at(&basis, i) {
                let j = s.jet_on_patch(PatchId::new(tr, sub), t.vertex(i));
                let cross = j.dx.cross(&j.dy).norm();
                assert!(
                    cross < 1e-11 * (1.0 + j.dx.norm() * j.dy.norm()),
                    "{name}: {cross:e}"
                );
            }
            checked += 1;
        }
        let line = Degenerate::Line {
            through: Vector3::zeros(),
            direction: Vector3::zeros(),
        };
        assert!(s.degenerate_control_triangle(0, line).is_err());
    }
    assert!(checked >= 20, "{checked}");
}

/// (3.86): the control triangles of both ends of an edge collapsed to points C_i ≠ C_j make a
/// corner along it: on both sides, every first derivative on the edge is parallel to
/// C_i − C_j.
#[test]
fn two_degenerate_control_triangles_make_a_corner_along_their_edge() {
    let mut r = rng(1772);
    let mut checked = 0;
    for (name, basis) in bases(19) {
        let t = basis.triangulation();
        let n = t.vertex_count();
        let pts = random_vec3_triples(&mut r, n);
        let weights = (0..n)
            .map(|_| std::array::from_fn(|_| uniform(&mut r, 0.3, 3.0)))
            .collect();
        let mut s = Nurps::new(basis.clone(), pts, weights).unwrap();
        for _ in 0..3 {
            let tr = (uniform(&mut r, 0.0, 1.0) * t.triangle_count() as f64) as usize
                % t.triangle_count();
            let [i, j, _] = t.triangle(tr);
            let (ci, cj) = (random_vec3(&mut r), random_vec3(&mut r));
            s.degenerate_control_triangle(i, Degenerate::Point(ci))
                .unwrap();
            s.degenerate_control_triangle(j, Degenerate::Point(cj))
                .unwrap();
            let along = (ci - cj).normalize();
            // Every triangle with the edge (i, j), on both of its sub-triangles at the edge.
            for &other in t.molecule(i) {
                let other = other as usize;
                let v = t.triangle(other);
                let Some(c) = (0..3).find(|&c| {
                    v[c] == i && v[(c + 1) % 3] == j || v[c] == j && v[(c + 1) % 3] == i
                }) else {
                    continue;
                };
                for sub in [2 * c, 2 * c + 1] {
                    let piece = s.patch(other, sub);
                    for k in 1..10 {
                        let a = k as f64 / 10.0;
                        let p = t.vertex(i) + (t.vertex(j) - t.vertex(i)) * a;
                        let Ok(jet) = piece.jet(p) else { continue };
                        for d in [jet.dx, jet.dy] {
                            let off = d.cross(&along).norm();
                            assert!(off < 1e-10 * (1.0 + d.norm()), "{name}: {off:e}");
                        }
                    }
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 30, "{checked}");
}

/// A PS-triangle made 1–2.5 times larger about its centroid and turned by up to 0.3 rad (it
/// may miss a PS-point: the caller counts those).
fn other_triangle(r: &mut rand_chacha::ChaCha8Rng, old: &Triangle2) -> Triangle2 {
    let centre = Point2::from((old.v[0].coords + old.v[1].coords + old.v[2].coords) / 3.0);
    let (grow, turn) = (uniform(r, 1.0, 2.5), uniform(r, -0.3, 0.3));
    let rot = Rotation2::new(turn);
    Triangle2 {
        v: old.v.map(|p| centre + rot * (p - centre) * grow),
    }
}

/// Replacing a PS-triangle by another valid one keeps the surface (functional, parametric and
/// NURPS); a triangle that misses a PS-point is refused, and so is one that would need a
/// non-positive weight.
#[test]
fn replacing_a_ps_triangle_keeps_the_surface() {
    let mut r = rng(1773);
    let (mut checked, mut outside, mut bad_weight) = (0, 0, 0);
    for (name, basis) in bases(20) {
        let t = basis.triangulation();
        let n = t.vertex_count();
        let heights: Vec<[f64; 3]> = (0..n)
            .map(|_| std::array::from_fn(|_| uniform(&mut r, -1.0, 1.0)))
            .collect();
        let f = PsSpline::new(basis.clone(), heights).unwrap();
        let weights: Vec<[f64; 3]> = (0..n)
            .map(|_| std::array::from_fn(|_| uniform(&mut r, 0.5, 2.0)))
            .collect();
        let g = Nurps::new(basis.clone(), random_vec3_triples(&mut r, n), weights).unwrap();
        for _ in 0..12 {
            let i = (uniform(&mut r, 0.0, 1.0) * n as f64) as usize % n;
            let new = other_triangle(&mut r, basis.ps_triangle(i));
            let f2 = match f.with_ps_triangle(i, new) {
                Ok(f2) => f2,
                Err(PsError::PsPointOutside { .. }) => {
                    outside += 1;
                    continue;
                }
                Err(e) => panic!("{name}: {e}"),
            };
            let g2 = match g.with_ps_triangle(i, new) {
                Ok(g2) => Some(g2),
                Err(PsError::InvalidWeight { .. }) => {
                    bad_weight += 1;
                    None
                }
                Err(e) => panic!("{name}: {e}"),
            };
            assert_ne!(f2.coefficients()[i], f.coefficients()[i]);
            for &tr in t.molecule(i) {
                let tri = t.triangle_geometry(tr as usize);
                for _ in 0..10 {
                    let p = tri.point(random_bary(&mut r));
                    let (a, b) = (f.eval(p).unwrap(), f2.eval(p).unwrap());
                    assert!(
                        (a - b).abs() < 1e-12 * (1.0 + a.abs()),
                        "{name}: {a} vs {b}"
                    );
                    if let Some(g2) = &g2 {
                        let (a, b) = (g.eval(p).unwrap(), g2.eval(p).unwrap());
                        assert!((a - b).norm() < 1e-12 * (1.0 + a.norm()), "{name}");
                        let (ja, jb) = (g.jet(p).unwrap().jet, g2.jet(p).unwrap().jet);
                        assert!((ja.dxx - jb.dxx).norm() < 1e-8 * (1.0 + ja.dxx.norm()));
                    }
                }
            }
            checked += 1;
        }
        // Too small: the PS-triangle shrunk towards its centre misses a PS-point.
        let old = basis.ps_triangle(0);
        let centre = Point2::from((old.v[0].coords + old.v[1].coords + old.v[2].coords) / 3.0);
        let small = Triangle2 {
            v: old.v.map(|p| centre + (p - centre) * 0.5),
        };
        assert!(matches!(
            f.with_ps_triangle(0, small),
            Err(PsError::PsPointOutside { vertex: 0, .. })
        ));
    }
    assert!(
        checked >= 40 && outside + bad_weight <= checked,
        "{checked} checked, {outside} outside, {bad_weight} non-positive weights"
    );
}

/// Shape parameters and their inverse, (3.67) and (3.72), as plain functions.
#[test]
fn weights_for_shape_inverts_shape_parameters() {
    let mut r = rng(1774);
    for _ in 0..200 {
        let alpha = random_bary(&mut r).map(|a| 0.05 + a);
        let s: f64 = alpha.iter().sum();
        let alpha = alpha.map(|a| a / s);
        let w = std::array::from_fn(|_| uniform(&mut r, 0.1, 10.0));
        let target = random_bary(&mut r).map(|a| 0.01 + a);
        let s: f64 = target.iter().sum();
        let target = target.map(|a| a / s);
        let w2 = weights_for_shape(3, alpha, w, target).unwrap();
        let got = shape_parameters(alpha, w2);
        for k in 0..3 {
            assert_near!(got[k], target[k], 1e-13);
        }
        let ws = |w: [f64; 3]| (0..3).map(|j| alpha[j] * w[j]).sum::<f64>();
        assert_near!(ws(w2), ws(w), 1e-13 * ws(w));
    }
    assert!(weights_for_shape(1, [0.3, 0.3, 0.4], [1.0; 3], [0.5, 0.6, -0.1]).is_err());
}
