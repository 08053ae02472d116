//! Issue 17: quadrics from the New dialog and the NURPS design tools of the control-triangle
//! editor, through the UI (egui_kittest).

mod support;

use egui::Pos2;
use egui_kittest::kittest::Queryable;
use pssurf::surface::Surface;
use pssurf_app::App;
use pssurf_app::command::{Command, Shape};
use pssurf_app::document::Selection;
use pssurf_app::edit::vertex_control;
use support::{harness, press};

/// The demo with the NURPS paraboloid's vertex 3 selected.
fn rational_app() -> App {
    let mut app = App::demo();
    app.doc.selection = Selection {
        object: Some(1),
        vertex: Some(3),
    };
    app
}

#[test]
fn the_new_dialog_makes_a_cylinder_of_eight_nurps_patches_in_one_undo_step() {
    let mut h = harness(App::demo());
    let before = h.state().doc.scene.objects.len();
    h.state_mut()
        .apply(Command::OpenNewSurface(Shape::Cylinder));
    h.run_steps(3);
    press(&mut h, "Create");
    let objects = &h.state().doc.scene.objects;
    assert_eq!(objects.len(), before + 8);
    assert!(
        objects[before..]
            .iter()
            .all(|o| o.group == "cylinder" && matches!(**o.surface().unwrap(), Surface::Nurps(_)))
    );
    assert!(
        h.state().status.contains("cylinder (8 patches)"),
        "{}",
        h.state().status
    );
    h.state_mut().apply(Command::Undo);
    assert_eq!(h.state().doc.scene.objects.len(), before);
    // A sphere with its sectors.
    h.state_mut().apply(Command::OpenNewSurface(Shape::Sphere));
    h.run_steps(3);
    press(&mut h, "Create");
    assert_eq!(h.state().doc.scene.objects.len(), before + 12);
}

#[test]
fn cusp_and_planar_section_buttons_change_the_selected_control_triangle() {
    let mut h = harness(rational_app());
    press(&mut h, "Cusp");
    let c = vertex_control(h.state().doc.scene.objects[1].surface().unwrap(), 3);
    assert!(
        c.points.iter().all(|p| (p - c.points[0]).norm() < 1e-15),
        "{c:?}"
    );
    press(&mut h, "Planar section");
    let d = vertex_control(h.state().doc.scene.objects[1].surface().unwrap(), 3);
    let w = d.weights.unwrap();
    let largest = c.weights.unwrap().iter().cloned().fold(0.0, f64::max);
    assert!(w.iter().all(|&x| x == 1e3 * largest), "{w:?}");
    // Two edits, two undo steps.
    h.state_mut().apply(Command::Undo);
    h.state_mut().apply(Command::Undo);
    let back = vertex_control(h.state().doc.scene.objects[1].surface().unwrap(), 3);
    assert_eq!(
        back,
        vertex_control(rational_app().doc.scene.objects[1].surface().unwrap(), 3)
    );
}

/// Dragging the tangent point in the widget changes the weights (one undo step per drag) and
/// keeps the control points.
#[test]
fn dragging_the_tangent_point_moves_the_weights() {
    let mut h = harness(rational_app());
    let before = vertex_control(h.state().doc.scene.objects[1].surface().unwrap(), 3);
    let label = h.get_by_label_contains("shape parameters").rect();
    // The widget is drawn just above its caption: drag from its centre towards Q1.
    let start = Pos2::new(label.left() + 75.0, label.top() - 60.0);
    let end = Pos2::new(start.x - 40.0, start.y + 30.0);
    support::drag(&mut h, start, end, 10, |_| {});
    let after = vertex_control(h.state().doc.scene.objects[1].surface().unwrap(), 3);
    assert_eq!(after.points, before.points);
    assert_ne!(after.weights, before.weights);
    assert!(
        h.state().status.contains("tangent point"),
        "{}",
        h.state().status
    );
    h.state_mut().apply(Command::Undo);
    assert_eq!(
        vertex_control(h.state().doc.scene.objects[1].surface().unwrap(), 3),
        before
    );
}
