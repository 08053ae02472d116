//! The scene tree: objects, grouped by their group name, with visibility (per object and per
//! group), selection, rename (in the properties) and delete.

use crate::command::{Command, ViewContext};
use crate::document::{Document, Selection};

/// What the user asked for in the tree this frame.
#[derive(Default)]
struct Actions {
    delete: Option<usize>,
    toggle: Vec<usize>,
    select: Option<usize>,
}

/// The scene tree view.
#[derive(Debug, Default)]
pub struct SceneTree;

impl SceneTree {
    /// Draws the tree; selection, visibility and deletion go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let actions = tree(cx.doc, ui);
        emit(cx, actions);
    }
}

/// Draws the tree and collects what the user asked for.
fn tree(doc: &Document, ui: &mut egui::Ui) -> Actions {
    ui.heading("Scene");
    let mut actions = Actions::default();
    let objects = &doc.scene.objects;
    let mut groups: Vec<&str> = Vec::new();
    for o in objects {
        if !o.group.is_empty() && !groups.contains(&o.group.as_str()) {
            groups.push(&o.group);
        }
    }
    for i in (0..objects.len()).filter(|&i| objects[i].group.is_empty()) {
        object_row(doc, ui, i, &mut actions);
    }
    for g in groups {
        let members: Vec<usize> = (0..objects.len())
            .filter(|&i| objects[i].group == g)
            .collect();
        ui.horizontal(|ui| {
            let mut visible = members.iter().any(|&i| objects[i].visible);
            let r = ui
                .checkbox(&mut visible, "")
                .on_hover_text("Show or hide the group");
            r.widget_info(|| {
                egui::WidgetInfo::selected(
                    egui::accesskit::Role::CheckBox,
                    true,
                    visible,
                    format!("visible group {g}"),
                )
            });
            if r.changed() {
                actions.toggle = members
                    .iter()
                    .copied()
                    .filter(|&i| objects[i].visible != visible)
                    .collect();
            }
            egui::CollapsingHeader::new(format!("group {g}"))
                .default_open(true)
                .show(ui, |ui| {
                    for &i in &members {
                        object_row(doc, ui, i, &mut actions);
                    }
                });
        });
    }
    if objects.is_empty() {
        ui.weak("No objects: open a file from the File menu, or make one in the New menu.");
    }
    actions
}

fn object_row(doc: &Document, ui: &mut egui::Ui, i: usize, actions: &mut Actions) {
    let o = &doc.scene.objects[i];
    ui.horizontal(|ui| {
        let mut visible = o.visible;
        let r = ui.checkbox(&mut visible, "").on_hover_text("Show or hide");
        r.widget_info(|| {
            egui::WidgetInfo::selected(
                egui::accesskit::Role::CheckBox,
                true,
                visible,
                format!("visible {}", o.name),
            )
        });
        if r.changed() {
            actions.toggle = vec![i];
        }
        let selected = doc.selection.object == Some(i);
        let label = format!("{} ({})", o.name, o.kind_name());
        if ui
            .selectable_label(selected, label)
            .on_hover_text("Select")
            .clicked()
            && !selected
        {
            actions.select = Some(i);
        }
        if ui
            .small_button("delete")
            .on_hover_text("Delete the object")
            .clicked()
        {
            actions.delete = Some(i);
        }
    });
}

fn emit(cx: &mut ViewContext<'_>, actions: Actions) {
    if let Some(i) = actions.select {
        cx.emit(Command::Select(Selection::object(i)));
    }
    if !actions.toggle.is_empty() {
        cx.emit(Command::ToggleVisible(actions.toggle));
    }
    if let Some(i) = actions.delete {
        cx.emit(Command::Delete(i));
    }
}
