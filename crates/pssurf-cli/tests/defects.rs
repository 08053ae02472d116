//! One regression test per defect found by the hardening issue (issue 13), named after it.
//! The adversarial suite (`adversarial.rs`) covers the whole class; these pin each report.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use common::{fails, ok, pssurf};

fn s(p: &Path) -> String {
    p.display().to_string()
}

/// The one error line of a failed run; fails the test unless there is exactly one, it is
/// short, and the run did not panic.
fn one_error(out: &Output) -> String {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "should fail");
    assert!(
        matches!(out.status.code(), Some(1 | 2)),
        "status {:?}: {err}",
        out.status
    );
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].starts_with("error: ") && lines[0].len() <= 300,
        "{err}"
    );
    lines[0].to_string()
}

/// The one error line of running `command` (with `FILE` standing for the path) on a file
/// `name` holding `contents`.
fn error_on_file(name: &str, contents: &str, command: &[&str]) -> String {
    let d = tempfile::tempdir().unwrap();
    let p = s(&d.path().join(name));
    std::fs::write(&p, contents).unwrap();
    let args: Vec<&str> = command
        .iter()
        .map(|&a| if a == "FILE" { p.as_str() } else { a })
        .collect();
    one_error(&pssurf(&args))
}

fn small_ups(dir: &Path) -> String {
    ups_file(dir, "u.json", "4", "3", "x*y")
}

/// `pssurf new ups` into `dir/name`: its path.
fn ups_file(dir: &Path, name: &str, sides: &str, size: &str, height: &str) -> String {
    let p = s(&dir.join(name));
    ok(&[
        "new", "ups", "--sides", sides, "--size", size, "--height", height, "-o", &p,
    ]);
    p
}

/// A small UPS file whose polygon holds 2.1e9 lattice points but whose control list has 16
/// entries: refused for the count before the lattice is built (it took 62 s and 6 GB).
#[test]
fn a_ups_file_whose_polygon_outgrows_its_control_points_is_refused_at_once() {
    let d = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(small_ups(d.path())).unwrap();
    let huge = text.replacen(
        "\"polygon\":[[0,0],[3,0],[3,3],[0,3]]",
        "\"polygon\":[[0,0],[46000,0],[46000,46000],[0,46000]]",
        1,
    );
    assert_ne!(huge, text, "the polygon was replaced");
    let p = d.path().join("big.json");
    std::fs::write(&p, huge).unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert!(
        e.contains("expected one entry per vertex (2116092001), found 16"),
        "{e}"
    );
}

#[test]
fn new_ups_with_base_1e200_is_refused_and_writes_nothing() {
    let d = tempfile::tempdir().unwrap();
    let o = d.path().join("b.json");
    let e = one_error(&pssurf(&[
        "new",
        "ups",
        "--sides",
        "4",
        "--size",
        "3",
        "--base",
        "1e200",
        "-o",
        &s(&o),
    ]));
    assert!(e.contains("beyond the supported ±1e60"), "{e}");
    assert!(!o.exists());
    // A file with such coordinates is refused on loading, by every command.
    let text = std::fs::read_to_string(small_ups(d.path())).unwrap();
    let big = text.replacen("\"base\":1.0", "\"base\":1e200", 1);
    assert_ne!(big, text, "the file names its base");
    std::fs::write(&o, big).unwrap();
    for cmd in [
        vec!["info", &s(&o)],
        vec!["eval", &s(&o), "--grid", "3x3"],
        vec!["curvature", &s(&o), "--grid", "3x3"],
        vec!["fairness", &s(&o)],
    ] {
        one_error(&pssurf(&cmd));
    }
}

#[test]
fn noise_of_amplitude_1e308_is_refused_for_both_distributions() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let o = d.path().join("n.json");
    for dist in ["uniform", "gaussian"] {
        let e = one_error(&pssurf(&[
            "noise",
            &u,
            "--amplitude",
            "1e308",
            "--seed",
            "1",
            "--distribution",
            dist,
            "-o",
            &s(&o),
        ]));
        assert!(e.contains("amplitude 1e308") && e.contains("±1e60"), "{e}");
        assert!(!o.exists());
    }
}

#[test]
fn denoise_with_levels_0_is_a_usage_error() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let e = one_error(&pssurf(&[
        "denoise",
        &u,
        "--levels",
        "0",
        "--threshold",
        "5%",
        "-o",
        "d.json",
    ]));
    assert!(e.contains("0 is not in 1..=40"), "{e}");
}

