//! Issue 14: files that behave like files, a colour scale that means what its legend says,
//! and number fields that no value can break, tested through the UI (egui_kittest).

use std::path::{Path, PathBuf};

use egui::accesskit::Role;
mod support;

use egui::{Key, Modifiers};
use egui_kittest::Harness;
use egui_kittest::kittest::{By, NodeT, Queryable};
use pssurf::surface::Surface;
use pssurf_app::App;
use pssurf_app::command::Command;
use pssurf_app::create::NewSurface;
use pssurf_app::display::{ViewMode, scale_for};
use pssurf_app::edit::vertex_control;
use pssurf_app::scene::{FileKind, Scene, SceneObject};
use pssurf_viz::colormap::ColorScale;
use support::{harness, press};

/// A surface file holding the demo's paraboloid, and an application showing it.
fn surface_document(dir: &Path) -> (PathBuf, App) {
    let path = dir.join("bowl.json");
    pssurf::io::save(&pssurf_app::demo::paraboloid(2), &path).unwrap();
    let (scene, kind) = Scene::load_file(&path).unwrap();
    assert_eq!(kind, FileKind::Surface);
    (path.clone(), App::from_file(scene, path, kind))
}

/// The titles the application asked the window to show, in order.
fn titles(h: &Harness<'_, App>) -> Vec<String> {
    (h.output().viewport_output.values())
        .flat_map(|v| v.commands.iter())
        .filter_map(|c| match c {
            egui::ViewportCommand::Title(t) => Some(t.clone()),
            _ => None,
        })
        .collect()
}

/// Moves control point Q2 of vertex `v` of object 0 up by `dz`, as one edit.
fn raise(h: &mut Harness<'_, App>, v: usize, dz: f64) {
    let app = h.state_mut();
    let mut c = vertex_control(app.doc.scene.objects[0].surface().unwrap(), v);
    c.points[1].z += dz;
    app.apply(Command::SetVertex {
        object: 0,
        vertex: v,
        control: c,
    });
    h.run_steps(2);
}

#[test]
fn a_single_surface_is_saved_as_a_surface_file_that_the_library_loads() {
    let dir = tempfile::tempdir().unwrap();
    let (path, app) = surface_document(dir.path());
    let mut h = harness(app);
    assert_eq!(h.state().title(), "bowl.json — pssurf");
    let app = h.state_mut();
    let mut c = vertex_control(app.doc.scene.objects[0].surface().unwrap(), 3);
    c.points[1].z += 0.25;
    app.apply(Command::SetVertex {
        object: 0,
        vertex: 3,
        control: c,
    });
    assert!(h.state().doc.dirty);
    // The window is told the new title on the next frame.
    h.run_steps(1);
    assert!(
        titles(&h).contains(&"*bowl.json — pssurf".to_string()),
        "{:?}",
        titles(&h)
    );
    // Ctrl+S keeps it a surface file.
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run_steps(2);
    assert!(!h.state().doc.dirty, "{}", h.state().status);
    let saved = pssurf::io::load(&path).expect("the library (and so `pssurf info`) loads it");
    let z = vertex_control(&saved, 3).points[1].z;
    assert!(
        (z - vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 3).points[1].z)
            .abs()
            == 0.0
    );
    assert_eq!(h.state().title(), "bowl.json — pssurf");

    // Save As Surface… through the menu and the in-app chooser.
    h.state_mut().views.files.folder = Some(dir.path().to_path_buf());
    h.state_mut().doc.path = None;
    h.get_by_label("File").click();
    h.run_steps(2);
    h.get_by_label_contains("Save As Surface").click();
    h.run_steps(3);
    assert_eq!(
        h.state().views.files.choosing(),
        Some(pssurf_app::files::Purpose::SaveAs(FileKind::Surface))
    );
    h.get_by_label("Save").click();
    h.run_steps(3);
    let copy = dir.path().join("bowl.json");
    let again = pssurf::io::load(&copy).expect("Save As wrote a surface file");
    assert_eq!(
        pssurf::io::to_json_string(&again),
        pssurf::io::to_json_string(h.state().doc.scene.objects[0].surface().unwrap())
    );
    assert_eq!(h.state().doc.kind, FileKind::Surface);
    assert_eq!(
        h.state()
            .view
            .recent
            .first()
            .map(|p| p.ends_with("bowl.json")),
        Some(true)
    );
}

