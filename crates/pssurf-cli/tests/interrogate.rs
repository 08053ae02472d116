//! End-to-end tests of the interrogation commands: curvature, plot, domain, fairness, export
//! and the showcase.

mod common;

use std::path::Path;

use common::*;

/// A quadratic z = a x² + b xy + c y² sampled with exact gradients on a jittered grid.
fn quadratic_csv(dir: &Path) -> String {
    let mut text = String::from("x,y,z,zx,zy\n");
    for j in 0..6 {
        for i in 0..6 {
            let (x, y) = (i as f64 / 5.0 + 0.01 * ((i * j) % 3) as f64, j as f64 / 5.0);
            let (z, zx, zy) = (
                x * x - 0.7 * x * y + 0.5 * y * y,
                2.0 * x - 0.7 * y,
                -0.7 * x + y,
            );
            text.push_str(&format!("{x},{y},{z},{zx},{zy}\n"));
        }
    }
    s(&write(dir, "quad.csv", &text))
}

#[test]
fn curvature_of_a_reproduced_quadratic_matches_the_closed_form() {
    let d = tmp();
    let surf = s(&d.path().join("q.json"));
    ok(&["fit", &quadratic_csv(d.path()), "-o", &surf]);
    let out = d.path().join("c.npy");
    ok(&[
        "curvature",
        &surf,
        "--grid",
        "9x9",
        "--outside",
        "nan",
        "-o",
        &s(&out),
    ]);
    let (shape, data) = read_npy(&out);
    assert_eq!(shape, vec![81, 17]);
    let mut checked = 0;
    for row in data.chunks(17) {
        let (x, y) = (row[0], row[1]);
        if row[5].is_nan() {
            continue; // outside the (jittered) domain
        }
        let (fx, fy, fxx, fxy, fyy) = (2.0 * x - 0.7 * y, -0.7 * x + y, 2.0, -0.7, 1.0);
        let w2: f64 = 1.0 + fx * fx + fy * fy;
        let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
        let h = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy)
            / (2.0 * w2 * w2.sqrt());
        assert!(
            (row[5] - k).abs() < 1e-10 && (row[6] - h).abs() < 1e-10,
            "{row:?}"
        );
        assert!(
            (row[7] + row[8] - 2.0 * h).abs() < 1e-10
                && (row[9] - row[7].abs() - row[8].abs()).abs() < 1e-12
        );
        let d1 = (row[10].powi(2) + row[11].powi(2) + row[12].powi(2)).sqrt();
        assert!((d1 - 1.0).abs() < 1e-12);
        assert!(
            row[16] >= 0.0 && row[16].fract() == 0.0,
            "patch index {}",
            row[16]
        );
        checked += 1;
    }
    assert!(checked > 50, "{checked}");
    // CSV output has the documented header.
    let csv = ok(&["curvature", &surf, "--grid", "2x2", "--outside", "skip"]);
    assert!(
        csv.starts_with("u,v,x,y,z,K,H,k1,k2,kabs,d1x,d1y,d1z,d2x,d2y,d2z,patch\n"),
        "{csv}"
    );
}

fn ups(dir: &Path) -> String {
    let surf = s(&dir.join("u.json"));
    ok(&[
        "new",
        "ups",
        "--sides",
        "6",
        "--size",
        "2",
        "--height",
        "0.3*sin(2*x)*cos(y)",
        "-o",
        &surf,
    ]);
    surf
}

#[test]
fn plot_writes_pictures_with_legends() {
    let d = tmp();
    let surf = ups(d.path());
    for show in [
        "shaded",
        "gaussian",
        "mean",
        "k1",
        "k2",
        "absolute",
        "zebra",
        "isophotes",
    ] {
        let png = d.path().join(format!("{show}.png"));
        ok(&[
            "plot",
            &surf,
            "--show",
            show,
            "--size",
            "300x200",
            "--level",
            "2",
            "-o",
            &s(&png),
        ]);
        let img = image::open(&png).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (300, 200), "{show}");
        assert_eq!(img.get_pixel(0, 0).0, [255, 255, 255]);
    }
    // Options: seed map with contrast, fixed range, overlays, perspective, flat shading.
    let png = d.path().join("o.png");
    ok(&[
        "plot",
        &surf,
        "--show",
        "mean",
        "--colormap",
        "seed",
        "--contrast",
        "2",
        "--size",
        "320x240",
        "--wire",
        "--refinement",
        "--control",
        "--boundary",
        "--perspective",
        "35",
        "--shading",
        "flat",
        "--view",
        "30,60",
        "-o",
        &s(&png),
    ]);
    ok(&[
        "plot",
        &surf,
        "--show",
        "k1",
        "--range",
        "-1,1",
        "--colormap",
        "viridis",
        "-o",
        &s(&png),
        "--size",
        "100x100",
    ]);
    // A user colour map from a file.
    let stops = write(d.path(), "map.txt", "# blue to red\n0 #0000ff\n1 #ff0000\n");
    ok(&[
        "plot",
        &surf,
        "--show",
        "mean",
        "--colormap",
        &s(&stops),
        "-o",
        &s(&png),
        "--size",
        "100x100",
    ]);
    // Bad options: clear errors and no picture.
    let bad = d.path().join("bad.png");
    for (args, why) in [
        (vec!["--size", "5x5"], "between 16"),
        (vec!["--range", "1"], "--range"),
        (vec!["--range", "2,1"], "increasing"),
        (vec!["--colormap", "nope"], "unknown colour map"),
        (vec!["--contrast", "-1"], "positive"),
        (vec!["--perspective", "200"], "field of view"),
    ] {
        let mut a = vec!["plot", &surf, "--show", "mean", "-o", bad.to_str().unwrap()];
        a.extend(args);
        let err = fails(&a);
        assert!(err.contains(why), "{a:?}: {err}");
        assert!(!bad.exists());
    }
}

