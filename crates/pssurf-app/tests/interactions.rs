//! State tests of the application's interactions through its UI (egui_kittest, no GPU).

mod support;

use egui::{Event, Key, Modifiers, PointerButton, Pos2, vec2};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use nalgebra::Point2;
use pssurf::surface::ParametricSurface;
use pssurf_app::App;
use pssurf_app::display::ViewMode;
use pssurf_app::domain_view::DomainMap;
use pssurf_app::edit::vertex_control;
use support::{click, click_with, harness, press};

/// The screen position of vertex `v` of the selected object in the domain view.
fn vertex_on_screen(h: &Harness<'_, App>, v: usize) -> Pos2 {
    let rect = h.get_by_label("domain view").rect();
    let app = h.state();
    let tri = app.doc.scene.objects[app.doc.selection.object.unwrap()]
        .surface()
        .unwrap()
        .ps_basis()
        .unwrap()
        .triangulation()
        .clone();
    let (lo, hi) = tri.bounds();
    DomainMap::new(lo, hi, rect).to_screen(tri.vertex(v))
}

fn z_at(app: &App, object: usize, uv: Point2<f64>) -> f64 {
    let s = app.doc.scene.objects[object].surface().unwrap();
    s.jet_with(uv, &mut s.cursor_near(uv)).unwrap().jet.value.z
}

#[test]
fn clicking_a_ps_triangle_in_the_domain_view_selects_its_vertex() {
    let mut h = harness(App::demo());
    assert_eq!(h.state().doc.selection.object, Some(0));
    assert_eq!(h.state().doc.selection.vertex, None);
    for v in [0, 7, 20] {
        let pos = vertex_on_screen(&h, v);
        click(&mut h, pos);
        assert_eq!(
            h.state().doc.selection.vertex,
            Some(v),
            "clicked vertex {v}"
        );
    }
    // The editor shows the selected vertex's control points.
    h.get_by_label("Q1 z");
}

#[test]
fn numeric_edit_changes_the_surface_and_undo_redo_restore_it() {
    let mut h = harness(App::demo());
    let v = 12;
    let pos = vertex_on_screen(&h, v);
    click(&mut h, pos);
    assert_eq!(h.state().doc.selection.vertex, Some(v));
    let before = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), v);
    let uv = h.state().doc.scene.objects[0]
        .surface()
        .unwrap()
        .ps_basis()
        .unwrap()
        .triangulation()
        .vertex(v);
    let z_before = z_at(h.state(), 0, uv);

    h.get_by_label("Q2 z")
        .set_value_accesskit(before.points[1].z + 0.25);
    h.run_steps(2);
    let after = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), v);
    assert!((after.points[1].z - (before.points[1].z + 0.25)).abs() < 1e-12);
    assert_eq!(after.points[0], before.points[0]);
    let z_after = z_at(h.state(), 0, uv);
    // s(V_i) is a convex combination of the three control points: it moved up.
    assert!(z_after > z_before + 1e-6, "{z_before} → {z_after}");

    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(
        vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), v),
        before
    );
    assert!((z_at(h.state(), 0, uv) - z_before).abs() < 1e-14);

    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run_steps(2);
    assert_eq!(
        vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), v),
        after
    );
}

