//! Pictures checked by their properties: size, background, legend, a single colour for a
//! surface of constant curvature.

use std::sync::Arc;

use nalgebra::{Point2, Vector3, Vector4};
use pssurf::bezier::RationalBezierTriangle;
use pssurf::bezier::index::multi_indices;
use pssurf::geometry::Triangle2;
use pssurf::ps::{Hermite, PsBasis, PsSpline};
use pssurf::triangulation::Triangulation;

use super::*;

fn grid_surface(f: impl Fn(Point2<f64>) -> Hermite<f64>) -> Surface {
    let pts: Vec<Point2<f64>> = (0..36)
        .map(|k| {
            Point2::new(
                (k % 6) as f64 / 5.0 + 0.013 * ((k * 7) % 5) as f64,
                (k / 6) as f64 / 5.0,
            )
        })
        .collect();
    let basis = Arc::new(PsBasis::optimal(Triangulation::delaunay(pts).unwrap()).unwrap());
    Surface::Functional(PsSpline::interpolate(basis, f).unwrap())
}

/// A rational quadratic patch on the sphere of radius `r` (inverse stereographic projection).
fn sphere_patch(r: f64) -> RationalBezierTriangle<Vector3<f64>> {
    let t = Triangle2::new(
        Point2::new(-0.5, -0.4),
        Point2::new(0.6, -0.3),
        Point2::new(0.0, 0.6),
    );
    let hom = |p: Point2<f64>| {
        let w = 1.0 + p.x * p.x + p.y * p.y;
        Vector4::new(
            2.0 * r * p.x,
            2.0 * r * p.y,
            r * (1.0 - p.x * p.x - p.y * p.y),
            w,
        )
    };
    let corner = |k: usize| {
        let mut b = [0.0; 3];
        b[k] = 1.0;
        hom(t.point(b))
    };
    let ords: Vec<Vector4<f64>> = multi_indices(2)
        .map(|l| {
            let p = hom(t.point(l.map(|x| x as f64 / 2.0)));
            if l.contains(&2) {
                p
            } else {
                let ones: Vec<usize> = (0..3).filter(|&k| l[k] == 1).collect();
                2.0 * p - 0.5 * (corner(ones[0]) + corner(ones[1]))
            }
        })
        .collect();
    RationalBezierTriangle::try_new(
        t,
        2,
        ords.iter().map(|h| h.xyz() / h.w).collect(),
        ords.iter().map(|h| h.w).collect(),
    )
    .unwrap()
}

fn opts(show: Show) -> PlotOptions {
    PlotOptions {
        show,
        width: 320,
        height: 240,
        ..PlotOptions::default()
    }
}

/// The colours of the picture's surface part (left of the legend), background excluded.
fn surface_colors(p: &Picture, right: usize) -> std::collections::HashSet<[u8; 3]> {
    (0..p.height)
        .flat_map(|row| (0..right).map(move |col| (row, col)))
        .map(|(row, col)| p.pixels[row * p.width + col])
        .filter(|&c| c != [255, 255, 255])
        .collect()
}

#[test]
fn constant_curvature_gives_one_colour() {
    let sphere = Surface::from(sphere_patch(2.0));
    for q in [
        CurvatureQuantity::Gaussian,
        CurvatureQuantity::Mean,
        CurvatureQuantity::K1,
    ] {
        let mut o = opts(Show::Quantity(q));
        o.range = Range::Fixed(-1.0, 1.0);
        let p = plot(&sphere, &o);
        let colors = surface_colors(&p, p.width - 120);
        // K = 1/4 and H = κ = −1/2 everywhere: one colour, the map's colour there.
        let value = match q {
            CurvatureQuantity::Gaussian => 0.25,
            _ => -0.5,
        };
        let want = o
            .colormap
            .at(ColorScale::Linear { lo: -1.0, hi: 1.0 }.position(value));
        assert_eq!(colors.len(), 1, "{q:?}: {colors:?}");
        assert!(colors.contains(&want), "{q:?}");
    }
    // A plane: K = H = 0, the middle of the map.
    let plane = grid_surface(|p| Hermite {
        value: 0.2 * p.x - 0.1 * p.y,
        dx: 0.2,
        dy: -0.1,
    });
    let p = plot(&plane, &opts(Show::Quantity(CurvatureQuantity::Mean)));
    assert_eq!(surface_colors(&p, p.width - 120).len(), 1);
}

