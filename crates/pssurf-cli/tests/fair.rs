//! End-to-end tests of `pssurf fair` (issue 18, part 5).

mod common;

use common::*;

/// The energy before and after, from the report "energy A -> B; …".
fn energies(report: &str) -> (f64, f64) {
    let line = report.lines().find(|l| l.starts_with("energy ")).unwrap();
    let rest = &line["energy ".len()..];
    let (a, rest) = rest.split_once(" -> ").unwrap();
    let b = rest.split(';').next().unwrap();
    (a.parse().unwrap(), b.parse().unwrap())
}

#[test]
fn fairing_a_noisy_ups_surface_lowers_its_energy_and_keeps_its_kind() {
    let d = tmp();
    let surf = s(&d.path().join("wave.json"));
    let height = "0.3*sin(3*x)*cos(2*y)";
    ok(&[
        "new", "ups", "--sides", "6", "--size", "8", "--base", "0.1", "--height", height, "-o",
        &surf,
    ]);
    let noisy = s(&d.path().join("noisy.json"));
    ok(&[
        "noise",
        &surf,
        "--amplitude",
        "0.01",
        "--seed",
        "3",
        "-o",
        &noisy,
    ]);
    let mut moved = f64::INFINITY;
    for weight in ["0", "0.1", "10"] {
        let out = s(&d.path().join(format!("fair-{weight}.json")));
        let report = ok_report(&["fair", &noisy, "--weight", weight, "-o", &out]);
        let (before, after) = energies(&report);
        assert!(after < before, "{weight}: {report}");
        let largest: f64 = report
            .split("largest move ")
            .nth(1)
            .unwrap()
            .split(')')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(largest < moved, "{weight}: {report}");
        moved = largest;
        let info: serde_json::Value = serde_json::from_str(&ok(&["info", &out, "--json"])).unwrap();
        assert_eq!(info["valid"], true);
        assert!(
            info["uniform"].is_object(),
            "a UPS surface stays one: {info}"
        );
    }
    for args in [
        vec!["fair", &noisy, "--weight", "-1", "-o", "x.json"],
        vec!["fair", &noisy, "--weight", "nan", "-o", "x.json"],
        vec!["fair", &noisy, "--weight", "1e308", "-o", "x.json"],
    ] {
        let msg = fails(&args);
        assert_eq!(msg.trim().lines().count(), 1, "{args:?}: {msg}");
    }
}

#[test]
fn a_surface_of_zero_energy_reports_no_negative_energy() {
    // A quadratic has no Hessian jumps: its energy was printed as about −1e-9 (rounding).
    let d = tmp();
    let surf = s(&d.path().join("q.json"));
    ok(&[
        "new", "ups", "--sides", "6", "--size", "4", "--height", "x*y", "-o", &surf,
    ]);
    let out = s(&d.path().join("f.json"));
    let (before, after) = energies(&ok_report(&["fair", &surf, "-o", &out]));
    assert!(
        (0.0..1e-8).contains(&before) && (0.0..1e-8).contains(&after),
        "{before} {after}"
    );
}
