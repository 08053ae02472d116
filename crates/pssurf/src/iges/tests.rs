//! IGES import on the real files of `../shared/data/iges/` (checked against a reference
//! reading of the parameter data written here), on files written by the test (delimiters,
//! Hollerith strings, `D` exponents, comments, transformations, units), and on malformed
//! variants.

use nalgebra::{Point2, Vector3};
use rand::RngExt;

use super::*;
use crate::surface::ParametricSurface;
use crate::test_util::*;

fn data(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/iges")
        .join(name);
    String::from_utf8_lossy(&std::fs::read(path).unwrap()).into_owned()
}

/// The sample files with their numbers of B-spline surfaces (the README's table).
const SAMPLES: [(&str, usize); 13] = [
    ("BUC50025.igs", 7),
    ("OCC131-3.igs", 3),
    ("OCC26138_Torus.igs", 1),
    ("OCC8842_cone_Ideas.igs", 2),
    ("PRO20360-T7.igs", 1),
    ("bad_header.igs", 1),
    ("bug22566_test_Bad.igs", 1),
    ("bug22869_Spring.igs", 2),
    ("bug23591_VZ-387.igs", 1),
    ("bug24012_face.igs", 1),
    ("bug33327.igs", 10),
    ("occ22470.igs", 18),
    ("hammer.iges", 45),
];

/// The reference reading: the numbers of entity `de`'s parameter lines, found by their back
/// pointers (columns 65–72), cut at the first `;`, split at `,`, `D` exponents read as `E`.
fn reference_params(text: &str, de: usize) -> Vec<f64> {
    let mut s = String::new();
    for line in text.lines() {
        if line.len() >= 73 && &line[72..73] == "P" && line[64..72].trim().parse() == Ok(de) {
            s.push_str(&line[..64]);
        }
    }
    let s = &s[..s.find(';').unwrap()];
    s.split(',')
        .map(|f| {
            f.trim()
                .replace(['D', 'd'], "E")
                .parse::<f64>()
                .unwrap_or(0.0)
        })
        .collect()
}

/// N_{i,p}(t) by the recursion, the domain's end closed on the last non-empty span.
fn basis(u: &[f64], i: usize, p: usize, t: f64, last: usize) -> f64 {
    if p == 0 {
        if t == u[last + 1] {
            return f64::from(i == last);
        }
        return f64::from(u[i] <= t && t < u[i + 1]);
    }
    let a = |n: f64, d: f64| if d == 0.0 { 0.0 } else { n / d };
    a(t - u[i], u[i + p] - u[i]) * basis(u, i, p - 1, t, last)
        + a(u[i + p + 1] - t, u[i + p + 1] - u[i + 1]) * basis(u, i + 1, p - 1, t, last)
}

/// The imported surface at `count` random points of its domain, back in the file's units
/// (`unit` per file unit), equals the independent reading of the file's parameters `v`
/// there to 1e-12 of the net's size.
fn assert_matches_reference(
    surface: &crate::nurbs::NurbsSurface,
    v: &[f64],
    unit: f64,
    count: usize,
    r: &mut rand_chacha::ChaCha8Rng,
    what: &str,
) {
    let size = surface
        .points()
        .iter()
        .map(|p| p.norm())
        .fold(1.0, f64::max);
    let (lo, hi) = surface.domain_bounds();
    for _ in 0..count {
        let uv = Point2::new(uniform(r, lo.x, hi.x), uniform(r, lo.y, hi.y));
        let ours = surface.point(uv).unwrap() / unit;
        let theirs = reference_point(v, uv);
        assert!(
            (ours - theirs).norm() <= 1e-12 * size,
            "{what} at {uv}: {ours} vs {theirs}"
        );
    }
}

/// The point of a 128 entity from its reference parameters (u fastest, as IGES lists them).
fn reference_point(v: &[f64], uv: Point2<f64>) -> Vector3<f64> {
    let (k1, k2, m1, m2) = (v[1] as usize, v[2] as usize, v[3] as usize, v[4] as usize);
    let (n1, n2) = (k1 + 1, k2 + 1);
    let ku = &v[10..10 + k1 + m1 + 2];
    let kv = &v[10 + k1 + m1 + 2..10 + k1 + m1 + 2 + k2 + m2 + 2];
    let w0 = 10 + k1 + m1 + 2 + k2 + m2 + 2;
    let p0 = w0 + n1 * n2;
    let last = |k: &[f64], n: usize, m: usize| (m..n).rev().find(|&i| k[i] < k[i + 1]).unwrap();
    let (lu, lv) = (last(ku, n1, m1), last(kv, n2, m2));
    let (mut num, mut den) = (Vector3::zeros(), 0.0);
    for j in 0..n2 {
        for i in 0..n1 {
            let s = j * n1 + i;
            let b = basis(ku, i, m1, uv.x, lu) * basis(kv, j, m2, uv.y, lv) * v[w0 + s];
            num += Vector3::new(v[p0 + 3 * s], v[p0 + 3 * s + 1], v[p0 + 3 * s + 2]) * b;
            den += b;
        }
    }
    num / den
}

