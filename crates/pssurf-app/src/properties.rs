//! The selected object's properties (name, group, material, placement) and the numeric
//! editor of the selected vertex's control points (like the thesis' Figure 6.12).

use pssurf::surface::PiecewiseSurface;

use crate::command::{Command, ObjectEdit, ViewContext};
use crate::edit::{self, VertexControl};
use crate::fields::{self, Rule};
use crate::scene::{Material, SceneObject, Shape, Transform};

/// Values typed into the control-point editor, kept while the edit they asked for has not
/// changed the object (a refused edit leaves them in the fields to correct).
#[derive(Clone, Debug, PartialEq)]
struct Typed {
    object: usize,
    vertex: usize,
    /// The object's revision when they were typed.
    revision: u64,
    control: VertexControl,
}

/// The properties view.
#[derive(Debug, Default)]
pub struct Properties {
    typed: Option<Typed>,
}

impl Properties {
    /// Draws the properties of the selection; changes go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let Some(i) = cx.selected() else {
            ui.weak("Select an object.");
            return;
        };
        let o = &cx.doc.scene.objects[i];
        ui.heading("Object");
        let mut refused = Vec::new();
        for edit in object_fields(ui, o, &mut refused) {
            cx.emit(Command::EditObject { object: i, edit });
        }
        for message in refused {
            cx.status(message);
        }
        ui.separator();
        self.vertex_ui(ui, cx, i);
    }

    /// The numeric editor of the selected vertex's control points.
    fn vertex_ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>, i: usize) {
        ui.heading("Control triangle");
        let o = &cx.doc.scene.objects[i];
        let Some(surface) = o.surface() else {
            ui.weak("A mesh object has no control points: subdivide it in the Subdivision panel.");
            return;
        };
        let Some(v) = cx
            .doc
            .selection
            .vertex
            .filter(|&v| v < edit::vertex_count(surface))
        else {
            ui.weak("Click a PS-triangle in the domain view to select its vertex.");
            return;
        };
        let current = edit::vertex_control(surface, v);
        // Keep the user's values while the same vertex stays selected and unchanged.
        self.typed = self
            .typed
            .take()
            .filter(|t| t.object == i && t.vertex == v && t.revision == o.revision);
        let mut c = self
            .typed
            .as_ref()
            .map_or(current.clone(), |t| t.control.clone());
        ui.label(format!("vertex {v}"));
        let mut refused = Vec::new();
        let changed = control_grid(ui, &mut c, &mut refused);
        for message in refused {
            cx.status(message);
        }
        if c.functional {
            ui.weak("A functional surface: only the heights of its control points can change.");
        }
        crate::shape_tools::ui(ui, cx, i, v, &current);
        if changed && c != current {
            self.typed = Some(Typed {
                object: i,
                vertex: v,
                revision: o.revision,
                control: c.clone(),
            });
            cx.emit(Command::SetVertex {
                object: i,
                vertex: v,
                control: c,
            });
        }
    }
}

/// The name, group, material and placement fields; returns what the user changed.
fn object_fields(ui: &mut egui::Ui, o: &SceneObject, refused: &mut Vec<String>) -> Vec<ObjectEdit> {
    let (mut name, mut group, mut material) = (o.name.clone(), o.group.clone(), o.material);
    let mut t = o.transform;
    ui.horizontal(|ui| {
        let label = ui.label("name");
        ui.text_edit_singleline(&mut name).labelled_by(label.id);
    });
    ui.horizontal(|ui| {
        let label = ui.label("group");
        ui.text_edit_singleline(&mut group)
            .labelled_by(label.id)
            .on_hover_text("Objects with the same group name are listed together");
    });
    egui::ComboBox::from_label("material")
        .selected_text(material.name())
        .show_ui(ui, |ui| {
            for m in Material::ALL {
                ui.selectable_value(&mut material, m, m.name());
            }
        });
    ui.label(describe_shape(o));
    transform_grid(ui, &mut t, refused);
    let mut edits = Vec::new();
    if name != o.name {
        edits.push(ObjectEdit::Rename(name));
    }
    if group != o.group {
        edits.push(ObjectEdit::Group(group.trim().to_string()));
    }
    if material != o.material {
        edits.push(ObjectEdit::Material(material));
    }
    if t != o.transform {
        edits.push(ObjectEdit::Transform(t));
    }
    edits
}

