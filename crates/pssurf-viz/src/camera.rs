//! The camera: where the eye is, and how points of space map to pixels.

use nalgebra::{Point2, Vector3};

/// Orthographic or perspective projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Parallel projection (sizes do not depend on distance).
    Orthographic,
    /// Central projection with the given vertical field of view in degrees.
    Perspective {
        /// The field of view, in degrees (0 < fov < 180).
        fov_deg: f64,
    },
}

/// A camera orbiting the scene's centre, z up.
///
/// The eye looks at the centre of the scene's bounding box from the direction
/// (cos el cos az, cos el sin az, sin el): azimuth 0 looks from +x, 90 from +y; elevation 90
/// looks straight down. Zoom 1 fits the scene into the picture with a margin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Azimuth in degrees.
    pub azimuth_deg: f64,
    /// Elevation in degrees (−90..90).
    pub elevation_deg: f64,
    /// Magnification relative to "fit the scene".
    pub zoom: f64,
    /// The projection.
    pub projection: Projection,
}

impl Default for Camera {
    /// Azimuth −50°, elevation 35°, orthographic.
    fn default() -> Self {
        Camera {
            azimuth_deg: -50.0,
            elevation_deg: 35.0,
            zoom: 1.0,
            projection: Projection::Orthographic,
        }
    }
}

/// A camera placed for a scene and a picture size: maps points to pixel coordinates.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// Unit vector from the scene towards the eye.
    pub to_eye: Vector3<f64>,
    /// Unit vector to the right on the screen.
    pub right: Vector3<f64>,
    /// Unit vector up on the screen.
    pub up: Vector3<f64>,
    centre: Vector3<f64>,
    /// Pixels per unit length (at the centre's depth for perspective).
    scale: f64,
    /// The picture centre in pixels.
    screen_centre: Point2<f64>,
    /// Distance from the eye to the centre (perspective only).
    eye_distance: Option<f64>,
}

/// A point projected to the screen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    /// Pixel column (0 at the left edge of the picture).
    pub x: f64,
    /// Pixel row (0 at the top).
    pub y: f64,
    /// Depth: larger is nearer the eye.
    pub depth: f64,
    /// 1/w for perspective-correct interpolation (1 for orthographic).
    pub inv_w: f64,
}

