//! Reproducible noise on a surface's control points (for denoising experiments).

use super::{Panel, load_settings, replace_selected, save_settings};
use crate::command::ViewContext;
use pssurf::noise::NoiseKind;

/// The noise dialog.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub struct NoisePanel {
    /// Amplitude (uniform: half-width; Gaussian: standard deviation).
    pub amplitude: f64,
    /// Gaussian instead of uniform.
    pub gaussian: bool,
    /// The random seed.
    pub seed: u64,
}

impl Default for NoisePanel {
    fn default() -> Self {
        NoisePanel {
            amplitude: 0.01,
            gaussian: false,
            seed: 2003,
        }
    }
}

impl Panel for NoisePanel {
    fn title(&self) -> &'static str {
        "Noise"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(surface) = cx.surface() else {
            ui.weak("Select a surface to perturb its control points.");
            return;
        };
        egui::Grid::new("noise").num_columns(2).show(ui, |ui| {
            let rule = crate::fields::Rule::Within(0.0, 10.0);
            let amplitude = &mut self.amplitude;
            let outcome = crate::fields::labelled(ui, "amplitude", amplitude, rule, 0.001);
            if let Some(m) = outcome.refusal() {
                cx.status(m);
            }
            ui.end_row();
            ui.label("distribution");
            ui.horizontal(|ui| {
                ui.radio_value(&mut self.gaussian, false, "uniform");
                ui.radio_value(&mut self.gaussian, true, "Gaussian");
            });
            ui.end_row();
            ui.label("seed");
            ui.add(egui::DragValue::new(&mut self.seed));
            ui.end_row();
        });
        if ui.button("Add noise").clicked() {
            let kind = if self.gaussian {
                NoiseKind::Gaussian
            } else {
                NoiseKind::Uniform
            };
            let (a, seed) = (self.amplitude, self.seed);
            let noisy = match surface.with_noise(a, kind, seed) {
                Ok(noisy) => noisy,
                Err(e) => {
                    cx.status(format!("noise refused: {e}"));
                    return;
                }
            };
            let status = format!("added noise of amplitude {a} (seed {seed})");
            replace_selected(cx, "add noise", noisy, status);
            self.seed += 1;
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(self)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<NoisePanel>(settings)
            && s.amplitude.is_finite()
        {
            *self = NoisePanel {
                amplitude: s.amplitude.clamp(0.0, 10.0),
                ..s
            };
        }
    }
}