#[test]
fn plot_levels_40_64_128_255_are_refused_not_wrapped() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    for level in ["40", "64", "128", "255"] {
        let e = one_error(&pssurf(&[
            "plot", &u, "--show", "mean", "--level", level, "-o", "p.png",
        ]));
        assert!(e.contains("is not in 0..=20"), "{e}");
    }
    let e = one_error(&pssurf(&["plot", &u, "--level", "20", "-o", "p.png"]));
    assert!(
        e.contains("would need about") && e.contains("--max-memory"),
        "{e}"
    );
}

#[test]
fn nurps_weights_1e300_and_1e_300_are_refused_on_loading() {
    let d = tempfile::tempdir().unwrap();
    for w in ["1e300", "1e-300"] {
        let text = format!(
            r#"{{"format":"pssurf","version":1,"kind":"nurps","domain":{{"vertices":[[0,0],[1,0],[0,1]],"triangles":[[0,1,2]]}},"control_points":[[[0,0,0],[0.5,0,0],[0,0.5,0]],[[1,0,0],[1,0.5,0],[0.5,0,0]],[[0,1,0],[0,0.5,0],[0.5,1,0]]],"weights":[[1,1,1],[1,{w},1],[1,1,1]]}}"#
        );
        let p = d.path().join("n.json");
        std::fs::write(&p, text).unwrap();
        let e = one_error(&pssurf(&["curvature", &s(&p), "--grid", "3x3"]));
        assert!(
            e.contains("weights[1][1]") && e.contains("1e-30 and 1e30"),
            "{e}"
        );
    }
}

#[test]
fn oversized_requests_are_refused_with_their_estimate_before_allocating() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let o = d.path().join("o");
    let budget = ["--max-memory", "256M"];
    for (args, flag) in [
        (
            vec!["export", &u, "--level", "9", "-o", "o.ply"],
            "--max-memory",
        ),
        (
            vec!["domain", &u, "--color", "H", "--level", "9", "-o", "o.svg"],
            "--max-memory",
        ),
        (
            vec!["subdivide", &u, "--times", "12", "-o", "o.json"],
            "--max-memory",
        ),
        (
            vec![
                "new", "ups", "--sides", "4", "--size", "20000", "-o", "o.json",
            ],
            "--max-memory",
        ),
        (
            vec![
                "new",
                "ups",
                "--polygon",
                "0,0 1000000000,0 0,1000000000",
                "-o",
                "o.json",
            ],
            "--max-memory",
        ),
        (
            vec!["plot", &u, "--level", "12", "-o", "o.png"],
            "--max-memory",
        ),
        (
            vec!["eval", &u, "--grid", "100000x100000", "-o", "o.csv"],
            "--max-output",
        ),
    ] {
        let mut all = args.clone();
        all.extend(budget);
        let out = Command::new(env!("CARGO_BIN_EXE_pssurf"))
            .args(&all)
            .current_dir(d.path())
            .output()
            .unwrap();
        let e = one_error(&out);
        assert!(e.contains("would ") && e.contains(flag), "{args:?}: {e}");
        assert!(
            std::fs::read_dir(d.path()).unwrap().count() == 1,
            "{args:?} wrote something"
        );
    }
    assert!(!o.exists());
}

#[test]
fn a_vertex_of_high_degree_loads() {
    // Issue: the PS-triangle search was about cubic in a vertex's degree (degree 2000 took
    // 8 s, 8000 over a minute) and adjacency quadratic; both are now near-linear
    // (docs/reliability.md: degree 8000 in 0.11 s, 100,000 in 0.5 s).
    let d = tempfile::tempdir().unwrap();
    let n = 8000;
    let mut v = vec!["[0,0]".to_string()];
    v.extend((0..n).map(|k| {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        format!("[{:e},{:e}]", a.cos(), a.sin())
    }));
    let t: Vec<String> = (0..n)
        .map(|k| format!("[0,{},{}]", 1 + k, 1 + (k + 1) % n))
        .collect();
    let text = format!(
        r#"{{"format":"pssurf","version":1,"kind":"functional","domain":{{"vertices":[{}],"triangles":[{}]}},"control":[{}]}}"#,
        v.join(","),
        t.join(","),
        vec!["[0,0,0]"; n + 1].join(",")
    );
    let p = d.path().join("fan.json");
    std::fs::write(&p, text).unwrap();
    let start = std::time::Instant::now();
    ok(&["info", &s(&p)]);
    assert!(start.elapsed().as_secs_f64() < 5.0, "{:?}", start.elapsed());
}

