//! The surfaces of the showcase (seed 000, section 4) and the numbers that compare them.

use std::sync::Arc;

use nalgebra::{Point2, Vector3};
use pssurf::interrogate::{Curvature, DEFAULT_QUADRATURE_DEGREE, FairnessIntegrals, fairness};
use pssurf::noise::NoiseKind;
use pssurf::ps::{Hermite, PsBasis, PsSpline};
use pssurf::surface::{ParametricSurface, Surface, UpsSurface};
use pssurf::triangulation::Triangulation;
use pssurf::ups::threshold::{Shrink, ThresholdRule};
use pssurf::ups::wavelet::Update;
use pssurf::ups::{Lattice, LatticePolygon, Ups, UpsGrid};
use rand::{RngExt, SeedableRng};

/// The amplitude of the uniform noise added to every control point (the domain is about 4
/// units across).
pub const NOISE: f64 = 0.02;
/// Subdivision steps before the noise, and wavelet levels of the denoising.
pub const LEVELS: u32 = 3;

/// The smooth surface: a parametric UPS surface on the hexagon with two triangles per side,
/// interpolating the graph of 0.5 sin(1.4x) cos(1.1y) + 0.08 x y.
pub fn smooth() -> Ups<Vector3<f64>> {
    let lattice = Lattice {
        base: 1.0,
        origin: Point2::new(-2.0, -3f64.sqrt()),
    };
    let grid = UpsGrid::new(
        lattice,
        LatticePolygon::standard(6, 2).expect("a valid hexagon"),
    )
    .expect("a valid grid");
    Ups::hermite(grid, |p| {
        let (x, y) = (p.x, p.y);
        Hermite {
            value: Vector3::new(x, y, 0.5 * (1.4 * x).sin() * (1.1 * y).cos() + 0.08 * x * y),
            dx: Vector3::new(1.0, 0.0, 0.7 * (1.4 * x).cos() * (1.1 * y).cos() + 0.08 * y),
            dy: Vector3::new(
                0.0,
                1.0,
                -0.55 * (1.4 * x).sin() * (1.1 * y).sin() + 0.08 * x,
            ),
        }
    })
}

/// One surface of the comparison.
pub struct Variant {
    /// File-name stem.
    pub key: &'static str,
    /// Caption.
    pub title: String,
    /// The surface.
    pub surface: Surface,
    /// The share of wavelet coefficients set to zero, in percent (denoised surfaces).
    pub zeroed_percent: Option<f64>,
}

/// The original, the noisy surface and its denoised versions.
pub fn variants() -> Vec<Variant> {
    let original = smooth().subdivide_times(LEVELS as usize);
    let noisy = original.with_noise(NOISE, NoiseKind::Uniform, 2003);
    let wrap = |u: Ups<Vector3<f64>>| {
        Surface::try_from(UpsSurface::Parametric(u)).expect("the showcase's values are small")
    };
    let mut out = vec![
        Variant {
            key: "original",
            title: format!("original (subdivided {LEVELS}×)"),
            surface: wrap(original),
            zeroed_percent: None,
        },
        Variant {
            key: "noisy",
            title: format!("noise added (uniform, ±{NOISE})"),
            surface: wrap(noisy.clone()),
            zeroed_percent: None,
        },
    ];
    for (key, title, rule, mode) in [
        (
            "hard5",
            "hard thresholding 5 %",
            ThresholdRule::PercentOfMax(5.0),
            Shrink::Hard,
        ),
        (
            "soft5",
            "soft thresholding 5 %",
            ThresholdRule::PercentOfMax(5.0),
            Shrink::Soft,
        ),
        (
            "soft10",
            "soft thresholding 10 %",
            ThresholdRule::PercentOfMax(10.0),
            Shrink::Soft,
        ),
        (
            "sure",
            "soft, SURE threshold (automatic)",
            ThresholdRule::Sure,
            Shrink::Soft,
        ),
    ] {
        // The stable update, as `pssurf denoise` (docs/ups.md).
        let mut dec = noisy
            .wavelet_transform_with(LEVELS, Update::Stable)
            .expect("a surface subdivided LEVELS times coarsens LEVELS times");
        let stats = dec.threshold(|_, _| rule, mode);
        let (zeroed, count) = stats
            .iter()
            .fold((0, 0), |(z, c), s| (z + s.zeroed, c + s.count));
        out.push(Variant {
            key,
            title: title.into(),
            surface: wrap(dec.reconstruct()),
            zeroed_percent: Some(100.0 * zeroed as f64 / count.max(1) as f64),
        });
    }
    out
}

