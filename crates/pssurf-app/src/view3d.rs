//! The 3D view: orbit (left drag), pan (right or middle drag), zoom (wheel), frame (double
//! click or F); click to probe the surface, Shift+drag to move the probe; drag the selected
//! vertex's control points in the view plane, or with Shift along the surface normal.

use egui::{Color32, Pos2, Rect, Sense, Stroke, pos2, vec2};
use nalgebra::{Point2, Point3, Vector3};

use crate::app::App;
use crate::camera::ray_triangles;
use crate::display::ViewMode;
use crate::edit;
use crate::gpu::{Uniforms, ViewCallback};

/// The camera uniforms for a view of `size` pixels.
pub fn uniforms(app: &App, size: [u32; 2]) -> Uniforms {
    let c = &app.camera;
    let aspect = size[0].max(1) as f32 / size[1].max(1) as f32;
    let (right, up) = c.right_up();
    let to_eye = c.to_eye();
    let light = app.light.direction(right, up, to_eye);
    let eye = c.eye();
    let mode = match app.display.mode {
        ViewMode::Shaded => 0.0,
        ViewMode::Curvature(_) => 1.0,
        ViewMode::Zebra => 2.0,
        ViewMode::Wireframe => 3.0,
    };
    Uniforms {
        view_proj: c.view_projection(aspect).into(),
        eye: [eye.x, eye.y, eye.z, if c.fov_deg > 0.0 { 1.0 } else { 0.0 }],
        to_eye: [to_eye.x, to_eye.y, to_eye.z, 0.0],
        light: [light.x, light.y, light.z, 0.0],
        axis: [right.x, right.y, right.z, 0.0],
        params: [
            mode,
            app.display.zebra_width_deg.to_radians(),
            if app.display.flat { 1.0 } else { 0.0 },
            0.0,
        ],
    }
}

/// Draws the 3D view and handles its input.
pub fn ui(app: &mut App, ui: &mut egui::Ui) {
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    response
        .widget_info(|| egui::WidgetInfo::labeled(egui::accesskit::Role::Canvas, true, "3D view"));
    app.update_geometry();
    if app.frame_pending {
        app.frame_all(rect.width() / rect.height().max(1.0));
    }
    if app.frame_selection_pending {
        app.frame_selection(rect.width() / rect.height().max(1.0));
    }
    let ppp = ui.ctx().pixels_per_point();
    let size = [
        (rect.width() * ppp).round().max(1.0) as u32,
        (rect.height() * ppp).round().max(1.0) as u32,
    ];
    app.refresh_probe();
    if app.gpu {
        let cb = ViewCallback {
            geometry: app.cache.geometry.clone(),
            extra: app.probe_lines.clone(),
            uniforms: uniforms(app, size),
            size,
        };
        ui.painter()
            .add(eframe::egui_wgpu::Callback::new_paint_callback(rect, cb));
    } else {
        ui.painter().rect_filled(rect, 0.0, Color32::from_gray(246));
        ui.painter().text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "3D view needs the wgpu renderer",
            egui::FontId::proportional(14.0),
            Color32::GRAY,
        );
    }
    probe_planes(app, ui, rect);
    handles_and_drag(app, ui, rect, &response);
    let shift = ui.input(|i| i.modifiers.shift);
    let probing = shift && app.drag.is_none() && response.dragged_by(egui::PointerButton::Primary);
    if !probing {
        camera_input(app, ui, rect, &response);
    }
    if (response.clicked() || probing)
        && let Some(pos) = response.interact_pointer_pos()
    {
        probe(app, rect, pos);
    }
    if let Some(p) = &app.probe
        && let Some(s) = project(app, rect, p.point)
    {
        ui.painter()
            .circle_stroke(s, 5.0, Stroke::new(2.0, Color32::BLACK));
    }
    legend(app, ui, rect);
}

/// The probe's two cross-planes, translucent, over the view.
fn probe_planes(app: &App, ui: &egui::Ui, rect: Rect) {
    let Some(p) = &app.probe else {
        return;
    };
    if !app.probe_settings.planes {
        return;
    }
    let painter = ui.painter_at(rect);
    for (k, corners) in crate::probe::plane_corners(p, app.scene_size())
        .iter()
        .enumerate()
    {
        let pts: Option<Vec<Pos2>> = corners.iter().map(|c| project(app, rect, *c)).collect();
        let Some(pts) = pts else {
            continue;
        };
        let [r, g, b] = crate::probe::COLORS[k];
        painter.add(egui::Shape::convex_polygon(
            pts,
            Color32::from_rgba_unmultiplied(r, g, b, 40),
            Stroke::new(1.0, Color32::from_rgba_unmultiplied(r, g, b, 160)),
        ));
    }
}