#[test]
fn one_hundred_thousand_collinear_points_are_refused_at_once() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("c.csv");
    let text: String = std::iter::once("x,y,z\n".to_string())
        .chain((0..100_000).map(|i| format!("{i},{},0\n", 2 * i)))
        .collect();
    std::fs::write(&p, text).unwrap();
    let start = std::time::Instant::now();
    let e = one_error(&pssurf(&[
        "fit",
        &s(&p),
        "-o",
        &s(&d.path().join("o.json")),
    ]));
    assert!(e.contains("collinear"), "{e}");
    assert!(start.elapsed().as_secs_f64() < 5.0, "{:?}", start.elapsed());
}

#[test]
fn overlapping_folded_triangles_are_refused() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("f.json");
    std::fs::write(&p, r#"{"format":"pssurf","version":1,"kind":"functional","domain":{"vertices":[[0,0],[4,0],[4,4],[0,4],[1,1],[2,1],[1,2]],"triangles":[[0,1,2],[0,2,3],[4,5,6]]},"control":[[0,0,0],[0,0,0],[0,0,0],[0,0,0],[0,0,0],[0,0,0],[0,0,0]]}"#).unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert!(e.contains("inside another part of the domain"), "{e}");
}

#[test]
fn a_csv_with_duplicate_column_names_is_refused() {
    let e = error_on_file(
        "d.csv",
        "x,y,z,Z\n0,0,0,0\n1,0,0,0\n0,1,0,0\n",
        &["fit", "FILE", "-o", "o.json"],
    );
    assert!(e.contains("appears twice"), "{e}");
    // 200,000 names, the last repeating the first: each used to be compared with every
    // earlier one (78 s); a set takes a fraction of a second.
    let names: Vec<String> = (0..200_000).map(|k| format!("c{k}")).collect();
    let header = format!("x,y,z,{},C0\n", names.join(","));
    let e = error_on_file("w.csv", &header, &["fit", "FILE", "-o", "o.json"]);
    assert!(e.contains("the column name `C0` appears twice"), "{e}");
}

#[test]
fn a_parametric_file_with_a_stray_control_field_is_refused() {
    let d = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(small_ups(d.path())).unwrap();
    let stray = text.replacen("\"control_points\"", "\"control\":[],\"control_points\"", 1);
    let p = d.path().join("s.json");
    std::fs::write(&p, stray).unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert!(e.contains("no field `control`"), "{e}");
    // Duplicate fields too.
    let dup = text.replacen("\"version\":1", "\"version\":1,\"version\":1", 1);
    std::fs::write(&p, dup).unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert!(e.contains("duplicate field `version`"), "{e}");
}

#[test]
fn export_fields_repeated_are_refused() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let e = one_error(&pssurf(&["export", &u, "--fields", "K,K,K", "-o", "e.ply"]));
    assert!(e.contains("names K twice"), "{e}");
}

#[cfg(unix)]
#[test]
fn temporary_files_are_removed_on_sigterm_and_sigint() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let o = d.path().join("g.csv");
    for signal in ["-TERM", "-INT"] {
        std::fs::write(&o, "old").unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_pssurf"))
            .args([
                "eval",
                &u,
                "--grid",
                "5000x5000",
                "--outside",
                "nan",
                "-o",
                &s(&o),
            ])
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        // Wait until the temporary file exists (the write has begun), then signal.
        let temp = || {
            std::fs::read_dir(d.path())
                .unwrap()
                .filter_map(|e| e.ok())
                .any(|e| e.file_name().to_string_lossy().starts_with(".pssurf-"))
        };
        let start = std::time::Instant::now();
        while !temp() && start.elapsed().as_secs() < 20 {
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert!(temp(), "the write never started");
        Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .unwrap();
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(130), "{signal}");
        assert!(!temp(), "{signal}: a temporary file was left");
        assert_eq!(std::fs::read_to_string(&o).unwrap(), "old");
    }
}

