//! Issue 16: the "Edit by curvature" panel at the probe, through the UI (egui_kittest).

mod support;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{By, Queryable};
use pssurf::edit::Measure;
use pssurf::surface::{ControlNet, ParametricSurface};
use pssurf_app::App;
use pssurf_app::command::Command;
use support::{harness, press};

/// The demo with the NURPS paraboloid selected, the probe at its centre and the panel open;
/// the probe's parameters.
fn panel_open() -> (Harness<'static, App>, nalgebra::Point2<f64>) {
    let mut app = App::demo();
    app.doc.selection.object = Some(1);
    let mut h = harness(app);
    let (lo, hi) = h.state().doc.scene.objects[1]
        .surface()
        .unwrap()
        .domain_bounds();
    let uv = nalgebra::Point2::from((lo.coords + hi.coords) / 2.0);
    h.state_mut().apply(Command::SetProbe { object: 1, uv });
    h.run_steps(2);
    press(&mut h, "Edit by curvature");
    (h, uv)
}

#[test]
fn the_panel_prescribes_k_at_the_probe_in_one_undo_step() {
    let (mut h, uv) = panel_open();
    let before = h.state().doc.scene.objects[1]
        .surface()
        .unwrap()
        .control_points();
    let k0 = Measure::Gaussian
        .of(&h.state().doc.scene.objects[1]
            .surface()
            .unwrap()
            .jet(uv)
            .unwrap()
            .jet)
        .unwrap();
    let target = k0 + 0.25;
    let node = h
        .query_all(By::new().label("target").role(Role::SpinButton))
        .next()
        .expect("the target field");
    node.set_value_accesskit(target);
    h.run_steps(2);
    press(&mut h, "Apply");
    let s = h.state().doc.scene.objects[1].surface().unwrap();
    let k = Measure::Gaussian.of(&s.jet(uv).unwrap().jet).unwrap();
    assert!(
        (k - target).abs() < 1e-8,
        "K = {k}, asked {target}: {}",
        h.state().status
    );
    assert_eq!(h.state().doc.undo_name(), Some("edit by curvature"));
    // The region is shown in the domain view while the panel is open.
    assert!(h.state().runtime.region.is_some());
    h.state_mut().apply(Command::Undo);
    assert_eq!(
        h.state().doc.scene.objects[1]
            .surface()
            .unwrap()
            .control_points(),
        before
    );
}

/// Dragging the target edits live (the measure follows during the drag) and the whole drag is
/// one undo step.
#[test]
fn dragging_the_target_edits_live() {
    let (mut h, uv) = panel_open();
    let before = h.state().doc.scene.objects[1]
        .surface()
        .unwrap()
        .control_points();
    let measure = |h: &egui_kittest::Harness<'_, App>| {
        let s = h.state().doc.scene.objects[1].surface().unwrap();
        Measure::Gaussian.of(&s.jet(uv).unwrap().jet).unwrap()
    };
    let k0 = measure(&h);
    let field = h
        .query_all(By::new().label("target").role(Role::SpinButton))
        .next()
        .expect("the target field")
        .rect();
    let start = field.center();
    let mut seen = Vec::new();
    support::drag(&mut h, start, start + egui::vec2(48.0, 0.0), 6, |h| {
        seen.push(measure(h))
    });
    // K rose step by step while dragging to the right.
    assert!(seen.windows(2).all(|w| w[1] > w[0]), "{seen:?}");
    assert!(seen[5] > k0, "{k0} then {seen:?}");
    h.state_mut().apply(Command::Undo);
    assert_eq!(
        h.state().doc.scene.objects[1]
            .surface()
            .unwrap()
            .control_points(),
        before
    );
}
