//! End-to-end tests of the `pssurf` binary.

mod common;

use std::path::Path;

use common::*;

#[test]
fn fit_info_eval_on_the_example() {
    let d = tmp();
    let surf = d.path().join("franke.json");
    ok(&["fit", &example("franke.csv"), "-o", &s(&surf)]);
    let info = ok(&["info", &s(&surf)]);
    assert!(
        info.contains("functional") && info.contains("vertices             400"),
        "{info}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&ok(&["info", &s(&surf), "--json"])).unwrap();
    assert_eq!(json["vertices"], 400);
    assert_eq!(json["basis_functions"], 1200);
    // Grid to .npy with derivatives: u,v,x,y,z + 6 columns; x = u, y = v for a function.
    let npy = d.path().join("g.npy");
    ok(&[
        "eval",
        &s(&surf),
        "--grid",
        "7x5",
        "--derivatives",
        "-o",
        &s(&npy),
    ]);
    let (shape, data) = read_npy(&npy);
    assert_eq!(shape, vec![35, 11]);
    for row in data.chunks(11) {
        assert_eq!(row[0], row[2]);
        assert_eq!(row[1], row[3]);
        assert_eq!((row[5], row[6], row[8], row[9]), (1.0, 0.0, 0.0, 1.0));
        assert!(row[4].is_finite());
    }
    // The same values as CSV.
    let csv = ok(&["eval", &s(&surf), "--grid", "7x5"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "u,v,x,y,z");
    assert_eq!(lines.len(), 36);
    for (line, row) in lines[1..].iter().zip(data.chunks(11)) {
        let z: f64 = line.split(',').nth(4).unwrap().parse().unwrap();
        assert_eq!(z, row[4]);
    }
}

/// `--columns` writes the chosen columns in the chosen order; `--raster` writes z of a grid as
/// an NY × NX array (SciPy's layout of f(X, Y) on a meshgrid), the same numbers as the table.
#[test]
fn eval_writes_chosen_columns_and_rasters() {
    let d = tmp();
    let surf = s(&d.path().join("franke.json"));
    ok(&["fit", &example("franke.csv"), "-o", &surf]);
    // `pssurf eval SURF --grid GRID ARGS…`.
    fn eval<'a>(surf: &'a str, grid: &'a str, rest: &[&'a str]) -> Vec<&'a str> {
        [&["eval", surf, "--grid", grid][..], rest].concat()
    }
    let npy = |name: &str, grid: &str, extra: &[&str]| {
        let path = s(&d.path().join(name));
        ok(&eval(&surf, grid, &[extra, &["-o", &path][..]].concat()));
        read_npy(Path::new(&path))
    };
    let (_, full) = npy("t.npy", "7x5", &[]);
    let (shape, data) = npy("p.npy", "7x5", &["--columns", "z,U"]);
    assert_eq!(shape, vec![35, 2]);
    for (row, f) in data.chunks(2).zip(full.chunks(5)) {
        assert_eq!((row[0], row[1]), (f[4], f[0]));
    }
    let csv = ok(&eval(&surf, "7x5", &["--columns", "v,z"]));
    assert_eq!(csv.lines().next(), Some("v,z"));
    // The raster: 5 rows (v) of 7 numbers (u).
    let (shape, data) = npy("r.npy", "7x5", &["--columns", "z", "--raster"]);
    assert_eq!(shape, vec![5, 7]);
    let z: Vec<f64> = full.chunks(5).map(|f| f[4]).collect();
    assert_eq!(data, z);
    let lines = ok(&eval(&surf, "7x5", &["--columns", "z", "--raster"]));
    let parsed: Vec<Vec<f64>> = lines
        .lines()
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(parsed.len(), 5);
    assert!(parsed.iter().all(|r| r.len() == 7));
    assert_eq!(parsed.concat(), z);
    // A raster larger than one chunk of evaluation (65,536 points) keeps its lines whole.
    let big = ok(&eval(&surf, "301x300", &["--columns", "z", "--raster"]));
    assert_eq!(big.lines().count(), 300);
    assert!(big.lines().all(|l| l.split(',').count() == 301));
    // Refused: unknown or repeated columns (a table our own reader would refuse), several
    // columns or a point list as a raster, skipping points of a raster.
    for (extra, says) in [
        (&["--columns", "w"][..], "no column `w`"),
        (&["--columns", "xu"], "no column `xu`"),
        (&["--columns", "z,x,Z"], "`Z` is named twice"),
        (&["--columns", ""], "no column ``"),
        (&["--columns", "x,z", "--raster"], "one column"),
        (&["--raster"], "one column"),
        (
            &["--columns", "z", "--raster", "--outside", "skip"],
            "every grid point",
        ),
    ] {
        let err = fails(&eval(&surf, "3x3", extra));
        assert!(err.contains(says), "{extra:?}: {err}");
    }
    let pts = s(&write(d.path(), "pts.csv", "u,v\n0.5,0.5\n"));
    let err = fails(&["eval", &surf, "--at", &pts, "--columns", "z", "--raster"]);
    assert!(err.contains("--raster needs --grid"), "{err}");
}

