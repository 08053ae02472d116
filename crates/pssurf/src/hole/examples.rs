//! The thesis' hole-filling examples (5.4, 5.6) and a two-curve gap, as boundaries with the
//! surfaces around them.

use std::f64::consts::{FRAC_PI_4, PI};
use std::sync::Arc;

use nalgebra::Vector3;

use super::boundary::unit;
use super::curves::{BoundaryCurve, CurveFns, NormalField, NurbsBoundary, Reversed, SurfaceEdge};
use super::{DynCurve, HoleBoundary, HoleError, two_curve_gap};
use crate::nurbs::{NurbsCurve, NurbsSurface};
use crate::ps::quadrics::Quadric;
use crate::surface::Surface;

/// A built-in example: the holes to fill and the surfaces around them.
pub struct HoleExample {
    /// The example's name.
    pub name: &'static str,
    /// One boundary per filling patch.
    pub holes: Vec<HoleBoundary>,
    /// The surrounding surfaces, or the surface the patch replaces (for pictures and
    /// scenes; may be empty).
    pub surroundings: Vec<Surface>,
}

/// The names of the built-in examples.
pub const EXAMPLES: [&str; 5] = [
    "hole-sphere",
    "two-cylinders",
    "prism-cap",
    "two-curve-gap",
    "degenerate-nurbs",
];

/// The example called `name`.
pub fn example(name: &str) -> Option<Result<HoleExample, HoleError>> {
    Some(match name {
        "hole-sphere" => sphere_hole(1.0),
        "two-cylinders" => cylinder_blend(1.0, PI / 6.0),
        "prism-cap" => prism_cap(1.0, 1.0, 0.5),
        "two-curve-gap" => saddle_gap(),
        "degenerate-nurbs" => degenerate_nurbs(35.0, 100.0),
        _ => return None,
    })
}

/// The rational quadratic Bézier curve p0, p1 (weight w), p2 as a NURBS curve.
fn conic(p: [Vector3<f64>; 3], w: f64) -> NurbsCurve {
    NurbsCurve::try_new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        p.to_vec(),
        Some(vec![1.0, w, 1.0]),
    )
    .expect("a valid conic")
}

/// A curve on the sphere of radius r about the origin, its normals radial.
fn on_sphere(c: NurbsCurve) -> Arc<dyn BoundaryCurve + Send + Sync> {
    Arc::new(NurbsBoundary {
        normals: NormalField::Curve(c.clone()),
        curve: c,
    })
}

/// The hole in the NURPS sphere (thesis 5.4, Figure 5.9): the sextant of the sphere with six
/// sectors (3.6.3) leaves a lens-shaped gap around the equator between its northern and
/// southern patch. The meridian through the middle of the gap bisects it into two
/// triangular holes.
pub fn sphere_hole(radius: f64) -> Result<HoleExample, HoleError> {
    let b = PI / 6.0;
    let (s, c) = b.sin_cos();
    let r = radius;
    let rise = (s / c).powi(2);
    let (west, east) = (Vector3::new(c, -s, 0.0) * r, Vector3::new(c, s, 0.0) * r);
    // The northern patch's lower edge (west → east) and the southern patch's upper edge
    // (east → west), each a conic of (3.118) with middle weight cos² b.
    let north = conic([west, Vector3::new(1.0 / c, 0.0, rise) * r, east], c * c);
    let south = conic([east, Vector3::new(1.0 / c, 0.0, -rise) * r, west], c * c);
    // Their middles at height ±g: the meridian arc between them.
    let top = north.point(0.5).expect("inside");
    let phi = (top.z / r).asin();
    let meridian = conic(
        [
            Vector3::new(phi.cos(), 0.0, phi.sin()) * r,
            Vector3::new(1.0 / phi.cos(), 0.0, 0.0) * r,
            Vector3::new(phi.cos(), 0.0, -phi.sin()) * r,
        ],
        phi.cos(),
    );
    let holes = two_curve_gap(on_sphere(north), on_sphere(south), on_sphere(meridian))?;
    let patches = Quadric::Sphere { radius, sectors: 6 }
        .bezier_patches()
        .map_err(|e| HoleError::Evaluation(e.to_string()))?;
    Ok(HoleExample {
        name: "hole-sphere",
        holes: holes.into_iter().collect(),
        surroundings: patches
            .into_iter()
            .take(2)
            .map(Surface::RationalBezier)
            .collect(),
    })
}

/// A boundary curve from closures.
fn curve(
    point: impl Fn(f64) -> Vector3<f64> + Send + Sync + 'static,
    tangent: impl Fn(f64) -> Vector3<f64> + Send + Sync + 'static,
    normal: impl Fn(f64) -> Vector3<f64> + Send + Sync + 'static,
) -> CurveFns {
    CurveFns {
        point: Arc::new(point),
        tangent: Arc::new(tangent),
        normal: Arc::new(normal),
    }
}

