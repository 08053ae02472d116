//! The orbit camera of the 3D view: turntable orbit about a target (z up), pan, zoom,
//! orthographic or perspective, "frame" to fit bounds; and rays for picking.

use nalgebra::{Matrix4, Point3, Vector3};

/// An orbit camera.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct OrbitCamera {
    /// The point looked at.
    pub target: Vector3<f32>,
    /// Distance from the target.
    pub distance: f32,
    /// Azimuth in degrees (0 looks from +x).
    pub azimuth_deg: f32,
    /// Elevation in degrees (90 looks from above).
    pub elevation_deg: f32,
    /// Vertical field of view in degrees; 0 for orthographic.
    pub fov_deg: f32,
    /// Half the height of the view at the target (orthographic).
    pub half_height: f32,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        OrbitCamera {
            target: Vector3::zeros(),
            distance: 4.0,
            azimuth_deg: -50.0,
            elevation_deg: 35.0,
            fov_deg: 0.0,
            half_height: 1.2,
        }
    }
}

impl OrbitCamera {
    /// The unit vector from the target to the eye.
    pub fn to_eye(&self) -> Vector3<f32> {
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        Vector3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
    }

    /// The eye position.
    pub fn eye(&self) -> Vector3<f32> {
        self.target + self.distance * self.to_eye()
    }

    /// Screen right and up directions in space.
    pub fn right_up(&self) -> (Vector3<f32>, Vector3<f32>) {
        let back = self.to_eye();
        let right = Vector3::z()
            .cross(&back)
            .try_normalize(1e-6)
            .unwrap_or_else(Vector3::x);
        (right, back.cross(&right))
    }

    /// The view matrix (world to camera).
    pub fn view(&self) -> Matrix4<f32> {
        let (_, up) = self.right_up();
        Matrix4::look_at_rh(&Point3::from(self.eye()), &Point3::from(self.target), &up)
    }

    /// The projection for an aspect ratio width / height (depth to wgpu's [0, 1]).
    pub fn projection(&self, aspect: f32) -> Matrix4<f32> {
        let near = (self.distance * 1e-3).max(1e-6);
        let far = self.distance * 4.0 + 4.0 * self.half_height;
        let gl = if self.fov_deg > 0.0 {
            Matrix4::new_perspective(aspect, self.fov_deg.to_radians(), near, far)
        } else {
            let h = self.half_height;
            Matrix4::new_orthographic(-h * aspect, h * aspect, -h, h, near, far)
        };
        // OpenGL's z ∈ [−1, 1] to wgpu's [0, 1].
        let fix = Matrix4::new(
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0,
        );
        fix * gl
    }

    /// Projection × view.
    pub fn view_projection(&self, aspect: f32) -> Matrix4<f32> {
        self.projection(aspect) * self.view()
    }

    /// Turns the camera by a mouse drag of (dx, dy) pixels.
    pub fn orbit(&mut self, dx: f32, dy: f32) {
        self.azimuth_deg = (self.azimuth_deg - 0.4 * dx).rem_euclid(360.0);
        self.elevation_deg = (self.elevation_deg + 0.4 * dy).clamp(-89.0, 89.0);
    }

    /// Moves the target by a drag of (dx, dy) pixels in a view `height` pixels tall.
    pub fn pan(&mut self, dx: f32, dy: f32, height: f32) {
        let (right, up) = self.right_up();
        let per_pixel = 2.0 * self.visible_half_height() / height.max(1.0);
        self.target += per_pixel * (-dx * right + dy * up);
    }

    /// Zooms by a factor (> 1 closer).
    pub fn zoom(&mut self, factor: f32) {
        let f = factor.clamp(0.05, 20.0);
        self.half_height /= f;
        self.distance /= f;
    }

    /// Half the height of what is seen at the target.
    pub fn visible_half_height(&self) -> f32 {
        if self.fov_deg > 0.0 {
            self.distance * (0.5 * self.fov_deg.to_radians()).tan()
        } else {
            self.half_height
        }
    }

