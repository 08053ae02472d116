//! End-to-end tests of `pssurf curve --subdivide` (issue 20, part 2).

mod common;

use common::*;

#[test]
fn polygons_subdivide_to_the_counts_of_their_schemes_and_four_point_interpolates() {
    let d = tmp();
    let poly = s(&write(d.path(), "p.csv", "x,y\n0,0\n1,0\n2,1\n3,3\n4,6\n"));
    for (scheme, closed, times, count) in [
        ("chaikin", false, 2, 14),
        ("cubic", false, 1, 7),
        ("four-point", false, 3, 33),
        ("chaikin", true, 3, 40),
        ("cubic", true, 1, 10),
    ] {
        let out = d.path().join("o.csv");
        let times = times.to_string();
        let mut args = vec!["curve", &poly, "--subdivide", scheme, "--times", &times];
        if closed {
            args.push("--closed");
        }
        let o = s(&out);
        args.extend(["-o", &o]);
        ok_report(&args);
        let text = std::fs::read_to_string(&out).unwrap();
        assert_eq!(text.lines().count(), count + 1, "{scheme} closed={closed}");
    }
    // The four-point scheme keeps the polygon's points: every 8th point after 3 steps.
    let out = d.path().join("f.csv");
    ok_report(&[
        "curve",
        &poly,
        "--subdivide",
        "four-point",
        "--times",
        "3",
        "-o",
        &s(&out),
    ]);
    let rows: Vec<Vec<f64>> = std::fs::read_to_string(&out)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    for (i, (x, y)) in [(0.0, 0.0), (1.0, 0.0), (2.0, 1.0), (3.0, 3.0), (4.0, 6.0)]
        .iter()
        .enumerate()
    {
        assert_eq!((rows[8 * i][0], rows[8 * i][1]), (*x, *y));
    }
    for args in [
        vec![
            "curve",
            &poly,
            "--subdivide",
            "cubic",
            "--times",
            "41",
            "-o",
            "x.csv",
        ],
        vec![
            "curve",
            &poly,
            "--subdivide",
            "four-point",
            "--tension",
            "nan",
            "-o",
            "x.csv",
        ],
    ] {
        let msg = fails(&args);
        assert_eq!(msg.trim().lines().count(), 1, "{args:?}: {msg}");
    }
    let two = s(&write(d.path(), "two.csv", "x,y\n0,0\n1,0\n"));
    let msg = fails(&["curve", &two, "--subdivide", "cubic", "-o", "x.csv"]);
    assert!(msg.contains("at least 4 points"), "{msg}");
}

/// `--comb` on a rational quadratic arc of radius 2: every tooth has κ = 1/2; SVG and CSV.
#[test]
fn the_comb_of_an_arc_is_constant() {
    let d = tmp();
    let arc = s(&write(
        d.path(),
        "arc.json",
        r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":2,"points":[[2,0,0],[2,2,0],[0,2,0]],"weights":[1,0.7071067811865476,1]}}"#,
    ));
    let csv = d.path().join("comb.csv");
    ok_report(&["curve", &arc, "--comb", "--scale", "1", "-o", &s(&csv)]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut teeth = 0;
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((v[4] - 0.5).abs() < 1e-12, "{line}");
        // The tip is outward, on the circle of radius 2 + 1 × 0.5.
        let r = (v[5] * v[5] + v[6] * v[6]).sqrt();
        assert!((r - 2.5).abs() < 1e-12, "{line}");
        teeth += 1;
    }
    assert_eq!(teeth, 25);
    let svg = d.path().join("comb.svg");
    ok_report(&["curve", &arc, "--comb", "-o", &s(&svg)]);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    let msg = fails(&["curve", &arc, "--comb", "--scale", "1e308", "-o", "x.csv"]);
    assert!(msg.contains("smaller scale"), "{msg}");
    let msg = fails(&[
        "curve",
        "no-such.csv",
        "--subdivide",
        "cubic",
        "-o",
        "x.csv",
    ]);
    assert!(
        msg.contains("no such file") && !msg.contains("os error"),
        "{msg}"
    );
    let poly = s(&write(d.path(), "p.csv", "x,y\n0,0\n1,0\n1,0\n"));
    let msg = fails(&["curve", &poly, "--comb", "-o", &s(&d.path().join("x.svg"))]);
    assert_eq!(msg.trim().lines().count(), 1, "{msg}");
    let huge = s(&write(d.path(), "huge.csv", "x,y\n0,0\n1e308,0\n0,1\n"));
    let msg = fails(&["curve", &huge, "--comb", "-o", &s(&d.path().join("x.csv"))]);
    assert!(msg.contains("row 2") && msg.contains("1e60"), "{msg}");
    assert!(!d.path().join("x.csv").exists());
    let png = d.path().join("comb.png");
    ok_report(&["curve", &arc, "--comb", "-o", &s(&png)]);
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.width(), 800);
    // The curve (black) and the envelope (orange) are drawn.
    assert!(img.pixels().any(|p| p.0 == [0, 0, 0]));
    assert!(img.pixels().any(|p| p.0 == [224, 110, 0]));
    // A line along z has no picture in the (x, y) plane: refused for SVG and PNG (they were
    // written full of NaN), its straight comb written as CSV. A curve whose control points
    // coincide has no defined curvature anywhere: refused, no file.
    let along_z = s(&write(
        d.path(),
        "z.json",
        r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":2,"points":[[0,0,0],[0,0,1],[0,0,3]]}}"#,
    ));
    for ext in ["svg", "png"] {
        let out = d.path().join(format!("z.{ext}"));
        let msg = fails(&["curve", &along_z, "--comb", "-o", &s(&out)]);
        assert!(msg.contains("(x, y) plane") && !out.exists(), "{msg}");
    }
    let z_csv = d.path().join("z.csv");
    ok_report(&["curve", &along_z, "--comb", "-o", &s(&z_csv)]);
    assert!(!std::fs::read_to_string(&z_csv).unwrap().contains("NaN"));
    let point = s(&write(
        d.path(),
        "point.json",
        r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":2,"points":[[1,1,1],[1,1,1],[1,1,1]]}}"#,
    ));
    for ext in ["svg", "csv"] {
        let out = d.path().join(format!("point.{ext}"));
        let msg = fails(&["curve", &point, "--comb", "-o", &s(&out)]);
        assert!(msg.contains("curvature") && !out.exists(), "{msg}");
    }
    // info says so too (it printed "curvature inf to -inf", the empty range).
    let info = ok(&["info", &point]);
    assert!(
        info.contains("undefined") && !info.contains("inf to"),
        "{info}"
    );
}

