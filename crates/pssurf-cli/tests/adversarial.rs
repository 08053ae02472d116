//! The adversarial suite (issue 13): every command driven with extreme numbers, sizes at and
//! past every limit, malformed and truncated files, unknown and duplicate fields, huge
//! strings, degenerate geometry and odd output targets. For every case it asserts:
//!
//! - the exit status is 0, 1 or 2 — never a panic (101), an abort or a kill;
//! - a failure prints exactly one short `error:` line (at most 300 characters);
//! - the run ends within 10 s and its peak memory (wait4's maxrss) stays under 1.5 GB,
//!   with the suite's budget `--max-memory 512M`;
//! - no temporary file is left, and a failed run leaves the previous output file unchanged;
//! - a surface file written by a successful run loads again.
//!
//! The counts per category are printed (`cargo test --test adversarial -- --nocapture`) and
//! reported in docs/reliability.md.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use wait4::Wait4;

/// The suite's memory budget, passed to every run.
const BUDGET: &str = "512M";
/// The longest a run may take.
const TIME_LIMIT: Duration = Duration::from_secs(10);
/// The most memory a run may use (the budget plus the program and a margin).
const MEMORY_LIMIT: u64 = 1536 << 20;
/// What a previous output file holds before a run.
const SENTINEL: &[u8] = b"previous output\n";

/// One run of the binary.
struct Case {
    category: &'static str,
    args: Vec<String>,
    /// The output file the run names (pre-filled with [`SENTINEL`]), if any.
    output: Option<PathBuf>,
}

/// What a run did.
struct Outcome {
    code: Option<i32>,
    stderr: String,
    elapsed: Duration,
    maxrss: u64,
}