/// Whether the directory entry whose first line is `entry` (1-based line of section D)
/// points to a transformation matrix (field 7, columns 49–56).
fn is_transformed(text: &str, entry: usize) -> bool {
    let line = text
        .lines()
        .filter(|l| l.len() >= 73 && &l[72..73] == "D")
        .nth(entry - 1)
        .unwrap();
    line[48..56].trim().parse::<i64>().unwrap_or(0) != 0
}

#[test]
fn every_sample_file_loads_and_its_surfaces_match_a_reference_reading() {
    let mut r = rng(1710);
    let mut compared = 0;
    for (name, surfaces) in SAMPLES {
        let text = data(name);
        let model = read_iges(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(model.surfaces.len(), surfaces, "{name}");
        for s in &model.surfaces {
            // Surfaces without a transformation: the reference reading has none to apply.
            if is_transformed(&text, s.entry) {
                continue;
            }
            let v = reference_params(&text, s.entry);
            let what = format!("{name} D{}", s.entry);
            assert_matches_reference(&s.surface, &v, model.unit.1, 10, &mut r, &what);
            compared += 10;
        }
    }
    assert!(compared >= 500, "{compared} points compared");
}

#[test]
fn sample_files_report_what_they_hold() {
    let torus = read_iges(&data("OCC26138_Torus.igs")).unwrap();
    assert!(torus.surfaces[0].trimmed && !torus.surfaces[0].loops.is_empty());
    assert!(
        torus
            .warnings
            .iter()
            .any(|w| w.contains("trimming is not applied"))
    );
    let cone = read_iges(&data("OCC8842_cone_Ideas.igs")).unwrap();
    // I-DEAS writes D exponents and B-rep entities, which are counted, not refused.
    assert_eq!(cone.unknown.get(&514), Some(&1));
    assert_eq!(cone.unknown.get(&508), Some(&2));
    let bad = read_iges(&data("bug22566_test_Bad.igs")).unwrap();
    assert!(
        bad.warnings
            .iter()
            .any(|w| w.contains("not a B-spline surface"))
    );
}

// ---- files written by the test ----

/// An IGES file from Global fields and entities (type, parameter text, transformation DE).
fn iges(global: &str, entities: &[(i64, &str, usize)]) -> String {
    let mut out = String::new();
    let rec = |out: &mut String, body: &str, letter: char, n: usize| {
        out.push_str(&format!("{body:<72}{letter}{n:>7}\n"));
    };
    rec(&mut out, "written by the pssurf test", 'S', 1);
    let g: Vec<String> = global
        .as_bytes()
        .chunks(72)
        .map(|c| String::from_utf8_lossy(c).into_owned())
        .collect();
    for (k, line) in g.iter().enumerate() {
        rec(&mut out, line, 'G', k + 1);
    }
    let mut p_lines: Vec<(String, usize)> = Vec::new();
    let mut dirs = Vec::new();
    for (k, (kind, params, transform)) in entities.iter().enumerate() {
        let de = 2 * k + 1;
        let start = p_lines.len() + 1;
        for chunk in params.as_bytes().chunks(64) {
            p_lines.push((String::from_utf8_lossy(chunk).into_owned(), de));
        }
        let count = p_lines.len() + 1 - start;
        dirs.push(format!(
            "{kind:>8}{start:>8}{:>8}{:>8}{:>8}{:>8}{transform:>8}{:>8}{:>8}",
            0, 0, 0, 0, 0, "00000000"
        ));
        dirs.push(format!(
            "{kind:>8}{:>8}{:>8}{count:>8}{:>8}{:>8}{:>8}{:>8}{:>8}",
            0, 0, 0, "", "", "", 0
        ));
    }
    for (k, d) in dirs.iter().enumerate() {
        rec(&mut out, d, 'D', k + 1);
    }
    for (k, (text, de)) in p_lines.iter().enumerate() {
        rec(&mut out, &format!("{text:<64}{de:>8}"), 'P', k + 1);
    }
    let counts = format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}",
        1,
        g.len(),
        dirs.len(),
        p_lines.len()
    );
    out.push_str(&format!("{counts:<72}T{:>7}\n", 1));
    out
}

