//! Files that behave like files: an in-app file chooser (the `egui_file` dialog, which also
//! runs in the headless test harness), the list of recent files, and the question asked
//! before unsaved changes would be lost (on New, Open, and closing the window).
//!
//! The rules the application follows (`App::request` and `App::save_to` carry them out):
//! a document keeps the kind of its file, so a surface opened from a surface file is saved
//! as a surface file until the user saves a scene; Save writes where the document came
//! from, or asks where (Save As) when it has no file yet or its file cannot hold it (a
//! surface file holds one object in its own coordinates); anything that would replace a
//! modified document first asks to save, discard or cancel.

use std::path::{Path, PathBuf};

use egui_file::FileDialog;

use crate::command::{Command, ViewContext};
use crate::scene::FileKind;

/// What the user wants to do that replaces the document (and so may need an answer about
/// unsaved changes first).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Intent {
    /// Open this file.
    Open(PathBuf),
    /// Start an empty scene.
    New,
    /// Close the application.
    Quit,
}

impl Intent {
    /// The question's ending: "… before opening x.json?".
    fn phrase(&self) -> String {
        match self {
            Intent::Open(p) => format!("before opening {}", file_name(p)),
            Intent::New => "before starting a new scene".into(),
            Intent::Quit => "before closing".into(),
        }
    }
}

/// The answer to the unsaved-changes question.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// Save first (asking where when the document has no file), then go on.
    Save,
    /// Go on without saving.
    Discard,
    /// Do nothing.
    Cancel,
}

/// What a chosen file is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Purpose {
    /// Open it as the document.
    Open,
    /// Add its objects to the scene.
    Add,
    /// Import an IGES file's surfaces into the scene.
    Import,
    /// Import scattered points (CSV x, y, z) as the PS-spline interpolating them.
    ImportPoints,
    /// Import a triangle mesh (OBJ, PLY, STL) for reference and subdivision.
    ImportMesh,
    /// Save the document to it as a file of this kind.
    SaveAs(FileKind),
    /// Use it as the Export dialog's file.
    ExportTo,
}

impl Purpose {
    fn title(self) -> &'static str {
        match self {
            Purpose::Open => "Open a surface or scene",
            Purpose::Add => "Add the objects of a file",
            Purpose::Import => "Import the surfaces of an IGES file",
            Purpose::ImportPoints => "Import points (CSV x, y, z) and fit a surface",
            Purpose::ImportMesh => "Import a triangle mesh (OBJ, PLY, STL)",
            Purpose::SaveAs(FileKind::Surface) => "Save as a surface file",
            Purpose::SaveAs(FileKind::Scene) => "Save as a scene file",
            Purpose::ExportTo => "Export to",
        }
    }

    fn saves(self) -> bool {
        matches!(self, Purpose::SaveAs(_) | Purpose::ExportTo)
    }

    /// The command for a chosen file.
    fn command(self, path: PathBuf) -> Command {
        match self {
            Purpose::Open => Command::Open(path),
            Purpose::Add | Purpose::Import | Purpose::ImportPoints | Purpose::ImportMesh => {
                Command::AddFile(path)
            }
            Purpose::SaveAs(kind) => Command::SaveTo { path, kind },
            Purpose::ExportTo => Command::SetExportPath(path),
        }
    }
}

/// The file name of a path for messages and titles (the whole path when it has none).
pub fn file_name(p: &Path) -> String {
    p.file_name()
        .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
}

/// The most recent files remembered.
pub const RECENT: usize = 10;

/// Puts `path` first in a recent-files list (once, at most [`RECENT`] entries).
pub fn remember(recent: &mut Vec<PathBuf>, path: &Path) {
    let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    recent.retain(|p| *p != path);
    recent.insert(0, path);
    recent.truncate(RECENT);
}

/// The in-app file chooser and the unsaved-changes question.
#[derive(Default)]
pub struct Files {
    /// The open chooser and what it is for.
    chooser: Option<(Purpose, FileDialog)>,
    /// The folder the chooser starts in when the document has none (the last one used).
    pub folder: Option<PathBuf>,
}

impl std::fmt::Debug for Files {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Files")
            .field("chooser", &self.chooser.as_ref().map(|(p, _)| p))
            .field("folder", &self.folder)
            .finish()
    }
}

