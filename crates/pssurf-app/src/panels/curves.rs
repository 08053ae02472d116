//! The Curves dialog: trace level lines, lines of curvature, asymptotic lines or a geodesic
//! on the selected surface; the curves are drawn in the 3D and domain views and follow edits.

use super::{Panel, load_settings, save_settings};
use crate::command::{Command, ViewContext};
use crate::curves::CurveRequest;

/// Which kind of curve the dialog traces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum CurveKind {
    /// Level lines of a field.
    #[default]
    Levels,
    /// Lines of curvature.
    Curvature,
    /// Asymptotic lines.
    Asymptotic,
    /// The shortest geodesic between two points.
    Geodesic,
}

impl CurveKind {
    const ALL: [CurveKind; 4] = [
        CurveKind::Levels,
        CurveKind::Curvature,
        CurveKind::Asymptotic,
        CurveKind::Geodesic,
    ];

    fn label(self) -> &'static str {
        match self {
            CurveKind::Levels => "Level lines",
            CurveKind::Curvature => "Lines of curvature",
            CurveKind::Asymptotic => "Asymptotic lines",
            CurveKind::Geodesic => "Shortest geodesic",
        }
    }
}

/// The Curves dialog's settings.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct CurvesPanel {
    /// What to trace.
    pub kind: CurveKind,
    /// The field of level lines (K, H, k1, k2, kabs, z or a formula).
    pub field: String,
    /// Its levels: `0,0.5` or `auto:N`.
    pub levels: String,
    /// Lines across the domain for evenly spaced lines.
    pub seeds: u32,
    /// The geodesic's start (u, v).
    pub from: Option<[f64; 2]>,
    /// The geodesic's end (u, v).
    pub to: Option<[f64; 2]>,
}

impl Default for CurvesPanel {
    fn default() -> Self {
        CurvesPanel {
            kind: CurveKind::Levels,
            field: "H".into(),
            levels: "auto:8".into(),
            seeds: 15,
            from: None,
            to: None,
        }
    }
}

impl CurvesPanel {
    /// The request the settings describe, or what is missing.
    fn request(&self) -> Result<CurveRequest, &'static str> {
        Ok(match self.kind {
            CurveKind::Levels => CurveRequest::Levels {
                field: self.field.clone(),
                levels: self.levels.clone(),
            },
            CurveKind::Curvature => CurveRequest::CurvatureLines { seeds: self.seeds },
            CurveKind::Asymptotic => CurveRequest::AsymptoticLines { seeds: self.seeds },
            CurveKind::Geodesic => CurveRequest::Geodesic {
                from: self
                    .from
                    .ok_or("set the start: probe a point, then 'Start here'")?,
                to: self
                    .to
                    .ok_or("set the end: probe a point, then 'End here'")?,
            },
        })
    }

    fn geodesic_ends(&mut self, ui: &mut egui::Ui, cx: &ViewContext<'_>, object: usize) {
        let probed = cx
            .probe()
            .filter(|p| p.object == object)
            .map(|p| [p.uv.x, p.uv.y]);
        let show = |p: Option<[f64; 2]>| {
            p.map_or("not set".to_string(), |p| {
                format!("({:.4}, {:.4})", p[0], p[1])
            })
        };
        ui.weak("Shift+click the surface or the domain to probe a point, then:");
        ui.horizontal(|ui| {
            if ui
                .add_enabled(probed.is_some(), egui::Button::new("Start here"))
                .clicked()
            {
                self.from = probed;
            }
            ui.label(show(self.from));
        });
        ui.horizontal(|ui| {
            if ui
                .add_enabled(probed.is_some(), egui::Button::new("End here"))
                .clicked()
            {
                self.to = probed;
            }
            ui.label(show(self.to));
        });
    }
}

impl Panel for CurvesPanel {
    fn title(&self) -> &'static str {
        "Curves"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let (Some(object), Some(o)) = (cx.selected(), cx.object()) else {
            ui.weak("Select a surface to trace curves on it.");
            return;
        };
        for k in CurveKind::ALL {
            ui.radio_value(&mut self.kind, k, k.label());
        }
        match self.kind {
            CurveKind::Levels => {
                ui.horizontal(|ui| {
                    ui.label("field");
                    ui.add(egui::TextEdit::singleline(&mut self.field).desired_width(90.0))
                        .on_hover_text(
                            "K, H, k1, k2, kabs, z, or a formula of u, v, x, y, z, K, H…",
                        );
                });
                ui.horizontal(|ui| {
                    ui.label("levels");
                    ui.add(egui::TextEdit::singleline(&mut self.levels).desired_width(90.0))
                        .on_hover_text("Values separated by commas, or auto:N");
                });
            }
            CurveKind::Curvature | CurveKind::Asymptotic => {
                ui.horizontal(|ui| {
                    ui.label("lines across");
                    ui.add(egui::DragValue::new(&mut self.seeds).range(2..=60));
                });
            }
            CurveKind::Geodesic => self.geodesic_ends(ui, cx, object),
        }
        let request = self.request();
        if let Err(why) = &request {
            ui.weak(*why);
        }
        ui.horizontal(|ui| {
            if ui
                .add_enabled(request.is_ok(), egui::Button::new("Trace"))
                .clicked()
                && let Ok(request) = request
            {
                cx.emit(Command::TraceCurves { object, request });
            }
            let traced = cx.runtime.curves.sets.iter().any(|s| s.object == o.id);
            if ui
                .add_enabled(traced, egui::Button::new("Clear"))
                .on_hover_text("Remove the curves traced on this surface")
                .clicked()
            {
                cx.emit(Command::ClearCurves(Some(o.id)));
            }
        });
        for set in cx.runtime.curves.sets.iter().filter(|s| s.object == o.id) {
            ui.small(format!("{}: {}", set.request.describe(), set.summary));
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(self)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<CurvesPanel>(settings) {
            *self = CurvesPanel {
                seeds: s.seeds.clamp(2, 60),
                ..s
            };
        }
    }
}
