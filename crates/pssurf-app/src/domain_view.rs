//! The 2D domain view: the triangulation, the PS refinement, the PS-points and PS-triangles
//! of the selected object. Clicking inside a PS-triangle selects its vertex.

use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, pos2, vec2};
use nalgebra::Point2;
use pssurf::ps::PsBasis;

use crate::command::{Command, ViewContext};
use crate::document::Selection;

/// Above this many triangles only the boundary and the selection are drawn.
const DETAIL_LIMIT: usize = 20_000;

/// Maps the domain's bounding box into a screen rectangle (y up, aspect kept).
#[derive(Clone, Copy, Debug)]
pub struct DomainMap {
    lo: Point2<f64>,
    scale: f64,
    origin: Pos2,
}

impl DomainMap {
    /// The map of bounds (lo, hi) into `rect` with a margin.
    pub fn new(lo: Point2<f64>, hi: Point2<f64>, rect: Rect) -> Self {
        let r = rect.shrink(8.0);
        let (w, h) = ((hi.x - lo.x).max(1e-300), (hi.y - lo.y).max(1e-300));
        let scale = (r.width() as f64 / w).min(r.height() as f64 / h);
        let used = vec2((w * scale) as f32, (h * scale) as f32);
        let origin = pos2(r.center().x - 0.5 * used.x, r.center().y + 0.5 * used.y);
        DomainMap { lo, scale, origin }
    }

    /// Domain point to screen.
    pub fn to_screen(&self, p: Point2<f64>) -> Pos2 {
        pos2(
            self.origin.x + ((p.x - self.lo.x) * self.scale) as f32,
            self.origin.y - ((p.y - self.lo.y) * self.scale) as f32,
        )
    }

    /// Screen to domain point.
    pub fn to_domain(&self, s: Pos2) -> Point2<f64> {
        Point2::new(
            self.lo.x + (s.x - self.origin.x) as f64 / self.scale,
            self.lo.y + (self.origin.y - s.y) as f64 / self.scale,
        )
    }
}

/// The vertex whose PS-triangle contains `p` (the nearest such vertex), or else the nearest
/// vertex within `radius` (domain units).
pub fn pick_vertex(basis: &PsBasis, p: Point2<f64>, radius: f64) -> Option<usize> {
    let tri = basis.triangulation();
    let dist = |i: usize| (tri.vertex(i) - p).norm();
    let inside = (0..tri.vertex_count())
        .filter(|&i| {
            let b = basis.ps_triangle(i).bary(p);
            b.iter().all(|x| *x >= -1e-12)
        })
        .min_by(|&a, &b| dist(a).total_cmp(&dist(b)));
    inside.or_else(|| {
        (0..tri.vertex_count())
            .filter(|&i| dist(i) <= radius)
            .min_by(|&a, &b| dist(a).total_cmp(&dist(b)))
    })
}

/// The domain view.
#[derive(Debug, Default)]
pub struct DomainView;

impl DomainView {
    /// Draws the domain view of the selected object; clicks go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let size = vec2(ui.available_width(), ui.available_width().min(320.0));
        let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
        let response = response.on_hover_text(
            "Click a PS-triangle to select its vertex; Shift+click or Shift+drag moves the probe",
        );
        response.widget_info(|| {
            egui::WidgetInfo::labeled(egui::accesskit::Role::Canvas, true, "domain view")
        });
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 2.0, Color32::from_gray(250));
        let Some(i) = cx.selected() else {
            return centered_message(&painter, rect, "no object selected");
        };
        let Some(basis) = cx.doc.scene.objects[i].surface.ps_basis() else {
            return centered_message(&painter, rect, "the domain view shows PS surfaces");
        };
        let (lo, hi) = basis.triangulation().bounds();
        let map = DomainMap::new(lo, hi, rect);
        let mut shapes = triangulation_shapes(basis, &map);
        if let Some(v) = cx.doc.selection.vertex {
            shapes.extend(selection_shapes(basis, &map, v));
        }
        if let Some(p) = cx.probe().filter(|p| p.object == i) {
            shapes.push(Shape::circle_stroke(
                map.to_screen(p.uv),
                5.0,
                Stroke::new(2.0, Color32::BLACK),
            ));
        }
        painter.extend(shapes);
        let shift = ui.input(|inp| inp.modifiers.shift);
        if let Some(command) = click_command(&response, shift, basis, &map, i) {
            if let Command::Select(s) = &command {
                cx.status(match s.vertex {
                    Some(v) => format!("selected vertex {v}"),
                    None => "no PS-triangle there".into(),
                });
            }
            cx.emit(command);
        }
    }
}

