//! The 3D view drawn by wgpu (on a machine without a GPU: Mesa's lavapipe), checked by
//! properties and against a reference snapshot.

use egui_kittest::SnapshotOptions;
use pssurf_app::App;
use pssurf_app::command::Command;
use pssurf_app::display::ViewMode;
use pssurf_app::headless;

fn is_background(p: &image::Rgba<u8>) -> bool {
    let [r, g, b] = pssurf_app::gpu::BACKGROUND.map(|c| (c * 255.0).round() as i32);
    (p[0] as i32 - r).abs() <= 1 && (p[1] as i32 - g).abs() <= 1 && (p[2] as i32 - b).abs() <= 1
}

#[test]
fn the_demo_scene_renders_with_curvature_colours_and_a_legend() {
    let mut h = headless::harness(App::demo(), 1000.0, 700.0);
    h.run_steps(4);
    let view = {
        use egui_kittest::kittest::Queryable;
        h.get_by_label("3D view").rect()
    };
    let img = h.render().expect("render");
    let (x0, y0, x1, y1) = (
        view.left() as u32 + 2,
        view.top() as u32 + 2,
        view.right() as u32 - 120,
        view.bottom() as u32 - 2,
    );
    let mut surface = 0;
    let mut reds = 0;
    let mut blues = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            let p = img.get_pixel(x, y);
            if !is_background(p) {
                surface += 1;
                reds += (p[0] as i32 > p[2] as i32 + 40) as usize;
                blues += (p[2] as i32 > p[0] as i32 + 40) as usize;
            }
        }
    }
    let area = ((x1 - x0) * (y1 - y0)) as usize;
    assert!(
        surface > area / 20,
        "the surfaces cover only {surface} of {area} pixels"
    );
    // The wave patch has both signs of H (coolwarm: red and blue), the bowl is convex (red).
    assert!(reds > 1000 && blues > 1000, "reds {reds}, blues {blues}");
}

/// Renders the demo in `mode` and compares with `tests/snapshots/NAME.png`.
fn snapshot(name: &str, mode: ViewMode) {
    let mut app = App::demo();
    app.view.display.mode = mode;
    let mut h = headless::harness(app, 900.0, 600.0);
    h.run_steps(4);
    // Software rasterisers differ in the last bit of shading and in edge coverage; a
    // threshold of 2.0 (dify's colour distance) with at most 0.5 % of pixels differing
    // accepts that and catches any change of geometry, camera, colours or stripes.
    let options = SnapshotOptions::new()
        .threshold(2.0)
        .max_failed_pixels(2700);
    h.snapshot_options(name, &options);
}

#[test]
fn the_shaded_view_matches_its_snapshot() {
    snapshot("shaded", ViewMode::Shaded);
}

#[test]
fn the_zebra_view_matches_its_snapshot() {
    snapshot("zebra", ViewMode::Zebra);
}

#[test]
fn export_picture_renders_the_view_offscreen_at_the_requested_size() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("view.png");
    let mut h = headless::harness(App::demo(), 900.0, 600.0);
    h.run_steps(3);
    {
        let app = h.state_mut();
        app.apply(Command::OpenExport(
            pssurf_app::command::ExportKind::Picture,
        ));
        app.views.export.size = [640, 360];
        app.views.export.path = path.display().to_string();
        let run = app.views.export.command();
        app.apply(run);
        assert!(app.error.is_none(), "{:?}", app.error);
    }
    let img = image::open(&path).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (640, 360));
    let surface = img.pixels().filter(|p| !is_background(p)).count();
    // Framed for the picture (the bounding sphere fills its height): both objects, one in
    // each half.
    assert!(surface > 640 * 360 / 30, "only {surface} surface pixels");
    let left = img
        .enumerate_pixels()
        .filter(|(x, _, p)| *x < 320 && !is_background(p))
        .count();
    assert!(
        left > surface / 5 && left < surface * 4 / 5,
        "{left} of {surface} on the left"
    );
}

#[test]
fn the_wireframe_shows_dark_edges_on_the_background_and_nothing_else() {
    let mut app = App::demo();
    app.view.display.mode = ViewMode::Wireframe;
    let mut h = headless::harness(app, 900.0, 600.0);
    h.run_steps(4);
    let view = {
        use egui_kittest::kittest::Queryable;
        h.get_by_label("3D view").rect()
    };
    let img = h.render().expect("render");
    let (mut edges, mut other) = (0, 0);
    for y in view.top() as u32 + 2..view.bottom() as u32 - 2 {
        for x in view.left() as u32 + 2..view.right() as u32 - 2 {
            let p = img.get_pixel(x, y);
            if is_background(p) {
                continue;
            }
            // Edge pixels are grey-blue blends of the edge colour and the background.
            let grey = (p[0] as i32 - p[1] as i32).abs() < 24 && p[2] as i32 >= p[0] as i32 - 4;
            if grey { edges += 1 } else { other += 1 }
        }
    }
    assert!(edges > 5000, "{edges} edge pixels");
    assert!(other < edges / 50, "{other} coloured pixels");
}
