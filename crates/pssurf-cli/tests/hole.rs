//! End-to-end tests of `pssurf fill-hole` and `pssurf example` (issue 18).

mod common;

use common::*;

/// The G0 and G1 maxima from the report's quality line.
fn quality(report: &str) -> (f64, f64) {
    let line = report.lines().find(|l| l.starts_with("quality")).unwrap();
    let number = |key: &str| -> f64 {
        let rest = &line[line.find(key).unwrap() + key.len()..];
        rest.split([' ', '°']).next().unwrap().parse().unwrap()
    };
    (number("G0 max "), number("G1 max "))
}

/// A triangular hole of three quadratic Bézier curves on the paraboloid z = (x² + y²)/2 … as
/// a specification: straight lines of the plane lifted exactly (the lift of a line is a
/// parabola, a quadratic Bézier curve), normals (−x, −y, 1) as linear curves of vectors.
fn paraboloid_spec() -> String {
    let corners = [
        (1.0f64, 0.0f64),
        (-0.5, 0.75f64.sqrt()),
        (-0.5, -(0.75f64.sqrt())),
    ];
    let z = |x: f64, y: f64| 0.5 * (x * x + y * y);
    let mut curves = Vec::new();
    for k in 0..3 {
        let ((x0, y0), (x1, y1)) = (corners[k], corners[(k + 1) % 3]);
        // The middle Bézier point of the lifted line: ((p0 + p1)/2, z0 + (∇z0 · d)/2).
        let (xm, ym) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let zm = z(x0, y0) + 0.5 * (x0 * (x1 - x0) + y0 * (y1 - y0));
        curves.push(format!(
            r#"{{"degree": 2, "points": [[{x0},{y0},{}],[{xm},{ym},{zm}],[{x1},{y1},{}]],
               "normals": {{"degree": 1, "points": [[{},{},1],[{},{},1]]}}}}"#,
            z(x0, y0),
            z(x1, y1),
            -x0,
            -y0,
            -x1,
            -y1
        ));
    }
    format!(
        r#"{{"format": "pssurf", "version": 1, "kind": "hole", "curves": [{}]}}"#,
        curves.join(",")
    )
}

