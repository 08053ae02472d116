//! End-to-end tests of `pssurf mesh subdivide` (issue 20, part 3).

mod common;

use common::*;

const OCTAHEDRON: &str = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

#[test]
fn every_scheme_writes_every_format_and_reads_it_back() {
    let d = tmp();
    let obj = write(d.path(), "oct.obj", OCTAHEDRON);
    for (scheme, factor) in [("loop", 4), ("sqrt3", 3), ("butterfly", 4)] {
        let mut input = s(&obj);
        let mut triangles = 8;
        for ext in ["ply", "stl", "obj"] {
            let out = s(&d.path().join(format!("{scheme}.{ext}")));
            let report = ok_report(&[
                "mesh",
                "subdivide",
                &input,
                "--scheme",
                scheme,
                "--times",
                "2",
                "-o",
                &out,
            ]);
            triangles *= factor * factor;
            assert!(
                report.contains(&format!("-> {triangles} triangles")),
                "{report}"
            );
            // The written mesh is read again (as the next input): PLY and STL keep the
            // shared vertices, so the closed mesh stays closed.
            input = out;
        }
    }
}

#[test]
fn loop_limit_positions_of_the_octahedron_are_symmetric() {
    let d = tmp();
    let obj = write(d.path(), "oct.obj", OCTAHEDRON);
    let out = d.path().join("lim.obj");
    ok_report(&[
        "mesh",
        "subdivide",
        &s(&obj),
        "--scheme",
        "loop",
        "--times",
        "3",
        "--limit",
        "-o",
        &s(&out),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    let radii: Vec<f64> = text
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let c: Vec<f64> = l[2..]
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
        })
        .collect();
    assert_eq!(radii.len(), 6 + 12 + 48 + 192);
    // The six original vertices stay symmetric: one limit radius for all of them.
    let r0 = radii[0];
    assert!(
        radii[..6].iter().all(|r| (r - r0).abs() < 1e-12),
        "{radii:?}"
    );
    assert!(r0 < 1.0 && r0 > 0.4);
}

#[test]
fn bad_meshes_get_one_clear_line() {
    let d = tmp();
    let out = s(&d.path().join("out.obj"));
    let cases = [
        ("index.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n", "index"),
        (
            "three.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
            "3 triangles",
        ),
        (
            "flip.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n",
            "oriented",
        ),
        (
            "bowtie.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n",
            "not manifold",
        ),
        ("empty.obj", "v 0 0 0\n", "no triangles"),
        (
            "nan.obj",
            "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            "finite",
        ),
        (
            "flat.obj",
            "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n",
            "collinear",
        ),
        ("junk.ply", "not a ply file", "junk.ply"),
        ("junk.stl", "", "junk.stl"),
    ];
    for (name, text, expected) in cases {
        let input = s(&write(d.path(), name, text));
        let e = fails(&["mesh", "subdivide", &input, "--scheme", "loop", "-o", &out]);
        assert!(
            e.contains(expected) && e.trim().lines().count() == 1,
            "{name}: {e}"
        );
    }
    let input = s(&write(d.path(), "oct.obj", OCTAHEDRON));
    let e = fails(&[
        "mesh",
        "subdivide",
        &input,
        "--scheme",
        "loop",
        "--times",
        "40",
        "-o",
        &out,
    ]);
    assert!(e.contains("more than"), "{e}");
    let e = fails(&[
        "mesh",
        "subdivide",
        &input,
        "--scheme",
        "sqrt3",
        "--limit",
        "-o",
        &out,
    ]);
    assert!(e.contains("--limit"), "{e}");
    let e = fails(&[
        "mesh",
        "subdivide",
        &input,
        "--scheme",
        "loop",
        "-o",
        &s(&d.path().join("x.txt")),
    ]);
    assert!(e.contains(".obj"), "{e}");
    assert!(!std::path::Path::new(&out).exists());
}

#[test]
fn compare_subdivision_writes_a_page_with_four_pictures() {
    let d = tmp();
    let dir = d.path().join("cmp");
    let report = ok_report(&[
        "compare-subdivision",
        &example("bump.obj"),
        "--times",
        "2",
        "--size",
        "320x240",
        "-o",
        &s(&dir),
    ]);
    assert!(report.contains("4 panels"), "{report}");
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    for name in ["loop.png", "sqrt3.png", "butterfly.png", "ps.png"] {
        assert!(html.contains(name), "{html}");
        let png = std::fs::read(dir.join(name)).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
    // A closed mesh is no height field: three panels, and the page says why.
    let obj = write(d.path(), "oct.obj", OCTAHEDRON);
    let report = ok_report(&[
        "compare-subdivision",
        &s(&obj),
        "-o",
        &s(&d.path().join("o")),
    ]);
    assert!(report.contains("3 panels"), "{report}");
    let html = std::fs::read_to_string(d.path().join("o/index.html")).unwrap();
    assert!(html.contains("not a height field"));
}
