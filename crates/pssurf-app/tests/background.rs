//! Issue 14: rebuilds of many triangles run on another thread while the previous geometry
//! stays drawn, with a busy indicator; the result equals a direct build.

use egui_kittest::kittest::Queryable;
use std::time::{Duration, Instant};

use pssurf_app::App;
use pssurf_app::cache::BACKGROUND_TRIANGLES;
use pssurf_app::create::NewSurface;
use pssurf_app::display::{self, ViewMode};
use pssurf_app::scene::{Scene, SceneObject};

/// Polls the background rebuild until it is done (at most a minute).
fn finish(app: &mut App) {
    let start = Instant::now();
    while app.runtime.cache.busy().is_some() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "meshing never ended"
        );
        std::thread::sleep(Duration::from_millis(5));
        app.update_geometry_in_background();
    }
}

/// The drawn mesh of object 0 equals a direct sampling with the current settings (the
/// colours aside: a curvature plot paints them afterwards).
fn equals_a_direct_build(app: &App) {
    let drawn = app.object_mesh(0).expect("meshed");
    let direct = display::object_mesh(&app.doc.scene.objects[0], &app.view.display);
    let shape = |v: &[display::GpuVertex]| -> Vec<([f32; 3], [f32; 3])> {
        v.iter().map(|v| (v.position, v.normal)).collect()
    };
    assert!(shape(&drawn.vertices) == shape(&direct.vertices));
    assert!(drawn.indices == direct.indices);
    assert!(drawn.values == direct.values);
    assert!(shape(&app.runtime.cache.geometry.vertices) == shape(&direct.vertices));
}

#[test]
fn large_rebuilds_run_in_the_background_and_equal_a_direct_build() {
    let surface = NewSurface {
        size: 32,
        formula: "0.3*sin(3*x)*cos(2*y)".into(),
        ..NewSurface::default()
    }
    .build()
    .unwrap();
    let scene = Scene {
        objects: vec![SceneObject::new("big", surface)],
    };
    let mut app = App::new(scene, None);
    // The first request starts a job: nothing is drawn yet, and the indicator says what runs.
    app.update_geometry_in_background();
    let busy = app
        .runtime
        .cache
        .busy()
        .expect("a large rebuild runs in the background");
    assert!(busy.triangles > BACKGROUND_TRIANGLES);
    assert!(
        busy.message().starts_with("meshing 1 object, about "),
        "{}",
        busy.message()
    );
    assert!(app.object_mesh(0).is_none());
    assert!(app.runtime.cache.geometry.vertices.is_empty());
    finish(&mut app);
    equals_a_direct_build(&app);
    let before = app.runtime.cache.geometry.vertices.clone();

    // A change of sampling while a job runs supersedes it: the old picture stays until the
    // new one is done, and the result is the new settings' mesh.
    app.view.display.mode = ViewMode::Curvature(pssurf::interrogate::CurvatureQuantity::Mean);
    app.update_geometry_in_background();
    assert!(app.runtime.cache.busy().is_some());
    assert_eq!(app.runtime.cache.geometry.vertices, before);
    app.view.display.level = 1;
    app.update_geometry_in_background();
    finish(&mut app);
    equals_a_direct_build(&app);
    assert!(app.legend().is_some());

    // A synchronous update (export, framing) never waits for a job and never leaves one.
    app.view.display.level = 2;
    app.update_geometry_in_background();
    assert!(app.runtime.cache.busy().is_some());
    app.update_geometry();
    assert!(app.runtime.cache.busy().is_none());
    equals_a_direct_build(&app);
}

#[test]
fn small_rebuilds_are_done_at_once() {
    let mut app = App::demo();
    app.update_geometry_in_background();
    assert!(app.runtime.cache.busy().is_none());
    assert!(app.object_mesh(0).is_some());
}

mod support;

/// A task on another thread shows a spinner with what it does, refuses a second one, and its
/// command is applied when it ends.
#[test]
fn background_tasks_show_a_spinner_and_apply_their_result() {
    use pssurf_app::command::{BackgroundWork, Command};
    let (open, gate) = std::sync::mpsc::channel::<()>();
    let mut app = App::demo();
    app.apply(Command::InBackground {
        what: "held work".into(),
        work: BackgroundWork::new(move || {
            let _ = gate.recv();
            Command::Status("work done".into())
        }),
    });
    let mut h = support::harness(app);
    h.get_by_label_contains("held work…");
    h.state_mut().apply(Command::InBackground {
        what: "second".into(),
        work: BackgroundWork::new(|| Command::Status("second done".into())),
    });
    assert!(
        h.state()
            .status
            .contains("wait: held work is still running")
    );
    open.send(()).unwrap();
    let start = Instant::now();
    while h.state_mut().poll_task() {
        assert!(start.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(h.state().status, "work done");
}

/// Subdividing a mesh to more than `BACKGROUND_TRIANGLES` runs as a background task; the
/// result is the library's subdivision, one undo step.
#[test]
fn large_mesh_subdivisions_run_in_the_background() {
    use pssurf::subdivision::{Mesh, SurfaceScheme};
    let control = Mesh::lattice(100, |x, y| 0.01 * (x * y).sin());
    let mut app = App::new(Scene::default(), None);
    let shape =
        pssurf_app::scene::MeshShape::new(pssurf::subdivision::RefinedMesh::new(control.clone()))
            .unwrap();
    app.doc
        .scene
        .objects
        .push(SceneObject::mesh("lattice", shape));
    app.doc.selection.object = Some(0);
    let mut h = support::harness(app);
    support::press(&mut h, "Subdivision");
    support::press(&mut h, "Subdivide");
    let start = Instant::now();
    while h.state_mut().poll_task() {
        assert!(start.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(5));
    }
    let m = h.state().doc.scene.objects[0].mesh_shape().unwrap().clone();
    assert_eq!(m.refined.triangles.len(), 16 * control.triangles.len());
    assert!(16.0 * control.triangles.len() as f64 > BACKGROUND_TRIANGLES);
    let mut expected = control;
    for _ in 0..2 {
        expected = SurfaceScheme::Loop.step(&expected).unwrap();
    }
    assert!(m.refined == expected);
    assert_eq!(h.state().doc.undo_name(), Some("subdivide mesh"));
}