/// A bilinear 128 patch: (0,0,0), (1,0,0), (0,1,0), (1,1,1) over [0,1]².
const BILINEAR: &str = "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,1.,0.,1.,0.,1.;";

#[test]
fn delimiters_hollerith_strings_exponents_units_and_transformations() {
    // Other delimiters (# and $), a Hollerith string holding them, inches.
    let global = "1H##1H$#5HA#B$C#7HNAME#$X#8Hpssurf!!########1.0D0#1#2HIN$";
    let params = BILINEAR
        .replace(',', "#")
        .replace(';', "$ this is a comment");
    let text = iges(global, &[(128, &params, 0)]);
    let m = read_iges(&text).unwrap();
    assert_eq!(m.unit, ("inch".to_string(), 25.4));
    let p = m.surfaces[0].surface.point(Point2::new(1.0, 1.0)).unwrap();
    assert!((p - Vector3::new(25.4, 25.4, 25.4)).norm() < 1e-12);
    // A 124 rotation about z by 90° with a translation, in millimetres (unit flag 2).
    let t124 = "124,0.,-1.,0.,10.,1.,0.,0.,20.,0.,0.,1.,30.;";
    let text = iges(
        ",,11HMM,ALSO#$%&,,,,,,,,,,1.,2,2HMM;",
        &[(124, t124, 0), (128, BILINEAR, 1)],
    );
    let m = read_iges(&text).unwrap();
    let p = m.surfaces[0].surface.point(Point2::new(1.0, 0.0)).unwrap();
    // (1, 0, 0) ↦ R (1, 0, 0) + t = (0, 1, 0) + (10, 20, 30).
    assert!((p - Vector3::new(10.0, 21.0, 30.0)).norm() < 1e-12, "{p}");
    // D exponents, blank lines between records.
    let text = iges(",,;", &[(128, &BILINEAR.replace("1.,", "1.0D0,"), 0)]).replace("\nP", "\n\nP");
    assert!(read_iges(&text).is_ok());
}

#[test]
fn malformed_files_fail_with_the_line_and_never_panic() {
    let good = iges(",,;", &[(128, BILINEAR, 0)]);
    if let Err(e) = read_iges(&good) {
        panic!("{e}\n{good}");
    }
    let lines: Vec<&str> = good.lines().collect();
    let with = |k: usize, f: &dyn Fn(&str) -> String| {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        l[k] = f(&l[k]);
        l.join("\n")
    };
    let error = |text: &str| read_iges(text).expect_err("should fail");
    // Truncated in the middle of the parameter data.
    let e = error(&lines[..lines.len() - 2].join("\n"));
    assert!(e.message.contains("record delimiter"), "{e}");
    // A short record.
    let e = error(&with(2, &|s| s[..40].to_string()));
    assert_eq!(e.line, 3, "{e}");
    // A bad number in the parameters, named with its line.
    let p = lines
        .iter()
        .position(|l| l.as_bytes().get(72) == Some(&b'P'))
        .unwrap();
    let e = error(&with(p, &|s| s.replacen("0.,", "0x,", 1)));
    assert_eq!(e.line, p + 1);
    assert!(e.message.contains("not a number"), "{e}");
    // A parameter pointer out of range.
    let e = error(&with(2, &|s| format!("{}{:>8}{}", &s[..8], 99, &s[16..])));
    assert!(e.message.contains("outside the Parameter section"), "{e}");
    // A transformation pointer to nothing.
    let e = error(&with(2, &|s| format!("{}{:>8}{}", &s[..48], 41, &s[56..])));
    assert!(e.message.contains("names no directory entry"), "{e}");
    // Text beyond column 80 (the audit's records of 85 columns imported silently).
    let e = error(&with(2, &|s| format!("{s}XXXXX")));
    assert_eq!(e.line, 3, "{e}");
    assert!(e.message.contains("80 columns (this one has 85)"), "{e}");
    // No Terminate record: a truncated file (it imported silently).
    let e = error(&lines[..lines.len() - 1].join("\n"));
    assert!(e.message.contains("without its Terminate record"), "{e}");
    // Terminate counts that are not the file's: read, with a warning naming the line.
    let last = lines.len() - 1;
    let miscounted = with(last, &|s| s.replacen("D      2", "D      9", 1));
    assert_ne!(miscounted, good);
    let model = read_iges(&miscounted).unwrap();
    assert!(
        model.warnings.iter().any(|w| w.starts_with(&format!(
            "line {}: the Terminate record gives `D      9` where the file has 2 `D` records",
            last + 1
        ))),
        "{:?}",
        model.warnings
    );
    assert!(read_iges(&good).unwrap().warnings.is_empty());
    // Random damage anywhere: an error or a model, never a panic.
    let mut r = rng(1711);
    let bytes = good.as_bytes();
    for _ in 0..2000 {
        let mut b = bytes.to_vec();
        for _ in 0..3 {
            let k = r.random_range(0..b.len());
            b[k] = b"0123456789,;.-+HDE \n"[r.random_range(0..20)];
        }
        let _ = read_iges(&String::from_utf8_lossy(&b));
    }
}

