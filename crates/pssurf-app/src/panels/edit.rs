//! Edit by curvature (issue 16): at the probe, prescribe ku, kv, k1, k2, K or H and let the
//! control points nearby move (the library's `edit::edit_locally`). Typing a target and
//! pressing Apply is one undo step; dragging the target edits live, one undo step per drag.
//! The region is drawn in the domain view while the panel is open.

use std::sync::Arc;

use pssurf::edit::{EditRequest, LocalEdit, Measure, edit_locally};
use pssurf::surface::{ParametricSurface, Surface};

use super::{Panel, load_settings, save_settings};
use crate::command::{Command, ViewContext};
use crate::runtime::RegionMark;

/// The settings of the panel.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct EditSettings {
    /// The measure's short name (ku, kv, k1, k2, K, H).
    pub measure: String,
    /// The region's radius in parameter units; 0 for automatic (2.5 times the longest edge of
    /// the triangle at the probe).
    pub radius: f64,
    /// Keep the point.
    pub keep_point: bool,
    /// Keep the tangent plane.
    pub keep_tangent: bool,
}

impl Default for EditSettings {
    fn default() -> Self {
        EditSettings {
            measure: "K".into(),
            radius: 0.0,
            keep_point: true,
            keep_tangent: true,
        }
    }
}

/// The edit-by-curvature dialog.
#[derive(Debug, Default)]
pub struct EditPanel {
    /// What to edit and how.
    pub settings: EditSettings,
    /// The target value (follows the measure at the probe until the user changes it).
    pub target: Option<f64>,
    /// The surface when a drag of the target began (each step edits it afresh).
    drag_base: Option<Arc<Surface>>,
    /// The last outcome, shown in the panel.
    pub report: Option<String>,
}

impl EditPanel {
    /// The measure chosen.
    fn measure(&self) -> Measure {
        Measure::parse(&self.settings.measure).unwrap_or(Measure::Gaussian)
    }

    /// The region's radius at `uv` on `s` (the automatic one when the setting is 0).
    fn radius(&self, s: &Surface, uv: nalgebra::Point2<f64>) -> f64 {
        if self.settings.radius > 0.0 {
            self.settings.radius
        } else {
            pssurf::edit::default_radius(s, uv).unwrap_or(1.0)
        }
    }

    /// The edit of `base` to the target at the probe: the changed control points.
    fn compute(
        &self,
        base: &Surface,
        uv: nalgebra::Point2<f64>,
        target: f64,
    ) -> Result<LocalEdit, String> {
        let mut s = base.clone();
        let req = EditRequest {
            at: uv,
            measure: self.measure(),
            target,
            radius: self.radius(base, uv),
            keep_point: self.settings.keep_point,
            keep_tangent: self.settings.keep_tangent,
        };
        edit_locally(&mut s, &req).map_err(|e| e.to_string())
    }
}

/// An edit's control points after it.
fn changes(e: &LocalEdit) -> Vec<(pssurf::surface::ControlId, pssurf::surface::ControlPoint)> {
    e.changes.iter().map(|c| (c.id, c.after)).collect()
}

/// One line about an edit.
fn describe(e: &LocalEdit) -> String {
    format!(
        "{} {:.6} -> {:.6}; {} control points moved (largest {:.3e}), {} iterations",
        e.measure.name(),
        e.before,
        e.after,
        e.changes.len(),
        e.largest_move,
        e.iterations
    )
}

impl Panel for EditPanel {
    fn title(&self) -> &'static str {
        "Edit by curvature"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(object) = cx.selected() else {
            ui.weak("Select a surface and put the probe on it (click it).");
            return;
        };
        let o = &cx.doc.scene.objects[object];
        let Some(surface) = o.surface() else {
            ui.weak("Editing by curvature works on surfaces; the selected object is a mesh.");
            return;
        };
        let Some(probe) = cx.probe().filter(|p| p.object == object) else {
            ui.weak("Put the probe on the selected surface (click it) to edit there.");
            return;
        };
        let uv = probe.uv;
        cx.emit(Command::MarkRegion(Some(RegionMark {
            id: o.id,
            uv,
            radius: self.radius(surface, uv),
            pass: ui.ctx().cumulative_pass_nr(),
        })));
        let current = surface.jet(uv).ok().and_then(|j| self.measure().of(&j.jet));
        egui::Grid::new("edit by curvature")
            .num_columns(2)
            .show(ui, |ui| {
                ui.label("measure");
                egui::ComboBox::from_id_salt("edit measure")
                    .selected_text(self.measure().description())
                    .show_ui(ui, |ui| {
                        for m in Measure::ALL {
                            if ui
                                .selectable_label(
                                    self.settings.measure == m.name(),
                                    m.description(),
                                )
                                .clicked()
                            {
                                self.settings.measure = m.name().to_string();
                                self.target = None;
                            }
                        }
                    });
                ui.end_row();
                ui.label("now");
                ui.monospace(current.map_or("undefined (singular)".into(), |v| format!("{v:.6}")));
                ui.end_row();
                let rule = crate::fields::Rule::Within(1e-9, 1e9);
                let outcome = crate::fields::labelled(
                    ui,
                    "region radius",
                    &mut self.settings.radius,
                    rule,
                    0.01,
                );
                if let Some(m) = outcome.refusal() {
                    cx.status(m);
                }
                ui.end_row();
            });
        ui.horizontal(|ui| {
            ui.checkbox(&mut self.settings.keep_point, "keep the point");
            ui.checkbox(&mut self.settings.keep_tangent, "keep the tangent plane");
        });
        let Some(now) = current else { return };
        let mut target = self.target.unwrap_or(now);
        let speed = 0.005 * now.abs().max(0.1);
        let drag = ui
            .horizontal(|ui| {
                let l = ui.label("target");
                ui.add(
                    egui::DragValue::new(&mut target)
                        .speed(speed)
                        .range(-1e12..=1e12),
                )
                .labelled_by(l.id)
                .on_hover_text("Drag to edit live, or type a value and press Apply")
            })
            .inner;
        if target != self.target.unwrap_or(now) {
            self.target = Some(target);
        }
        if drag.drag_started() {
            self.drag_base = Some(surface.clone());
            cx.emit(Command::StartDrag);
        }
        if drag.dragged()
            && drag.changed()
            && let Some(base) = &self.drag_base
        {
            match self.compute(base, uv, target) {
                Ok(e) => {
                    self.report = Some(describe(&e));
                    cx.emit(Command::DragControls {
                        object,
                        changes: changes(&e),
                    });
                }
                Err(e) => self.report = Some(e),
            }
        }
        if drag.drag_stopped() {
            self.drag_base = None;
            cx.emit(Command::EndDrag);
            cx.status("edited by curvature");
        }
        if ui
            .button("Apply")
            .on_hover_text("Move the control points within the radius so that the measure takes the target at the probe")
            .clicked()
        {
            match self.compute(surface, uv, target) {
                Ok(e) => {
                    self.report = Some(describe(&e));
                    cx.status(format!("edited by curvature: {}", describe(&e)));
                    cx.emit(Command::SetControls {
                        object,
                        what: "edit by curvature",
                        changes: changes(&e),
                    });
                }
                Err(e) => {
                    cx.status(format!("not edited: {e}"));
                    self.report = Some(e);
                }
            }
        }
        if let Some(r) = &self.report {
            ui.weak(r);
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(&self.settings)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<EditSettings>(settings)
            && s.radius.is_finite()
            && s.radius >= 0.0
            && Measure::parse(&s.measure).is_some()
        {
            self.settings = s;
        }
    }
}