#[test]
fn a_surface_document_that_grew_a_second_object_is_saved_as_a_scene_not_silently() {
    let dir = tempfile::tempdir().unwrap();
    let (path, app) = surface_document(dir.path());
    let mut h = harness(app);
    let second = SceneObject::new("wave", pssurf_app::demo::wave_patch(2));
    h.state_mut().apply(Command::Add(vec![second]));
    h.run_steps(2);
    // Placed beside the first, not on it.
    let app = h.state();
    let a = pssurf_app::display::bounds([app.object_mesh(0).unwrap()]).unwrap();
    let b = pssurf_app::display::bounds([app.object_mesh(1).unwrap()]).unwrap();
    assert!(
        b.0.x > a.1.x,
        "the new object starts right of the first: {a:?} {b:?}"
    );
    h.state_mut().views.files.folder = Some(dir.path().to_path_buf());
    h.key_press_modifiers(Modifiers::COMMAND, Key::S);
    h.run_steps(3);
    // The surface file is untouched; the chooser asks where to put a scene.
    assert!(pssurf::io::load(&path).is_ok());
    assert_eq!(
        h.state().views.files.choosing(),
        Some(pssurf_app::files::Purpose::SaveAs(FileKind::Scene))
    );
    assert!(
        h.state().status.contains("2 objects"),
        "{}",
        h.state().status
    );
}

#[test]
fn unsaved_changes_are_asked_about_before_new_open_and_close() {
    let dir = tempfile::tempdir().unwrap();
    let (path, app) = surface_document(dir.path());
    let mut h = harness(app);
    raise(&mut h, 2, 0.1);
    let edited = h.state().doc.scene.to_json();
    // New: asked; Cancel keeps everything.
    h.key_press_modifiers(Modifiers::COMMAND, Key::N);
    h.run_steps(3);
    assert!(h.state().pending.is_some());
    h.get_by_label_contains("not saved");
    h.get_by_label("Cancel").click();
    h.run_steps(3);
    assert!(h.state().pending.is_none());
    assert_eq!(h.state().doc.scene.to_json(), edited);
    // Open another file: asked; Don't save opens it.
    let other = dir.path().join("wave.json");
    pssurf::io::save(&pssurf_app::demo::wave_patch(2), &other).unwrap();
    h.state_mut().apply(Command::Open(other.clone()));
    h.run_steps(3);
    assert_eq!(
        h.state().pending,
        Some(pssurf_app::files::Intent::Open(other.clone()))
    );
    h.get_by_label("Don't save").click();
    h.run_steps(3);
    assert_eq!(h.state().doc.path.as_deref(), Some(other.as_path()));
    assert!(!h.state().doc.dirty);
    // Close with changes: the close is held back and asked about; Save saves, then closes.
    raise(&mut h, 1, 0.1);
    let close = egui::ViewportEvent::Close;
    (h.input_mut()
        .viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .events)
        .push(close);
    h.run_steps(1);
    let held = (h.output().viewport_output.values())
        .flat_map(|v| v.commands.iter())
        .any(|c| *c == egui::ViewportCommand::CancelClose);
    assert!(held, "the close was not held back");
    h.run_steps(2);
    assert_eq!(h.state().pending, Some(pssurf_app::files::Intent::Quit));
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert!(h.state().closing(), "{}", h.state().status);
    let saved = pssurf::io::load(&other).unwrap();
    assert_eq!(
        pssurf::io::to_json_string(&saved),
        pssurf::io::to_json_string(h.state().doc.scene.objects[0].surface().unwrap())
    );
    // An unmodified document closes without a question.
    let mut clean = harness(surface_document(dir.path()).1);
    let close = egui::ViewportEvent::Close;
    (clean
        .input_mut()
        .viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .events)
        .push(close);
    clean.run_steps(1);
    assert!(clean.state().pending.is_none());
    assert!(path.exists());
}