#[test]
fn domain_pictures_are_svg() {
    let d = tmp();
    let surf = ups(d.path());
    let svg = d.path().join("d.svg");
    ok(&[
        "domain",
        &surf,
        "--show",
        "triangulation,refinement,ps-points,ps-triangles,labels",
        "--color",
        "H",
        "-o",
        &s(&svg),
    ]);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    for part in [
        "<polygon",
        "<circle",
        "linearGradient",
        // The legend names the quantity with its unit.
        "mean curvature H [1/length]",
        "stroke-dasharray",
    ] {
        assert!(text.contains(part), "missing {part}");
    }
    assert!(
        fails(&["domain", &surf, "--color", "Q", "-o", &s(&svg)])
            .contains("not a curvature quantity")
    );
}

#[test]
fn fairness_reports_integrals() {
    let d = tmp();
    let surf = ups(d.path());
    let json = ok(&["fairness", &surf, "--json"]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let area = v["integrals"]["area"].as_f64().unwrap();
    assert!(area > 10.0 && area < 13.0, "{area}"); // a hexagon of side 2 is 10.39 flat
    assert!(v["integrals"]["mean_squared"].as_f64().unwrap() > 0.0);
    assert_eq!(v["stats"].as_array().unwrap().len(), 5);
    let table = ok(&["fairness", &surf]);
    assert!(
        table.contains("∫ H² dA") && table.contains("p50"),
        "{table}"
    );
    // A plane: no bending at all.
    let flat = s(&d.path().join("flat.json"));
    ok(&[
        "new", "ups", "--sides", "4", "--size", "3", "--height", "0.5*x-y", "-o", &flat,
    ]);
    let v: serde_json::Value = serde_json::from_str(&ok(&["fairness", &flat, "--json"])).unwrap();
    assert!(v["integrals"]["mean_squared"].as_f64().unwrap().abs() < 1e-20);
    assert!(v["integrals"]["thin_plate"].as_f64().unwrap().abs() < 1e-20);
}

#[test]
fn export_writes_every_format() {
    let d = tmp();
    let surf = ups(d.path());
    let pieces = 6 * 24;
    for (ext, level) in [
        ("ply", 1u32),
        ("obj", 1),
        ("stl", 1),
        ("glb", 1),
        ("vtk", 1),
    ] {
        let out = d.path().join(format!("m.{ext}"));
        ok(&[
            "export",
            &surf,
            "--level",
            &level.to_string(),
            "-o",
            &s(&out),
        ]);
        let bytes = std::fs::read(&out).unwrap();
        let (verts, tris) = (pieces * 6, pieces * 4);
        match ext {
            "ply" => assert!(
                String::from_utf8_lossy(&bytes[..400]).contains(&format!("element vertex {verts}"))
            ),
            "obj" => {
                let t = String::from_utf8(bytes).unwrap();
                assert_eq!(t.lines().filter(|l| l.starts_with("v ")).count(), verts);
                assert_eq!(t.lines().filter(|l| l.starts_with("f ")).count(), tris);
            }
            "stl" => assert_eq!(bytes.len(), 84 + 50 * tris),
            "glb" => assert_eq!(&bytes[..4], b"glTF"),
            "vtk" => assert!(
                String::from_utf8_lossy(&bytes[..200]).contains(&format!("POINTS {verts} double"))
            ),
            _ => unreachable!(),
        }
    }
    let out = s(&d.path().join("m.stl"));
    assert!(
        fails(&["export", &surf, "--fields", "K", "-o", &out])
            .contains("cannot store scalar fields")
    );
    assert!(
        fails(&["export", &surf, "-o", &s(&d.path().join("m.xyz"))])
            .contains("unknown mesh format")
    );
    ok(&[
        "export",
        &surf,
        "--format",
        "ply",
        "--fields",
        "K,H",
        "-o",
        &s(&d.path().join("two")),
    ]);
}

#[test]
fn showcase_makes_the_gallery() {
    let d = tmp();
    let dir = d.path().join("gallery");
    ok(&["showcase", "--out", &s(&dir), "--size", "200x150"]);
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    for part in [
        "soft thresholding 5 %",
        "hard thresholding 5 %",
        "soft thresholding 10 %",
        "RMS distance",
        "∫ H² dA",
        "coefficients zeroed",
    ] {
        assert!(html.contains(part), "index.html lacks {part}");
    }
    // Every picture the page shows exists.
    let mut count = 0;
    for piece in html.split("src=\"").skip(1) {
        let name = &piece[..piece.find('"').unwrap()];
        assert!(dir.join(name).is_file(), "{name} missing");
        count += 1;
    }
    // Six surfaces × four pictures, three of the basis function, two domain pictures.
    assert_eq!(count, 6 * 4 + 3 + 2);
}

#[test]
fn view_names_a_missing_file_instead_of_starting_the_application() {
    let err = fails(&["view", "no/such/surface.json"]);
    assert!(
        err.contains("no/such/surface.json") && err.contains("no such file"),
        "{err}"
    );
}

/// q(x, y) = x² − 0.7 xy + 0.5 y² (as a formula for `new ups`) with its curvature.
const Q_FORMULA: &str = "x^2 - 0.7*x*y + 0.5*y^2";

fn q(x: f64, y: f64) -> f64 {
    x * x - 0.7 * x * y + 0.5 * y * y
}

/// Gaussian and mean curvature of the graph of q at (x, y).
fn q_curvature(x: f64, y: f64) -> (f64, f64) {
    let (fx, fy, fxx, fxy, fyy) = (2.0 * x - 0.7 * y, -0.7 * x + y, 2.0, -0.7, 1.0);
    let w2: f64 = 1.0 + fx * fx + fy * fy;
    let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
    let h = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy)
        / (2.0 * w2 * w2.sqrt());
    (k, h)
}

