//! The settings panels of the 3D view: what it shows (mode, colours, level, light,
//! overlays) and what the probe shows, with the probe's values.

use pssurf::interrogate::CurvatureQuantity;
use pssurf_viz::colormap::ColorMap;
use pssurf_viz::plot::Range;

use crate::command::{Command, ViewContext};
use crate::display::{DisplaySettings, Light, ViewMode};
use crate::fields::{self, Rule, compact};
use crate::probe::{Alignment, Probe};

/// The display settings panel (its state is the view state itself).
#[derive(Debug, Default)]
pub struct DisplayPanel;

impl DisplayPanel {
    /// Draws the display settings of the 3D view; a change goes to `cx` as a command.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        display_ui(ui, cx);
    }
}

/// The probe panel: what the probe shows, and its values.
#[derive(Debug, Default)]
pub struct ProbePanel;

impl ProbePanel {
    /// Draws the probe's settings and values; changes go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        probe_ui(ui, cx);
    }
}

fn display_ui(ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
    ui.heading("Display");
    let mut d = cx.view.display.clone();
    let mut light = cx.view.light;
    let shown = cx
        .runtime
        .cache
        .legend(&cx.doc.scene, cx.doc.selection.object)
        .map(|l| l.scale.ends());
    let mut refused = Vec::new();
    mode_and_colours(ui, &mut d, shown, &mut refused);
    if d.mode == ViewMode::Shaded {
        light_ui(ui, &mut light);
    }
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut d.flat, "flat");
        ui.checkbox(&mut d.mesh_edges, "mesh edges")
            .on_hover_text("The edges of the drawn triangles (display level)");
        ui.checkbox(&mut d.overlays.wire, "triangulation");
        ui.checkbox(&mut d.overlays.refinement, "PS refinement");
        ui.checkbox(&mut d.overlays.control, "control triangles");
        ui.checkbox(&mut d.overlays.boundary, "boundary");
        ui.checkbox(&mut d.overlays.combs, "curvature combs")
            .on_hover_text("Curvature combs on the sides of the boundary (the longest tooth a tenth of the surface's size)");
    });
    for message in refused {
        cx.status(message);
    }
    if d != cx.view.display {
        cx.emit(Command::SetDisplay(d));
    }
    if light != cx.view.light {
        cx.emit(Command::SetLight(light));
    }
}

/// The view mode, its colour map and range or band width, and the display level. `shown`
/// is the range of the scale on screen (a fixed range starts from it).
fn mode_and_colours(
    ui: &mut egui::Ui,
    d: &mut DisplaySettings,
    shown: Option<(f64, f64)>,
    refused: &mut Vec<String>,
) {
    egui::ComboBox::from_label("show")
        .selected_text(d.mode.name())
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut d.mode, ViewMode::Shaded, "shaded");
            for q in CurvatureQuantity::ALL {
                ui.selectable_value(
                    &mut d.mode,
                    ViewMode::Curvature(q),
                    ViewMode::Curvature(q).name(),
                );
            }
            ui.selectable_value(&mut d.mode, ViewMode::Zebra, "zebra stripes");
            ui.selectable_value(&mut d.mode, ViewMode::Wireframe, "wireframe");
        });
    if matches!(d.mode, ViewMode::Curvature(_)) {
        egui::ComboBox::from_label("colour map")
            .selected_text(d.colormap.clone())
            .show_ui(ui, |ui| {
                for name in ColorMap::NAMES {
                    ui.selectable_value(&mut d.colormap, name.to_string(), name);
                }
            });
        range_ui(ui, d, shown, refused);
    }
    if d.mode == ViewMode::Zebra {
        ui.add(egui::Slider::new(&mut d.zebra_width_deg, 1.0..=20.0).text("band width °"));
    }
    ui.add(egui::Slider::new(&mut d.level, 0..=5).text("display level"))
        .on_hover_text("Each PS piece is drawn as 4^level triangles");
}

/// Headlight, or the azimuth and elevation of a light fixed in the scene.
fn light_ui(ui: &mut egui::Ui, l: &mut Light) {
    ui.checkbox(&mut l.headlight, "headlight")
        .on_hover_text("The light moves with the camera; off: fixed in the scene");
    if !l.headlight {
        ui.add(egui::Slider::new(&mut l.azimuth_deg, -180.0..=180.0).text("light azimuth °"));
        ui.add(egui::Slider::new(&mut l.elevation_deg, -90.0..=90.0).text("light elevation °"));
    }
}