/// `--comb` on polylines: points on circles (a polygon, and two traced curves in the format
/// `pssurf trace` writes) have κ = 1/R at every point, exactly up to rounding.
#[test]
fn the_comb_of_points_on_a_circle_is_constant() {
    let d = tmp();
    let mut polygon = String::from("x,y\n");
    let mut traced = String::from("curve,u,v,x,y,z\n");
    for k in 0..40 {
        let a = 0.1 * k as f64 + 0.01 * (k * k % 7) as f64;
        polygon.push_str(&format!("{},{}\n", 3.0 * a.cos(), 3.0 * a.sin()));
        traced.push_str(&format!("0,0,0,{},{},0\n", 3.0 * a.cos(), 3.0 * a.sin()));
    }
    for k in 0..20 {
        let a = 0.2 * k as f64;
        traced.push_str(&format!("1,0,0,0.5,{},{}\n", 0.5 * a.cos(), 0.5 * a.sin()));
    }
    let poly = s(&write(d.path(), "circle.csv", &polygon));
    let out = d.path().join("comb.csv");
    ok_report(&["curve", &poly, "--comb", "--scale", "1", "-o", &s(&out)]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("t,x,y,z,kappa"));
    assert_eq!(text.lines().count(), 41);
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((v[4] * 3.0 - 1.0).abs() < 1e-12, "{line}");
    }
    let curves = s(&write(d.path(), "traced.csv", &traced));
    ok_report(&["curve", &curves, "--comb", "-o", &s(&out)]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("curve,t,x,y,z,kappa"));
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let r = if v[0] == 0.0 { 3.0 } else { 0.5 };
        assert!((v[5] * r - 1.0).abs() < 1e-12, "{line}");
    }
    assert_eq!(text.lines().count(), 1 + 40 + 20);
}

#[test]
fn info_reports_the_torsion_of_the_twisted_cubic() {
    let d = tmp();
    let file = write(
        d.path(),
        "twisted.json",
        r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":3,
        "points":[[0,0,0],[0.3333333333333333,0,0],[0.6666666666666666,0.3333333333333333,0],[1,1,1]]}}"#,
    );
    let out = ok(&["info", &s(&file)]);
    // τ = 3/(9t⁴ + 9t² + 1): 3 at t = 0, 3/19 at t = 1; κ(0) = 2.
    let line = out.lines().find(|l| l.starts_with("torsion")).unwrap();
    let v: Vec<f64> = line
        .split_whitespace()
        .filter_map(|x| x.parse().ok())
        .collect();
    assert!(
        (v[0] - 3.0 / 19.0).abs() < 1e-12 && (v[1] - 3.0).abs() < 1e-12,
        "{line}"
    );
    let line = out.lines().find(|l| l.starts_with("curvature")).unwrap();
    assert!(line.contains(" to 2 "), "{line}");
}