#[test]
fn a_specified_hole_is_filled_and_the_patch_loads_again() {
    let d = tmp();
    let spec = write(d.path(), "hole.json", &paraboloid_spec());
    let patch = s(&d.path().join("patch.json"));
    let report_file = s(&d.path().join("report.json"));
    let report = ok_report(&[
        "fill-hole",
        &s(&spec),
        "-o",
        &patch,
        "--report",
        &report_file,
    ]);
    assert!(report.contains("iteration"), "{report}");
    let (g0, g1) = quality(&report);
    assert!(g0 < 1e-10 && g1 < 1e-6, "{report}");
    let info = ok(&["info", &patch]);
    assert!(info.to_lowercase().contains("ups"), "{info}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report_file).unwrap()).unwrap();
    assert!(json[0]["g0_max"].as_f64().unwrap() < 1e-10);
    // Every interior method writes a loadable patch.
    for method in [
        "instant",
        "copy",
        "average",
        "subdivision",
        "threshold",
        "fair",
    ] {
        let out = s(&d.path().join(format!("{method}.json")));
        ok_report(&[
            "fill-hole",
            &s(&spec),
            "--interior",
            method,
            "--iterations",
            "3",
            "-o",
            &out,
        ]);
        ok(&["info", &out]);
    }
}

#[test]
fn the_examples_meet_the_quality_goals() {
    let d = tmp();
    for name in [
        "hole-sphere",
        "two-cylinders",
        "prism-cap",
        "two-curve-gap",
        "degenerate-nurbs",
    ] {
        let dir = d.path().join(name);
        let report = ok_report(&["example", name, "-o", &s(&dir)]);
        for line in report.lines().filter(|l| l.starts_with("quality")) {
            let (g0, g1) = quality(line);
            assert!(g1 <= 0.5, "{name}: {line}");
            // G0 against the model size, which the line prints.
            let size: f64 = line
                .split("model size ")
                .nth(1)
                .unwrap()
                .split(')')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            assert!(g0 <= 1e-4 * size, "{name}: {line}");
        }
        assert_eq!(
            report.contains("singular corner between curves"),
            name == "degenerate-nurbs",
            "{report}"
        );
        ok(&["info", &s(&dir.join(format!("{name}.json")))]);
        ok(&["info", &s(&dir.join(format!("{name}-patch-1.json")))]);
    }
}

#[test]
fn bad_hole_specifications_get_one_clear_line() {
    let d = tmp();
    let out = s(&d.path().join("p.json"));
    let two_open = r#"{"format": "pssurf", "version": 1, "kind": "hole", "curves": [
        {"degree": 1, "points": [[0,0,0],[1,0,0]], "normal": [0,0,1]},
        {"degree": 1, "points": [[1,0,0],[0,1,0]], "normal": [0,0,1]},
        {"degree": 1, "points": [[0,1.5,0],[0,0,0]], "normal": [0,0,1]}]}"#;
    let e = fails(&[
        "fill-hole",
        &s(&write(d.path(), "a.json", two_open)),
        "-o",
        &out,
    ]);
    assert!(e.contains("curve 2") && e.lines().count() == 1, "{e}");
    let no_normal = r#"{"format": "pssurf", "version": 1, "kind": "hole", "curves": [
        {"degree": 1, "points": [[0,0,0],[1,0,0]]}]}"#;
    let e = fails(&[
        "fill-hole",
        &s(&write(d.path(), "b.json", no_normal)),
        "-o",
        &out,
    ]);
    assert!(e.contains("curves[0]"), "{e}");
    let along = r#"{"format": "pssurf", "version": 1, "kind": "hole", "curves": [
        {"degree": 1, "points": [[0,0,0],[1,0,0]], "normal": [0,0,1]},
        {"degree": 1, "points": [[1,0,0],[0,1,0]], "normal": [-1,1,0]},
        {"degree": 1, "points": [[0,1,0],[0,0,0]], "normal": [0,0,1]}]}"#;
    let e = fails(&[
        "fill-hole",
        &s(&write(d.path(), "c.json", along)),
        "-o",
        &out,
    ]);
    assert!(e.contains("curve 2") && e.contains("parallel"), "{e}");
    let nan = r#"{"format": "pssurf", "version": 1, "kind": "hole", "curves": [
        {"degree": 1, "points": [[0,0,0],[1,0,NaN]], "normal": [0,0,1]}]}"#;
    fails(&["fill-hole", &s(&write(d.path(), "d.json", nan)), "-o", &out]);
    let seven: Vec<String> = (0..7)
        .map(|k| {
            let a = |i: usize| {
                let t = 2.0 * std::f64::consts::PI * (i % 7) as f64 / 7.0;
                format!("[{},{},0]", t.cos(), t.sin())
            };
            format!(
                r#"{{"degree": 1, "points": [{},{}], "normal": [0,0,1]}}"#,
                a(k),
                a(k + 1)
            )
        })
        .collect();
    let seven = format!(
        r#"{{"format": "pssurf", "version": 1, "kind": "hole", "curves": [{}]}}"#,
        seven.join(",")
    );
    let e = fails(&[
        "fill-hole",
        &s(&write(d.path(), "e.json", &seven)),
        "-o",
        &out,
    ]);
    assert!(e.contains("3 to 6"), "{e}");
    assert!(!std::path::Path::new(&out).exists());
    let e = fails(&[
        "fill-hole",
        &s(&write(d.path(), "f.json", &paraboloid_spec())),
        "--iterations",
        "12",
        "-o",
        &out,
    ]);
    assert!(e.contains("at most 9"), "{e}");
}

#[test]
fn a_hole_between_scene_edges_is_filled() {
    let d = tmp();
    let scene = s(&d.path().join("sphere.json"));
    ok(&["new", "sphere", "--sectors", "6", "-o", &scene]);
    let listing = ok(&["fill-hole", "--scene", &scene, "--list-edges"]);
    assert!(
        listing.contains("1:1") && listing.contains("2:3"),
        "{listing}"
    );
    // The lens between patch 1 (north) and 2 (south): the side of each with both ends on
    // the equator.
    let on_equator = |object: usize| -> String {
        listing
            .lines()
            .filter(|l| l.trim_start().starts_with(&format!("{object}:")))
            .find(|l| {
                let numbers: Vec<f64> = l
                    .split(['(', ')', ','])
                    .filter_map(|x| x.trim().parse().ok())
                    .collect();
                numbers.len() == 6 && numbers[2].abs() < 1e-9 && numbers[5].abs() < 1e-9
            })
            .unwrap()
            .split_whitespace()
            .next()
            .unwrap()
            .to_string()
    };
    let edges = format!("{},{}", on_equator(1), on_equator(2));
    let out = s(&d.path().join("p.json"));
    let report = ok_report(&[
        "fill-hole",
        "--scene",
        &scene,
        "--edges",
        &edges,
        "-o",
        &out,
    ]);
    assert_eq!(
        report.lines().filter(|l| l.starts_with("quality")).count(),
        2,
        "{report}"
    );
    for line in report.lines().filter(|l| l.starts_with("quality")) {
        let (g0, g1) = quality(line);
        assert!(g0 < 1e-4 && g1 <= 0.5, "{line}");
    }
    ok(&["info", &out]);
    let e = fails(&[
        "fill-hole",
        "--scene",
        &scene,
        "--edges",
        "1:9,2:1,2:2",
        "-o",
        &out,
    ]);
    assert!(e.contains("object 1 has sides 1 to 3"), "{e}");
}
