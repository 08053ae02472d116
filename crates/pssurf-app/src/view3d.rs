//! The 3D view: orbit (left drag), pan (right or middle drag), zoom (wheel), frame (double
//! click or F); click to probe the surface, Shift+drag to move the probe; drag the selected
//! vertex's control points in the view plane, or with Shift along the surface normal.

use egui::{Color32, Pos2, Rect, Sense, Stroke, pos2};
use nalgebra::{Point2, Point3, Vector3};

use crate::camera::{OrbitCamera, ray_triangles};
use crate::command::{Command, FrameTarget, ViewContext};
use crate::display::ViewMode;
use crate::document::Document;
use crate::edit::{self, VertexControl};
use crate::gpu::{Uniforms, ViewCallback};
use crate::state::ViewState;

/// The camera uniforms for a view of `size` pixels.
pub fn uniforms(view: &ViewState, size: [u32; 2]) -> Uniforms {
    let c = &view.camera;
    let aspect = size[0].max(1) as f32 / size[1].max(1) as f32;
    let (right, up) = c.right_up();
    let to_eye = c.to_eye();
    let light = view.light.direction(right, up, to_eye);
    let eye = c.eye();
    let mode = match view.display.mode {
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
            view.display.zebra_width_deg.to_radians(),
            if view.display.flat { 1.0 } else { 0.0 },
            0.0,
        ],
    }
}

/// A control point being dragged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DragHandle {
    /// The object's index.
    pub object: usize,
    /// The vertex (control group).
    pub vertex: usize,
    /// The control point within the group.
    pub point: usize,
}

/// The 3D view and what it is in the middle of.
#[derive(Debug, Default)]
pub struct View3d {
    /// The control point being dragged, if any.
    pub drag: Option<DragHandle>,
}

impl View3d {
    /// Draws the 3D view; camera moves, probing and control-point drags go to `cx` as
    /// commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let rect = ui.available_rect_before_wrap();
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        response.widget_info(|| {
            egui::WidgetInfo::labeled(egui::accesskit::Role::Canvas, true, "3D view")
        });
        paint_scene(ui, rect, cx);
        let camera = cx.view.camera;
        probe_planes(&camera, cx, ui, rect);
        self.handles_and_drag(ui, rect, &response, cx);
        let shift = ui.input(|i| i.modifiers.shift);
        let probing =
            shift && self.drag.is_none() && response.dragged_by(egui::PointerButton::Primary);
        let mut moved = camera;
        if !probing {
            camera_input(&mut moved, self.drag.is_some(), ui, rect, &response, cx);
        }
        if moved != camera {
            cx.emit(Command::SetCamera(moved));
        }
        if (response.clicked() || probing)
            && let Some(pos) = response.interact_pointer_pos()
        {
            let command = pick(cx, &moved, rect, pos);
            cx.emit(command);
        }
        if let Some(p) = cx.probe()
            && let Some(s) = project(&camera, rect, p.point)
        {
            ui.painter()
                .circle_stroke(s, 5.0, Stroke::new(2.0, Color32::BLACK));
        }
    }

    /// Draws the selected vertex's control points and turns drags on them into commands.
    fn handles_and_drag(
        &mut self,
        ui: &egui::Ui,
        rect: Rect,
        r: &egui::Response,
        cx: &mut ViewContext<'_>,
    ) {
        let camera = cx.view.camera;
        let Some((object, vertex, pts)) = control_points(cx.doc) else {
            if self.drag.take().is_some() {
                cx.emit(Command::EndDrag);
            }
            return;
        };
        let screen: Vec<Option<Pos2>> = pts.iter().map(|p| project(&camera, rect, *p)).collect();
        draw_handles(ui, rect, &screen);
        if r.drag_started_by(egui::PointerButton::Primary)
            && let Some(pos) = ui.input(|i| i.pointer.press_origin())
            && let Some(point) = nearest_handle(&screen, pos, 8.0)
        {
            cx.emit(Command::StartDrag);
            self.drag = Some(DragHandle {
                object,
                vertex,
                point,
            });
        }
        let Some(handle) = self.drag else {
            return;
        };
        if r.dragged_by(egui::PointerButton::Primary) {
            let along_normal = ui.input(|i| i.modifiers.shift);
            let d = r.drag_delta();
            if let Some(control) = drag_point(cx.doc, &camera, rect, handle, d, along_normal) {
                cx.emit(Command::DragVertex {
                    object: handle.object,
                    vertex: handle.vertex,
                    control,
                });
            }
        }
        if r.drag_stopped() {
            self.drag = None;
            cx.emit(Command::EndDrag);
            cx.status(format!("moved a control point of vertex {}", handle.vertex));
        }
    }
}