#[test]
fn dragging_a_control_point_moves_it_and_is_one_undo_step() {
    let mut app = App::demo();
    app.doc.selection.vertex = Some(5);
    let mut h = harness(app);
    let before = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 5);
    // Find the first control point's handle on the screen.
    let view = h.get_by_label("3D view").rect();
    let app = h.state();
    let p = app.doc.scene.objects[0]
        .transform
        .matrix()
        .transform_point(&nalgebra::Point3::from(before.points[0]));
    let m = app
        .view
        .camera
        .view_projection(view.width() / view.height());
    let c = m * nalgebra::Vector4::new(p.x as f32, p.y as f32, p.z as f32, 1.0);
    let start = Pos2::new(
        view.left() + 0.5 * (c.x / c.w + 1.0) * view.width(),
        view.top() + 0.5 * (1.0 - c.y / c.w) * view.height(),
    );
    h.event(Event::PointerMoved(start));
    h.run_steps(1);
    h.event(Event::PointerButton {
        pos: start,
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Modifiers::NONE,
    });
    h.run_steps(1);
    for k in 1..=10 {
        h.event(Event::PointerMoved(start + vec2(0.0, -3.0 * k as f32)));
        h.run_steps(1);
    }
    let end = start + vec2(0.0, -30.0);
    h.event(Event::PointerButton {
        pos: end,
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Modifiers::NONE,
    });
    h.run_steps(2);
    let after = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 5);
    // Dragged upwards on the screen: the point moved along the camera's up direction.
    let (_, up) = h.state().view.camera.right_up();
    let moved = after.points[0] - before.points[0];
    assert!(
        moved.norm() > 1e-3,
        "the point did not move (start {start:?}, view {view:?}, camera {:?}, status {})",
        h.state().view.camera,
        h.state().status
    );
    assert!(
        moved.normalize().dot(&up.cast::<f64>()) > 0.99,
        "moved {moved:?}, up {up:?}"
    );
    assert_eq!(after.points[1], before.points[1]);
    // The whole drag is one undo step.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(
        vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 5),
        before
    );
}

#[test]
fn the_curvature_plot_toggles_and_colours_the_mesh() {
    let mut app = App::demo();
    app.view.display.mode = ViewMode::Shaded;
    let mut h = harness(app);
    assert!(h.state().runtime.cache.legends.is_empty());
    h.get_by_label("show").click();
    h.run_steps(2);
    h.get_by_label("mean curvature H").click();
    h.run_steps(3);
    let app = h.state();
    assert!(matches!(app.view.display.mode, ViewMode::Curvature(_)));
    assert!(
        !app.runtime.cache.legends.is_empty(),
        "a curvature plot has a colour scale for its legend"
    );
    let colours: std::collections::HashSet<[u8; 4]> = app
        .runtime
        .cache
        .geometry
        .vertices
        .iter()
        .map(|v| v.color)
        .collect();
    assert!(colours.len() > 20, "only {} colours", colours.len());
}

#[test]
fn a_wavelet_step_from_the_panel_thresholds_and_can_be_undone() {
    let mut app = App::demo();
    // Subdivide first so that there is a level to decompose.
    let mut h = harness(app);
    press(&mut h, "Subdivision");
    press(&mut h, "Subdivide");
    let n = h.state().doc.scene.objects[0]
        .surface()
        .unwrap()
        .uniform()
        .unwrap()
        .grid()
        .vertex_count();
    assert!(n > 61, "subdivided: {n} vertices");
    let smooth = h.state().doc.scene.objects[0].surface().unwrap().clone();
    press(&mut h, "Noise");
    press(&mut h, "Add noise");
    press(&mut h, "Wavelets");
    press(&mut h, "Threshold");
    assert!(
        h.state().status.contains("set"),
        "status: {}",
        h.state().status
    );
    let denoised = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 10);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    let noisy = vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 10);
    assert_ne!(denoised, noisy);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(
        vertex_control(h.state().doc.scene.objects[0].surface().unwrap(), 10),
        vertex_control(&smooth, 10)
    );
    app = h.into_state();
    assert_eq!(app.doc.undo_name(), Some("subdivide"));
}