/// The colour range: automatic (robust percentiles, symmetric or not), the seed's contrast
/// curve with C, or a fixed interval (starting from the range on screen); shared by all
/// objects or one per object.
fn range_ui(
    ui: &mut egui::Ui,
    d: &mut DisplaySettings,
    shown: Option<(f64, f64)>,
    refused: &mut Vec<String>,
) {
    #[derive(PartialEq)]
    enum Kind {
        Auto,
        Contrast,
        Fixed,
    }
    let mut kind = match d.range {
        Range::Auto => Kind::Auto,
        Range::Contrast(_) => Kind::Contrast,
        Range::Fixed(..) => Kind::Fixed,
    };
    ui.horizontal_wrapped(|ui| {
        ui.radio_value(&mut kind, Kind::Auto, "auto").on_hover_text(
            "Fitted to the data whenever they change, leaving out the tails (outliers) \
             at both ends",
        );
        ui.radio_value(&mut kind, Kind::Contrast, "contrast C")
            .on_hover_text(
                "Every value in the map: t = (1 + sign(κ)(1 − e^(−C|κ|)))/2 (seed 000); \
             a larger C shows smaller curvatures",
            );
        ui.radio_value(&mut kind, Kind::Fixed, "fixed")
            .on_hover_text("A range you set, the same whatever the data");
    });
    let (lo, hi) = shown.unwrap_or((-1.0, 1.0));
    d.range = match kind {
        Kind::Auto => {
            ui.horizontal(|ui| {
                let rule = Rule::Within(0.0, 25.0);
                let tail = &mut d.tail_percent;
                refused.extend(fields::labelled(ui, "tails %", tail, rule, 0.05).refusal());
                ui.checkbox(&mut d.symmetric, "symmetric")
                    .on_hover_text("For signed quantities: ±the larger end, 0 in the middle");
            });
            Range::Auto
        }
        Kind::Contrast => {
            let mut c = match d.range {
                Range::Contrast(c) => c,
                // From the range on screen: C that maps its end to κ_norm = 0.9.
                _ => std::f64::consts::LN_10 / hi.abs().max(lo.abs()).max(1e-300),
            };
            ui.horizontal(|ui| {
                ui.label("C");
                let rule = Rule::Positive(1e300);
                refused.extend(fields::number(ui, "contrast C", &mut c, rule, 0.05).refusal());
            });
            Range::Contrast(c)
        }
        Kind::Fixed => {
            let (mut from, mut to) = match d.range {
                Range::Fixed(a, b) => (a, b),
                _ => (lo, hi),
            };
            ui.horizontal(|ui| {
                ui.label("from");
                let rule = Rule::Coordinate;
                refused.extend(fields::number(ui, "range from", &mut from, rule, 0.01).refusal());
                ui.label("to");
                refused.extend(fields::number(ui, "range to", &mut to, rule, 0.01).refusal());
            });
            if to > from {
                Range::Fixed(from, to)
            } else {
                refused.push(format!(
                    "the range {} to {} is refused: it must run upwards",
                    compact(from),
                    compact(to)
                ));
                d.range
            }
        }
    };
    ui.checkbox(&mut d.shared_scale, "one scale for all objects")
        .on_hover_text("Off: each object gets its own scale (the legend shows the selected one's)");
}

fn probe_ui(ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
    ui.label("Click the surface (Shift+drag to move), or Shift+click the domain view.");
    let mut settings = cx.view.probe;
    let s = &mut settings;
    ui.horizontal(|ui| {
        ui.label("cross-planes:");
        ui.radio_value(&mut s.alignment, Alignment::Principal, "principal")
            .on_hover_text("Along the principal directions: the sections have curvatures κ1, κ2");
        ui.radio_value(&mut s.alignment, Alignment::Parametric, "parametric")
            .on_hover_text("Along the parameter directions s_u and s_v");
    });
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut s.planes, "planes");
        ui.checkbox(&mut s.sections, "sections");
        ui.checkbox(&mut s.circles, "osculating circles");
        ui.checkbox(&mut s.glyphs, "normal, directions");
        ui.checkbox(&mut s.coil, "torsion coils").on_hover_text(
            "The torsion of the coordinate curves (zero inside PS pieces: they are parabolas)",
        );
    });
    ui.add(egui::Slider::new(&mut s.size_percent, 5..=400).text("size %"))
        .on_hover_text("The size of the planes, sections, circles and glyphs");
    if settings != cx.view.probe {
        cx.emit(Command::SetProbeSettings(settings));
    }
    let Some(p) = cx.probe() else {
        ui.weak("no probe");
        return;
    };
    probe_values(ui, p);
    if ui.button("Remove probe").clicked() {
        cx.emit(Command::RemoveProbe);
    }
}

/// The probe's parameters, point, curvatures and normal curvatures of its cross-planes, in
/// a table of fixed-width columns (six significant digits, e-notation only outside
/// 1e-3 … 1e6), with units.
fn probe_values(ui: &mut egui::Ui, p: &Probe) {
    let cell = |x: f64| format!("{:>12}", compact(x));
    let triple = |v: [f64; 3]| v.map(cell).join(" ");
    egui::Grid::new("probe values")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            let mut row = |name: &str, value: String, unit: &str| {
                ui.label(name);
                ui.monospace(value);
                ui.weak(unit);
                ui.end_row();
            };
            row("u, v", format!("{} {}", cell(p.uv.x), cell(p.uv.y)), "");
            let q = p.point;
            row("point", triple([q.x, q.y, q.z]), "");
            match (&p.curvature, &p.cross) {
                (Some(c), Some(x)) => {
                    row("K", cell(c.gaussian), "1/length²");
                    row("H", cell(c.mean), "1/length");
                    row("κ1", cell(c.k1), "1/length");
                    row("κ2", cell(c.k2), "1/length");
                    let n = c.normal;
                    row("normal", triple([n.x, n.y, n.z]), "");
                    row("κn plane 1", cell(x.curvatures[0]), "1/length");
                    row("κn plane 2", cell(x.curvatures[1]), "1/length");
                }
                _ => row("curvature", "undefined (singular point)".into(), ""),
            }
        });
}
