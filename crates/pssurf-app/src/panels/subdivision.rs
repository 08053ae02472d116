//! Subdivision: dyadic subdivision of a UPS surface (thesis 4.4: exact, the surface is
//! unchanged), and the classic schemes on a mesh object (seed 004: Loop, √3, butterfly),
//! always applied to its control mesh, so that changing the scheme or the steps never
//! compounds.

use std::sync::Arc;

use super::{Panel, load_settings, needs_ups, replace_selected, save_settings};
use crate::command::{Command, ViewContext};
use crate::scene::{MAX_MESH_TRIANGLES, MeshShape};
use pssurf::subdivision::{RefinedMesh, SurfaceScheme};
use pssurf::surface::Surface;

/// The subdivision dialog.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct SubdivisionPanel {
    /// Subdivision steps per click (UPS surfaces).
    pub times: usize,
    /// The scheme for meshes, by its name (loop, sqrt3, butterfly).
    pub scheme: String,
    /// The steps from the control mesh (meshes).
    pub mesh_times: u32,
    /// Why the last mesh subdivision failed (cleared by the next attempt).
    #[serde(skip)]
    pub error: Option<String>,
}

impl Default for SubdivisionPanel {
    fn default() -> Self {
        SubdivisionPanel {
            times: 1,
            scheme: SurfaceScheme::Loop.name().into(),
            mesh_times: 2,
            error: None,
        }
    }
}

impl SubdivisionPanel {
    /// The mesh part: scheme, steps, the counts after them, Apply and Reset.
    fn mesh_ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>, m: &MeshShape) {
        let c = &m.recipe.control;
        ui.label(format!(
            "control mesh: {} vertices, {} triangles",
            c.positions.len(),
            c.triangles.len()
        ));
        let mut scheme = SurfaceScheme::parse(&self.scheme).unwrap_or(SurfaceScheme::Loop);
        ui.horizontal(|ui| {
            ui.label("scheme");
            egui::ComboBox::from_id_salt("mesh scheme")
                .selected_text(scheme_label(scheme))
                .show_ui(ui, |ui| {
                    for s in SurfaceScheme::ALL {
                        ui.selectable_value(&mut scheme, s, scheme_label(s));
                    }
                });
            ui.label("steps");
            ui.add(egui::DragValue::new(&mut self.mesh_times).range(0..=8));
        });
        self.scheme = scheme.name().into();
        let after = scheme.triangles_after(c.triangles.len(), self.mesh_times);
        let too_many = after > MAX_MESH_TRIANGLES as f64;
        if too_many {
            ui.colored_label(
                egui::Color32::DARK_RED,
                format!(
                    "{} step(s) would make about {} triangles, more than {} million.",
                    self.mesh_times,
                    crate::fields::compact(after),
                    MAX_MESH_TRIANGLES / 1_000_000
                ),
            );
        } else {
            ui.weak(format!("{} triangles after", crate::fields::compact(after)));
        }
        let same = m.recipe.scheme == scheme && m.recipe.times == self.mesh_times;
        ui.horizontal(|ui| {
            let apply = ui
                .add_enabled(!too_many && !same, egui::Button::new("Subdivide"))
                .on_hover_text("Refine the control mesh by the scheme, the chosen number of steps");
            if apply.clicked() {
                let recipe = RefinedMesh {
                    control: c.clone(),
                    scheme,
                    times: self.mesh_times,
                };
                self.replace(cx, recipe);
            }
            let reset = ui
                .add_enabled(m.recipe.times > 0, egui::Button::new("Control mesh"))
                .on_hover_text("Show the control mesh itself (no steps)");
            if reset.clicked() {
                self.replace(cx, RefinedMesh::new(c.clone()));
            }
        });
        if let Some(e) = &self.error {
            ui.colored_label(egui::Color32::DARK_RED, e);
        }
    }

    /// Asks to show `recipe` on the selected mesh (one undo step), or says why it cannot.
    /// A large subdivision (more than `BACKGROUND_TRIANGLES`) runs on another thread and
    /// reports a failure in the status line.
    fn replace(&mut self, cx: &mut ViewContext<'_>, recipe: RefinedMesh) {
        let Some(object) = cx.object().map(|o| o.id) else {
            return;
        };
        self.error = None;
        let (scheme, times) = (recipe.scheme, recipe.times);
        let after = recipe.triangles_after();
        if after > crate::cache::BACKGROUND_TRIANGLES {
            let what = format!(
                "subdividing: {} × {}, about {} triangles",
                times,
                scheme.name(),
                crate::fields::compact(after)
            );
            let work = move || mesh_command(object, recipe).unwrap_or_else(Command::Status);
            cx.emit(Command::InBackground {
                what,
                work: crate::command::BackgroundWork::new(work),
            });
            return;
        }
        match mesh_command(object, recipe) {
            Ok(command) => cx.emit(command),
            Err(e) => self.error = Some(e),
        }
    }
}

/// The command that shows `recipe` on mesh object `object`, or why it cannot be made.
fn mesh_command(id: u64, recipe: RefinedMesh) -> Result<Command, String> {
    let (scheme, times) = (recipe.scheme, recipe.times);
    let mesh = MeshShape::new(recipe).map_err(|e| format!("cannot subdivide: {e}"))?;
    let status = if times == 0 {
        "the control mesh".to_string()
    } else {
        format!(
            "{} × {}: {} triangles",
            times,
            scheme.name(),
            mesh.refined.triangles.len()
        )
    };
    Ok(Command::ReplaceMesh {
        id,
        what: "subdivide mesh",
        mesh: Arc::new(mesh),
        status,
    })
}

/// A scheme's name in the interface.
fn scheme_label(s: SurfaceScheme) -> &'static str {
    match s {
        SurfaceScheme::Loop => "Loop",
        SurfaceScheme::Sqrt3 => "√3 (Kobbelt)",
        SurfaceScheme::Butterfly => "butterfly",
    }
}

impl Panel for SubdivisionPanel {
    fn title(&self) -> &'static str {
        "Subdivision"
    }

    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        if let Some(m) = cx.mesh() {
            return self.mesh_ui(ui, cx, m);
        }
        let Some(u) = cx.uniform() else {
            needs_ups(ui);
            ui.weak("A mesh (File, Import mesh…) is refined by Loop, √3 or butterfly here.");
            return;
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
            let s = Surface::try_from(s)
                .expect("subdivision averages the control values of a usable surface");
            replace_selected(cx, "subdivide", s, status);
        }
    }

    fn settings(&self) -> Option<serde_json::Value> {
        save_settings(self)
    }

    fn restore(&mut self, settings: &serde_json::Value) {
        if let Some(s) = load_settings::<SubdivisionPanel>(settings) {
            self.times = s.times.clamp(1, 4);
            self.mesh_times = s.mesh_times.min(8);
            if SurfaceScheme::parse(&s.scheme).is_some() {
                self.scheme = s.scheme;
            }
        }
    }
}