#[test]
fn saving_and_reopening_a_scene_gives_the_same_scene() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.json");
    let mut app = App::demo();
    app.doc.scene.objects[1].name = "bowl".into();
    app.doc.scene.objects[1].group = "quadrics".into();
    app.doc.scene.objects[1].material = pssurf_app::scene::Material::Gold;
    app.save_to(path.clone(), pssurf_app::scene::FileKind::Scene);
    assert!(app.error.is_none(), "{:?}", app.error);
    let mut other = App::new(Default::default(), None);
    other.open(path.clone());
    assert!(other.error.is_none(), "{:?}", other.error);
    assert_eq!(other.doc.scene.to_json(), app.doc.scene.to_json());
    assert_eq!(other.doc.scene.objects[1].name, "bowl");
    assert_eq!(other.doc.scene.objects[1].group, "quadrics");
    assert_eq!(
        other.doc.scene.objects[1].material,
        pssurf_app::scene::Material::Gold
    );
    assert_eq!(
        other.doc.scene.objects[1].transform,
        app.doc.scene.objects[1].transform
    );
}

#[test]
fn opening_a_bad_file_shows_a_message_and_keeps_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let mut h = harness(App::demo());
    let before = h.state().doc.scene.to_json();
    for (name, text) in [
        (
            "truncated.json",
            "{\"format\": \"pssurf-scene\", \"version\": 1, \"objects\": [",
        ),
        (
            "nan.json",
            "{\"format\": \"pssurf-scene\", \"version\": 1, \"objects\": [{\"name\": \"a\", \"surface\": {\"format\": \"pssurf\", \"version\": 1, \"kind\": \"functional\", \"vertices\": [[0,0],[1,0],[0,1]], \"triangles\": [[0,1,2]], \"coefficients\": [[NaN,0,0],[0,0,0],[0,0,0]]}}]}",
        ),
        (
            "version.json",
            "{\"format\": \"pssurf-scene\", \"version\": 99, \"objects\": []}",
        ),
        ("missing.json", ""),
    ] {
        let path = dir.path().join(name);
        if !text.is_empty() {
            std::fs::write(&path, text).unwrap();
        }
        h.state_mut().open(path);
        h.run_steps(2);
        assert!(h.state().error.is_some(), "{name}: no message");
        h.get_by_label("Problem");
        h.get_by_label("OK").click();
        h.run_steps(2);
        assert!(h.state().error.is_none());
        assert_eq!(
            h.state().doc.scene.to_json(),
            before,
            "{name}: the scene changed"
        );
    }
}

#[test]
fn shift_clicking_the_domain_view_probes_the_paraboloid_with_its_exact_curvature() {
    let mut app = App::demo();
    app.doc.selection.object = Some(1);
    let mut h = harness(app);
    let rect = h.get_by_label("domain view").rect();
    let pos = rect.center() + vec2(23.0, -11.0);
    click_with(&mut h, pos, Modifiers::SHIFT);
    let app = h.state();
    let p = app.probe().cloned().expect("a probe");
    assert_eq!(p.object, 1);
    assert_eq!(
        app.doc.selection.vertex, None,
        "Shift+click probes instead of selecting"
    );
    // z = (u² + v²)/2: K = 1/W⁴, κ1 = 1/W, κ2 = 1/W³ with W = √(1 + u² + v²).
    let (u, v) = (p.uv.x, p.uv.y);
    let w = (1.0 + u * u + v * v).sqrt();
    let c = p.curvature.as_ref().unwrap();
    assert!((c.gaussian - w.powi(-4)).abs() < 1e-12);
    assert!((c.k1 - 1.0 / w).abs() < 1e-12 && (c.k2 - w.powi(-3)).abs() < 1e-12);
    let cross = p.cross.as_ref().unwrap();
    assert!((cross.curvatures[0] - c.k1).abs() < 1e-12);
    assert!((cross.curvatures[1] - c.k2).abs() < 1e-12);
    // The sections lie on the paraboloid and in their planes (scene coordinates).
    let inverse = app.doc.scene.objects[1]
        .transform
        .matrix()
        .try_inverse()
        .unwrap();
    for k in 0..2 {
        let plane = c.normal.cross(&cross.directions[k]);
        assert!(cross.sections[k].len() > 50);
        for q in &cross.sections[k] {
            let l = inverse.transform_point(&nalgebra::Point3::from(*q));
            assert!((l.z - 0.5 * (l.x * l.x + l.y * l.y)).abs() < 1e-12);
            assert!((q - p.point).dot(&plane).abs() < 1e-12);
        }
    }
    assert!(!app.runtime.probe.lines.lines.is_empty());
    // Parametric alignment turns the planes to s_u and s_v: here the x and y axes.
    h.get_by_label("Probe").click();
    h.run_steps(2);
    h.get_by_label("parametric").click();
    h.run_steps(2);
    let p = h.state().probe().cloned().unwrap();
    let d = p.cross.unwrap().directions;
    let su = nalgebra::Vector3::new(1.0, 0.0, u).normalize();
    assert!((d[0] - su).norm() < 1e-12, "{:?}", d[0]);
}

