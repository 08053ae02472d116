//! Rendering the whole application without a window: for `--screenshot` and for tests. The
//! UI runs in an `egui_kittest` harness drawn by wgpu (a software rasteriser such as Mesa's
//! lavapipe is enough), with the 3D view's GPU resources installed.

use egui_kittest::Harness;
use egui_kittest::wgpu::{WgpuTestRenderer, create_render_state, default_wgpu_setup};

use crate::app::App;

/// A harness running `app` in a `width` × `height` window, drawn with wgpu.
pub fn harness(mut app: App, width: f32, height: f32) -> Harness<'static, App> {
    let state = create_render_state(
        default_wgpu_setup(),
        eframe::egui_wgpu::RendererOptions::PREDICTABLE,
    );
    app.attach_gpu(state.clone());
    Harness::builder()
        .with_size(egui::vec2(width, height))
        .renderer(WgpuTestRenderer::from_render_state(state))
        .build_ui_state(|ui, app: &mut App| app.ui(ui), app)
}

/// Renders the application once, after any background meshing or task has ended, and
/// returns the picture.
pub fn screenshot(app: App, width: f32, height: f32) -> Result<image::RgbaImage, String> {
    let mut h = harness(app, width, height);
    h.run_steps(2);
    while h.state().is_busy() {
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    // Framing and colour scales settle in the frames after the geometry arrives.
    h.run_steps(4);
    h.render()
}