/// The scene drawn by the GPU (or a note that it needs one).
fn paint_scene(ui: &egui::Ui, rect: Rect, cx: &ViewContext<'_>) {
    let ppp = ui.ctx().pixels_per_point();
    let size = [
        (rect.width() * ppp).round().max(1.0) as u32,
        (rect.height() * ppp).round().max(1.0) as u32,
    ];
    if cx.runtime.gpu.is_some() {
        let cb = ViewCallback {
            geometry: cx.runtime.cache.geometry.clone(),
            extra: cx.runtime.extra.clone(),
            uniforms: uniforms(cx.view, size),
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
}

/// The probe's two cross-planes, translucent, over the view.
fn probe_planes(camera: &OrbitCamera, cx: &ViewContext<'_>, ui: &egui::Ui, rect: Rect) {
    let Some(p) = cx.probe() else {
        return;
    };
    if !cx.view.probe.planes {
        return;
    }
    let painter = ui.painter_at(rect);
    let size = cx.view.probe.reach(cx.runtime.cache.scene_size());
    for (k, corners) in crate::probe::plane_corners(p, size).iter().enumerate() {
        let pts: Option<Vec<Pos2>> = corners.iter().map(|c| project(camera, rect, *c)).collect();
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

/// Orbit (left drag, unless a control point is being dragged), pan (right or middle drag),
/// zoom (wheel); a double click asks to frame the scene.
fn camera_input(
    camera: &mut OrbitCamera,
    dragging_point: bool,
    ui: &egui::Ui,
    rect: Rect,
    r: &egui::Response,
    cx: &mut ViewContext<'_>,
) {
    if !dragging_point && r.dragged_by(egui::PointerButton::Primary) {
        let d = r.drag_delta();
        camera.orbit(d.x, d.y);
    }
    if r.dragged_by(egui::PointerButton::Secondary) || r.dragged_by(egui::PointerButton::Middle) {
        let d = r.drag_delta();
        camera.pan(d.x, d.y, rect.height());
    }
    if r.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            camera.zoom((scroll * 0.002).exp());
        }
    }
    if r.double_clicked() {
        cx.emit(Command::Frame(FrameTarget::All));
    }
}

/// Screen position of a scene point, or None behind the camera.
fn project(camera: &OrbitCamera, rect: Rect, p: Vector3<f64>) -> Option<Pos2> {
    let m = camera.view_projection(rect.width() / rect.height().max(1.0));
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

/// The probe command for a click at `pos`: the surface point under it (found on the drawn
/// meshes, then evaluated exactly), or removing the probe when the click misses.
pub fn pick(cx: &ViewContext<'_>, camera: &OrbitCamera, rect: Rect, pos: Pos2) -> Command {
    let (x, y) = ndc(rect, pos);
    let (origin, dir) = camera.ray(x, y, rect.width() / rect.height().max(1.0));
    let mut best: Option<(usize, f32, Option<Point2<f64>>)> = None;
    let scene = &cx.doc.scene;
    for (i, _) in scene.visible() {
        let Some(m) = cx.runtime.cache.object_mesh(scene, i) else {
            continue;
        };
        if let Some((t, d, b)) = ray_triangles(
            origin,
            dir,
            |k| Vector3::from(m.vertices[k as usize].position),
            &m.indices,
        ) && best.is_none_or(|(_, bd, _)| d < bd)
        {
            // A mesh has no parameters (no uvs): it hides what lies behind, and the probe,
            // which reads surfaces, is removed.
            let idx = &m.indices[3 * t..3 * t + 3];
            let uv = (m.uvs.len() == m.vertices.len()).then(|| {
                let uv = idx.iter().zip(b).fold([0.0, 0.0], |acc, (&k, w)| {
                    let p = m.uvs[k as usize];
                    [acc[0] + w as f64 * p[0], acc[1] + w as f64 * p[1]]
                });
                Point2::new(uv[0], uv[1])
            });
            best = Some((i, d, uv));
        }
    }
    match best {
        Some((object, _, Some(uv))) => Command::SetProbe { object, uv },
        _ => Command::RemoveProbe,
    }
}

/// The control points of the selected vertex in scene coordinates.
fn control_points(doc: &Document) -> Option<(usize, usize, Vec<Vector3<f64>>)> {
    let i = doc.selection.object?;
    let v = doc.selection.vertex?;
    let o = doc.scene.objects.get(i)?;
    let surface = o.surface()?;
    if v >= edit::vertex_count(surface) {
        return None;
    }
    let m = o.transform.matrix();
    let c = edit::vertex_control(surface, v);
    Some((
        i,
        v,
        c.points
            .iter()
            .map(|p| m.transform_point(&Point3::from(*p)).coords)
            .collect::<Vec<_>>(),
    ))
}

/// The control triangle's edges and points over the view.
fn draw_handles(ui: &egui::Ui, rect: Rect, screen: &[Option<Pos2>]) {
    let painter = ui.painter_at(rect);
    let stroke = Stroke::new(1.5, Color32::from_rgb(230, 110, 0));
    let n = screen.len();
    if n > 1 {
        for k in 0..n {
            if let (Some(a), Some(b)) = (screen[k], screen[(k + 1) % n]) {
                painter.line_segment([a, b], stroke);
            }
        }
    }
    for s in screen.iter().flatten() {
        painter.circle(*s, 5.0, Color32::WHITE, stroke);
    }
}

/// The handle nearest to `pos` within `radius` pixels.
fn nearest_handle(screen: &[Option<Pos2>], pos: Pos2, radius: f32) -> Option<usize> {
    let d = |k: usize| screen[k].map_or(f32::INFINITY, |s| s.distance(pos));
    (0..screen.len())
        .filter(|&k| d(k) <= radius)
        .min_by(|&a, &b| d(a).total_cmp(&d(b)))
}

/// The control points of `handle`'s vertex after moving its point by a screen displacement
/// `d`: in the view plane, or with `along_normal` along the surface normal at the vertex (the
/// normal of its control triangle, which spans the tangent plane there, Theorem 2.25) by the
/// part of the displacement along the normal's screen image. For a functional surface only
/// the height changes, by the vertical displacement. None when nothing moves or the handle
/// no longer exists.
pub fn drag_point(
    doc: &Document,
    camera: &OrbitCamera,
    rect: Rect,
    handle: DragHandle,
    d: egui::Vec2,
    along_normal: bool,
) -> Option<VertexControl> {
    let DragHandle {
        object: i,
        vertex: v,
        point: k,
    } = handle;
    let o = doc.scene.objects.get(i)?;
    let surface = o.surface()?;
    if d == egui::Vec2::ZERO || v >= edit::vertex_count(surface) {
        return None;
    }
    let per_pixel = 2.0 * camera.visible_half_height() as f64 / rect.height().max(1.0) as f64;
    let (right, up) = camera.right_up();
    let (right, up) = (right.cast::<f64>(), up.cast::<f64>());
    let mut c = edit::vertex_control(surface, v);
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
    let p = c.points.get_mut(k)?;
    if c.functional {
        p.z -= d.y as f64 * per_pixel / t.scale;
    } else {
        *p += local;
    }
    Some(c)
}
