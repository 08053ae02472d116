//! The settings panels of the 3D view: what it shows (mode, colours, level, light,
//! overlays) and what the probe shows, with the probe's values.

use pssurf::interrogate::CurvatureQuantity;
use pssurf_viz::colormap::ColorMap;
use pssurf_viz::plot::Range;

use crate::command::{Command, ViewContext};
use crate::display::{DisplaySettings, Light, ViewMode};
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
    mode_and_colours(ui, &mut d);
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
    });
    if d != cx.view.display {
        cx.emit(Command::SetDisplay(d));
    }
    if light != cx.view.light {
        cx.emit(Command::SetLight(light));
    }
}

/// The view mode, its colour map and range or band width, and the display level.
fn mode_and_colours(ui: &mut egui::Ui, d: &mut DisplaySettings) {
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
        range_ui(ui, &mut d.range);
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

/// The colour range: automatic, the seed's contrast curve with C, or a fixed interval.
fn range_ui(ui: &mut egui::Ui, range: &mut Range) {
    #[derive(PartialEq)]
    enum Kind {
        Auto,
        Contrast,
        Fixed,
    }
    let mut kind = match range {
        Range::Auto => Kind::Auto,
        Range::Contrast(_) => Kind::Contrast,
        Range::Fixed(..) => Kind::Fixed,
    };
    ui.horizontal(|ui| {
        ui.radio_value(&mut kind, Kind::Auto, "auto range")
            .on_hover_text("Symmetric about 0 at the 98th percentile of |q| for signed quantities");
        ui.radio_value(&mut kind, Kind::Contrast, "contrast C")
            .on_hover_text("The seed's contrast curve");
        ui.radio_value(&mut kind, Kind::Fixed, "fixed");
    });
    *range = match kind {
        Kind::Auto => Range::Auto,
        Kind::Contrast => {
            let mut c = match *range {
                Range::Contrast(c) => c,
                _ => 1.0,
            };
            ui.horizontal(|ui| {
                let l = ui.label("C");
                ui.add(egui::DragValue::new(&mut c).speed(0.05).range(1e-6..=1e6))
                    .labelled_by(l.id);
            });
            Range::Contrast(c)
        }
        Kind::Fixed => {
            let (mut lo, mut hi) = match *range {
                Range::Fixed(a, b) => (a, b),
                _ => (-1.0, 1.0),
            };
            ui.horizontal(|ui| {
                let l = ui.label("from");
                ui.add(egui::DragValue::new(&mut lo).speed(0.01))
                    .labelled_by(l.id);
                let l = ui.label("to");
                ui.add(egui::DragValue::new(&mut hi).speed(0.01))
                    .labelled_by(l.id);
            });
            // Keep the interval non-empty.
            if hi <= lo {
                hi = lo + 1e-9_f64.max(lo.abs() * 1e-9);
            }
            Range::Fixed(lo, hi)
        }
    };
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
    });
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

/// The probe's parameters, point, curvatures and normal curvatures of its cross-planes.
fn probe_values(ui: &mut egui::Ui, p: &Probe) {
    egui::Grid::new("probe values")
        .num_columns(2)
        .show(ui, |ui| {
            let mut row = |name: &str, value: String| {
                ui.label(name);
                ui.monospace(value);
                ui.end_row();
            };
            row("u, v", format!("{:.6}, {:.6}", p.uv.x, p.uv.y));
            let q = p.point;
            row("point", format!("{:.5}, {:.5}, {:.5}", q.x, q.y, q.z));
            match (&p.curvature, &p.cross) {
                (Some(c), Some(x)) => {
                    row("K", format!("{:.6e}", c.gaussian));
                    row("H", format!("{:.6e}", c.mean));
                    row("κ1", format!("{:.6e}", c.k1));
                    row("κ2", format!("{:.6e}", c.k2));
                    let n = c.normal;
                    row("normal", format!("{:.4}, {:.4}, {:.4}", n.x, n.y, n.z));
                    row("κn plane 1", format!("{:.6e}", x.curvatures[0]));
                    row("κn plane 2", format!("{:.6e}", x.curvatures[1]));
                }
                _ => row("curvature", "undefined (singular point)".into()),
            }
        });
}
