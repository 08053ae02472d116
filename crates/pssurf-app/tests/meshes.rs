//! Issue 20, part 6, and issue 14's mesh import: a triangle mesh opened from OBJ, PLY or STL
//! is a mesh object, refined by Loop, √3 or butterfly from the Subdivision panel, shown with
//! the same shaded, zebra and curvature views, saved in scenes and exported.

mod support;

use egui_kittest::kittest::Queryable;
use pssurf::interrogate::CurvatureQuantity;
use pssurf::subdivision::mesh::discrete_curvature;
use pssurf::subdivision::{Mesh, SurfaceScheme};
use pssurf_app::App;
use pssurf_app::command::Command;
use pssurf_app::display::ViewMode;
use pssurf_app::scene::{FileKind, Scene};
use support::{harness, press};

/// A mesh as OBJ text (1-based indices).
fn obj_text(m: &Mesh) -> String {
    let mut s = String::new();
    for p in &m.positions {
        s.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
    }
    for t in &m.triangles {
        s.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    s
}

/// A bumpy height field over a lattice: curved everywhere, with a boundary.
fn bump() -> Mesh {
    Mesh::lattice(5, |x, y| {
        0.3 * (-(x - 3.5).powi(2) - (y - 2.2).powi(2)).exp()
    })
}

/// Opens `mesh` written as `name.obj` in a new application, the object selected.
fn app_with(dir: &std::path::Path, name: &str, mesh: &Mesh) -> App {
    let path = dir.join(format!("{name}.obj"));
    std::fs::write(&path, obj_text(mesh)).unwrap();
    let mut app = App::new(Scene::default(), None);
    app.apply(Command::AddFile(path));
    assert!(app.error.is_none(), "{:?}", app.error);
    app.doc.selection.object = Some(0);
    app
}

#[test]
fn an_imported_mesh_is_subdivided_from_the_panel_in_one_undo_step() {
    let dir = tempfile::tempdir().unwrap();
    let app = app_with(dir.path(), "bump", &bump());
    let o = &app.doc.scene.objects[0];
    assert_eq!((o.name.as_str(), o.kind_name()), ("bump", "mesh"));
    assert!(o.surface().is_none());
    // The reader may number the vertices in the order the faces use them: the control mesh
    // is the file's, read by the library's reader.
    let control = pssurf_viz::import::read_mesh(&dir.path().join("bump.obj")).unwrap();
    assert_eq!(o.mesh_shape().unwrap().refined, control);

    let mut h = harness(app);
    press(&mut h, "Subdivision");
    // The panel's defaults: Loop, 2 steps.
    press(&mut h, "Subdivide");
    let m = h.state().doc.scene.objects[0].mesh_shape().unwrap().clone();
    let mut expected = control.clone();
    for _ in 0..2 {
        expected = SurfaceScheme::Loop.step(&expected).unwrap();
    }
    assert_eq!(m.refined, expected);
    assert_eq!(m.refined.triangles.len(), 16 * control.triangles.len());
    assert_eq!(m.recipe.control, control);
    assert_eq!(h.state().doc.undo_name(), Some("subdivide mesh"));
    assert!(h.state().status.contains("loop"), "{}", h.state().status);

    // Shaded and zebra views draw the refined mesh with its vertex normals.
    let drawn = h.state().object_mesh(0).unwrap().clone();
    assert_eq!(drawn.indices.len(), 3 * expected.triangles.len());
    for (v, n) in drawn.vertices.iter().zip(expected.vertex_normals()) {
        for k in 0..3 {
            assert!((v.normal[k] - n[k] as f32).abs() < 1e-6);
        }
    }
    // The curvature view colours by the discrete curvature, with a legend fitted to it.
    h.state_mut().view.display.mode = ViewMode::Curvature(CurvatureQuantity::Mean);
    h.run_steps(2);
    let (_, mean) = discrete_curvature(&expected).unwrap();
    let values = &h.state().object_mesh(0).unwrap().values;
    assert_eq!(values.len(), mean.len());
    for (a, b) in values.iter().zip(&mean) {
        assert!(a == b || (a.is_nan() && b.is_nan()));
    }
    let legend = h.state().legend().unwrap().clone();
    let data = legend.data.unwrap();
    let finite: Vec<f64> = mean.iter().copied().filter(|x| x.is_finite()).collect();
    let max = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(data.max, max);

    // "Control mesh" shows the control mesh again; undo brings the subdivision back.
    press(&mut h, "Control mesh");
    assert_eq!(
        h.state().doc.scene.objects[0].mesh_shape().unwrap().refined,
        control
    );
    h.state_mut().apply(Command::Undo);
    assert_eq!(
        h.state().doc.scene.objects[0].mesh_shape().unwrap().refined,
        expected
    );
}

#[test]
fn mesh_objects_save_in_scenes_and_export_with_their_curvature() {
    let dir = tempfile::tempdir().unwrap();
    let mut app = app_with(dir.path(), "octahedron", &Mesh::octahedron());
    let m = app.doc.scene.objects[0].mesh_shape().unwrap().clone();
    let recipe = pssurf::subdivision::RefinedMesh {
        scheme: SurfaceScheme::Sqrt3,
        times: 3,
        ..m.recipe.clone()
    };
    let shape = pssurf_app::scene::MeshShape::new(recipe.clone()).unwrap();
    let id = app.doc.scene.objects[0].id;
    app.apply(Command::ReplaceMesh {
        id,
        what: "subdivide mesh",
        mesh: std::sync::Arc::new(shape),
        status: String::new(),
    });
    // A surface file cannot hold a mesh: saving one says so and writes nothing.
    let surface_path = dir.path().join("mesh.json");
    assert!(
        (app.doc.scene.save_as(&surface_path, FileKind::Surface))
            .unwrap_err()
            .to_string()
            .contains("mesh")
    );
    assert!(!surface_path.exists());
    // A scene keeps the control mesh and the subdivision; the library reads it too.
    let scene_path = dir.path().join("scene.json");
    app.apply(Command::SaveTo {
        path: scene_path.clone(),
        kind: FileKind::Scene,
    });
    assert!(app.error.is_none(), "{:?}", app.error);
    let text = std::fs::read_to_string(&scene_path).unwrap();
    let contents = pssurf::io::scene_contents_from_json(&text).unwrap();
    assert_eq!(contents.meshes.len(), 1);
    assert_eq!(contents.meshes[0].mesh, recipe);
    let (back, _) = Scene::load_file(&scene_path).unwrap();
    let again = back.objects[0].mesh_shape().unwrap();
    assert_eq!(again.recipe, recipe);
    assert_eq!(again.refined.triangles.len(), 8 * 27);

    // Export: the refined mesh with its discrete curvature fields, loading again.
    app.doc.selection.object = Some(0);
    let mut h = harness(app);
    let ply = dir.path().join("mesh.ply");
    h.state_mut().apply(Command::ExportMesh {
        path: ply.clone(),
        format: pssurf_viz::MeshFormat::Ply,
    });
    assert!(h.state().error.is_none(), "{:?}", h.state().error);
    let read = pssurf_viz::import::read_mesh(&ply).unwrap();
    assert_eq!(read.triangles.len(), 8 * 27);
    let header = String::from_utf8_lossy(&std::fs::read(&ply).unwrap()[..600]).into_owned();
    assert!(
        header.contains("property double K") || header.contains("property float K"),
        "{header}"
    );
}

#[test]
fn bad_and_non_manifold_meshes_are_explained() {
    let dir = tempfile::tempdir().unwrap();
    // A non-manifold mesh (three triangles on one edge) is shown, but not subdivided.
    let mut fin = Mesh::octahedron();
    fin.positions.push(nalgebra::Vector3::new(0.3, 0.3, 0.6));
    fin.triangles.push([0, 2, 6]);
    let app = app_with(dir.path(), "fin", &fin);
    let m = app.doc.scene.objects[0].mesh_shape().unwrap().clone();
    assert!(m.curvature.is_err());
    let mut h = harness(app);
    press(&mut h, "Subdivision");
    press(&mut h, "Subdivide");
    h.get_by_label_contains("cannot subdivide: the edge between vertices");
    assert_eq!(
        h.state().doc.scene.objects[0].mesh_shape().unwrap().refined,
        m.refined
    );
    // Files that are not meshes say so with their name, and add nothing.
    let mut app = App::new(Scene::default(), None);
    for (name, text) in [
        ("nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n"),
        ("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"),
        ("empty.obj", "# nothing\n"),
        (
            "cut.stl",
            "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n",
        ),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        app.apply(Command::AddFile(path));
        let e = app.error.take().unwrap_or_default();
        assert!(e.contains(name), "{name}: {e}");
        assert!(app.doc.scene.objects.is_empty());
    }
}
