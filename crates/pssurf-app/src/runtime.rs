//! What the running application holds besides the document and the view state: the drawable
//! geometry, the probe's results and the GPU. None of it is saved; all of it can be rebuilt
//! from the document and the view state.

use eframe::egui_wgpu::RenderState;

use std::sync::Arc;

use crate::cache::GeometryCache;
use nalgebra::Point2;

use crate::curves::CurvesState;
use crate::gpu::LineSet;
use crate::probe::ProbeState;

/// The region of an edit by curvature, drawn in the domain view while its panel is open.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionMark {
    /// The object's identity (see `SceneObject::id`).
    pub id: u64,
    /// The centre (the probe's parameters).
    pub uv: Point2<f64>,
    /// The radius in parameter units.
    pub radius: f64,
    /// The frame (egui pass) that set it: the domain view draws marks of the last two passes
    /// only, so that the mark goes away with its panel.
    pub pass: u64,
}

/// The application's rebuildable resources.
#[derive(Default)]
pub struct Runtime {
    /// The drawable geometry of the visible objects.
    pub cache: GeometryCache,
    /// The probe and its lines.
    pub probe: ProbeState,
    /// The traced curves and their lines.
    pub curves: CurvesState,
    /// The probe's and the curves' lines together, as the 3D view draws them.
    pub extra: Arc<LineSet>,
    /// The generations `extra` was made from.
    extra_key: (u64, u64),
    /// The region of the edit-by-curvature panel, while it is open.
    pub region: Option<RegionMark>,
    /// The wgpu device and queue, when the 3D view's GPU resources are installed (the view
    /// and the picture export need them).
    pub gpu: Option<RenderState>,
    /// The task running on another thread, if any (`Command::InBackground`).
    pub task: Option<BackgroundTask>,
}

/// A computation running on another thread, ending in a command to apply.
pub struct BackgroundTask {
    /// What runs, for the busy indicator.
    pub what: String,
    /// When it started.
    pub started: std::time::Instant,
    /// The command it ends in.
    pub result: std::sync::mpsc::Receiver<crate::command::Command>,
}

impl Runtime {
    /// Joins the probe's and the curves' lines into `extra` when either changed.
    pub fn join_extra_lines(&mut self) {
        let key = (self.probe.lines.generation, self.curves.lines.generation);
        if key == self.extra_key {
            return;
        }
        let mut lines = self.probe.lines.lines.clone();
        lines.extend_from_slice(&self.curves.lines.lines);
        self.extra = Arc::new(LineSet {
            generation: crate::scene::fresh_revision(),
            lines,
        });
        self.extra_key = key;
    }
}