fn camera_input(app: &mut App, ui: &egui::Ui, rect: Rect, r: &egui::Response) {
    if app.drag.is_none() && r.dragged_by(egui::PointerButton::Primary) {
        let d = r.drag_delta();
        app.camera.orbit(d.x, d.y);
    }
    if r.dragged_by(egui::PointerButton::Secondary) || r.dragged_by(egui::PointerButton::Middle) {
        let d = r.drag_delta();
        app.camera.pan(d.x, d.y, rect.height());
    }
    if r.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            app.camera.zoom((scroll * 0.002).exp());
        }
    }
    if r.double_clicked() {
        app.frame_pending = true;
    }
}

/// Screen position of a scene point, or None behind the camera.
fn project(app: &App, rect: Rect, p: Vector3<f64>) -> Option<Pos2> {
    let m = app
        .camera
        .view_projection(rect.width() / rect.height().max(1.0));
    let c = m * nalgebra::Vector4::new(p.x as f32, p.y as f32, p.z as f32, 1.0);
    (c.w > 0.0).then(|| {
        let (x, y) = (c.x / c.w, c.y / c.w);
        pos2(
            rect.left() + 0.5 * (x + 1.0) * rect.width(),
            rect.top() + 0.5 * (1.0 - y) * rect.height(),
        )
    })
}

fn ndc(rect: Rect, pos: Pos2) -> (f32, f32) {
    (
        2.0 * (pos.x - rect.left()) / rect.width() - 1.0,
        1.0 - 2.0 * (pos.y - rect.top()) / rect.height(),
    )
}

/// Picks the surface under `pos` and evaluates the exact curvature there.
pub fn probe(app: &mut App, rect: Rect, pos: Pos2) {
    let (x, y) = ndc(rect, pos);
    let (origin, dir) = app.camera.ray(x, y, rect.width() / rect.height().max(1.0));
    let mut best: Option<(usize, f32, Point2<f64>)> = None;
    for (i, _) in app.doc.scene.visible() {
        let Some(m) = app.object_mesh(i) else {
            continue;
        };
        if let Some((t, d, b)) = ray_triangles(
            origin,
            dir,
            |k| Vector3::from(m.vertices[k as usize].position),
            &m.indices,
        ) && best.is_none_or(|(_, bd, _)| d < bd)
        {
            let idx = &m.indices[3 * t..3 * t + 3];
            let uv = idx.iter().zip(b).fold([0.0, 0.0], |acc, (&k, w)| {
                let p = m.uvs[k as usize];
                [acc[0] + w as f64 * p[0], acc[1] + w as f64 * p[1]]
            });
            best = Some((i, d, Point2::new(uv[0], uv[1])));
        }
    }
    match best {
        Some((i, _, uv)) => app.set_probe(i, uv),
        None => {
            app.probe = None;
            app.refresh_probe();
        }
    }
}

/// The control points of the selected vertex in scene coordinates.
fn control_points(app: &App) -> Option<(usize, usize, Vec<Vector3<f64>>)> {
    let i = app.selection.object?;
    let v = app.selection.vertex?;
    let o = app.doc.scene.objects.get(i)?;
    if v >= edit::vertex_count(&o.surface) {
        return None;
    }
    let m = o.transform.matrix();
    let c = edit::vertex_control(&o.surface, v);
    Some((
        i,
        v,
        c.points
            .iter()
            .map(|p| m.transform_point(&Point3::from(*p)).coords)
            .collect::<Vec<_>>(),
    ))
}

fn handles_and_drag(app: &mut App, ui: &egui::Ui, rect: Rect, r: &egui::Response) {
    let Some((i, v, pts)) = control_points(app) else {
        app.drag = None;
        return;
    };
    let screen: Vec<Option<Pos2>> = pts.iter().map(|p| project(app, rect, *p)).collect();
    let painter = ui.painter_at(rect);
    let stroke = Stroke::new(1.5, Color32::from_rgb(230, 110, 0));
    for k in 0..3 {
        if let (Some(a), Some(b)) = (screen[k], screen[(k + 1) % 3]) {
            painter.line_segment([a, b], stroke);
        }
    }
    for s in screen.iter().flatten() {
        painter.circle(*s, 5.0, Color32::WHITE, stroke);
    }
    if r.drag_started_by(egui::PointerButton::Primary)
        && let Some(pos) = ui.input(|i| i.pointer.press_origin())
        && let Some(k) = (0..3)
            .filter(|&k| screen[k].is_some_and(|s| s.distance(pos) <= 8.0))
            .min_by(|&a, &b| {
                let d = |k: usize| screen[k].map(|s| s.distance(pos)).unwrap_or(f32::INFINITY);
                d(a).total_cmp(&d(b))
            })
    {
        app.doc.checkpoint("drag control point");
        app.drag = Some((i, v, k));
    }
    if let Some((i, v, k)) = app.drag {
        if r.dragged_by(egui::PointerButton::Primary) {
            let d = r.drag_delta();
            let along_normal = ui.input(|i| i.modifiers.shift);
            drag_point(app, rect, (i, v, k), d, along_normal);
        }
        if r.drag_stopped() {
            app.drag = None;
            app.status = format!("moved a control point of vertex {v}");
        }
    }
}

