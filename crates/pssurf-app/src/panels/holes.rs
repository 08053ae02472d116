//! Hole filling (issue 18, part 8; thesis 6.3.3, Figure 6.14): the edges bounding a hole are
//! picked in the 3D view (click near an edge, then *Add edge at probe*), the iteration runs one
//! step per click with the interior method chosen at each step, and the patches (one, or two
//! for a gap between two edges) appear in place, each step one undo step. The quality report
//! of the last step is shown.

use std::sync::Arc;

use pssurf::hole::{
    FillOptions, HoleBoundary, HoleError, HoleFill, Interior, QualityReport, SurfaceEdge,
    gap_between, quality,
};
use pssurf::surface::{Surface, UniformSurface, UpsSurface};

use super::Panel;
use crate::command::{Command, ViewContext};
use crate::scene::{SceneObject, Transform};

/// The most steps the dialog runs (a hexagonal patch then has about 50,000 vertices, which
/// the view redraws at once; the CLI goes to 9).
pub const MAX_DIALOG_STEPS: usize = 7;

/// A picked edge: an object (by identity) and one of its sides.
#[derive(Clone, Debug, PartialEq)]
pub struct PickedEdge {
    /// The object's identity.
    pub object: u64,
    /// The side (0-based) of its domain boundary.
    pub side: usize,
    /// "name, side k" for the list.
    pub label: String,
}

/// A running fill: the iterations and the objects that show their patches.
struct Session {
    fills: Vec<HoleFill>,
    patches: Vec<u64>,
    reports: Vec<QualityReport>,
}

/// The hole dialog.
pub struct HolesPanel {
    /// The picked edges, in order.
    pub edges: Vec<PickedEdge>,
    /// The interior method for the next step.
    pub interior: Interior,
    /// The tolerance (relative to the model size) of *Run to tolerance*.
    pub tolerance: f64,
    /// The angle tolerance in degrees.
    pub angle_tolerance: f64,
    session: Option<Session>,
}

impl Default for HolesPanel {
    fn default() -> Self {
        let d = FillOptions::default();
        HolesPanel {
            edges: Vec::new(),
            interior: d.interior,
            tolerance: d.tolerance,
            angle_tolerance: d.angle_tolerance,
            session: None,
        }
    }
}

