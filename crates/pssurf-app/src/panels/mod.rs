//! Algorithm panels: each is a self-contained dialog that edits the document through
//! [`PanelContext`]. New capabilities (curves, editing by curvature, hole filling, NURBS)
//! plug in by implementing [`Panel`] and adding one line to [`default_panels`].

mod noise;
mod subdivision;
mod wavelet;

pub use noise::NoisePanel;
pub use subdivision::SubdivisionPanel;
pub use wavelet::WaveletPanel;

use crate::document::Document;
use crate::scene::SceneObject;
use pssurf::surface::UpsSurface;

/// What a panel may read and change.
pub struct PanelContext<'a> {
    /// The document (edits go through `Document::edit` so they can be undone).
    pub doc: &'a mut Document,
    /// The selected object, if any.
    pub selected: Option<usize>,
    /// A message for the status bar.
    pub status: &'a mut String,
}

impl PanelContext<'_> {
    /// The selected object.
    pub fn object(&self) -> Option<&SceneObject> {
        self.selected.and_then(|i| self.doc.scene.objects.get(i))
    }

    /// The selected object's uniform (UPS) form, if it has one.
    pub fn uniform(&self) -> Option<&UpsSurface> {
        self.object().and_then(|o| o.surface.uniform())
    }

    /// Replaces the selected object's surface as one undoable edit named `what`.
    pub fn replace_surface(&mut self, what: &str, surface: pssurf::surface::Surface) {
        let Some(i) = self.selected else { return };
        let _ = self.doc.edit::<()>(what, |scene| {
            let o = &mut scene.objects[i];
            o.surface = surface;
            o.touch();
            Ok(())
        });
    }
}

/// A dialog of the application.
pub trait Panel {
    /// The title shown on the panel's header.
    fn title(&self) -> &'static str;
    /// Draws the panel and applies what the user asks for.
    fn ui(&mut self, ui: &mut egui::Ui, cx: &mut PanelContext<'_>);
}

/// The panels of this build, in display order.
pub fn default_panels() -> Vec<Box<dyn Panel>> {
    vec![
        Box::new(SubdivisionPanel::default()),
        Box::new(WaveletPanel::default()),
        Box::new(NoisePanel::default()),
    ]
}

/// A hint shown when a panel needs a UPS surface.
pub fn needs_ups(ui: &mut egui::Ui) {
    ui.weak("Select a UPS surface (uniform triangulation) to use this.");
}
