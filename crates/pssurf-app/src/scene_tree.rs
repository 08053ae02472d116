//! The scene tree: objects with visibility, selection, rename and delete.

use crate::app::{App, Selection};

/// Draws the scene tree.
pub fn ui(app: &mut App, ui: &mut egui::Ui) {
    ui.heading("Scene");
    let mut delete = None;
    let mut toggle = None;
    for (i, o) in app.doc.scene.objects.iter().enumerate() {
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
                toggle = Some(i);
            }
            let selected = app.selection.object == Some(i);
            let label = format!("{} ({})", o.name, o.surface.kind_name());
            if ui
                .selectable_label(selected, label)
                .on_hover_text("Select")
                .clicked()
                && !selected
            {
                app.selection = Selection {
                    object: Some(i),
                    vertex: None,
                };
                app.vertex_edit = None;
            }
            if ui
                .small_button("delete")
                .on_hover_text("Delete the object")
                .clicked()
            {
                delete = Some(i);
            }
        });
    }
    if app.doc.scene.objects.is_empty() {
        ui.weak("No objects: open a file from the File menu.");
    }
    if let Some(i) = toggle {
        let _ = app.doc.edit::<()>("show/hide", |s| {
            s.objects[i].visible = !s.objects[i].visible;
            Ok(())
        });
    }
    if let Some(i) = delete {
        let name = app.doc.scene.objects[i].name.clone();
        let _ = app.doc.edit::<()>("delete", |s| {
            s.objects.remove(i);
            Ok(())
        });
        app.selection = Selection::default();
        app.vertex_edit = None;
        app.status = format!("deleted {name}");
    }
}