/// Drags control point 2 of vertex `v` of object 1 by `d` pixels in a view of `rect`.
fn drag(app: &mut App, rect: egui::Rect, v: usize, d: egui::Vec2, along_normal: bool) {
    use pssurf_app::view3d::{DragHandle, drag_point};
    let handle = DragHandle {
        object: 1,
        vertex: v,
        point: 2,
    };
    let c = drag_point(&app.doc, &app.view.camera, rect, handle, d, along_normal).unwrap();
    app.drag_vertex(1, v, c).unwrap();
}

#[test]
fn a_shift_drag_moves_a_control_point_along_the_surface_normal() {
    let mut app = App::demo();
    app.update_geometry();
    app.frame_all(1.5);
    let rect = egui::Rect::from_min_size(Pos2::ZERO, vec2(900.0, 600.0));
    let v = 9;
    let before = vertex_control(app.doc.scene.objects[1].surface().unwrap(), v);
    let [a, b, c] = [before.points[0], before.points[1], before.points[2]];
    let normal = (b - a).cross(&(c - a)).normalize();
    drag(&mut app, rect, v, vec2(4.0, -25.0), true);
    let after = vertex_control(app.doc.scene.objects[1].surface().unwrap(), v);
    let moved = after.points[2] - before.points[2];
    assert!(moved.norm() > 1e-3, "did not move");
    assert!(moved.cross(&normal).norm() < 1e-12 * moved.norm().max(1.0));
    assert_eq!(after.points[..2], before.points[..2]);
    // Without Shift the point moves in the view plane, not along the normal.
    drag(&mut app, rect, v, vec2(25.0, 0.0), false);
    let again = vertex_control(app.doc.scene.objects[1].surface().unwrap(), v);
    let step = again.points[2] - after.points[2];
    assert!(step.cross(&normal).norm() > 1e-3);
}

#[test]
fn the_new_quadric_dialog_adds_an_exact_hyperbolic_paraboloid_that_undo_removes() {
    let mut h = harness(App::demo());
    h.get_by_label("New").click();
    h.run_steps(2);
    h.get_by_label("Quadric…").click();
    h.run_steps(2);
    h.get_by_label("a (x²)").set_value_accesskit(0.8);
    h.get_by_label("c (y²)").set_value_accesskit(-0.3);
    h.get_by_label("b (xy)").set_value_accesskit(0.25);
    h.run_steps(2);
    h.get_by_label("Create").click();
    h.run_steps(3);
    let app = h.state();
    assert_eq!(app.doc.scene.objects.len(), 3, "status: {}", app.status);
    assert_eq!(app.doc.selection.object, Some(2));
    let o = &app.doc.scene.objects[2];
    assert!(o.name.starts_with("hyperbolic paraboloid"), "{}", o.name);
    let s = o.surface().unwrap();
    let tri = s.ps_basis().unwrap().triangulation();
    for t in (0..tri.triangle_count()).step_by(5) {
        let v = tri.triangle(t);
        let c: Point2<f64> =
            ((tri.vertex(v[0]).coords + tri.vertex(v[1]).coords + tri.vertex(v[2]).coords) / 3.0)
                .into();
        let p = s.jet_with(c, &mut s.cursor_near(c)).unwrap().jet.value;
        let z = 0.8 * c.x * c.x + 0.25 * c.x * c.y - 0.3 * c.y * c.y;
        assert!((p - nalgebra::Vector3::new(c.x, c.y, z)).norm() < 1e-12);
    }
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().doc.scene.objects.len(), 2);
}