#[test]
fn pictures_have_the_asked_size_background_legend_and_surface() {
    let s = grid_surface(|p| Hermite {
        value: (3.0 * p.x).sin() * p.y,
        dx: 3.0 * (3.0 * p.x).cos() * p.y,
        dy: (3.0 * p.x).sin(),
    });
    for show in [
        Show::Shaded,
        Show::Quantity(CurvatureQuantity::Gaussian),
        Show::Zebra,
        Show::Isophotes,
    ] {
        let p = plot(&s, &opts(show));
        assert_eq!((p.width, p.height, p.pixels.len()), (320, 240, 320 * 240));
        assert_eq!(p.to_image().dimensions(), (320, 240));
        // Corners are background; the middle of the drawing area is surface.
        assert_eq!(p.pixels[0], [255, 255, 255]);
        let area_w = if matches!(show, Show::Quantity(_)) {
            320 - 110
        } else {
            320
        };
        assert_ne!(
            p.pixels[120 * 320 + area_w / 2],
            [255, 255, 255],
            "{show:?}"
        );
        // The legend: a colour bar and dark text in the right strip, only for quantities.
        let strip: Vec<[u8; 3]> = (0..240)
            .flat_map(|r| (215..320).map(move |c| (r, c)))
            .map(|(r, c)| p.pixels[r * 320 + c])
            .collect();
        let dark = strip.iter().filter(|c| c.iter().all(|&x| x < 60)).count();
        let colored = strip.iter().filter(|c| c[0].abs_diff(c[2]) > 60).count();
        if matches!(show, Show::Quantity(_)) {
            assert!(
                dark > 100 && colored > 200,
                "legend missing: dark {dark}, coloured {colored}"
            );
        }
    }
    // Zebra pictures are black and white stripes: both present in quantity.
    let z = plot(&s, &opts(Show::Zebra));
    let black = z.pixels.iter().filter(|&&c| c == [20, 20, 20]).count();
    let white = z.pixels.iter().filter(|&&c| c == [245, 245, 245]).count();
    assert!(black > 1000 && white > 1000, "{black} {white}");
    // PNG encoding round-trips.
    let mut png = Vec::new();
    z.write_png(&mut png).unwrap();
    let back = image::load_from_memory(&png).unwrap().to_rgb8();
    assert_eq!(back.as_raw().len(), 320 * 240 * 3);
    assert_eq!(back.get_pixel(0, 0).0, [255, 255, 255]);
}

#[test]
fn overlays_draw_lines() {
    let s = grid_surface(|p| Hermite {
        value: p.x * p.y,
        dx: p.y,
        dy: p.x,
    });
    let plain = plot(&s, &opts(Show::Shaded));
    let mut o = opts(Show::Shaded);
    o.overlays = Overlays {
        wire: true,
        refinement: true,
        control: true,
        boundary: true,
        combs: false,
    };
    let lined = plot(&s, &o);
    let orange = lined.pixels.iter().filter(|&&c| c == [230, 120, 0]).count();
    let blue = lined.pixels.iter().filter(|&&c| c == [30, 60, 200]).count();
    let black = lined.pixels.iter().filter(|&&c| c == [0, 0, 0]).count();
    assert!(
        orange > 50 && blue > 50 && black > 50,
        "{orange} {blue} {black}"
    );
    assert_eq!(
        plain.pixels.iter().filter(|&&c| c == [230, 120, 0]).count(),
        0
    );
}

#[test]
fn combs_draw_teeth_and_envelopes_on_curved_boundaries_only() {
    let envelope = |p: &Picture| p.pixels.iter().filter(|&&c| c == [30, 30, 140]).count();
    let mut o = opts(Show::Shaded);
    o.overlays.combs = true;
    // A curved graph: its boundary curves bend, so the teeth stand out.
    let curved = grid_surface(|p| Hermite {
        value: p.x * p.x + 0.5 * p.y * p.y,
        dx: 2.0 * p.x,
        dy: p.y,
    });
    assert!(envelope(&plot(&curved, &o)) > 50);
    assert_eq!(envelope(&plot(&curved, &opts(Show::Shaded))), 0);
    // A plane has straight sides: the teeth have no length and the envelope lies on them.
    let plane = grid_surface(|p| Hermite {
        value: 0.1 * p.x,
        dx: 0.1,
        dy: 0.0,
    });
    let curved_tips: Vec<_> = pssurf::interrogate::comb::boundary_combs(&plane, 10, 1.0)
        .into_iter()
        .flatten()
        .filter(|t| (t.tip - t.point).norm() > 1e-12)
        .collect();
    assert!(curved_tips.is_empty());
}