#[test]
fn a_trimmed_surface_is_placed_by_its_transformation_after_the_surfaces_own() {
    // R: 90° about z with t = (10, 20, 30); S: the translation (1, 2, 3).
    let rot = "124,0.,-1.,0.,10.,1.,0.,0.,20.,0.,0.,1.,30.;";
    let shift = "124,1.,0.,0.,1.,0.,1.,0.,2.,0.,0.,1.,3.;";
    let corner = |entities: &[(i64, &str, usize)]| {
        let m = read_iges(&iges(",,;", entities)).unwrap();
        assert!(m.surfaces.len() == 1 && m.surfaces[0].trimmed);
        m.surfaces[0].surface.point(Point2::new(1.0, 0.0)).unwrap()
    };
    // R on the 144 (D5) only: (1, 0, 0) ↦ (0, 1, 0) + t.
    let p = corner(&[(124, rot, 0), (128, BILINEAR, 0), (144, "144,3,1,0,0;", 1)]);
    assert!((p - Vector3::new(10.0, 21.0, 30.0)).norm() < 1e-12, "{p}");
    // S on the 128 (D5), R on the 144 (D7): R (S x) = R (2, 2, 3) + t = (8, 22, 33), not
    // S (R x) = (11, 23, 33).
    let p = corner(&[
        (124, rot, 0),
        (124, shift, 0),
        (128, BILINEAR, 3),
        (144, "144,5,1,0,0;", 1),
    ]);
    assert!((p - Vector3::new(8.0, 22.0, 33.0)).norm() < 1e-12, "{p}");
    // A bounded surface (143) likewise.
    let p = corner(&[(124, rot, 0), (128, BILINEAR, 0), (143, "143,0,3,0;", 1)]);
    assert!((p - Vector3::new(10.0, 21.0, 30.0)).norm() < 1e-12, "{p}");
    // A second trimmed surface placing the same 128 elsewhere is reported, not merged.
    let m = read_iges(&iges(
        ",,;",
        &[
            (124, rot, 0),
            (128, BILINEAR, 0),
            (144, "144,3,1,0,0;", 1),
            (144, "144,3,1,0,0;", 0),
        ],
    ))
    .unwrap();
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("second time") && w.contains("D7"))
    );
}

/// The declared range U(0), U(1), V(0), V(1) and the knot domain (the same order) of a 128
/// entity's reference parameters.
fn declared_range(v: &[f64]) -> ([f64; 4], [f64; 4]) {
    let (k1, k2, m1, m2) = (v[1] as usize, v[2] as usize, v[3] as usize, v[4] as usize);
    let ku = &v[10..10 + k1 + m1 + 2];
    let kv = &v[10 + k1 + m1 + 2..10 + k1 + m1 + 2 + k2 + m2 + 2];
    let at = 10 + k1 + m1 + 2 + k2 + m2 + 2 + 4 * (k1 + 1) * (k2 + 1);
    (
        [v[at], v[at + 1], v[at + 2], v[at + 3]],
        [ku[m1], ku[k1 + 1], kv[m2], kv[k2 + 1]],
    )
}

