//! The UPS wavelet dialog (thesis 4.5, Figure 6.13): the spectrum per level and component,
//! thresholds, hard or soft, applied as an undoable step.

use super::{Panel, load_settings, needs_ups, replace_selected, save_settings};
use crate::command::ViewContext;
use pssurf::surface::Surface;
use pssurf::ups::threshold::{LevelStats, Shrink, ThresholdRule};

/// The wavelet dialog's settings.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct WaveletSettings {
    /// Decomposition levels F.
    pub levels: u32,
    /// Threshold in percent of each level's largest coefficient.
    pub percent: f64,
    /// Soft instead of hard thresholding.
    pub soft: bool,
}

/// The wavelet dialog.
#[derive(Debug)]
pub struct WaveletPanel {
    /// Its settings.
    pub settings: WaveletSettings,
    /// The spectrum of the selected surface (computed on demand).
    pub spectrum: Option<(u64, Vec<LevelStats>)>,
    /// What the last thresholding did.
    pub last: Vec<LevelStats>,
}

impl Default for WaveletPanel {
    fn default() -> Self {
        WaveletPanel {
            settings: WaveletSettings {
                levels: 1,
                percent: 5.0,
                soft: true,
            },
            spectrum: None,
            last: Vec::new(),
        }
    }
}

impl Panel for WaveletPanel {
    fn title(&self) -> &'static str {
        "Wavelets"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(u) = cx.uniform() else {
            return needs_ups(ui);
        };
        let revision = cx.object().map(|o| o.revision).unwrap_or(0);
        let available = u.grid().coarsening_levels();
        if available == 0 {
            ui.weak("This surface has no coarser level: subdivide it first.");
            return;
        }
        let settings = &mut self.settings;
        settings.levels = settings.levels.clamp(1, available);
        egui::Grid::new("wavelet").num_columns(2).show(ui, |ui| {
            ui.label("levels F");
            ui.add(egui::DragValue::new(&mut settings.levels).range(1..=available));
            ui.end_row();
            ui.label("threshold (% of max)");
            let rule = crate::fields::Rule::Within(0.0, 100.0);
            let percent = &mut settings.percent;
            if let Some(m) = crate::fields::number(ui, "threshold %", percent, rule, 0.5).refusal()
            {
                cx.status(m);
            }
            ui.end_row();
            ui.label("mode");
            ui.horizontal(|ui| {
                ui.radio_value(&mut settings.soft, true, "soft");
                ui.radio_value(&mut settings.soft, false, "hard");
            });
            ui.end_row();
        });
        let stale = self.spectrum.as_ref().is_none_or(|(r, s)| {
            *r != revision || s.iter().map(|x| x.level).max() != Some(self.settings.levels as usize)
        });
        if stale {
            match u.wavelet_transform(self.settings.levels) {
                Ok(d) => self.spectrum = Some((revision, d.spectrum())),
                Err(e) => {
                    ui.colored_label(egui::Color32::DARK_RED, e.to_string());
                    return;
                }
            }
        }
        let names = u.coordinate_names();
        if let Some((_, s)) = &self.spectrum {
            stats_grid(ui, "spectrum", s, names, false);
        }
        let apply = ui.button("Threshold").on_hover_text(
            "Decompose, threshold every level and component, reconstruct (undo with Ctrl+Z)",
        );
        if apply.clicked() {
            let rule = ThresholdRule::PercentOfMax(self.settings.percent);
            let mode = if self.settings.soft {
                Shrink::Soft
            } else {
                Shrink::Hard
            };
            let denoised = u
                .denoise(self.settings.levels, |_, _| rule, mode)
                .and_then(|(s, stats)| Ok((Surface::try_from(s)?, stats)));
            match denoised {
                Ok((s, stats)) => {
                    let zeroed: usize = stats.iter().map(|s| s.zeroed).sum();
                    let total: usize = stats.iter().map(|s| s.count).sum();
                    let status =
                        format!("thresholding set {zeroed} of {total} coefficients to zero");
                    replace_selected(cx, "wavelet threshold", s, status);
                    self.last = stats;
                }
                Err(e) => cx.status(e.to_string()),
            }
        }
        if !self.last.is_empty() {
            ui.label("last thresholding:");
            stats_grid(ui, "last", &self.last, names, true);
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(&self.settings)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<WaveletSettings>(settings)
            && s.percent.is_finite()
        {
            self.settings = WaveletSettings {
                levels: s.levels.clamp(1, 12),
                percent: s.percent.clamp(0.0, 100.0),
                soft: s.soft,
            };
        }
    }
}

fn stats_grid(ui: &mut egui::Ui, id: &str, stats: &[LevelStats], names: &[&str], zeroed: bool) {
    egui::Grid::new(id).striped(true).show(ui, |ui| {
        for h in [
            "level",
            "coord",
            "count",
            "max |d|",
            if zeroed { "zeroed" } else { "norm" },
        ] {
            ui.strong(h);
        }
        ui.end_row();
        for s in stats {
            ui.label(s.level.to_string());
            ui.label(names.get(s.component).copied().unwrap_or("?"));
            ui.label(s.count.to_string());
            ui.label(format!("{:.2e}", s.max_abs));
            ui.label(if zeroed {
                format!("{:.1}%", s.zeroed_percent())
            } else {
                format!("{:.2e}", s.norm)
            });
            ui.end_row();
        }
    });
}
