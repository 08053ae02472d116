//! Reading and changing one control group (a PS vertex's control triangle, one Bézier
//! ordinate) through the library's [`ControlNet`]: the library validates the edit, keeps the
//! uniform and general forms of a UPS surface in step and reports the pieces to re-sample.

use nalgebra::Vector3;
use pssurf::surface::{ControlFreedom, ControlId, ControlNet, ControlPoint, Surface};

/// The control points of one group (Definition 2.24 for a PS vertex) and, for rational
/// surfaces, their weights.
#[derive(Clone, Debug, PartialEq)]
pub struct VertexControl {
    /// The control points in space (for a functional surface (X_ij, Y_ij, c_ij): only the
    /// heights can change).
    pub points: Vec<Vector3<f64>>,
    /// The weights of a rational surface.
    pub weights: Option<Vec<f64>>,
    /// True for a functional surface z = s(x, y).
    pub functional: bool,
}

/// The number of control points per group (3 for PS kinds, 1 for Bézier ordinates).
fn group_len(s: &Surface) -> usize {
    s.control_group(ControlId(0)).len().max(1)
}

/// The ids of group `i`.
fn group_ids(s: &Surface, i: usize) -> std::ops::Range<usize> {
    let len = group_len(s);
    len * i..len * (i + 1)
}

/// The number of control groups (vertices of a PS surface) of a surface.
pub fn vertex_count(s: &Surface) -> usize {
    s.control_count() / group_len(s)
}

/// The first control point id of group `i`.
pub fn group_start(s: &Surface, i: usize) -> ControlId {
    ControlId(group_ids(s, i).start)
}

/// The control points of group `i`.
///
/// # Panics
/// If there is no group `i`.
pub fn vertex_control(s: &Surface, i: usize) -> VertexControl {
    let points: Vec<ControlPoint> = group_ids(s, i)
        .map(|id| s.control_point(ControlId(id)).expect("group in range"))
        .collect();
    VertexControl {
        points: points.iter().map(|p| p.position).collect(),
        weights: s
            .is_rational()
            .then(|| points.iter().map(|p| p.weight).collect()),
        functional: s.freedom() == ControlFreedom::Height,
    }
}

/// Replaces the control points of group `i` (for a functional surface only the heights are
/// used). Returns the pieces whose shape changed (the support), or why the library refused
/// (then nothing changed).
pub fn set_vertex_control(
    s: &mut Surface,
    i: usize,
    c: &VertexControl,
) -> Result<Vec<usize>, String> {
    if i >= vertex_count(s) {
        return Err(format!("there is no vertex {i}"));
    }
    let ids = group_ids(s, i);
    if c.points.len() != ids.len() || c.weights.as_ref().is_some_and(|w| w.len() != ids.len()) {
        return Err(format!("vertex {i} has {} control points", ids.len()));
    }
    let changes: Vec<(ControlId, ControlPoint)> = ids
        .enumerate()
        .map(|(k, id)| {
            (
                ControlId(id),
                ControlPoint {
                    position: c.points[k],
                    weight: c.weights.as_ref().map_or(1.0, |w| w[k]),
                },
            )
        })
        .collect();
    s.set_control_points(&changes).map_err(|e| e.to_string())
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
            let _ = s.jet(s.domain_bounds().0); // build the cached general form first
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
        let mut c = before.clone();
        c.points[0].x = f64::NAN;
        assert!(
            set_vertex_control(&mut s, 3, &c)
                .unwrap_err()
                .contains("finite")
        );
        let mut c = before.clone();
        c.weights = Some(vec![1.0, 0.0, 1.0]);
        assert!(
            set_vertex_control(&mut s, 3, &c)
                .unwrap_err()
                .contains("between 1e-30 and 1e30")
        );
        assert!(
            set_vertex_control(&mut s, 10_000, &before)
                .unwrap_err()
                .contains("no vertex")
        );
        assert_eq!(vertex_control(&s, 3), before);
    }
}
