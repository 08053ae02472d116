//! Issue 18, part 8: the hole dialog, through the UI (egui_kittest): edges picked with the
//! probe in the 3D view's place, steps one click at a time, patches in place, undoable.

mod support;

use std::sync::Arc;

use pssurf::hole::{BoundaryCurve, SurfaceEdge};
use pssurf::ps::quadrics::Quadric;
use pssurf::surface::{ControlNet, ParametricSurface, Surface};
use pssurf_app::App;
use pssurf_app::command::Command;
use pssurf_app::scene::SceneObject;
use support::{harness, press};

/// The domain point just inside the side of `surface` that lies on the equator.
fn near_the_equator(surface: &Surface) -> nalgebra::Point2<f64> {
    let sides = SurfaceEdge::sides(Arc::new(surface.clone()));
    let e = sides
        .iter()
        .find(|e| e.point(0.0).z.abs() < 1e-12 && e.point(1.0).z.abs() < 1e-12)
        .expect("one side on the equator");
    let (lo, hi) = surface.domain().bounds();
    let centre = nalgebra::Point2::from((lo.coords + hi.coords) * 0.5);
    let mid = nalgebra::Point2::from((e.from.coords + e.to.coords) * 0.5);
    mid + (centre - mid) * 0.01
}

#[test]
fn the_hole_dialog_fills_the_sphere_gap_step_by_step() {
    let mut app = App::demo();
    let patches = Quadric::Sphere {
        radius: 1.0,
        sectors: 6,
    }
    .bezier_patches()
    .unwrap();
    app.doc.scene.objects = patches
        .into_iter()
        .take(2)
        .enumerate()
        .map(|(k, p)| SceneObject::new(format!("sphere {}", k + 1), Surface::RationalBezier(p)))
        .collect();
    let mut h = harness(app);
    press(&mut h, "Hole filling");
    for object in 0..2 {
        let uv = near_the_equator(h.state().doc.scene.objects[object].surface().unwrap());
        h.state_mut().apply(Command::SetProbe { object, uv });
        h.run();
        press(&mut h, "Add edge at probe");
        assert!(h.state().status.contains("picked"), "{}", h.state().status);
    }
    press(&mut h, "Start");
    assert_eq!(h.state().doc.scene.objects.len(), 4, "{}", h.state().status);
    assert_eq!(h.state().doc.undo_name(), Some("fill hole"));
    let level0 = h.state().doc.scene.objects[2]
        .surface()
        .unwrap()
        .control_points()
        .len();
    press(&mut h, "Step");
    press(&mut h, "Step");
    let level2 = h.state().doc.scene.objects[2]
        .surface()
        .unwrap()
        .control_points()
        .len();
    // A triangle of side 1, then 4: 3 and 15 vertices, three control points each.
    assert_eq!((level0, level2), (9, 45));
    assert_eq!(h.state().doc.undo_name(), Some("hole step"));
    // The patch stays in its hole: its corner on the equator is the sphere's (x, y) =
    // (cos 30°, sin 30°).
    let patch = h.state().doc.scene.objects[2].surface().unwrap();
    let east = nalgebra::Vector3::new(0.75f64.sqrt(), 0.5, 0.0);
    let nearest = patch.domain().boundary()[0]
        .iter()
        .map(|&uv| (patch.point(uv).unwrap() - east).norm())
        .fold(f64::INFINITY, f64::min);
    assert!(nearest < 1e-12, "{nearest}");
    press(&mut h, "Run to tolerance");
    assert!(
        h.state().status.contains("interior"),
        "{}",
        h.state().status
    );
    // Undo takes back each step (both patches at once), then the patches.
    for _ in 0..3 {
        assert_eq!(h.state().doc.undo_name(), Some("hole step"));
        h.state_mut().apply(Command::Undo);
    }
    assert_eq!(h.state().doc.undo_name(), Some("fill hole"));
    h.state_mut().apply(Command::Undo);
    assert_eq!(h.state().doc.scene.objects.len(), 2);
}
