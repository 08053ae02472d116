//! Issue 12: fitting scattered data never writes a surface that does not load again, and
//! estimated gradients stay bounded on nearly gridded data.
#![cfg(feature = "io")]

use pssurf::prelude::*;
use pssurf::scattered::{GradientMethod, interpolate};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

const METHODS: [GradientMethod; 2] = [GradientMethod::Local, GradientMethod::Global];

/// The interpolant as `pssurf fit` makes it (Delaunay triangulation, incentre split,
/// optimal PS-triangles) with gradients estimated by `method`.
fn fit(points: &[Point2<f64>], z: &[f64], method: GradientMethod) -> PsSpline<f64> {
    try_fit(points, z, method).unwrap()
}

fn try_fit(
    points: &[Point2<f64>],
    z: &[f64],
    method: GradientMethod,
) -> Result<PsSpline<f64>, String> {
    interpolate(points, z, method)
        .map(|i| i.spline)
        .map_err(|e| e.to_string())
}

/// Writes the spline in the file format and reads it back (which validates it).
fn round_trip(s: &PsSpline<f64>) -> Result<Surface, String> {
    let text = pssurf::io::to_json_string(&Surface::from(s.clone()));
    pssurf::io::from_json_str(&text).map_err(|e| e.to_string())
}

fn grid(n: usize, jitter: f64, seed: u64) -> Vec<Point2<f64>> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let h = 1.0 / (n - 1) as f64;
    let mut pts = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let mut p = Point2::new(i as f64 * h, j as f64 * h);
            if i > 0 && j > 0 && i + 1 < n && j + 1 < n {
                p.x += r.random_range(-jitter..=jitter);
                p.y += r.random_range(-jitter..=jitter);
            }
            pts.push(p);
        }
    }
    pts
}

/// Adversarial point sets: the minimal case, nearly collinear runs, jittered grids,
/// clusters of points within 1e-12 of each other, large offsets with small spreads.
fn adversarial_sets() -> Vec<(String, Vec<Point2<f64>>)> {
    let p = Point2::new;
    let mut sets = vec![(
        "issue 12 minimal case".to_string(),
        vec![
            p(1., 4.),
            p(2., 3.),
            p(3., 0.),
            p(3., 1.),
            p(3., 4.),
            p(4., 0.),
        ],
    )];
    let mut r = ChaCha8Rng::seed_from_u64(12);
    for delta in [1e-12, 1e-9, 1e-6, 1e-3] {
        sets.push((format!("jittered grid δ={delta:e}"), grid(12, delta, 1)));
    }
    sets.extend(offset_set(&mut r, 1e6));
    sets.extend(offset_set(&mut r, 1e9));
    for k in 0..12 {
        // Random 20 % subsamples of a grid (the real-terrain case of the issue).
        let full = grid(25, 0.0, 0);
        let pts: Vec<Point2<f64>> = full.into_iter().filter(|_| r.random_bool(0.2)).collect();
        sets.push((format!("20% subsample {k}"), pts));
    }
    sets
}

/// Large offsets with small spreads.
fn offset_set(r: &mut ChaCha8Rng, offset: f64) -> Option<(String, Vec<Point2<f64>>)> {
    let pts: Vec<Point2<f64>> = (0..30)
        .map(|_| {
            Point2::new(
                offset + r.random_range(0.0..1e-3),
                offset + r.random_range(0.0..1e-3),
            )
        })
        .collect();
    Some((format!("offset {offset:e} spread 1e-3"), pts))
}

/// Sets on which the Delaunay triangulation has boundary slivers (nearly collinear runs on
/// the hull) or needles between nearly coincident points.
fn sliver_sets() -> Vec<(String, Vec<Point2<f64>>)> {
    let p = Point2::new;
    let mut sets = Vec::new();
    let mut r = ChaCha8Rng::seed_from_u64(13);
    for k in 0..6 {
        // A nearly collinear run with a few points off the line.
        let mut pts: Vec<Point2<f64>> = (0..20)
            .map(|i| {
                p(
                    i as f64 * 0.1,
                    i as f64 * 0.1 + r.random_range(-1e-12..1e-12),
                )
            })
            .collect();
        pts.extend((0..3).map(|i| p(0.3 + i as f64 * 0.5, 1.5 + k as f64 * 0.1)));
        sets.push((format!("nearly collinear run {k}"), pts));
    }
    for k in 0..4 {
        // Clusters: points within 1e-12 of a few centres.
        let mut pts = Vec::new();
        for c in [p(0., 0.), p(1., 0.), p(0.4, 0.9), p(0.6, 0.3)] {
            for _ in 0..4 {
                let e = 1e-12 * (k + 1) as f64;
                pts.push(p(c.x + r.random_range(-e..e), c.y + r.random_range(-e..e)));
            }
        }
        sets.push((format!("clusters {k}"), pts));
    }
    sets
}

