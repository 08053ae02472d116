//! Reproducible noise on a surface's control points (for denoising experiments).

use super::{Panel, PanelContext};
use pssurf::noise::NoiseKind;

/// The noise dialog.
#[derive(Debug)]
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

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut PanelContext<'_>) {
        let Some(surface) = cx.object().map(|o| &o.surface) else {
            ui.weak("Select a surface to perturb its control points.");
            return;
        };
        egui::Grid::new("noise").num_columns(2).show(ui, |ui| {
            ui.label("amplitude");
            ui.add(
                egui::DragValue::new(&mut self.amplitude)
                    .speed(0.001)
                    .range(0.0..=10.0),
            );
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
                    *cx.status = format!("noise refused: {e}");
                    return;
                }
            };
            cx.replace_surface("add noise", noisy);
            *cx.status = format!("added noise of amplitude {a} (seed {seed})");
            self.seed += 1;
        }
    }
}
