//! Dyadic subdivision of a UPS surface (thesis 4.4): exact, the surface is unchanged.

use super::{Panel, load_settings, needs_ups, replace_selected, save_settings};
use crate::command::ViewContext;
use pssurf::surface::Surface;

/// The subdivision dialog.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub struct SubdivisionPanel {
    /// Subdivision steps per click.
    pub times: usize,
}

impl Default for SubdivisionPanel {
    fn default() -> Self {
        SubdivisionPanel { times: 1 }
    }
}

impl Panel for SubdivisionPanel {
    fn title(&self) -> &'static str {
        "Subdivision"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(u) = cx.uniform() else {
            return needs_ups(ui);
        };
        let n = u.grid().vertex_count();
        ui.label(format!(
            "{n} vertices, {} triangles",
            u.grid().triangle_count()
        ));
        ui.horizontal(|ui| {
            ui.label("steps");
            ui.add(egui::DragValue::new(&mut self.times).range(1..=4));
        });
        let after = n as f64 * 4f64.powi(self.times as i32);
        // The limit is said here, beside the steps it is about, and the button waits.
        let too_many = after > 4e6;
        if too_many {
            ui.colored_label(
                egui::Color32::DARK_RED,
                format!(
                    "{} subdivision(s) would make about {} vertices, more than 4 million.",
                    self.times,
                    crate::fields::compact(after)
                ),
            );
        }
        let button = ui
            .add_enabled(!too_many, egui::Button::new("Subdivide"))
            .on_hover_text("Refine the triangulation; the surface stays the same");
        if button.clicked() {
            let s = u.subdivide_times(self.times);
            let vertices = s.grid().vertex_count();
            let status = format!("subdivided {} time(s): {vertices} vertices", self.times);
            replace_selected(cx, "subdivide", Surface::from(s), status);
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(self)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<SubdivisionPanel>(settings) {
            self.times = s.times.clamp(1, 4);
        }
    }
}
