//! The Curves panel (issue 15): lines of curvature, level lines and geodesics traced from the
//! UI, drawn in the views, and following a drag of a control point; the probe's torsion coil.

mod support;

use nalgebra::Point2;
use pssurf::interrogate::{FieldLineOptions, trace_field_line};
use pssurf_app::App;
use pssurf_app::curves::trace;
use pssurf_app::edit::vertex_control;
use support::{harness, press};

/// The demo with the paraboloid z = (u² + v²)/2 (object 1) selected.
fn paraboloid_selected() -> App {
    let mut app = App::demo();
    app.doc.selection.object = Some(1);
    app
}

#[test]
fn lines_of_curvature_from_the_panel_are_meridians_and_parallels_and_follow_a_drag() {
    let mut h = harness(paraboloid_selected());
    press(&mut h, "Curves");
    press(&mut h, "Lines of curvature");
    press(&mut h, "Trace");
    let app = h.state();
    assert!(
        app.status.starts_with("traced lines of curvature"),
        "{}",
        app.status
    );
    let set = &app.runtime.curves.sets[0];
    assert!(set.curves.len() > 10, "{}", set.summary);
    // κ2-lines (the second colour) are meridians: straight through the apex in the domain;
    // κ1-lines are parallels: circles about it.
    let mut meridians = 0;
    for c in &set.curves {
        let uvs = &c.curve.uvs;
        let far = uvs
            .iter()
            .max_by(|a, b| a.coords.norm().total_cmp(&b.coords.norm()))
            .unwrap();
        if c.color == set.curves.last().unwrap().color {
            meridians += 1;
            let d = far.coords.normalize();
            assert!(uvs.iter().all(|q| (d.x * q.y - d.y * q.x).abs() < 1e-7));
        } else {
            let r = uvs[0].coords.norm();
            assert!(uvs.iter().all(|q| (q.coords.norm() - r).abs() < 1e-7));
        }
    }
    assert!(meridians > 3);
    // Drawn: in the 3D view's lines and in the domain view.
    let drawn = app.runtime.extra.lines.len();
    assert!(drawn >= 2 * set.curves.len(), "{drawn} line vertices");
    let id = app.doc.scene.objects[1].id;
    assert_eq!(
        app.runtime.curves.domain_polylines(id).len(),
        set.curves.len()
    );

    // A drag moves one vertex: only the lines through its support are traced again, and
    // they are the lines of the new surface.
    let before = set.clone();
    let mut app = h.into_state();
    let mut c = vertex_control(app.doc.scene.objects[1].surface().unwrap(), 5);
    c.points[0].z += 0.2;
    app.drag_vertex(1, 5, c).unwrap();
    app.refresh_probe();
    let after = &app.runtime.curves.sets[0];
    let o = &app.doc.scene.objects[1];
    assert_eq!(after.revision, o.revision);
    let (mut kept, mut retraced) = (0, 0);
    for (a, b) in before.curves.iter().zip(&after.curves) {
        if a.curve == b.curve {
            kept += 1;
            continue;
        }
        retraced += 1;
        let (family, seed) = b.seed.unwrap();
        let opts = FieldLineOptions {
            max_points: 5_000,
            ..FieldLineOptions::default()
        };
        let fresh = trace_field_line(o.surface().unwrap().as_ref(), family, seed, &opts).unwrap();
        assert_eq!(fresh.curve, b.curve);
    }
    assert!(
        kept > 0 && retraced > 0,
        "{kept} kept, {retraced} traced again"
    );
}

#[test]
fn level_lines_and_a_geodesic_from_the_panel_and_clearing_them() {
    let mut h = harness(paraboloid_selected());
    press(&mut h, "Curves");
    press(&mut h, "Trace");
    let app = h.state();
    assert!(
        app.status.starts_with("traced H = auto:8"),
        "{}",
        app.status
    );
    let set = &app.runtime.curves.sets[0];
    let o = &app.doc.scene.objects[1];
    let (fresh, _) = trace(o.surface().unwrap(), &set.request).unwrap();
    assert_eq!(fresh.len(), set.curves.len());
    assert!(!set.curves.is_empty());
    // A numeric edit changes the surface: the level lines are traced again for it.
    let mut app = h.into_state();
    let mut c = vertex_control(app.doc.scene.objects[1].surface().unwrap(), 7);
    c.points[1].z -= 0.1;
    app.set_vertex(1, 7, c).unwrap();
    app.refresh_probe();
    let set = &app.runtime.curves.sets[0];
    let o = &app.doc.scene.objects[1];
    assert_eq!(set.revision, o.revision);
    let (fresh, _) = trace(o.surface().unwrap(), &set.request).unwrap();
    let same = fresh
        .iter()
        .zip(&set.curves)
        .all(|(a, b)| a.curve == b.curve);
    assert!(same && fresh.len() == set.curves.len());

    // The geodesic: probe, "Start here", probe, "End here", Trace.
    let mut h = harness(app);
    press(&mut h, "Curves");
    press(&mut h, "Shortest geodesic");
    let (start, end) = (Point2::new(-0.3, 0.1), Point2::new(0.4, -0.3));
    h.state_mut().set_probe(1, start);
    h.run_steps(2);
    assert!(h.state().probe().is_some());
    press(&mut h, "Start here");
    h.state_mut().set_probe(1, end);
    h.run_steps(2);
    press(&mut h, "End here");
    press(&mut h, "Trace");
    let app = h.state();
    assert!(
        app.status.contains("geodesic") && app.status.contains("length"),
        "{}",
        app.status
    );
    assert_eq!(app.runtime.curves.sets.len(), 2);
    let g = &app.runtime.curves.sets[1].curves[0].curve;
    assert!((g.uvs[0] - start).norm() < 1e-12);
    assert!((g.uvs.last().unwrap() - end).norm() < 1e-6);
    press(&mut h, "Clear");
    assert!(h.state().runtime.curves.sets.is_empty());
}

#[test]
fn the_torsion_coils_show_with_the_probe_when_switched_on() {
    let mut app = paraboloid_selected();
    app.set_probe(1, Point2::new(0.3, 0.2));
    app.refresh_probe();
    let without = app.runtime.probe.lines.lines.len();
    let p = app.probe().unwrap();
    // A NURPS paraboloid: coordinate curves are parabolas, torsion zero.
    let cc = p.coordinate.as_ref().unwrap();
    assert!(cc.iter().all(|c| c.torsion.unwrap_or(0.0).abs() < 1e-12));
    app.view.probe.coil = true;
    app.refresh_probe();
    assert!(app.runtime.probe.lines.lines.len() > without + 100);
}