fn run(dir: &Path, args: &[String]) -> Outcome {
    let start = Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_pssurf"))
        .args(args)
        .args(["--max-memory", BUDGET])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let pid = child.id();
    let done = Arc::new(AtomicBool::new(false));
    let watchdog = {
        let done = done.clone();
        std::thread::spawn(move || {
            // Twice the limit before killing, so that a slow run is reported with its time.
            let until = Instant::now() + 2 * TIME_LIMIT;
            while Instant::now() < until {
                if done.load(Ordering::Relaxed) {
                    return;
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            let _ = Command::new("kill")
                .args(["-KILL", &pid.to_string()])
                .status();
        })
    };
    let mut child = child;
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        use std::io::Read;
        let _ = e.read_to_string(&mut stderr);
    }
    let used = child.wait4().expect("wait4");
    done.store(true, Ordering::Relaxed);
    let _ = watchdog.join();
    Outcome {
        code: used.status.code(),
        stderr,
        elapsed: start.elapsed(),
        maxrss: used.rusage.maxrss,
    }
}

/// Checks one case's outcome against the suite's promises; returns what went wrong.
fn check(dir: &Path, case: &Case, out: &Outcome) -> Result<(), String> {
    let code = out
        .code
        .ok_or("killed by a signal (crash, abort, or over twice the time limit)")?;
    if ![0, 1, 2].contains(&code) {
        return Err(format!("exit status {code}: {}", out.stderr));
    }
    if out.elapsed > TIME_LIMIT {
        return Err(format!("took {:?}", out.elapsed));
    }
    if out.maxrss > MEMORY_LIMIT {
        return Err(format!("peak memory {} MB", out.maxrss >> 20));
    }
    let lines: Vec<&str> = out.stderr.lines().collect();
    let errors: Vec<&&str> = lines.iter().filter(|l| l.starts_with("error:")).collect();
    if code != 0 {
        if errors.len() != 1 || !lines.last().is_some_and(|l| l.starts_with("error:")) {
            return Err(format!("not one error line: {:?}", out.stderr));
        }
    } else if !errors.is_empty() {
        return Err(format!("succeeded with an error line: {:?}", out.stderr));
    }
    if let Some(l) = lines.iter().find(|l| l.chars().count() > 300) {
        return Err(format!("a line of {} characters", l.chars().count()));
    }
    let temp = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .find(|e| e.file_name().to_string_lossy().starts_with(".pssurf-"));
    if let Some(t) = temp {
        return Err(format!("temporary file left: {:?}", t.file_name()));
    }
    if let Some(o) = &case.output {
        let meta = std::fs::symlink_metadata(o);
        let regular = meta.as_ref().is_ok_and(|m| m.is_file());
        if code != 0 && regular && std::fs::read(o).unwrap() != SENTINEL {
            return Err("a failed run changed the previous output".into());
        }
        if code == 0 && regular && o.extension().is_some_and(|e| e == "json") {
            let text = std::fs::read_to_string(o).unwrap_or_default();
            if text.starts_with('{') {
                let again = run(dir, &["info".into(), o.display().to_string()]);
                if again.code != Some(0) {
                    return Err(format!("wrote a file that does not load: {}", again.stderr));
                }
            }
        }
    }
    Ok(())
}

/// The fixtures every case may use, written into the case's directory.
struct Fixtures {
    files: Vec<(&'static str, Vec<u8>)>,
}

fn fixtures() -> Fixtures {
    let dir = tempfile::tempdir().unwrap();
    let make = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_pssurf"))
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    make(&[
        "new",
        "ups",
        "--sides",
        "6",
        "--size",
        "4",
        "--height",
        "0.3*sin(x)*cos(y)",
        "-o",
        "ups.json",
    ]);
    make(&[
        "new",
        "ups",
        "--sides",
        "6",
        "--size",
        "4",
        "--kind",
        "functional",
        "-o",
        "upsf.json",
    ]);
    make(&["fit", &common::example("franke.csv"), "-o", "ps.json"]);
    let read = |n: &str| std::fs::read(dir.path().join(n)).unwrap();
    let mut files = vec![
        ("ups.json", read("ups.json")),
        ("upsf.json", read("upsf.json")),
        ("ps.json", read("ps.json")),
        (
            "data.csv",
            std::fs::read(common::example("franke.csv")).unwrap(),
        ),
    ];
    files.push(("bezier.json", br#"{"format":"pssurf","version":1,"kind":"bezier","bezier":{"triangle":[[0,0],[1,0],[0,1]],"degree":2,"points":[[0,0,0],[0.5,0,0],[0,0.5,0],[1,0,0],[0.5,0.5,0.5],[0,1,0]]}}"#.to_vec()));
    files.push(("nurps.json", nurps_text(1.0, 2.0).into_bytes()));
    files.push(("pts.csv", b"u,v\n0.5,0.5\n1,1\n".to_vec()));
    Fixtures { files }
}

/// A NURPS surface on two triangles with weights w1 (vertices 0, 2) and w2 (1, 3).
fn nurps_text(w1: f64, w2: f64) -> String {
    format!(
        r#"{{"format":"pssurf","version":1,"kind":"nurps","domain":{{"vertices":[[0,0],[1,0],[1,1],[0,1]],"triangles":[[0,1,2],[0,2,3]]}},"control_points":{cp},"weights":[[{w1:e},{w1:e},{w1:e}],[{w2:e},{w2:e},{w2:e}],[{w1:e},{w1:e},{w1:e}],[{w2:e},{w2:e},{w2:e}]]}}"#,
        cp = "[[[0,0,0],[0.5,0,0],[0,0.5,0]],[[1,0,0],[1,0.5,0],[0.5,0,0]],[[1,1,1],[0.5,1,1],[1,0.5,1]],[[0,1,0],[0,0.5,0],[0.5,1,0]]]"
    )
}

/// A functional PS file on the given vertices and triangles, all control values zero.
fn ps_text(vertices: &[[f64; 2]], triangles: &[[usize; 3]]) -> String {
    let v: Vec<String> = vertices
        .iter()
        .map(|p| format!("[{:e},{:e}]", p[0], p[1]))
        .collect();
    let t: Vec<String> = triangles
        .iter()
        .map(|t| format!("[{},{},{}]", t[0], t[1], t[2]))
        .collect();
    format!(
        r#"{{"format":"pssurf","version":1,"kind":"functional","domain":{{"vertices":[{}],"triangles":[{}]}},"control":[{}]}}"#,
        v.join(","),
        t.join(","),
        vec!["[0,0,0]"; vertices.len()].join(",")
    )
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| s.to_string()).collect()
}

/// The extreme numbers every numeric argument is tried with.
const EXTREMES: [&str; 13] = [
    "0",
    "-0",
    "1e300",
    "-1e300",
    "1e-300",
    "9e307",
    "1.8e308",
    "NaN",
    "inf",
    "-inf",
    "12345678901234567890",
    "-12345678901234567890",
    "1e-320",
];

/// Files to create for a case: (name, content).
type Files = Vec<(String, Vec<u8>)>;

/// All cases, by category. Files named in a case are created in its directory first
/// (`extra`).
fn cases() -> Vec<(Case, Files)> {
    let mut out: Vec<(Case, Files)> = Vec::new();
    let mut add =
        |category: &'static str, args: Vec<String>, output: Option<&str>, extra: Files| {
            out.push((
                Case {
                    category,
                    args,
                    output: output.map(PathBuf::from),
                },
                extra,
            ));
        };
    // Extreme numbers in every numeric option.
    for x in EXTREMES {
        let numeric: Vec<Vec<String>> = vec![
            strings(&[
                "noise",
                "ups.json",
                "--amplitude",
                x,
                "--seed",
                "1",
                "-o",
                "o.json",
            ]),
            strings(&[
                "noise",
                "ups.json",
                "--amplitude",
                x,
                "--seed",
                "1",
                "--distribution",
                "gaussian",
                "-o",
                "o.json",
            ]),
            strings(&[
                "new", "ups", "--sides", "4", "--size", "3", "--base", x, "-o", "o.json",
            ]),
            strings(&["new", "ups", "--sides", "4", "--size", x, "-o", "o.json"]),
            strings(&["new", "ups", "--sides", x, "--size", "3", "-o", "o.json"]),
            strings(&[
                "new",
                "ups",
                "--sides",
                "4",
                "--size",
                "3",
                "--height",
                &format!("{x}*x"),
                "-o",
                "o.json",
            ]),
            strings(&["plot", "ups.json", "--zoom", x, "-o", "o.png"]),
            strings(&[
                "plot",
                "ups.json",
                "--view",
                &format!("{x},{x}"),
                "-o",
                "o.png",
            ]),
            strings(&["plot", "ups.json", "--perspective", x, "-o", "o.png"]),
            strings(&[
                "plot",
                "ups.json",
                "--band-width",
                x,
                "--show",
                "zebra",
                "-o",
                "o.png",
            ]),
            strings(&[
                "plot",
                "ups.json",
                "--show",
                "mean",
                "--range",
                &format!("{x},1"),
                "-o",
                "o.png",
            ]),
            strings(&["plot", "ups.json", "--level", x, "-o", "o.png"]),
            strings(&["export", "ups.json", "--level", x, "-o", "o.ply"]),
            strings(&["domain", "ups.json", "--width", x, "-o", "o.svg"]),
            strings(&[
                "domain", "ups.json", "--color", "H", "--level", x, "-o", "o.svg",
            ]),
            strings(&[
                "eval",
                "ups.json",
                "--grid",
                &format!("{x}x3"),
                "-o",
                "o.csv",
            ]),
            strings(&["subdivide", "ups.json", "--times", x, "-o", "o.json"]),
            strings(&[
                "denoise",
                "ups.json",
                "--levels",
                "1",
                "--threshold",
                x,
                "-o",
                "o.json",
            ]),
            strings(&[
                "denoise",
                "ups.json",
                "--levels",
                x,
                "--threshold",
                "5%",
                "-o",
                "o.json",
            ]),
            strings(&["fairness", "ps.json", "--degree", x]),
            strings(&["fit", "data.csv", "--approximate", x, "-o", "o.json"]),
            strings(&[
                "fit",
                "data.csv",
                "--approximate",
                "30",
                "--smooth",
                x,
                "-o",
                "o.json",
            ]),
            strings(&["eval", "ups.json", "--grid", "3x3", "--max-memory", x]),
        ];
        for args in numeric {
            let output = args
                .iter()
                .position(|a| a == "-o")
                .map(|k| args[k + 1].clone());
            add(
                "extreme numbers in options",
                args,
                output.as_deref(),
                vec![],
            );
        }
        // In data: a CSV row, a coordinate and control value of a surface, a weight.
        let csv = format!("x,y,z\n0,0,0\n1,0,{x}\n0,1,1\n1,1,2\n0.5,0.5,{x}\n").into_bytes();
        add(
            "extreme numbers in data",
            strings(&["fit", "d.csv", "-o", "o.json"]),
            Some("o.json"),
            vec![("d.csv".into(), csv)],
        );
        let csv = format!("x,y,z\n0,0,0\n1,0,1\n{x},1,1\n1,1,2\n0.5,0.5,3\n").into_bytes();
        add(
            "extreme numbers in data",
            strings(&["fit", "d.csv", "-o", "o.json"]),
            Some("o.json"),
            vec![("d.csv".into(), csv)],
        );
        let pts = format!("u,v\n{x},0.5\n").into_bytes();
        add(
            "extreme numbers in data",
            strings(&[
                "eval",
                "ps.json",
                "--at",
                "p.csv",
                "--outside",
                "nan",
                "-o",
                "o.csv",
            ]),
            Some("o.csv"),
            vec![("p.csv".into(), pts)],
        );
        // JSON has no NaN or infinity: such a file is malformed, and must be refused as such.
        let json_number = x.replace("inf", "Infinity");
        let surf = ps_text(
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            &[[0, 1, 2], [0, 2, 3]],
        )
        .replacen("[1e0,1e0]", &format!("[{json_number},1]"), 1);
        add(
            "extreme numbers in data",
            strings(&["info", "s.json"]),
            None,
            vec![("s.json".into(), surf.into_bytes())],
        );
        let surf = ps_text(
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            &[[0, 1, 2], [0, 2, 3]],
        )
        .replacen("[0,0,0]", &format!("[{json_number},0,0]"), 1);
        add(
            "extreme numbers in data",
            strings(&["eval", "s.json", "--grid", "3x3", "--outside", "nan"]),
            None,
            vec![("s.json".into(), surf.into_bytes())],
        );
        if let Ok(w) = x.parse::<f64>() {
            add(
                "extreme numbers in data",
                strings(&["curvature", "n.json", "--grid", "3x3"]),
                None,
                vec![("n.json".into(), nurps_text(w, 1.0).into_bytes())],
            );
        }
    }
    // Sizes at and past every limit.
    for (args, output) in [
        (
            vec!["eval", "ups.json", "--grid", "100000x100000", "-o", "o.csv"],
            "o.csv",
        ),
        (
            vec![
                "eval",
                "ups.json",
                "--grid",
                "18446744073709551615x18446744073709551615",
                "-o",
                "o.csv",
            ],
            "o.csv",
        ),
        (
            vec![
                "eval",
                "ups.json",
                "--grid",
                "5000x5000",
                "--outside",
                "skip",
                "-o",
                "o.npy",
            ],
            "o.npy",
        ),
        (
            vec![
                "curvature",
                "ups.json",
                "--grid",
                "100000x100000",
                "-o",
                "o.npy",
            ],
            "o.npy",
        ),
        (
            vec!["plot", "ups.json", "--level", "20", "-o", "o.png"],
            "o.png",
        ),
        (
            vec!["plot", "ups.json", "--level", "21", "-o", "o.png"],
            "o.png",
        ),
        (
            vec!["plot", "ups.json", "--level", "64", "-o", "o.png"],
            "o.png",
        ),
        (
            vec!["plot", "ups.json", "--level", "255", "-o", "o.png"],
            "o.png",
        ),
        (
            vec![
                "plot", "ups.json", "--show", "mean", "--level", "40", "-o", "o.png",
            ],
            "o.png",
        ),
        (
            vec!["plot", "ups.json", "--size", "16384x16384", "-o", "o.png"],
            "o.png",
        ),
        (
            vec!["plot", "ups.json", "--size", "16385x16", "-o", "o.png"],
            "o.png",
        ),
        (
            vec!["export", "ups.json", "--level", "7", "-o", "o.ply"],
            "o.ply",
        ),
        (
            vec!["export", "ups.json", "--level", "20", "-o", "o.obj"],
            "o.obj",
        ),
        (
            vec![
                "export",
                "ups.json",
                "--level",
                "2",
                "--max-output",
                "1K",
                "-o",
                "o.ply",
            ],
            "o.ply",
        ),
        (
            vec![
                "domain", "ups.json", "--color", "H", "--level", "6", "-o", "o.svg",
            ],
            "o.svg",
        ),
        (
            vec![
                "domain", "ups.json", "--color", "H", "--level", "20", "-o", "o.svg",
            ],
            "o.svg",
        ),
        (
            vec!["subdivide", "ups.json", "--times", "9", "-o", "o.json"],
            "o.json",
        ),
        (
            vec![
                "subdivide",
                "ups.json",
                "--times",
                "4294967295",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "new", "ups", "--sides", "4", "--size", "2000", "-o", "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "new", "ups", "--sides", "4", "--size", "1048576", "-o", "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "new",
                "ups",
                "--polygon",
                "0,0 1099511627776,0 0,1099511627776",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "new",
                "ups",
                "--polygon",
                "0,0 9223372036854775807,0 0,9223372036854775807",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "new",
                "ups",
                "--polygon",
                "-9223372036854775808,0 0,0 0,1",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "denoise",
                "ups.json",
                "--levels",
                "0",
                "--threshold",
                "5%",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (
            vec![
                "denoise",
                "ups.json",
                "--levels",
                "40",
                "--threshold",
                "5%",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (vec!["wavelet", "ups.json", "--levels", "4294967295"], ""),
        (
            vec![
                "fit",
                "data.csv",
                "--approximate",
                "100000000",
                "-o",
                "o.json",
            ],
            "o.json",
        ),
        (
            vec!["eval", "ups.json", "--grid", "3x3", "--max-memory", "1"],
            "",
        ),
    ] {
        let output = (!output.is_empty()).then_some(output);
        add(
            "sizes at and past the limits",
            strings(&args),
            output,
            vec![],
        );
    }
    // The showcase at picture sizes at and past the limit (refused by the budget before it
    // starts), and into odd places.
    for (size, out) in [
        ("16384x16384", "g"),
        ("16385x16", "g"),
        ("64x64", "/dev/null"),
        ("64x64", "ups.json"),
    ] {
        add(
            "sizes at and past the limits",
            strings(&["showcase", "--out", out, "--size", size]),
            None,
            vec![],
        );
    }
    // Endless and special inputs.
    for args in [
        vec!["info", "/dev/zero"],
        vec!["info", "/dev/null"],
        vec!["info", "."],
        vec!["eval", "ups.json", "--at", "/dev/zero"],
        vec!["fit", "/dev/zero", "-o", "o.json"],
        vec!["fit", "/dev/urandom", "-o", "o.json"],
        // The application, through `pssurf view`: bad files fail before any window opens.
        vec!["view", "/dev/zero"],
        vec!["view", "pts.csv"],
        vec!["view", "missing.json"],
    ] {
        add(
            "malformed and truncated files",
            strings(&args),
            None,
            vec![],
        );
    }
    // Malformed and truncated files, unknown and duplicate fields, huge strings.
    let base = ps_text(
        &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        &[[0, 1, 2], [0, 2, 3]],
    );
    for cut in [0, 1, 10, 40, 80, base.len() / 2, base.len() - 1] {
        add(
            "malformed and truncated files",
            strings(&["info", "s.json"]),
            None,
            vec![("s.json".into(), base.as_bytes()[..cut].to_vec())],
        );
    }
    for (from, to) in [
        (
            r#""kind":"functional""#,
            r#""kind":"functional","kind":"functional""#,
        ),
        (r#""kind":"functional""#, r#""kind":"functional","extra":1"#),
        (r#""control":"#, r#""control_points":[],"control":"#),
        (r#""version":1"#, r#""version":2"#),
        (r#""version":1"#, r#""version":1e400"#),
        (
            r#""triangles":[[0,1,2],[0,2,3]]"#,
            r#""triangles":[[0,1,2],[0,2,3],[0,1,2]]"#,
        ),
        (
            r#""triangles":[[0,1,2],[0,2,3]]"#,
            r#""triangles":[[0,1,2],[0,2,99]]"#,
        ),
        (
            r#""triangles":[[0,1,2],[0,2,3]]"#,
            r#""triangles":[[0,1,2],[0,3,2]]"#,
        ),
        (
            r#""triangles":[[0,1,2],[0,2,3]]"#,
            r#""triangles":[[0,1,2],[0,1,2,3]]"#,
        ),
        (
            r#""triangles":[[0,1,2],[0,2,3]]"#,
            r#""triangles":[[0,1,2],[0,2,-3]]"#,
        ),
        (
            r#""triangles":[[0,1,2],[0,2,3]]"#,
            r#""triangles":[[0,1,2],[0,2,18446744073709551616]]"#,
        ),
        (
            r#""format":"pssurf""#,
            r#""format":"pssurf","domain":{"vertices":[]}"#,
        ),
    ] {
        add(
            "unknown and duplicate fields",
            strings(&["info", "s.json"]),
            None,
            vec![("s.json".into(), base.replacen(from, to, 1).into_bytes())],
        );
    }
    let huge = "x".repeat(10 << 20);
    add(
        "huge strings",
        strings(&["info", "s.json"]),
        None,
        vec![(
            "s.json".into(),
            base.replacen(r#""functional""#, &format!("\"{huge}\""), 1)
                .into_bytes(),
        )],
    );
    add(
        "huge strings",
        strings(&["info", "s.json"]),
        None,
        vec![(
            "s.json".into(),
            base.replacen(r#""format""#, &format!("\"{huge}\""), 1)
                .into_bytes(),
        )],
    );
    add(
        "huge strings",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![("d.csv".into(), format!("x,y,z\n0,0,{huge}\n").into_bytes())],
    );
    add(
        "huge strings",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![(
            "d.csv".into(),
            format!("x,y,z,{huge}\n0,0,0,1\n").into_bytes(),
        )],
    );
    add(
        "huge strings",
        strings(&[
            "new",
            "ups",
            "--sides",
            "4",
            "--size",
            "3",
            "--height",
            &"(x".repeat(30_000),
            "-o",
            "o.json",
        ]),
        Some("o.json"),
        vec![],
    );
    add(
        "huge strings",
        strings(&[
            "new", "ups", "--sides", "4", "--size", "3", "--height", "foo(x)", "-o", "o.json",
        ]),
        Some("o.json"),
        vec![],
    );
    add(
        "huge strings",
        strings(&["eval", &huge[..5000], "--grid", "3x3"]),
        None,
        vec![],
    );
    add(
        "huge strings",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![("d.csv".into(), b"x,x,y,z\n0,0,0,0\n".to_vec())],
    );
    add(
        "huge strings",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![("d.csv".into(), vec![0xff, 0xfe, 0, 1, 2])],
    );
    // Degenerate geometry.
    let collinear: String = std::iter::once("x,y,z\n".to_string())
        .chain((0..100_000).map(|i| format!("{i},{},0\n", 2 * i)))
        .collect();
    add(
        "degenerate geometry",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![("d.csv".into(), collinear.into_bytes())],
    );
    add(
        "degenerate geometry",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![(
            "d.csv".into(),
            b"x,y,z\n0,0,0\n0,0,1\n1,0,0\n0,1,0\n".to_vec(),
        )],
    );
    add(
        "degenerate geometry",
        strings(&["fit", "d.csv", "-o", "o.json"]),
        Some("o.json"),
        vec![("d.csv".into(), b"x,y,z\n0,0,0\n1,0,0\n".to_vec())],
    );
    let stacked = ps_text(
        &[
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [0.0, 4.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [1.0, 2.0],
        ],
        &[[0, 1, 2], [0, 2, 3], [4, 5, 6]],
    );
    add(
        "degenerate geometry",
        strings(&["info", "s.json"]),
        None,
        vec![("s.json".into(), stacked.into_bytes())],
    );
    let folded = ps_text(
        &[
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [-1.0, 0.0],
            [0.0, -1.0],
            [0.9, 0.1],
        ],
        &[[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]],
    );
    add(
        "degenerate geometry",
        strings(&["info", "s.json"]),
        None,
        vec![("s.json".into(), folded.into_bytes())],
    );
    let flat = ps_text(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], &[[0, 1, 2]]);
    add(
        "degenerate geometry",
        strings(&["info", "s.json"]),
        None,
        vec![("s.json".into(), flat.into_bytes())],
    );
    let duplicate = ps_text(
        &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]],
        &[[0, 1, 2], [3, 1, 2]],
    );
    add(
        "degenerate geometry",
        strings(&["info", "s.json"]),
        None,
        vec![("s.json".into(), duplicate.into_bytes())],
    );
    // Vertices of degree 8,000 and 100,000 (the PS-triangle search was cubic in the degree,
    // the adjacency quadratic).
    for d in [8_000usize, 100_000] {
        let mut fan = vec![[0.0, 0.0]];
        fan.extend((0..d).map(|k| {
            let a = std::f64::consts::TAU * k as f64 / d as f64;
            [a.cos(), a.sin()]
        }));
        let tris: Vec<[usize; 3]> = (0..d).map(|k| [0, 1 + k, 1 + (k + 1) % d]).collect();
        add(
            "degenerate geometry",
            strings(&["info", "s.json"]),
            None,
            vec![("s.json".into(), ps_text(&fan, &tris).into_bytes())],
        );
    }
    // Odd output targets.
    for target in [
        "/dev/null",
        "/dev/full",
        "-",
        "nowhere/o.json",
        ".",
        "link.json",
        "o.json/",
    ] {
        add(
            "odd output targets",
            strings(&["new", "ups", "--sides", "3", "--size", "2", "-o", target]),
            None,
            vec![],
        );
        add(
            "odd output targets",
            strings(&[
                "eval",
                "ups.json",
                "--grid",
                "3x3",
                "--outside",
                "nan",
                "-o",
                target,
            ]),
            None,
            vec![],
        );
        add(
            "odd output targets",
            strings(&[
                "plot", "ups.json", "--level", "0", "--size", "64x64", "-o", target,
            ]),
            None,
            vec![],
        );
    }
    out
}

#[test]
fn every_command_fails_cleanly_on_adversarial_input() {
    let fx = fixtures();
    let mut per_category: BTreeMap<&str, (usize, usize)> = BTreeMap::new();
    let mut failures = Vec::new();
    let mut slowest = (Duration::ZERO, String::new());
    let mut largest = (0u64, String::new());
    for (case, extra) in cases() {
        let dir = tempfile::tempdir().unwrap();
        for (name, bytes) in &fx.files {
            std::fs::write(dir.path().join(name), bytes).unwrap();
        }
        for (name, bytes) in &extra {
            std::fs::write(dir.path().join(name), bytes).unwrap();
        }
        // The odd target "link.json": a symbolic link to a regular file.
        std::fs::write(dir.path().join("target.json"), SENTINEL).unwrap();
        #[cfg(unix)]
        std::os::unix::fs::symlink("target.json", dir.path().join("link.json")).unwrap();
        if let Some(o) = &case.output {
            std::fs::write(dir.path().join(o), SENTINEL).unwrap();
        }
        let case = Case {
            output: case.output.as_ref().map(|o| dir.path().join(o)),
            ..case
        };
        let out = run(dir.path(), &case.args);
        let entry = per_category.entry(case.category).or_default();
        entry.0 += 1;
        if out.code != Some(0) {
            entry.1 += 1;
        }
        let shown = common::short_args(&case.args);
        if out.elapsed > slowest.0 {
            slowest = (out.elapsed, shown.clone());
        }
        if out.maxrss > largest.0 {
            largest = (out.maxrss, shown.clone());
        }
        if let Err(why) = check(dir.path(), &case, &out) {
            failures.push(format!("{shown}: {why}"));
        }
    }
    let total: usize = per_category.values().map(|c| c.0).sum();
    println!("adversarial suite: {total} cases");
    for (category, (n, refused)) in &per_category {
        println!("  {category}: {n} cases, {refused} refused");
    }
    println!("slowest: {:?} ({})", slowest.0, slowest.1);
    println!("largest: {} MB ({})", largest.0 >> 20, largest.1);
    assert!(
        failures.is_empty(),
        "{} of {total} cases broke a promise:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