/// The graph of q as a file of every kind: UPS (functional, parametric), the same as general
/// PS surfaces (the `uniform` section removed), NURPS (weights 1), and quadratic Bézier and
/// rational Bézier triangles written by hand.
fn every_kind(dir: &Path) -> Vec<(String, String)> {
    let mut files = Vec::new();
    for kind in ["functional", "parametric"] {
        let ups = s(&dir.join(format!("ups-{kind}.json")));
        ok(&[
            "new", "ups", "--sides", "4", "--size", "3", "--base", "0.3", "--height", Q_FORMULA,
            "--kind", kind, "-o", &ups,
        ]);
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&ups).unwrap()).unwrap();
        v.as_object_mut().unwrap().remove("uniform");
        let general = write(dir, &format!("{kind}.json"), &v.to_string());
        files.push((format!("uniform {kind}"), ups));
        files.push((kind.to_string(), s(&general)));
        if kind == "parametric" {
            let n = v["control_points"].as_array().unwrap().len();
            v["kind"] = "nurps".into();
            v["weights"] = serde_json::json!(vec![[1.0, 1.0, 1.0]; n]);
            files.push(("nurps".into(), s(&write(dir, "nurps.json", &v.to_string()))));
        }
    }
    // The quadratic Bézier triangle of the graph over (0, 0), (1, 0.1), (0.2, 0.9): corner
    // values, and 2 q(mid) − (q(a) + q(b))/2 on the edges.
    let t = [[0.0, 0.0], [1.0, 0.1], [0.2, 0.9]];
    let p = |a: [f64; 2]| [a[0], a[1], q(a[0], a[1])];
    let mid = |i: usize, j: usize| {
        let m = [(t[i][0] + t[j][0]) / 2.0, (t[i][1] + t[j][1]) / 2.0];
        let (pm, pi, pj) = (p(m), p(t[i]), p(t[j]));
        [0, 1, 2].map(|k| 2.0 * pm[k] - (pi[k] + pj[k]) / 2.0)
    };
    let points = [p(t[0]), mid(0, 1), mid(0, 2), p(t[1]), mid(1, 2), p(t[2])];
    let bezier = serde_json::json!({"format": "pssurf", "version": 1, "kind": "bezier",
        "bezier": {"triangle": t, "degree": 2, "points": points}});
    files.push((
        "bezier".into(),
        s(&write(dir, "bezier.json", &bezier.to_string())),
    ));
    let rational = serde_json::json!({"format": "pssurf", "version": 1, "kind": "rational_bezier",
        "bezier": {"triangle": t, "degree": 2, "points": points, "weights": vec![1.0; 6]}});
    files.push((
        "rational_bezier".into(),
        s(&write(dir, "rational.json", &rational.to_string())),
    ));
    // A biquadratic NURBS patch over [0, 1]²: control points by the blossom of each term,
    // u² → (0, 0, 1), u → (0, ½, 1), uv → u-blossom × v-blossom.
    let (u2, u1) = ([0.0, 0.0, 1.0], [0.0, 0.5, 1.0]);
    let mut net = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            net.push([u1[i], u1[j], u2[i] - 0.7 * u1[i] * u1[j] + 0.5 * u2[j]]);
        }
    }
    let nurbs = serde_json::json!({"format": "pssurf", "version": 1, "kind": "nurbs",
        "nurbs": {"degree": [2, 2], "knots": [[0, 0, 0, 1, 1, 1], [0, 0, 0, 1, 1, 1]],
                  "counts": [3, 3], "points": net, "weights": vec![0.5; 9]}});
    files.push((
        "nurbs".into(),
        s(&write(dir, "nurbs.json", &nurbs.to_string())),
    ));
    files
}