#[test]
fn messages_follow_the_state_they_describe() {
    let dir = tempfile::tempdir().unwrap();
    let (path, app) = surface_document(dir.path());
    let mut h = harness(app);
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, "{ not json").unwrap();
    h.state_mut().open(bad);
    assert!(h.state().error.as_deref().unwrap().contains("bad.json"));
    // A good load clears the old error.
    h.state_mut().open(path.clone());
    assert!(h.state().error.is_none());
    assert!(h.state().status.starts_with("opened"));
    // A failed save says so, with the path and the cause in words, and no temporary name.
    let nowhere = dir.path().join("missing-folder").join("x.json");
    h.state_mut().save_to(nowhere.clone(), FileKind::Surface);
    let status = h.state().status.clone();
    assert!(status.starts_with("not saved"), "{status}");
    assert!(
        status.contains("missing-folder") && status.contains("does not exist"),
        "{status}"
    );
    assert!(
        !status.contains(".pssurf-") && !status.contains("os error"),
        "{status}"
    );
    assert!(h.state().doc.path.as_deref() == Some(path.as_path()));
    // Dropping a file on the window adds its objects (one undo step).
    let wave = dir.path().join("wave.json");
    pssurf::io::save(&pssurf_app::demo::wave_patch(2), &wave).unwrap();
    h.state_mut().dropped(vec![wave]);
    assert_eq!(h.state().doc.scene.objects.len(), 2);
    assert_eq!(h.state().doc.undo_name(), Some("add file"));
}

/// The shared automatic scale that the settings give for `values`.
fn expected(app: &App, values: &[f64]) -> ColorScale {
    let ViewMode::Curvature(q) = app.view.display.mode else {
        panic!("not a curvature plot")
    };
    scale_for(&app.view.display, q, values, app.scene_size())
}

/// The values drawn for the visible objects.
fn visible_values(app: &App) -> Vec<f64> {
    (app.doc.scene.visible())
        .flat_map(|(i, _)| app.object_mesh(i).unwrap().values.clone())
        .collect()
}

#[test]
fn the_automatic_range_follows_drags_hiding_and_per_object_choice() {
    let mut app = App::demo();
    app.doc.selection.vertex = Some(20);
    let mut h = harness(app);
    let before = h.state().legend().unwrap().scale;
    assert_eq!(before, expected(h.state(), &visible_values(h.state())));
    // A drag: the scale holds still while the point moves, then fits the new data.
    let mut c = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 20);
    h.state_mut().apply(Command::StartDrag);
    for _ in 0..5 {
        c.points[0].z += 0.4;
        let control = c.clone();
        h.state_mut().apply(Command::DragVertex {
            object: 0,
            vertex: 20,
            control,
        });
        h.run_steps(1);
        assert_eq!(
            h.state().legend().unwrap().scale,
            before,
            "held during the drag"
        );
    }
    h.state_mut().apply(Command::EndDrag);
    h.run_steps(2);
    let after = h.state().legend().unwrap().scale;
    assert_ne!(after, before);
    assert_eq!(after, expected(h.state(), &visible_values(h.state())));
    // Hiding the wave patch: the scale is the paraboloid's alone.
    h.state_mut().apply(Command::ToggleVisible(vec![0]));
    h.run_steps(2);
    let bowl = h.state().object_mesh(1).unwrap().values.clone();
    assert_eq!(
        h.state().legend().unwrap().scale,
        expected(h.state(), &bowl)
    );
    // One scale per object: each object's own values, each with its legend.
    h.state_mut().apply(Command::ToggleVisible(vec![0]));
    let mut d = h.state().view.display.clone();
    d.shared_scale = false;
    h.state_mut().apply(Command::SetDisplay(d));
    h.run_steps(2);
    let app = h.state();
    assert_eq!(app.runtime.cache.legends.len(), 2);
    for (i, legend) in app.runtime.cache.legends.iter().enumerate() {
        let own = app.object_mesh(i).unwrap().values.clone();
        assert_eq!(legend.scale, expected(app, &own), "object {i}");
        assert_eq!(
            legend.object.as_ref().unwrap().1,
            app.doc.scene.objects[i].name
        );
    }
}

