//! What the running application holds besides the document and the view state: the drawable
//! geometry, the probe's results and the GPU. None of it is saved; all of it can be rebuilt
//! from the document and the view state.

use eframe::egui_wgpu::RenderState;

use crate::cache::GeometryCache;
use crate::probe::ProbeState;

/// The application's rebuildable resources.
#[derive(Default)]
pub struct Runtime {
    /// The drawable geometry of the visible objects.
    pub cache: GeometryCache,
    /// The probe and its lines.
    pub probe: ProbeState,
    /// The wgpu device and queue, when the 3D view's GPU resources are installed (the view
    /// and the picture export need them).
    pub gpu: Option<RenderState>,
}