impl Files {
    /// Opens the chooser for `purpose`, in `folder` (else the last folder used, else the
    /// working directory), with `name` proposed when saving.
    pub fn choose(&mut self, purpose: Purpose, folder: Option<&Path>, name: &str) {
        let mut dialog = if purpose.saves() {
            FileDialog::save_file().default_filename(name)
        } else {
            FileDialog::open_file()
        }
        .title(purpose.title())
        .show_rename(false)
        .id(egui::Id::unique("file chooser"));
        if purpose != Purpose::ExportTo {
            dialog = dialog.show_files_filter(Box::new(move |p: &Path| {
                p.extension().is_some_and(|e| match purpose {
                    Purpose::Import => crate::scene::is_iges_path(p),
                    Purpose::ImportPoints => crate::scene::is_points_path(p),
                    Purpose::ImportMesh => crate::scene::is_mesh_path(p),
                    _ => {
                        e.eq_ignore_ascii_case("json")
                            || e.eq_ignore_ascii_case(pssurf::io::BINARY_EXTENSION)
                            || crate::scene::is_import_path(p)
                    }
                })
            }));
        }
        let start = folder
            .map(Path::to_path_buf)
            .or_else(|| self.folder.clone())
            .filter(|f| f.is_dir());
        if let Some(start) = start {
            dialog = dialog.initial_path(start);
        }
        dialog.open();
        self.chooser = Some((purpose, dialog));
    }

    /// What the open chooser is for, if one is open.
    pub fn choosing(&self) -> Option<Purpose> {
        self.chooser.as_ref().map(|(p, _)| *p)
    }

    /// Draws the chooser while it is open; a chosen file goes to `cx` as a command.
    pub fn window(&mut self, ctx: &egui::Context, cx: &mut ViewContext<'_>) {
        let Some((purpose, dialog)) = &mut self.chooser else {
            return;
        };
        let purpose = *purpose;
        let state = dialog.show(ctx).state();
        match state {
            egui_file::State::Open => {}
            egui_file::State::Selected => {
                if let Some(path) = dialog.path().map(Path::to_path_buf) {
                    self.folder = path.parent().map(Path::to_path_buf);
                    cx.emit(purpose.command(path));
                }
                self.chooser = None;
            }
            egui_file::State::Cancelled | egui_file::State::Closed => {
                if purpose.saves() {
                    cx.emit(Command::SaveCancelled);
                }
                self.chooser = None;
            }
        }
    }
}

/// Asks whether to save the document `name` before `intent`; the answer goes to `cx`.
pub fn unsaved_question(
    ctx: &egui::Context,
    name: &str,
    intent: &Intent,
    cx: &mut ViewContext<'_>,
) {
    let modal = egui::Modal::new(egui::Id::unique("unsaved changes")).show(ctx, |ui| {
        ui.set_max_width(420.0);
        ui.heading("Unsaved changes");
        ui.label(format!(
            "“{name}” has changes that are not saved. Save them {}?",
            intent.phrase()
        ));
        ui.add_space(8.0);
        let mut answer = None;
        ui.horizontal(|ui| {
            if ui.button("Save").clicked() {
                answer = Some(Answer::Save);
            }
            if ui.button("Don't save").clicked() {
                answer = Some(Answer::Discard);
            }
            if ui.button("Cancel").clicked() {
                answer = Some(Answer::Cancel);
            }
        });
        answer
    });
    if modal.should_close() {
        cx.emit(Command::Answer(Answer::Cancel));
    } else if let Some(answer) = modal.inner {
        cx.emit(Command::Answer(answer));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recent_files_are_unique_newest_first_and_bounded() {
        let mut recent = Vec::new();
        for k in 0..15 {
            remember(&mut recent, Path::new(&format!("/tmp/f{k}.json")));
        }
        remember(&mut recent, Path::new("/tmp/f7.json"));
        assert_eq!(recent.len(), RECENT);
        assert_eq!(recent[0], Path::new("/tmp/f7.json"));
        assert_eq!(recent[1], Path::new("/tmp/f14.json"));
        assert_eq!(recent.iter().filter(|p| p.ends_with("f7.json")).count(), 1);
    }
}