#[test]
fn one_outlier_does_not_stretch_the_scale_and_the_legend_shows_it_clipped() {
    // A paraboloid (H ≈ 1 about the middle) with a narrow dent: a few samples of |H| ≫ 1.
    let mut d = NewSurface {
        size: 16,
        formula: "0.5*(x^2+y^2) - 0.05*exp(-((x-0.31)^2+(y-0.22)^2)/0.002)".into(),
        ..NewSurface::default()
    };
    d.kind = pssurf::ups::GraphKind::Parametric;
    let surface: Surface = d.build().unwrap();
    let scene = Scene {
        objects: vec![SceneObject::new("dented bowl", surface)],
    };
    let mut app = App::new(scene, None);
    app.view.display.mode = ViewMode::Curvature(pssurf::interrogate::CurvatureQuantity::Mean);
    let h = harness(app);
    let legend = h.state().legend().unwrap().clone();
    let data = legend.data.unwrap();
    let (lo, hi) = legend.scale.ends();
    let end = hi.abs().max(lo.abs());
    let extreme = data.max.abs().max(data.min.abs());
    assert!(extreme > 8.0 * end, "extreme {extreme} vs scale end {end}");
    assert!(
        end < 2.0,
        "the scale keeps to the bulk of the values: ±{end}"
    );
    assert!(
        data.above + data.below > 0 && data.clipped_percent() <= 2.5,
        "{data:?}"
    );
    // Min/max (tails 0) would have been stretched to the outlier.
    let mut d = h.state().view.display.clone();
    d.tail_percent = 0.0;
    let values = visible_values(h.state());
    let q = pssurf::interrogate::CurvatureQuantity::Mean;
    let stretched = scale_for(&d, q, &values, h.state().scene_size());
    assert!(stretched.ends().1 >= extreme * 0.999);
}

#[test]
fn z_1e300_typed_into_the_editor_is_refused_without_a_panic() {
    let mut app = App::demo();
    app.doc.selection.vertex = Some(7);
    let mut h = harness(app);
    let before = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 7);
    // Through accessibility, and by typing as a user would.
    h.get_by_label("Q1 z").set_value_accesskit(1e300);
    h.run_steps(3);
    assert!(h.state().status.contains("refused"), "{}", h.state().status);
    assert!(h.state().status.contains("Q1 z"), "{}", h.state().status);
    h.get_by_label("Q2 z").focus();
    h.run_steps(1);
    h.key_press_modifiers(Modifiers::COMMAND, Key::A);
    h.get_by_label("Q2 z").type_text("1e300");
    h.run_steps(1);
    h.key_press(Key::Enter);
    h.run_steps(3);
    assert_eq!(
        vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 7),
        before
    );
    assert!(h.state().status.contains("±1e60"), "{}", h.state().status);
    // 1e59 is accepted (the library's range) and the view copes with it.
    h.get_by_label("Q1 z").set_value_accesskit(1e59);
    h.run_steps(4);
    let after = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 7);
    assert_eq!(after.points[0].z, 1e59);
    let m = h.state().view.camera.view_projection(1.5);
    assert!(m.iter().all(|x| x.is_finite()));
}