#[test]
fn the_new_ups_dialog_reports_a_bad_formula_and_adds_nothing() {
    let mut app = App::demo();
    app.views.new_surface.open = true;
    app.views.new_surface.formula = "sqrt(x) + t".into();
    let mut h = harness(app);
    h.get_by_label("Create").click();
    h.run_steps(2);
    let app = h.state();
    assert_eq!(app.doc.scene.objects.len(), 2);
    let e = app.views.new_surface.error.clone().expect("an error");
    assert!(e.contains("`t`"), "{e}");
    assert!(app.views.new_surface.open);
}

#[test]
fn materials_colour_the_shaded_mesh_and_groups_hide_together() {
    use pssurf_app::scene::Material;
    let mut app = App::demo();
    app.view.display.mode = ViewMode::Shaded;
    app.doc.selection.object = Some(1);
    let mut h = harness(app);
    h.get_by_label("material").click();
    h.run_steps(2);
    h.get_by_label("gold").click();
    h.run_steps(2);
    let app = h.state();
    assert_eq!(app.doc.scene.objects[1].material, Material::Gold);
    let gold = Material::Gold.color();
    let mesh = app.object_mesh(1).unwrap();
    assert!(mesh.vertices.iter().all(|v| v.color == gold));
    let clay = Material::Clay.color();
    assert!(
        app.object_mesh(0)
            .unwrap()
            .vertices
            .iter()
            .all(|v| v.color == clay)
    );
    // Put both objects in one group; its checkbox hides both, undo shows them again.
    for object in [1, 0] {
        h.state_mut().doc.selection.object = Some(object);
        h.run_steps(2);
        h.get_by_label("group").click();
        h.run_steps(1);
        h.get_by_label("group").type_text("demo");
        h.run_steps(2);
    }
    assert!(
        h.state()
            .doc
            .scene
            .objects
            .iter()
            .all(|o| o.group == "demo")
    );
    h.get_by_label("visible group demo").click();
    h.run_steps(2);
    assert!(h.state().doc.scene.objects.iter().all(|o| !o.visible));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert!(h.state().doc.scene.objects.iter().all(|o| o.visible));
}

#[test]
fn the_export_dialog_writes_the_selected_mesh_in_scene_placement() {
    let dir = tempfile::tempdir().unwrap();
    let mut app = App::demo();
    app.doc.selection.object = Some(1);
    let mut h = harness(app);
    h.get_by_label("File").click();
    h.run_steps(2);
    h.get_by_label("Export mesh…").click();
    h.run_steps(2);
    assert!(
        h.state()
            .views
            .export
            .path
            .ends_with("NURPS_paraboloid.ply")
    );
    h.get_by_label("format").click();
    h.run_steps(2);
    h.get_by_label("obj").click();
    h.run_steps(2);
    let path = dir.path().join("bowl.obj");
    h.state_mut().views.export.path = path.display().to_string();
    h.run_steps(1);
    h.get_by_role_and_label(egui::accesskit::Role::Button, "Export")
        .click();
    h.run_steps(2);
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let text = std::fs::read_to_string(&path).unwrap();
    let xs: Vec<f64> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect();
    let app = h.state();
    assert_eq!(xs.len(), app.object_mesh(1).unwrap().vertices.len());
    // The paraboloid (x, y, z(x, y)) is moved by 2.6 along x.
    let (lo, hi) = xs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
    let (dlo, dhi) = app.doc.scene.objects[1]
        .surface()
        .unwrap()
        .ps_basis()
        .unwrap()
        .triangulation()
        .bounds();
    assert!(
        (lo - dlo.x - 2.6).abs() < 1e-9 && (hi - dhi.x - 2.6).abs() < 1e-9,
        "{lo} {hi}"
    );
    assert!(!app.views.export.open);
}