#[test]
fn every_kind_goes_through_every_interrogation_command() {
    let d = tmp();
    for (name, file) in every_kind(d.path()) {
        let info: serde_json::Value =
            serde_json::from_str(&ok(&["info", &file, "--json"])).unwrap();
        let kind = info["kind"].as_str().unwrap();
        assert!(name.ends_with(kind), "{name}: {kind}");
        if name == "nurbs" {
            assert_eq!(info["nurbs"]["degrees"], serde_json::json!([2, 2]));
            assert_eq!(info["nurbs"]["net"], serde_json::json!([3, 3]));
            assert_eq!(info["nurbs"]["rational"], true);
        }
        // Curvature: the closed form wherever the grid point is in the domain.
        let c = d.path().join(format!("{name}.npy"));
        ok(&[
            "curvature",
            &file,
            "--grid",
            "7x7",
            "--outside",
            "skip",
            "-o",
            &s(&c),
        ]);
        let (shape, data) = read_npy(&c);
        assert!(shape[0] >= 10, "{name}: only {} points inside", shape[0]);
        for row in data.chunks(shape[1]) {
            let (x, y) = (row[2], row[3]);
            assert!((row[4] - q(x, y)).abs() < 1e-12, "{name}: z at {x}, {y}");
            let (k, h) = q_curvature(x, y);
            assert!((row[5] - k).abs() < 1e-9, "{name}: K {} vs {k}", row[5]);
            assert!((row[6] - h).abs() < 1e-9, "{name}: H {} vs {h}", row[6]);
        }
        // Fairness: the thin-plate energy of the graph is (4 + 2·0.49 + 1) × the area.
        let f: serde_json::Value =
            serde_json::from_str(&ok(&["fairness", &file, "--json"])).unwrap();
        let area = info["domain_area"].as_f64().unwrap();
        let tp = f["integrals"]["thin_plate"].as_f64().unwrap();
        assert!(
            (tp - 5.98 * area).abs() < 1e-9 * area,
            "{name}: {tp} vs {area}"
        );
        // Pictures and meshes.
        let png = d.path().join(format!("{name}.png"));
        ok(&[
            "plot",
            &file,
            "--show",
            "mean",
            "--size",
            "160x120",
            "-o",
            &s(&png),
        ]);
        assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG", "{name}");
        let ply = d.path().join(format!("{name}.ply"));
        ok(&[
            "export",
            &file,
            "--format",
            "ply",
            "--fields",
            "K,H",
            "-o",
            &s(&ply),
        ]);
        assert!(
            std::fs::read_to_string(&ply)
                .unwrap_or_default()
                .starts_with("ply")
                || std::fs::read(&ply).unwrap().starts_with(b"ply"),
            "{name}"
        );
        let svg = d.path().join(format!("{name}.svg"));
        ok(&["domain", &file, "--color", "H", "-o", &s(&svg)]);
        assert!(
            std::fs::read_to_string(&svg).unwrap().contains("<svg"),
            "{name}"
        );
    }
}

/// Noise whose amplitude overflows a coordinate is refused for every kind, and no file is
/// written.
#[test]
fn noise_that_overflows_is_refused_for_every_kind() {
    let d = tmp();
    for (name, file) in every_kind(d.path()) {
        let out = d.path().join(format!("{name}-noisy.json"));
        let err = fails(&[
            "noise",
            &file,
            "--amplitude",
            "1.7e308",
            "--distribution",
            "gaussian",
            "--seed",
            "1",
            "-o",
            &s(&out),
        ]);
        assert!(
            err.contains("would make the surface invalid"),
            "{name}: {err}"
        );
        assert!(!out.exists(), "{name}");
        // Ordinary noise works on every kind and the result loads again.
        ok(&[
            "noise",
            &file,
            "--amplitude",
            "0.01",
            "--seed",
            "1",
            "-o",
            &s(&out),
        ]);
        ok(&["info", &s(&out)]);
    }
}

