//! Fairing (issue 18, part 5): the selected PS, UPS or NURPS surface made fairer with its
//! boundary fixed, by the library's `ps::fair` (one undo step).

use super::{Panel, load_settings, replace_selected, save_settings};
use crate::command::ViewContext;
use pssurf::ps::{FairOptions, fair};

/// The fairing dialog.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct FairingPanel {
    /// The weight of staying close to the original (0: the fairest surface).
    pub weight: f64,
}

impl Default for FairingPanel {
    fn default() -> Self {
        FairingPanel { weight: 0.1 }
    }
}

impl Panel for FairingPanel {
    fn title(&self) -> &'static str {
        "Fairing"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(o) = cx.object() else {
            ui.weak("Select a PS, UPS or NURPS surface to fair it.");
            return;
        };
        let Some(surface) = o.surface().filter(|s| s.ps_basis().is_some()) else {
            ui.weak("Fairing works on PS, UPS and NURPS surfaces.");
            return;
        };
        ui.horizontal(|ui| {
            let rule = crate::fields::Rule::Within(0.0, 1e9);
            let outcome = crate::fields::labelled(ui, "weight", &mut self.weight, rule, 0.01);
            if let Some(m) = outcome.refusal() {
                cx.status(m);
            }
        });
        ui.weak("0: the fairest surface with this boundary; larger: closer to the original.");
        if ui
            .button("Fair")
            .on_hover_text("Minimise the jumps of the second derivatives (thesis 5.4.3) with the boundary control triangles fixed")
            .clicked()
        {
            let opts = FairOptions {
                weight: self.weight,
                ..FairOptions::default()
            };
            match fair(surface, &opts) {
                Ok(f) => {
                    let status = format!(
                        "faired {}: energy {:.4e} -> {:.4e}, {} control points moved",
                        o.name, f.energy_before, f.energy_after, f.moved
                    );
                    replace_selected(cx, "fair", f.surface, status);
                }
                Err(e) => cx.status(format!("not faired: {e}")),
            }
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(self)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<FairingPanel>(settings)
            && s.weight.is_finite()
            && s.weight >= 0.0
        {
            *self = s;
        }
    }
}