/// What brings a panel or dialog on screen.
type Setup = dyn Fn(&mut Harness<'_, App>);

/// Every number field on screen, by its accessibility label.
fn number_fields(h: &Harness<'_, App>) -> Vec<String> {
    let mut names: Vec<String> = h
        .query_all(By::new().role(Role::SpinButton))
        .filter_map(|n| n.accesskit_node().label())
        .collect();
    names.sort();
    names.dedup();
    names
}

#[test]
fn no_value_typed_into_any_number_field_breaks_the_application() {
    const ODD: [f64; 8] = [
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e300,
        -1e300,
        1e-300,
        0.0,
        -1.0,
    ];
    let setups: Vec<(&str, Box<Setup>)> = vec![
        ("editor", Box::new(|_| {})),
        ("fixed range", Box::new(|h| press(h, "fixed"))),
        ("contrast", Box::new(|h| press(h, "contrast C"))),
        (
            "panels",
            Box::new(|h| {
                press(h, "Noise");
                press(h, "Wavelets");
                press(h, "Subdivision");
                press(h, "Probe");
            }),
        ),
        (
            "new quadric",
            Box::new(|h| {
                h.state_mut()
                    .apply(Command::OpenNewSurface(pssurf_app::command::Shape::Quadric))
            }),
        ),
        (
            "new sphere",
            Box::new(|h| {
                h.state_mut()
                    .apply(Command::OpenNewSurface(pssurf_app::command::Shape::Sphere))
            }),
        ),
        (
            "new cone",
            Box::new(|h| {
                h.state_mut()
                    .apply(Command::OpenNewSurface(pssurf_app::command::Shape::Cone))
            }),
        ),
        (
            "new patch",
            Box::new(|h| {
                h.state_mut()
                    .apply(Command::OpenNewSurface(pssurf_app::command::Shape::Formula))
            }),
        ),
        (
            "export",
            Box::new(|h| {
                h.state_mut().apply(Command::OpenExport(
                    pssurf_app::command::ExportKind::Picture,
                ))
            }),
        ),
    ];
    let mut tried = 0;
    let mut fields_seen = std::collections::BTreeSet::new();
    for (k, (what, setup)) in setups.iter().enumerate() {
        let app = if k == 0 { rational_app() } else { App::demo() };
        let mut h = harness(app);
        setup(&mut h);
        h.run_steps(3);
        let names = number_fields(&h);
        assert!(!names.is_empty(), "{what}: no number field found");
        for name in names {
            for x in ODD {
                let by = By::new().label(&name).role(Role::SpinButton);
                let Some(node) = h.query_all(by).next() else {
                    continue;
                };
                node.set_value_accesskit(x);
                h.run_steps(2);
                tried += 1;
                let app = h.state();
                for o in &app.doc.scene.objects {
                    let t = o.transform;
                    assert!(t.scale > 0.0 && t.scale.is_finite(), "{what} {name} = {x}");
                    assert!(
                        t.translate.iter().all(|v| v.abs() <= 1e60),
                        "{what} {name} = {x}"
                    );
                    for g in 0..pssurf_app::edit::vertex_count(o.surface().unwrap()) {
                        let c = vertex_control(o.surface().unwrap(), g);
                        assert!(c.points.iter().all(|p| p.iter().all(|v| v.abs() <= 1e60)));
                        if let Some(w) = &c.weights {
                            assert!(w.iter().all(|w| (1e-30..=1e30).contains(w)));
                        }
                    }
                }
                let m = app.view.camera.view_projection(1.5);
                assert!(m.iter().all(|v| v.is_finite()), "{what} {name} = {x}");
                fields_seen.insert(name.clone());
            }
        }
    }
    // Every kind of field was reached: placement, control points, weights, colour range,
    // contrast, panel settings, dialog fields.
    for must in [
        "move x",
        "scale",
        "Q1 z",
        "Q1 weight",
        "range from",
        "contrast C",
        "amplitude",
        "side length",
        "a (x²)",
    ] {
        assert!(
            fields_seen.contains(must),
            "{must} not tried; saw {fields_seen:?}"
        );
    }
    assert!(tried >= 8 * fields_seen.len(), "{tried}");
}

/// The demo with the NURPS paraboloid's vertex 3 selected (its fields include weights).
fn rational_app() -> App {
    let mut app = App::demo();
    app.doc.selection = pssurf_app::document::Selection {
        object: Some(1),
        vertex: Some(3),
    };
    app
}

#[test]
fn an_exported_surface_file_loads_again_and_bad_targets_say_why() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(App::demo());
    h.state_mut().doc.selection.object = Some(1);
    let out = dir.path().join("bowl.json");
    h.state_mut()
        .apply(Command::ExportSurface { path: out.clone() });
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let loaded = pssurf::io::load(&out).expect("the exported surface file loads");
    assert_eq!(
        pssurf::io::to_json_string(&loaded),
        pssurf::io::to_json_string(h.state().doc.scene.objects[1].surface().unwrap())
    );
    // A folder, a missing folder, a picture too small for its legend: one clear message
    // each, and nothing written.
    let missing = dir.path().join("no").join("x.json");
    for (command, words) in [
        (
            Command::ExportSurface {
                path: dir.path().to_path_buf(),
            },
            "is a directory",
        ),
        (
            Command::ExportSurface {
                path: missing.clone(),
            },
            "does not exist",
        ),
    ] {
        h.state_mut().apply(command);
        let status = h.state().status.clone();
        assert!(
            status.starts_with("not exported") && status.contains(words),
            "{status}"
        );
        h.state_mut().error = None;
    }
    assert!(!missing.exists());
    let entries = std::fs::read_dir(dir.path()).unwrap().count();
    assert_eq!(entries, 1, "only the exported file, no temporary one");
}

