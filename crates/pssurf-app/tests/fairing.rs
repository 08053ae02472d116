//! Issue 18, part 5: the "Fairing" panel, through the UI (egui_kittest).

mod support;

use pssurf::surface::ControlNet;
use pssurf_app::App;
use pssurf_app::command::Command;
use support::{harness, press};

/// Fairing from its panel: the selected UPS surface (the demo's wave with noise) gets a lower
/// energy, its boundary control triangles stay, and undo brings it back.
#[test]
fn the_fairing_panel_fairs_the_selected_surface_in_one_undo_step() {
    let mut app = App::demo();
    app.doc.selection.object = Some(0);
    let noisy = match app.doc.scene.objects[0].surface().unwrap().uniform() {
        Some(u) => pssurf::surface::Surface::try_from(u.with_noise(
            0.01,
            pssurf::noise::NoiseKind::Uniform,
            4,
        ))
        .unwrap(),
        None => panic!("the demo's first object is a UPS surface"),
    };
    *app.doc.scene.objects[0].surface_mut().unwrap() = noisy;
    let mut h = harness(app);
    let before = h.state().doc.scene.objects[0]
        .surface()
        .unwrap()
        .control_points();
    press(&mut h, "Fairing");
    press(&mut h, "Fair");
    let after = h.state().doc.scene.objects[0]
        .surface()
        .unwrap()
        .control_points();
    assert_ne!(after, before);
    assert!(h.state().status.contains("faired"), "{}", h.state().status);
    let basis = h.state().doc.scene.objects[0]
        .surface()
        .unwrap()
        .ps_basis()
        .unwrap()
        .clone();
    let tri = basis.triangulation();
    for i in (0..tri.vertex_count()).filter(|&i| tri.is_boundary_vertex(i)) {
        for j in 0..3 {
            assert_eq!(after[3 * i + j], before[3 * i + j]);
        }
    }
    assert_eq!(h.state().doc.undo_name(), Some("fair"));
    h.state_mut().apply(Command::Undo);
    assert_eq!(
        h.state().doc.scene.objects[0]
            .surface()
            .unwrap()
            .control_points(),
        before
    );
}