/// The side of `surface`'s domain nearest to `uv`.
fn nearest_side(surface: &Arc<Surface>, uv: nalgebra::Point2<f64>) -> Option<usize> {
    let distance = |e: &SurfaceEdge| {
        let d = e.to - e.from;
        let t = ((uv - e.from).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
        (e.from + d * t - uv).norm()
    };
    SurfaceEdge::sides(surface.clone())
        .iter()
        .enumerate()
        .min_by(|a, b| distance(a.1).total_cmp(&distance(b.1)))
        .map(|(k, _)| k)
}

/// A filled patch as a surface.
fn as_surface(patch: pssurf::ups::Ups<nalgebra::Vector3<f64>>) -> Result<Surface, String> {
    UniformSurface::new(UpsSurface::Parametric(patch))
        .map(Surface::Uniform)
        .map_err(|e| format!("the patch: {e}"))
}

impl HolesPanel {
    /// Adds the side nearest the probe.
    fn add_probed_edge(&mut self, cx: &mut ViewContext<'_>) {
        let Some(probe) = cx.probe() else {
            cx.status("click near an edge of a surface first: the probe marks it");
            return;
        };
        let Some(o) = cx.doc.scene.objects.get(probe.object) else {
            return;
        };
        let Some(side) = o.surface().and_then(|s| nearest_side(s, probe.uv)) else {
            cx.status(format!("{} has no edges", o.name));
            return;
        };
        let edge = PickedEdge {
            object: o.id,
            side,
            label: format!("{}, side {}", o.name, side + 1),
        };
        if self.edges.contains(&edge) {
            cx.status(format!("{} is already picked", edge.label));
        } else {
            cx.status(format!("picked {}", edge.label));
            self.edges.push(edge);
        }
    }

    /// The boundaries of the picked edges (two for a gap).
    fn boundaries(&self, cx: &ViewContext<'_>) -> Result<Vec<HoleBoundary>, String> {
        let mut curves = Vec::new();
        for e in &self.edges {
            let i = cx
                .doc
                .scene
                .index_of(e.object)
                .ok_or_else(|| format!("{} was deleted", e.label))?;
            let o = &cx.doc.scene.objects[i];
            if o.transform != Transform::default() {
                return Err(format!(
                    "{} is moved or turned: hole filling works on surfaces at their own place",
                    o.name
                ));
            }
            let surface = (o.surface().cloned()).ok_or_else(|| {
                format!("{} is a mesh: holes are filled between surfaces", o.name)
            })?;
            let side = SurfaceEdge::sides(surface)
                .into_iter()
                .nth(e.side)
                .ok_or_else(|| format!("{} no longer has that side", e.label))?;
            curves.push(side);
        }
        let result: Result<Vec<HoleBoundary>, HoleError> = match &curves[..] {
            [a, b] => gap_between(Arc::new(a.clone()), Arc::new(b.clone())).map(Vec::from),
            _ => HoleBoundary::new(
                curves
                    .into_iter()
                    .map(|c| Box::new(c) as pssurf::hole::DynCurve)
                    .collect(),
            )
            .map(|b| vec![b]),
        };
        result.map_err(|e| e.to_string())
    }

    /// Starts a fill: the initial solutions, added to the scene in place.
    fn start(&mut self, cx: &mut ViewContext<'_>) {
        let holes = match self.boundaries(cx) {
            Ok(h) => h,
            Err(e) => return cx.status(format!("cannot fill: {e}")),
        };
        let mut fills = Vec::new();
        for hole in holes {
            match HoleFill::new(hole, self.tolerance, self.angle_tolerance) {
                Ok(f) => fills.push(f),
                Err(e) => return cx.status(format!("cannot fill: {e}")),
            }
        }
        let mut objects = Vec::new();
        let mut reports = Vec::new();
        for (k, f) in fills.iter().enumerate() {
            let patch = match f.patch(self.interior) {
                Ok(p) => p,
                Err(e) => return cx.status(format!("cannot fill: {e}")),
            };
            match quality(f, &patch) {
                Ok(r) => reports.push(r),
                Err(e) => return cx.status(format!("cannot measure the patch: {e}")),
            }
            let surface = match as_surface(patch) {
                Ok(s) => s,
                Err(e) => return cx.status(format!("cannot fill: {e}")),
            };
            let mut o = SceneObject::new(format!("hole patch {}", k + 1), surface);
            o.group = "hole".into();
            objects.push(o);
        }
        let patches = objects.iter().map(|o| o.id).collect();
        cx.emit(Command::Insert {
            objects,
            what: "fill hole",
        });
        self.session = Some(Session {
            fills,
            patches,
            reports,
        });
    }

    /// One step (or, with `to_tolerance`, steps until the tolerances are met), then the
    /// patches with the chosen interior method replace the shown ones.
    fn advance(&mut self, cx: &mut ViewContext<'_>, to_tolerance: bool) {
        let interior = self.interior;
        let Some(s) = &mut self.session else { return };
        for f in &mut s.fills {
            let result = if to_tolerance {
                f.run_to_tolerance(MAX_DIALOG_STEPS)
            } else if f.level() >= MAX_DIALOG_STEPS {
                Err(HoleError::TooManyIterations {
                    requested: f.level() + 1,
                })
            } else {
                f.step()
            };
            if let Err(e) = result {
                return cx.status(format!("no further step: {e} (the dialog stops at {MAX_DIALOG_STEPS}; the CLI goes to 9)"));
            }
        }
        self.show(cx, interior, "hole step");
    }

    /// Replaces the shown patches by the current level's patches with `interior`, as one
    /// undo step.
    fn show(&mut self, cx: &mut ViewContext<'_>, interior: Interior, what: &'static str) {
        let Some(s) = &mut self.session else { return };
        s.reports.clear();
        let mut surfaces = Vec::new();
        for (f, &id) in s.fills.iter().zip(&s.patches) {
            let Some(object) = cx.doc.scene.index_of(id) else {
                return cx.status("the patch was deleted: start again");
            };
            let patch = match f.patch(interior) {
                Ok(p) => p,
                Err(e) => return cx.status(format!("no patch: {e}")),
            };
            match quality(f, &patch) {
                Ok(r) => s.reports.push(r),
                Err(e) => return cx.status(format!("cannot measure the patch: {e}")),
            }
            match as_surface(patch) {
                Ok(surface) => surfaces.push((object, Box::new(surface))),
                Err(e) => return cx.status(format!("no patch: {e}")),
            }
        }
        let level = s.fills.first().map_or(0, |f| f.level());
        cx.emit(Command::ReplaceSurfaces {
            surfaces,
            what,
            status: format!(
                "hole patch at level {level} with the {} interior",
                interior.name()
            ),
        });
    }

    fn edge_list(&mut self, ui: &mut egui::Ui) {
        let mut remove = None;
        for (k, e) in self.edges.iter().enumerate() {
            ui.horizontal(|ui| {
                ui.label(format!("{}. {}", k + 1, e.label));
                if ui
                    .small_button("x")
                    .on_hover_text("Remove this edge")
                    .clicked()
                {
                    remove = Some(k);
                }
            });
        }
        if let Some(k) = remove {
            self.edges.remove(k);
        }
    }

    fn report(&self, ui: &mut egui::Ui) {
        let Some(s) = &self.session else { return };
        for (k, (r, f)) in s.reports.iter().zip(&s.fills).enumerate() {
            ui.separator();
            ui.label(format!("patch {}: level {}", k + 1, f.level()));
            let last = r.iterations.last();
            ui.monospace(format!(
                "G0 max {:.3e} ({:.1e} of the size)\nG1 max {:.3}°\n∫H² dA {:.5}\nthin plate {:.5}\nedge deviation {:.3e}, angle {:.3}°{}",
                r.g0_max,
                r.g0_max / r.model_size,
                r.g1_max_degrees,
                r.mean_curvature_squared,
                r.thin_plate,
                last.map_or(0.0, |l| l.max_deviation),
                last.map_or(0.0, |l| l.max_angle),
                if f.converged() { " (within the tolerances)" } else { "" }
            ));
            for c in &r.singular_corners {
                ui.weak(format!(
                    "singular corner between curves {} and {} ({:.1}° off): G1 is measured away from it",
                    c.curve_in, c.curve_out, c.degrees
                ));
            }
        }
    }
}

impl Panel for HolesPanel {
    fn title(&self) -> &'static str {
        "Hole filling"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        ui.weak("Click near an edge of a surface (the probe marks it), then add it. 3 to 6 edges bound a hole, 2 a gap.");
        if ui
            .add_enabled(cx.probe().is_some(), egui::Button::new("Add edge at probe"))
            .clicked()
        {
            self.add_probed_edge(cx);
        }
        self.edge_list(ui);
        egui::ComboBox::from_label("interior")
            .selected_text(self.interior.name())
            .show_ui(ui, |ui| {
                for m in Interior::ALL {
                    ui.selectable_value(&mut self.interior, m, m.name());
                }
            });
        ui.horizontal(|ui| {
            let rule = crate::fields::Rule::Within(1e-12, 0.5);
            if let Some(m) =
                crate::fields::labelled(ui, "tolerance", &mut self.tolerance, rule, 1e-5).refusal()
            {
                cx.status(m);
            }
            let rule = crate::fields::Rule::Within(1e-6, 45.0);
            if let Some(m) =
                crate::fields::labelled(ui, "angle°", &mut self.angle_tolerance, rule, 0.01)
                    .refusal()
            {
                cx.status(m);
            }
        });
        let count = self.edges.len();
        let can_start = (2..=6).contains(&count);
        ui.horizontal(|ui| {
            if ui
                .add_enabled(can_start, egui::Button::new("Start"))
                .on_hover_text("The initial solution (thesis 5.3.1), added in place")
                .clicked()
            {
                self.start(cx);
            }
            let running = self.session.is_some();
            if ui
                .add_enabled(running, egui::Button::new("Step"))
                .on_hover_text("One refinement step (5.3.2) with the interior method above")
                .clicked()
            {
                self.advance(cx, false);
            }
            if ui
                .add_enabled(running, egui::Button::new("Run to tolerance"))
                .clicked()
            {
                self.advance(cx, true);
            }
            if ui
                .add_enabled(running, egui::Button::new("Apply interior"))
                .on_hover_text("Recompute the interior of the current level with the method above")
                .clicked()
            {
                let interior = self.interior;
                self.show(cx, interior, "hole interior");
            }
            if ui.button("Clear").clicked() {
                self.edges.clear();
                self.session = None;
            }
        });
        self.report(ui);
    }
}