/// Issue 17: an IGES file opens as an untitled scene of its NURBS surfaces (saving must not
/// write over the IGES file), and File → Import IGES adds them beside the others.
#[test]
fn an_iges_file_opens_as_an_untitled_scene_of_nurbs_surfaces() {
    let iges =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/iges/bug24012_face.igs");
    let mut app = App::demo();
    let before = app.doc.scene.objects.len();
    app.apply(Command::AddFile(iges.clone()));
    assert_eq!(app.doc.scene.objects.len(), before + 1, "{}", app.status);
    assert!(matches!(
        **app.doc.scene.objects[before].surface().unwrap(),
        Surface::Nurbs(_)
    ));
    // Open replaces the document (App::open: the unsaved-changes question is tested above).
    app.open(iges.clone());
    assert_eq!(app.doc.scene.objects.len(), 1, "{}", app.status);
    assert_eq!(
        app.doc.path, None,
        "an imported IGES file is not the document's file"
    );
    assert_eq!(app.doc.scene.objects[0].group, "bug24012_face");
    // A broken IGES file leaves the scene as it was and says why, with the line.
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.igs");
    std::fs::write(&bad, "not an IGES file\n").unwrap();
    app.open(bad);
    assert_eq!(app.doc.scene.objects.len(), 1);
    assert!(
        app.error.as_deref().unwrap_or("").contains("line 1"),
        "{:?}",
        app.error
    );
}

/// Issue 17: the NURBS → UPS panel adds a UPS approximation of the selected NURBS surface
/// within the tolerance (one undo step).
#[test]
fn the_nurbs_panel_adds_a_ups_approximation_within_the_tolerance() {
    let iges =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/iges/bug24012_face.igs");
    let mut app = App::demo();
    app.open(iges);
    app.doc.selection.object = Some(0);
    let mut h = harness(app);
    press(&mut h, "NURBS to UPS");
    press(&mut h, "Approximate");
    let app = h.state();
    assert!(app.status.starts_with("approximated"), "{}", app.status);
    assert_eq!(app.doc.scene.objects.len(), 2);
    let max: f64 = app
        .status
        .split("max deviation ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(max <= 0.01, "{}", app.status);
    assert!(matches!(
        **app.doc.scene.objects[1].surface().unwrap(),
        Surface::Uniform(_)
    ));
    assert_eq!(app.doc.undo_name(), Some("new surface"));
}