#[test]
fn trace_writes_level_lines_that_satisfy_the_level_and_read_back() {
    let d = tmp();
    let surf = s(&d.path().join("q.json"));
    ok(&["fit", &quadratic_csv(d.path()), "-o", &surf]);
    let csv = d.path().join("lines.csv");
    let report = ok(&["trace", &surf, "--level", "z=0.05,0.2", "-o", &s(&csv)]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let curves = pssurf::io::read_curves_csv(&text).unwrap();
    assert!(!curves.is_empty(), "{report}");
    let f = |x: f64, y: f64| x * x - 0.7 * x * y + 0.5 * y * y;
    for c in &curves {
        for (uv, p) in c.uvs.iter().zip(&c.points) {
            // The fit reproduces the quadratic, so the level lines are its conics.
            let z = f(uv.x, uv.y);
            assert!((z - 0.05).abs() < 1e-9 || (z - 0.2).abs() < 1e-9, "{z}");
            assert!((p.z - z).abs() < 1e-9);
        }
    }
    for ext in ["obj", "svg"] {
        let out = d.path().join(format!("lines.{ext}"));
        ok(&[
            "trace",
            &surf,
            "--level",
            "K=auto:3",
            "--level",
            "x^2+y^2=0.3",
            "-o",
            &s(&out),
        ]);
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text.contains(if ext == "obj" { "\nl " } else { "<path" }));
        if ext == "obj" {
            // Every line element refers to a written vertex (OBJ counts from 1).
            let vertices = text.lines().filter(|l| l.starts_with("v ")).count();
            for l in text.lines().filter(|l| l.starts_with("l ")) {
                for i in l[2..].split_whitespace() {
                    let i: usize = i.parse().unwrap();
                    assert!((1..=vertices).contains(&i), "{l}");
                }
            }
        }
    }
    // A level that does not occur gives no curves, not an error.
    let none = d.path().join("none.csv");
    ok(&["trace", &surf, "--level", "z=100", "-o", &s(&none)]);
    assert!(
        pssurf::io::read_curves_csv(&std::fs::read_to_string(&none).unwrap())
            .unwrap()
            .is_empty()
    );
    for bad in ["K", "K=", "K=nan", "K=auto:0", "w*2=1", "K=1e999"] {
        let msg = fails(&["trace", &surf, "--level", bad]);
        assert_eq!(msg.trim().lines().count(), 1, "{bad}: {msg}");
    }
    let msg = fails(&[
        "trace",
        &surf,
        "--level",
        "K=0",
        "-o",
        &s(&d.path().join("x.png")),
    ]);
    assert!(msg.contains(".csv, .obj or .svg"), "{msg}");
}

/// z = (x² + y²)/2 on [-1, 1]² (a paraboloid of revolution, reproduced exactly by `fit`).
fn bowl(dir: &Path) -> String {
    let mut text = String::from("x,y,z,zx,zy\n");
    for j in 0..9 {
        for i in 0..9 {
            let (x, y) = (-1.0 + 0.25 * i as f64, -1.0 + 0.25 * j as f64);
            text.push_str(&format!("{x},{y},{},{x},{y}\n", 0.5 * (x * x + y * y)));
        }
    }
    let surf = s(&dir.join("bowl.json"));
    ok(&["fit", &s(&write(dir, "bowl.csv", &text)), "-o", &surf]);
    surf
}

