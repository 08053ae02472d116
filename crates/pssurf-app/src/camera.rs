//! The orbit camera of the 3D view: turntable orbit about a target (z up), pan, zoom,
//! orthographic or perspective, "frame" to fit bounds; and rays for picking.

use nalgebra::{Matrix4, Point3, Vector3};

/// The smallest size or distance the camera uses.
pub const MIN_SIZE: f32 = 1e-12;
/// The largest size, distance or target coordinate the camera uses: the squared lengths
/// that normalising a vector computes stay finite in f32 (whose largest value is 3.4e38).
pub const MAX_SIZE: f32 = 1e18;

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

    /// The view matrix (world to camera), of the [`OrbitCamera::sane`] camera.
    pub fn view(&self) -> Matrix4<f32> {
        let c = self.sane();
        let (_, up) = c.right_up();
        Matrix4::look_at_rh(&Point3::from(c.eye()), &Point3::from(c.target), &up)
    }

    /// The projection for an aspect ratio width / height (depth to wgpu's [0, 1]). Never
    /// degenerate: sizes, distance, field of view and aspect are first brought into a range
    /// where the matrix is finite and invertible in f32 (see [`OrbitCamera::sane`]).
    pub fn projection(&self, aspect: f32) -> Matrix4<f32> {
        let c = self.sane();
        let aspect = if aspect.is_finite() {
            aspect.clamp(1e-3, 1e3)
        } else {
            1.0
        };
        let near = (c.distance * 1e-3).max(MIN_SIZE);
        let far = (c.distance * 4.0 + 4.0 * c.half_height).max(4.0 * near);
        // Written out rather than nalgebra's constructors, which assert (and so panic) on
        // views narrower than f32's epsilon.
        let depth = far - near;
        let gl = if c.fov_deg > 0.0 {
            let f = 1.0 / (0.5 * c.fov_deg.to_radians()).tan();
            Matrix4::new(
                f / aspect,
                0.0,
                0.0,
                0.0,
                0.0,
                f,
                0.0,
                0.0,
                0.0,
                0.0,
                -(far + near) / depth,
                -2.0 * far * (near / depth),
                0.0,
                0.0,
                -1.0,
                0.0,
            )
        } else {
            let h = c.half_height;
            Matrix4::new(
                1.0 / (h * aspect),
                0.0,
                0.0,
                0.0,
                0.0,
                1.0 / h,
                0.0,
                0.0,
                0.0,
                0.0,
                -2.0 / depth,
                -(far + near) / depth,
                0.0,
                0.0,
                0.0,
                1.0,
            )
        };
        // OpenGL's z ∈ [−1, 1] to wgpu's [0, 1].
        let fix = Matrix4::new(
            1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0,
        );
        fix * gl
    }

    /// This camera with every number usable: a non-finite target becomes the origin, sizes
    /// and distance are clamped to [`MIN_SIZE`] … [`MAX_SIZE`] (a non-finite or non-positive
    /// one takes the default), the field of view to 0 (orthographic) or 1° … 170°, the
    /// angles to finite values. A scene larger than `MAX_SIZE` is seen from `MAX_SIZE` away:
    /// drawn imperfectly, never a degenerate matrix.
    pub fn sane(&self) -> OrbitCamera {
        let d = OrbitCamera::default();
        let size = |x: f32, default: f32| {
            if x.is_finite() && x > 0.0 {
                x.clamp(MIN_SIZE, MAX_SIZE)
            } else {
                default
            }
        };
        let angle = |x: f32, default: f32| if x.is_finite() { x } else { default };
        let target = if self.target.iter().all(|x| x.is_finite()) {
            self.target.map(|x| x.clamp(-MAX_SIZE, MAX_SIZE))
        } else {
            Vector3::zeros()
        };
        // The eye must differ from the target in f32.
        let distance = size(self.distance, d.distance).max(1e-6 * target.amax());
        OrbitCamera {
            target,
            distance,
            azimuth_deg: angle(self.azimuth_deg, d.azimuth_deg).rem_euclid(360.0),
            elevation_deg: angle(self.elevation_deg, d.elevation_deg).clamp(-89.0, 89.0),
            fov_deg: if self.fov_deg.is_finite() && self.fov_deg > 0.0 {
                self.fov_deg.clamp(1.0, 170.0)
            } else {
                0.0
            },
            half_height: size(self.half_height, d.half_height),
        }
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
    /// Bounds beyond what the camera can show (see [`OrbitCamera::sane`]) are fitted as far
    /// as it can; non-finite bounds leave the camera as it is.
    pub fn frame(&mut self, lo: Vector3<f32>, hi: Vector3<f32>, aspect: f32) {
        if !(lo.iter().chain(hi.iter()).all(|x| x.is_finite())) {
            return;
        }
        let aspect = if aspect.is_finite() { aspect } else { 1.0 };
        // Halves first: (hi − lo) of two large f32 values may overflow.
        self.target = (0.5 * lo + 0.5 * hi).map(|x| x.clamp(-MAX_SIZE, MAX_SIZE));
        let half = (0.5 * hi - 0.5 * lo).map(f64::from).norm();
        let r =
            (half.max(1e-6) / f64::from(aspect.clamp(1e-3, 1.0))).min(f64::from(MAX_SIZE) / 4.0);
        let r = r as f32;
        self.half_height = 1.05 * r;
        self.distance = if self.fov_deg > 0.0 {
            1.1 * r / (0.5 * self.fov_deg.clamp(1.0, 170.0).to_radians()).tan() + r
        } else {
            3.0 * r
        }
        .min(MAX_SIZE);
    }

    /// The ray (origin, unit direction) through a point of the view given in normalised
    /// device coordinates (x, y ∈ [−1, 1], y up).
    pub fn ray(&self, ndc_x: f32, ndc_y: f32, aspect: f32) -> (Vector3<f32>, Vector3<f32>) {
        let c = self.sane();
        let inv = c
            .view_projection(aspect)
            .try_inverse()
            .unwrap_or_else(Matrix4::identity);
        let near = inv.transform_point(&Point3::new(ndc_x, ndc_y, 0.0));
        let far = inv.transform_point(&Point3::new(ndc_x, ndc_y, 1.0));
        let d = (far - near)
            .try_normalize(1e-12)
            .unwrap_or_else(|| -c.to_eye());
        if near.coords.iter().chain(d.iter()).all(|x| x.is_finite()) {
            (near.coords, d)
        } else {
            // A view too large or too small for f32: the ray from the eye through the target.
            (c.eye(), -c.to_eye())
        }
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

    /// Issue 14: no camera state, however absurd, makes a degenerate or non-finite matrix
    /// (nalgebra's projections assert on zero-width views).
    #[test]
    fn absurd_cameras_still_give_finite_matrices() {
        let odd = [
            0.0,
            -0.0,
            -1.0,
            1e-45,
            1e-30,
            1e30,
            1e18,
            3e38,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let mut checked = 0;
        for &a in &odd {
            for &b in &odd {
                for fov in [0.0, 40.0, a, 180.0] {
                    let c = OrbitCamera {
                        target: Vector3::new(a, 0.0, b),
                        distance: a,
                        half_height: b,
                        fov_deg: fov,
                        azimuth_deg: b,
                        elevation_deg: a,
                    };
                    for aspect in [1.5, 0.0, f32::NAN, 1e9] {
                        let m = c.view_projection(aspect);
                        assert!(m.iter().all(|x| x.is_finite()), "{c:?} aspect {aspect}");
                        let (o, d) = c.ray(0.1, -0.2, aspect);
                        assert!(o.iter().chain(d.iter()).all(|x| x.is_finite()), "{c:?}");
                        checked += 1;
                    }
                }
                let mut framed = OrbitCamera::default();
                framed.frame(Vector3::repeat(-a), Vector3::repeat(b), 1.5);
                assert!(framed.view_projection(1.5).iter().all(|x| x.is_finite()));
            }
        }
        assert_eq!(checked, odd.len() * odd.len() * 4 * 4);
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