#[cfg(unix)]
#[test]
fn special_files_and_symlinks_are_written_through_never_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    // /dev/null stays a character device (the write goes into it).
    ok(&[
        "eval",
        &u,
        "--grid",
        "3x3",
        "--outside",
        "nan",
        "-o",
        "/dev/null",
    ]);
    assert!(
        std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
    // A symlink keeps pointing at its target, which gets the content.
    let target = d.path().join("t.csv");
    std::fs::write(&target, "old").unwrap();
    let link = d.path().join("l.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    ok(&[
        "eval",
        &u,
        "--grid",
        "3x3",
        "--outside",
        "nan",
        "-o",
        &s(&link),
    ]);
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(std::fs::read_to_string(&target).unwrap().starts_with("u,v"));
}

#[cfg(target_os = "linux")]
#[test]
fn writing_to_dev_full_reports_the_full_disk() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    for args in [
        vec![
            "eval",
            &u,
            "--grid",
            "3x3",
            "--outside",
            "nan",
            "-o",
            "/dev/full",
        ],
        vec![
            "plot",
            &u,
            "--level",
            "0",
            "--size",
            "64x64",
            "-o",
            "/dev/full",
        ],
        vec![
            "new",
            "ups",
            "--sides",
            "3",
            "--size",
            "2",
            "-o",
            "/dev/full",
        ],
    ] {
        let e = one_error(&pssurf(&args));
        assert!(e.contains("no space left on the device"), "{e}");
    }
}

#[test]
fn output_to_a_directory_or_a_missing_one_is_explained() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let dir = format!("{}/", d.path().display());
    let e = one_error(&pssurf(&[
        "eval",
        &u,
        "--grid",
        "3x3",
        "--outside",
        "nan",
        "-o",
        &dir,
    ]));
    assert!(e.contains("is a directory"), "{e}");
    // `-o o.json/` where o.json does not exist, or is a file (was "Not a directory").
    for name in ["new.json/", "file.json/", "file.json/x.csv"] {
        std::fs::write(d.path().join("file.json"), "keep").unwrap();
        let target = format!("{}/{name}", d.path().display());
        let e = one_error(&pssurf(&[
            "eval",
            &u,
            "--grid",
            "3x3",
            "--outside",
            "nan",
            "-o",
            &target,
        ]));
        assert!(!e.contains("Not a directory"), "{e}");
        assert!(
            e.contains("names a directory") || e.contains("file.json is not a directory"),
            "{e}"
        );
        assert_eq!(
            std::fs::read_to_string(d.path().join("file.json")).unwrap(),
            "keep"
        );
    }
    let missing = s(&d.path().join("no/such/o.csv"));
    let e = one_error(&pssurf(&[
        "eval",
        &u,
        "--grid",
        "3x3",
        "--outside",
        "nan",
        "-o",
        &missing,
    ]));
    assert!(e.contains("does not exist"), "{e}");
}

#[test]
fn endless_inputs_are_read_only_as_far_as_the_budget() {
    // /dev/zero has no size to check: reading stops at the budget with one line.
    if !Path::new("/dev/zero").exists() {
        return;
    }
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    for args in [
        vec!["info", "/dev/zero"],
        vec!["eval", &u, "--at", "/dev/zero"],
        vec!["fit", "/dev/zero", "-o", "o.json"],
    ] {
        let mut all = args.clone();
        all.extend(["--max-memory", "200M"]);
        let e = one_error(&pssurf(&all));
        assert!(e.contains("longer than"), "{e}");
    }
}

#[test]
fn output_dash_means_standard_output() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let out = Command::new(env!("CARGO_BIN_EXE_pssurf"))
        .args(["new", "ups", "--sides", "3", "--size", "2", "-o", "-"])
        .current_dir(d.path())
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(out.stdout.starts_with(b"{\"format\":\"pssurf\""));
    assert!(!d.path().join("-").exists());
    let png = Command::new(env!("CARGO_BIN_EXE_pssurf"))
        .args(["plot", &u, "--level", "0", "--size", "64x64", "-o", "-"])
        .output()
        .unwrap();
    assert!(png.stdout.starts_with(b"\x89PNG"));
}

#[test]
fn load_errors_are_printed_once_with_values_shortened() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("t.json");
    std::fs::write(&p, "{\"format\":\"pssurf\"").unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert_eq!(e.matches("EOF").count(), 1, "{e}");
    // A 10 MB value is not echoed.
    let huge = format!(
        "{{\"format\":\"pssurf\",\"version\":1,\"kind\":\"{}\"}}",
        "k".repeat(10 << 20)
    );
    std::fs::write(&p, huge).unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert!(e.len() < 300 && e.contains("kkkk…"), "{e}");
}

