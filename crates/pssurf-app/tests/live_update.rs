//! A drag re-tessellates only the edited vertex's molecule, and the result is exactly what a
//! full rebuild gives — in the meshes, in the combined geometry and on the GPU.

use egui_kittest::wgpu::{create_render_state, default_wgpu_setup};
use pssurf::interrogate::{CurvatureQuantity, vertices_per_piece};
use pssurf::surface::PieceKind;
use pssurf_app::App;
use pssurf_app::display::ViewMode;
use pssurf_app::edit::vertex_control;
use pssurf_app::gpu::{ViewRenderer, read_texture};
use pssurf_app::view3d::uniforms;
use pssurf_viz::plot::{Overlays, Range};

/// The demo with a fixed colour range (so a full rebuild colours exactly as the live update)
/// and every overlay on.
fn app() -> App {
    let mut app = App::demo();
    app.view.display.mode = ViewMode::Curvature(CurvatureQuantity::Mean);
    app.view.display.range = Range::Fixed(-2.0, 2.0);
    app.view.display.overlays = Overlays {
        wire: true,
        refinement: true,
        control: true,
        boundary: true,
        combs: false,
    };
    app.view.display.mesh_edges = true;
    app.update_geometry();
    app
}

/// Drags control point 0 of `vertex` of object 1 (the NURPS paraboloid) by `d`.
fn drag(app: &mut App, vertex: usize, d: f64) {
    let mut c = vertex_control(app.doc.scene.objects[1].surface().unwrap(), vertex);
    c.points[0].z += d;
    c.points[1].x -= 0.5 * d;
    app.drag_vertex(1, vertex, c).unwrap();
}

#[test]
fn a_drag_rewrites_only_the_molecule_and_equals_a_full_rebuild() {
    let mut app = app();
    let before = app.runtime.cache.geometry.clone();
    let vertex = 4;
    drag(&mut app, vertex, 0.3);
    let g = app.runtime.cache.geometry.clone();
    assert_eq!(g.history.len(), 1);
    let update = &g.history[0];
    assert_eq!(update.from, before.generation);
    // Exactly the pieces of the molecule: 6 per triangle.
    let surface = app.doc.scene.objects[1].surface().unwrap();
    let molecule = surface
        .ps_basis()
        .unwrap()
        .triangulation()
        .molecule(vertex)
        .len();
    let level = pssurf_app::display::display_level(&app.doc.scene.objects[1], &app.view.display);
    let rewritten: usize = update.vertices.iter().map(|r| r.len()).sum();
    assert_eq!(
        rewritten,
        6 * molecule * vertices_per_piece(PieceKind::Triangle, level)
    );
    // Outside those ranges nothing changed; inside, something did.
    let inside = |k: usize| update.vertices.iter().any(|r| r.contains(&k));
    let mut moved = 0;
    for (k, (a, b)) in before.vertices.iter().zip(&g.vertices).enumerate() {
        if inside(k) {
            moved += usize::from(a != b);
        } else {
            assert_eq!(a, b, "vertex {k} outside the molecule changed");
        }
    }
    assert!(moved > 0);
    let line_inside = |k: usize| update.lines.iter().any(|r| r.contains(&k));
    for (k, (a, b)) in before.lines.iter().zip(&g.lines).enumerate() {
        if !line_inside(k) {
            assert_eq!(a, b, "line vertex {k} outside the molecule changed");
        }
    }
    // A second drag step chains on the first.
    drag(&mut app, vertex, -0.1);
    let g = app.runtime.cache.geometry.clone();
    assert_eq!(g.history.len(), 2);
    assert_eq!(g.history[1].from, g.history[0].to);
    // The same scene built from scratch gives the same geometry, bit for bit.
    let mut fresh = App::new(app.doc.scene.clone(), None);
    fresh.view.display = app.view.display.clone();
    fresh.update_geometry();
    let f = &fresh.runtime.cache.geometry;
    assert_eq!(f.vertices, g.vertices);
    assert_eq!(f.indices, g.indices);
    assert_eq!(f.lines, g.lines);
}

#[test]
fn a_rejected_drag_changes_nothing() {
    let mut app = app();
    let before = app.runtime.cache.geometry.clone();
    let mut c = vertex_control(app.doc.scene.objects[1].surface().unwrap(), 2);
    c.weights = Some(vec![1.0, 0.0, 1.0]);
    assert!(app.drag_vertex(1, 2, c).is_err());
    assert_eq!(app.runtime.cache.geometry.generation, before.generation);
    assert!(app.runtime.cache.geometry.history.is_empty());
}

#[test]
fn the_gpu_gets_only_the_rewritten_ranges_and_draws_what_a_full_upload_draws() {
    let state = create_render_state(
        default_wgpu_setup(),
        eframe::egui_wgpu::RendererOptions::PREDICTABLE,
    );
    let (device, queue) = (&state.device, &state.queue);
    let mut app = app();
    app.frame_all(1.5);
    let size = [300, 200];
    let u = uniforms(&app.view, size);
    let draw = |r: &mut ViewRenderer| {
        let mut encoder = device.create_command_encoder(&Default::default());
        r.render(device, queue, &mut encoder, size, &u);
        queue.submit([encoder.finish()]);
        read_texture(device, queue, r.color_texture().unwrap()).unwrap()
    };
    let mut live = ViewRenderer::new(device);
    live.upload(device, queue, &app.runtime.cache.geometry);
    let first = draw(&mut live);
    drag(&mut app, 4, 0.4);
    drag(&mut app, 4, 0.2);
    live.upload(device, queue, &app.runtime.cache.geometry);
    assert_eq!(live.uploads.full, 1);
    assert_eq!(live.uploads.partial, 1);
    let partial = draw(&mut live);
    let mut full = ViewRenderer::new(device);
    full.upload(device, queue, &app.runtime.cache.geometry);
    let whole = draw(&mut full);
    assert!(partial == whole, "a partial upload draws another picture");
    assert!(first != partial, "the drag changed nothing on screen");
}

/// With curvature combs on, a drag rebuilds the object: its combs follow the new boundary
/// and equal those of a full rebuild.
#[test]
fn combs_follow_a_drag_by_rebuilding_the_object() {
    let mut app = app();
    let plain_lines = app.runtime.cache.geometry.lines.len();
    app.view.display.overlays.combs = true;
    app.update_geometry();
    let with_combs = app.runtime.cache.geometry.lines.clone();
    assert!(
        with_combs.len() > plain_lines,
        "{} {plain_lines}",
        with_combs.len()
    );
    // A boundary vertex of the paraboloid moves: its combs change.
    let tri = app.doc.scene.objects[1]
        .surface()
        .unwrap()
        .ps_basis()
        .unwrap()
        .triangulation()
        .clone();
    let vertex = (0..tri.vertex_count())
        .find(|&v| tri.is_boundary_vertex(v))
        .unwrap();
    drag(&mut app, vertex, 0.3);
    app.update_geometry();
    let after = app.runtime.cache.geometry.lines.clone();
    assert_ne!(after, with_combs);
    // The same as building from scratch.
    let mut fresh = App::demo();
    fresh.view.display = app.view.display.clone();
    fresh.doc.scene = app.doc.scene.clone();
    fresh.update_geometry();
    assert_eq!(fresh.runtime.cache.geometry.lines, after);
}