/// Blending two intersecting cylinders (thesis 5.6.1, Figure 5.27), the patch over the first
/// quadrant: C₁ about the y-axis and C₂ about the x-axis, both of radius r, meet at
/// t = (0, 0, r) and b = (r, r, 0). The planes through the z-axis at 45° ± θ cut C₁ along the
/// ellipse E₁ (to c₁ in z = 0) and C₂ along E₂ (to c₂); the third curve is the quadratic
/// Bézier curve c₂, b, c₁ in z = 0 with horizontal normals.
pub fn cylinder_blend(r: f64, theta: f64) -> Result<HoleExample, HoleError> {
    let k = (FRAC_PI_4 + theta).tan();
    // E₂ from t to c₂ on y² + z² = r²: (k y, y, z) with y = r sin ψ, z = r cos ψ.
    let q = PI / 2.0;
    let e2 = curve(
        move |t| Vector3::new(k * r * (q * t).sin(), r * (q * t).sin(), r * (q * t).cos()),
        move |t| Vector3::new(k * (q * t).cos(), (q * t).cos(), -(q * t).sin()) * (r * q),
        move |t| Vector3::new(0.0, (q * t).sin(), (q * t).cos()),
    );
    // E₁ from c₁ to t on x² + z² = r²: (x, k x, z) with x = r cos ψ, z = r sin ψ.
    let e1 = curve(
        move |t| Vector3::new(r * (q * t).cos(), k * r * (q * t).cos(), r * (q * t).sin()),
        move |t| Vector3::new(-(q * t).sin(), -k * (q * t).sin(), (q * t).cos()) * (r * q),
        move |t| Vector3::new((q * t).cos(), 0.0, (q * t).sin()),
    );
    let (c2, bp, c1) = (
        Vector3::new(k * r, r, 0.0),
        Vector3::new(r, r, 0.0),
        Vector3::new(r, k * r, 0.0),
    );
    let bez = move |t: f64| c2 * (1.0 - t).powi(2) + bp * (2.0 * t * (1.0 - t)) + c1 * (t * t);
    let dbez = move |t: f64| ((bp - c2) * (1.0 - t) + (c1 - bp) * t) * 2.0;
    let floor = curve(bez, dbez, move |t| dbez(t).cross(&Vector3::z()));
    let hole = HoleBoundary::new(vec![Box::new(e2), Box::new(floor), Box::new(e1)])?;
    Ok(HoleExample {
        name: "two-cylinders",
        holes: vec![hole],
        surroundings: Vec::new(),
    })
}

/// A cap on a prism (thesis 5.6.2, Figure 5.28): the upright prism over the equilateral
/// triangle of circumradius `r`, of height `height`, gets three triangular patches, each
/// bounded by a top edge and two quadratic Bézier curves from the edge's ends to the
/// junction J = (0, 0, height + rise): first leg straight up along the prism's vertical edge,
/// second leg level to J. Along those curves the normals lie in their vertical planes; at J
/// they are vertical.
pub fn prism_cap(r: f64, height: f64, rise: f64) -> Result<HoleExample, HoleError> {
    let corner = |i: usize| {
        let a = PI / 2.0 + 2.0 * PI * i as f64 / 3.0;
        Vector3::new(r * a.cos(), r * a.sin(), height)
    };
    let junction = Vector3::new(0.0, 0.0, height + rise);
    // The curve from prism corner v up and in to J, as seen from the patch over the face
    // with outward normal `face`: the prism's vertical edges are creases, and so are the
    // curves above them. Its normals turn from the face's normal at v to the vertical at J:
    // the blend (1 − t) face + t ẑ made perpendicular to the tangent.
    let ridge = |v: Vector3<f64>, face: Vector3<f64>| -> CurveFns {
        let p = [v, Vector3::new(v.x, v.y, height + rise), junction];
        let point =
            move |t: f64| p[0] * (1.0 - t).powi(2) + p[1] * (2.0 * t * (1.0 - t)) + p[2] * (t * t);
        let tangent = move |t: f64| ((p[1] - p[0]) * (1.0 - t) + (p[2] - p[1]) * t) * 2.0;
        let normal = move |t: f64| {
            let b = face * (1.0 - t) + Vector3::z() * t;
            let d = tangent(t).normalize();
            b - d * d.dot(&b)
        };
        curve(point, tangent, normal)
    };
    let mut holes = Vec::new();
    for i in 0..3 {
        let (a, b) = (corner(i), corner((i + 1) % 3));
        let outward = unit((a + b).component_mul(&Vector3::new(1.0, 1.0, 0.0)))
            .expect("the edge is off the axis");
        let edge = curve(move |t| a + (b - a) * t, move |_| b - a, move |_| outward);
        let curves: Vec<DynCurve> = vec![
            Box::new(edge),
            Box::new(ridge(b, outward)),
            Box::new(Reversed(ridge(a, outward))),
        ];
        holes.push(HoleBoundary::new(curves)?);
    }
    Ok(HoleExample {
        name: "prism-cap",
        holes,
        surroundings: Vec::new(),
    })
}