#[test]
fn numbers_in_messages_are_short() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let e = one_error(&pssurf(&[
        "plot",
        &u,
        "--perspective",
        "1e300",
        "-o",
        "p.png",
    ]));
    assert!(e.contains("got 1e300"), "{e}");
    let e = fails(&[
        "noise",
        &u,
        "--amplitude",
        "1e307",
        "--seed",
        "1",
        "-o",
        "n.json",
    ]);
    assert!(!e.contains("00000000000"), "{e}");
}

#[test]
fn formula_errors_are_in_our_own_words() {
    let e = one_error(&pssurf(&[
        "new", "ups", "--sides", "4", "--size", "3", "--height", "foo(x)", "-o", "o.json",
    ]));
    assert!(e.contains("`foo` is not a function"), "{e}");
    assert!(!e.contains("wlog"), "{e}");
}

#[test]
fn given_gradients_too_large_for_the_control_values_are_named_by_their_row() {
    // Audit: the message named an internal (space-filling-curve ordered) vertex.
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("g.csv");
    std::fs::write(
        &p,
        "x,y,z,zx,zy\n0,0,0,0,0\n1,0,0,0,0\n0,1,0,1e300,0\n1,1,0,0,0\n0.4,0.6,0,0,0\n",
    )
    .unwrap();
    let out = d.path().join("o.json");
    let e = one_error(&pssurf(&["fit", &s(&p), "-o", &s(&out)]));
    assert!(e.contains("row 3: its value and gradient"), "{e}");
    assert!(!out.exists());
}

#[test]
fn a_surface_file_that_is_not_utf8_is_a_format_error() {
    let d = tempfile::tempdir().unwrap();
    let p = d.path().join("b.json");
    std::fs::write(&p, b"{\"format\": \"pssurf\xff\"}").unwrap();
    let e = one_error(&pssurf(&["info", &s(&p)]));
    assert!(e.contains("is not UTF-8 text"), "{e}");
}

#[test]
fn a_centroid_split_that_misses_an_edge_is_named_by_rows() {
    // Audit: the message named internal triangles and vertices, and advised the incentres.
    let d = tempfile::tempdir().unwrap();
    let (p, t) = (d.path().join("c.csv"), d.path().join("t.csv"));
    std::fs::write(&p, "x,y,z\n0,0,0\n0,0.1,0\n-5,1,1\n5,1,2\n").unwrap();
    std::fs::write(&t, "0,1,2\n1,0,3\n").unwrap();
    let out = d.path().join("o.json");
    let e = one_error(&pssurf(&[
        "fit",
        &s(&p),
        "--triangles",
        &s(&t),
        "--split",
        "centroid",
        "-o",
        &s(&out),
    ]));
    assert!(e.contains("triangles at rows 1, 2, 3 and 2, 1, 4"), "{e}");
    assert!(e.contains("--split incenter"), "{e}");
    assert!(!out.exists());
}

#[test]
fn negative_option_values_are_read_as_values() {
    // clap read `-1` as an unknown option ("unexpected argument '-1' found") and advised
    // `-- -1`, which does not work for an option.
    let d = tempfile::tempdir().unwrap();
    let data = d.path().join("d.csv");
    std::fs::write(&data, "x,y,z\n0,0,0\n1,0,1\n0,1,2\n1,1,3\n0.5,0.4,1\n").unwrap();
    let out = d.path().join("o.json");
    let e = one_error(&pssurf(&[
        "fit",
        &s(&data),
        "--approximate",
        "4",
        "--smooth",
        "-1",
        "-o",
        &s(&out),
    ]));
    assert!(!e.contains("unexpected argument"), "{e}");
    assert!(e.contains("-1"), "{e}");
    // A negative number where one is allowed is simply used.
    let u = small_ups(d.path());
    let probe = pssurf(&["probe", &u, "--at", "-0.5,0.25"]);
    assert!(
        !String::from_utf8_lossy(&probe.stderr).contains("unexpected argument"),
        "{}",
        String::from_utf8_lossy(&probe.stderr)
    );
}