#[test]
fn quadratic_data_is_reproduced_through_the_cli() {
    let d = tmp();
    // With given gradients and triangles, and with estimated gradients on a Delaunay mesh.
    let a = d.path().join("a.json");
    ok(&[
        "fit",
        &example("saddle.csv"),
        "--triangles",
        &example("saddle_triangles.csv"),
        "-o",
        &s(&a),
    ]);
    let mut rows = String::from("x,y,z\n");
    for k in 0..60 {
        let (x, y) = ((k as f64 * 0.618).fract(), (k as f64 * 0.377).fract());
        rows += &format!("{x},{y},{}\n", x * x - y * y + x * y);
    }
    let data = write(d.path(), "q.csv", &rows);
    let b = d.path().join("b.json");
    ok(&["fit", &s(&data), "-o", &s(&b)]);
    // Centroids do not always give a valid refinement; the error says what to do.
    let err = fails(&["fit", &s(&data), "-o", &s(&b), "--split", "centroid"]);
    assert!(err.contains("use --split incenter"), "{err}");
    let pts = write(
        d.path(),
        "pts.csv",
        "u,v\n0.1,0.2\n0.33,0.71\n0.5,0.5\n0.9,0.05\n",
    );
    for surf in [&a, &b] {
        let out = ok(&["eval", &s(surf), "--at", &s(&pts), "--derivatives"]);
        for line in out.lines().skip(1) {
            let v: Vec<f64> = line.split(',').map(|t| t.parse().unwrap()).collect();
            let (x, y) = (v[0], v[1]);
            assert!((v[4] - (x * x - y * y + x * y)).abs() < 1e-13, "{line}");
            assert!(
                (v[7] - (2.0 * x + y)).abs() < 1e-12 && (v[10] - (x - 2.0 * y)).abs() < 1e-12,
                "{line}"
            );
        }
    }
}

#[test]
fn points_outside_the_domain() {
    let d = tmp();
    let surf = d.path().join("s.json");
    ok(&["fit", &example("saddle.csv"), "-o", &s(&surf)]);
    let pts = write(d.path(), "pts.csv", "x,y\n0.5,0.5\n1.5,0.5\n0.25,0.25\n");
    let out = d.path().join("out.csv");
    std::fs::write(&out, "previous").unwrap();
    let err = fails(&["eval", &s(&surf), "--at", &s(&pts), "-o", &s(&out)]);
    assert!(err.contains("row 2") && err.contains("outside"), "{err}");
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "previous",
        "failed runs keep the old file"
    );
    let skip = ok(&["eval", &s(&surf), "--at", &s(&pts), "--outside", "skip"]);
    assert_eq!(skip.lines().count(), 3);
    let nan = ok(&["eval", &s(&surf), "--at", &s(&pts), "--outside", "nan"]);
    assert!(
        nan.lines().nth(2).unwrap().ends_with("nan,nan,nan"),
        "{nan}"
    );
}

#[test]
fn bad_inputs_give_clear_errors_and_no_output() {
    let d = tmp();
    let out = d.path().join("never.json");
    let o = s(&out);
    let cases: Vec<(String, &str)> = vec![
        (
            s(&write(d.path(), "a.csv", "x,y,z\n0,0,1\n1,0,abc\n0,1,2\n")),
            "row 2, column z: `abc` is not a number",
        ),
        (
            s(&write(d.path(), "b.csv", "x,y\n0,0\n1,0\n0,1\n")),
            "needs columns x,y,z",
        ),
        (
            s(&write(
                d.path(),
                "c.csv",
                "x,y,z\n0,0,1\n1,0,1\n0,0,2\n0,1,2\n",
            )),
            "rows 1 and 3 have the same (x, y)",
        ),
        (
            s(&write(d.path(), "e.csv", "x,y,z\n0,0,1\n1,1,1\n2,2,2\n")),
            "collinear",
        ),
        (
            // Ten points within 1e-9 of the line y = 2x: split points cannot be placed in
            // their slivers; the message says why and names rows (it used to ask for the
            // incentres, which were in use).
            s(&write(
                d.path(),
                "line.csv",
                "x,y,z\n0.87024920397008465,1.740498405907617,0.87\n0.28681720908755537,0.57363441958553418,0.28\n0.60314815005156186,1.2062963000554914,0.6\n0.77753408292017878,1.555068168362685,0.77\n0.71607462960356527,1.4321492600333487,0.71\n0.91538012049050754,1.8307602412587956,0.91\n0.86039364918288463,1.7207872977083383,0.86\n0.91823762904876238,1.836475259489994,0.91\n0.026587734467597213,0.053175468428905311,0.02\n0.43724800012950871,0.87449600182896658,0.43\n",
            )),
            "line.csv: rows 4, 3 and 5 are nearly collinear",
        ),
        (
            s(&write(d.path(), "f.csv", "x,y,z\n0,0,NaN\n1,0,1\n0,1,2\n")),
            "not a finite number",
        ),
        (
            s(&write(
                d.path(),
                "g.csv",
                "x,y,z,zx\n0,0,1,1\n1,0,1,1\n0,1,2,1\n",
            )),
            "both zx and zy",
        ),
        (s(&d.path().join("missing.csv")), "cannot read"),
    ];
    for (path, msg) in cases {
        let err = fails(&["fit", &path, "-o", &o]);
        assert!(err.contains(msg), "expected `{msg}` in: {err}");
        assert!(!out.exists());
    }
    let data = write(d.path(), "ok.csv", "x,y,z\n0,0,1\n1,0,1\n0,1,2\n1,1,0\n");
    let tris = write(d.path(), "t.csv", "0,1,2\n1,3,7\n");
    let err = fails(&["fit", &s(&data), "--triangles", &s(&tris), "-o", &o]);
    assert!(err.contains("refers to vertex 7"), "{err}");
    let tris = write(d.path(), "t2.csv", "0,1,2\n0,1,2\n");
    let err = fails(&["fit", &s(&data), "--triangles", &s(&tris), "-o", &o]);
    assert!(err.contains("triangle 1 repeats triangle 0"), "{err}");
    // A broken surface file: the location is named.
    let bad = write(
        d.path(),
        "bad.json",
        "{\"format\":\"pssurf\",\"version\":1,\"kind\":\"functional\",\"domain\":{\"vertices\":[[0,0],[1,0]",
    );
    let err = fails(&["info", &s(&bad)]);
    assert!(
        err.contains("bad.json") && err.contains("line 1, column"),
        "{err}"
    );
    let err = fails(&["eval", &s(&bad), "--grid", "2x2"]);
    assert!(err.contains("bad.json"), "{err}");
    let err = fails(&["eval", &s(&bad), "--grid", "1x5"]);
    assert!(err.contains("at least 2"), "{err}");
    assert!(!out.exists());
}

