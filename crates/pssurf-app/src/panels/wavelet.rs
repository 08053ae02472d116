//! The UPS wavelet dialog (thesis 4.5, Figure 6.13): the spectrum per level and component,
//! thresholds, hard or soft, applied as an undoable step.

use super::{Panel, PanelContext, needs_ups};
use pssurf::surface::{Surface, UpsSurface};
use pssurf::ups::Ups;
use pssurf::ups::threshold::{LevelStats, Shrink, ThresholdRule};
use pssurf::vector::Vector;

/// The wavelet dialog.
#[derive(Debug)]
pub struct WaveletPanel {
    /// Decomposition levels F.
    pub levels: u32,
    /// Threshold in percent of each level's largest coefficient.
    pub percent: f64,
    /// Soft instead of hard thresholding.
    pub soft: bool,
    /// The spectrum of the selected surface (computed on demand).
    pub spectrum: Option<(u64, Vec<LevelStats>)>,
    /// What the last thresholding did.
    pub last: Vec<LevelStats>,
}

impl Default for WaveletPanel {
    fn default() -> Self {
        WaveletPanel {
            levels: 1,
            percent: 5.0,
            soft: true,
            spectrum: None,
            last: Vec::new(),
        }
    }
}

fn spectrum<V: Vector + Default>(s: &Ups<V>, levels: u32) -> Result<Vec<LevelStats>, String> {
    Ok(s.wavelet_transform(levels)
        .map_err(|e| e.to_string())?
        .spectrum())
}

fn threshold<V: Vector + Default>(
    s: &Ups<V>,
    levels: u32,
    rule: ThresholdRule,
    mode: Shrink,
) -> Result<(Ups<V>, Vec<LevelStats>), String> {
    let mut d = s.wavelet_transform(levels).map_err(|e| e.to_string())?;
    let stats = d.threshold(|_, _| rule, mode);
    Ok((d.reconstruct(), stats))
}

impl Panel for WaveletPanel {
    fn title(&self) -> &'static str {
        "Wavelets"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut PanelContext<'_>) {
        let Some(u) = cx.uniform() else {
            return needs_ups(ui);
        };
        let revision = cx.object().map(|o| o.revision).unwrap_or(0);
        let available = u.grid().coarsening_levels();
        if available == 0 {
            ui.weak("This surface has no coarser level: subdivide it first.");
            return;
        }
        self.levels = self.levels.clamp(1, available);
        egui::Grid::new("wavelet").num_columns(2).show(ui, |ui| {
            ui.label("levels F");
            ui.add(egui::DragValue::new(&mut self.levels).range(1..=available));
            ui.end_row();
            ui.label("threshold (% of max)");
            ui.add(
                egui::DragValue::new(&mut self.percent)
                    .speed(0.5)
                    .range(0.0..=100.0),
            );
            ui.end_row();
            ui.label("mode");
            ui.horizontal(|ui| {
                ui.radio_value(&mut self.soft, true, "soft");
                ui.radio_value(&mut self.soft, false, "hard");
            });
            ui.end_row();
        });
        let stale = self.spectrum.as_ref().is_none_or(|(r, s)| {
            *r != revision || s.iter().map(|x| x.level).max() != Some(self.levels as usize)
        });
        if stale {
            let s = match u {
                UpsSurface::Functional(s) => spectrum(s, self.levels),
                UpsSurface::Parametric(s) => spectrum(s, self.levels),
                UpsSurface::Rational(_) => {
                    Err("wavelets are defined for polynomial UPS surfaces".into())
                }
            };
            match s {
                Ok(s) => self.spectrum = Some((revision, s)),
                Err(e) => {
                    ui.colored_label(egui::Color32::DARK_RED, e);
                    return;
                }
            }
        }
        let names: &[&str] = if matches!(u, UpsSurface::Functional(_)) {
            &["z"]
        } else {
            &["x", "y", "z"]
        };
        if let Some((_, s)) = &self.spectrum {
            stats_grid(ui, "spectrum", s, names, false);
        }
        let apply = ui.button("Threshold").on_hover_text(
            "Decompose, threshold every level and component, reconstruct (undo with Ctrl+Z)",
        );
        if apply.clicked() {
            let rule = ThresholdRule::PercentOfMax(self.percent);
            let mode = if self.soft {
                Shrink::Soft
            } else {
                Shrink::Hard
            };
            let r = match u {
                UpsSurface::Functional(s) => threshold(s, self.levels, rule, mode)
                    .map(|(s, st)| (UpsSurface::Functional(s), st)),
                UpsSurface::Parametric(s) => threshold(s, self.levels, rule, mode)
                    .map(|(s, st)| (UpsSurface::Parametric(s), st)),
                UpsSurface::Rational(_) => {
                    Err("wavelets are defined for polynomial UPS surfaces".into())
                }
            };
            match r {
                Ok((s, stats)) => {
                    let zeroed: usize = stats.iter().map(|s| s.zeroed).sum();
                    let total: usize = stats.iter().map(|s| s.count).sum();
                    cx.replace_surface("wavelet threshold", Surface::from(s));
                    *cx.status =
                        format!("thresholding set {zeroed} of {total} coefficients to zero");
                    self.last = stats;
                }
                Err(e) => *cx.status = e,
            }
        }
        if !self.last.is_empty() {
            ui.label("last thresholding:");
            stats_grid(ui, "last", &self.last, names, true);
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