#[test]
fn a_ragged_csv_row_is_named_with_its_length() {
    let e = error_on_file(
        "r.csv",
        "x,y,z\n1,2,3\n4,5\n",
        &["fit", "FILE", "-o", "o.json"],
    );
    // It was the csv crate's "CSV error: record 2 (line: 3, byte: 12): found record with 2
    // fields, but the previous record has 3 fields".
    assert!(e.contains("row 2 has 2 fields, the header has 3"), "{e}");
}

#[test]
fn a_json_file_where_csv_is_expected_is_named_as_such() {
    // `curve u.json` said "the column name `0.0]` appears twice".
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    let out = d.path().join("c.csv");
    let e = one_error(&pssurf(&[
        "curve",
        &u,
        "--subdivide",
        "cubic",
        "-o",
        &s(&out),
    ]));
    assert!(
        e.contains("a JSON file, where a CSV table is expected"),
        "{e}"
    );
}

#[test]
fn info_on_a_hole_filling_report_says_it_is_not_a_surface() {
    // It said "line 2, column 2: invalid type: map, expected a string".
    let report = "[\n  {\n    \"g0_max\": 3e-7\n  }\n]\n";
    let e = error_on_file("report.json", report, &["info", "FILE"]);
    assert!(e.contains("not a pssurf surface file"), "{e}");
}

/// Refining holes nine times made 132k-vertex patches per hole whose quality report kept
/// every quadrature node (8 GB against a 256 MB budget): the fill is now estimated first.
#[test]
fn hole_filling_beyond_the_memory_budget_is_refused_before_it_starts() {
    let d = tempfile::tempdir().unwrap();
    let out = s(&d.path().join("ex"));
    let e = one_error(&pssurf(&[
        "--max-memory",
        "256M",
        "example",
        "prism-cap",
        "--iterations",
        "9",
        "-o",
        &out,
    ]));
    assert!(
        e.contains(
            "filling 3 holes with up to 9 refinement steps (395,523 vertices) would need about"
        ),
        "{e}"
    );
    assert!(!d.path().join("ex").exists(), "nothing written");
}

/// An unreachable K: the Gaussian re-seeding ended farther from the target than the start,
/// and that last value was named "the closest" (2.7e-5 from 0.68, for a target of 1e6).
#[test]
fn an_unreachable_edit_names_the_closest_value_over_every_attempt() {
    let d = tempfile::tempdir().unwrap();
    let u = ups_file(d.path(), "u.json", "6", "4", "sin(x)*cos(y)");
    let o = s(&d.path().join("o.json"));
    let e = one_error(&pssurf(&[
        "edit", &u, "--at", "5,3", "--set", "K=1e6", "-o", &o,
    ]));
    let number = |after: &str| -> f64 {
        let rest = &e[e.find(after).unwrap_or_else(|| panic!("{e}")) + after.len()..];
        let end = rest.find([' ', ')', ';']).unwrap();
        rest[..end].parse().unwrap()
    };
    let (closest, start) = (number("the closest was "), number("(from "));
    assert!(
        (closest - 1e6).abs() <= (start - 1e6).abs(),
        "closest {closest}, start {start}: {e}"
    );
    assert!(!d.path().join("o.json").exists());
}

/// compare-subdivision left its pictures and the PS panel out of its estimate (16384² took
/// 4.6 GB against a 1 GB budget).
#[test]
fn compare_subdivision_counts_its_pictures_in_the_estimate() {
    let e = error_on_file(
        "m.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nv 0.5 0.5 2\nf 1 2 5\nf 2 4 5\nf 4 3 5\nf 3 1 5\n",
        &[
            "--max-memory",
            "1G",
            "compare-subdivision",
            "FILE",
            "--times",
            "1",
            "--size",
            "16384x16384",
            "-o",
            "out",
        ],
    );
    assert!(
        e.contains("at 16384x16384") && e.contains("would need about 4.1 GB"),
        "{e}"
    );
}

/// probe --extent far below or above the surface's size made 200,000 points of rounding or
/// one point: refused, naming the range.
#[test]
fn probe_extents_beyond_the_surface_scale_are_refused() {
    let d = tempfile::tempdir().unwrap();
    let u = small_ups(d.path());
    for extent in ["1e-9", "1e12"] {
        let e = one_error(&pssurf(&["probe", &u, "--at", "1,1", "--extent", extent]));
        assert!(e.contains(&format!("--extent {extent} is outside")), "{e}");
    }
    ok(&["probe", &u, "--at", "1,1", "--extent", "0.5"]);
}