/// The saddle z = (x² − y²)/4 over a lens between two arcs of its graph, the exact surface
/// known: the gap between the curve over (−1 + 2t, ½ sin πt) and the one over
/// (1 − 2t, −½ sin πt), normals of the saddle, bisected by the curve over the y-axis.
pub fn saddle_gap() -> Result<HoleExample, HoleError> {
    let height = |x: f64, y: f64| 0.25 * (x * x - y * y);
    let normal = |x: f64, y: f64| Vector3::new(-0.5 * x, 0.5 * y, 1.0);
    let lift = move |sign: f64| {
        curve(
            move |t| {
                let (x, y) = (sign * (2.0 * t - 1.0), sign * 0.5 * (PI * t).sin());
                Vector3::new(x, y, height(x, y))
            },
            move |t| {
                let (x, y) = (sign * (2.0 * t - 1.0), sign * 0.5 * (PI * t).sin());
                let (dx, dy) = (2.0 * sign, sign * 0.5 * PI * (PI * t).cos());
                Vector3::new(dx, dy, 0.5 * (x * dx - y * dy))
            },
            move |t| normal(sign * (2.0 * t - 1.0), sign * 0.5 * (PI * t).sin()),
        )
    };
    // The bisector over x = 0 from y = ½ down to y = −½.
    let bisector = curve(
        move |t| {
            let y = 0.5 - t;
            Vector3::new(0.0, y, height(0.0, y))
        },
        move |t| Vector3::new(0.0, -1.0, 0.5 * (0.5 - t)),
        move |t| normal(0.0, 0.5 - t),
    );
    let holes = two_curve_gap(
        Arc::new(lift(1.0)),
        Arc::new(lift(-1.0)),
        Arc::new(bisector),
    )?;
    Ok(HoleExample {
        name: "two-curve-gap",
        holes: holes.into_iter().collect(),
        surroundings: Vec::new(),
    })
}

/// A degenerate NURBS patch replaced by a triangular patch (thesis 6.4.1): a quarter of the
/// cone of base radius r about the y-axis with its apex at (0, h, 0), as a rational NURBS of
/// degrees 2 × 1 whose v = 1 row of control points is the apex repeated (the usual way to
/// make a triangle of a rectangle; the normal is undefined there). The hole's curves are the
/// patch's base arc and its two rulings, with the NURBS' own normals; the algorithm needs no
/// normal at the corners, so the degenerate corner is no problem. The same cone as the real
/// IGES file `OCC8842_cone_Ideas.igs` (radius 35, height 100), whose surface is a full turn
/// (its sides a closed circle, the seam twice and the apex) and so no triangle itself.
pub fn degenerate_nurbs(r: f64, h: f64) -> Result<HoleExample, HoleError> {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let apex = Vector3::new(0.0, h, 0.0);
    let points = vec![
        Vector3::new(r, 0.0, 0.0),
        apex,
        Vector3::new(r, 0.0, r),
        apex,
        Vector3::new(0.0, 0.0, r),
        apex,
    ];
    let nurbs = NurbsSurface::try_new(
        [2, 1],
        [vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]],
        [3, 2],
        points,
        Some(vec![1.0, 1.0, w, w, 1.0, 1.0]),
    )
    .map_err(|e| HoleError::Evaluation(e.to_string()))?;
    let surface = Arc::new(Surface::Nurbs(nurbs));
    let edge = |from: (f64, f64), to: (f64, f64)| -> DynCurve {
        Box::new(SurfaceEdge {
            surface: surface.clone(),
            from: nalgebra::Point2::new(from.0, from.1),
            to: nalgebra::Point2::new(to.0, to.1),
        })
    };
    let hole = HoleBoundary::new(vec![
        edge((0.0, 0.0), (1.0, 0.0)),
        edge((1.0, 0.0), (1.0, 1.0)),
        edge((0.0, 1.0), (0.0, 0.0)),
    ])?;
    Ok(HoleExample {
        name: "degenerate-nurbs",
        holes: vec![hole],
        surroundings: vec![(*surface).clone()],
    })
}
