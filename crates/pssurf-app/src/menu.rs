//! The menu bar: File (new, open, recent files, save, save as, add a file, recover the
//! autosave, export, quit), New (surfaces), Edit (undo, redo) and View (framing, flat
//! shading). Every item is a command.

use crate::command::{Command, ExportKind, FrameTarget, Shape, ViewContext};
use crate::files::Purpose;
use crate::scene::FileKind;

/// The menu bar.
#[derive(Debug, Default)]
pub struct MenuBar;

impl MenuBar {
    /// Draws the menu bar; chosen items go to `cx` as commands.
    pub fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| file_menu(ui, cx));
            ui.menu_button("New", |ui| new_menu(ui, cx));
            ui.menu_button("Edit", |ui| edit_menu(ui, cx));
            ui.menu_button("View", |ui| view_menu(ui, cx));
        });
    }
}

/// A menu item with its shortcut; emits `command` when clicked.
fn item(ui: &mut egui::Ui, cx: &mut ViewContext<'_>, text: &str, keys: &str, command: Command) {
    if ui
        .add(egui::Button::new(text).shortcut_text(keys))
        .clicked()
    {
        cx.emit(command);
    }
}

fn file_menu(ui: &mut egui::Ui, cx: &mut ViewContext<'_>) {
    item(ui, cx, "New scene", "Ctrl+N", Command::New);
    item(ui, cx, "Open…", "Ctrl+O", Command::Choose(Purpose::Open));
    ui.menu_button("Open Recent", |ui| {
        let recent: Vec<_> = cx.view.recent.iter().filter(|p| p.exists()).collect();
        if recent.is_empty() {
            ui.weak("no recent files");
        }
        for p in recent {
            let name = crate::files::file_name(p);
            if ui
                .button(name)
                .on_hover_text(p.display().to_string())
                .clicked()
            {
                cx.emit(Command::Open(p.clone()));
            }
        }
    });
    ui.separator();
    let kind = cx.doc.kind.name();
    let save = egui::Button::new("Save").shortcut_text("Ctrl+S");
    if ui
        .add(save)
        .on_hover_text(format!("Save to the document's file (a {kind})"))
        .clicked()
    {
        cx.emit(Command::Save);
    }
    let surface_problem = cx.doc.scene.surface_file_problem();
    let as_surface = ui
        .add_enabled(
            surface_problem.is_none(),
            egui::Button::new("Save As Surface…").shortcut_text("Ctrl+Shift+S"),
        )
        .on_hover_text("One surface in the library's format, which `pssurf` reads")
        .on_disabled_hover_text(surface_problem.unwrap_or_default());
    if as_surface.clicked() {
        cx.emit(Command::Choose(Purpose::SaveAs(FileKind::Surface)));
    }
    if ui
        .button("Save As Scene…")
        .on_hover_text("All objects with their names, materials, visibility and placements")
        .clicked()
    {
        cx.emit(Command::Choose(Purpose::SaveAs(FileKind::Scene)));
    }
    ui.separator();
    if ui
        .button("Add From File…")
        .on_hover_text("Add the objects of a surface or scene file beside the others")
        .clicked()
    {
        cx.emit(Command::Choose(Purpose::Add));
    }
    if ui
        .button("Import IGES…")
        .on_hover_text(
            "Add the B-spline surfaces of an IGES file (in millimetres; trimming is not applied)",
        )
        .clicked()
    {
        cx.emit(Command::Choose(Purpose::Import));
    }
    if ui
        .button("Import points (CSV)…")
        .on_hover_text(
            "Add the PS-spline interpolating scattered points x, y, z (like pssurf fit, with estimated gradients)",
        )
        .clicked()
    {
        cx.emit(Command::Choose(Purpose::ImportPoints));
    }
    if ui
        .button("Import mesh (OBJ, PLY, STL)…")
        .on_hover_text(
            "Add a triangle mesh for reference: shaded, zebra and discrete curvature views, and the subdivision schemes (Loop, √3, butterfly) in the Subdivision panel",
        )
        .clicked()
    {
        cx.emit(Command::Choose(Purpose::ImportMesh));
    }
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
        .on_hover_text("PLY, OBJ, STL, glTF or VTK, with curvature fields and colours")
        .clicked()
    {
        cx.emit(Command::OpenExport(ExportKind::Mesh));
    }
    if ui
        .add_enabled(
            cx.runtime.gpu.is_some(),
            egui::Button::new("Export picture…"),
        )
        .on_hover_text("The 3D view and its legend as a PNG picture of any size")
        .clicked()
    {
        cx.emit(Command::OpenExport(ExportKind::Picture));
    }
    ui.separator();
    item(ui, cx, "Quit", "Ctrl+Q", Command::Quit);
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
        (
            "Cylinder…",
            "A closed cylinder of 8 exact NURPS patches",
            Shape::Cylinder,
        ),
        ("Cone…", "A cone of 6 exact NURPS patches", Shape::Cone),
        (
            "Sphere…",
            "A sphere of exact NURPS patches with two thin open bands",
            Shape::Sphere,
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
