//! The 2D domain view: the triangulation, the PS refinement, the PS-points and PS-triangles
//! of the selected object. Clicking inside a PS-triangle selects its vertex; the wheel
//! zooms about the pointer, a right or middle drag pans, a double click shows it all.
//!
//! The triangulation is shown at any density: the edges in view are drawn as lines up to
//! [`VECTOR_EDGES`], beyond that rasterised into a picture of the view's pixels (each edge
//! darkening the pixels it crosses, so dense regions read as shading), cached until the
//! object, the zoom or the view's size change.

use std::sync::Arc;

use egui::{Color32, Pos2, Rect, Sense, Shape, Stroke, pos2, vec2};
use nalgebra::Point2;
use pssurf::ps::PsBasis;

use crate::command::{Command, ViewContext};
use crate::document::Selection;

/// The most edges in view drawn as lines; more are rasterised.
pub const VECTOR_EDGES: usize = 20_000;

/// The most triangles in view whose PS split lines are drawn.
const SPLIT_TRIANGLES: usize = 4000;

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

    /// This map magnified `zoom` times about the domain point `center`, which goes to the
    /// middle of `rect`.
    pub fn zoomed(self, zoom: f64, center: Point2<f64>, rect: Rect) -> Self {
        let scale = self.scale * zoom;
        let c = rect.center();
        let origin = pos2(
            c.x - ((center.x - self.lo.x) * scale) as f32,
            c.y + ((center.y - self.lo.y) * scale) as f32,
        );
        DomainMap {
            lo: self.lo,
            scale,
            origin,
        }
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

/// Where the domain view looks: a magnification and the domain point in its middle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Zoom {
    /// The object looked at (its id): another object starts unzoomed.
    pub object: u64,
    /// Magnification (1: the whole domain fits).
    pub factor: f64,
    /// The domain point in the middle of the view.
    pub center: Point2<f64>,
}

/// What the cached drawing of a triangulation depends on.
#[derive(Clone, Copy, Debug, PartialEq)]
struct DrawingKey {
    revision: u64,
    zoom: Option<Zoom>,
    rect: Rect,
}

/// The triangulation drawn for a view: lines, or a picture of rasterised edges with the
/// boundary as lines.
#[derive(Clone)]
enum Drawing {
    Lines(Arc<Vec<Shape>>),
    Picture(egui::TextureHandle, Arc<Vec<Shape>>),
}

/// The domain view: its zoom and its cached drawing.
#[derive(Default)]
pub struct DomainView {
    /// The zoom, if the user zoomed.
    pub zoom: Option<Zoom>,
    drawing: Option<(DrawingKey, Drawing)>,
}

impl std::fmt::Debug for DomainView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DomainView")
            .field("zoom", &self.zoom)
            .finish()
    }
}

impl DomainView {
    /// Whether the triangulation is drawn as a rasterised picture (many edges in view).
    pub fn rasterised(&self) -> bool {
        matches!(self.drawing, Some((_, Drawing::Picture(..))))
    }

    /// Draws the domain view of the selected object; clicks go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let size = vec2(ui.available_width(), ui.available_width().min(320.0));
        let (rect, response) = ui.allocate_exact_size(size, Sense::click_and_drag());
        let response = response.on_hover_text(
            "Click a PS-triangle to select its vertex; Shift+click or Shift+drag moves the \
             probe; the wheel zooms, a right drag pans, a double click shows all",
        );
        response.widget_info(|| {
            egui::WidgetInfo::labeled(egui::accesskit::Role::Canvas, true, "domain view")
        });
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 2.0, Color32::from_gray(250));
        let Some(i) = cx.selected() else {
            return centered_message(&painter, rect, "no object selected");
        };
        let object = &cx.doc.scene.objects[i];
        let Some(basis) = object.surface().and_then(|s| s.ps_basis()) else {
            return centered_message(&painter, rect, "the domain view shows PS surfaces");
        };
        let (lo, hi) = basis.triangulation().bounds();
        let whole = DomainMap::new(lo, hi, rect);
        self.zoom = self.zoom.filter(|z| z.object == object.id);
        self.navigate(ui, &response, &whole, rect, object.id);
        let map = match self.zoom {
            Some(z) => whole.zoomed(z.factor, z.center, rect),
            None => whole,
        };
        let key = DrawingKey {
            revision: object.revision,
            zoom: self.zoom,
            rect,
        };
        let drawing = match &self.drawing {
            Some((k, d)) if *k == key => d.clone(),
            _ => {
                let d = draw_triangulation(ui.ctx(), basis, &map, rect);
                self.drawing = Some((key, d.clone()));
                d
            }
        };
        let mut shapes: Vec<Shape> = match &drawing {
            Drawing::Lines(lines) => lines.as_ref().clone(),
            Drawing::Picture(texture, boundary) => {
                painter.image(
                    texture.id(),
                    rect,
                    Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0)),
                    Color32::WHITE,
                );
                boundary.as_ref().clone()
            }
        };
        if let Some(v) = cx.doc.selection.vertex {
            shapes.extend(selection_shapes(basis, &map, v));
        }
        for (uvs, color) in cx.runtime.curves.domain_polylines(object.id) {
            let points: Vec<Pos2> = uvs.iter().map(|p| map.to_screen(*p)).collect();
            let [r, g, b] = color;
            shapes.push(Shape::line(
                points,
                Stroke::new(1.5, Color32::from_rgb(r, g, b)),
            ));
        }
        let pass = ui.ctx().cumulative_pass_nr();
        if let Some(mark) = cx
            .runtime
            .region
            .filter(|m| m.id == object.id && m.pass + 2 >= pass)
        {
            // The region of an edit by curvature: control triangles of vertices inside move.
            let centre = map.to_screen(mark.uv);
            let edge = map.to_screen(mark.uv + nalgebra::Vector2::new(mark.radius, 0.0));
            shapes.push(Shape::circle_stroke(
                centre,
                (edge - centre).length(),
                Stroke::new(1.5, Color32::from_rgb(230, 110, 0)),
            ));
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

    /// Zoom (wheel, about the pointer), pan (right or middle drag), reset (double click).
    fn navigate(
        &mut self,
        ui: &egui::Ui,
        response: &egui::Response,
        whole: &DomainMap,
        rect: Rect,
        object: u64,
    ) {
        if response.double_clicked() {
            self.zoom = None;
            return;
        }
        let mut z = self.zoom.unwrap_or(Zoom {
            object,
            factor: 1.0,
            center: whole.to_domain(rect.center()),
        });
        let before = z;
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if response.hovered()
            && scroll != 0.0
            && let Some(pointer) = response.hover_pos()
        {
            let at = whole.zoomed(z.factor, z.center, rect).to_domain(pointer);
            let factor = (z.factor * f64::from((scroll * 0.003).exp())).clamp(1.0, 1e6);
            // Keep the domain point under the pointer where it is.
            z.center = at + (z.center - at) * (z.factor / factor);
            z.factor = factor;
        }
        if response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
        {
            let d = response.drag_delta();
            let per_pixel = 1.0 / (whole.scale * z.factor);
            z.center.x -= f64::from(d.x) * per_pixel;
            z.center.y += f64::from(d.y) * per_pixel;
        }
        if z != before {
            self.zoom = Some(z);
        }
    }
}

