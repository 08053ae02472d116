//! The application's hot paths on a large surface (100k control triangles, 1.2M PS pieces):
//! one drag step (edit → re-tessellate the molecule → upload the rewritten ranges), and the
//! time to draw a frame of 1.2M triangles. The GPU is whatever wgpu finds; on a machine
//! without one that is Mesa's software rasteriser, so frame times are only indicative.

use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use eframe::egui_wgpu::wgpu;
use egui_kittest::wgpu::{create_render_state, default_wgpu_setup};
use pssurf::prelude::*;
use pssurf_app::App;
use pssurf_app::display::ViewMode;
use pssurf_app::edit::vertex_control;
use pssurf_app::gpu::ViewRenderer;
use pssurf_app::scene::{Scene, SceneObject};
use pssurf_app::view3d::uniforms;

/// A functional PS-spline on the Delaunay triangulation of a jittered n × n grid.
fn surface(n: usize) -> Surface {
    let mut pts = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            // A deterministic jitter keeps the Delaunay triangulation unique.
            let h = ((i * 7919 + j * 104_729) % 1000) as f64 / 1000.0 - 0.5;
            let g = ((i * 3571 + j * 6007) % 1000) as f64 / 1000.0 - 0.5;
            let d = if i == 0 || j == 0 || i + 1 == n || j + 1 == n {
                0.0
            } else {
                0.3
            };
            pts.push(Point2::new(i as f64 + d * h, j as f64 + d * g) / (n - 1) as f64);
        }
    }
    let tri = Triangulation::delaunay(pts).expect("grid triangulates");
    let basis = Arc::new(PsBasis::optimal(tri).expect("PS basis"));
    Surface::Functional(
        PsSpline::interpolate(basis, |p| Hermite {
            value: (6.0 * p.x).sin() * (5.0 * p.y).cos() * 0.2,
            dx: 1.2 * (6.0 * p.x).cos() * (5.0 * p.y).cos(),
            dy: -(6.0 * p.x).sin() * (5.0 * p.y).sin(),
        })
        .expect("interpolates"),
    )
}

fn app(mode: ViewMode) -> App {
    let object = SceneObject::new("big", surface(317));
    let mut app = App::new(
        Scene {
            objects: vec![object],
        },
        None,
    );
    app.view.display.mode = mode;
    app.update_geometry();
    app.frame_all(1.6);
    app
}

fn device() -> (wgpu::Device, wgpu::Queue) {
    let state = create_render_state(
        default_wgpu_setup(),
        eframe::egui_wgpu::RendererOptions::PREDICTABLE,
    );
    (state.device.clone(), state.queue.clone())
}

fn wait(device: &wgpu::Device, queue: &wgpu::Queue) {
    let index = queue.submit([]);
    device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: Some(Duration::from_secs(60)),
        })
        .expect("GPU");
}

fn drag_step(c: &mut Criterion) {
    let (device, queue) = device();
    let mut g = c.benchmark_group("app_drag_100k_control_triangles");
    g.throughput(Throughput::Elements(1));
    for (name, mode) in [
        ("shaded", ViewMode::Shaded),
        (
            "mean curvature",
            ViewMode::Curvature(CurvatureQuantity::Mean),
        ),
    ] {
        let mut app = app(mode);
        let vertices = pssurf_app::edit::vertex_count(app.doc.scene.objects[0].surface().unwrap());
        assert!(vertices >= 100_000, "{vertices} vertices");
        let mut renderer = ViewRenderer::new(&device);
        renderer.upload(&device, &queue, &app.runtime.cache.geometry);
        wait(&device, &queue);
        let mut step = 0usize;
        g.bench_function(format!("edit+retessellate+upload/{name}"), |b| {
            b.iter(|| {
                step += 1;
                let v = (step * 7_919) % vertices;
                let mut c = vertex_control(app.doc.scene.objects[0].surface().unwrap(), v);
                c.points[0].z += 1e-3;
                app.drag_vertex(0, v, c).expect("edit");
                renderer.upload(&device, &queue, &app.runtime.cache.geometry);
                wait(&device, &queue);
            })
        });
        assert_eq!(
            renderer.uploads.full, 1,
            "every drag step must be a partial upload"
        );
    }
    g.finish();
    // For comparison: what every edit cost before live updates, a full rebuild and upload.
    let mut g = c.benchmark_group("app_full_rebuild_100k_control_triangles");
    g.sample_size(10);
    let mut app = app(ViewMode::Shaded);
    let mut renderer = ViewRenderer::new(&device);
    g.bench_function("resample+upload whole object/shaded", |b| {
        b.iter(|| {
            app.doc.scene.objects[0].touch();
            app.update_geometry();
            renderer.upload(&device, &queue, &app.runtime.cache.geometry);
            wait(&device, &queue);
        })
    });
    g.finish();
}

fn frame(c: &mut Criterion) {
    let (device, queue) = device();
    let app = app(ViewMode::Shaded);
    let triangles = app.runtime.cache.geometry.indices.len() / 3;
    let mut renderer = ViewRenderer::new(&device);
    renderer.upload(&device, &queue, &app.runtime.cache.geometry);
    let size = [1600, 1000];
    let u = uniforms(&app.view, size);
    let mut g = c.benchmark_group("app_frame");
    g.sample_size(10);
    g.throughput(Throughput::Elements(triangles as u64));
    g.bench_function(format!("draw {triangles} triangles at 1600x1000"), |b| {
        b.iter(|| {
            let mut encoder = device.create_command_encoder(&Default::default());
            renderer.render(&device, &queue, &mut encoder, size, &u);
            queue.submit([encoder.finish()]);
            wait(&device, &queue);
        })
    });
    g.finish();
}

criterion_group!(benches, drag_step, frame);
criterion_main!(benches);