/// Moves control point `k` of vertex `v` of object `i` by a screen displacement: in the view
/// plane, or with `along_normal` along the surface normal at the vertex (the normal of its
/// control triangle, which spans the tangent plane there, Theorem 2.25) by the part of the
/// displacement along the normal's screen image. For a functional surface only the height
/// changes, by the vertical displacement.
pub fn drag_point(
    app: &mut App,
    rect: Rect,
    (i, v, k): (usize, usize, usize),
    d: egui::Vec2,
    along_normal: bool,
) {
    if d == egui::Vec2::ZERO {
        return;
    }
    let per_pixel = 2.0 * app.camera.visible_half_height() as f64 / rect.height().max(1.0) as f64;
    let (right, up) = app.camera.right_up();
    let (right, up) = (right.cast::<f64>(), up.cast::<f64>());
    let o = &app.doc.scene.objects[i];
    let mut c = edit::vertex_control(&o.surface, v);
    let mut world = per_pixel * (d.x as f64 * right - d.y as f64 * up);
    let t = o.transform;
    let m = t.matrix();
    if along_normal && !c.functional && c.points.len() == 3 {
        let [a, b, e] =
            std::array::from_fn(|j| m.transform_point(&Point3::from(c.points[j])).coords);
        if let Some(n) = (b - a).cross(&(e - a)).try_normalize(1e-300) {
            // The normal's image in the view plane; moving by s·n moves the point on the
            // screen by s·|n_view|.
            let n_view = n - n.dot(&right.cross(&up)) * right.cross(&up);
            let visible = n_view.norm().max(0.2);
            world = n * (world.dot(&(n_view / n_view.norm().max(1e-12))) / visible);
        }
    }
    let inverse = m.try_inverse().unwrap_or_else(nalgebra::Matrix4::identity);
    let local = inverse.transform_vector(&world);
    if c.functional {
        c.points[k].z -= d.y as f64 * per_pixel / t.scale;
    } else {
        c.points[k] += local;
    }
    if let Err(e) = app.drag_vertex(i, v, c) {
        app.status = e;
    }
    app.vertex_edit = None;
}

fn legend(app: &App, ui: &egui::Ui, rect: Rect) {
    let (Some(scale), ViewMode::Curvature(_)) = (&app.cache.scale, app.display.mode) else {
        return;
    };
    let map = crate::display::color_map(&app.display);
    let painter = ui.painter_at(rect);
    let bar = Rect::from_min_size(
        pos2(rect.right() - 90.0, rect.top() + 40.0),
        vec2(18.0, (rect.height() - 80.0).max(40.0)),
    );
    let steps = 64;
    let mut mesh = egui::Mesh::default();
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        let [r, g, b] = map.at(t);
        let y = bar.bottom() - t as f32 * bar.height();
        let c = Color32::from_rgb(r, g, b);
        mesh.colored_vertex(pos2(bar.left(), y), c);
        mesh.colored_vertex(pos2(bar.right(), y), c);
        if s > 0 {
            let k = 2 * s as u32;
            mesh.add_triangle(k - 2, k - 1, k);
            mesh.add_triangle(k - 1, k, k + 1);
        }
    }
    painter.add(mesh);
    painter.rect_stroke(
        bar,
        0.0,
        Stroke::new(1.0, Color32::DARK_GRAY),
        egui::StrokeKind::Outside,
    );
    let ticks = pssurf_viz::legend::ticks(scale);
    let step = ticks
        .windows(2)
        .map(|w| (w[1].0 - w[0].0).abs())
        .next()
        .unwrap_or(1.0);
    for (value, t) in ticks {
        let y = bar.bottom() - t as f32 * bar.height();
        painter.line_segment(
            [pos2(bar.right(), y), pos2(bar.right() + 4.0, y)],
            Stroke::new(1.0, Color32::DARK_GRAY),
        );
        painter.text(
            pos2(bar.right() + 6.0, y),
            egui::Align2::LEFT_CENTER,
            pssurf_viz::legend::format_tick(value, step),
            egui::FontId::monospace(11.0),
            Color32::BLACK,
        );
    }
    painter.text(
        pos2(bar.center().x, bar.top() - 8.0),
        egui::Align2::CENTER_BOTTOM,
        crate::properties::mode_name(app.display.mode),
        egui::FontId::proportional(12.0),
        Color32::BLACK,
    );
}
