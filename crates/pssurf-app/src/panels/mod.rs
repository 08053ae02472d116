//! Algorithm panels: each is a self-contained dialog with its own settings that reads the
//! application through a [`ViewContext`] and asks for changes with commands (a new surface is
//! [`Command::ReplaceSurface`], one undo step). New capabilities (curves, editing by
//! curvature, hole filling, NURBS) plug in by implementing [`Panel`] and adding one line to
//! [`default_panels`].

mod curves;
mod edit;
mod fairing;
mod holes;
mod noise;
mod nurbs;
mod subdivision;
mod wavelet;

pub use curves::CurvesPanel;
pub use edit::EditPanel;
pub use fairing::FairingPanel;
pub use holes::HolesPanel;
pub use noise::NoisePanel;
pub use nurbs::NurbsPanel;
pub use subdivision::SubdivisionPanel;
pub use wavelet::WaveletPanel;

use pssurf::surface::Surface;
use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::command::{Command, ViewContext};

/// A dialog of the application.
pub trait Panel {
    /// The title shown on the panel's header (also the key of its saved settings).
    fn title(&self) -> &'static str;
    /// Draws the panel; what the user asks for goes to `cx` as commands.
    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut ViewContext<'_>);
    /// The settings worth keeping to the next session, as JSON (none by default).
    fn settings(&self) -> Option<serde_json::Value> {
        None
    }
    /// Takes back settings saved by [`Panel::settings`]; values that do not fit are ignored.
    fn restore(&mut self, _settings: &serde_json::Value) {}
}

/// The panels of this build, in display order.
pub fn default_panels() -> Vec<Box<dyn Panel>> {
    vec![
        Box::new(SubdivisionPanel::default()),
        Box::new(WaveletPanel::default()),
        Box::new(NoisePanel::default()),
        Box::new(CurvesPanel::default()),
        Box::new(EditPanel::default()),
        Box::new(FairingPanel::default()),
        Box::new(HolesPanel::default()),
        Box::new(NurbsPanel::default()),
    ]
}

/// A hint shown when a panel needs a UPS surface.
pub fn needs_ups(ui: &mut egui::Ui) {
    ui.weak("Select a UPS surface (uniform triangulation) to use this.");
}

/// Asks to replace the selected object's surface as one undoable edit named `what`.
pub fn replace_selected(
    cx: &mut ViewContext<'_>,
    what: &'static str,
    surface: Surface,
    status: String,
) {
    if let Some(object) = cx.selected() {
        cx.emit(Command::ReplaceSurface {
            object,
            what,
            surface: Box::new(surface),
            status,
        });
    }
}

/// A panel's settings as JSON.
fn save_settings<T: Serialize>(settings: &T) -> Option<serde_json::Value> {
    serde_json::to_value(settings).ok()
}

/// Settings read back from JSON, if they fit `T`.
fn load_settings<T: DeserializeOwned>(value: &serde_json::Value) -> Option<T> {
    serde_json::from_value(value.clone()).ok()
}