/// Whether the segment `a`–`b` may cross `rect` (false only when both ends lie beyond the
/// same side).
fn may_cross(rect: Rect, a: Pos2, b: Pos2) -> bool {
    !((a.x < rect.left() && b.x < rect.left())
        || (a.x > rect.right() && b.x > rect.right())
        || (a.y < rect.top() && b.y < rect.top())
        || (a.y > rect.bottom() && b.y > rect.bottom()))
}

/// The triangulation in view: each edge once, boundary edges darker; the PS split lines
/// when few triangles are in view. Beyond [`VECTOR_EDGES`] edges in view, the inner edges
/// become a picture.
fn draw_triangulation(
    ctx: &egui::Context,
    basis: &PsBasis,
    map: &DomainMap,
    rect: Rect,
) -> Drawing {
    let tri = basis.triangulation();
    let edge = Stroke::new(1.0, Color32::from_gray(90));
    let border = Stroke::new(1.5, Color32::from_gray(40));
    let split = Stroke::new(0.5, Color32::from_rgb(70, 110, 210));
    let mut inner: Vec<[Pos2; 2]> = Vec::new();
    let mut boundary: Vec<Shape> = Vec::new();
    let mut in_view = Vec::new();
    for t in 0..tri.triangle_count() {
        let mut seen = false;
        for k in 0..3 {
            let (a, b) = tri.edge_vertices(t, k);
            let (pa, pb) = (map.to_screen(tri.vertex(a)), map.to_screen(tri.vertex(b)));
            if !may_cross(rect, pa, pb) {
                continue;
            }
            seen = true;
            if tri.is_boundary_edge(t, k) {
                boundary.push(Shape::line_segment([pa, pb], border));
            } else if a < b {
                inner.push([pa, pb]);
            }
        }
        if seen {
            in_view.push(t);
        }
    }
    if inner.len() > VECTOR_EDGES {
        let image = rasterise(&inner, rect);
        let texture = ctx.load_texture("domain edges", image, egui::TextureOptions::LINEAR);
        return Drawing::Picture(texture, Arc::new(boundary));
    }
    let mut shapes: Vec<Shape> = (inner.into_iter())
        .map(|s| Shape::line_segment(s, edge))
        .collect();
    if in_view.len() <= SPLIT_TRIANGLES {
        let r = basis.refinement();
        for &t in &in_view {
            let z = map.to_screen(r.z(t));
            let v = tri.triangle(t);
            for k in 0..3 {
                let to_vertex = [z, map.to_screen(tri.vertex(v[k]))];
                shapes.push(Shape::line_segment(to_vertex, split));
                let to_edge = [z, map.to_screen(r.edge_point(tri, t, k))];
                shapes.push(Shape::line_segment(to_edge, split));
            }
        }
    }
    shapes.extend(boundary);
    Drawing::Lines(Arc::new(shapes))
}

/// Edges rasterised into a picture of `rect` (one pixel per point): each edge adds ink
/// along its length, so a pixel crossed by many edges is dark and one crossed by a single
/// edge is a faint line, whatever the density.
fn rasterise(edges: &[[Pos2; 2]], rect: Rect) -> egui::ColorImage {
    let (w, h) = (
        rect.width().ceil().max(1.0) as usize,
        rect.height().ceil().max(1.0) as usize,
    );
    let mut ink = vec![0f32; w * h];
    for [a, b] in edges {
        let (a, b) = (*a - rect.min, *b - rect.min);
        let length = (b - a).length();
        let steps = length.ceil().clamp(1.0, 4.0 * (w + h) as f32) as usize;
        let per_step = length.max(0.3) / steps as f32;
        for s in 0..=steps {
            let p = a + (b - a) * (s as f32 / steps as f32);
            if p.x >= 0.0 && p.y >= 0.0 && (p.x as usize) < w && (p.y as usize) < h {
                ink[p.y as usize * w + p.x as usize] += 0.35 * per_step;
            }
        }
    }
    let pixels = (ink.iter())
        .map(|&k| Color32::from_rgba_unmultiplied(50, 50, 60, (k.min(1.0) * 200.0) as u8))
        .collect();
    egui::ColorImage::new([w, h], pixels)
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