/// Fits every set and reloads the written surface; returns how many were tried and what
/// failed.
fn fit_and_reload(sets: Vec<(String, Vec<Point2<f64>>)>) -> (usize, Vec<String>) {
    let mut tried = 0;
    let mut failed = Vec::new();
    for (name, pts) in sets {
        let mut unique = pts.clone();
        unique.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        unique.dedup();
        let z: Vec<f64> = unique.iter().map(|q| (3.0 * q.x).sin() * q.y).collect();
        tried += 1;
        for method in METHODS {
            match try_fit(&unique, &z, method) {
                Ok(s) => {
                    if let Err(e) = round_trip(&s) {
                        failed.push(format!(
                            "{name}, {method:?}: the written surface does not load: {e}"
                        ));
                    }
                }
                Err(e) => failed.push(format!("{name}, {method:?}: no fit: {e}")),
            }
        }
    }
    (tried, failed)
}

#[test]
fn fit_writes_files_that_load_on_near_degenerate_sets() {
    let (tried, failed) = fit_and_reload(adversarial_sets());
    assert!(failed.is_empty(), "{}", failed.join("\n"));
    assert_eq!(tried, 19, "every set fitted and reloaded");
}

/// Nearly collinear runs on the hull make boundary slivers, which the Delaunay triangulation
/// peels off (thinner than `PEEL_THICKNESS`); points within 1e-12 of each other are merged
/// into their mean. Every fit succeeds, loads again, interpolates every (merged) value and
/// stays bounded.
#[test]
fn fit_handles_slivers_and_near_duplicates() {
    let (tried, failed) = fit_and_reload(sliver_sets());
    assert!(failed.is_empty(), "{}", failed.join("\n"));
    assert_eq!(tried, 10);
    for (name, pts) in sliver_sets() {
        let z: Vec<f64> = pts.iter().map(|q| (3.0 * q.x).sin() * q.y).collect();
        let fit = interpolate(&pts, &z, GradientMethod::Local).unwrap();
        if name.starts_with("clusters") {
            // Four centres, four points each.
            assert_eq!(fit.merged.len(), 4, "{name}");
            assert!(fit.merged.iter().all(|g| g.len() == 4), "{name}");
        } else {
            assert!(fit.merged.is_empty(), "{name}");
        }
        let t = fit.spline.basis().triangulation();
        let mut at = fit.spline.evaluator();
        let z_max = z.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (k, &row) in fit.data_index.iter().enumerate() {
            let group = fit.merged.iter().find(|g| g[0] == row);
            let want = group.map_or(z[row], |g| {
                g.iter().map(|&i| z[i]).sum::<f64>() / g.len() as f64
            });
            let got = at.value(t.vertex(k)).expect("a vertex is in the domain");
            assert!(
                (got - want).abs() <= 1e-12 * z_max,
                "{name}: vertex {k}: {got} vs {want}"
            );
        }
        // Bounded between the data: sample every triangle at interior points.
        for tr in 0..t.triangle_count() {
            let g = t.triangle_geometry(tr);
            for b in [
                [1.0 / 3.0; 3],
                [0.6, 0.2, 0.2],
                [0.2, 0.6, 0.2],
                [0.2, 0.2, 0.6],
            ] {
                let v = at.value(g.point(b)).expect("inside its triangle");
                assert!(v.abs() <= 10.0 * z_max, "{name}: triangle {tr}: {v}");
            }
        }
    }
}

/// The largest error of the fit of sin(3x) cos(2y) on a 20 × 20 grid jittered by `delta`,
/// over a 40 × 40 grid of the unit square.
fn grid_error(delta: f64, method: GradientMethod) -> f64 {
    let f = |x: f64, y: f64| (3.0 * x).sin() * (2.0 * y).cos();
    let pts = grid(20, delta, 2);
    let z: Vec<f64> = pts.iter().map(|p| f(p.x, p.y)).collect();
    let s = fit(&pts, &z, method);
    let mut at = s.evaluator();
    let mut worst: f64 = 0.0;
    for i in 0..40 {
        for j in 0..40 {
            let q = Point2::new(i as f64 / 39.0, j as f64 / 39.0);
            let v = at.value(q).expect("inside the domain");
            worst = worst.max((v - f(q.x, q.y)).abs());
        }
    }
    worst
}

#[test]
fn gradients_do_not_explode_on_nearly_gridded_data() {
    for method in METHODS {
        let unperturbed = grid_error(0.0, method);
        assert!(unperturbed < 1e-2, "{method:?}: {unperturbed}");
        for delta in [1e-12, 1e-9, 1e-6, 1e-3] {
            let e = grid_error(delta, method);
            assert!(
                e < 3.0 * unperturbed,
                "{method:?}, δ = {delta:e}: max error {e:.3e}, unperturbed {unperturbed:.3e}"
            );
        }
    }
}