/// The triangulation's edges (only the boundary above [`DETAIL_LIMIT`] triangles) and, for
/// small triangulations, the PS refinement's split lines.
fn triangulation_shapes(basis: &PsBasis, map: &DomainMap) -> Vec<Shape> {
    let tri = basis.triangulation();
    let detailed = tri.triangle_count() <= DETAIL_LIMIT;
    let edge = Stroke::new(1.0, Color32::from_gray(90));
    let split = Stroke::new(0.5, Color32::from_rgb(70, 110, 210));
    let mut shapes = Vec::new();
    for t in 0..tri.triangle_count() {
        for k in 0..3 {
            let (a, b) = tri.edge_vertices(t, k);
            let boundary = tri.is_boundary_edge(t, k);
            if boundary || (detailed && a < b) {
                shapes.push(Shape::line_segment(
                    [map.to_screen(tri.vertex(a)), map.to_screen(tri.vertex(b))],
                    edge,
                ));
            }
        }
        if detailed && tri.triangle_count() <= 4000 {
            let r = basis.refinement();
            let z = map.to_screen(r.z(t));
            let v = tri.triangle(t);
            for k in 0..3 {
                shapes.push(Shape::line_segment(
                    [z, map.to_screen(tri.vertex(v[k]))],
                    split,
                ));
                shapes.push(Shape::line_segment(
                    [z, map.to_screen(r.edge_point(tri, t, k))],
                    split,
                ));
            }
        }
    }
    shapes
}

/// The PS-triangle of vertex `v` with its PS-points (none if there is no such vertex).
fn selection_shapes(basis: &PsBasis, map: &DomainMap, v: usize) -> Vec<Shape> {
    let tri = basis.triangulation();
    if v >= tri.vertex_count() {
        return Vec::new();
    }
    let t = basis.ps_triangle(v);
    let pts: Vec<Pos2> = t.v.iter().map(|p| map.to_screen(*p)).collect();
    let mut shapes = vec![Shape::convex_polygon(
        pts,
        Color32::from_rgba_unmultiplied(255, 140, 0, 50),
        Stroke::new(2.0, Color32::from_rgb(230, 110, 0)),
    )];
    for p in pssurf::ps::ps_triangles::ps_points(tri, basis.refinement(), v) {
        shapes.push(Shape::circle_filled(
            map.to_screen(p),
            2.5,
            Color32::from_rgb(200, 40, 40),
        ));
    }
    shapes.push(Shape::circle_filled(
        map.to_screen(tri.vertex(v)),
        4.0,
        Color32::from_rgb(230, 110, 0),
    ));
    shapes
}

/// What a click asks for: with Shift, the probe at the clicked point; else the vertex whose
/// PS-triangle was clicked.
fn click_command(
    response: &egui::Response,
    shift: bool,
    basis: &PsBasis,
    map: &DomainMap,
    object: usize,
) -> Option<Command> {
    let pos = response.interact_pointer_pos()?;
    if shift && (response.clicked() || response.dragged()) {
        return Some(Command::SetProbe {
            object,
            uv: map.to_domain(pos),
        });
    }
    if !response.clicked() {
        return None;
    }
    let vertex = pick_vertex(basis, map.to_domain(pos), 15.0 / map.scale);
    Some(Command::Select(Selection {
        object: Some(object),
        vertex,
    }))
}

/// A grey message in the middle of the view.
fn centered_message(painter: &egui::Painter, rect: Rect, text: &str) {
    painter.text(
        rect.center(),
        egui::Align2::CENTER_CENTER,
        text,
        egui::FontId::proportional(13.0),
        Color32::GRAY,
    );
}
