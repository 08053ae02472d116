//! End-to-end tests of `pssurf edit` (issue 16): the measure asked for is what `pssurf probe`
//! then measures, failures write nothing, and the graph demo writes a valid NURBS surface.

mod common;

use common::*;

/// `probe --json` at a point: (K, H, k1, k2).
fn probe(surf: &str, at: &str) -> serde_json::Value {
    serde_json::from_str(&ok(&["probe", surf, "--at", at, "--json"])).unwrap()
}

/// A UPS hexagon of a wave, written into `dir`.
fn wave(dir: &std::path::Path) -> String {
    let surf = s(&dir.join("wave.json"));
    let height = "0.3*sin(3*x)*cos(2*y)";
    let args = [
        "new", "ups", "--sides", "6", "--size", "8", "--height", height, "-o", &surf,
    ];
    ok(&args);
    surf
}

#[test]
fn edits_of_a_ups_surface_are_measured_by_probe() {
    let d = tmp();
    let surf = wave(d.path());
    for (set, key, value) in [
        ("K=0.5", "K", 0.5),
        ("H=-0.2", "H", -0.2),
        ("k1=0.4", "k1", 0.4),
        ("k2=-1.5", "k2", -1.5),
    ] {
        let out = s(&d.path().join(format!("{key}.json")));
        let report = ok_report(&[
            "edit",
            &surf,
            "--at",
            "12,7",
            "--set",
            set,
            "--keep",
            "point,tangent",
            "-o",
            &out,
        ]);
        assert!(report.contains("moved"), "{report}");
        let p = probe(&out, "12,7");
        let got = p[key].as_f64().unwrap_or_else(|| panic!("{p}"));
        assert!(
            (got - value).abs() <= 1e-8 * value.abs().max(1.0),
            "{key}: {got}"
        );
        // The point stayed.
        let before = probe(&surf, "12,7");
        for k in 0..3 {
            let (a, b) = (
                before["point"][k].as_f64().unwrap(),
                p["point"][k].as_f64().unwrap(),
            );
            assert!((a - b).abs() < 1e-12, "{key}: {a} vs {b}");
        }
    }
}

#[test]
fn failures_are_one_line_and_write_nothing() {
    let d = tmp();
    let surf = wave(d.path());
    let out = d.path().join("out.json");
    for args in [
        vec![
            "edit",
            &surf,
            "--at",
            "12,7",
            "--set",
            "K=-50",
            "--region",
            "0.3",
            "--keep",
            "point,tangent",
        ],
        vec![
            "edit", &surf, "--at", "12,7", "--set", "K=1", "--region", "0.01",
        ],
        vec!["edit", &surf, "--at", "99,7", "--set", "K=1"],
        vec!["edit", &surf, "--at", "12,7", "--set", "Q=1"],
        vec!["edit", &surf, "--at", "12,7", "--set", "K=nan"],
        vec![
            "edit",
            &surf,
            "--at",
            "12,7",
            "--set",
            "K=1",
            "--torsion",
            "2",
        ],
        vec!["edit", &surf, "--set", "K=1"],
        vec!["edit", "--graph-demo", "--set", "cu=1e6"],
        vec!["edit", &surf, "--at", "12,7", "--set", "H=1e308"],
        vec!["edit", "--graph-demo", "--set", "cu=1", "--region", "1e308"],
        vec![
            "edit",
            "--graph-demo",
            "--set",
            "cv=0.5",
            "--torsion",
            "1",
            "--continuity",
            "0",
        ],
    ] {
        let mut all = args.clone();
        let o = s(&out);
        all.extend(["-o", &o]);
        let msg = fails(&all);
        assert_eq!(msg.trim().lines().count(), 1, "{args:?}: {msg}");
        assert!(!out.exists(), "{args:?}");
    }
}

#[test]
fn the_graph_demo_writes_nurbs_surfaces_with_the_asked_curvature() {
    let d = tmp();
    for (args, want) in [
        (
            vec!["--set", "cu=0.9"],
            "curvature of the u coordinate curve at (0.1, -0.2): 0.9 ",
        ),
        (
            vec!["--set", "cv=-0.3", "--continuity", "1"],
            "curvature of the v coordinate curve at (0.1, -0.2): -0.3 ",
        ),
        (vec!["--set", "K=0.3"], "-> 0.3 (asked 0.3)"),
        (
            vec!["--set", "cu=0.8", "--torsion", "0.5", "--continuity", "1"],
            "torsion 0.5 (asked 0.5)",
        ),
    ] {
        let out = s(&d.path().join("g.json"));
        let mut all = vec!["edit", "--graph-demo"];
        all.extend(&args);
        all.extend(["-o", &out]);
        let report = ok_report(&all);
        assert!(report.contains(want), "{args:?}: {report}");
        let info: serde_json::Value = serde_json::from_str(&ok(&["info", &out, "--json"])).unwrap();
        assert_eq!(info["kind"], "nurbs");
        assert_eq!(info["valid"], true);
    }
}

/// A region larger than the domain is the whole domain (the bump's window is not stretched
/// flat): the edit still reaches its target.
#[test]
fn a_huge_region_is_the_whole_domain() {
    let d = tmp();
    let surf = wave(d.path());
    let out = s(&d.path().join("h.json"));
    let report = ok_report(&[
        "edit", &surf, "--at", "12,7", "--set", "H=-0.5", "--region", "1e308", "-o", &out,
    ]);
    assert!(report.contains("(asked -0.5)"), "{report}");
    let p: serde_json::Value =
        serde_json::from_str(&ok(&["probe", &out, "--at", "12,7", "--json"])).unwrap();
    assert!((p["H"].as_f64().unwrap() + 0.5).abs() < 1e-8, "{p}");
}
