//! Issue 14: File → Import points (CSV) fits the PS-spline that interpolates them.

use pssurf::surface::{ParametricSurface, Surface};
use pssurf_app::App;
use pssurf_app::command::Command;

#[test]
fn imported_points_become_an_interpolating_surface() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("x,y,z\n");
    let mut data = Vec::new();
    for k in 0..60 {
        // A low-discrepancy set in the unit square.
        let (x, y) = ((k as f64 * 0.618_033_988_75) % 1.0, (k as f64 + 0.5) / 60.0);
        let z = (2.0 * x).sin() * y;
        text.push_str(&format!("{x},{y},{z}\n"));
        data.push((x, y, z));
    }
    let path = dir.path().join("hills.csv");
    std::fs::write(&path, text).unwrap();
    let mut app = App::new(pssurf_app::scene::Scene::default(), None);
    app.apply(Command::AddFile(path));
    assert!(app.error.is_none(), "{:?}", app.error);
    let o = &app.doc.scene.objects[0];
    assert_eq!(o.name, "hills (fit)");
    assert!(matches!(**o.surface().unwrap(), Surface::Functional(_)));
    // It interpolates the data.
    for (x, y, z) in data {
        let p = o
            .surface()
            .unwrap()
            .point(nalgebra::Point2::new(x, y))
            .unwrap();
        assert!((p.z - z).abs() < 1e-12, "at ({x}, {y}): {} vs {z}", p.z);
    }
    // Bad files say which line, and add nothing.
    for (bad, words) in [
        ("x,y,z\n0,0,0\n1,0,nan\n0,1,1\n", "line 3"),
        ("x,y,z\n0,0,0\n1,0\n", "line 3"),
        ("x,y,z\n0,0,0\n1,0,1\n", "at least 3"),
        ("x,y,z\n0,0,0\n1,1,1\n2,2,2\n", ""),
    ] {
        let path = dir.path().join("bad.csv");
        std::fs::write(&path, bad).unwrap();
        let before = app.doc.scene.objects.len();
        app.apply(Command::AddFile(path));
        let e = app.error.clone().unwrap_or_default();
        assert!(!e.is_empty() && e.contains(words), "{bad:?}: {e}");
        assert_eq!(app.doc.scene.objects.len(), before);
    }
}
