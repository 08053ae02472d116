//! Reading and changing one vertex's control triangle, for every surface kind. A change
//! updates only the Bézier nets of the vertex's molecule (local control).

use nalgebra::Vector3;
use pssurf::ps::net::Weighted;
use pssurf::surface::{PsSurface, Surface, UpsSurface};

/// The three control points of a vertex (Definition 2.23) and, for NURPS, their weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexControl {
    /// The control points in space (for a functional surface (X_ij, Y_ij, c_ij): only the
    /// heights can change).
    pub points: [Vector3<f64>; 3],
    /// The weights of a rational surface.
    pub weights: Option<[f64; 3]>,
    /// True for a functional surface z = s(x, y).
    pub functional: bool,
}

/// The number of vertices (control triangles) of a surface.
pub fn vertex_count(s: &Surface) -> usize {
    s.general().basis().triangulation().vertex_count()
}

/// The control triangle of vertex `i`.
pub fn vertex_control(s: &Surface, i: usize) -> VertexControl {
    let g = s.general();
    VertexControl {
        points: g.control_triangle(i),
        weights: match g {
            PsSurface::Rational(n) => Some(n.weights()[i]),
            _ => None,
        },
        functional: matches!(g, PsSurface::Functional(_)),
    }
}

/// Replaces the control triangle of vertex `i` (for a functional surface only the heights
/// are used). Weights must be positive and everything finite.
pub fn set_vertex_control(s: &mut Surface, i: usize, c: &VertexControl) -> Result<(), String> {
    if i >= vertex_count(s) {
        return Err(format!("there is no vertex {i}"));
    }
    if !c.points.iter().all(|p| p.iter().all(|x| x.is_finite())) {
        return Err("control points must be finite numbers".into());
    }
    if let Some(w) = c.weights
        && !w.iter().all(|w| *w > 0.0 && w.is_finite())
    {
        return Err("weights must be positive".into());
    }
    let heights = c.points.map(|p| p.z);
    let weights = c.weights.unwrap_or([1.0; 3]);
    match s {
        Surface::General(g) => set_general(g, i, c, heights, weights),
        Surface::Uniform(u, general) => {
            let slot = u.grid().real_slots()[i];
            match u {
                UpsSurface::Functional(f) => f.blocks_mut()[slot] = heights,
                UpsSurface::Parametric(p) => p.blocks_mut()[slot] = c.points,
                UpsSurface::Rational(r) => {
                    r.blocks_mut()[slot] = std::array::from_fn(|j| Weighted {
                        point: c.points[j],
                        weight: weights[j],
                    })
                }
            }
            match general.get_mut() {
                Some(g) => set_general(g, i, c, heights, weights),
                None => Ok(()),
            }
        }
    }
}

fn set_general(
    g: &mut PsSurface,
    i: usize,
    c: &VertexControl,
    heights: [f64; 3],
    weights: [f64; 3],
) -> Result<(), String> {
    match g {
        PsSurface::Functional(f) => f.set_coefficients(i, heights),
        PsSurface::Parametric(p) => p.set_coefficients(i, c.points),
        PsSurface::Rational(n) => n.set_vertex(i, c.points, weights),
    }
    .map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use pssurf::surface::ParametricSurface;

    /// Editing a UPS surface changes its uniform form and its cached general form alike:
    /// the general form rebuilt from the edited uniform one agrees everywhere.
    #[test]
    fn uniform_edits_keep_both_forms_in_step() {
        for mut s in [crate::demo::wave_patch(3), crate::demo::paraboloid(3)] {
            let _ = s.general(); // build the cached general form first
            let n = vertex_count(&s);
            for v in [0, n / 2, n - 1] {
                let mut c = vertex_control(&s, v);
                c.points[1] += nalgebra::Vector3::new(0.01, -0.02, 0.3);
                if let Some(w) = &mut c.weights {
                    w[2] = 2.5;
                }
                set_vertex_control(&mut s, v, &c).unwrap();
                assert_eq!(vertex_control(&s, v), c);
            }
            let fresh = s.uniform().unwrap().to_general().unwrap();
            let (lo, hi) = s.domain_bounds();
            let mut compared = 0;
            for k in 0..400 {
                let t = (k as f64 + 0.5) / 400.0;
                let uv = nalgebra::Point2::new(
                    lo.x + t * (hi.x - lo.x),
                    lo.y + (0.37 + 0.26 * (7.0 * t).sin()) * (hi.y - lo.y),
                );
                let (Ok(a), Ok(b)) = (
                    s.jet_with(uv, &mut s.cursor_near(uv)),
                    fresh.jet_with(uv, &mut fresh.cursor_near(uv)),
                ) else {
                    continue;
                };
                assert!((a.jet.value - b.jet.value).norm() < 1e-13, "at {uv}");
                assert!((a.jet.dxx - b.jet.dxx).norm() < 1e-10, "at {uv}");
                compared += 1;
            }
            assert!(compared > 200, "only {compared} points inside the domain");
        }
    }

    #[test]
    fn bad_control_points_are_rejected_and_leave_the_surface_alone() {
        let mut s = crate::demo::paraboloid(2);
        let before = vertex_control(&s, 3);
        let mut c = before;
        c.points[0].x = f64::NAN;
        assert!(
            set_vertex_control(&mut s, 3, &c)
                .unwrap_err()
                .contains("finite")
        );
        let mut c = before;
        c.weights = Some([1.0, 0.0, 1.0]);
        assert!(
            set_vertex_control(&mut s, 3, &c)
                .unwrap_err()
                .contains("positive")
        );
        assert!(
            set_vertex_control(&mut s, 10_000, &before)
                .unwrap_err()
                .contains("no vertex")
        );
        assert_eq!(vertex_control(&s, 3), before);
    }
}
