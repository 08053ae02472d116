//! NURPS design tools on the selected vertex (thesis 3.4): drag the tangent point inside its
//! control triangle (the weights follow by (3.72)), make a local planar section by large
//! weights (3.73), a cusp by collapsing the control triangle to the tangent point (3.84), or a
//! crease by collapsing it to a line (3.86, Figure 3.10).

use egui::{Color32, Pos2, Sense, Stroke, Vec2};
use nalgebra::Vector3;
use pssurf::ps::Degenerate;
use pssurf::ps::design::{shape_parameters, weights_for_shape};
use pssurf::surface::Surface;

use crate::command::{Command, ViewContext};
use crate::edit::VertexControl;

/// Barycentric coordinates of V_i in its PS-triangle at most this are on the edge (as in the
/// library: the tangent point then stays on that edge).
const ON_EDGE: f64 = 1e-9;
/// The smallest shape parameter a drag gives off an edge (weights stay within 1e-30…1e30).
const MIN_PARAMETER: f64 = 1e-3;
/// The planar-section weight relative to the vertex's largest weight.
const PLANAR_FACTOR: f64 = 1e3;

/// The vertex's position α in its PS-triangle, when it has a rational control triangle.
pub fn alpha(surface: &Surface, vertex: usize, c: &VertexControl) -> Option<[f64; 3]> {
    if c.points.len() != 3 || c.weights.is_none() {
        return None;
    }
    let basis = surface.ps_basis()?;
    (vertex < basis.triangulation().vertex_count()).then(|| basis.alpha(vertex))
}

/// The shape parameters asked for by barycentric coordinates `b` of the pointer in the drawn
/// triangle: inside, at least `MIN_PARAMETER` (1e-3) from the edges, and 0 where V_i lies on an
/// edge of its PS-triangle (the tangent point cannot leave that edge).
pub fn target_from_pointer(alpha: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let mut t: [f64; 3] = std::array::from_fn(|j| {
        if alpha[j] <= ON_EDGE {
            0.0
        } else {
            b[j].max(MIN_PARAMETER)
        }
    });
    let sum: f64 = t.iter().sum();
    if sum > 0.0 {
        t = t.map(|x| x / sum);
    }
    t
}

/// The control group with its weights moved so that the tangent point sits at `target`.
pub fn with_tangent_point(
    vertex: usize,
    alpha: [f64; 3],
    c: &VertexControl,
    target: [f64; 3],
) -> Result<VertexControl, String> {
    let w = c.weights.as_ref().ok_or("not a rational surface")?;
    let w = [w[0], w[1], w[2]];
    let new = weights_for_shape(vertex, alpha, w, target).map_err(|e| e.to_string())?;
    Ok(VertexControl {
        weights: Some(new.to_vec()),
        ..c.clone()
    })
}

/// The tangent point s(V_i) = Σ α̃_j c_j (3.67).
pub fn tangent_point(alpha: [f64; 3], c: &VertexControl) -> Option<Vector3<f64>> {
    let w = c.weights.as_ref()?;
    let a = shape_parameters(alpha, [w[0], w[1], w[2]]);
    Some((0..3).map(|j| c.points[j] * a[j]).sum())
}

/// The control group collapsed as `how` says.
fn collapsed(c: &VertexControl, how: Degenerate) -> Option<VertexControl> {
    let p = how.apply([c.points[0], c.points[1], c.points[2]])?;
    Some(VertexControl {
        points: p.to_vec(),
        ..c.clone()
    })
}