    /// Centres on bounds and fits them in a view of the given aspect ratio (width / height).
    pub fn frame(&mut self, lo: Vector3<f32>, hi: Vector3<f32>, aspect: f32) {
        self.target = 0.5 * (lo + hi);
        let r = (0.5 * (hi - lo).norm()).max(1e-6) / aspect.clamp(1e-3, 1.0);
        self.half_height = 1.05 * r;
        self.distance = if self.fov_deg > 0.0 {
            1.1 * r / (0.5 * self.fov_deg.to_radians()).tan() + r
        } else {
            3.0 * r
        };
    }

    /// The ray (origin, unit direction) through a point of the view given in normalised
    /// device coordinates (x, y ∈ [−1, 1], y up).
    pub fn ray(&self, ndc_x: f32, ndc_y: f32, aspect: f32) -> (Vector3<f32>, Vector3<f32>) {
        let inv = self
            .view_projection(aspect)
            .try_inverse()
            .unwrap_or_else(Matrix4::identity);
        let near = inv.transform_point(&Point3::new(ndc_x, ndc_y, 0.0));
        let far = inv.transform_point(&Point3::new(ndc_x, ndc_y, 1.0));
        let d = (far - near)
            .try_normalize(1e-12)
            .unwrap_or_else(|| -self.to_eye());
        (near.coords, d)
    }
}

/// The nearest hit of a ray with triangles: (triangle index, distance, barycentric (b0, b1, b2)).
pub fn ray_triangles(
    origin: Vector3<f32>,
    dir: Vector3<f32>,
    positions: impl Fn(u32) -> Vector3<f32>,
    indices: &[u32],
) -> Option<(usize, f32, [f32; 3])> {
    let mut best: Option<(usize, f32, [f32; 3])> = None;
    for (t, tri) in indices.chunks_exact(3).enumerate() {
        let (a, b, c) = (positions(tri[0]), positions(tri[1]), positions(tri[2]));
        // Möller–Trumbore.
        let (e1, e2) = (b - a, c - a);
        let p = dir.cross(&e2);
        let det = e1.dot(&p);
        if det.abs() < 1e-12 {
            continue;
        }
        let inv = 1.0 / det;
        let s = origin - a;
        let u = s.dot(&p) * inv;
        if !(-1e-6..=1.0 + 1e-6).contains(&u) {
            continue;
        }
        let q = s.cross(&e1);
        let v = dir.dot(&q) * inv;
        if v < -1e-6 || u + v > 1.0 + 1e-6 {
            continue;
        }
        let dist = e2.dot(&q) * inv;
        if dist > 0.0 && best.is_none_or(|(_, d, _)| dist < d) {
            best = Some((t, dist, [1.0 - u - v, u, v]));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_ray_goes_from_the_eye_side_to_the_target() {
        let mut c = OrbitCamera::default();
        c.frame(
            Vector3::new(-1.0, -1.0, 0.0),
            Vector3::new(1.0, 1.0, 0.0),
            1.5,
        );
        for fov in [0.0, 40.0] {
            c.fov_deg = fov;
            let (o, d) = c.ray(0.0, 0.0, 1.5);
            // The ray passes through the target.
            let to_target = c.target - o;
            let off = (to_target - to_target.dot(&d) * d).norm();
            // f32 arithmetic through an inverted perspective matrix.
            assert!(off < 1e-3 * c.distance, "fov {fov}: off {off}");
            assert!((d + c.to_eye()).norm() < 1e-4);
        }
    }

    #[test]
    fn rays_hit_the_nearest_triangle() {
        let pos = [
            Vector3::new(-1.0, -1.0, 0.0),
            Vector3::new(1.0, -1.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(-1.0, -1.0, 1.0),
            Vector3::new(1.0, -1.0, 1.0),
            Vector3::new(0.0, 1.0, 1.0),
        ];
        let hit = ray_triangles(
            Vector3::new(0.0, 0.0, 5.0),
            -Vector3::z(),
            |i| pos[i as usize],
            &[0, 1, 2, 3, 4, 5],
        );
        let (t, d, b) = hit.unwrap();
        assert_eq!(t, 1);
        assert!((d - 4.0).abs() < 1e-6);
        assert!((b.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        assert!(
            ray_triangles(
                Vector3::new(5.0, 5.0, 5.0),
                -Vector3::z(),
                |i| pos[i as usize],
                &[0, 1, 2]
            )
            .is_none()
        );
    }
}
