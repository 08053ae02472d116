//! The legend of a curvature plot, in its own strip beside the 3D view (never over the
//! geometry): the quantity and its unit, the colour bar with ticks, the data's true maximum
//! and minimum with an arrow when the scale clips values on that side, and how the range
//! was chosen.

use egui::{Align2, Color32, FontId, Rect, Stroke, pos2, vec2};
use pssurf::text::Significant;
use pssurf_viz::colormap::{ColorMap, ColorScale};
use pssurf_viz::legend::extreme_labels;
use pssurf_viz::plot::Range;

use crate::display::{DisplaySettings, Legend};
use crate::fields::compact;

/// The width of the legend strip, in points.
pub const WIDTH: f32 = 150.0;

/// The colour of the arrows and extremes of clipped values.
const CLIPPED: Color32 = Color32::from_rgb(170, 40, 20);

/// How the range was chosen, in a few words (`auto: 1–99 %, symmetric`).
pub fn range_note(settings: &DisplaySettings, legend: &Legend) -> String {
    let (lo, hi) = legend.scale.ends();
    match settings.range {
        // The seed's map has the contrast curve as its automatic scale.
        Range::Auto if matches!(legend.scale, ColorScale::Contrast { .. }) => {
            "auto: the seed's contrast curve".into()
        }
        Range::Auto => {
            let t = settings.tail_percent;
            let mut note = if t == 0.0 {
                "auto: min to max".to_string()
            } else {
                format!("auto: {}–{} %", compact(t), compact(100.0 - t))
            };
            if settings.symmetric && lo == -hi {
                note.push_str(", symmetric");
            }
            note
        }
        Range::Fixed(..) => "fixed range".into(),
        Range::Contrast(c) => format!("contrast C = {}", compact(c)),
    }
}

/// Draws `legend` in `rect` (the strip beside the view): title, the data's maximum, the
/// bar with ticks, the minimum, then `note` and the share of clipped values.
pub fn paint(ui: &egui::Ui, rect: Rect, legend: &Legend, map: &ColorMap, note: &str) {
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 0.0, ui.visuals().panel_fill);
    let ink = ui.visuals().strong_text_color();
    let weak = ui.visuals().weak_text_color();
    let text = TextBlock {
        painter: &painter,
        left: rect.left() + 8.0,
        width: rect.width() - 16.0,
    };
    let (body, small) = (FontId::proportional(13.0), FontId::proportional(11.0));
    // The extremes in the monospace face, which has the arrows ▲ ▼.
    let mono = FontId::monospace(11.0);
    let mut title = vec![(legend.title(), body, ink)];
    if let Some((_, name)) = &legend.object {
        title.push((format!("of {name}"), small.clone(), weak));
    }
    let mut y = text.lines(rect.top() + 8.0, title);
    let data = legend.data;
    let (max, min) = data.as_ref().map_or_else(
        || ("  max —".to_string(), "  min —".to_string()),
        extreme_labels,
    );
    let clipped = |n: usize| if n > 0 { CLIPPED } else { ink };
    let above = clipped(data.map_or(0, |d| d.above));
    y = text.lines(y + 4.0, [(max, mono.clone(), above)]);
    let notes_height = 60.0;
    let bar = Rect::from_min_size(
        pos2(text.left + 4.0, y + 4.0),
        vec2(18.0, (rect.bottom() - y - notes_height - 26.0).max(40.0)),
    );
    paint_bar(&painter, bar, map);
    paint_ticks(&painter, bar, legend, ink);
    let below = clipped(data.map_or(0, |d| d.below));
    y = text.lines(bar.bottom() + 6.0, [(min, mono, below)]);
    let mut notes = vec![(note.to_string(), small.clone(), weak)];
    if let Some(d) = data {
        let share = format!("clipped: {} %", Significant(d.clipped_percent(), 3));
        notes.push((share, small.clone(), weak));
        if d.undefined > 0 {
            notes.push((format!("{} undefined", d.undefined), small, weak));
        }
    }
    text.lines(y + 6.0, notes);
}

/// Lines of text wrapped to a column of the legend.
struct TextBlock<'a> {
    painter: &'a egui::Painter,
    left: f32,
    width: f32,
}

impl TextBlock<'_> {
    /// Draws `(text, font, colour)` lines from `y` down; returns the `y` below them.
    fn lines(&self, mut y: f32, lines: impl IntoIterator<Item = (String, FontId, Color32)>) -> f32 {
        for (text, font, color) in lines {
            let galley = (self.painter).layout(text, font, color, self.width);
            let height = galley.size().y;
            self.painter.galley(pos2(self.left, y), galley, color);
            y += height + 2.0;
        }
        y
    }
}

/// The colour bar: the map from its start at the bottom to its end at the top.
fn paint_bar(painter: &egui::Painter, bar: Rect, map: &ColorMap) {
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
}

/// Tick marks and their values right of the bar.
fn paint_ticks(painter: &egui::Painter, bar: Rect, legend: &Legend, ink: Color32) {
    for (value, t) in pssurf_viz::legend::ticks(&legend.scale) {
        let y = bar.bottom() - t as f32 * bar.height();
        painter.line_segment(
            [pos2(bar.right(), y), pos2(bar.right() + 4.0, y)],
            Stroke::new(1.0, Color32::DARK_GRAY),
        );
        painter.text(
            pos2(bar.right() + 7.0, y),
            Align2::LEFT_CENTER,
            compact(value),
            FontId::monospace(11.0),
            ink,
        );
    }
}

/// The legend drawn into a picture strip `width` × `height` pixels (for exported pictures):
/// the same content as on screen, drawn by `pssurf_viz`'s software text and bar.
pub fn picture(
    legend: &Legend,
    map: &ColorMap,
    note: &str,
    width: u32,
    height: u32,
) -> image::RgbImage {
    let (w, h) = (width as usize, height as usize);
    let mut pixels = vec![[255u8, 255, 255]; w * h];
    let title = match &legend.object {
        Some((_, name)) => format!("{} of {name}", legend.title()),
        None => legend.title(),
    };
    let area = pssurf_viz::legend::Rect {
        x: 6.0,
        y: 6.0,
        w: width as f32 - 12.0,
        h: height as f32 - 40.0,
    };
    pssurf_viz::legend::draw_legend_data(
        &mut pixels,
        w,
        area,
        &title,
        map,
        &legend.scale,
        legend.data.as_ref(),
    );
    let style = pssurf_viz::text::TextStyle {
        size: 12.0,
        color: [90, 90, 90],
        align: pssurf_viz::text::Align::Left,
    };
    pssurf_viz::text::draw_text(&mut pixels, w, 8.0, height as f32 - 14.0, note, &style);
    let raw: Vec<u8> = pixels.into_iter().flatten().collect();
    image::RgbImage::from_raw(width, height, raw).expect("the buffer has width × height pixels")
}