/// The design tools for vertex `vertex` of object `object` with control group `c`.
pub fn ui(
    ui: &mut egui::Ui,
    cx: &mut ViewContext<'_>,
    object: usize,
    vertex: usize,
    c: &VertexControl,
) {
    let Some(alpha) = (cx.doc.scene.objects[object].surface()).and_then(|s| alpha(s, vertex, c))
    else {
        return;
    };
    let set = |control| Command::SetVertex {
        object,
        vertex,
        control,
    };
    ui.label("Tangent point (drag it: the weights follow)");
    tangent_widget(ui, cx, object, vertex, alpha, c);
    ui.horizontal_wrapped(|ui| {
        let w = c.weights.as_ref().map_or(1.0, |w| w.iter().cloned().fold(0.0, f64::max));
        let planar = ui
            .button("Planar section")
            .on_hover_text("All three weights 1000 times the largest: the surface near the vertex flattens into the control plane (thesis 3.4.3)");
        if planar.clicked() {
            let control = VertexControl {
                weights: Some(vec![PLANAR_FACTOR * w; 3]),
                ..c.clone()
            };
            cx.emit(set(control));
        }
        if ui
            .button("Cusp")
            .on_hover_text("All three control points at the tangent point: a cusp at the vertex (thesis 3.4.4)")
            .clicked()
            && let Some(p) = tangent_point(alpha, c)
            && let Some(control) = collapsed(c, Degenerate::Point(p))
        {
            cx.emit(set(control));
        }
        let line = Degenerate::Line {
            through: c.points[0],
            direction: c.points[1] - c.points[0],
        };
        if ui
            .button("Crease line")
            .on_hover_text("The control points onto the line through Q1 and Q2: with cusps at the neighbours, a curved corner (thesis Figure 3.10)")
            .clicked()
        {
            match collapsed(c, line) {
                Some(control) => cx.emit(set(control)),
                None => cx.status("Q1 and Q2 coincide: there is no line through them"),
            }
        }
    });
}

/// The control triangle drawn as an equilateral triangle with the tangent point at its shape
/// parameters; dragging the point moves it (one undo step per drag).
fn tangent_widget(
    ui: &mut egui::Ui,
    cx: &mut ViewContext<'_>,
    object: usize,
    vertex: usize,
    alpha: [f64; 3],
    c: &VertexControl,
) {
    let Some(w) = c.weights.as_ref() else { return };
    let shape = shape_parameters(alpha, [w[0], w[1], w[2]]);
    let size = Vec2::new(150.0, 130.0);
    let (rect, response) = ui.allocate_exact_size(size, Sense::drag());
    let corners = [
        rect.left_bottom() + Vec2::new(10.0, -10.0),
        rect.right_bottom() + Vec2::new(-10.0, -10.0),
        rect.center_top() + Vec2::new(0.0, 10.0),
    ];
    let at = |b: [f64; 3]| -> Pos2 {
        let v = (0..3).fold(Vec2::ZERO, |acc, j| {
            acc + corners[j].to_vec2() * b[j] as f32
        });
        v.to_pos2()
    };
    let painter = ui.painter_at(rect);
    let stroke = Stroke::new(1.5, Color32::from_rgb(230, 110, 0));
    painter.add(egui::Shape::closed_line(corners.to_vec(), stroke));
    for (j, p) in corners.iter().enumerate() {
        let label = format!("Q{}", j + 1);
        let anchor = if j == 2 {
            egui::Align2::CENTER_BOTTOM
        } else {
            egui::Align2::CENTER_TOP
        };
        painter.text(
            *p,
            anchor,
            label,
            egui::FontId::proportional(11.0),
            ui.visuals().text_color(),
        );
    }
    painter.circle(at(shape), 5.0, Color32::WHITE, stroke);
    ui.weak(format!(
        "shape parameters {:.3}, {:.3}, {:.3}",
        shape[0], shape[1], shape[2]
    ));
    match alpha.iter().filter(|&&a| a <= ON_EDGE).count() {
        0 => {}
        1 => {
            ui.weak("The vertex lies on an edge of its PS-triangle: the point moves along it.");
        }
        _ => {
            ui.weak("The vertex is a corner of its PS-triangle: the tangent point is fixed.");
        }
    }
    if response.drag_started() {
        cx.emit(Command::StartDrag);
    }
    if response.dragged()
        && let Some(pos) = response.interact_pointer_pos()
    {
        let b = screen_bary(corners, pos);
        let target = target_from_pointer(alpha, b);
        match with_tangent_point(vertex, alpha, c, target) {
            Ok(control) => cx.emit(Command::DragVertex {
                object,
                vertex,
                control,
            }),
            Err(e) => cx.status(e),
        }
    }
    if response.drag_stopped() {
        cx.emit(Command::EndDrag);
        cx.status(format!("moved the tangent point of vertex {vertex}"));
    }
}