/// How a surface compares with the original.
pub struct Comparison {
    /// RMS distance of the points at the same parameters.
    pub position_rms: f64,
    /// RMS difference of the mean curvature at the same parameters.
    pub mean_curvature_rms: f64,
    /// RMS difference of the Gaussian curvature.
    pub gaussian_rms: f64,
    /// The fairness integrals.
    pub fairness: FairnessIntegrals,
}

/// Random parameter points of a surface's domain (one per triangle piece, seeded).
pub fn sample_points(s: &Surface, n: usize) -> Vec<Point2<f64>> {
    let tri = s.ps_basis().expect("a PS surface").triangulation();
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    (0..n)
        .map(|_| {
            let t = r.random_range(0..tri.triangle_count());
            let (mut a, mut b) = (r.random_range(0.0..1.0), r.random_range(0.0..1.0));
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            tri.triangle_geometry(t).point([a, b, 1.0 - a - b])
        })
        .collect()
}

/// Compares `s` with the original at the points.
pub fn compare(original: &Surface, s: &Surface, points: &[Point2<f64>]) -> Comparison {
    let (mut p2, mut h2, mut k2) = (0.0, 0.0, 0.0);
    let (mut c0, mut c1) = (original.cursor_near(points[0]), s.cursor_near(points[0]));
    for &p in points {
        let (a, b) = (
            original.jet_with(p, &mut c0).expect("inside"),
            s.jet_with(p, &mut c1).expect("same domain"),
        );
        p2 += (a.jet.value - b.jet.value).norm_squared();
        if let (Ok(ca), Ok(cb)) = (Curvature::from_jet(&a.jet), Curvature::from_jet(&b.jet)) {
            h2 += (ca.mean - cb.mean).powi(2);
            k2 += (ca.gaussian - cb.gaussian).powi(2);
        }
    }
    let n = points.len() as f64;
    Comparison {
        position_rms: (p2 / n).sqrt(),
        mean_curvature_rms: (h2 / n).sqrt(),
        gaussian_rms: (k2 / n).sqrt(),
        fairness: fairness(s, DEFAULT_QUADRATURE_DEGREE).integrals,
    }
}

/// A single PS B-spline basis function (seed 000, Figure 4): the functional PS-spline with
/// coefficient 1 for basis function B_0^0 of the centre vertex and 0 elsewhere, on a
/// triangulation of a centre, a ring of 6 and a ring of 12 points.
pub fn basis_function() -> Surface {
    let mut pts = vec![Point2::new(0.0, 0.0)];
    for (ring, count) in [(1.0, 6), (2.0, 12)] {
        for k in 0..count {
            let a = std::f64::consts::TAU * (k as f64 + 0.25) / count as f64;
            pts.push(Point2::new(ring * a.cos(), ring * a.sin()));
        }
    }
    let tri = Triangulation::delaunay(pts).expect("distinct points");
    let basis = Arc::new(PsBasis::optimal(tri).expect("a valid triangulation"));
    let centre = (0..basis.triangulation().vertex_count())
        .min_by(|&a, &b| {
            basis
                .triangulation()
                .vertex(a)
                .coords
                .norm()
                .total_cmp(&basis.triangulation().vertex(b).coords.norm())
        })
        .expect("vertices");
    let mut coeffs = vec![[0.0; 3]; basis.triangulation().vertex_count()];
    coeffs[centre][0] = 1.0;
    Surface::Functional(PsSpline::new(basis, coeffs).expect("finite coefficients"))
}