fn read_curves(path: &Path) -> Vec<pssurf::interrogate::SurfaceCurve> {
    pssurf::io::read_curves_csv(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn trace_draws_lines_of_curvature_geodesics_and_the_probe_reports_closed_forms() {
    let d = tmp();
    let surf = bowl(d.path());
    // Lines of κ2 are meridians (straight in the domain through the apex), of κ1 parallels.
    let csv = d.path().join("meridians.csv");
    let report = ok_report(&[
        "trace",
        &surf,
        "--curvature-lines",
        "--family",
        "2",
        "--seeds",
        "8",
        "-o",
        &s(&csv),
    ]);
    assert!(
        report.contains("umbilics: 1 at (") && report.contains("k2-line"),
        "{report}"
    );
    let meridians = read_curves(&csv);
    assert!(meridians.len() >= 4, "{report}");
    for c in &meridians {
        let far = c
            .uvs
            .iter()
            .max_by(|a, b| a.coords.norm().total_cmp(&b.coords.norm()))
            .unwrap();
        let dir = far.coords.normalize();
        for q in &c.uvs {
            assert!(
                (dir.x * q.y - dir.y * q.x).abs() < 1e-7,
                "{q} is off its meridian"
            );
        }
    }
    let seeds = write(d.path(), "seeds.csv", "u,v\n0.3,0.1\n-0.5,0.2\n");
    let parallels = d.path().join("parallels.csv");
    ok(&[
        "trace",
        &surf,
        "--curvature-lines",
        "--family",
        "1",
        "--from",
        &s(&seeds),
        "-o",
        &s(&parallels),
    ]);
    let curves = read_curves(&parallels);
    assert_eq!(curves.len(), 2);
    for (c, r) in curves.iter().zip([0.1f64.hypot(0.3), 0.2f64.hypot(0.5)]) {
        assert!(c.closed, "a parallel inside the square is a closed circle");
        for q in &c.uvs {
            assert!((q.coords.norm() - r).abs() < 1e-7);
        }
    }
    // The shortest geodesic between two points on a meridian runs over the apex; its length
    // is twice the parabola's arc ∫₀^½ √(1 + r²) dr.
    let g = d.path().join("g.csv");
    let report = ok_report(&[
        "trace",
        &surf,
        "--geodesic",
        "--from",
        "-0.5,0",
        "--to",
        "0.5,0",
        "-o",
        &s(&g),
    ]);
    assert!(
        report.contains("a geodesic ending at the target"),
        "{report}"
    );
    let length: f64 = report
        .split("length ")
        .nth(1)
        .and_then(|t| t.split([' ', ';']).next())
        .and_then(|t| t.parse().ok())
        .unwrap();
    let exact = 0.5 * 1.25f64.sqrt() + 0.5f64.asinh();
    assert!((length - exact).abs() < 1e-8, "{length} vs {exact}");
    assert_eq!(read_curves(&g).len(), 1);
    let report = ok_report(&[
        "trace",
        &surf,
        "--geodesic",
        "--from",
        "0,-0.5",
        "--dir",
        "0,1",
        "--length",
        "0.5",
        "-o",
        &s(&g),
    ]);
    assert!(report.contains("the length asked for"), "{report}");
    // The curves show on a picture.
    let png = d.path().join("lines.png");
    ok(&[
        "plot",
        &surf,
        "--lines",
        &s(&csv),
        "--lines",
        &s(&g),
        "--size",
        "200x150",
        "-o",
        &s(&png),
    ]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // …on the domain, and into exported meshes where the format holds lines.
    let svg = d.path().join("lines.svg");
    ok(&["domain", &surf, "--lines", &s(&csv), "-o", &s(&svg)]);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<path"));
    for (ext, tag) in [
        ("ply", &b"element edge "[..]),
        ("vtk", &b"\nLINES "[..]),
        ("obj", &b"\nl "[..]),
    ] {
        let out = d.path().join(format!("mesh.{ext}"));
        ok(&[
            "export",
            &surf,
            "--level",
            "0",
            "--lines",
            &s(&csv),
            "-o",
            &s(&out),
        ]);
        let bytes = std::fs::read(&out).unwrap();
        assert!(bytes.windows(tag.len()).any(|w| w == tag), "{ext}");
    }
    // The probe: K and H of the bowl, the sections' curvatures κ1 and κ2, zero torsion.
    let json = ok(&["probe", &surf, "--at", "0.3,0.2", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let w: f64 = 1.0 + 0.09 + 0.04;
    let (k, h) = (1.0 / (w * w), (2.0 + 0.13) / (2.0 * w.powf(1.5)));
    assert!(
        (v["K"].as_f64().unwrap() - k).abs() < 1e-12
            && (v["H"].as_f64().unwrap() - h).abs() < 1e-12
    );
    let planes = v["cross_planes"].as_array().unwrap();
    assert!(
        (planes[0]["normal_curvature"].as_f64().unwrap() - v["k1"].as_f64().unwrap()).abs() < 1e-12
    );
    let radius = planes[1]["osculating_circle"]["radius"].as_f64().unwrap();
    assert!((radius - 1.0 / v["k2"].as_f64().unwrap()).abs() < 1e-12);
    assert_eq!(v["coordinate_curves"]["u"]["torsion"].as_f64(), Some(0.0));
    let sections = d.path().join("sections.csv");
    assert!(ok(&["probe", &surf, "--at", "0.3,0.2", "-o", &s(&sections)]).contains("κ1 ="));
    let two = read_curves(&sections);
    assert_eq!(two.len(), 2);
    for c in &two {
        for p in &c.points {
            assert!(
                (p.z - 0.5 * (p.x * p.x + p.y * p.y)).abs() < 1e-12,
                "on the bowl"
            );
        }
    }
    // Bad input: one line, non-zero exit.
    for args in [
        vec!["trace", &surf, "--geodesic", "--to", "0,0"],
        vec!["trace", &surf, "--geodesic", "--from", "5,5", "--to", "0,0"],
        vec![
            "trace",
            &surf,
            "--geodesic",
            "--from",
            "0,0",
            "--dir",
            "0,0",
            "--length",
            "1",
        ],
        vec!["trace", &surf, "--curvature-lines", "--from", "nope.csv"],
        vec!["trace", &surf, "--curvature-lines", "--level", "K=0"],
        vec!["trace", &surf, "--curvature-lines", "--step", "1e-300"],
        vec!["trace", &surf, "--curvature-lines", "-o", "lines.png"],
        vec![
            "trace",
            &surf,
            "--geodesic",
            "--from",
            "0,0",
            "--to",
            "nan,0",
        ],
        vec!["probe", &surf, "--at", "9,9"],
        vec!["probe", &surf, "--at", "x"],
        vec!["plot", &surf, "--lines", &surf, "-o", "x.png"],
        vec!["export", &surf, "--lines", &s(&csv), "-o", "x.stl"],
    ] {
        let msg = fails(&args);
        assert_eq!(msg.trim().lines().count(), 1, "{args:?}: {msg}");
    }
}

fn iges_file(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/iges")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn import_writes_a_scene_of_nurbs_surfaces_that_info_and_plot_read() {
    let d = tmp();
    let scene = d.path().join("hammer.json");
    let loops = d.path().join("loops.csv");
    let report = ok_report(&[
        "import",
        &iges_file("hammer.iges"),
        "-o",
        &s(&scene),
        "--loops",
        &s(&loops),
    ]);
    assert!(
        report.contains("45 B-spline surfaces (45 trimmed"),
        "{report}"
    );
    assert!(report.contains("not imported: 402×1"), "{report}");
    assert!(report.contains("trimming is not applied"), "{report}");
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["info", &s(&scene), "--json"])).unwrap();
    let objects = info.as_array().unwrap();
    assert_eq!(objects.len(), 45);
    assert!(
        objects
            .iter()
            .all(|o| o["kind"] == "nurbs" && o["valid"] == true)
    );
    assert!(ok(&["info", &s(&scene)]).starts_with("scene "));
    let curves = read_curves(&loops);
    assert!(curves.len() >= 45, "{} loops", curves.len());
    let png = d.path().join("hammer.png");
    ok(&[
        "plot",
        &s(&scene),
        "--show",
        "absolute",
        "--size",
        "200x150",
        "-o",
        &s(&png),
    ]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // NURBS → UPS: the tolerance is met and reported; the result is a UPS surface file.
    let ups = d.path().join("ups.json");
    let report = ok_report(&[
        "approx",
        &s(&scene),
        "--object",
        "1",
        "--tolerance",
        "0.05",
        "-o",
        &s(&ups),
    ]);
    let last = report
        .lines()
        .rev()
        .find(|l| l.contains("max deviation"))
        .unwrap();
    let max: f64 = last
        .split("max deviation ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(max <= 0.05, "{report}");
    let info: serde_json::Value = serde_json::from_str(&ok(&["info", &s(&ups), "--json"])).unwrap();
    assert_eq!(info["kind"], "parametric");
    for args in [
        vec!["approx", &s(&scene), "-o", &s(&ups)],
        vec!["approx", &s(&scene), "--object", "99", "-o", &s(&ups)],
        vec![
            "approx",
            &s(&scene),
            "--object",
            "0",
            "--nu",
            "3",
            "-o",
            &s(&ups),
        ],
        vec![
            "approx",
            &s(&scene),
            "--object",
            "0",
            "--tolerance",
            "-1",
            "-o",
            &s(&ups),
        ],
    ] {
        let msg = fails(&args);
        assert_eq!(msg.trim().lines().count(), 1, "{args:?}: {msg}");
    }
    // Every sample file imports (one line of report per file at least).
    for name in [
        "BUC50025.igs",
        "OCC131-3.igs",
        "OCC26138_Torus.igs",
        "OCC8842_cone_Ideas.igs",
        "PRO20360-T7.igs",
        "bad_header.igs",
        "bug22566_test_Bad.igs",
        "bug22869_Spring.igs",
        "bug23591_VZ-387.igs",
        "bug24012_face.igs",
        "bug33327.igs",
        "occ22470.igs",
    ] {
        let out = d.path().join(format!("{name}.json"));
        ok(&["import", &iges_file(name), "-o", &s(&out)]);
        ok(&["info", &s(&out)]);
    }
    // Not IGES, truncated IGES, a missing file: one line each, nothing written.
    let text = std::fs::read_to_string(iges_file("bug24012_face.igs")).unwrap();
    let cut = write(d.path(), "cut.igs", &text[..text.len() / 2]);
    let bad = write(d.path(), "bad.igs", "hello\n");
    for input in [s(&cut), s(&bad), s(&d.path().join("missing.igs"))] {
        let out = d.path().join("never.json");
        let msg = fails(&["import", &input, "-o", &s(&out)]);
        assert_eq!(msg.trim().lines().count(), 1, "{msg}");
        assert!(msg.contains("line") || msg.contains("cannot read"), "{msg}");
        assert!(!out.exists());
    }
}

/// `pssurf new cylinder|cone|sphere`: scenes of valid NURPS (or rational Bézier) patches, as
/// many as the construction has; bad sizes are one line each.
#[test]
fn new_quadrics_write_scenes_of_exact_patches() {
    let d = tmp();
    for (args, count, kind) in [
        (
            vec!["cylinder", "--radius", "2", "--height", "3"],
            8,
            "nurps",
        ),
        (vec!["cone", "--form", "bezier"], 6, "rational_bezier"),
        (vec!["sphere", "--sectors", "12"], 24, "nurps"),
    ] {
        let out = d.path().join(format!("{}.json", args[0]));
        let path = s(&out);
        let mut all = vec!["new"];
        all.extend(&args);
        all.extend(["-o", &path]);
        let report = ok_report(&all);
        assert!(report.contains(&format!("of {count} ")), "{report}");
        let info: serde_json::Value =
            serde_json::from_str(&ok(&["info", &s(&out), "--json"])).unwrap();
        let objects = info.as_array().unwrap();
        assert_eq!(objects.len(), count, "{args:?}");
        assert!(
            objects
                .iter()
                .all(|o| o["kind"] == kind && o["valid"] == true),
            "{args:?}"
        );
        if args[0] == "sphere" {
            // r sin²(π/12) / (cos²(π/12) + 1) = 0.0669873 / 1.9330127 = 0.034654…
            assert!(report.contains("0.03465 high"), "{report}");
        }
    }
    for args in [
        vec!["new", "cylinder", "--radius", "0", "-o", "x.json"],
        vec!["new", "cone", "--height", "nan", "-o", "x.json"],
        vec!["new", "sphere", "--radius", "1e300", "-o", "x.json"],
        vec!["new", "sphere", "--sectors", "2", "-o", "x.json"],
    ] {
        let msg = fails(&args);
        assert_eq!(msg.trim().lines().count(), 1, "{args:?}: {msg}");
    }
}

/// `pssurf info` on a curve file: a rational quadratic quarter circle written without knots
/// (a Bézier curve) has length π/2; a surface command names it a curve file.
#[test]
fn info_reads_curve_files() {
    let d = tmp();
    let path = d.path().join("arc.json");
    std::fs::write(
        &path,
        r#"{"format":"pssurf","version":1,"kind":"curve","curve":{"degree":2,"points":[[2,0,0],[2,2,0],[0,2,0]],"weights":[1,0.7071067811865476,1]}}"#,
    )
    .unwrap();
    let info: serde_json::Value =
        serde_json::from_str(&ok(&["info", &s(&path), "--json"])).unwrap();
    assert_eq!(info["kind"], "curve");
    assert_eq!(info["degree"], 2);
    let length = info["length"].as_f64().unwrap();
    assert!((length - std::f64::consts::PI).abs() < 1e-13, "{length}");
    assert_eq!(
        info["inflections"],
        serde_json::json!([]),
        "a circular arc is convex"
    );
    let msg = fails(&["plot", &s(&path), "-o", "x.png"]);
    assert!(msg.contains("a curve file"), "{msg}");
}

/// A loops file that cannot be written stops the import before the scene is written.
#[test]
fn import_with_an_unwritable_loops_file_writes_nothing() {
    let d = tmp();
    let scene = d.path().join("scene.json");
    let loops = d.path().join("no-such-dir").join("loops.csv");
    let msg = fails(&[
        "import",
        &iges_file("hammer.iges"),
        "-o",
        &s(&scene),
        "--loops",
        &s(&loops),
    ]);
    assert_eq!(msg.trim().lines().count(), 1, "{msg}");
    assert!(!scene.exists());
}

/// A scene file (here the sphere's 12 patches) given where one surface is expected is refused
/// with the way to name one object, `SCENE.json#K`, which then works like a surface file.
#[test]
fn one_surface_of_a_scene_is_named_with_its_index() {
    let d = tmp();
    let scene = s(&d.path().join("sphere.json"));
    ok_report(&["new", "sphere", "-o", &scene]);
    let msg = fails(&["fairness", &scene]);
    assert!(
        msg.contains("scene of 12 surfaces") && msg.contains("sphere.json#K"),
        "{msg}"
    );
    let table = ok(&[
        "curvature",
        &format!("{scene}#3"),
        "--grid",
        "6x6",
        "--outside",
        "skip",
    ]);
    let mut rows = 0;
    for line in table.lines().skip(1) {
        let row: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        // A unit sphere: K = 1 and |H| = 1 at every point.
        assert!((row[5] - 1.0).abs() < 1e-10, "{line}");
        assert!((row[6].abs() - 1.0).abs() < 1e-10, "{line}");
        rows += 1;
    }
    assert!(rows > 5, "{table}");
    let msg = fails(&["fairness", &format!("{scene}#12")]);
    assert!(msg.contains("objects 0 to 11"), "{msg}");
}

/// `plot` writes PNG only: a name ending in another extension is refused, and nothing is
/// written (it wrote PNG bytes into x.jpg).
#[test]
fn plot_refuses_a_picture_name_that_is_not_png() {
    let d = tmp();
    let surf = s(&d.path().join("u.json"));
    ok_report(&["new", "ups", "--sides", "3", "--size", "2", "-o", &surf]);
    let jpg = d.path().join("x.jpg");
    let msg = fails(&["plot", &surf, "-o", &s(&jpg)]);
    assert!(msg.contains(".png") && !jpg.exists(), "{msg}");
    ok_report(&["plot", &surf, "-o", &s(&d.path().join("x.PNG"))]);
}