impl View {
    /// Places `camera` so that the points `extent` (e.g. the corners of the bounding box)
    /// fill the rectangle of `width` × `height` pixels whose centre is `screen_centre`, with a
    /// 6 % margin at zoom 1.
    pub fn fit(
        camera: &Camera,
        extent: &[Vector3<f64>],
        width: f64,
        height: f64,
        screen_centre: Point2<f64>,
    ) -> View {
        let (az, el) = (
            camera.azimuth_deg.to_radians(),
            camera.elevation_deg.to_radians(),
        );
        let to_eye = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let z = Vector3::z();
        let right = if to_eye.cross(&z).norm() > 1e-9 {
            z.cross(&to_eye).normalize()
        } else {
            // Looking straight down or up: keep x to the right.
            Vector3::new(-az.sin(), az.cos(), 0.0)
        };
        let up = to_eye.cross(&right);
        let (mut lo, mut hi) = (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        );
        for p in extent {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        if extent.is_empty() {
            (lo, hi) = (Vector3::zeros(), Vector3::zeros());
        }
        let centre = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo).norm()).max(1e-300);
        let eye_distance = match camera.projection {
            Projection::Orthographic => None,
            Projection::Perspective { fov_deg } => {
                Some(radius / (0.5 * fov_deg.clamp(1.0, 170.0).to_radians()).sin())
            }
        };
        let mut view = View {
            to_eye,
            right,
            up,
            centre,
            scale: 1.0,
            screen_centre,
            eye_distance,
        };
        // Fit the projected extent.
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in extent {
            let q = view.project(p);
            x0 = x0.min(q.x);
            x1 = x1.max(q.x);
            y0 = y0.min(q.y);
            y1 = y1.max(q.y);
        }
        let (ex, ey) = ((x1 - x0).max(1e-300), (y1 - y0).max(1e-300));
        view.scale = camera.zoom * 0.94 * (width / ex).min(height / ey);
        // Centre the projected extent.
        let mid = Point2::new(0.5 * (x0 + x1), 0.5 * (y0 + y1)) - screen_centre;
        view.screen_centre -= mid * view.scale;
        view
    }

    /// The pixel position and depth of a point.
    #[inline]
    pub fn project(&self, p: &Vector3<f64>) -> Projected {
        let d = p - self.centre;
        let (x, y, depth) = (d.dot(&self.right), d.dot(&self.up), d.dot(&self.to_eye));
        let inv_w = match self.eye_distance {
            None => 1.0,
            Some(e) => 1.0 / (e - depth).max(1e-9 * e),
        };
        let f = match self.eye_distance {
            None => self.scale,
            Some(e) => self.scale * e * inv_w,
        };
        Projected {
            x: self.screen_centre.x + f * x,
            y: self.screen_centre.y - f * y,
            depth,
            inv_w,
        }
    }

    /// The unit direction in which the eye sees the point `p` (from the eye to `p`).
    #[inline]
    pub fn view_direction(&self, p: &Vector3<f64>) -> Vector3<f64> {
        match self.eye_distance {
            None => -self.to_eye,
            Some(e) => (p - (self.centre + self.to_eye * e)).normalize(),
        }
    }

    /// Pixels per unit length at the scene's centre.
    pub fn pixels_per_unit(&self) -> f64 {
        self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> Vec<Vector3<f64>> {
        (0..8)
            .map(|k| {
                Vector3::new(
                    (k & 1) as f64,
                    ((k >> 1) & 1) as f64,
                    ((k >> 2) & 1) as f64 * 2.0,
                )
            })
            .collect()
    }

    #[test]
    fn fit_keeps_the_scene_inside_the_picture_with_a_margin() {
        for projection in [
            Projection::Orthographic,
            Projection::Perspective { fov_deg: 40.0 },
        ] {
            for (az, el) in [(-60.0, 30.0), (0.0, 90.0), (45.0, -20.0), (200.0, 10.0)] {
                let cam = Camera {
                    azimuth_deg: az,
                    elevation_deg: el,
                    zoom: 1.0,
                    projection,
                };
                let v = View::fit(&cam, &cube(), 400.0, 300.0, Point2::new(200.0, 150.0));
                let pts: Vec<Projected> = cube().iter().map(|p| v.project(p)).collect();
                let (x0, x1) = pts
                    .iter()
                    .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(p.x), a.1.max(p.x)));
                let (y0, y1) = pts
                    .iter()
                    .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(p.y), a.1.max(p.y)));
                assert!(
                    x0 >= 0.0 && x1 <= 400.0 && y0 >= 0.0 && y1 <= 300.0,
                    "{az} {el}"
                );
                // One direction is filled up to the 6 % margin.
                let fill = ((x1 - x0) / 400.0).max((y1 - y0) / 300.0);
                assert!((fill - 0.94).abs() < 1e-9, "{fill}");
            }
        }
    }

    #[test]
    fn the_eye_sees_from_the_given_direction() {
        let cam = Camera {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
            ..Camera::default()
        };
        let v = View::fit(&cam, &cube(), 100.0, 100.0, Point2::new(50.0, 50.0));
        // Looking from +x: +x is nearer, +y is to the right, +z up.
        let c = Vector3::new(0.5, 0.5, 1.0);
        assert!(v.project(&(c + Vector3::x())).depth > v.project(&c).depth);
        assert!(v.project(&(c + Vector3::y())).x > v.project(&c).x);
        assert!(v.project(&(c + Vector3::z())).y < v.project(&c).y);
        // From straight above, x still runs to the right.
        let top = Camera {
            azimuth_deg: -90.0,
            elevation_deg: 90.0,
            ..Camera::default()
        };
        let v = View::fit(&top, &cube(), 100.0, 100.0, Point2::new(50.0, 50.0));
        assert!(v.project(&(c + Vector3::x())).x > v.project(&c).x);
        assert!(v.project(&(c + Vector3::y())).y < v.project(&c).y);
    }
}
