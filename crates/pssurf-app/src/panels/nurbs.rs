//! NURBS → UPS (thesis 6.4.2): the selected NURBS surface approximated by a UPS surface to a
//! tolerance, added to the scene beside it (the library's `nurbs::approximate`).

use super::{Panel, load_settings, save_settings};
use crate::command::{Command, ViewContext};
use crate::scene::SceneObject;
use pssurf::nurbs::{ApproxOptions, approximate};
use pssurf::surface::Surface;

/// The NURBS → UPS dialog.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct NurbsPanel {
    /// The largest deviation allowed (model units).
    pub tolerance: f64,
}

impl Default for NurbsPanel {
    fn default() -> Self {
        NurbsPanel { tolerance: 0.01 }
    }
}

impl Panel for NurbsPanel {
    fn title(&self) -> &'static str {
        "NURBS to UPS"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(o) = cx.object() else {
            ui.weak("Select a NURBS surface to approximate it by a UPS surface.");
            return;
        };
        let Some(Surface::Nurbs(nurbs)) = o.surface().map(|s| s.as_ref()) else {
            ui.weak("Select a NURBS surface (File, Import IGES… reads them).");
            return;
        };
        ui.horizontal(|ui| {
            let rule = crate::fields::Rule::Within(1e-9, 1e9);
            let outcome =
                crate::fields::labelled(ui, "tolerance", &mut self.tolerance, rule, 0.001);
            if let Some(m) = outcome.refusal() {
                cx.status(m);
            }
        });
        if ui
            .button("Approximate")
            .on_hover_text("Add a UPS surface that interpolates the NURBS surface's values and derivatives at its vertices, refined until the deviation is within the tolerance")
            .clicked()
        {
            let opts = ApproxOptions {
                tolerance: Some(self.tolerance),
                ..ApproxOptions::default()
            };
            match approximate(nurbs, &opts) {
                Ok(a) => {
                    let mut object =
                        SceneObject::new(
                        format!("{} (UPS)", o.name),
                        // `approximate` refuses results with unusable values.
                        Surface::try_from(a.surface).expect("an approximation of usable values"),
                    );
                    object.group = o.group.clone();
                    object.transform = o.transform;
                    cx.emit(Command::Add(vec![object]));
                    cx.status(format!(
                        "approximated {} by a {} × {} UPS surface: max deviation {:.3e}, RMS {:.3e}",
                        o.name, a.counts[0], a.counts[1], a.max_deviation, a.rms_deviation
                    ));
                }
                Err(e) => cx.status(format!("not approximated: {e}")),
            }
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(self)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<NurbsPanel>(settings)
            && s.tolerance > 0.0
            && s.tolerance.is_finite()
        {
            self.tolerance = s.tolerance;
        }
    }
}