/// The move / turn / scale fields of a placement; a refused value's message goes to
/// `refused`.
fn transform_grid(ui: &mut egui::Ui, t: &mut Transform, refused: &mut Vec<String>) {
    egui::Grid::new("transform")
        .num_columns(4)
        .spacing([4.0, 4.0])
        .show(ui, |ui| {
            for (row, values, rule, speed) in [
                ("move", &mut t.translate, Rule::Coordinate, 0.01),
                (
                    "turn",
                    &mut t.rotate_deg,
                    Rule::Within(-36_000.0, 36_000.0),
                    0.5,
                ),
            ] {
                ui.label(row);
                for (x, axis) in values.iter_mut().zip(["x", "y", "z"]) {
                    let name = format!("{row} {axis}");
                    refused.extend(fields::number(ui, &name, x, rule, speed).refusal());
                }
                ui.end_row();
            }
            let rule = Rule::Within(1e-6, 1e6);
            refused.extend(fields::labelled(ui, "scale", &mut t.scale, rule, 0.01).refusal());
            ui.end_row();
        });
}

/// The grid of control points (x, y, z and the weight of a rational surface); returns
/// whether a field changed, and puts a refused value's message in `refused`.
fn control_grid(ui: &mut egui::Ui, c: &mut VertexControl, refused: &mut Vec<String>) -> bool {
    let mut changed = false;
    egui::Grid::new("control")
        .num_columns(5)
        .spacing([4.0, 4.0])
        .striped(true)
        .show(ui, |ui| {
            ui.strong("");
            let weight = if c.weights.is_some() { "weight" } else { "" };
            for h in ["x", "y", "z", weight] {
                ui.strong(h);
            }
            ui.end_row();
            for j in 0..c.points.len() {
                ui.label(format!("Q{}", j + 1));
                for k in 0..3 {
                    let enabled = !c.functional || k == 2;
                    let name = format!("Q{} {}", j + 1, ["x", "y", "z"][k]);
                    let x = &mut c.points[j][k];
                    let outcome =
                        fields::number_enabled(ui, enabled, &name, x, Rule::Coordinate, 0.005);
                    changed |= outcome.changed();
                    refused.extend(outcome.refusal());
                }
                if let Some(w) = &mut c.weights {
                    let name = format!("Q{} weight", j + 1);
                    let outcome = fields::number(ui, &name, &mut w[j], Rule::Weight, 0.01);
                    changed |= outcome.changed();
                    refused.extend(outcome.refusal());
                }
                ui.end_row();
            }
        });
    changed
}

/// One line on what an object is: its kind and size.
fn describe_shape(o: &SceneObject) -> String {
    match &o.shape {
        Shape::Surface(s) => {
            let triangles = s
                .ps_basis()
                .map_or(s.piece_count(), |b| b.triangulation().triangle_count());
            format!(
                "{} surface, {} vertices, {triangles} triangles",
                s.kind().name(),
                edit::vertex_count(s),
            )
        }
        Shape::Mesh(m) => {
            let (c, r) = (&m.recipe.control, &m.refined);
            let refined = if m.recipe.times == 0 {
                String::new()
            } else {
                format!(
                    "; after {} × {}: {} vertices, {} triangles",
                    m.recipe.times,
                    m.recipe.scheme.name(),
                    r.positions.len(),
                    r.triangles.len()
                )
            };
            format!(
                "mesh, {} vertices, {} triangles{refined}",
                c.positions.len(),
                c.triangles.len()
            )
        }
    }
}