#[test]
fn help_teaches_the_commands() {
    let help = ok(&["--help"]);
    for cmd in ["fit", "eval", "info"] {
        assert!(help.contains(cmd), "{help}");
    }
    // How to name one surface of a scene.
    assert!(help.contains("SCENE.json#K"), "{help}");
    let fit = ok(&["fit", "--help"]);
    assert!(
        fit.contains("zx,zy") && fit.contains("--triangles"),
        "{fit}"
    );
}

#[test]
fn the_example_in_docs_format_md_loads() {
    let doc =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/format.md"))
            .unwrap();
    let start = doc.find("```json").unwrap() + 7;
    let end = start + doc[start..].find("```").unwrap();
    let d = tmp();
    let f = write(d.path(), "doc.json", &doc[start..end]);
    let info = ok(&["info", &s(&f)]);
    assert!(info.contains("functional"), "{info}");
}

#[test]
fn ups_commands_end_to_end() {
    let d = tmp();
    let ups = d.path().join("ups.json");
    ok(&[
        "new",
        "ups",
        "--sides",
        "6",
        "--size",
        "2",
        "--height",
        "sin(x)*cos(y) + 0.1*x*y",
        "-o",
        &s(&ups),
    ]);
    let info = ok(&["info", &s(&ups)]);
    assert!(
        info.contains("uniform (UPS)") && info.contains("parametric"),
        "{info}"
    );
    // Subdivision does not change the surface.
    let fine = d.path().join("fine.json");
    ok(&["subdivide", &s(&ups), "--times", "2", "-o", &s(&fine)]);
    let pts = write(d.path(), "pts.csv", "u,v\n2.5,1.0\n3.0,2.0\n4.0,1.5\n");
    let a = ok(&["eval", &s(&ups), "--at", &s(&pts), "--derivatives"]);
    let b = ok(&["eval", &s(&fine), "--at", &s(&pts), "--derivatives"]);
    for (la, lb) in a.lines().skip(1).zip(b.lines().skip(1)) {
        let va: Vec<f64> = la.split(',').map(|t| t.parse().unwrap()).collect();
        let vb: Vec<f64> = lb.split(',').map(|t| t.parse().unwrap()).collect();
        for (x, y) in va.iter().zip(&vb) {
            assert!((x - y).abs() < 1e-12, "{la} vs {lb}");
        }
    }
    // Noise is reproducible.
    let (n1, n2, n3) = (
        d.path().join("n1.json"),
        d.path().join("n2.json"),
        d.path().join("n3.json"),
    );
    ok(&[
        "noise",
        &s(&fine),
        "--amplitude",
        "0.01",
        "--seed",
        "3",
        "-o",
        &s(&n1),
    ]);
    ok(&[
        "noise",
        &s(&fine),
        "--amplitude",
        "0.01",
        "--seed",
        "3",
        "-o",
        &s(&n2),
    ]);
    ok(&[
        "noise",
        &s(&fine),
        "--amplitude",
        "0.01",
        "--seed",
        "4",
        "--distribution",
        "gaussian",
        "-o",
        &s(&n3),
    ]);
    assert_eq!(std::fs::read(&n1).unwrap(), std::fs::read(&n2).unwrap());
    assert_ne!(std::fs::read(&n1).unwrap(), std::fs::read(&n3).unwrap());
    // Denoising prints the per-level table and writes a valid UPS surface.
    let clean = d.path().join("clean.json");
    let table = ok(&[
        "denoise",
        &s(&n1),
        "--levels",
        "2",
        "--threshold",
        "5%",
        "--mode",
        "hard",
        "-o",
        &s(&clean),
    ]);
    assert!(
        table.contains("level  coord")
            && table.contains("hard thresholding, 5% of max at every level"),
        "{table}"
    );
    assert_eq!(
        table
            .lines()
            .filter(|l| l.trim_start().starts_with(['1', '2']))
            .count(),
        6,
        "{table}"
    );
    assert!(ok(&["info", &s(&clean)]).contains("uniform (UPS)"));
    for auto in ["universal", "sure", "gcv"] {
        let t = ok(&[
            "denoise",
            &s(&n1),
            "--levels",
            "2",
            "--auto",
            auto,
            "-o",
            &s(&clean),
        ]);
        assert!(t.to_lowercase().contains(auto), "{t}");
    }
    ok(&[
        "denoise",
        &s(&n1),
        "--levels",
        "2",
        "--per-level",
        "10%,0.001",
        "-o",
        &s(&clean),
    ]);
    // The wavelet spectrum and the decomposition file.
    let coeffs = d.path().join("coeffs.json");
    let spec = ok(&["wavelet", &s(&n1), "--levels", "2", "-o", &s(&coeffs)]);
    assert!(spec.contains("histograms"), "{spec}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&coeffs).unwrap()).unwrap();
    assert_eq!(json["format"], "pssurf-wavelet");
    assert_eq!(json["details"].as_array().unwrap().len(), 2);
    assert!(json["coarse"]["uniform"].is_object());
    // A user polygon (an L-shape) and a functional surface.
    let l = d.path().join("l.json");
    ok(&[
        "new",
        "ups",
        "--polygon",
        "0,0 4,0 4,2 2,2 2,4 0,4",
        "--kind",
        "functional",
        "--height",
        "x*y",
        "-o",
        &s(&l),
    ]);
    assert!(ok(&["info", &s(&l)]).contains("functional"));
}

#[test]
fn ups_commands_reject_bad_input() {
    let d = tmp();
    let out = d.path().join("never.json");
    let o = s(&out);
    let general = d.path().join("g.json");
    ok(&["fit", &example("saddle.csv"), "-o", &s(&general)]);
    let e = fails(&["subdivide", &s(&general), "--times", "1", "-o", &o]);
    assert!(e.contains("needs a uniform (UPS) surface"), "{e}");
    assert!(
        e.contains("holds a functional PS surface on a general triangulation"),
        "{e}"
    );
    // A Bézier triangle is named as one (it was called a PS surface).
    let e = fails(&["wavelet", &example("cubic-bezier.json"), "--levels", "1"]);
    assert!(e.contains("this file holds a Bézier triangle"), "{e}");
    let e = fails(&["new", "ups", "--polygon", "0,0 3,1 0,3", "-o", &o]);
    assert!(e.contains("grid line"), "{e}");
    let e = fails(&[
        "new",
        "ups",
        "--sides",
        "3",
        "--size",
        "2",
        "--height",
        "sqrt(x - 5)",
        "-o",
        &o,
    ]);
    assert!(e.contains("no finite value"), "{e}");
    let e = fails(&[
        "new", "ups", "--sides", "3", "--size", "2", "--height", "sin(", "-o", &o,
    ]);
    assert!(e.contains("cannot parse"), "{e}");
    let ups = d.path().join("u.json");
    ok(&["new", "ups", "--sides", "4", "--size", "3", "-o", &s(&ups)]);
    let e = fails(&[
        "denoise",
        &s(&ups),
        "--levels",
        "2",
        "--threshold",
        "5%",
        "-o",
        &o,
    ]);
    assert!(e.contains("allows only 0 coarsening levels"), "{e}");
    let e = fails(&[
        "denoise",
        &s(&ups),
        "--levels",
        "1",
        "--threshold",
        "five",
        "-o",
        &o,
    ]);
    assert!(e.contains("not a number"), "{e}");
    let e = fails(&[
        "denoise",
        &s(&ups),
        "--levels",
        "1",
        "--per-level",
        "1%,2%",
        "-o",
        &o,
    ]);
    assert!(e.contains("2 thresholds for 1 levels"), "{e}");
    let e = fails(&["subdivide", &s(&ups), "--times", "20", "-o", &o]);
    assert!(
        e.contains("would need about") && e.contains("--max-memory"),
        "{e}"
    );
    let e = fails(&[
        "noise",
        &s(&ups),
        "--amplitude",
        "NaN",
        "--seed",
        "1",
        "-o",
        &o,
    ]);
    assert!(e.contains("finite"), "{e}");
    assert!(!out.exists());
}

/// Issue 13 ("every load error is printed twice"): the cause appears once in the message.
#[test]
fn load_errors_are_printed_once() {
    let d = tmp();
    let truncated = write(
        d.path(),
        "t.json",
        "{\"format\":\"pssurf\",\"version\":1,\"kind\":[",
    );
    let missing = d.path().join("missing.json");
    for (file, cause) in [
        (s(&truncated), "EOF while parsing"),
        (s(&missing), "no such file or folder"),
    ] {
        let err = fails(&["info", &file]);
        assert_eq!(err.matches(cause).count(), 1, "{err}");
        assert!(!err.contains("os error"), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}

/// Issue 12, defect 1, as reported: the hull dropped the true corner (1.5, 4) of a PS-point
/// set and `fit` wrote a file that `info` refused.
#[test]
fn fit_writes_a_surface_that_loads_on_the_issue_12_minimal_case() {
    let d = tmp();
    let data = write(
        d.path(),
        "t.csv",
        "x,y,z\n1,4,0\n2,3,0\n3,0,0\n3,1,0\n3,4,0\n4,0,0\n",
    );
    let out = d.path().join("t.json");
    ok(&["fit", &s(&data), "-o", &s(&out)]);
    let info = ok(&["info", &s(&out)]);
    assert!(info.contains("vertices             6"), "{info}");
}

/// Issue 12: the global estimator and the smoothing fit from the command line write
/// surfaces that load, and report what they did.
#[test]
fn fit_global_gradients_and_smoothing_fit_write_loadable_surfaces() {
    let d = tmp();
    let mut csv = String::from("x,y,z\n");
    for k in 0..400 {
        let (x, y) = ((k % 20) as f64 / 19.0, (k / 20) as f64 / 19.0);
        let noise = if k % 2 == 0 { 0.01 } else { -0.01 };
        csv += &format!("{x},{y},{}\n", (3.0 * x).sin() * y + noise);
    }
    let data = write(d.path(), "n.csv", &csv);
    for (method, says) in [
        ("global", "least network curvature"),
        ("jumps", "least Hessian-jump energy"),
    ] {
        let out = d.path().join(format!("{method}.json"));
        let msg = ok_stderr(&["fit", &s(&data), "-o", &s(&out), "--gradients", method]);
        assert!(msg.contains(says), "{msg}");
        ok(&["info", &s(&out)]);
    }
    let out = d.path().join("a.json");
    let msg = ok_stderr(&["fit", &s(&data), "-o", &s(&out), "--approximate", "60"]);
    assert!(
        msg.contains("by GCV") && msg.contains("RMS residual"),
        "{msg}"
    );
    ok(&["info", &s(&out)]);
    let msg = ok_stderr(&[
        "fit",
        &s(&data),
        "-o",
        &s(&out),
        "--approximate",
        "60",
        "--smooth",
        "1e-3",
    ]);
    assert!(msg.contains("λ = 1.000e-3"), "{msg}");
    fails(&[
        "fit",
        &s(&data),
        "-o",
        &s(&out),
        "--approximate",
        "60",
        "--smooth",
        "-1",
    ]);
    fails(&["fit", &s(&data), "-o", &s(&out), "--smooth", "1"]);
    // λ beyond what floating point can balance, and points that leave quadratics free:
    // one line each, naming the cause, and no file.
    let other = d.path().join("other.json");
    let e = fails(&[
        "fit",
        &s(&data),
        "-o",
        &s(&other),
        "--approximate",
        "60",
        "--smooth",
        "1e300",
    ]);
    assert!(
        e.contains("too large") && e.trim_end().lines().count() == 1,
        "{e}"
    );
    let five = write(
        d.path(),
        "five.csv",
        "x,y,z\n0,0,1\n1,0,2\n0,1,1\n1,1,3\n0.5,0.5,1\n",
    );
    let e = fails(&["fit", &s(&five), "-o", &s(&other), "--approximate", "5"]);
    assert!(
        e.contains("quadratics free") && e.trim_end().lines().count() == 1,
        "{e}"
    );
    assert!(!other.exists());
    // Gradient columns are not used by the smoothing fit: a warning says so.
    let with_gradient = write(
        d.path(),
        "g.csv",
        &csv.replace("x,y,z\n", "x,y,z,zx,zy\n")
            .replace("\n", ",0,0\n")
            .replacen("x,y,z,zx,zy,0,0", "x,y,z,zx,zy", 1),
    );
    let msg = ok_stderr(&[
        "fit",
        &s(&with_gradient),
        "-o",
        &s(&out),
        "--approximate",
        "60",
    ]);
    assert!(msg.contains("zx, zy are not used"), "{msg}");
    // The user's own coarse triangulation: its vertices, with or without its triangles.
    let vertices = write(
        d.path(),
        "v.csv",
        "x,y\n0,0\n1,0\n1,1\n0,1\n0.5,0.5\n0.5,0\n1,0.5\n0.5,1\n0,0.5\n",
    );
    let triangles = write(
        d.path(),
        "vt.csv",
        "0,5,4\n5,1,4\n1,6,4\n6,2,4\n2,7,4\n7,3,4\n3,8,4\n8,0,4\n",
    );
    let (data_s, out_s, vertices_s) = (s(&data), s(&out), s(&vertices));
    let triangles_s = s(&triangles);
    for extra in [vec![], vec!["--triangles", triangles_s.as_str()]] {
        let mut args = vec![
            "fit",
            &data_s,
            "-o",
            &out_s,
            "--approximate-on",
            &vertices_s,
            "--smooth",
            "1e-4",
        ];
        args.extend(extra);
        let msg = ok_stderr(&args);
        assert!(msg.contains("on 9 vertices (8 triangles)"), "{msg}");
        let info = ok(&["info", &s(&out)]);
        assert!(info.contains("vertices             9"), "{info}");
    }
    // Data outside the coarse triangulation are named.
    let small = write(d.path(), "s.csv", "x,y\n0,0\n0.9,0\n0,0.9\n0.9,0.9\n");
    let e = fails(&[
        "fit",
        &s(&data),
        "-o",
        &s(&other),
        "--approximate-on",
        &s(&small),
    ]);
    assert!(
        e.contains("lies outside the coarse triangulation") && e.trim_end().lines().count() == 1,
        "{e}"
    );
    let e = fails(&[
        "fit",
        &s(&data),
        "-o",
        &s(&other),
        "--approximate",
        "60",
        "--triangles",
        &s(&triangles),
    ]);
    assert!(e.contains("--approximate-on"), "{e}");
    assert!(!other.exists());
}

/// Writing through a symbolic link updates the file it points to and keeps the link; a
/// directory or a missing directory as output is one clear error.
#[cfg(unix)]
#[test]
fn outputs_never_replace_links_or_directories() {
    let d = tmp();
    let real = d.path().join("real.json");
    let link = d.path().join("link.json");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    ok(&["fit", &example("franke.csv"), "-o", &s(&link)]);
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    ok(&["info", &s(&real)]);
    let e = fails(&["fit", &example("franke.csv"), "-o", &s(d.path())]);
    assert!(
        e.contains("is a directory") && e.trim_end().lines().count() == 1,
        "{e}"
    );
    let missing = d.path().join("no").join("o.json");
    let e = fails(&["fit", &example("franke.csv"), "-o", &s(&missing)]);
    assert!(e.contains("does not exist"), "{e}");
    assert_eq!(
        std::fs::read_dir(d.path()).unwrap().count(),
        2,
        "real and link only"
    );
}

/// pssurf started with its standard output and error piped to this test.
fn spawn_piped(args: &[&str]) -> std::process::Child {
    use std::process::{Command, Stdio};
    Command::new(env!("CARGO_BIN_EXE_pssurf"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// A reader that stops early (`pssurf eval … | head -1`) is not an error: no panic, no
/// message, success.
#[test]
fn a_closed_standard_output_ends_quietly() {
    use std::io::Read;
    let d = tmp();
    let surf = d.path().join("f.json");
    ok(&["fit", &example("franke.csv"), "-o", &s(&surf)]);
    for args in [
        vec!["eval", &s(&surf), "--grid", "700x700"],
        vec!["info", &s(&surf)],
    ] {
        let mut child = spawn_piped(&args);
        let mut first = [0u8; 1];
        child.stdout.take().unwrap().read_exact(&mut first).unwrap();
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success() && err.is_empty(), "{args:?}: {err}");
    }
}

/// A report whose reader has gone (`pssurf denoise … -o clean.json | true`) does not stop
/// the command before its files: denoise and wavelet exited 0 without writing them.
#[test]
fn a_closed_standard_output_does_not_stop_the_files() {
    let d = tmp();
    let ups = new_ups(d.path(), "u.json", 6, 4, "sin(x)*cos(y)");
    let noisy = d.path().join("n.json");
    ok(&["subdivide", &s(&ups), "--times", "2", "-o", &s(&noisy)]);
    ok(&[
        "noise",
        &s(&noisy),
        "--amplitude",
        "0.02",
        "--seed",
        "1",
        "-o",
        &s(&noisy),
    ]);
    let (clean, coeffs) = (d.path().join("c.json"), d.path().join("w.json"));
    for (args, written) in [
        (
            vec![
                "denoise",
                &s(&noisy),
                "--levels",
                "2",
                "--auto",
                "sure",
                "-o",
                &s(&clean),
            ],
            &clean,
        ),
        (
            vec!["wavelet", &s(&noisy), "--levels", "2", "-o", &s(&coeffs)],
            &coeffs,
        ),
    ] {
        let mut child = spawn_piped(&args);
        drop(child.stdout.take()); // the reader is gone before the report is printed
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {err}");
        assert!(written.exists(), "{args:?} wrote nothing: {err}");
    }
    assert!(ok(&["info", &s(&clean)]).contains("valid"));
}

/// A table that fails before its first rows (a point outside, the default `--outside
/// error`) leaves nothing on standard output: its header was printed before the error.
#[test]
fn a_failed_table_prints_nothing() {
    let d = tmp();
    let surf = new_ups(d.path(), "s.json", 6, 2, "x*y");
    let pts = write(d.path(), "p.csv", "u,v\n3,1.7\n30,1\n");
    for command in ["curvature", "eval"] {
        let out = pssurf(&[command, &s(&surf), "--at", &s(&pts)]);
        assert!(!out.status.success(), "{command}");
        assert!(
            out.stdout.is_empty(),
            "{command}: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        assert!(String::from_utf8_lossy(&out.stderr).contains("outside the domain"));
    }
}

/// Runs pssurf, which must succeed, and returns what it printed on standard error.
fn ok_stderr(args: &[&str]) -> String {
    let out = pssurf(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "pssurf {args:?} failed: {err}");
    err
}

/// Issue 12, defect 2, as reported: a 20 × 20 grid with interior points moved by up to 1e-6
/// gave values from −68 to 114 for z = sin(3x) cos(2y).
#[test]
fn fit_gradients_stay_bounded_on_a_nearly_gridded_csv() {
    let d = tmp();
    let mut text = String::from("x,y,z\n");
    let mut seed = 2u64;
    let mut jitter = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * 1e-6
    };
    for i in 0..20 {
        for j in 0..20 {
            let (mut x, mut y) = (i as f64 / 19.0, j as f64 / 19.0);
            if (1..19).contains(&i) && (1..19).contains(&j) {
                x += jitter();
                y += jitter();
            }
            let z = (3.0 * x).sin() * (2.0 * y).cos();
            text += &format!("{x:.17e},{y:.17e},{z:.17e}\n");
        }
    }
    let data = write(d.path(), "nl.csv", &text);
    let out = d.path().join("nl.json");
    ok(&["fit", &s(&data), "-o", &s(&out)]);
    let csv = ok(&["eval", &s(&out), "--grid", "40x40"]);
    let mut worst: f64 = 0.0;
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|t| t.parse().unwrap()).collect();
        let (x, y, z) = (v[0], v[1], v[v.len() - 1]);
        worst = worst.max((z - (3.0 * x).sin() * (2.0 * y).cos()).abs());
    }
    assert!(worst < 3e-3, "max error {worst:e}");
}

/// Issue 12, item 4: nearly collinear rows are a warning naming them, not a failure; nearly
/// duplicate rows are named and merged into their mean (every column), and the fit succeeds.
#[test]
fn fit_warns_about_nearly_duplicate_and_nearly_collinear_rows() {
    let d = tmp();
    let out = d.path().join("w.json");
    // Given triangles with a sliver: rows 1, 2 and 3 lie within 1e-10 of a line.
    let data = write(
        d.path(),
        "c.csv",
        "x,y,z\n0,0,0\n2,0,1\n1,0.0000000001,1\n1,-1,0\n",
    );
    let tris = write(d.path(), "c_tri.csv", "0,1,2\n0,3,1\n");
    let run = pssurf(&["fit", &s(&data), "--triangles", &s(&tris), "-o", &s(&out)]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    assert!(
        err.contains("warning: rows 1, 2 and 3 are nearly collinear"),
        "{err}"
    );
    ok(&["info", &s(&out)]);
    // Without given triangles, the hull sliver (rows 1, 2, 3: row 3 is 1e-10 inside the
    // hull edge from row 1 to row 2) is left out of the domain, with a warning.
    let data = write(d.path(), "h.csv", "x,y,z\n0,0,0\n2,0,1\n1,1e-10,1\n1,1,0\n");
    let err = ok_stderr(&["fit", &s(&data), "-o", &s(&out)]);
    assert!(
        err.contains("are nearly collinear on the boundary"),
        "{err}"
    );
    for r in ["1", "2", "3"] {
        assert!(err.contains(r), "{err}");
    }
    assert!(
        err.contains("fitted 4 rows on 4 vertices (2 triangles"),
        "{err}"
    );
    ok(&["info", &s(&out)]);
    // Rows 2 and 6 are 1e-12 apart.
    let data = write(
        d.path(),
        "n.csv",
        "x,y,z\n0,0,0\n1,0,1\n0,1,1\n2,1,0\n3,3,1\n1.000000000001,0,1\n",
    );
    let run = pssurf(&["fit", &s(&data), "-o", &s(&out)]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{err}");
    assert!(
        err.contains(
            "warning: rows 2 and 6 are only 1.00e-12 apart (under 4.24e-9, nearly coincident for this data's extent and coordinates): merged into one point with their mean"
        ),
        "{err}"
    );
    assert!(err.contains("fitted 6 rows on 5 vertices"), "{err}");
    // The merged vertex carries the mean of the rows' values, (1 + 1) / 2, exactly.
    let pts = write(d.path(), "at.csv", "x,y\n1.0000000000005,0\n");
    let at = ok(&["eval", &s(&out), "--at", &s(&pts)]);
    let z: f64 = at
        .lines()
        .nth(1)
        .unwrap()
        .rsplit(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((z - 1.0).abs() < 1e-9, "{z}");
}

/// A value of 1e308 in row 3 is named there: it was found only through the control values
/// of a neighbour whose estimated gradient it spoiled, and row 1 was named.
#[test]
fn a_value_beyond_1e60_is_named_by_its_own_row() {
    let d = tmp();
    let out = d.path().join("never.json");
    let data = write(
        d.path(),
        "v.csv",
        "x,y,z\n0,0,0\n1,0,1\n0,1,1e308\n1,1,2\n0.5,0.3,1\n",
    );
    let (data, out) = (s(&data), s(&out));
    for extra in [&[][..], &["--approximate", "4"][..]] {
        // The smoothing fit said only "the fitted surface does not fit in floating point".
        let mut args = vec!["fit", data.as_str(), "-o", out.as_str()];
        args.extend_from_slice(extra);
        let e = fails(&args);
        assert!(
            e.contains("row 3: z = 1e308 is beyond ±1e60"),
            "{extra:?}: {e}"
        );
        assert!(!std::path::Path::new(&out).exists());
    }
}

/// Issue 13: "a coordinate of 1e308 is reported as collinear". Coordinates beyond ±1e60
/// (where areas overflow) are refused as out of range, naming the row, with no output.
#[test]
fn a_coordinate_of_1e308_is_not_reported_as_collinear() {
    let d = tmp();
    let out = d.path().join("never.json");
    let data = write(d.path(), "big.csv", "x,y,z\n0,0,0\n1e308,0,1\n0,1,2\n");
    let e = fails(&["fit", &s(&data), "-o", &s(&out)]);
    assert!(
        e.contains("row 2: a coordinate outside the range") && !e.contains("collinear"),
        "{e}"
    );
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(!out.exists());
    // The smoothing fit too (its grid would have panicked on 1e152).
    let data = write(
        d.path(),
        "big2.csv",
        "x,y,z\n0,0,0\n1e152,0,1\n0,1e152,2\n1e152,1e152,3\n5e151,5e151,1\n",
    );
    // And tiny nonzero ones, which the Delaunay triangulation cannot take (they were
    // "collinear or too few" too).
    let tiny = write(
        d.path(),
        "tiny.csv",
        "x,y,z\n0,0,0\n1,0,1\n1e-100,0.5,1\n0,1,2\n1,1,3\n",
    );
    let e = fails(&["fit", &s(&tiny), "-o", &s(&out)]);
    assert!(e.contains("row 3: a coordinate outside the range"), "{e}");
    for m in ["3", "100"] {
        let e = fails(&["fit", &s(&data), "-o", &s(&out), "--approximate", m]);
        assert!(e.contains("row 2: a coordinate outside the range"), "{e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    }
    assert!(!out.exists());
}

/// Found by trying `fit` as a careless user: each input gets one clear line naming the cause.
#[test]
fn careless_inputs_to_fit_get_one_clear_line() {
    let d = tmp();
    let out = d.path().join("never.json");
    let long = "9".repeat(100_000);
    let cases: Vec<(String, &str)> = vec![
        // A repeated column name (the first `z` used to be taken silently).
        (
            s(&write(
                d.path(),
                "dup.csv",
                "x,y,z,Z\n0,0,0,1\n1,0,1,1\n0,1,1,1\n",
            )),
            "the column name `Z` appears twice",
        ),
        // Tabs instead of commas (used to complain about a number).
        (
            s(&write(
                d.path(),
                "tab.csv",
                "x\ty\tz\n0\t0\t1\n1\t0\t1\n0\t1\t2\n",
            )),
            "columns must be separated by commas",
        ),
        // A huge cell is shortened in the message.
        (
            s(&write(
                d.path(),
                "long.csv",
                &format!("x,y,z\n0,0,1\n1,0,{long}x\n0,1,2\n"),
            )),
            "is not a number",
        ),
    ];
    for (file, want) in cases {
        let e = fails(&["fit", &file, "-o", &s(&out)]);
        assert!(e.contains(want), "{file}: {e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{file}: {e}");
        assert!(e.len() < 300, "{file}: {} bytes", e.len());
    }
    // A bad first line of a triangles file is an error, not a header skipped silently.
    let data = write(d.path(), "q.csv", "x,y,z\n0,0,0\n1,0,1\n1,1,2\n0,1,1\n");
    let tris = write(d.path(), "t.csv", "3,0,-4\n0,1,2\n");
    let e = fails(&["fit", &s(&data), "--triangles", &s(&tris), "-o", &s(&out)]);
    assert!(e.contains("line 1 is not three vertex indices"), "{e}");
    assert!(!out.exists());
    // Columns `fit` does not use may hold text.
    let data = write(
        d.path(),
        "named.csv",
        "x,y,z,name\n0,0,0,a\n1,0,1,b\n1,1,2,c\n0,1,1,d\n",
    );
    ok(&["fit", &s(&data), "-o", &s(&out)]);
    ok(&["info", &s(&out)]);
}