#[test]
fn sample_surfaces_are_imported_on_their_declared_parameter_ranges() {
    let mut r = rng(1712);
    let (mut narrower, mut whole) = (0, 0);
    for (name, _) in SAMPLES {
        let text = data(name);
        let model = read_iges(&text).unwrap();
        for s in &model.surfaces {
            let v = reference_params(&text, s.entry);
            let (range, knots) = declared_range(&v);
            let (lo, hi) = s.surface.domain_bounds();
            let ours = [lo.x, hi.x, lo.y, hi.y];
            let width = [knots[1] - knots[0], knots[3] - knots[2]];
            let inside = (0..2).all(|d| {
                let (a, b, tol) = (range[2 * d], range[2 * d + 1], 1e-9 * width[d]);
                a < b && a >= knots[2 * d] - tol && b <= knots[2 * d + 1] + tol
            });
            let expected = if inside { range } else { knots };
            for k in 0..4 {
                assert!(
                    (ours[k] - expected[k]).abs() <= 1e-9 * width[k / 2],
                    "{name} D{}: domain {ours:?}, declared {range:?}, knots {knots:?}",
                    s.entry
                );
            }
            if !inside {
                whole += 1;
                let de = format!("D{}", s.entry);
                assert!(
                    model
                        .warnings
                        .iter()
                        .any(|w| w.contains("parameter range") && w.contains(&de)),
                    "{name} {de}: {:?}",
                    model.warnings
                );
            } else if (0..4).any(|k| (range[k] - knots[k]).abs() > 1e-9 * width[k / 2]) {
                narrower += 1;
            }
            // The same points as the whole surface of the file (where it is untransformed).
            if is_transformed(&text, s.entry) {
                continue;
            }
            let what = format!("{name} D{}", s.entry);
            assert_matches_reference(&s.surface, &v, model.unit.1, 5, &mut r, &what);
        }
    }
    // hammer.iges: 42 of 45 surfaces are narrower than their knots; bug23591_VZ-387.igs
    // writes its range in the order U(0), V(0), U(1), V(1) (U(1) < U(0)): kept whole.
    assert_eq!((narrower, whole), (42, 1));
}

/// A rational 128 entity of degrees (2, 1) on the knots U = (0, 0, 0, 1, 2, 3, 3, 3),
/// V = (0, 0, 1, 1), random weights and points, with the declared range `range`.
fn quadratic_128(r: &mut rand_chacha::ChaCha8Rng, range: [f64; 4]) -> String {
    let mut f: Vec<String> = "128,4,1,2,1,0,0,0,0,0,0.,0.,0.,1.,2.,3.,3.,3.,0.,0.,1.,1."
        .split(',')
        .map(String::from)
        .collect();
    f.extend((0..10).map(|_| format!("{}", 10f64.powf(uniform(r, -1.0, 1.0)))));
    f.extend((0..30).map(|_| format!("{}", uniform(r, -5.0, 5.0))));
    f.extend(range.iter().map(|x| format!("{x:?}")));
    f.join(",") + ";"
}

#[test]
fn a_surface_is_imported_on_its_declared_range_with_the_files_parametrisation() {
    let mut r = rng(1713);
    for _ in 0..20 {
        let range = [
            uniform(&mut r, 0.0, 1.4),
            uniform(&mut r, 1.6, 3.0),
            0.25,
            1.0,
        ];
        let params = quadratic_128(&mut r, range);
        let m = read_iges(&iges(",,;", &[(128, &params, 0)])).unwrap();
        let s = &m.surfaces[0].surface;
        let (lo, hi) = s.domain_bounds();
        assert_eq!([lo.x, hi.x, lo.y, hi.y], range);
        let v = reference_params(&iges(",,;", &[(128, &params, 0)]), 1);
        let size = s.points().iter().map(|p| p.norm()).fold(1.0, f64::max);
        for k in 0..25 {
            let uv = if k < 4 {
                Point2::new(range[k % 2], range[2 + k / 2])
            } else {
                Point2::new(uniform(&mut r, lo.x, hi.x), uniform(&mut r, lo.y, hi.y))
            };
            let (ours, theirs) = (s.point(uv).unwrap(), reference_point(&v, uv));
            assert!(
                (ours - theirs).norm() <= 1e-12 * size,
                "{uv}: {ours} vs {theirs}"
            );
        }
    }
    // A range that is not a rectangle inside the knots keeps the knot domain, with a warning.
    let params = quadratic_128(&mut r, [2.5, 0.5, 0.0, 1.0]);
    let m = read_iges(&iges(",,;", &[(128, &params, 0)])).unwrap();
    let (lo, hi) = m.surfaces[0].surface.domain_bounds();
    assert_eq!([lo.x, hi.x, lo.y, hi.y], [0.0, 3.0, 0.0, 1.0]);
    assert!(
        m.warnings
            .iter()
            .any(|w| w.contains("parameter range") && w.contains("D1"))
    );
}