/// Barycentric coordinates of `p` in the screen triangle `v`.
fn screen_bary(v: [Pos2; 3], p: Pos2) -> [f64; 3] {
    let d = |a: Pos2, b: Pos2, c: Pos2| {
        ((b.x - a.x) as f64) * ((c.y - a.y) as f64) - ((c.x - a.x) as f64) * ((b.y - a.y) as f64)
    };
    let area = d(v[0], v[1], v[2]);
    [
        d(p, v[1], v[2]) / area,
        d(v[0], p, v[2]) / area,
        d(v[0], v[1], p) / area,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use pssurf::surface::ParametricSurface;

    /// A NURPS UPS surface: moving the tangent point by the widget's rules puts s(V_i) at
    /// Σ target_j c_j and keeps it on the edge where V_i lies on its PS-triangle's edge; a cusp
    /// puts s(V_i) at the old tangent point with zero derivatives.
    #[test]
    fn tangent_point_and_cusp_edits_do_what_they_say() {
        let dialog = crate::create::NewSurface {
            kind: pssurf::ups::GraphKind::Rational,
            size: 2,
            ..Default::default()
        };
        let mut s = dialog.build().unwrap();
        let n = crate::edit::vertex_count(&s);
        let mut inside = 0;
        for vertex in 0..n {
            let c = crate::edit::vertex_control(&s, vertex);
            let a = alpha(&s, vertex, &c).unwrap();
            let target = target_from_pointer(a, [0.5, 0.3, 0.2]);
            assert!((target.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            if a.iter().all(|&x| x > ON_EDGE) {
                inside += 1;
                assert!(target.iter().all(|&x| x > 0.1), "{target:?}");
            }
            let moved = with_tangent_point(vertex, a, &c, target).unwrap();
            crate::edit::set_vertex_control(&mut s, vertex, &moved).unwrap();
            let at = s.ps_basis().unwrap().triangulation().vertex(vertex);
            let p = s.point(at).unwrap();
            let want: Vector3<f64> = (0..3).map(|j| moved.points[j] * target[j]).sum();
            assert!((p - want).norm() < 1e-12, "vertex {vertex}: {p} vs {want}");
            let tangent = tangent_point(a, &moved).unwrap();
            let cusp = collapsed(&moved, Degenerate::Point(tangent)).unwrap();
            crate::edit::set_vertex_control(&mut s, vertex, &cusp).unwrap();
            let j = s.jet(at).unwrap().jet;
            assert!((j.value - tangent).norm() < 1e-12);
            assert!(j.dx.norm() + j.dy.norm() < 1e-12, "vertex {vertex}");
        }
        assert!(
            inside >= 3,
            "only {inside} of {n} vertices inside their PS-triangles"
        );
    }

    #[test]
    fn the_pointer_outside_is_kept_inside_and_on_the_allowed_edge() {
        let t = target_from_pointer([0.2, 0.3, 0.5], [-0.5, 1.2, 0.3]);
        assert!(t.iter().all(|&x| x >= MIN_PARAMETER / 2.0));
        let t = target_from_pointer([0.0, 0.4, 0.6], [0.5, 0.3, 0.2]);
        assert_eq!(t[0], 0.0);
        assert!((t[1] + t[2] - 1.0).abs() < 1e-15);
    }
}
