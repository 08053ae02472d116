//! The application's state split: cheap undo snapshots that restore only what changed, and
//! the saved view settings.

use std::sync::Arc;

use pssurf::interrogate::CurvatureQuantity;
use pssurf_app::App;
use pssurf_app::command::{Command, ObjectEdit};
use pssurf_app::display::ViewMode;
use pssurf_app::edit::vertex_control;
use pssurf_app::probe::Alignment;
use pssurf_app::state::ViewState;

#[test]
fn undo_resamples_only_the_object_that_changed() {
    let mut app = App::demo();
    app.update_geometry();
    assert_eq!(app.runtime.cache.sampled, 2);
    let mut c = vertex_control(app.doc.scene.objects[1].surface().unwrap(), 3);
    c.points[0].z += 0.2;
    app.set_vertex(1, 3, c).unwrap();
    app.update_geometry();
    let after_edit = app.runtime.cache.sampled;
    app.undo();
    app.update_geometry();
    assert_eq!(
        app.runtime.cache.sampled,
        after_edit + 1,
        "undo re-samples the edited object only"
    );
    app.redo();
    app.update_geometry();
    assert_eq!(app.runtime.cache.sampled, after_edit + 2);
    // A rename changes no geometry: neither it nor its undo samples anything.
    let before = app.runtime.cache.sampled;
    app.apply(Command::EditObject {
        object: 0,
        edit: ObjectEdit::Rename("wave".into()),
    });
    app.update_geometry();
    app.undo();
    app.update_geometry();
    assert_eq!(app.runtime.cache.sampled, before);
}

#[test]
fn history_snapshots_share_the_surfaces_an_edit_did_not_touch() {
    let mut app = App::demo();
    let original: Vec<_> = app
        .doc
        .scene
        .objects
        .iter()
        .map(|o| o.surface().unwrap().clone())
        .collect();
    app.apply(Command::EditObject {
        object: 1,
        edit: ObjectEdit::Rename("bowl".into()),
    });
    let mut c = vertex_control(app.doc.scene.objects[1].surface().unwrap(), 2);
    c.points[1].z -= 0.1;
    app.set_vertex(1, 2, c).unwrap();
    let now = &app.doc.scene.objects;
    assert!(
        Arc::ptr_eq(now[0].surface().unwrap(), &original[0]),
        "object 0 was copied"
    );
    assert!(
        !Arc::ptr_eq(now[1].surface().unwrap(), &original[1]),
        "the edit wrote in place"
    );
    app.undo();
    app.undo();
    let back = &app.doc.scene.objects;
    for (o, s) in back.iter().zip(&original) {
        assert!(
            Arc::ptr_eq(o.surface().unwrap(), s),
            "undo gives back the very surfaces"
        );
    }
    assert_eq!(back[1].name, "NURPS paraboloid");
}

#[test]
fn view_settings_round_trip_with_the_panels_settings() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("deep/view.json");
    let mut app = App::demo();
    app.view.display.mode = ViewMode::Curvature(CurvatureQuantity::Gaussian);
    app.view.display.level = 4;
    app.view.camera.azimuth_deg = 12.5;
    app.view.light.headlight = false;
    app.view.display.range = pssurf_viz::plot::Range::Fixed(-2.0, 0.5);
    app.view.probe.alignment = Alignment::Parametric;
    let noise = app.view_state().panels["Noise"].clone();
    let mut changed = noise.clone();
    changed["seed"] = 77.into();
    let mut view = app.view_state();
    view.panels.insert("Noise".into(), changed.clone());
    view.save(&path).unwrap();
    let loaded = ViewState::load(&path).unwrap();
    assert_eq!(loaded, view);
    let mut fresh = App::demo();
    fresh.restore_view(loaded);
    assert_eq!(fresh.view.camera.azimuth_deg, 12.5);
    assert_eq!(fresh.view_state().panels["Noise"], changed);
    assert_eq!(fresh.view_state(), view);
}

#[test]
fn damaged_view_settings_are_refused_with_a_message() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("garbage", "{ not json".to_string()),
        ("nan", r#"{"camera": {"distance": NaN}}"#.to_string()),
        ("huge", r#"{"camera": {"distance": 1e400}}"#.to_string()),
        ("negative", r#"{"camera": {"half_height": -1}}"#.to_string()),
        ("level", r#"{"display": {"level": 40}}"#.to_string()),
        ("mode", r#"{"display": {"mode": "glossy"}}"#.to_string()),
        ("far", r#"{"camera": {"distance": 1e20}}"#.to_string()),
        ("overflow", r#"{"camera": {"distance": 1e308}}"#.to_string()),
        (
            "zebra",
            r#"{"display": {"zebra_width_deg": 0}}"#.to_string(),
        ),
        (
            "range",
            r#"{"display": {"range": {"fixed": [1, -1]}}}"#.to_string(),
        ),
        (
            "contrast",
            r#"{"display": {"range": {"contrast": -2}}}"#.to_string(),
        ),
        (
            "big",
            format!("{{\"panels\": {{\"x\": \"{}\"}}}}", "a".repeat(2 << 20)),
        ),
    ];
    for (name, text) in cases {
        let path = dir.path().join(format!("{name}.json"));
        std::fs::write(&path, text).unwrap();
        let e = ViewState::load(&path).unwrap_err();
        assert!(e.contains(&format!("{name}.json")), "{name}: {e}");
        let why = match name {
            "range" => "colour range",
            "contrast" => "contrast",
            "zebra" => "zebra",
            "far" => "1e12",
            _ => "",
        };
        assert!(e.contains(why), "{name}: {e}");
    }
    // Unknown fields and missing ones are fine: settings of another build still load.
    let path = dir.path().join("partial.json");
    std::fs::write(&path, r#"{"display": {"level": 3}, "future": 1}"#).unwrap();
    let v = ViewState::load(&path).unwrap();
    assert_eq!(v.display.level, 3);
    assert_eq!(v.camera, ViewState::default().camera);
}