#[test]
fn the_camera_moves_from_the_keyboard() {
    let mut h = harness(App::demo());
    let before = h.state().view.camera;
    h.key_press(Key::ArrowLeft);
    h.run_steps(1);
    let after = h.state().view.camera;
    let turned = (after.azimuth_deg - before.azimuth_deg).rem_euclid(360.0);
    assert!((turned - 355.0).abs() < 1e-3, "{turned}");
    h.key_press(Key::Plus);
    h.run_steps(1);
    assert!(h.state().view.camera.half_height < 0.81 * after.half_height);
    h.key_press(Key::F);
    h.run_steps(2);
    assert!(
        (h.state().view.camera.half_height - before.half_height).abs() < 1e-4 * before.half_height,
        "{:?} vs {:?}",
        h.state().view.camera,
        before
    );
}

#[test]
fn a_fixed_colour_range_and_frame_selection_from_the_ui() {
    let mut app = App::demo();
    app.doc.selection.object = Some(1);
    let mut h = harness(app);
    h.get_by_label("fixed").click();
    h.run_steps(2);
    h.get_by_label("range from").set_value_accesskit(-0.5);
    h.run_steps(2);
    h.get_by_label("range to").set_value_accesskit(2.0);
    h.run_steps(3);
    match h.state().runtime.cache.legends.first().map(|l| l.scale) {
        Some(pssurf_viz::colormap::ColorScale::Linear { lo, hi }) => {
            assert_eq!((lo, hi), (-0.5, 2.0));
        }
        ref other => panic!("{other:?}"),
    }
    h.key_press_modifiers(Modifiers::SHIFT, Key::F);
    h.run_steps(2);
    let app = h.state();
    let (lo, hi) = pssurf_app::display::bounds([app.object_mesh(1).unwrap()]).unwrap();
    assert!((app.view.camera.target - 0.5 * (lo + hi)).norm() < 1e-5);
}

#[test]
fn exports_with_bad_settings_fail_with_a_message_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut app = App::demo();
    app.update_geometry();
    let path = dir.path().join("x.png");
    let e = app.export_picture(&path, [8, 600]).unwrap_err();
    assert!(e.contains("between 16 and 8192"), "{e}");
    // No GPU in this test: a clear message instead of a picture.
    let e = app.export_picture(&path, [800, 600]).unwrap_err();
    assert!(e.contains("wgpu"), "{e}");
    app.doc.selection.object = None;
    let e = app
        .export_mesh(&dir.path().join("m.ply"), pssurf_viz::MeshFormat::Ply)
        .unwrap_err();
    assert!(e.contains("select"), "{e}");
    app.views.export.path = "  ".into();
    let run = app.views.export.command();
    app.apply(run);
    assert!(
        app.error
            .as_deref()
            .is_some_and(|e| e.contains("file name"))
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn the_probe_follows_its_object_when_another_is_deleted() {
    let mut app = App::demo();
    app.update_geometry();
    app.set_probe(1, Point2::new(0.1, 0.2));
    let before = app.probe().cloned().unwrap();
    let _ = app.doc.edit::<()>("delete", |s| {
        s.objects.remove(0);
        Ok(())
    });
    app.refresh_probe();
    let p = app.probe().cloned().expect("still probing the paraboloid");
    assert_eq!((p.object, p.id), (0, before.id));
    assert_eq!(p.uv, before.uv);
    // Undo brings the deleted object back in front; the probe moves with the paraboloid.
    app.undo();
    app.refresh_probe();
    assert_eq!(app.probe().unwrap().object, 1);
}
