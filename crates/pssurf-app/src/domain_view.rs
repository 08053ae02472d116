//! The 2D domain view: the triangulation, the PS refinement, the PS-points and PS-triangles
//! of the selected object. Clicking inside a PS-triangle selects its vertex.

use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, pos2, vec2};
use nalgebra::Point2;
use pssurf::ps::PsBasis;

use crate::app::{App, Selection};

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

/// Draws the domain view of the selected object and handles clicks.
pub fn ui(app: &mut App, ui: &mut egui::Ui) {
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
    let Some(i) = app
        .selection
        .object
        .filter(|&i| i < app.doc.scene.objects.len())
    else {
        return centered_message(&painter, rect, "no object selected");
    };
    let Some(basis) = app.doc.scene.objects[i].surface.ps_basis().cloned() else {
        return centered_message(&painter, rect, "the domain view shows PS surfaces");
    };
    let tri = basis.triangulation();
    let (lo, hi) = tri.bounds();
    let map = DomainMap::new(lo, hi, rect);
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
    if let Some(v) = app.selection.vertex.filter(|&v| v < tri.vertex_count()) {
        let t = basis.ps_triangle(v);
        let pts: Vec<Pos2> = t.v.iter().map(|p| map.to_screen(*p)).collect();
        shapes.push(Shape::convex_polygon(
            pts.clone(),
            Color32::from_rgba_unmultiplied(255, 140, 0, 50),
            Stroke::new(2.0, Color32::from_rgb(230, 110, 0)),
        ));
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
    }
    if let Some(p) = app.probe.as_ref().filter(|p| p.object == i) {
        shapes.push(Shape::circle_stroke(
            map.to_screen(p.uv),
            5.0,
            Stroke::new(2.0, Color32::BLACK),
        ));
    }
    painter.extend(shapes);
    let shift = ui.input(|inp| inp.modifiers.shift);
    if shift
        && (response.clicked() || response.dragged())
        && let Some(pos) = response.interact_pointer_pos()
    {
        app.set_probe(i, map.to_domain(pos));
    } else if response.clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        let p = map.to_domain(pos);
        let picked = pick_vertex(&basis, p, 15.0 / map.scale);
        app.selection = Selection {
            object: Some(i),
            vertex: picked,
        };
        app.vertex_edit = None;
        app.status = match picked {
            Some(v) => format!("selected vertex {v}"),
            None => "no PS-triangle there".into(),
        };
    }
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
