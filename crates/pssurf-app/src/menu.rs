//! The menu bar: File (open, save, recover the autosave, export), New (surfaces), Edit (undo,
//! redo) and View (framing, flat shading). Every item is a command.

use std::path::PathBuf;

use crate::command::{Command, ExportKind, FrameTarget, Shape, ViewContext};

/// The menu bar and the path typed in its File menu.
#[derive(Debug, Default)]
pub struct MenuBar {
    /// The path typed in the File menu.
    pub path_text: String,
}

impl MenuBar {
    /// Draws the menu bar; chosen items go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| self.file_menu(ui, cx));
            ui.menu_button("New", |ui| new_menu(ui, cx));
            ui.menu_button("Edit", |ui| edit_menu(ui, cx));
            ui.menu_button("View", |ui| view_menu(ui, cx));
        });
    }

    fn file_menu(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        let label = ui.label("File (scene or surface .json):");
        ui.text_edit_singleline(&mut self.path_text)
            .labelled_by(label.id)
            .on_hover_text("Type a path, then Open or Save");
        ui.horizontal(|ui| {
            let path = PathBuf::from(self.path_text.trim());
            if ui.button("Open").clicked() {
                cx.emit(Command::Open(path.clone()));
            }
            if ui.button("Save").clicked() {
                cx.emit(Command::Save(path));
            }
        });
        if let Some(p) = cx.autosave.filter(|p| p.exists())
            && ui
                .button("Recover autosave")
                .on_hover_text(p.display().to_string())
                .clicked()
        {
            cx.emit(Command::RecoverAutosave);
        }
        ui.separator();
        if ui
            .button("Export mesh…")
            .on_hover_text("PLY, OBJ, STL, glTF or VTK, with curvature fields")
            .clicked()
        {
            cx.emit(Command::OpenExport(ExportKind::Mesh));
        }
        if ui
            .add_enabled(
                cx.runtime.gpu.is_some(),
                egui::Button::new("Export picture…"),
            )
            .on_hover_text("The 3D view as a PNG picture of any size")
            .clicked()
        {
            cx.emit(Command::OpenExport(ExportKind::Picture));
        }
    }
}

fn new_menu(ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
    for (label, tip, shape) in [
        (
            "UPS patch…",
            "A 3–6-sided UPS patch interpolating a height formula",
            Shape::Formula,
        ),
        (
            "Quadric…",
            "z = a x² + b xy + c y², reproduced exactly",
            Shape::Quadric,
        ),
    ] {
        if ui.button(label).on_hover_text(tip).clicked() {
            cx.emit(Command::OpenNewSurface(shape));
        }
    }
}

fn edit_menu(ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
    let doc = cx.doc;
    let items = [
        ("Undo", doc.undo_name(), "Ctrl+Z", Command::Undo),
        ("Redo", doc.redo_name(), "Ctrl+Shift+Z", Command::Redo),
    ];
    for (verb, name, shortcut, command) in items {
        let text = name.map_or(verb.to_string(), |n| format!("{verb} {n}"));
        let button = egui::Button::new(text).shortcut_text(shortcut);
        if ui.add_enabled(name.is_some(), button).clicked() {
            cx.emit(command);
        }
    }
}

fn view_menu(ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
    if ui.button("Frame all (F)").clicked() {
        cx.emit(Command::Frame(FrameTarget::All));
    }
    if ui.button("Frame selection (Shift+F)").clicked() {
        cx.emit(Command::Frame(FrameTarget::Selection));
    }
    let mut display = cx.view.display.clone();
    if ui.checkbox(&mut display.flat, "Flat shading").changed() {
        cx.emit(Command::SetDisplay(display));
    }
}
